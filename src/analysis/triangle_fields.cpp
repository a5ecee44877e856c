#include "analysis/triangle_fields.h"

#include <algorithm>
#include <limits>

#include "kernels/closest_point.h"

namespace peensim {

TriangleFields::TriangleFields(const TriangleMesh& mesh, double shot_mass_kg)
    : mesh_(&mesh),
      shot_mass_(shot_mass_kg),
      area_(mesh.triangle_count()),
      count_(mesh.triangle_count(), 0),
      sum_(mesh.triangle_count(), 0.0),
      max_(mesh.triangle_count(), 0.0),
      energy_(mesh.triangle_count(), 0.0) {
    int facets = 0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const int f = mesh.source_facet.empty() ? static_cast<int>(t) : mesh.source_facet[t];
        facets = std::max(facets, f + 1);
        area_[t] = 0.5 * (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0)).norm();
    }
    first_triangle_of_facet_.assign(static_cast<std::size_t>(facets), -1);
    triangles_of_facet_.assign(static_cast<std::size_t>(facets), 0);
    // Triangles of one facet are consecutive (the loader fans each polygon in place).
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const auto f = static_cast<std::size_t>(mesh.source_facet.empty() ? static_cast<int>(t) : mesh.source_facet[t]);
        if (first_triangle_of_facet_[f] < 0) first_triangle_of_facet_[f] = static_cast<int>(t);
        ++triangles_of_facet_[f];
    }
}

int TriangleFields::add(int facet, const Vec3& point, double vn, double shot_mass_kg) {
    if (facet < 0 || static_cast<std::size_t>(facet) >= first_triangle_of_facet_.size() ||
        first_triangle_of_facet_[static_cast<std::size_t>(facet)] < 0) {
        ++unknown_;
        return -1;
    }
    int t = first_triangle_of_facet_[static_cast<std::size_t>(facet)];
    const int n = triangles_of_facet_[static_cast<std::size_t>(facet)];
    if (n > 1) {
        double best = std::numeric_limits<double>::infinity();
        for (int k = 0; k < n; ++k) {
            const auto tt = static_cast<std::size_t>(first_triangle_of_facet_[static_cast<std::size_t>(facet)] + k);
            const double d2 =
                (closest_point_on_triangle(point, mesh_->corner(tt, 0), mesh_->corner(tt, 1), mesh_->corner(tt, 2)).point - point)
                    .squaredNorm();
            if (d2 < best) {
                best = d2;
                t = static_cast<int>(tt);
            }
        }
    }
    const auto i = static_cast<std::size_t>(t);
    ++count_[i];
    sum_[i] += vn;
    max_[i] = std::max(max_[i], vn);
    energy_[i] += 0.5 * shot_mass_kg * vn * vn;
    return t;
}

double TriangleFields::mean_normal_speed(std::size_t t) const {
    return count_[t] ? sum_[t] / static_cast<double>(count_[t]) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace peensim
