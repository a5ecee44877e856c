// Impact-history restitution (reference section 4, the DEM-FEM study): the part's surface
// remembers how often each spot was hit. Every impact marks the triangles within one dent
// diameter (eq. 10) of its contact point (or within `influence_distance`: the study's region of
// influence was one shot diameter); the normal restitution of the next impact on a triangle
// is looked up from a table by how many times that triangle was marked before (work hardening
// raises it: the study used 0.4 on a fresh surface and averaged 0.57 over successive hits). The
// tangential restitution and sustained-contact friction are the impulse law's (eq. 5, Coulomb).
#pragma once

#include <memory>
#include <vector>

#include "contact/contact_law.h"
#include "contact/facet_index.h"
#include "contact/law_parameters.h"

namespace peensim::contact {

// What the law must know of its pair beyond its parameters.
struct ImpactHistoryGeometry {
    std::vector<Vec3> corners_m;          // three per mesh triangle, component frame (m)
    double shot_diameter_m = 0.0;         // m, the largest of the mix (sizes the facet index; each dent takes its shot's own)
    double shot_density_kg_per_m3 = 0.0;  // kg/m3
    double yield_stress_pa = 0.0;         // Pa, of the component's material (eq. 10)
};

class ImpactHistoryLaw final : public SurfaceLaw {
public:
    // restitution_by_hits: C for a triangle hit 0, 1, 2, ... times before (-, the last value for
    // every count beyond); mu: tangential restitution (-); f: Coulomb friction (-);
    // influence_distance: m, how far an impact marks (0: its dent diameter, eq. 10).
    ImpactHistoryLaw(std::vector<double> restitution_by_hits, double mu, double f, double influence_distance_m,
                     const ImpactHistoryGeometry& geometry);

    std::string_view name() const override { return "impact-history"; }
    int state_per_triangle() const override { return 1; }  // marks: how often the triangle was hit
    SurfaceContactResponse impact(const SurfaceContactInput& in, std::span<double> marks) const override;
    SurfaceContactResponse sustain(const SurfaceContactInput& in, std::span<double> marks) const override;

    // "1234 of 4960 triangles hit, up to 17 times (next restitution there 0.6-0.85)".
    std::string describe_state(std::span<const double> marks) const override;

    double restitution_after(double hits) const;

private:
    std::vector<double> restitution_by_hits_;
    double mu_, f_;
    double influence_distance_m_;  // m; 0: each impact's dent diameter
    double shot_density_kg_per_m3_, yield_stress_pa_;
    FacetIndex facets_;
};

std::span<const LawParameter> impact_history_parameters();

}  // namespace peensim::contact
