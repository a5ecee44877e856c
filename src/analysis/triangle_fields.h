// Per-triangle impact statistics of one component, accumulated row by row from the impact log
// (constant memory per triangle, whatever the number of impacts): count, mean and max normal
// speed, and the kinetic energy of the normal motion delivered per unit area.
#pragma once

#include <cstdint>
#include <vector>

#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

class TriangleFields {
public:
    // shot_mass_kg: mass of one shot (kg), for the delivered energy.
    TriangleFields(const TriangleMesh& mesh, double shot_mass_kg);

    // One impact on facet `facet` of the mesh file at `point` (component frame, m), normal speed
    // `vn` (m/s). A facet the file split into several triangles (a polygon) credits the one of
    // them closest to the point. Returns the triangle credited, or -1 for a facet the mesh lacks.
    int add(int facet, const Vec3& point, double vn_m_per_s) { return add(facet, point, vn_m_per_s, shot_mass_); }
    // The same for a shot of its own mass (kg; a mix's log gives each impact's shot).
    int add(int facet, const Vec3& point, double vn_m_per_s, double shot_mass_kg);

    std::size_t triangle_count() const { return count_.size(); }
    std::uint64_t count(std::size_t t) const { return count_[t]; }
    double area_m2(std::size_t t) const { return area_[t]; }
    double mean_normal_speed(std::size_t t) const;                                 // m/s (NaN without impacts)
    double max_normal_speed(std::size_t t) const { return max_[t]; }               // m/s (0 without impacts)
    double energy_per_area(std::size_t t) const { return energy_[t] / area_[t]; }  // J/m2, 1/2 m vn^2 summed
    // Impacts per mm2 per second over `duration_s`.
    double rate_per_mm2_s(std::size_t t, double duration_s) const { return count_[t] / (area_[t] * 1e6) / duration_s; }
    std::uint64_t unknown_facets() const { return unknown_; }

private:
    const TriangleMesh* mesh_;
    double shot_mass_;
    std::vector<int> first_triangle_of_facet_;  // -1: no such facet
    std::vector<int> triangles_of_facet_;       // number of triangles per facet
    std::vector<double> area_;                  // m2
    std::vector<std::uint64_t> count_;
    std::vector<double> sum_;     // m/s
    std::vector<double> max_;     // m/s
    std::vector<double> energy_;  // J
    std::uint64_t unknown_ = 0;
};

}  // namespace peensim
