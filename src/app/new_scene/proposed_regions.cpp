#include "app/new_scene/proposed_regions.h"

#include <cmath>
#include <numbers>

#include "analysis/regions.h"

namespace peensim {

namespace {

constexpr double kFacingWithinRad = std::numbers::pi / 4.0;  // 45 deg: each face goes to the direction it looks most

RegionDesc facing(const std::string& name, const Vec3& direction) {
    RegionDesc r;
    r.name = name;
    r.facing = FacingCondition{direction, kFacingWithinRad};
    return r;
}

}  // namespace

ProposedRegions propose_regions(const TriangleMesh& mesh, const PartEnvelope& envelope, const std::optional<Axis>& turning_axis) {
    std::vector<RegionDesc> candidates;
    if (turning_axis) {
        const Axis a = *turning_axis;
        const Vec3 n = axis_unit(a);
        candidates.push_back(facing(std::string("end-plus-") + axis_name(a), n));
        candidates.push_back(facing(std::string("end-minus-") + axis_name(a), -n));
        RegionDesc sectors;
        sectors.name = "sectors";
        SectorsCondition c;
        // Angle 0 up, unless the axis is upright.
        c.frame = AxisAngleFrame{envelope.centre_m, n, a == Axis::z ? Vec3::UnitX() : Vec3::UnitZ()};
        c.count = kProposedSectors;
        c.width_rad = 2.0 * std::numbers::pi / kProposedSectors;
        c.offset_rad = 0.0;
        c.name_prefix = "sector-";
        sectors.sectors = c;
        candidates.push_back(sectors);
    } else {
        // The sonotrode is below (-z).
        candidates.push_back(facing("facing-sonotrode", -Vec3::UnitZ()));
        candidates.push_back(facing("facing-lid", Vec3::UnitZ()));
        candidates.push_back(facing("facing-plus-x", Vec3::UnitX()));
        candidates.push_back(facing("facing-minus-x", -Vec3::UnitX()));
        candidates.push_back(facing("facing-plus-y", Vec3::UnitY()));
        candidates.push_back(facing("facing-minus-y", -Vec3::UnitY()));
    }

    // Each candidate's area, by the analysis's own rule (a `sectors` entry gives its 8 regions in order).
    const RegionSet set(mesh, candidates);
    ProposedRegions out;
    std::size_t r = 0;
    for (const RegionDesc& entry : candidates) {
        if (!entry.sectors) {
            if (set.area_m2(r++) > 0.0)
                out.entries.push_back(entry);
            else
                out.left_out.push_back(entry.name);
            continue;
        }
        const SectorsCondition& c = *entry.sectors;
        std::vector<RegionDesc> held;
        for (int i = 0; i < c.count; ++i, ++r) {
            const std::string name = c.name_prefix + std::to_string(i);
            if (!(set.area_m2(r) > 0.0)) {
                out.left_out.push_back(name);
                continue;
            }
            RegionDesc one;
            one.name = name;
            const double centre = c.offset_rad + i * 2.0 * std::numbers::pi / c.count;
            one.sector = SectorCondition{c.frame, centre - 0.5 * c.width_rad, centre + 0.5 * c.width_rad};
            held.push_back(one);
        }
        if (static_cast<int>(held.size()) == c.count)
            out.entries.push_back(entry);
        else
            out.entries.insert(out.entries.end(), held.begin(), held.end());
    }
    return out;
}

}  // namespace peensim
