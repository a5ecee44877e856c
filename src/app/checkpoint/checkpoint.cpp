#include "app/checkpoint/checkpoint.h"

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "app/checkpoint/checkpoint_fields.h"
#include "app/checkpoint/field_checks.h"
#include "app/checkpoint/field_codec.h"
#include "common/byte_stream.h"
#include "common/fnv_hash.h"
#include "common/input_error.h"
#include "engine/law_input.h"
#include "output/atomic_file.h"
#include "scene/scene_difference.h"

namespace peensim {

namespace {

// The file: "PEENCKPT", the format version (kSavedStateVersion, 4 bytes), the fields of
// checkpoint_fields.h in their order, and a checksum of everything before it (8 bytes). Files of
// formats 1-9 began "PEENCKP" and their version as one character.
constexpr std::string_view kCheckpointMagic = "PEENCKPT";
constexpr std::string_view kOldMagic = "PEENCKP";

// Any single flipped bit (and almost any damage) changes it.
std::uint64_t checksum(std::string_view bytes) { return fnv1a64(bytes); }

InputError damaged(const std::string& path, const std::string& what) {
    return InputError(SourceLocation{path, 0, 0}, "checkpoint", what + "; run without --resume to start over");
}

// What a file of format `version` lacks, or has that this one does not know, in words.
std::string version_difference(std::uint32_t version) {
    std::string text = "written by another version of peensim (checkpoint format " + std::to_string(version) + ", this one reads " +
                       std::to_string(kSavedStateVersion) + ")";
    if (version >= kSavedStateVersion) return text;
    std::string added;
    int shown = 0;
    for (const FieldName& f : checkpoint_field_names())
        if (f.since > version && shown++ < 6) added += (added.empty() ? "" : ", ") + f.name;
    return text + (added.empty() ? "" : "; added since: " + added + (shown > 6 ? ", ..." : ""));
}

}  // namespace

std::vector<FieldName> checkpoint_field_names() {
    Checkpoint c;
    FieldLister lister;
    checkpoint_fields(c, lister);
    return lister.names();
}

void save_checkpoint(const std::string& path, const Checkpoint& c) {
    ByteWriter w;
    w.put_raw(kCheckpointMagic);
    w.put(kSavedStateVersion);
    FieldWriter fields(w);
    checkpoint_fields(c, fields);
    w.put(checksum(w.bytes()));
    write_file_atomically(path, w.bytes());
}

Checkpoint load_checkpoint(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": no checkpoint to resume from");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    const std::string bytes = buffer.str();
    const std::string_view view(bytes);
    if (!view.starts_with(kOldMagic)) throw damaged(path, "not a peensim checkpoint");
    if (!view.starts_with(kCheckpointMagic)) {
        const char old = bytes.size() > kOldMagic.size() ? bytes[kOldMagic.size()] : '?';
        if (old < '1' || old > '9') throw damaged(path, "not a peensim checkpoint");
        throw damaged(path, version_difference(static_cast<std::uint32_t>(old - '0')));
    }
    constexpr std::size_t kSum = sizeof(std::uint64_t);
    constexpr std::size_t kHeader = kCheckpointMagic.size() + sizeof(std::uint32_t);
    if (bytes.size() < kHeader + kSum) throw damaged(path, "the file is truncated");
    std::uint32_t version = 0;
    std::memcpy(&version, bytes.data() + kCheckpointMagic.size(), sizeof(version));
    const std::string_view body = view.substr(0, bytes.size() - kSum);
    std::uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + body.size(), kSum);
    // A damaged version number reads as damage, not as another version.
    if (stored != checksum(body)) throw damaged(path, "the file is damaged (its checksum does not match its contents)");
    if (version != kSavedStateVersion) throw damaged(path, version_difference(version));
    ByteReader r(body.substr(kHeader), path + ": checkpoint");
    Checkpoint c;
    try {
        FieldReader fields(r);
        checkpoint_fields(c, fields);
    } catch (const std::runtime_error& e) {
        throw damaged(path, e.what());
    }
    if (!r.at_end()) throw damaged(path, "the file has trailing bytes");
    return c;
}

