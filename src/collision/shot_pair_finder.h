// Candidate shot-shot pairs from Bullet's dynamic AABB tree broad phase (btDbvtBroadphase).
// Each shot is a proxy whose box is its sphere's; the broad phase keeps the boxes fattened by
// a margin so that most steps move no leaf. Only pairs of active shot whose boxes overlap come
// back (every pair of spheres within a diameter among them); the engine tests the spheres exactly.
#pragma once

#include <memory>
#include <utility>
#include <vector>

namespace peensim {

struct ShotPairFinderStats {
    std::size_t candidate_pairs = 0;  // pairs in Bullet's cache after the last update
};

class ShotPairFinder {
public:
    // radius_m: shot radius; fat_margin_m: how far a shot may move before its leaf is re-inserted.
    ShotPairFinder(int shot_count, double radius_m, double fat_margin_m);
    ~ShotPairFinder();
    ShotPairFinder(const ShotPairFinder&) = delete;
    ShotPairFinder& operator=(const ShotPairFinder&) = delete;

    // Room for shot_count shot (more than before: a source emitted; never fewer), the new ones inactive.
    void grow(int shot_count);

    // Moves every active shot's box to its position (x, y, z arrays, m) and refreshes the pairs.
    // Inactive shots (lost) have their proxies parked far away.
    void update(const double* x, const double* y, const double* z, const unsigned char* active);

    // Calls visit(i, j) with i < j for every candidate pair (boxes overlap). Order is deterministic.
    template <class Visit>
    void for_each_pair(Visit&& visit) const {
        for (const auto& p : pairs_) visit(p.first, p.second);
    }
    std::size_t pair_count() const { return pairs_.size(); }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::vector<std::pair<int, int>> pairs_;
};

}  // namespace peensim
