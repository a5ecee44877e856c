#include "engine/event/pair_predictor.h"

#include <limits>

#include "common/float_limits.h"
#include "kernels/sphere_pair_toi.h"

namespace peensim {

PairPredictor::PairPredictor(int shot_count, double resting_speed_m_per_s)
    : shot_count_(shot_count), resting_speed_(resting_speed_m_per_s), boxes_(std::make_unique<ShotBoxTree>(shot_count)) {
    neighbours_.reserve(64);
}

void PairPredictor::reset() { boxes_ = std::make_unique<ShotBoxTree>(shot_count_); }

void PairPredictor::grow(int shot_count) {
    if (shot_count <= shot_count_) return;
    shot_count_ = shot_count;
    boxes_->grow(shot_count);
}

void PairPredictor::set_box(int shot, const Vec3& lo, const Vec3& hi) { boxes_->set(shot, lo, hi); }

void PairPredictor::remove(int shot) { boxes_->remove(shot); }

bool PairPredictor::predict(int i, double t, std::span<EventShot> shots, const std::vector<unsigned char>& active, const EventQueue& queue,
                            StepStats& stats) {
    EventShot& s = shots[static_cast<std::size_t>(i)];
    s.pair_time = kInf;
    s.partner = -1;
    bool joins_pile = false;
    // One timer for the neighbour query and the pair tests: both are short, and reading the clock
    // around each was a visible cost.
    StageTimer timer(stats, Stage::shot_contacts);
    boxes_->overlapping(s.box_lo, s.box_hi, neighbours_);
    pooled_neighbours_.clear();
    // Ties between partners go to the lowest index, whatever order the tree returns them in.
    for (const int j : neighbours_) {
        if (j == i || !active[static_cast<std::size_t>(j)]) continue;
        const EventShot& o = shots[static_cast<std::size_t>(j)];
        if (o.motion == EventMotion::pooled) {
            pooled_neighbours_.push_back(j);
            continue;
        }
        // The partner's flight is known up to its own next event; after that it re-predicts.
        const double end = std::min(s.box_until, queue.time_of(j));
        if (end < t) continue;
        ++stats.pair_tests;
        PairContact pc;
        const ToiStatus st = sphere_pair_toi(s.path, s.radius_m, o.path, o.radius_m, t, end, pc);
        if (st == ToiStatus::miss) continue;
        // Riding shots' paths leave out the plate's motion: their exact positions are checked in collide_pair.
        if (st == ToiStatus::overlapping || pc.time == t) {
            if (st == ToiStatus::impact && j == s.last_partner && s.last_pair_time == t) continue;  // just collided
            if (t == s.no_pairs_at || t == o.no_pairs_at) continue;                                 // forced progress (see advance)
            // Touching (or overlapping) now, with a shot in sustained contact or asleep: a contact
            // within a pile, which the substeps resolve. As events, shot touching several others at
            // once pass the approach (or the overlap) round among themselves forever at the same
            // instant: a pile jams. A flying shot pressed into a pile (overlapping it, or touching
            // it slower than the resting speed) joins it; a faster one bounces off it (an event).
            const bool s_rests = s.motion == EventMotion::sustained || s.motion == EventMotion::sleeping;
            const bool o_rests = o.motion == EventMotion::sustained || o.motion == EventMotion::sleeping;
            if (s_rests && o_rests) continue;
            if (s_rests || o_rests) {
                const double approach = -(o.path.velocity(t) - s.path.velocity(t)).dot(pc.normal);
                if (st == ToiStatus::overlapping || approach <= resting_speed_) {
                    joins_pile |= !s_rests;
                    continue;
                }
            }
        }
        const double when = st == ToiStatus::overlapping ? t : pc.time;
        if (when < s.pair_time || (when == s.pair_time && j < s.partner)) {
            s.pair_time = when;
            s.partner = j;
            s.partner_version = o.version;
        }
    }
    return joins_pile;
}

}  // namespace peensim
