// The event-driven scheme's shot-shot prediction: each shot's flight box in a tree (ShotBoxTree),
// and for a shot the earliest contact with a neighbour whose box overlaps its own, taken exactly
// (sphere_pair_toi) up to the earlier of the two flights' next events. Owns the tree; reads the
// shot records, writes only the predicted shot's pair event.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "collision/shot_box_tree.h"
#include "engine/event/event_queue.h"
#include "engine/event/shot_record.h"
#include "engine/step_stats.h"

namespace peensim {

class PairPredictor {
public:
    // resting_speed_m_per_s: a shot touching a resting one slower than this joins its pile. Each
    // shot's radius is its record's (EventShot::radius_m).
    PairPredictor(int shot_count, double resting_speed_m_per_s);

    void reset();                                            // an empty tree (a restart)
    void grow(int shot_count);                               // room for shot_count shot (a source emitted)
    void set_box(int shot, const Vec3& lo, const Vec3& hi);  // m, world
    void remove(int shot);
    // The shot whose boxes overlap [lo, hi] (m, world), in no particular order.
    void overlapping(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const { boxes_->overlapping(lo, hi, out); }

    // Sets shots[i]'s earliest pair event from t on (pair_time, partner, partner_version; +inf and
    // -1 for none). Returns true if shot i is pressed into a pile (touching a resting shot without
    // bouncing off it): it should join the pile's sustained contact. Ties go to the lowest index.
    // Members of a pool (hand_off_pool.h: the soft scheme's) are not predicted against (the pool finds their contacts):
    // the members whose boxes overlap shot i's are listed in pooled_neighbours() instead.
    bool predict(int i, double t, std::span<EventShot> shots, const std::vector<unsigned char>& active, const EventQueue& queue,
                 StepStats& stats);
    // The pool members met by the last predict() (valid until the next).
    const std::vector<int>& pooled_neighbours() const { return pooled_neighbours_; }

private:
    int shot_count_;
    double resting_speed_;  // m/s
    std::unique_ptr<ShotBoxTree> boxes_;
    std::vector<int> neighbours_;  // scratch
    std::vector<int> pooled_neighbours_;
};

}  // namespace peensim
