// Pieces shared by the persistent back ends (tree and trie): the leaf that holds one landmark, the tagged
// child reference, and the float bounding box that inner nodes keep for spatial pruning.
#ifndef ARBOR_VARIANTS_MAPS_PERSISTENT_NODE_H_
#define ARBOR_VARIANTS_MAPS_PERSISTENT_NODE_H_

#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <new>

#include "core/types/box2.h"
#include "core/types/landmark.h"
#include "core/memory/node_pool.h"

namespace arbor::internal {

// A landmark with its reference count. Deriving (rather than holding a member) lets the Itanium C++ ABI put
// the count in Landmark's tail padding: a leaf costs exactly sizeof(Landmark) = 112 bytes, not 128.
struct LeafNode : Landmark {
  explicit LeafNode(const Landmark& lm) : Landmark(lm) {}
  std::atomic<std::uint32_t> rc{1};
};
static_assert(sizeof(LeafNode) == sizeof(Landmark), "the count should live in Landmark's tail padding");

// A reference to a child: a leaf or an inner node, told apart by the low bit (nodes are 16-byte aligned).
class NodeRef {
 public:
  NodeRef() = default;
  static NodeRef leaf(LeafNode* p) { return NodeRef(reinterpret_cast<std::uintptr_t>(p) | 1u); }
  template <class Inner>
  static NodeRef inner(Inner* p) { return NodeRef(reinterpret_cast<std::uintptr_t>(p)); }

  explicit operator bool() const { return bits_ != 0; }
  bool is_leaf() const { return (bits_ & 1u) != 0; }
  LeafNode* as_leaf() const { return reinterpret_cast<LeafNode*>(bits_ & ~std::uintptr_t{1}); }
  template <class Inner>
  Inner* as_inner() const { return reinterpret_cast<Inner*>(bits_); }
  bool operator==(const NodeRef&) const = default;

 private:
  explicit NodeRef(std::uintptr_t bits) : bits_(bits) {}
  std::uintptr_t bits_ = 0;
};

// Bounding box of the landmark means below an inner node, in float to keep nodes small. Coordinates are
// rounded outward, so the float box always contains the double one and pruning never loses a landmark.
// Inner nodes keep a superset of the true box (it grows on set and is not shrunk on every erase): still
// correct for pruning, and O(1) per copied node instead of a pass over the siblings.
struct FBox {
  float x0 = std::numeric_limits<float>::infinity();
  float y0 = std::numeric_limits<float>::infinity();
  float x1 = -std::numeric_limits<float>::infinity();
  float y1 = -std::numeric_limits<float>::infinity();

  static float down(double v) {
    float f = static_cast<float>(v);
    return static_cast<double>(f) > v ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
  }
  static float up(double v) {
    float f = static_cast<float>(v);
    return static_cast<double>(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
  }
  // The box of one point: a write computes it once and grows every node of its path by it (the outward
  // rounding calls nextafter, so it is not free).
  static FBox around(const Vec2& p) {
    FBox b;
    b.grow(p);
    return b;
  }
  void grow(const Vec2& p) {
    const float lx = down(p.x()), ly = down(p.y()), hx = up(p.x()), hy = up(p.y());
    x0 = lx < x0 ? lx : x0;
    y0 = ly < y0 ? ly : y0;
    x1 = hx > x1 ? hx : x1;
    y1 = hy > y1 ? hy : y1;
  }
  void grow(const FBox& b) {
    x0 = b.x0 < x0 ? b.x0 : x0;
    y0 = b.y0 < y0 ? b.y0 : y0;
    x1 = b.x1 > x1 ? b.x1 : x1;
    y1 = b.y1 > y1 ? b.y1 : y1;
  }
  bool intersects(const Box2& q) const {
    return x0 <= q.max.x() && q.min.x() <= x1 && y0 <= q.max.y() && q.min.y() <= y1;
  }
};

template <class Pool>
LeafNode* new_leaf(const Landmark& lm) {
  return new (Pool::allocate(sizeof(LeafNode))) LeafNode(lm);
}
template <class Pool>
void delete_leaf(LeafNode* leaf) {
  leaf->~LeafNode();
  Pool::deallocate(leaf, sizeof(LeafNode));
}
// Drops one reference to a leaf and frees it when it was the last.
template <class Pool>
void release_leaf(LeafNode* leaf) {
  if (ref_dec(leaf->rc)) delete_leaf<Pool>(leaf);
}
// The leaf holding lm in place of `old` (whose reference the caller owns and gives up): written in place when
// nobody else holds it, else a fresh copy.
template <class Pool>
LeafNode* replace_leaf(LeafNode* old, const Landmark& lm) {
  if (ref_unique(old->rc)) {
    static_cast<Landmark&>(*old) = lm;
    return old;
  }
  LeafNode* fresh = new_leaf<Pool>(lm);
  release_leaf<Pool>(old);
  return fresh;
}

}  // namespace arbor::internal

#endif  // ARBOR_VARIANTS_MAPS_PERSISTENT_NODE_H_
