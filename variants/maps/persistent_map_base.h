// The scaffold every persistent back end stands on: the root reference and its counting (an O(1) copy, a
// move, a destruction that frees only what no other map reaches), size, memory_stats, and the ordered walk
// with bounding-box pruning. A back end derives from PersistentMapBase<Itself, Inner> and writes only its
// node layout and its search (find, set, insert, erase).
#ifndef ARBOR_VARIANTS_MAPS_PERSISTENT_MAP_BASE_H_
#define ARBOR_VARIANTS_MAPS_PERSISTENT_MAP_BASE_H_

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/check.h"
#include "core/engine/map_concept.h"
#include "core/types/box2.h"
#include "core/types/landmark.h"
#include "core/memory/node_pool.h"
#include "variants/maps/persistent_node.h"

namespace arbor::internal {

// Nodes and bytes of a whole subtree, its root included.
struct SubtreeSize {
  std::size_t nodes = 0;
  std::size_t bytes = 0;
};

// What a back end tells the scaffold, as static members (private; it befriends its base): its Inner node
// has an atomic `rc`, a `leaves` count, an FBox `box` of the means below it, optionally the borrowing
// fields `Inner* base` and `std::uint32_t borrowed` (see derive), and it gives
//   children(n)        std::span<const NodeRef>: n's child references in walk order (n->child[i] is slot i)
//   copy_of(n)         a fresh node with n's fields and child references, the references not yet counted
//   delete_inner(n)    frees n itself (its children were already let go)
//   inner_bytes(n)     bytes of n itself
//   subtree_size(n)    SubtreeSize of n's whole subtree, from n's own counts (a shared part's memory_stats)
//   kStackSize         the deepest stack of a depth-first walk: children per node times levels, plus one
//   kSlotOrderIsIdOrder  whether walking children in order visits ascending ids (else the walk sorts)
template <class Derived, class Inner>
class PersistentMapBase {
 public:
  // Each back end (each instantiation) has its own pool and so its own live-node counters.
  using Pool = NodePool<Derived>;

  PersistentMapBase() = default;
  PersistentMapBase(const PersistentMapBase& o) : root_(o.root_) { acquire(root_); }
  PersistentMapBase(PersistentMapBase&& o) noexcept : root_(std::exchange(o.root_, {})) {}
  PersistentMapBase& operator=(const PersistentMapBase& o) {
    if (this != &o) {
      acquire(o.root_);
      release(std::exchange(root_, o.root_));
    }
    return *this;
  }
  PersistentMapBase& operator=(PersistentMapBase&& o) noexcept {
    if (this != &o) release(std::exchange(root_, std::exchange(o.root_, {})));
    return *this;
  }
  ~PersistentMapBase() { release(root_); }

  std::size_t size() const { return leaves(root_); }

  // Ascending id order.
  template <class F>
  void for_each(F&& f) const {
    walk(nullptr, f);
  }
  // Landmarks whose mean lies in box, ascending id; subtrees whose bounding box misses the box are skipped.
  template <class F>
  void visit_near(const Box2& box, F&& f) const {
    walk(&box, f);
  }

  // Nodes and bytes reachable through child references (the map's own structure; an unshared node's base,
  // see derive, counts too, as the one node it is); a node counts as shared if it, or a node above it, has
  // count > 1 (so another map reaches it), and a borrowed child is shared when its lender is. Only the
  // unshared part is walked: a shared subtree is summed from its root's counts.
  MapMemoryStats memory_stats() const {
    MapMemoryStats s;
    if (!root_) return s;
    struct Item {
      NodeRef r;
      bool shared;  // through a shared lender
    };
    std::vector<Item> stack{{root_, false}};
    while (!stack.empty()) {
      const Item it = stack.back();
      stack.pop_back();
      if (it.r.is_leaf()) {
        s.add(1, sizeof(LeafNode), it.shared || it.r.as_leaf()->rc.load(std::memory_order_relaxed) > 1);
        continue;
      }
      const Inner* n = it.r.template as_inner<Inner>();
      if (it.shared || n->rc.load(std::memory_order_relaxed) > 1) {
        const SubtreeSize sub = Derived::subtree_size(n);
        s.add(sub.nodes, sub.bytes, true);
        continue;
      }
      s.add(1, Derived::inner_bytes(n), false);
      const Inner* lender = base_of(n);
      const bool lender_shared = lender != nullptr && lender->rc.load(std::memory_order_relaxed) > 1;
      if (lender != nullptr && !lender_shared) s.add(1, Derived::inner_bytes(lender), false);
      const std::span<const NodeRef> kids = Derived::children(n);
      for (std::size_t i = 0; i < kids.size(); ++i)
        if (kids[i]) stack.push_back({kids[i], lender_shared && borrows(n, i)});
    }
    return s;
  }

