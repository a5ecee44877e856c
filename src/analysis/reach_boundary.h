// Where the reachable surface ends: how far each coverage sample lies from the samples no shot can
// touch, so that the forecast covers the samples near them at the rate they are really covered.
//
// Why it matters. A dent is centred where a shot touched (the reachable surface) and covers its
// disc, so a reachable point at distance d from the end of the reachable surface (a bore that an
// axle fills, a root fillet narrower than the shot, the corner of a concave step) is covered only
// by the dents centred on its own side: at the rate mu f(d, rho), with f the share of the dent's
// disc on the reachable side of a straight boundary (1/2 at the boundary). The areal kernel's rate
// assumes the whole disc. On the shipped gear the bands within a dent radius of the axle ring and
// of the roots stay uncovered longest, and without f the forecast was early there (the ring band
// 3-12 % early from 60 s) by an amount no kernel radius changes. (At a convex edge the dents
// centred on the edge line make up for the missing half: they are the edge lines' own process.)
//
// How. Near the boundary only (within a cube of side reach of it; reach: the largest dent
// radius), the reachable samples are binned into voxels of side reach / kReachVoxelsPerRadius and
// the unreachable ones (the sources) into finer voxels at their samples' mean. Each source is
// passed on from voxel to neighbouring reachable voxel while it is the nearest one seen there and
// faces within 60 degrees the same way (vector propagation, as in a Euclidean distance transform).
// A sample's distance is the one to the boundary taken as the straight line through its voxel's
// source, square to the direction from that source to the voxel: not to the source itself, which
// for a sample beside the voxel's point lies off to the side (that read the distances too long and
// undid half of the correction on the gear's axle ring).
//
// Pure computation: no file I/O.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "analysis/coverage_progress.h"
#include "analysis/cube_keys.h"
#include "common/flat_key_map.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

inline constexpr int kReachBands = 8;                 // the forecast's bands of distance to the boundary per largest dent radius
inline constexpr double kReachVoxelsPerRadius = 2.0;  // voxels of the propagation per largest dent radius (nesting in cubes of one)

// The share of a disc of radius rho (m) that lies on its centre's side of a straight line at
// distance d (m) from the centre: 1 - (circular segment beyond the line) / (pi rho^2).
double disc_share_inside(double d_m, double rho_m);

class ReachBoundary {
public:
    // The reach boundary of the progress's samples; reach_m: the largest dent radius (m), the
    // farthest a boundary matters.
    ReachBoundary(const CoverageProgress& progress, const TriangleMesh& mesh, double reach_m);

    // Whether triangle t may hold reachable samples within reach_m of the boundary.
    bool near(std::size_t t) const { return !near_triangle_.empty() && near_triangle_[t]; }

    // The voxel of the reachable sample at x (m) when the propagation found an unreachable sample
    // facing within 60 degrees its way within reach_m of it; else kNoSource.
    std::uint32_t source_near(const Vec3& x) const;
    static constexpr std::uint32_t kNoSource = 0xFFFFFFFFu;

    // The distance (m) from the reachable sample at x (m) of voxel `voxel` (source_near) to the
    // boundary; +inf from reach_m on, or without a voxel.
    double distance(const Vec3& x, std::uint32_t voxel) const;

    // Whether a reachable voxel with a source lies in the cube of side reach_m (corner at the
    // origin) holding x: only there can source_near find one, so a row's samples need looking up
    // voxel by voxel only in those cubes.
    bool sources_near(const Vec3& x) const { return !source_cubes_.empty() && source_cubes_.contains(cube_key_of(x, inverse_reach_)); }

    // f(key) for the key (cube_key, side reach_m) of every cube sources_near is true in, in no order.
    template <class F>
    void for_each_source_cube(F&& f) const {
        source_cubes_.for_each([&](std::uint64_t key, std::uint8_t) { f(key); });
    }

    double reach_m() const { return reach_m_; }
    double inverse_side() const { return inverse_side_; }  // 1/m, of the voxels

private:
    struct Voxel {
        Vec3 point = Vec3::Zero();  // m: a reachable voxel's first sample; a source's sample mean
        float normal[3] = {0, 0, 0};
        float source_d2 = std::numeric_limits<float>::infinity();  // m2: from point to the nearest source found
        std::uint32_t source = kNoSource;                          // that source (its voxel)
        std::uint32_t count = 0;                                   // samples (sources)
        bool reachable = false;
    };
    // The sources' voxels are finer (a source's place is its samples' mean: off the boundary by
    // up to half its voxel, which would read as distance).
    static constexpr double kSourceVoxelsPerVoxel = 4.0;
    static constexpr std::uint64_t kReachableKeyBit = std::uint64_t{1} << 63;  // a reachable voxel's key has it
    std::uint64_t key(const Vec3& p, bool reachable) const {
        return reachable ? cube_key_of(p, inverse_side_) | kReachableKeyBit : cube_key_of(p, kSourceVoxelsPerVoxel * inverse_side_);
    }
    double reach_m_ = 0.0;
    double inverse_reach_ = 0.0;  // 1/m, of the cubes of side reach_m
    double inverse_side_ = 0.0;   // 1/m, of the voxels
    std::vector<Voxel> voxels_;
    FlatKeyMap<std::uint32_t> index_;
    FlatKeyMap<std::uint8_t> source_cubes_;  // the cubes of side reach_m with a reachable voxel that has a source
    std::vector<bool> near_triangle_;
};

}  // namespace peensim
