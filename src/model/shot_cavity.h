// The space the shot move in: the chamber's cavity, joined to the sonotrode's upper faces. Built
// from the assembly at t = 0 (Enclosure: a voxel flood fill; exact distances at the walls), it
// refuses a chamber that does not close around the sonotrode, and answers whether a point is in
// the cavity, which excludes the inside of closed parts and sealed pockets. Shot placement and
// the assembly checks (a part out of the shot's reach, an opening they can reach) both ask it.
#pragma once

#include <array>
#include <vector>

#include "common/random.h"
#include "common/vec.h"
#include "model/enclosure.h"
#include "model/model.h"

namespace peensim {

// Area-weighted sampler of the sonotrode's upward faces (world frame at t = 0).
struct SonotrodeFaces {
    std::vector<std::array<Vec3, 3>> faces;
    std::vector<double> cumulative_area;
    Vec3 sample(Random& rng) const;
};

class ShotCavity {
public:
    // Throws InputError if the sonotrode has no upper face or the chamber is not closed around
    // it. Draws its probes of the chamber from `rng` (shot placement goes on with it).
    ShotCavity(const Model& model, Random& rng);

    // True if a shot centre at p (world, m) lies in the cavity (not inside a part, not outside).
    // Safe from several threads at once.
    bool contains(const Vec3& p) const;

    const SonotrodeFaces& sonotrode_faces() const { return faces_; }
    const Vec3& up() const { return up_; }  // unit, world: from the sonotrode into the chamber

private:
    const Model& model_;
    Vec3 up_;
    SonotrodeFaces faces_;
    Enclosure enclosure_;
    int region_ = -1;
};

// The direction "up" from the sonotrode into the chamber (unit, world).
Vec3 sonotrode_up(const Model& model);

// Exact distance (m) from p (world) to component c at t = 0, or `within` (m) if it is not closer.
double distance_to(const Component& c, const Vec3& p, double within);

// Exact distance (m) from p (world) to the nearest component at t = 0, or `within` (m) if none is closer.
double clearance(const Model& model, const Vec3& p, double within);

// True if a sphere of radius r (m) at p (world) touches no component at t = 0.
bool clear_of_meshes(const Model& model, const Vec3& p, double r);

// "(x, y, z) mm", for messages.
std::string mm_point(const Vec3& p);

// "components[i]": a component's field path in messages.
std::string component_field(std::size_t i);

}  // namespace peensim