  // Nodes (bytes) of all maps of this back end alive now: the leak tests and the memory benchmarks.
  static std::int64_t live_nodes() { return Pool::live_nodes(); }
  static std::int64_t live_bytes() { return Pool::live_bytes(); }

 protected:
  static std::uint32_t leaves(NodeRef r) { return !r ? 0 : r.is_leaf() ? 1 : r.as_inner<Inner>()->leaves; }

  static void acquire(NodeRef r) {
    if (!r) return;
    if (r.is_leaf()) ref_inc(r.as_leaf()->rc);
    else ref_inc(r.as_inner<Inner>()->rc);
  }
  // One more reference to each of a copied node's children.
  static void acquire_all(std::span<const NodeRef> children) {
    prefetch_counts(children);
    for (NodeRef c : children) acquire(c);
  }
  // The same for all but children[path]: the child a write is about to replace, which the copy borrows from
  // the node it was copied from until then (see the back ends' set), so it never takes and drops a reference.
  static void acquire_all_but(std::span<const NodeRef> children, std::size_t path) {
    prefetch_counts(children);
    for (std::size_t i = 0; i < children.size(); ++i)
      if (i != path) acquire(children[i]);
  }
  // Whether the back end's nodes borrow (they have the fields); one that does not gets the classic path copy.
  static constexpr bool kBorrows = requires(Inner* n) {
    n->base;
    n->borrowed;
  };
  // Borrowing. A path copy c of a node n needs every child of n but the one the write replaces. Counting
  // each of them (the classic path copy) is a locked increment on a cache line of its own, all over the heap:
  // at 10^6 landmarks a 16-way trie's set took ~75 of them, and freeing the copy as many decrements, which
  // was most of its time. Instead c takes one reference to n, its `base`, which keeps n's children alive, and
  // marks them `borrowed` (bit i: child i is held by base, not counted by c). n was just read, so its count
  // is in cache. The base is always a node that borrows nothing, so bases never chain: copying a borrowing
  // node borrows from its base and counts only the few children it had replaced.
  //
  // The price is memory: a base lives as long as a node borrows from it, and with it the children its
  // borrowers replaced (old leaves, mostly), until the borrower has replaced every borrowed child itself
  // (stop_borrowing) or dies (BM_Map_Lineage in bench/map_benchmark.cc measures it). A back end whose nodes
  // lack the fields gets the classic copy here.
  //
  // c, a fresh copy of n's child references (not yet counted), is made to share all of them but
  // children[path], which the caller is about to replace with a reference of c's own.
  static void derive(Inner* c, const Inner* n, std::size_t path) {
    const std::span<const NodeRef> kids = Derived::children(c);
    if constexpr (kBorrows) {
      if (kids.size() <= 32) {  // (a wider collision node counts its children, as a classic path copy does)
        const std::uint32_t all = kids.size() == 32 ? ~0u : (1u << kids.size()) - 1;
        const std::uint32_t from_base = (n->base != nullptr ? n->borrowed : all) & ~(1u << path);
        for (std::uint32_t own = all & ~from_base & ~(1u << path); own != 0; own &= own - 1)
          acquire(kids[std::countr_zero(own)]);
        if (from_base == 0) return;
        Inner* base = n->base != nullptr ? n->base : const_cast<Inner*>(n);
        ref_inc(base->rc);
        c->base = base;
        c->borrowed = from_base;
        return;
      }
    }
    acquire_all_but(kids, path);
  }
  static bool borrows(const Inner* n, std::size_t i) {
    if constexpr (kBorrows) return i < 32 && ((n->borrowed >> i) & 1u) != 0;
    else return false;
  }
  static Inner* base_of(const Inner* n) {
    if constexpr (kBorrows) return n->base;
    else return nullptr;
  }
  // n (ours alone) has just replaced its borrowed child i with a reference of its own; once it borrows
  // nothing it lets its base go, and with it whatever only the base still held.
  static void stop_borrowing(Inner* n, std::size_t i) {
    if constexpr (kBorrows) {
      n->borrowed &= ~(1u << i);
      if (n->borrowed == 0) release(NodeRef::inner(std::exchange(n->base, nullptr)));
    }
  }
  // n (ours alone) is about to be restructured, which moves its references around: it counts what it
  // borrowed and lets its base go.
  static void own_all(Inner* n) {
    if constexpr (kBorrows) {
      if (n->base == nullptr) return;
      const std::span<const NodeRef> kids = Derived::children(n);
      for (std::uint32_t b = n->borrowed; b != 0; b &= b - 1) acquire(kids[std::countr_zero(b)]);
      n->borrowed = 0;
      release(NodeRef::inner(std::exchange(n->base, nullptr)));
    }
  }

