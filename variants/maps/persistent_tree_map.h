// PersistentTreeMap ("tree"): the path-copying balanced binary tree of FastSLAM (Montemerlo et al. 2002;
// Probabilistic Robotics §13.8). Copying a map is O(1); set/insert/erase copy one root-to-leaf path.
#ifndef ARBOR_VARIANTS_MAPS_PERSISTENT_TREE_MAP_H_
#define ARBOR_VARIANTS_MAPS_PERSISTENT_TREE_MAP_H_

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <span>
#include <utility>

#include "core/check.h"
#include "core/types/box2.h"
#include "core/types/landmark.h"
#include "core/engine/map_concept.h"
#include "core/memory/node_pool.h"
#include "variants/maps/persistent_map_base.h"
#include "variants/maps/persistent_node.h"

namespace arbor {

namespace internal {
// An inner node: separator, AVL height, leaf count and bounding box below, two children.
struct alignas(16) TreeInner {
  std::atomic<std::uint32_t> rc{1};
  std::int32_t height = 1;
  LandmarkId split = 0;
  std::uint32_t leaves = 0;
  FBox box;
  NodeRef child[2];
};
static_assert(sizeof(TreeInner) == 48);
}  // namespace internal

// A leaf-oriented AVL tree keyed by LandmarkId: landmarks sit in the leaves; an inner node holds a separator
// (every id in its left subtree is <= split < every id in its right one), its height, its leaf count and the
// bounding box of the landmark means below it.
//
// Balancing: AVL (Adelson-Velsky & Landis 1962) on the inner nodes, heights of the two subtrees differ by at
// most one, so the height is <= 1.44 log2(N+2) whatever the order of inserts (the engine's increasing ids
// are the worst case for an unbalanced tree) and erases. Rotations never change a separator, so a stale
// separator left by an erase stays valid.
//
// Sharing: nodes carry an intrusive atomic count. A write walks down from the root and copies each node that
// another map also references (count > 1); below the first copied node every node it reaches is copied too,
// the siblings off the path are shared. A node with count 1 reached through nodes with count 1 is ours and
// is written in place (the rvalue case: a particle updating its own, unshared, path).
//
// Freeing: dropping a reference frees only nodes whose count reaches zero, with an explicit stack; the
// freed nodes are the ones a write made unreachable, so freeing costs amortised O(log N) per update.
//
// Complexity (N landmarks, k results): find O(log N); set/insert/erase O(log N) time and at most
// height+1 new nodes (48 B each, 96 B per leaf); copy O(1); visit_near O(log N + k) nodes when ids are
// spatially coherent (ids are a creation serial, so neighbours in id were created near each other).
class PersistentTreeMap : public internal::PersistentMapBase<PersistentTreeMap, internal::TreeInner> {
 public:
  static constexpr std::string_view kName = "tree";

  // O(log N), no allocation. The pointer is valid until this map is next modified.
  const Landmark* find(LandmarkId id) const {
    Ref r = root_;
    while (r && !r.is_leaf()) {
      const Inner* n = r.as_inner<Inner>();
      r = n->child[id <= n->split ? 0 : 1];
    }
    return r && r.as_leaf()->id == id ? r.as_leaf() : nullptr;
  }

  // Replaces the landmark with id lm.id, which must exist. Copies the shared part of its path.
  void set(const Landmark& lm) {
    ARBOR_CHECK(root_, "set of absent landmark {}", lm.id);
    root_ = set_rec(root_, true, lm, internal::FBox::around(lm.mean));
  }

  // Adds a landmark whose id is absent. O(log N), at most height+2 new nodes.
  void insert(const Landmark& lm) {
    if (!root_) {
      root_ = Ref::leaf(internal::new_leaf<Pool>(lm));
      return;
    }
    root_ = insert_rec(root_, lm);
  }

  // Removes the landmark with this id if present.
  bool erase(LandmarkId id) {
    if (find(id) == nullptr) return false;
    root_ = erase_rec(root_, id);
    return true;
  }

  // Height of the tree (0 for a single leaf; tests check the AVL bound).
  int height() const { return height(root_); }

 private:
  friend PersistentMapBase;
  using Ref = internal::NodeRef;
  using Inner = internal::TreeInner;

  // The scaffold's hooks (persistent_map_base.h).
  // AVL height <= 1.44 log2(N + 2) < 46 for N < 2^31; a depth-first walk holds at most 2 per level.
  static constexpr int kStackSize = 128;
  static constexpr bool kSlotOrderIsIdOrder = true;  // in-order: every left id <= split < every right id
  static std::span<const Ref> children(const Inner* n) { return n->child; }
  static void delete_inner(Inner* n) {
    n->~Inner();
    Pool::deallocate(n, sizeof(Inner));
  }
  static std::size_t inner_bytes(const Inner*) { return sizeof(Inner); }
  // A leaf-oriented binary tree of L leaves has L - 1 inner nodes.
  static internal::SubtreeSize subtree_size(const Inner* n) {
    return {2 * std::size_t{n->leaves} - 1, n->leaves * sizeof(internal::LeafNode) + (n->leaves - 1) * sizeof(Inner)};
  }

