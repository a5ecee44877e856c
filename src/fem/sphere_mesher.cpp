#include "fem/sphere_mesher.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace peensim {

namespace {

constexpr double kCentreCubeHalfWidth = 0.6;  // -, half-width of the blended inner cube, in radii per shell

// Position of the cube grid point t (each component in [-1, 1]) on the ball of radius r.
Vec3 ball_point(const Vec3& t, double r) {
    const double s = t.cwiseAbs().maxCoeff();  // the shell: 0 at the centre, 1 on the surface
    if (s == 0.0) return Vec3::Zero();
    const Vec3 q = t / s;  // on the unit cube's surface
    const Vec3 d(std::tan(M_PI / 4.0 * q.x()), std::tan(M_PI / 4.0 * q.y()), std::tan(M_PI / 4.0 * q.z()));
    const Vec3 on_sphere = d.normalized();
    return r * s * ((1.0 - s) * kCentreCubeHalfWidth * q + s * on_sphere);
}

}  // namespace

SphereMesh mesh_sphere(double radius_m, int divisions, bool quarter) {
    if (!(radius_m > 0.0) || divisions < 2 || divisions % 2 != 0)
        throw std::invalid_argument("mesh_sphere: radius must be positive and divisions even and >= 2");
    const int n = divisions, h = n / 2;
    const int i0 = quarter ? h : 0;  // first grid index in x and y
    const int nxy = n - i0 + 1, nz = n + 1;
    auto node = [&](int i, int j, int k) { return (i - i0) + nxy * ((j - i0) + nxy * k); };
    SphereMesh s;
    for (int k = 0; k < nz; ++k)
        for (int j = i0; j <= n; ++j)
            for (int i = i0; i <= n; ++i) {
                const Vec3 t(2.0 * i / n - 1.0, 2.0 * j / n - 1.0, 2.0 * k / n - 1.0);
                Vec3 p = ball_point(t, radius_m);
                if (i == h) p.x() = 0.0;  // exactly on the symmetry planes
                if (j == h) p.y() = 0.0;
                if (i == h && j == h && k == h) s.centre_node = node(i, j, k);
                if (i == h) s.x0.push_back(node(i, j, k));
                if (j == h) s.y0.push_back(node(i, j, k));
                s.mesh.nodes.push_back(p);
            }
    for (int k = 0; k < n; ++k)
        for (int j = i0; j < n; ++j)
            for (int i = i0; i < n; ++i) {
                const int e = static_cast<int>(s.mesh.elements.size());
                s.mesh.elements.push_back(grid_cell(i, j, k, node));
                if (k == 0) s.surface.push_back({e, 1});
                if (k == n - 1) s.surface.push_back({e, 2});
                if (j == 0) s.surface.push_back({e, 3});
                if (i == n - 1) s.surface.push_back({e, 4});
                if (j == n - 1) s.surface.push_back({e, 5});
                if (i == 0) s.surface.push_back({e, 6});
            }
    return s;
}

}  // namespace peensim
