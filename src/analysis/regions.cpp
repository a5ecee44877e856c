#include "analysis/regions.h"

#include <cmath>
#include <numbers>

#include "common/input_error.h"

namespace peensim {
namespace {

constexpr double full_turn_rad = 2.0 * std::numbers::pi;  // rad

Vec3 centroid(const TriangleMesh& mesh, std::size_t t) {
    return (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;  // m
}

// Angle of `p` about the axis, right-hand about axis_direction, 0 along the reference projected
// normal to the axis; in [0, 2 pi) (rad). A point on the axis gets angle 0.
class AxisAngle {
public:
    explicit AxisAngle(const RegionDesc& r) : point_(r.axis_point_m), axis_(r.axis_direction) {
        u_ = (r.reference - r.reference.dot(axis_) * axis_).normalized();
        v_ = axis_.cross(u_);
    }
    double operator()(const Vec3& p) const {
        const Vec3 d = p - point_;
        const double a = std::atan2(d.dot(v_), d.dot(u_));  // rad, (-pi, pi]
        return a < 0.0 ? a + full_turn_rad : a;
    }

private:
    Vec3 point_, axis_, u_, v_;
};

// Whether `angle` lies in [from, from + width) modulo a full turn (rad).
bool in_sector(double angle, double from, double width) {
    double d = std::fmod(angle - from, full_turn_rad);
    if (d < 0.0) d += full_turn_rad;
    return d < width || width >= full_turn_rad;
}

template <class Inside>
Region select(const TriangleMesh& mesh, std::string name, Inside inside) {
    Region out{std::move(name), {}};
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
        if (inside(t)) out.triangles.push_back(static_cast<int>(t));
    return out;
}

void add_sectors(const TriangleMesh& mesh, const RegionDesc& r, std::vector<Region>& out) {
    const AxisAngle angle_of(r);
    const double pitch = full_turn_rad / r.count;  // rad between sector centres
    const std::vector<std::string> names = region_names(r);
    const std::size_t first = out.size();
    for (const std::string& n : names) out.push_back({n, {}});
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const double a = angle_of(centroid(mesh, t));
        for (int i = 0; i < r.count; ++i)
            if (in_sector(a, r.offset_rad + i * pitch - 0.5 * r.width_rad, r.width_rad))
                out[first + static_cast<std::size_t>(i)].triangles.push_back(static_cast<int>(t));
    }
}

int group_index(const TriangleMesh& mesh, const RegionDesc& r) {
    for (std::size_t g = 0; g < mesh.group_names.size(); ++g)
        if (mesh.group_names[g] == r.group) return static_cast<int>(g);
    std::string known;
    for (const std::string& g : mesh.group_names)
        if (!g.empty()) known += (known.empty() ? "'" : ", '") + g + "'";
    throw InputError(r.where, "regions." + r.name + ".group",
                     "the mesh has no group '" + r.group + "'; its groups: " + (known.empty() ? "none named" : known));
}

}  // namespace

std::vector<Region> select_regions(const TriangleMesh& mesh, const std::vector<RegionDesc>& regions) {
    std::vector<Region> out;
    for (const RegionDesc& r : regions) {
        switch (r.kind) {
            case RegionKind::sector: {
                const AxisAngle angle_of(r);
                out.push_back(select(mesh, r.name, [&](std::size_t t) {
                    return in_sector(angle_of(centroid(mesh, t)), r.from_rad, r.to_rad - r.from_rad);
                }));
                break;
            }
            case RegionKind::sectors: add_sectors(mesh, r, out); break;
            case RegionKind::box:
                out.push_back(select(mesh, r.name, [&](std::size_t t) {
                    const Vec3 c = centroid(mesh, t);
                    return (c.array() >= r.box_min_m.array()).all() && (c.array() <= r.box_max_m.array()).all();
                }));
                break;
            case RegionKind::half_space:
                out.push_back(
                    select(mesh, r.name, [&](std::size_t t) { return (centroid(mesh, t) - r.plane_point_m).dot(r.plane_normal) >= 0.0; }));
                break;
            case RegionKind::group: {
                const int g = group_index(mesh, r);
                out.push_back(select(mesh, r.name,
                                     [&](std::size_t t) { return t < mesh.group_of_triangle.size() && mesh.group_of_triangle[t] == g; }));
                break;
            }
        }
    }
    return out;
}

}  // namespace peensim
