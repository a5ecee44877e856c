#include "app/fem/export_fem_job.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "analysis/impact_log_reader.h"
#include "analysis/regions.h"
#include "app/report_errors.h"
#include "common/units.h"
#include "contact/dent.h"
#include "fem/block_mesher.h"
#include "fem/ccx_cost.h"
#include "fem/impact_steps.h"
#include "fem/inp_writer.h"
#include "fem/patch_frame.h"
#include "model/component_mesh.h"
#include "output/atomic_file.h"
#include "output/impact_csv_writer.h"
#include "output/output_names.h"
#include "scene/scene_parser.h"
#include "scene/scene_sections.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// Steel, where the scene does not say (documented in docs/user-guide.md, "FEM hand-off").
constexpr double kSteelYoungsModulusPa = 210e9;  // Pa
constexpr double kSteelPoissonRatio = 0.3;       // -
constexpr double kSteelDensity = 7850.0;         // kg/m3
constexpr double kSteelYieldStressPa = 500e6;    // Pa
constexpr double kPatchRadii = 3.0;              // -, the smallest patch radius, in shot radii
constexpr double kPatchDents = 2.0;              // -, ... and in dent diameters
constexpr double kCandidateRadii = 10.0;         // -, impacts kept while the default radius is found, in shot radii
constexpr double kDepthDents = 3.0;              // -, block depth in dent diameters
constexpr double kFineDepthDents = 0.3;          // -, depth of the uniform fine layer in dent diameters
constexpr double kPenaltyPerModulus = 10.0;      // -, contact stiffness = this x E / h
constexpr double kMaxElements = 2e6;             // the largest block written
// The dents the default element size resolves (issue 30): the 10th percentile of the patch's dent
// diameters, floored at half their median. The smallest dent (an almost resting shot's) set it
// before and made decks of millions of elements (a 10-impact USP patch: 1.38 M; the shipped gear's
// default patch: 4.45 M) for dents that carry almost no plastic work (their volume goes with d^4).
constexpr double kSizingPercentile = 0.10;    // -
constexpr double kSizingFloorOfMedian = 0.5;  // -
constexpr double kCentreTolerance = 1e-9;     // -, in shot radii: the quarter model's impact at the centre

const ComponentDesc& logged_component(const SceneDescription& scene, const std::string& wanted, const std::string& scene_file) {
    std::vector<const ComponentDesc*> logged;
    for (const ComponentDesc& c : scene.components)
        if (is_logged(scene, c)) logged.push_back(&c);
    std::string names;
    for (const ComponentDesc* c : logged) names += (names.empty() ? "'" : ", '") + c->name + "'";
    for (const ComponentDesc* c : logged)
        if (c->name == wanted) return *c;
    if (!wanted.empty())
        throw InputError({"--component"}, "", "'" + wanted + "' is not a logged component of " + scene_file + "; expected one of " + names);
    if (logged.size() != 1)
        throw InputError({"--component"}, "", "the run logged " + std::to_string(logged.size()) + " components (" + names + "); name one");
    return *logged.front();
}

std::vector<std::string> split_commas(std::string text) {
    text.erase(std::remove(text.begin(), text.end(), '['), text.end());
    text.erase(std::remove(text.begin(), text.end(), ']'), text.end());
    std::vector<std::string> parts;
    std::stringstream in(text);
    for (std::string p; std::getline(in, p, ',');) parts.push_back(p);
    return parts;
}

double quantity(const std::string& option, const std::string& text, Dimension dim) {
    try {
        return parse_quantity(text, dim);
    } catch (const QuantityError& e) {
        throw InputError({option}, "", e.what());  // it quotes the text
    }
}

// A quantity > 0 (`what` names it in the message: "a duration"; default the dimension's noun).
double positive(const std::string& option, const std::string& text, Dimension dim, std::string what = "") {
    const double v = quantity(option, text, dim);
    if (what.empty()) what = dimension_noun(dim);
    if (!(v > 0.0)) throw InputError({option}, "", "expected " + what + " > 0, got '" + text + "'");
    return v;
}

