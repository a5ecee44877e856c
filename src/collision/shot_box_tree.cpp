#include "collision/shot_box_tree.h"

#include <BulletCollision/BroadphaseCollision/btDbvt.h>

namespace peensim {

namespace {

btDbvtVolume volume(const Vec3& lo, const Vec3& hi) {
    return btDbvtVolume::FromMM(btVector3(lo.x(), lo.y(), lo.z()), btVector3(hi.x(), hi.y(), hi.z()));
}

}  // namespace

struct ShotBoxTree::Impl {
    btDbvt tree;
    std::vector<btDbvtNode*> leaf;                 // per shot, nullptr if none
    mutable std::vector<const btDbvtNode*> stack;  // traversal stack, reused
};

ShotBoxTree::ShotBoxTree(int shot_count) : impl_(std::make_unique<Impl>()) {
    impl_->leaf.assign(static_cast<std::size_t>(shot_count), nullptr);
    impl_->stack.resize(128);  // the walk's stack, its size (grown as the walk needs)
}

ShotBoxTree::~ShotBoxTree() = default;

void ShotBoxTree::grow(int shot_count) {
    if (static_cast<std::size_t>(shot_count) > impl_->leaf.size()) impl_->leaf.resize(static_cast<std::size_t>(shot_count), nullptr);
}

void ShotBoxTree::set(int shot, const Vec3& lo, const Vec3& hi) {
    btDbvtNode*& leaf = impl_->leaf[static_cast<std::size_t>(shot)];
    btDbvtVolume v = volume(lo, hi);
    if (leaf == nullptr)
        leaf = impl_->tree.insert(v, reinterpret_cast<void*>(static_cast<std::intptr_t>(shot)));
    else
        impl_->tree.update(leaf, v);
    // No optimizeIncremental pass (what btDbvtBroadphase runs on its trees): measured on the rod
    // scene, one pass per update made the whole run 27 % slower, four 42 %; the queries it
    // shortens cost less than the rotations.
}

void ShotBoxTree::remove(int shot) {
    btDbvtNode*& leaf = impl_->leaf[static_cast<std::size_t>(shot)];
    if (leaf == nullptr) return;
    impl_->tree.remove(leaf);
    leaf = nullptr;
}

void ShotBoxTree::overlapping(const Vec3& lo, const Vec3& hi, std::vector<int>& out) const {
    out.clear();
    if (impl_->tree.m_root == nullptr) return;
    // btDbvt::collideTVNoStackAlloc's walk (the same nodes in the same order), written out: its
    // leaves came back through a virtual call each, and its stack checked its capacity per push.
    // The neighbour queries are a third of a dense bed's run.
    // A child is tested before it is pushed, so only boxes that overlap go through the stack (most
    // children a dense bed's query reaches do not): the nodes that overlap are popped in the same
    // order as when each was tested after its pop, so the shot come out in the same order.
    const btDbvtVolume box = volume(lo, hi);
    const btDbvtNode* root = impl_->tree.m_root;
    if (!Intersect(root->volume, box)) return;
    // The stack is written through a pointer, grown (rarely) before a push could pass its end:
    // push_back was a call of its own per node.
    std::vector<const btDbvtNode*>& stack = impl_->stack;
    const btDbvtNode** top = stack.data();
    *top++ = root;
    while (top != stack.data()) {
        const btDbvtNode* n = *--top;
        if (n->isinternal()) {
            if (static_cast<std::size_t>(top - stack.data()) + 2 > stack.size()) {
                const std::ptrdiff_t used = top - stack.data();
                stack.resize(2 * stack.size());
                top = stack.data() + used;
            }
            const btDbvtNode* a = n->childs[0];
            const btDbvtNode* b = n->childs[1];
            if (Intersect(a->volume, box)) *top++ = a;
            if (Intersect(b->volume, box)) *top++ = b;
        } else {
            out.push_back(static_cast<int>(reinterpret_cast<std::intptr_t>(n->data)));
        }
    }
}

}  // namespace peensim
