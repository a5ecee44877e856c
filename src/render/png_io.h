// PNG files of rendered frames: fast to write (a run may write one per frame), never left
// half-written under their final name.
#pragma once

#include <string>

#include "render/image.h"

namespace peensim::render {

// Writes `image` as an 8-bit PNG: RGB when every pixel is opaque (rendered frames are), RGBA
// otherwise. Speed over size: zlib level 1, no row filters. On a 1280x720 gear frame this took
// 8.7 ms for 142 kB as RGB (10.7 ms, 164 kB as RGBA); level 3 was within noise and 5 % smaller;
// "sub"/"up" filters 1.6x slower; level 6 with all filters 6.5x slower for 23 % less; RLE and
// Huffman-only 3x slower and 9x larger. The bytes go to `path.tmp`, which is then
// renamed over `path` (write_file_atomically): a crash or a full disk leaves the previous file or none, never a
// truncated PNG. No fsync: a frame is cheap to render again, and an fsync per frame would cost
// more than the encoding. Throws std::runtime_error (path + reason) on any failure, after
// removing `path.tmp`; std::invalid_argument for an empty or inconsistent image.
void write_png(const std::string& path, const RgbaImage& image);

// Reads any PNG libpng understands, converted to 8-bit RGBA. Throws std::runtime_error
// (path + libpng's message) if the file is missing or not a valid PNG.
RgbaImage read_png(const std::string& path);

}  // namespace peensim::render
