#include "app/checkpoint/checkpoint.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "common/byte_stream.h"
#include "common/fnv_hash.h"
#include "common/input_error.h"
#include "engine/law_input.h"
#include "output/atomic_file.h"

namespace peensim {

namespace {

// The last character is the format version: 2 added the slow-contact counters and the per-shot
// in-flight flags; 3 a checksum of everything before it (the file's last 8 bytes); 4 the contact
// laws' per-triangle state; 5 the counts of the shot sources and sinks; 6 the laws' per-contact state;
// 7 the shot's angular velocities and the soft scheme's contacts in progress; 8 each shot's size
// (a mix) and a lost shot's radius; 9 the search fallbacks (their count and where the first was).
constexpr char kMagic[8] = {'P', 'E', 'E', 'N', 'C', 'K', 'P', '9'};

// Any single flipped bit (and almost any damage) changes it.
std::uint64_t checksum(std::string_view bytes) { return fnv1a64(bytes); }

InputError damaged(const std::string& path, const std::string& what) {
    return InputError(SourceLocation{path, 0, 0}, "checkpoint", what + "; run without --resume to start over");
}

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

void put_vec(ByteWriter& w, const Vec3& v) {
    for (int k = 0; k < 3; ++k) w.put(v[k]);
}

Vec3 get_vec(ByteReader& r) {
    Vec3 v;
    for (int k = 0; k < 3; ++k) v[k] = r.get<double>();
    return v;
}

}  // namespace

void save_checkpoint(const std::string& path, const Checkpoint& c) {
    ByteWriter w;
    w.put_raw({kMagic, sizeof(kMagic)});
    w.put(c.scene_hash);
    const SimulationState& s = c.state;
    w.put(s.time.hi);
    w.put(s.time.lo);
    w.put(s.steps);
    w.put(s.shot_steps);
    w.put(s.shot_shot_impacts);
    w.put(s.fastest_shot_m_per_s);
    w.put(s.health);
    w.put_vector(s.impacts_per_component);
    w.put_vector(s.slow_contacts_per_component);
    w.put(s.shot_shot_slow_contacts);
    w.put<std::uint64_t>(s.law_state.size());
    for (const std::vector<double>& v : s.law_state) w.put_vector(v);
    w.put<std::uint64_t>(s.lost.size());
    for (const LostShot& l : s.lost) {
        w.put(l.shot);
        w.put(l.time_s);
        for (int k = 0; k < 3; ++k) w.put(l.position_m[k]);
        w.put(l.cause);
        w.put(l.from_time_s);
        for (int k = 0; k < 3; ++k) w.put(l.from_m[k]);
        w.put(l.component);
        for (int k = 0; k < 3; ++k) w.put(l.where_m[k]);
        w.put(l.clearance_m);
        w.put(l.radius_m);
    }
    const SearchFallback& f = s.first_search_fallback;
    w.put(f.time_s);
    w.put(f.shot);
    w.put(f.component);
    for (int k = 0; k < 3; ++k) w.put(f.position_m[k]);
    for (const auto* v : {&s.shots.x, &s.shots.y, &s.shots.z, &s.shots.vx, &s.shots.vy, &s.shots.vz, &s.shots.wx, &s.shots.wy, &s.shots.wz})
        w.put_vector(*v);
    w.put_vector(s.shots.active);
    w.put_vector(s.shots.in_flight);
    w.put_vector(s.shots.size_class);
    w.put_vector(s.emitted_per_source);
    w.put_vector(s.collected_per_sink);
    w.put_vector(s.shots_per_size);
    w.put(s.contacts.resolutions());
    w.put<std::uint64_t>(s.contacts.entries().size());
    for (const auto& [key, entry] : s.contacts.entries()) {
        w.put(key.first);
        w.put(key.second);
        w.put(entry.seen);
        w.put_vector(entry.values);
    }
    w.put<std::uint64_t>(s.soft_contacts.size());
    for (const SoftContact& k : s.soft_contacts) {
        w.put(k.shot);
        w.put(k.partner);
        w.put(k.component);
        put_vec(w, k.spring_m);
        put_vec(w, k.normal);
        w.put(k.approach_m_per_s);
        w.put(k.start_time_s);
        w.put(k.mesh_triangle);
        put_vec(w, k.start_point_m);
        put_vec(w, k.start_velocity_m_per_s);
        w.put(k.start_tangential_m_per_s);
    }
    w.put(c.csv_bytes);
    w.put(c.csv_rows);
    w.put<std::uint64_t>(c.normal_speeds.size());
    for (const SpeedHistogram& h : c.normal_speeds) w.put_string(h.serialize());
    w.put(c.wall_time_s);
    w.put(checksum(w.bytes()));
    write_file_atomically(path, w.bytes());
}

Checkpoint load_checkpoint(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": no checkpoint to resume from");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    const std::string bytes = buffer.str();
    if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic) - 1) != 0)
        throw damaged(path, "not a peensim checkpoint");
    if (bytes[sizeof(kMagic) - 1] != kMagic[sizeof(kMagic) - 1])
        throw damaged(path, std::string("written by another version of peensim (checkpoint format ") + bytes[sizeof(kMagic) - 1] +
                                ", this one reads " + kMagic[sizeof(kMagic) - 1] + ")");
    constexpr std::size_t kSum = sizeof(std::uint64_t);
    if (bytes.size() < sizeof(kMagic) + kSum) throw damaged(path, "the file is truncated");
    const std::string_view body = std::string_view(bytes).substr(0, bytes.size() - kSum);
    std::uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + body.size(), kSum);
    if (stored != checksum(body)) throw damaged(path, "the file is damaged (its checksum does not match its contents)");
    ByteReader r(body.substr(sizeof(kMagic)), path + ": checkpoint");
    Checkpoint c;
    c.scene_hash = r.get<std::uint64_t>();
    SimulationState& s = c.state;
    s.time.hi = r.get<double>();
    s.time.lo = r.get<double>();
    s.steps = r.get<std::uint64_t>();
    s.shot_steps = r.get<std::uint64_t>();
    s.shot_shot_impacts = r.get<std::uint64_t>();
    s.fastest_shot_m_per_s = r.get<double>();
    s.health = r.get<HealthCounters>();
    s.impacts_per_component = r.get_vector<std::uint64_t>();
    s.slow_contacts_per_component = r.get_vector<std::uint64_t>();
    s.shot_shot_slow_contacts = r.get<std::uint64_t>();
    const auto law_components = r.get<std::uint64_t>();
    if (law_components > bytes.size()) throw damaged(path, "a law state for more components than the file has bytes");
    for (std::uint64_t k = 0; k < law_components; ++k) s.law_state.push_back(r.get_vector<double>());
    const auto lost = r.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < lost; ++k) {
        LostShot l;
        l.shot = r.get<int>();
        l.time_s = r.get<double>();
        for (int a = 0; a < 3; ++a) l.position_m[a] = r.get<double>();
        l.cause = r.get<LossCause>();
        l.from_time_s = r.get<double>();
        for (int a = 0; a < 3; ++a) l.from_m[a] = r.get<double>();
        l.component = r.get<int>();
        for (int a = 0; a < 3; ++a) l.where_m[a] = r.get<double>();
        l.clearance_m = r.get<double>();
        l.radius_m = r.get<double>();
        s.lost.push_back(l);
    }
    SearchFallback& f = s.first_search_fallback;
    f.time_s = r.get<double>();
    f.shot = r.get<int>();
    f.component = r.get<int>();
    for (int a = 0; a < 3; ++a) f.position_m[a] = r.get<double>();
    for (auto* v : {&s.shots.x, &s.shots.y, &s.shots.z, &s.shots.vx, &s.shots.vy, &s.shots.vz, &s.shots.wx, &s.shots.wy, &s.shots.wz})
        *v = r.get_vector<double>();
    s.shots.active = r.get_vector<unsigned char>();
    s.shots.in_flight = r.get_vector<unsigned char>();
    s.shots.size_class = r.get_vector<unsigned char>();
    s.emitted_per_source = r.get_vector<std::uint64_t>();
    s.collected_per_sink = r.get_vector<std::uint64_t>();
    s.shots_per_size = r.get_vector<std::uint64_t>();
    const auto resolutions = r.get<std::uint64_t>();
    const auto contacts = r.get<std::uint64_t>();
    if (contacts > bytes.size()) throw damaged(path, "more contacts than the file has bytes");
    std::map<ContactStates::Key, ContactStates::Entry> entries;
    for (std::uint64_t k = 0; k < contacts; ++k) {
        ContactStates::Key key;
        key.first = r.get<int>();
        key.second = r.get<int>();
        ContactStates::Entry e;
        e.seen = r.get<std::uint64_t>();
        e.values = r.get_vector<double>();
        entries.emplace(key, std::move(e));
    }
    s.contacts.restore(resolutions, std::move(entries));
    const auto soft = r.get<std::uint64_t>();
    if (soft > bytes.size()) throw damaged(path, "more soft contacts than the file has bytes");
    for (std::uint64_t k = 0; k < soft; ++k) {
        SoftContact sc;
        sc.shot = r.get<int>();
        sc.partner = r.get<int>();
        sc.component = r.get<int>();
        sc.spring_m = get_vec(r);
        sc.normal = get_vec(r);
        sc.approach_m_per_s = r.get<double>();
        sc.start_time_s = r.get<double>();
        sc.mesh_triangle = r.get<int>();
        sc.start_point_m = get_vec(r);
        sc.start_velocity_m_per_s = get_vec(r);
        sc.start_tangential_m_per_s = r.get<double>();
        s.soft_contacts.push_back(sc);
    }
    c.csv_bytes = r.get<std::uint64_t>();
    c.csv_rows = r.get<std::uint64_t>();
    const auto histograms = r.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < histograms; ++k) c.normal_speeds.push_back(SpeedHistogram::deserialize(r.get_string()));
    c.wall_time_s = r.get<double>();
    if (!r.at_end()) throw damaged(path, "the file has trailing bytes");
    return c;
}