void check_resumable(const std::string& path, const Checkpoint& c, const Model& model, std::size_t logged_components) {
    if (c.scene_hash != model.scene_hash) {
        // What differs, from the scene the run wrote beside its checkpoint.
        const std::string what =
            scene_difference((std::filesystem::path(path).parent_path() / "scene.resolved.yaml").string(), model.description);
        throw InputError(
            SourceLocation{path, 0, 0}, "checkpoint",
            "the scene changed since this checkpoint was written (" +
                (what.empty() ? std::string("a setting, or a mesh file's bytes") : what) +
                "; only output.checkpoint_interval and render settings may change on resume); run without --resume to start over");
    }
    const SimulationState& s = c.state;
    const double t = s.time.seconds();
    if (!std::isfinite(s.time.hi) || !std::isfinite(s.time.lo) || t < 0.0 || t > model.duration_s)
        throw damaged(path, "expected a time in [0, " + std::to_string(model.duration_s) + "] s, got " + std::to_string(t));
    // The placed shot, and as many slots again as the sources have emitted at most.
    const std::size_t n = s.shots.x.size();
    std::uint64_t emitted = 0;
    for (std::uint64_t e : s.emitted_per_source) emitted += e;
    if (n < static_cast<std::size_t>(model.shot_count) || n > static_cast<std::size_t>(model.shot_count) + emitted)
        throw damaged(path, "expected " + std::to_string(model.shot_count) + " shot" +
                                (emitted > 0 ? " (and up to " + std::to_string(emitted) + " emitted)" : std::string()) + ", got " +
                                std::to_string(n));
    // Every list's length and every number, from the field list.
    ExtentLengths lengths{};
    lengths[static_cast<std::size_t>(Extent::shots)] = n;
    lengths[static_cast<std::size_t>(Extent::components)] = model.components.size();
    lengths[static_cast<std::size_t>(Extent::logged_components)] = logged_components;
    lengths[static_cast<std::size_t>(Extent::sources)] = model.sources.size();
    lengths[static_cast<std::size_t>(Extent::sinks)] = model.sinks.size();
    lengths[static_cast<std::size_t>(Extent::shot_sizes)] = model.shot_sizes.size();
    try {
        FieldChecker checks(lengths, s.shots.active);
        checkpoint_fields(c, checks);
    } catch (const std::runtime_error& e) {
        throw damaged(path, e.what());
    }
    const std::vector<std::vector<double>> fresh = fresh_law_state(model);
    if (s.law_state.size() != fresh.size()) throw damaged(path, "contact law state for the wrong number of components");
    for (std::size_t k = 0; k < fresh.size(); ++k) {
        if (s.law_state[k].size() != fresh[k].size())
            throw damaged(path, "component " + model.components[k].name + ": contact law state of the wrong length");
    }
    for (const auto& [key, entry] : s.contacts.entries()) {
        const auto [shot, c] = key;
        if (shot < 0 || static_cast<std::size_t>(shot) >= n || c < 0 || static_cast<std::size_t>(c) >= model.components.size())
            throw damaged(path, "a contact of shot " + std::to_string(shot) + " with component " + std::to_string(c) + ": no such pair");
        const std::size_t per = static_cast<std::size_t>(model.components[static_cast<std::size_t>(c)].law->state_per_contact());
        if (entry.values.size() != per)
            throw damaged(path, "component " + model.components[static_cast<std::size_t>(c)].name + ": contact state of the wrong length");
    }
    for (const SoftContact& k : s.soft_contacts) {
        const bool with_shot = k.partner >= 0;
        const bool shot_ok = k.shot >= 0 && static_cast<std::size_t>(k.shot) < n && s.shots.active[static_cast<std::size_t>(k.shot)] == 1;
        const bool other_ok = with_shot ? k.component < 0 && k.partner > k.shot && static_cast<std::size_t>(k.partner) < n &&
                                              s.shots.active[static_cast<std::size_t>(k.partner)] == 1
                                        : k.component >= 0 && static_cast<std::size_t>(k.component) < model.components.size() &&
                                              k.mesh_triangle >= 0 &&
                                              static_cast<std::size_t>(k.mesh_triangle) <
                                                  model.components[static_cast<std::size_t>(k.component)].mesh->triangle_count();
        if (model.scheme != SteppingScheme::soft || !shot_ok || !other_ok)
            throw damaged(path, "a soft contact of shot " + std::to_string(k.shot) + " with " +
                                    (with_shot ? "shot " + std::to_string(k.partner) : "component " + std::to_string(k.component)) +
                                    ": no such pair in this scene");
        if (!(std::abs(k.normal.norm() - 1.0) < 1e-6) || !(k.approach_m_per_s >= 0.0))
            throw damaged(path, "a soft contact of shot " + std::to_string(k.shot) + ": not a unit normal, or a negative approach speed");
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (s.shots.active[i] > 1 || s.shots.in_flight[i] > 1) throw damaged(path, "shot " + std::to_string(i) + ": flags not 0 or 1");
        if (s.shots.size_class[i] >= model.shot_sizes.size())
            throw damaged(path, "shot " + std::to_string(i) + ": size " + std::to_string(s.shots.size_class[i]) + ", the scene has " +
                                    std::to_string(model.shot_sizes.size()));
        if (!s.shots.active[i]) continue;
        const Vec3 p = s.shots.position(i);
        if ((p.array() < model.world_lo.array()).any() || (p.array() > model.world_hi.array()).any())
            throw damaged(path, "shot " + std::to_string(i) + ": active but outside the assembly");
    }
    if (c.wall_time_s < 0.0) throw damaged(path, "a negative wall time");
    if (!(c.log_shift_s >= 0.0) || c.log_shift_s > model.duration_s - t)
        throw damaged(path, "expected a log shift in [0, " + std::to_string(model.duration_s - t) + "] s");
    const std::size_t entries = model.components.size() + 1;  // shot-shot, then each component
    if ((!c.replica_impacts.empty() && c.replica_impacts.size() != entries) ||
        (!c.replica_slow_contacts.empty() && c.replica_slow_contacts.size() != entries))
        throw damaged(path, "the other replicas' counts for the wrong number of components");
}

}  // namespace peensim