Vec3 point_option(const std::string& option, const std::string& text) {
    const auto parts = split_commas(text);
    if (parts.size() != 3) throw InputError({option}, "", "expected x,y,z (lengths, e.g. \"1 mm, 0, 2.5 mm\"), got '" + text + "'");
    return {quantity(option, parts[0], Dimension::length), quantity(option, parts[1], Dimension::length),
            quantity(option, parts[2], Dimension::length)};
}

std::string fem_mm(double m) {
    std::ostringstream s;
    s.precision(4);
    s << m * 1e3;
    return s.str();
}

// "40 s", "12 min", "3.5 h": a duration as a person reads it.
std::string fem_duration_text(double seconds) {
    std::ostringstream s;
    if (seconds < 90.0)
        s << std::fixed << std::setprecision(0) << seconds << " s";
    else if (seconds < 5400.0)
        s << std::fixed << std::setprecision(0) << seconds / 60.0 << " min";
    else
        s << std::fixed << std::setprecision(1) << seconds / 3600.0 << " h";
    return s.str();
}

// Bytes in GB, two decimals below 10 GB.
std::string gigabytes(double bytes) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(bytes < 1e10 ? 2 : 0) << bytes / 1e9;
    return s.str();
}

std::string mm3(const Vec3& p) { return "(" + fem_mm(p.x()) + ", " + fem_mm(p.y()) + ", " + fem_mm(p.z()) + ") mm"; }

// The centre of a --region's patch: the point of the region's surface nearest its area centroid.
// Not the centroid itself: a region that is not flat (a gear tooth: both flanks, the tip and the
// side faces) has its centroid inside the part, millimetres off the surface. Not the most impacted
// point either: a FEM user asking for "the region" expects its middle, the same patch whatever
// the run's seed (two runs' decks then compare like for like); --center picks any other point.
// The nearest point is looked for on the triangles wholly inside the region (a triangle split by
// the region's boundary may have its nearest point outside it), on all of its triangles only if
// none is whole.
Vec3 region_centre(const TriangleMesh& mesh, const RegionSet& regions, std::size_t r) {
    Vec3 sum = Vec3::Zero();
    double area = 0.0;  // m2
    std::vector<int> whole;
    for (const RegionShare& share : regions.shares(r)) {
        const auto t = static_cast<std::size_t>(share.triangle);
        const double a = share.fraction * regions.triangle_area_m2(t);
        sum += a * (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
        area += a;
        if (share.fraction >= 1.0) whole.push_back(share.triangle);
    }
    const Vec3 centroid = sum / area;
    return closest_surface_point(mesh, centroid, whole.empty() ? regions.triangles(r) : whole).point_m;
}

// A run's impacts on the component near the centre (component frame, m).
struct LoggedImpact {
    std::uint64_t row = 0;
    double time_s = 0.0;
    Vec3 point_m, v_m_per_s;
    double vn_m_per_s = 0.0;
    int triangle = -1;
};

}  // namespace

