#include "model/shot_placement.h"

#include <cmath>
#include <sstream>
#include <unordered_map>

#include "common/input_error.h"
#include "scene/shot_mix.h"

namespace peensim {

namespace {

constexpr int kRejectionsPerLayer = 400;
constexpr double kPlacementClearance = 0.01;  // -, gap left between placed shot and surfaces, fraction of R

// Shot already placed, hashed by cells one diameter wide.
class PlacedShots {
public:
    explicit PlacedShots(double diameter) : cell_(diameter) {}
    bool overlaps(const Vec3& p) const {
        const auto [i, j, k] = cell(p);
        for (long a = i - 1; a <= i + 1; ++a)
            for (long b = j - 1; b <= j + 1; ++b)
                for (long c = k - 1; c <= k + 1; ++c) {
                    const auto it = cells_.find(key(a, b, c));
                    if (it == cells_.end()) continue;
                    for (const Vec3& q : it->second)
                        if ((q - p).squaredNorm() < cell_ * cell_) return true;
                }
        return false;
    }
    void add(const Vec3& p) {
        const auto [i, j, k] = cell(p);
        cells_[key(i, j, k)].push_back(p);
    }

private:
    std::array<long, 3> cell(const Vec3& p) const {
        return {std::lround(std::floor(p.x() / cell_)), std::lround(std::floor(p.y() / cell_)), std::lround(std::floor(p.z() / cell_))};
    }
    static long long key(long i, long j, long k) {
        return (static_cast<long long>(i) * 73856093) ^ (static_cast<long long>(j) * 19349663) ^ (static_cast<long long>(k) * 83492791);
    }
    double cell_;
    std::unordered_map<long long, std::vector<Vec3>> cells_;
};

}  // namespace

InitialShots place_shots(const Model& model) {
    if (model.shot_count == 0) return {};  // a scene fed by its sources (it may have no sonotrode)
    Random rng(model.seed);
    ShotCavity cavity(model, rng);
    return place_shots(model, cavity, rng);
}

InitialShots place_shots(const Model& model, ShotCavity& cavity, Random& rng) {
    const SceneDescription& scene = model.description;
    // A mix is placed as if every shot were of the largest size: no two overlap whatever sizes they draw.
    const double R = model.max_shot_radius_m, D = 2.0 * R;
    const Vec3& up = cavity.up();
    const SonotrodeFaces& faces = cavity.sonotrode_faces();

    InitialShots out;
    PlacedShots placed(D);
    int layer = 0, in_layer = 0, rejections = 0;
    while (static_cast<int>(out.positions.size()) < model.shot_count) {
        const Vec3 p = faces.sample(rng) + up * (R * (1.0 + kPlacementClearance) + layer * D * (1.0 + kPlacementClearance));
        const bool ok = cavity.contains(p) && !placed.overlaps(p) && clear_of_meshes(model, p, R * (1.0 + 0.5 * kPlacementClearance));
        if (ok) {
            placed.add(p);
            out.positions.push_back(p);
            ++in_layer;
            rejections = 0;
            continue;
        }
        if (++rejections < kRejectionsPerLayer) continue;
        if (in_layer == 0) {
            std::ostringstream msg;
            msg << "expected at most about " << out.positions.size() << " shot of " << D * 1e3
                << " mm to fit on the sonotrode inside the chamber (" << layer << " layers up to the first obstacle), got "
                << model.shot_count << "; lower shot.count or shot.diameter";
            throw InputError(scene.shot.where, "shot.count", msg.str());
        }
        ++layer;
        in_layer = 0;
        rejections = 0;
    }
    out.layers = layer + 1;

    // Sizes, from a generator of their own (a scene of one size draws nothing, and the positions
    // and velocities do not depend on the mix).
    out.sizes.assign(out.positions.size(), 0);
    if (model.has_size_mix()) {
        Random size_rng(model.seed ^ 0x5a17e5u);
        for (int& size : out.sizes) size = size_for_draw(model.size_count_fraction, size_rng.uniform());
    }

    // Initial velocities.
    const Vec3 side = (std::abs(up.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(up).normalized();
    const Vec3 side2 = up.cross(side);
    for (int i = 0; i < model.shot_count; ++i) {
        switch (scene.shot.initial) {
            case InitialVelocityKind::rest: out.velocities.push_back(Vec3::Zero()); break;
            case InitialVelocityKind::vector: out.velocities.push_back(scene.shot.initial_velocity_m_per_s); break;
            case InitialVelocityKind::random_upward: {
                // Uniform on the upper hemisphere: cos(theta) uniform in [0, 1].
                const double c = rng.uniform(), s = std::sqrt(std::max(0.0, 1.0 - c * c)), phi = 2.0 * M_PI * rng.uniform();
                out.velocities.push_back(scene.shot.initial_speed_m_per_s *
                                         (c * up + s * std::cos(phi) * side + s * std::sin(phi) * side2));
                break;
            }
        }
    }
    return out;
}

}  // namespace peensim