  static int height(Ref r) { return !r || r.is_leaf() ? 0 : r.as_inner<Inner>()->height; }
  static internal::FBox box_of(Ref r) {
    if (!r.is_leaf()) return r.as_inner<Inner>()->box;
    internal::FBox b;
    b.grow(r.as_leaf()->mean);
    return b;
  }

  static Inner* new_inner() { return new (Pool::allocate(sizeof(Inner))) Inner; }
  // n (whose reference the caller owns) made writable: itself when unshared, else a copy sharing its children.
  static Inner* writable(Inner* n) {
    if (internal::ref_unique(n->rc)) {
      own_all(n);  // (a no-op: the tree's nodes do not borrow)
      return n;
    }
    Inner* c = copy_of(n);
    acquire_all(c->child);
    release(Ref::inner(n));
    return c;
  }
  // A fresh node with n's fields and child references, the references not yet counted.
  static Inner* copy_of(const Inner* n) {
    Inner* c = new_inner();
    c->height = n->height;
    c->split = n->split;
    c->leaves = n->leaves;
    c->box = n->box;
    c->child[0] = n->child[0];
    c->child[1] = n->child[1];
    return c;
  }

  // Writes lm below r; returns the new subtree root (PersistentMapBase::set_inner). The tree's nodes do not
  // borrow, so derive counts the one sibling: with two children a base saves one increment per level and keeps
  // an old path alive per copy; tried, a filter-like run was slower and held 75 % more memory.
  static Ref set_rec(Ref r, bool owned, const Landmark& lm, const internal::FBox& at) {
    if (r.is_leaf()) return set_leaf(r, owned, lm);
    Inner* n = r.as_inner<Inner>();
    const std::size_t side = lm.id <= n->split ? 0 : 1;
    return set_inner(n, owned, side, at, [&](Ref child, bool own) { return set_rec(child, own, lm, at); });
  }

  static Ref insert_rec(Ref r, const Landmark& lm) {
    if (r.is_leaf()) {
      const internal::LeafNode* old = r.as_leaf();
      ARBOR_CHECK(old->id != lm.id, "insert of present landmark {}", lm.id);
      Ref fresh = Ref::leaf(internal::new_leaf<Pool>(lm));
      Inner* n = new_inner();
      const bool fresh_right = lm.id > old->id;
      n->child[0] = fresh_right ? r : fresh;
      n->child[1] = fresh_right ? fresh : r;
      n->split = std::min(lm.id, old->id);
      n->leaves = 2;
      n->box.grow(old->mean);
      n->box.grow(lm.mean);
      return Ref::inner(n);
    }
    Inner* n = writable(r.as_inner<Inner>());
    Ref& c = n->child[lm.id <= n->split ? 0 : 1];
    c = insert_rec(c, lm);
    return Ref::inner(rebalance(n));
  }

  static Ref erase_rec(Ref r, LandmarkId id) {
    if (r.is_leaf()) {
      release(r);
      return {};
    }
    Inner* n = writable(r.as_inner<Inner>());
    const int side = id <= n->split ? 0 : 1;
    Ref c = erase_rec(n->child[side], id);
    if (!c) {  // the leaf went: n's other child takes n's place
      Ref other = std::exchange(n->child[1 - side], {});
      n->child[side] = {};
      release(Ref::inner(n));
      return other;
    }
    n->child[side] = c;
    return Ref::inner(rebalance(n));
  }

  static void refresh(Inner* n) {
    n->height = 1 + std::max(height(n->child[0]), height(n->child[1]));
    n->leaves = leaves(n->child[0]) + leaves(n->child[1]);
    n->box = box_of(n->child[0]);
    n->box.grow(box_of(n->child[1]));
  }
  // Rotates n's child on `side` up into n's place (side 0: a right rotation, 1: a left one) and returns it.
  // n is writable; its children are n's own references.
  static Inner* rotate(Inner* n, int side) {
    Inner* up = writable(n->child[side].as_inner<Inner>());
    n->child[side] = up->child[1 - side];
    refresh(n);
    up->child[1 - side] = Ref::inner(n);
    refresh(up);
    return up;
  }
  static Inner* rebalance(Inner* n) {
    const int hl = height(n->child[0]), hr = height(n->child[1]);
    if (hl > hr + 1 || hr > hl + 1) {
      const int tall = hl > hr ? 0 : 1;
      const Inner* t = n->child[tall].as_inner<Inner>();
      // A tall child leaning inwards first turns outwards: the double rotation.
      if (height(t->child[tall]) < height(t->child[1 - tall]))
        n->child[tall] = Ref::inner(rotate(writable(n->child[tall].as_inner<Inner>()), 1 - tall));
      return rotate(n, tall);
    }
    refresh(n);
    return n;
  }
};

static_assert(LandmarkMap<PersistentTreeMap>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_MAPS_PERSISTENT_TREE_MAP_H_
