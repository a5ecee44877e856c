#include "app/checkpoint.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "output/atomic_file.h"

namespace peensim {

namespace {

constexpr char kMagic[8] = {'P', 'E', 'E', 'N', 'C', 'K', 'P', '1'};

class Writer {
public:
    template <class T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
    }
    template <class T>
    void put_vector(const std::vector<T>& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        put<std::uint64_t>(v.size());
        bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }
    void put_string(const std::string& s) {
        put<std::uint64_t>(s.size());
        bytes_ += s;
    }
    std::string& bytes() { return bytes_; }

private:
    std::string bytes_;
};

class Reader {
public:
    Reader(const std::string& bytes, const std::string& path) : bytes_(bytes), path_(path) {}
    template <class T>
    T get() {
        T v;
        need(sizeof(T));
        std::memcpy(&v, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return v;
    }
    template <class T>
    std::vector<T> get_vector() {
        const auto n = get<std::uint64_t>();
        need(n * sizeof(T));
        std::vector<T> v(n);
        std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(T));
        at_ += n * sizeof(T);
        return v;
    }
    std::string get_string() {
        const auto n = get<std::uint64_t>();
        need(n);
        std::string s = bytes_.substr(at_, n);
        at_ += n;
        return s;
    }
    bool at_end() const { return at_ == bytes_.size(); }

private:
    void need(std::size_t n) const {
        if (at_ + n > bytes_.size()) throw std::runtime_error(path_ + ": checkpoint is truncated");
    }
    const std::string& bytes_;
    const std::string& path_;
    std::size_t at_ = 0;
};

}  // namespace

void save_checkpoint(const std::string& path, const Checkpoint& c) {
    Writer w;
    w.bytes().append(kMagic, sizeof(kMagic));
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
    w.put<std::uint64_t>(s.lost.size());
    for (const LostShot& l : s.lost) {
        w.put(l.shot);
        w.put(l.time_s);
        for (int k = 0; k < 3; ++k) w.put(l.position_m[k]);
    }
    for (const auto* v : {&s.shots.x, &s.shots.y, &s.shots.z, &s.shots.vx, &s.shots.vy, &s.shots.vz}) w.put_vector(*v);
    w.put_vector(s.shots.active);
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
    const std::string body = bytes.substr(sizeof(kMagic));  // Reader keeps a reference: must outlive it
    Reader r(body, path);
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
    const auto lost = r.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < lost; ++k) {
        LostShot l;
        l.shot = r.get<int>();
        l.time_s = r.get<double>();
        for (int a = 0; a < 3; ++a) l.position_m[a] = r.get<double>();
        s.lost.push_back(l);
    }
    for (auto* v : {&s.shots.x, &s.shots.y, &s.shots.z, &s.shots.vx, &s.shots.vy, &s.shots.vz}) *v = r.get_vector<double>();
    s.shots.active = r.get_vector<unsigned char>();
    c.csv_bytes = r.get<std::uint64_t>();
    c.csv_rows = r.get<std::uint64_t>();
    const auto histograms = r.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < histograms; ++k) c.normal_speeds.push_back(SpeedHistogram::deserialize(r.get_string()));
    c.wall_time_s = r.get<double>();
    if (!r.at_end()) throw std::runtime_error(path + ": checkpoint has trailing bytes");
    return c;
}

}  // namespace peensim
