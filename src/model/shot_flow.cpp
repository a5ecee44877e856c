#include "model/shot_flow.h"

#include "kernels/box_entry.h"

namespace peensim {

bool BoxSink::contains(const Vec3& p) const {
    const bool in = (p.array() >= lo_.array()).all() && (p.array() <= hi_.array()).all();
    return side_ == Side::inside ? in : !in;
}

std::optional<double> BoxSink::first_entry(const Trajectory& path, double ta, double tb) const {
    return side_ == Side::inside ? first_time_inside_box(path, lo_, hi_, ta, tb) : first_time_outside_box(path, lo_, hi_, ta, tb);
}

}  // namespace peensim
