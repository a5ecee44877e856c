#include "app/checkpoint.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/byte_stream.h"
#include "output/atomic_file.h"

namespace peensim {

namespace {

// The last character is the format version: 2 added the slow-contact counters and the per-shot
// in-flight flags.
constexpr char kMagic[8] = {'P', 'E', 'E', 'N', 'C', 'K', 'P', '2'};

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
    }
    for (const auto* v : {&s.shots.x, &s.shots.y, &s.shots.z, &s.shots.vx, &s.shots.vy, &s.shots.vz}) w.put_vector(*v);
    w.put_vector(s.shots.active);
    w.put_vector(s.shots.in_flight);
    w.put(c.csv_bytes);
    w.put(c.csv_rows);
    w.put<std::uint64_t>(c.normal_speeds.size());
    for (const SpeedHistogram& h : c.normal_speeds) w.put_string(h.serialize());
    w.put(c.wall_time_s);
    write_file_atomically(path, w.bytes());
}

Checkpoint load_checkpoint(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": no checkpoint to resume from");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    const std::string bytes = buffer.str();
    if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
        throw std::runtime_error(path + ": not a peensim checkpoint of this version");
    ByteReader r(std::string_view(bytes).substr(sizeof(kMagic)), path + ": checkpoint");
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
        s.lost.push_back(l);
    }
    for (auto* v : {&s.shots.x, &s.shots.y, &s.shots.z, &s.shots.vx, &s.shots.vy, &s.shots.vz}) *v = r.get_vector<double>();
    s.shots.active = r.get_vector<unsigned char>();
    s.shots.in_flight = r.get_vector<unsigned char>();
    c.csv_bytes = r.get<std::uint64_t>();
    c.csv_rows = r.get<std::uint64_t>();
    const auto histograms = r.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < histograms; ++k) c.normal_speeds.push_back(SpeedHistogram::deserialize(r.get_string()));
    c.wall_time_s = r.get<double>();
    if (!r.at_end()) throw std::runtime_error(path + ": checkpoint has trailing bytes");
    return c;
}

}  // namespace peensim
