// The resolved scene: a SceneDescription written back as a scene file with every default filled
// in, SI numbers (unit in a trailing comment), absolute mesh paths and rotations as matrices.
// Parsing it again gives the same description, bit for bit; its hash identifies a run's input.
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene_description.h"

namespace peensim {

std::string resolved_scene_yaml(const SceneDescription& scene);

// What follows a mesh file's path in the resolved scene: "  # " and the digest of its bytes
// (common/file_digest.h), e.g. "mesh: /parts/rod.stl  # fnv1a64 0123456789abcdef, 336084 B".
inline constexpr const char* kMeshDigestComment = "  # ";

// FNV-1a 64 of resolved_scene_yaml(scene) without the settings that do not change the run (render
// block, checkpoint interval, the analysis' output settings), each mesh file's path replaced by its
// bytes' digest: equal for scenes that differ only in how they were written or where the same mesh
// lies, another for a mesh rewritten in place.
std::uint64_t scene_hash(const SceneDescription& scene);

// The text scene_hash hashes (what a run simulates, its mesh files as digests of their bytes).
std::string hashed_scene_yaml(const SceneDescription& scene);

// A scene hash as summary.json and the checkpoints write it: 16 lowercase hexadecimal digits.
std::string scene_hash_hex(std::uint64_t hash);

// One region entry as the resolved scene writes it (a flow map on one line, SI values, angles in
// rad): the same text for the same entry, bit for bit.
std::string resolved_region_text(const RegionDesc& region);

}  // namespace peensim