  // The two ends of a set's walk down, the same in every back end. `owned`: the caller's slot holds a counted
  // reference to r, which this gives up; otherwise the slot borrows r (from the node it was copied from, or
  // from that node's base), which keeps r alive, and r is left as it is. Only an owned, unshared node is
  // written in place. A copy borrows every child but the one on the path (derive), which it fills with what
  // `down(child, owned)` returns; it drops the reference to the node it copied only after the write.
  template <class Down>
  static NodeRef set_inner(Inner* n, bool owned, std::size_t i, const FBox& at, Down&& down) {
    if (owned && ref_unique(n->rc)) {
      const bool borrowed = borrows(n, i);
      n->child[i] = down(n->child[i], !borrowed);
      if (borrowed) stop_borrowing(n, i);
      n->box.grow(at);
      return NodeRef::inner(n);
    }
    Inner* c = Derived::copy_of(n);
    derive(c, n, i);
    c->child[i] = down(n->child[i], false);
    c->box.grow(at);
    if (owned) release(NodeRef::inner(n));
    return NodeRef::inner(c);
  }
  static NodeRef set_leaf(NodeRef r, bool owned, const Landmark& lm) {
    ARBOR_CHECK(r.as_leaf()->id == lm.id, "set of absent landmark {}", lm.id);
    return NodeRef::leaf(owned ? replace_leaf<Pool>(r.as_leaf(), lm) : new_leaf<Pool>(lm));
  }

  // Drops one reference; frees every node whose count reaches zero, with an explicit stack (no recursion).
  // A freed node drops its own children's references and its base's, not the ones it borrowed.
  static void release(NodeRef r) {
    if (!r) return;
    if (r.is_leaf()) {
      release_leaf<Pool>(r.as_leaf());
      return;
    }
    Inner* n = r.as_inner<Inner>();
    if (!ref_dec(n->rc)) return;
    // A base sits at its borrower's level and borrows nothing, so a chain of frees descends a level at least
    // every second node: twice the walk's depth, one more slot per node for its base.
    std::array<Inner*, 3 * Derived::kStackSize> stack;
    int top = 0;
    stack[top++] = n;
    while (top > 0) {
      Inner* cur = stack[--top];
      const std::span<const NodeRef> kids = Derived::children(cur);
      for (std::size_t i = 0; i < kids.size(); ++i) {
        const NodeRef c = kids[i];
        if (!c || borrows(cur, i)) continue;  // empty: a slot cleared just before the node is dropped
        if (c.is_leaf()) release_leaf<Pool>(c.as_leaf());
        else if (ref_dec(c.as_inner<Inner>()->rc)) stack[top++] = c.as_inner<Inner>();
      }
      if (Inner* base = base_of(cur); base != nullptr && ref_dec(base->rc)) stack[top++] = base;
      Derived::delete_inner(cur);
    }
  }

  NodeRef root_;

 private:
  // Each increment is a locked read-modify-write, which waits for its cache line before the next may start;
  // the siblings of a path live all over the heap, so their counts are requested together first.
  static void prefetch_counts(std::span<const NodeRef> children) {
    for (NodeRef c : children) {
      if (!c) continue;
      if (c.is_leaf()) __builtin_prefetch(&c.as_leaf()->rc, 1);
      else __builtin_prefetch(&c.as_inner<Inner>()->rc, 1);
    }
  }

  // From the root, depth first, children in walk order: on_leaf for every leaf reached, on_inner for every
  // inner node reached, whose children are visited only when it returns true. No recursion.
  template <class OnLeaf, class OnInner>
  void depth_first(OnLeaf&& on_leaf, OnInner&& on_inner) const {
    if (!root_) return;
    std::array<NodeRef, Derived::kStackSize> stack;
    int top = 0;
    stack[top++] = root_;
    while (top > 0) {
      const NodeRef r = stack[--top];
      if (r.is_leaf()) {
        on_leaf(r.as_leaf());
        continue;
      }
      const Inner* n = r.as_inner<Inner>();
      if (!on_inner(n)) continue;
      const std::span<const NodeRef> children = Derived::children(n);
      for (auto c = children.rbegin(); c != children.rend(); ++c) stack[top++] = *c;
    }
  }

  template <class F>
  void walk(const Box2* box, F& f) const {
    std::vector<const Landmark*> found;  // only where slot order is not id order
    depth_first(
        [&](const Landmark* lm) {
          if (box != nullptr && !box->contains(lm->mean)) return;
          if constexpr (Derived::kSlotOrderIsIdOrder) f(*lm);
          else found.push_back(lm);
        },
        [&](const Inner* n) { return box == nullptr || n->box.intersects(*box); });
    if constexpr (!Derived::kSlotOrderIsIdOrder) {
      std::sort(found.begin(), found.end(), [](const Landmark* a, const Landmark* b) { return a->id < b->id; });
      for (const Landmark* lm : found) f(*lm);
    }
  }
};

}  // namespace arbor::internal

#endif  // ARBOR_VARIANTS_MAPS_PERSISTENT_MAP_BASE_H_
