#include "geometry/winding_number.h"

#include <cmath>

namespace peensim {

double winding_number(const TriangleMesh& mesh, const Vec3& p) {
    double sum_rad = 0.0;  // sr, the signed solid angle
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        // Van Oosterom and Strackee (1983): tan(Omega / 2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|).
        const Vec3 a = mesh.corner(t, 0) - p, b = mesh.corner(t, 1) - p, c = mesh.corner(t, 2) - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double numerator = a.dot(b.cross(c));
        const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        sum_rad += 2.0 * std::atan2(numerator, denominator);
    }
    return sum_rad / (4.0 * M_PI);
}

}  // namespace peensim
