// report.md as one HTML page: the subset of Markdown the analysis writes (headings, paragraphs,
// bullet lists, tables, indented code blocks, images on their own line; **bold** and `code` inside
// text), every picture embedded as a data: URI so the page is a single file to send or archive.
// Text is HTML-escaped; nothing else of Markdown is interpreted, except that a line equal to a key
// of `raw_blocks` (an HTML comment such as "<!-- view: gear -->", which Markdown viewers hide) is
// replaced by that block's HTML as it stands: how the report places its 3D views.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>

namespace peensim {

// `image_bytes(src)`: the bytes of the image a Markdown image names (nullopt: the image is left as
// a link to src). `title`: the page's <title>.
std::string markdown_to_html(const std::string& markdown, const std::string& title,
                             const std::function<std::optional<std::string>(const std::string& src)>& image_bytes,
                             const std::map<std::string, std::string>& raw_blocks = {});

// image_bytes for pictures beside the page: the bytes of directory/src, nullopt when unreadable.
std::function<std::optional<std::string>(const std::string& src)> image_files_in(const std::string& directory);

// RFC 4648 base64 (with padding).
std::string base64(const std::string& bytes);

}  // namespace peensim