int export_fem_job(const ExportFemOptions& o, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] {
        if (o.output_dir.empty()) throw InputError({"-o"}, "", "expected an output directory for the deck");
        if (o.run_dir.empty() && o.single.empty())
            throw InputError({"RUNDIR"}, "", "expected a run directory (or --single x,y,z,vx,vy,vz for one synthetic impact)");
        if (o.shot_divisions < 2 || o.shot_divisions % 2 != 0 || o.shot_divisions > 64)
            throw InputError({"--shot-divisions"}, "", "expected an even number from 2 to 64, got " + std::to_string(o.shot_divisions));
        if (!(o.elements_per_dent >= 1.0 && o.elements_per_dent <= 100.0))
            throw InputError({"--elements-per-dent"}, "", "expected a number from 1 to 100");
        if (!(o.contact_times >= 1.0 && o.contact_times <= 100.0))
            throw InputError({"--contact-times"}, "", "expected a number from 1 to 100");
        if (o.max_impacts && *o.max_impacts < 1)
            throw InputError({"--impacts"}, "",
                             "expected a count >= 1 (leave it out for every impact), got " + std::to_string(*o.max_impacts));
        const FemElement element = o.element == "C3D8I"   ? FemElement::C3D8I
                                   : o.element == "C3D8R" ? FemElement::C3D8R
                                   : o.element == "C3D8"
                                       ? FemElement::C3D8
                                       : throw InputError({"--element"}, "", "expected C3D8I, C3D8R or C3D8, got '" + o.element + "'");
        if (o.dynamics != "explicit" && o.dynamics != "implicit")
            throw InputError({"--dynamics"}, "", "expected explicit or implicit, got '" + o.dynamics + "'");
        check_output_name("--name", o.name);  // the deck's file name: inside -o, and ccx's job name
        const double window = positive("--group-window", o.group_window, Dimension::time, "a duration");

        // The run: its scene, the shot, the part and its material.
        std::optional<SceneDescription> scene;
        std::string scene_file;
        if (!o.run_dir.empty()) {
            const fs::path dir(o.run_dir);
            if (!fs::is_directory(dir)) throw InputError({o.run_dir}, "", "no such run directory");
            scene_file = (dir / "scene.resolved.yaml").string();
            if (!fs::exists(scene_file)) throw InputError({o.run_dir}, "", "not a peensim run directory (no scene.resolved.yaml)");
            scene = parse_scene_file(scene_file);
        }
        double shot_diameter = 0.0, shot_density = kSteelDensity;
        FemMaterial shot_mat{"SHOT", kSteelYoungsModulusPa, kSteelPoissonRatio, kSteelDensity, std::nullopt, 0.0};
        FemMaterial target{"TARGET", kSteelYoungsModulusPa, kSteelPoissonRatio, kSteelDensity, kSteelYieldStressPa, 0.0};
        std::vector<std::string> notes;
        const ComponentDesc* component = nullptr;
        if (scene) {
            shot_diameter = scene->shot.sizes.front().diameter_m;
            shot_density = scene->shot.density_kg_per_m3;
            if (const MaterialDesc* m = find_material(scene->materials, scene->shot.material)) {
                if (m->youngs_modulus_pa) shot_mat.youngs_modulus_pa = *m->youngs_modulus_pa;
                if (m->poisson_ratio) shot_mat.poisson_ratio = *m->poisson_ratio;
            }
            component = &logged_component(*scene, o.component, scene_file);
            if (const MaterialDesc* m = find_material(scene->materials, component->material)) {
                if (m->youngs_modulus_pa)
                    target.youngs_modulus_pa = *m->youngs_modulus_pa;
                else
                    notes.push_back("material '" + m->name + "' has no youngs_modulus: steel's used");
                if (m->poisson_ratio) target.poisson_ratio = *m->poisson_ratio;
                if (m->density_kg_per_m3) target.density_kg_per_m3 = *m->density_kg_per_m3;
                if (m->yield_stress_pa)
                    target.yield_stress_pa = *m->yield_stress_pa;
                else
                    notes.push_back("material '" + m->name + "' has no yield_stress: steel's 500 MPa used");
            }
        }
        if (!o.shot_diameter.empty()) shot_diameter = positive("--shot-diameter", o.shot_diameter, Dimension::length);
        // A run of a shot mix: the deck has one ball, so one size's impacts are exported, the size chosen.
        const bool mix = scene && scene->shot.sizes.size() > 1;
        if (mix) {
            std::string sizes;
            bool known = false;
            for (const ShotSizeDesc& size : scene->shot.sizes) {
                sizes += (sizes.empty() ? "" : ", ") + fem_mm(size.diameter_m) + " mm";
                known |= std::abs(size.diameter_m - shot_diameter) <= 1e-9 * size.diameter_m;
            }
            if (o.shot_diameter.empty())
                throw InputError({"--shot-diameter"}, "",
                                 "the run peened with a shot mix (" + sizes +
                                     "); expected --shot-diameter to choose whose impacts to export (the deck has one ball size)");
            if (!known)
                throw InputError({"--shot-diameter"}, "",
                                 "expected one of the run's sizes (" + sizes + "), got " + fem_mm(shot_diameter) + " mm");
        }
        if (!(shot_diameter > 0.0))
            throw InputError({"--shot-diameter"}, "", "expected the shot diameter (there is no run directory to take it from)");
        shot_mat.density_kg_per_m3 = shot_density;
        if (!o.yield_stress.empty()) target.yield_stress_pa = positive("--yield-stress", o.yield_stress, Dimension::stress);
        if (!o.hardening.empty()) target.hardening_modulus_pa = quantity("--hardening", o.hardening, Dimension::stress);
        if (target.hardening_modulus_pa < 0.0) throw InputError({"--hardening"}, "", "expected a stress >= 0");
        const double R = 0.5 * shot_diameter;
        auto dent = [&](double vn) { return dent_diameter(shot_diameter, shot_density, vn, *target.yield_stress_pa); };

        // The patch frame and the candidate impacts (component frame).
        PatchFrame frame;
        std::vector<LoggedImpact> candidates;
        std::optional<TriangleMesh> mesh;
        std::vector<int> region_triangles;
        std::optional<RegionSet> regions;  // with --region: the component's, and which one is asked for
        std::size_t region_index = 0;
        std::vector<int> first_triangle_of_facet;
        if (component) {
            mesh = load_component_mesh(*component);
            for (std::size_t t = 0; t < mesh->triangle_count(); ++t) {
                const auto f = static_cast<std::size_t>(mesh->source_facet[t]);
                if (first_triangle_of_facet.size() <= f) first_triangle_of_facet.resize(f + 1, -1);
                if (first_triangle_of_facet[f] < 0) first_triangle_of_facet[f] = static_cast<int>(t);
            }
        }
        Vec3 centre;
        bool have_centre = false;
        bool centre_on_region = false;  // the centre is a point of the --region's surface (not a user's point)
        if (!o.center.empty()) {
            centre = point_option("--center", o.center);
            have_centre = true;
        }
        if (!o.region.empty()) {
            if (!mesh) throw InputError({"--region"}, "", "needs a run directory");
            regions.emplace(*mesh, component->regions);
            std::string names;
            for (std::size_t r = 0; r < regions->size(); ++r) {
                names += (names.empty() ? "'" : ", '") + regions->name(r) + "'";
                if (regions->name(r) == o.region) {
                    region_index = r;
                    region_triangles = regions->triangles(r);
                }
            }
            if (region_triangles.empty())
                throw InputError({"--region"}, "",
                                 "component '" + component->name + "' has no region '" + o.region + "'" +
                                     (names.empty() ? std::string(" (it has no regions)") : "; expected one of " + names));
            if (!have_centre) {
                centre = region_centre(*mesh, *regions, region_index);
                have_centre = true;
                centre_on_region = true;
            }
        }
        std::vector<PatchImpact> synthetic;
        if (!o.single.empty()) {
            const auto parts = split_commas(o.single);
            if (parts.size() != 6)
                throw InputError({"--single"}, "",
                                 "expected x,y,z,vx,vy,vz (lengths and speeds, e.g. \"0,0,0,0,0,-50 m/s\"), got '" + o.single + "'");
            Vec3 p, v;
            for (int k = 0; k < 3; ++k) {
                p[k] = quantity("--single", parts[static_cast<std::size_t>(k)], Dimension::length);
                v[k] = quantity("--single", parts[static_cast<std::size_t>(k + 3)], Dimension::speed);
            }
            if (!have_centre) {
                centre = p;
                have_centre = true;
            }
            LoggedImpact li{0, 0.0, p, v, 0.0, -1};
            candidates.push_back(li);
        }
        if (!have_centre)
            throw InputError({"--center"}, "", "expected the patch centre (--center x,y,z in the component's frame) or --region");

        if (mesh) {
            const SurfacePoint s = closest_surface_point(*mesh, centre, region_triangles);
            if (s.distance_m > R && !centre_on_region)
                throw InputError({"--center"}, "",
                                 mm3(centre) + " is " + fem_mm(s.distance_m) + " mm from the surface of component '" + component->name +
                                     "'; expected a point on it (within a shot radius, " + fem_mm(R) + " mm)");
            centre = s.point_m;
            const double r_frame = o.radius.empty() ? kPatchRadii * R : positive("--radius", o.radius, Dimension::length);
            frame = tangent_frame(*mesh, centre, s.triangle, r_frame);
        } else {
            frame = frame_from_normal(centre, Vec3::UnitZ());
        }
        const double candidate_radius = o.radius.empty() ? kCandidateRadii * R : positive("--radius", o.radius, Dimension::length);

        // The run's impacts on the component within the candidate radius, facing the patch's side.
        std::uint64_t log_rows = 0;
        if (o.single.empty()) {
            const fs::path dir(o.run_dir);
            fs::path log = dir / kImpactCsvFileName;
            if (!fs::exists(log)) log = dir / kImpactCsvPartialFileName;
            if (!fs::exists(log)) throw InputError({o.run_dir}, "", "no impact log (impacts.csv or impacts.csv.partial)");
            ImpactLogReader reader(log.string());
            ImpactRow row;
            while (reader.next(row)) {
                ++log_rows;
                if (row.component != component->name) continue;
                if (mix && !(std::abs(row.shot_diameter_m - shot_diameter) <= 1e-9 * shot_diameter)) continue;  // another size's
                if ((row.point_m - frame.centre_m).norm() > candidate_radius) continue;
                int tri = -1;
                if (row.triangle >= 0 && static_cast<std::size_t>(row.triangle) < first_triangle_of_facet.size())
                    tri = first_triangle_of_facet[static_cast<std::size_t>(row.triangle)];
                if (tri >= 0 && triangle_normal(*mesh, static_cast<std::size_t>(tri)).dot(frame.normal) < 0.5) continue;
                if (regions && !(tri >= 0 && regions->contains(region_index, row.point_m, static_cast<std::size_t>(tri)))) continue;
                candidates.push_back({reader.rows(), row.time_s, row.point_m, row.v_in_m_per_s, row.vn_in_m_per_s, tri});
            }
        }

        // Into the patch frame: on the tangent plane, the normal speed kept.
        auto to_patch = [&](const LoggedImpact& li) {
            PatchImpact p;
            p.row = li.row;
            p.time_s = li.time_s;
            const Vec3 q = frame.to_local(li.point_m);
            p.point_m = Vec3(q.x(), q.y(), 0.0);
            p.plane_offset_m = q.z();
            if (li.triangle >= 0) {
                const Vec3 n = triangle_normal(*mesh, static_cast<std::size_t>(li.triangle));
                const Vec3 vt = frame.direction_to_local(li.v_m_per_s - li.v_m_per_s.dot(n) * n);
                p.velocity_m_per_s = Vec3(vt.x(), vt.y(), -li.vn_m_per_s);
            } else {
                p.velocity_m_per_s = frame.direction_to_local(li.v_m_per_s);
            }
            const double vn = -p.velocity_m_per_s.z();
            p.dent_diameter_m = vn > 0.0 ? dent(vn) : 0.0;
            return p;
        };
        std::vector<PatchImpact> all;
        for (const LoggedImpact& li : candidates) all.push_back(to_patch(li));
        for (const PatchImpact& p : all)
            if (!(-p.velocity_m_per_s.z() > 0.0))
                throw InputError({"--single"}, "",
                                 "the impact's velocity must point into the surface (its z component, along the patch normal, negative)");
        std::stable_sort(all.begin(), all.end(), [](const PatchImpact& a, const PatchImpact& b) { return a.time_s < b.time_s; });

        // The patch radius: given, or max(3 R, 2 dent diameters of the impacts inside it).
        double radius = candidate_radius;
        if (o.radius.empty()) {
            radius = kPatchRadii * R;
            for (int pass = 0; pass < 4; ++pass) {
                double largest = 0.0;
                for (const PatchImpact& p : all)
                    if (p.point_m.norm() <= radius) largest = std::max(largest, p.dent_diameter_m);
                radius = std::max(kPatchRadii * R, kPatchDents * largest);
            }
        }
        std::vector<PatchImpact> impacts;
        for (const PatchImpact& p : all)
            if (p.point_m.norm() <= radius && (!o.max_impacts || static_cast<int>(impacts.size()) < *o.max_impacts)) impacts.push_back(p);
        if (impacts.empty())
            throw InputError({o.run_dir.empty() ? "--single" : o.run_dir}, "",
                             "no impact of component '" + (component ? component->name : std::string("-")) + "' within " + fem_mm(radius) +
                                 " mm of " + mm3(frame.centre_m) + " (" + std::to_string(log_rows) +
                                 " rows read); expected a centre where the part was hit");
        if (o.quarter) {
            const PatchImpact& p = impacts.front();
            const double vt = std::hypot(p.velocity_m_per_s.x(), p.velocity_m_per_s.y());
            if (impacts.size() != 1 || p.point_m.norm() > kCentreTolerance * R + 1e-15 || vt > 1e-9 * p.velocity_m_per_s.norm())
                throw InputError({"--quarter"}, "",
                                 "the quarter model needs exactly one normal impact at the patch centre (the patch has " +
                                     std::to_string(impacts.size()) + "); use the full model");
        }

        // Meshes.
        double largest_dent = 0.0, fine = 0.0, max_offset = 0.0;
        for (const PatchImpact& p : impacts) {
            largest_dent = std::max(largest_dent, p.dent_diameter_m);
            fine = std::max(fine, std::max(std::abs(p.point_m.x()), std::abs(p.point_m.y())) + p.dent_diameter_m);
            max_offset = std::max(max_offset, std::abs(p.plane_offset_m));
        }
        std::vector<double> dents;
        for (const PatchImpact& p : impacts) dents.push_back(p.dent_diameter_m);
        std::sort(dents.begin(), dents.end());
        const auto dent_at = [&dents](double q) { return dents[static_cast<std::size_t>(q * static_cast<double>(dents.size() - 1))]; };
        const double sizing_dent = std::max(dent_at(kSizingPercentile), kSizingFloorOfMedian * dent_at(0.5));  // m
        const double h =
            o.element_size.empty() ? sizing_dent / o.elements_per_dent : positive("--element-size", o.element_size, Dimension::length);
        BlockMeshSpec spec;
        spec.half_width_m = radius;
        spec.depth_m = std::max(kDepthDents * largest_dent, 4.0 * h);
        spec.fine_half_width_m = std::min(fine, radius);
        spec.fine_depth_m = std::max(kFineDepthDents * largest_dent, h);
        spec.element_size_m = h;
        spec.quarter = o.quarter;
        // The limit on the whole block, checked before meshing: the fine zone first (it bounds the
        // grid lines counted next), then every element, the coarse ones around and below it too
        // (the default deck of the shipped gear had 4.45 M elements while the fine zone was checked alone).
        const double cells = std::pow((o.quarter ? 1.0 : 2.0) * spec.fine_half_width_m / h, 2.0) * spec.fine_depth_m / h;
        if (cells > kMaxElements)
            throw InputError({"--element-size"}, "",
                             "the fine zone alone would need ~" + std::to_string(static_cast<long long>(cells)) + " elements (h = " +
                                 fem_mm(h) + " mm), more than the " + std::to_string(static_cast<long long>(kMaxElements)) +
                                 " written at most; give a larger --element-size or fewer --impacts");
        const double elements = block_element_count(spec);
        if (elements > kMaxElements)
            throw InputError({"--element-size"}, "",
                             "the block would have " + std::to_string(static_cast<long long>(elements)) + " elements (h = " + fem_mm(h) +
                                 " mm, patch radius " + fem_mm(radius) + " mm), more than the " +
                                 std::to_string(static_cast<long long>(kMaxElements)) +
                                 " written at most; give a larger --element-size, a smaller --radius or fewer --impacts");

        FemDeck deck;
        deck.quarter = o.quarter;
        deck.block_element = element;
        deck.explicit_dynamics = o.dynamics == "explicit";
        deck.block = mesh_block(spec);
        deck.shot_mesh = mesh_sphere(R, o.shot_divisions, o.quarter);
        deck.target = target;
        deck.shot = shot_mat;
        deck.contact_stiffness_pa_per_m = kPenaltyPerModulus * target.youngs_modulus_pa / h;
        const auto groups = group_impacts(impacts, GroupingRule{kPatchDents, window});
        StepTiming timing;
        timing.contact_times = o.contact_times;
        plan_steps(deck, impacts, groups, R, timing);

        // Header.
        auto line = [&](const std::string& s) { deck.header.push_back(s); };
        deck.heading = "peensim export-fem: " + std::to_string(impacts.size()) + " impacts in " + std::to_string(groups.size()) + " steps";
        line("Written by peensim export-fem (" + std::string(o.run_dir.empty() ? "synthetic impact" : "run " + o.run_dir) + ").");
        line("Units: SI throughout (m, kg, s, Pa = N/m2, m/s).");
        line("Patch frame (the deck's axes): origin at the patch centre on the surface, z = the outward surface normal,");
        line("the target block below z = 0. In the component frame (m): centre " + format_si(frame.centre_m.x()) + ", " +
             format_si(frame.centre_m.y()) + ", " + format_si(frame.centre_m.z()));
        line("  x axis " + format_si(frame.e1.x()) + ", " + format_si(frame.e1.y()) + ", " + format_si(frame.e1.z()) + "; y axis " +
             format_si(frame.e2.x()) + ", " + format_si(frame.e2.y()) + ", " + format_si(frame.e2.z()) + "; z axis " +
             format_si(frame.normal.x()) + ", " + format_si(frame.normal.y()) + ", " + format_si(frame.normal.z()));
        if (mesh)
            line("The part is replaced by its tangent plane at the centre; the impacts were at most " + format_si(max_offset) +
                 " m off it (projected onto it, normal speed kept).");
        line("Patch radius " + format_si(radius) + " m; block " + format_si(2 * radius) + " m square (" +
             (o.quarter ? "quarter model, symmetry planes x = 0, y = 0" : "full") + "), " + format_si(spec.depth_m) +
             " m deep; fine elements " + format_si(h) + " m.");
        line("Target: E " + format_si(target.youngs_modulus_pa) + " Pa, nu " + format_si(target.poisson_ratio) + ", density " +
             format_si(target.density_kg_per_m3) + " kg/m3, yield " + format_si(*target.yield_stress_pa) + " Pa, hardening " +
             format_si(target.hardening_modulus_pa) + " Pa (isotropic).");
        line("Shot: elastic balls of diameter " + format_si(shot_diameter) + " m, E " + format_si(shot_mat.youngs_modulus_pa) + " Pa, nu " +
             format_si(shot_mat.poisson_ratio) + ", density " + format_si(shot_density) + " kg/m3.");
        for (const std::string& n : notes) line("Note: " + n + ".");
        line("Block elements " + std::string(fem_element_name(element)) + "; impacts in " + o.dynamics +
             " dynamic steps, then a static relaxation step (contact removed,");
        line("  shot held) brings the block to equilibrium: its printed U (NPROFILE) and S (EAXIS) are the residual state.");
        line("Sets: NTOP, NBOTTOM, NXMIN, NXMAX, NYMIN, NYMAX, NPROFILE (top nodes on y = 0, x >= 0), ETOP, EBLOCK,");
        line("  EAXIS (the element column under the centre, x and y in [0, h]),");
        line("  NSHOT<k>/ESHOT<k> (shot k), NSHOTCENTRES, ESHOTS; surfaces STOP (slave) and SSHOTS (master).");

        // What CalculiX will make of it, said before the files are written (a deck of hours is
        // better refused by its user now than found out after a night of ccx).
        const CcxCostEstimate cost = estimate_ccx_cost(deck);
        out << "export-fem: " << impacts.size() << " impacts in " << deck.steps.size() << " steps; block "
            << deck.block.mesh.elements.size() << " " << fem_element_name(element) << " elements (fine " << fem_mm(h) << " mm), "
            << deck.shots.size() << " shots x " << deck.shot_mesh.mesh.elements.size()
            << " elements\n  CalculiX estimate: " << fem_duration_text(cost.seconds) << ", " << gigabytes(cost.bytes) << " GB ("
            << static_cast<long long>(cost.nodes) << " nodes, " << static_cast<long long>(cost.planned_increments)
            << " planned increments; one core, the cost model of docs/user-guide.md, \"FEM hand-off\")\n";
        if (cost.seconds > kCcxPracticalSeconds || cost.bytes > kCcxPracticalBytes)
            err << "warning: this deck is impractical for CalculiX on one core: about " << fem_duration_text(cost.seconds) << " and "
                << gigabytes(cost.bytes) << " GB estimated (more than " << fem_duration_text(kCcxPracticalSeconds) << " or "
                << gigabytes(kCcxPracticalBytes)
                << " GB); fewer --impacts, a larger --element-size (fewer --elements-per-dent), "
                   "a smaller --radius or --shot-divisions 4 make it smaller; it is written all the same\n";

        // Files.
        fs::create_directories(o.output_dir);
        const fs::path deck_path = fs::path(o.output_dir) / (o.name + ".inp");
        std::ostringstream text;
        write_inp(text, deck);
        write_file_atomically(deck_path.string(), text.str());

        std::ostringstream csv;
        csv << "step,shot,row,time_s,x_m,y_m,plane_offset_m,vx_mps,vy_mps,vz_mps,vn_mps,dent_diameter_m\n";
        for (std::size_t s = 0; s < deck.shots.size(); ++s) {
            const FemShot& shot = deck.shots[s];
            const PatchImpact& p = impacts[static_cast<std::size_t>(shot.impact)];
            csv << shot.step + 1 << "," << s + 1 << "," << p.row << "," << format_si(p.time_s) << "," << format_si(p.point_m.x()) << ","
                << format_si(p.point_m.y()) << "," << format_si(p.plane_offset_m) << "," << format_si(p.velocity_m_per_s.x()) << ","
                << format_si(p.velocity_m_per_s.y()) << "," << format_si(p.velocity_m_per_s.z()) << ","
                << format_si(-p.velocity_m_per_s.z()) << "," << format_si(p.dent_diameter_m) << "\n";
        }
        write_file_atomically((fs::path(o.output_dir) / "impacts.csv").string(), csv.str());

        std::ostringstream readme;
        readme << "# FEM deck `" << o.name << ".inp` (peensim export-fem)\n\n";
        for (const std::string& l : deck.header) readme << l << "\n";
        readme << "\nRun it with CalculiX: `ccx -i " << o.name << "` (in this directory; results in " << o.name << ".dat and " << o.name
               << ".frd). Expect about " << fem_duration_text(cost.seconds) << " and " << gigabytes(cost.bytes) << " GB on one core ("
               << static_cast<long long>(cost.nodes) << " nodes, " << static_cast<long long>(cost.planned_increments)
               << " planned increments; the cost model of peensim's docs/user-guide.md, \"FEM hand-off\", fitted to measured ccx 2.20 "
                  "runs).\n\n";
        readme << "Block: " << deck.block.mesh.nodes.size() << " nodes, " << deck.block.mesh.elements.size() << " "
               << fem_element_name(element) << " elements; each shot " << deck.shot_mesh.mesh.nodes.size() << " nodes, "
               << deck.shot_mesh.mesh.elements.size() << " elements.\n\n";
        readme << "| step | duration s | shots (impacts.csv rows of the run) |\n|---|---|---|\n";
        for (std::size_t k = 0; k < deck.steps.size(); ++k) {
            readme << "| " << k + 1 << " | " << format_si(deck.steps[k].duration_s) << " |";
            for (int s : deck.steps[k].shots)
                readme << " " << s + 1 << " (row " << impacts[static_cast<std::size_t>(deck.shots[static_cast<std::size_t>(s)].impact)].row
                       << ")";
            readme << " |\n";
        }
        readme << "\n`impacts.csv` lists every shot: its step, the run's row (0: synthetic), time, point and velocity in the deck's frame, "
                  "normal speed and the dent diameter of eq. 10.\n";
        write_file_atomically((fs::path(o.output_dir) / "README.md").string(), readme.str());

        out << "  deck: " << deck_path.string() << "  (run: cd " << o.output_dir << " && ccx -i " << o.name << ")\n";
        for (const std::string& n : notes) err << "note: " << n << "\n";
        return 0;
    });
}

}  // namespace peensim
