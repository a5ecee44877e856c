#include "geometry/box_mesh.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "common/input_error.h"
#include "geometry/mesh_builder.h"
#include "geometry/polar_surfaces.h"

namespace peensim {

namespace {

const std::array<std::string, 6> kFaceNames{"-x", "+x", "-y", "+y", "-z", "+z"};

void check(const BoxSpec& spec) {
    for (int a = 0; a < 3; ++a) {
        if (!(spec.size_m[a] > 0.0)) throw InputError({}, "box", "every edge length must be positive");
        if (spec.divisions[a] < 1) throw InputError({}, "box", "every face needs at least one division per edge");
    }
}

TriangleMesh build_box(const BoxSpec& spec, std::optional<BoxFace> open_face, Facing facing) {
    check(spec);
    // Grid coordinates per axis, computed once: faces that meet share exact values.
    std::array<std::vector<double>, 3> grid;
    for (int a = 0; a < 3; ++a) {
        const double lo = spec.center_m[a] - 0.5 * spec.size_m[a];
        const double hi = spec.center_m[a] + 0.5 * spec.size_m[a];
        for (int k = 0; k <= spec.divisions[a]; ++k) grid[static_cast<std::size_t>(a)].push_back(subdivision(lo, hi, k, spec.divisions[a]));
    }

    MeshBuilder builder;
    // The open face's number, read once (-1: none): GCC merged `open_face && *open_face == face`
    // into one test that reads the empty optional's payload, which valgrind reports.
    const int open = open_face.has_value() ? static_cast<int>(open_face.value()) : -1;
    for (int face = 0; face < 6; ++face) {
        if (face == open) continue;
        const int normal_axis = face / 2;
        const bool on_max_side = face % 2 == 1;
        // (b, c, normal) is a cyclic, right-handed order: b x c = +normal.
        const int b = (normal_axis + 1) % 3;
        const int c = (normal_axis + 2) % 3;
        const auto& gn = grid[static_cast<std::size_t>(normal_axis)];
        const auto& gb = grid[static_cast<std::size_t>(b)];
        const auto& gc = grid[static_cast<std::size_t>(c)];
        const double level = on_max_side ? gn.back() : gn.front();
        // Counter-clockwise around +normal; flipped on the min side (outward there is -normal)
        // and again for inward-facing surfaces.
        const bool counter_clockwise = on_max_side == (facing == Facing::outward);
        const int group = builder.group(kFaceNames[static_cast<std::size_t>(face)]);
        auto corner = [&](std::size_t i, std::size_t j) {
            Vec3 p;
            p[normal_axis] = level;
            p[b] = gb[i];
            p[c] = gc[j];
            return p;
        };
        for (std::size_t i = 0; i + 1 < gb.size(); ++i) {
            for (std::size_t j = 0; j + 1 < gc.size(); ++j) {
                const Vec3 p00 = corner(i, j), p10 = corner(i + 1, j), p11 = corner(i + 1, j + 1), p01 = corner(i, j + 1);
                if (counter_clockwise)
                    builder.add_quad(p00, p10, p11, p01, group);
                else
                    builder.add_quad(p00, p01, p11, p10, group);
            }
        }
    }
    return builder.take();
}

}  // namespace

TriangleMesh box(const BoxSpec& spec) { return build_box(spec, std::nullopt, Facing::outward); }

TriangleMesh box_open(const BoxSpec& spec, BoxFace open_face, Facing facing) { return build_box(spec, open_face, facing); }

}  // namespace peensim
