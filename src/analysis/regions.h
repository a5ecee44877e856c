// Regions of a component: its scene's `regions` entries as selections of its surface. A region is
// the set of surface points that meet all of its entry's conditions (on the point: sectors, box,
// half-space, distances; on the triangle holding it: facing, group). So an impact belongs to a
// region by its own point, and a triangle by the share of its area inside: each triangle is
// sampled on a regular grid of sub-triangles (the coverage map's scheme, coverage_map.h), and its
// share is the fraction of its samples inside. A sliver crossing a boundary is split by area, not
// given whole to the side its centroid falls on (which made the 20 identical teeth of the shipped
// gear 189 to 431 mm2). Pure computation: no file I/O, no printing.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "geometry/triangle_sampling.h"
#include "scene/scene_description.h"

namespace peensim {

// Triangle `triangle` has `fraction` (0..1] of its area in the region.
struct RegionShare {
    int triangle = 0;
    double fraction = 0.0;
};

// The samples per triangle are bounded so that a mesh costs at most about this many (a triangle of
// any size gets at least one, and at most kRegionSamplesPerEdge^2).
inline constexpr double kRegionSampleBudget = 2e6;
inline constexpr int kRegionSamplesPerEdge = 64;
inline constexpr double kRegionFinestSpacing_m = 0.1e-3;  // m: finer sampling would not change a share

class RegionSet {
public:
    // One region per name of each entry, in order (a `sectors` entry gives `count` regions, sector i
    // centred at offset + i 2 pi / count; angles are taken modulo a full turn, so sectors that tile
    // the turn put every point in exactly one). Throws InputError (at the entry's place in the
    // scene file) for a `group` the mesh does not have.
    RegionSet(const TriangleMesh& mesh, const std::vector<RegionDesc>& regions);
    RegionSet() = default;
    // Its regions point into its own copy of the entries: a move keeps them (the vector's buffer
    // moves with it), a copy points its regions at its own copy. (A copy is far cheaper than the
    // tally: the check, the coverage geometry and the analysis share one set.)
    RegionSet(RegionSet&&) = default;
    RegionSet& operator=(RegionSet&&) = default;
    RegionSet(const RegionSet& other);
    RegionSet& operator=(const RegionSet& other);

    std::size_t size() const { return regions_.size(); }
    bool empty() const { return regions_.empty(); }
    const std::string& name(std::size_t r) const { return regions_[r].name; }
    bool excluded(std::size_t r) const { return regions_[r].entry->exclude; }
    // The scene's entry region r comes from (a `sectors` entry makes several).
    const RegionDesc& entry(std::size_t r) const { return *regions_[r].entry; }
    // The triangles with area in region r, increasing, and their shares.
    const std::vector<RegionShare>& shares(std::size_t r) const { return regions_[r].shares; }
    double area_m2(std::size_t r) const { return regions_[r].area_m2; }  // m2
    double triangle_area_m2(std::size_t t) const { return areas_[t]; }   // m2
    // The triangles with any area in region r (increasing).
    std::vector<int> triangles(std::size_t r) const;

    // Whether the point p (component frame, m) of triangle t lies in region r.
    bool contains(std::size_t r, const Vec3& p, std::size_t t) const;
    // Clears `out`, then lists the regions holding p on triangle t (the candidates: the regions
    // with a share of t, or whose conditions hold at one of its corners). Allocates nothing once
    // `out` has grown.
    void regions_at(const Vec3& p, std::size_t t, std::vector<std::uint32_t>& out) const;

    // The share of triangle t's area in any excluded region (0..1; the union, not a sum).
    double excluded_fraction(std::size_t t) const { return excluded_.empty() ? 0.0 : excluded_[t]; }
    // The region holding most of triangle t's area (the first of equals, an excluded one before the
    // others: a mask names what it masks), -1 for none.
    int dominant_region(std::size_t t) const { return dominant_.empty() ? -1 : dominant_[t]; }

private:
    struct Selected {
        std::string name;
        const RegionDesc* entry = nullptr;  // its conditions (into entries_)
        int sector = -1;                    // sectors: which one
        std::vector<RegionShare> shares;
        double area_m2 = 0.0;
    };

    bool holds(const Selected& s, const Vec3& p, std::size_t t) const;
    bool holds_apart_from_sectors(const RegionDesc& entry, const Vec3& p, std::size_t t) const;

    const TriangleMesh* mesh_ = nullptr;
    std::vector<RegionDesc> entries_;
    std::vector<int> group_of_entry_;  // per entry: the mesh group a `group` names (-1: none)
    std::vector<Vec3> normals_;        // per triangle: unit normal by winding
    std::vector<double> areas_;        // per triangle, m2
    std::vector<Selected> regions_;
    // Candidate regions of triangle t: candidates_[candidate_start_[t] .. candidate_start_[t + 1]).
    std::vector<std::uint32_t> candidate_start_;
    std::vector<std::uint32_t> candidates_;
    std::vector<double> excluded_;  // per triangle (empty: no excluded region)
    std::vector<int> dominant_;     // per triangle (empty: no region)
};

}  // namespace peensim
