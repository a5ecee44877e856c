#include "app/run/replica_result_codec.h"

#include <cstring>
#include <type_traits>

#include "common/byte_stream.h"

namespace peensim {

namespace {

constexpr std::uint32_t kResultMagic = 0x52505231;       // "RPR1"
constexpr std::uint32_t kPlanMagic = 0x504c4e31;         // "PLN1"
constexpr std::uint32_t kRoundPlanMagic = 0x524e4431;    // "RND1"
constexpr std::uint32_t kSlotMagic = 0x534c5431;         // "SLT1"
constexpr std::uint32_t kRoundResultMagic = 0x52524531;  // "RRE1"

static_assert(std::is_trivially_copyable_v<HealthCounters>);

void put_window(ByteWriter& w, const ReplicaWindow& x) {
    w.put(x.replica);
    w.put(x.seed);
    w.put(x.log_from_s);
    w.put(x.run_to_s);
    w.put(x.shift_s);
}

ReplicaWindow get_window(ByteReader& r) {
    ReplicaWindow x;
    x.replica = r.get<int>();
    x.seed = r.get<std::uint64_t>();
    x.log_from_s = r.get<double>();
    x.run_to_s = r.get<double>();
    x.shift_s = r.get<double>();
    return x;
}

void put_vec(ByteWriter& w, const Vec3& v) {
    for (int i = 0; i < 3; ++i) w.put(v[i]);
}

Vec3 get_vec(ByteReader& r) {
    Vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = r.get<double>();
    return v;
}

void put_lost(ByteWriter& w, const std::vector<LostShot>& lost) {
    w.put<std::uint64_t>(lost.size());
    for (const LostShot& l : lost) {
        w.put(l.shot);
        w.put(l.time_s);
        put_vec(w, l.position_m);
        w.put(l.cause);
        w.put(l.from_time_s);
        put_vec(w, l.from_m);
        w.put(l.component);
        put_vec(w, l.where_m);
        w.put(l.clearance_m);
        w.put(l.radius_m);
    }
}

std::vector<LostShot> get_lost(ByteReader& r) {
    const auto n = r.get<std::uint64_t>();
    if (n > r.remaining()) r.fail("truncated");
    std::vector<LostShot> lost(n);
    for (LostShot& l : lost) {
        l.shot = r.get<int>();
        l.time_s = r.get<double>();
        l.position_m = get_vec(r);
        l.cause = r.get<LossCause>();
        l.from_time_s = r.get<double>();
        l.from_m = get_vec(r);
        l.component = r.get<int>();
        l.where_m = get_vec(r);
        l.clearance_m = r.get<double>();
        l.radius_m = r.get<double>();
    }
    return lost;
}

void put_counts(ByteWriter& w, const std::vector<NamedCount>& v) {
    w.put<std::uint64_t>(v.size());
    for (const NamedCount& c : v) {
        w.put_string(c.name);
        w.put(c.count);
    }
}

std::vector<NamedCount> get_counts(ByteReader& r) {
    const auto n = r.get<std::uint64_t>();
    if (n > r.remaining()) r.fail("truncated");
    std::vector<NamedCount> v(n);
    for (NamedCount& c : v) {
        c.name = r.get_string();
        c.count = r.get<std::uint64_t>();
    }
    return v;
}

// A reader of bytes that must begin with `magic`; what: what they hold ("a replica's slot").
ByteReader reader_of(std::string_view bytes, const std::string& what, std::uint32_t magic) {
    ByteReader r(bytes, what);
    if (r.get<std::uint32_t>() != magic) r.fail("not " + what);
    return r;
}

// What the run's summary merges from a replica's own: its counts, health, stage times and steps.
void put_summary(ByteWriter& w, const RunSummary& s) {
    put_counts(w, s.impacts_per_component);
    put_counts(w, s.slow_contacts_per_component);
    put_counts(w, s.health_counters);
    w.put<std::uint64_t>(s.stage_times.size());
    for (const StageTime& t : s.stage_times) {
        w.put_string(t.stage);
        w.put(t.seconds);
    }
    w.put(s.steps);
    w.put(s.shot_steps);
    w.put(s.shot_lost);
    w.put(s.shots_in_flight);
    w.put(s.shots_at_rest);
    w.put(s.finished);
}

RunSummary get_summary(ByteReader& r) {
    RunSummary s;
    s.impacts_per_component = get_counts(r);
    s.slow_contacts_per_component = get_counts(r);
    s.health_counters = get_counts(r);
    const auto stages = r.get<std::uint64_t>();
    if (stages > r.remaining()) r.fail("truncated");
    s.stage_times.resize(stages);
    for (StageTime& t : s.stage_times) {
        t.stage = r.get_string();
        t.seconds = r.get<double>();
    }
    s.steps = r.get<std::uint64_t>();
    s.shot_steps = r.get<std::uint64_t>();
    s.shot_lost = r.get<std::uint64_t>();
    s.shots_in_flight = r.get<std::uint64_t>();
    s.shots_at_rest = r.get<std::uint64_t>();
    s.finished = r.get<bool>();
    return s;
}

}  // namespace

std::string encode_replica_result(const ReplicaResult& x) {
    ByteWriter w;
    w.put(kResultMagic);
    put_window(w, x.window);
    put_summary(w, x.summary);
    w.put_vector(x.impacts_at_window_start);
    w.put_vector(x.slow_contacts_at_window_start);
    w.put<std::uint64_t>(x.speeds.size());
    for (const SpeedHistogram& h : x.speeds) w.put_string(h.serialize());
    w.put(x.logged_impacts);
    put_lost(w, x.lost);
    w.put(x.health);
    w.put(x.wall_s);
    return w.bytes();
}

ReplicaResult decode_replica_result(std::string_view bytes) {
    ByteReader r = reader_of(bytes, "a replica's result", kResultMagic);
    ReplicaResult x;
    x.window = get_window(r);
    x.summary = get_summary(r);
    x.impacts_at_window_start = r.get_vector<std::uint64_t>();
    x.slow_contacts_at_window_start = r.get_vector<std::uint64_t>();
    const auto histograms = r.get<std::uint64_t>();
    if (histograms > r.remaining()) r.fail("truncated");
    for (std::uint64_t k = 0; k < histograms; ++k) x.speeds.push_back(SpeedHistogram::deserialize(r.get_string()));
    x.logged_impacts = r.get<std::uint64_t>();
    x.lost = get_lost(r);
    x.health = r.get<HealthCounters>();
    x.wall_s = r.get<double>();
    if (!r.at_end()) r.fail("bytes after its end");
    return x;
}

std::string encode_replica_plan(const ReplicaPlan& plan) {
    ByteWriter w;
    w.put(kPlanMagic);
    w.put(plan.pilot_s);
    w.put(plan.warm_up_s);
    w.put(plan.turn_s);
    w.put<std::uint64_t>(plan.windows.size());
    for (const ReplicaWindow& x : plan.windows) put_window(w, x);
    return w.bytes();
}

ReplicaPlan decode_replica_plan(std::string_view bytes) {
    ByteReader r = reader_of(bytes, "the replicas' plan", kPlanMagic);
    ReplicaPlan plan;
    plan.pilot_s = r.get<double>();
    plan.warm_up_s = r.get<double>();
    plan.turn_s = r.get<double>();
    const auto n = r.get<std::uint64_t>();
    if (n > r.remaining()) r.fail("truncated");
    for (std::uint64_t k = 0; k < n; ++k) plan.windows.push_back(get_window(r));
    if (!r.at_end()) r.fail("bytes after its end");
    return plan;
}

std::string encode_round_plan(const RoundPlan& plan) {
    ByteWriter w;
    w.put(kRoundPlanMagic);
    w.put(plan.pilot_s);
    w.put(plan.warm_up_s);
    w.put(plan.turn_s);
    w.put(plan.first_s);
    w.put(plan.round_s);
    w.put_vector(plan.seeds);
    w.put_vector(plan.first_from_s);
    return w.bytes();
}

bool is_round_plan(std::string_view bytes) {
    std::uint32_t magic = 0;
    if (bytes.size() < sizeof(magic)) return false;
    std::memcpy(&magic, bytes.data(), sizeof(magic));
    return magic == kRoundPlanMagic;
}

RoundPlan decode_round_plan(std::string_view bytes) {
    ByteReader r = reader_of(bytes, "the rounds' plan", kRoundPlanMagic);
    RoundPlan plan;
    plan.pilot_s = r.get<double>();
    plan.warm_up_s = r.get<double>();
    plan.turn_s = r.get<double>();
    plan.first_s = r.get<double>();
    plan.round_s = r.get<double>();
    plan.seeds = r.get_vector<std::uint64_t>();
    plan.first_from_s = r.get_vector<double>();
    if (plan.first_from_s.size() != plan.seeds.size()) r.fail("a start per replica");
    if (!r.at_end()) r.fail("bytes after its end");
    return plan;
}

std::string encode_slot_result(const SlotResult& x) {
    ByteWriter w;
    w.put(kSlotMagic);
    put_window(w, x.window);
    w.put_string(x.spill);
    w.put(x.logged_impacts);
    w.put_vector(x.impacts_at_start);
    w.put_vector(x.slow_contacts_at_start);
    w.put_vector(x.impacts_at_end);
    w.put_vector(x.slow_contacts_at_end);
    return w.bytes();
}

SlotResult decode_slot_result(std::string_view bytes) {
    ByteReader r = reader_of(bytes, "a replica's slot", kSlotMagic);
    SlotResult x;
    x.window = get_window(r);
    x.spill = r.get_string();
    x.logged_impacts = r.get<std::uint64_t>();
    x.impacts_at_start = r.get_vector<std::uint64_t>();
    x.slow_contacts_at_start = r.get_vector<std::uint64_t>();
    x.impacts_at_end = r.get_vector<std::uint64_t>();
    x.slow_contacts_at_end = r.get_vector<std::uint64_t>();
    if (!r.at_end()) r.fail("bytes after its end");
    return x;
}

std::string encode_round_replica_result(const RoundReplicaResult& x) {
    ByteWriter w;
    w.put(kRoundResultMagic);
    w.put(x.replica);
    w.put(x.seed);
    w.put(x.first_from_s);
    put_summary(w, x.summary);
    put_lost(w, x.lost);
    w.put(x.health);
    return w.bytes();
}

RoundReplicaResult decode_round_replica_result(std::string_view bytes) {
    ByteReader r = reader_of(bytes, "a replica's rounds", kRoundResultMagic);
    RoundReplicaResult x;
    x.replica = r.get<int>();
    x.seed = r.get<std::uint64_t>();
    x.first_from_s = r.get<double>();
    x.summary = get_summary(r);
    x.lost = get_lost(r);
    x.health = r.get<HealthCounters>();
    if (!r.at_end()) r.fail("bytes after its end");
    return x;
}

}  // namespace peensim