void check_resumable(const std::string& path, const Checkpoint& c, const Model& model, std::size_t logged_components) {
    if (c.scene_hash != model.scene_hash)
        throw InputError(SourceLocation{path, 0, 0}, "checkpoint",
                         "the scene changed since this checkpoint was written (only output.checkpoint_interval and render "
                         "settings may change on resume); run without --resume to start over");
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
    for (const auto* v : {&s.shots.y, &s.shots.z, &s.shots.vx, &s.shots.vy, &s.shots.vz, &s.shots.wx, &s.shots.wy, &s.shots.wz})
        if (v->size() != n) throw damaged(path, "shot arrays of different lengths");
    if (s.shots.active.size() != n || s.shots.in_flight.size() != n || s.shots.size_class.size() != n)
        throw damaged(path, "shot flags of the wrong length");
    if (s.emitted_per_source.size() != model.sources.size() || s.collected_per_sink.size() != model.sinks.size())
        throw damaged(path, "counts for " + std::to_string(s.emitted_per_source.size()) + " sources and " +
                                std::to_string(s.collected_per_sink.size()) + " sinks, the scene has " +
                                std::to_string(model.sources.size()) + " and " + std::to_string(model.sinks.size()));
    if (s.shots_per_size.size() != model.shot_sizes.size())
        throw damaged(path, "shot counts for " + std::to_string(s.shots_per_size.size()) + " sizes, the scene has " +
                                std::to_string(model.shot_sizes.size()));
    if (s.impacts_per_component.size() != model.components.size() || s.slow_contacts_per_component.size() != model.components.size())
        throw damaged(path, "impact counters for " + std::to_string(s.impacts_per_component.size()) + " components, the scene has " +
                                std::to_string(model.components.size()));
    if (c.normal_speeds.size() != logged_components) throw damaged(path, "logged components differ from the scene");
    const std::vector<std::vector<double>> fresh = fresh_law_state(model);
    if (s.law_state.size() != fresh.size()) throw damaged(path, "contact law state for the wrong number of components");
    for (std::size_t k = 0; k < fresh.size(); ++k) {
        if (s.law_state[k].size() != fresh[k].size())
            throw damaged(path, "component " + model.components[k].name + ": contact law state of the wrong length");
        for (double x : s.law_state[k])
            if (!std::isfinite(x))
                throw damaged(path, "component " + model.components[k].name + ": contact law state that is not a number");
    }
    for (const auto& [key, entry] : s.contacts.entries()) {
        const auto [shot, c] = key;
        if (shot < 0 || static_cast<std::size_t>(shot) >= n || c < 0 || static_cast<std::size_t>(c) >= model.components.size())
            throw damaged(path, "a contact of shot " + std::to_string(shot) + " with component " + std::to_string(c) + ": no such pair");
        const std::size_t per = static_cast<std::size_t>(model.components[static_cast<std::size_t>(c)].law->state_per_contact());
        if (entry.values.size() != per)
            throw damaged(path, "component " + model.components[static_cast<std::size_t>(c)].name + ": contact state of the wrong length");
        for (double x : entry.values)
            if (!std::isfinite(x))
                throw damaged(path,
                              "component " + model.components[static_cast<std::size_t>(c)].name + ": contact state that is not a number");
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
        if (!finite(k.spring_m) || !finite(k.normal) || !(std::abs(k.normal.norm() - 1.0) < 1e-6) || !std::isfinite(k.approach_m_per_s) ||
            !(k.approach_m_per_s >= 0.0) || !std::isfinite(k.start_time_s) || !finite(k.start_point_m) ||
            !finite(k.start_velocity_m_per_s) || !std::isfinite(k.start_tangential_m_per_s))
            throw damaged(path, "a soft contact of shot " + std::to_string(k.shot) + ": values that are not numbers, or not a unit normal");
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (s.shots.active[i] > 1 || s.shots.in_flight[i] > 1) throw damaged(path, "shot " + std::to_string(i) + ": flags not 0 or 1");
        if (s.shots.size_class[i] >= model.shot_sizes.size())
            throw damaged(path, "shot " + std::to_string(i) + ": size " + std::to_string(s.shots.size_class[i]) + ", the scene has " +
                                    std::to_string(model.shot_sizes.size()));
        if (!s.shots.active[i]) continue;
        const Vec3 p = s.shots.position(i), v = s.shots.velocity(i);
        if (!finite(p) || !finite(v) || !finite(s.shots.spin(i)))
            throw damaged(path, "shot " + std::to_string(i) + ": a position, velocity or spin that is not a number");
        if ((p.array() < model.world_lo.array()).any() || (p.array() > model.world_hi.array()).any())
            throw damaged(path, "shot " + std::to_string(i) + ": active but outside the assembly");
    }
    if (!std::isfinite(c.wall_time_s) || c.wall_time_s < 0.0) throw damaged(path, "a wall time that is not a non-negative number");
}

}  // namespace peensim
