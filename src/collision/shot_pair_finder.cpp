#include "collision/shot_pair_finder.h"

#include <btBulletCollisionCommon.h>

#include <cstdint>

namespace peensim {

struct ShotPairFinder::Impl {
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher{&configuration};
    btDbvtBroadphase broadphase;
    std::vector<btBroadphaseProxy*> proxies;
    std::vector<btVector3> anchor;  // m, centre each proxy's box was last set around
    double radius = 0.0;            // m
    double margin = 0.0;            // m, how much each proxy's box is larger than its sphere's
};

ShotPairFinder::ShotPairFinder(int shot_count, double radius_m, double fat_margin_m) : impl_(std::make_unique<Impl>()) {
    // gDbvtMargin is a Bullet process global (default 0.05 m, fifty times a shot). It is set here,
    // the one place that creates a shot broad phase; every finder in a process uses the same rule.
    // Our own fattening replaces Bullet's: a proxy's box is its sphere's box grown by the margin,
    // and is moved only when the shot has left it, so most steps touch no proxy at all. Bullet's
    // leaf fattening (gDbvtMargin, a process global, 0.05 m by default: fifty times a shot) is
    // therefore set to nothing, here, the one place that creates a shot broad phase.
    gDbvtMargin = 0.0;
    impl_->radius = radius_m;
    impl_->margin = fat_margin_m;
    grow(shot_count);
}

void ShotPairFinder::grow(int shot_count) {
    const double r = impl_->radius;
    const int before = static_cast<int>(impl_->proxies.size());
    if (shot_count <= before) return;
    impl_->anchor.resize(static_cast<std::size_t>(shot_count), btVector3(1e30, 1e30, 1e30));
    impl_->proxies.resize(static_cast<std::size_t>(shot_count));
    for (int i = before; i < shot_count; ++i) {
        const btVector3 far(1e3 + 10.0 * i * r, 1e3, 1e3);  // parked until the first update
        impl_->proxies[static_cast<std::size_t>(i)] =
            impl_->broadphase.createProxy(far - btVector3(r, r, r), far + btVector3(r, r, r),
                                          /*shapeType=*/SPHERE_SHAPE_PROXYTYPE, reinterpret_cast<void*>(static_cast<std::intptr_t>(i)),
                                          btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter, &impl_->dispatcher);
    }
    pairs_.reserve(static_cast<std::size_t>(shot_count) * 4);
}

ShotPairFinder::~ShotPairFinder() {
    for (btBroadphaseProxy* p : impl_->proxies) impl_->broadphase.destroyProxy(p, &impl_->dispatcher);
}

void ShotPairFinder::update(const double* x, const double* y, const double* z, const unsigned char* active) {
    const double r = impl_->radius, m = impl_->margin;
    const btVector3 half(r + m, r + m, r + m);
    for (std::size_t i = 0; i < impl_->proxies.size(); ++i) {
        btVector3 c(x[i], y[i], z[i]);
        if (!active[i]) c = btVector3(-1e3 - 10.0 * static_cast<double>(i) * r, -1e3, -1e3);
        const btVector3 moved = (c - impl_->anchor[i]).absolute();
        if (moved.x() <= m && moved.y() <= m && moved.z() <= m) continue;  // still inside its box
        impl_->anchor[i] = c;
        impl_->broadphase.setAabb(impl_->proxies[i], c - half, c + half, &impl_->dispatcher);
    }
    impl_->broadphase.calculateOverlappingPairs(&impl_->dispatcher);
    pairs_.clear();
    // Bullet's cache is a superset: it drops pairs that stopped overlapping a tenth of the cache per
    // update (btDbvtBroadphase's cleanup), so stale pairs (lost shot parked together with their
    // old neighbours' pairs) are filtered here by the boxes as they are now.
    const double reach = 2.0 * (r + m);
    const btBroadphasePairArray& cache = impl_->broadphase.getOverlappingPairCache()->getOverlappingPairArray();
    for (int k = 0; k < cache.size(); ++k) {
        int a = static_cast<int>(reinterpret_cast<std::intptr_t>(cache[k].m_pProxy0->m_clientObject));
        int b = static_cast<int>(reinterpret_cast<std::intptr_t>(cache[k].m_pProxy1->m_clientObject));
        if (!active[a] || !active[b]) continue;
        const btVector3 apart = (impl_->anchor[static_cast<std::size_t>(a)] - impl_->anchor[static_cast<std::size_t>(b)]).absolute();
        if (apart.x() > reach || apart.y() > reach || apart.z() > reach) continue;
        if (a > b) std::swap(a, b);
        pairs_.emplace_back(a, b);
    }
}

}  // namespace peensim
