// HamtMap ("trie"): a persistent hash array mapped trie (Bagwell 2001, "Ideal Hash Trees") of landmarks,
// 16-way, with path copying and the same reference counting and pool as the tree.
#ifndef ARBOR_VARIANTS_MAPS_HAMT_MAP_H_
#define ARBOR_VARIANTS_MAPS_HAMT_MAP_H_

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "core/check.h"
#include "core/types/box2.h"
#include "core/types/landmark.h"
#include "core/engine/map_concept.h"
#include "core/memory/node_pool.h"
#include "variants/maps/persistent_map_base.h"
#include "variants/maps/persistent_node.h"

namespace arbor {

// Hash policies. kOrderPreserving: walking the trie in slot order gives ascending ids, so for_each and
// visit_near need no sort.
//
// The identity: ids are a dense creation serial, so the trie is a radix tree on the id and each subtree holds
// one run of consecutive ids, i.e. landmarks created close together: bounding boxes stay tight.
struct HamtIdentityHash {
  static constexpr bool kOrderPreserving = true;
  std::uint32_t operator()(LandmarkId id) const { return static_cast<std::uint32_t>(id); }
};
// A mixing hash (the MurmurHash3 finaliser): a classic HAMT, balanced whatever the ids, no spatial coherence.
struct HamtMixHash {
  static constexpr bool kOrderPreserving = false;
  std::uint32_t operator()(LandmarkId id) const {
    std::uint32_t h = static_cast<std::uint32_t>(id);
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
  }
};
// Deliberately bad: 6 bits of hash, so many ids share a full hash and end in collision nodes (tests only).
struct HamtCollidingHash {
  static constexpr bool kOrderPreserving = false;
  std::uint32_t operator()(LandmarkId id) const { return HamtMixHash{}(id) & 0xE0000007u; }
};

namespace internal {
// An inner node (count = popcount(bitmap)) or, below the last level, a collision node (count entries sorted
// by id, bitmap unused). Children are allocated right after the header.
struct alignas(16) HamtNode {
  std::atomic<std::uint32_t> rc{1};
  std::uint16_t bitmap = 0;
  std::uint16_t count = 0;
  std::uint32_t leaves = 0;  // landmarks below
  std::uint32_t inners = 0;  // inner and collision nodes below, this one included
  FBox box;
  HamtNode* base = nullptr;    // the node whose children this one borrows (PersistentMapBase::derive)
  std::uint32_t borrowed = 0;  // bit i: child i is base's, not counted here
  NodeRef child[];  // flexible array member (a GNU/Clang extension in C++)
};
static_assert(sizeof(HamtNode) == 48);
}  // namespace internal

// The trie consumes the 32-bit hash 4 bits per level from the most significant end, so that with the
// identity hash slot order is id order. The root starts at the lowest level that holds every hash seen and
// grows a level when a larger hash arrives (as a persistent vector does), so dense ids of N landmarks give
// ceil(log16 N) levels, not 8. An entry lives at the shallowest level where its hash prefix is unique
// (Bagwell); two entries whose 32 hash bits are all equal share a collision node, a list sorted by id.
//
// A node is one allocation: a 48-byte header (count, bitmap, leaf and inner-node counts below it, bounding
// box of the means below it, the borrowing fields) and a packed array of popcount(bitmap) child references.
//
// Complexity (N landmarks, k results, L = levels ~ log16 N): find O(L); set O(L) with L node copies
// when shared (at N = 10^6 and the identity hash: 5 nodes of <= 176 B and one 96 B leaf); insert and erase
// O(L), each level reallocated at its new size; copy O(1); visit_near O(L + k) nodes for spatially coherent
// ids (identity hash), plus a sort of the k results for hashes that do not preserve order.
template <class Hash = HamtIdentityHash, int Bits = 4>
class HamtMap : public internal::PersistentMapBase<HamtMap<Hash, Bits>, internal::HamtNode> {
  using Base = internal::PersistentMapBase<HamtMap<Hash, Bits>, internal::HamtNode>;
  static_assert(Bits >= 1 && Bits <= 4, "the bitmap holds 16 slots");
  using Base::acquire;
  using Base::acquire_all;
  using Base::leaves;
  using Base::own_all;
  using Base::release;
  using Base::root_;

 public:
  static constexpr std::string_view kName = "trie";
  using typename Base::Pool;

  // O(L), no allocation. Valid until this map is next modified.
  const Landmark* find(LandmarkId id) const {
    const std::uint32_t h = Hash{}(id);
    if (!fits(h, root_shift_)) return nullptr;
    Ref r = root_;
    int shift = root_shift_;
    while (r && !r.is_leaf()) {
      const Node* n = r.as_inner<Node>();
      if (shift < 0) {  // collision node
        for (int i = 0; i < n->count; ++i)
          if (n->child[i].as_leaf()->id == id) return n->child[i].as_leaf();
        return nullptr;
      }
      const std::uint32_t bit = 1u << digit(h, shift);
      if ((n->bitmap & bit) == 0) return nullptr;
      r = n->child[index(n->bitmap, bit)];
      shift -= kBits;
    }
    return r && r.as_leaf()->id == id ? r.as_leaf() : nullptr;
  }

  // Replaces the landmark with id lm.id, which must exist; copies the shared nodes of its path.
  void set(const Landmark& lm) {
    ARBOR_CHECK(root_ && fits(Hash{}(lm.id), root_shift_), "set of absent landmark {}", lm.id);
    root_ = set_rec(root_, true, root_shift_, Hash{}(lm.id), lm, internal::FBox::around(lm.mean));
  }

  // Adds a landmark whose id is absent.
  void insert(const Landmark& lm) {
    const std::uint32_t h = Hash{}(lm.id);
    Ref fresh = Ref::leaf(internal::new_leaf<Pool>(lm));
    if (!root_) {
      root_shift_ = 0;
      while (!fits(h, root_shift_)) root_shift_ += kBits;
      root_ = fresh;
      return;
    }
    while (!fits(h, root_shift_)) {  // grow a level on top: every old hash has digit 0 there
      root_shift_ += kBits;
      if (!root_.is_leaf()) {
        Node* top = new_node(1);
        top->bitmap = 1;
        top->child[0] = root_;
        top->leaves = leaves(root_);
        top->inners = inners(root_) + 1;
        top->box = root_.template as_inner<Node>()->box;
        root_ = Ref::inner(top);
      }
    }
    if (root_.is_leaf()) {
      ARBOR_CHECK(root_.as_leaf()->id != lm.id, "insert of present landmark {}", lm.id);
      root_ = merge(root_, fresh, root_shift_);
      return;
    }
    root_ = Ref::inner(insert_rec(root_.template as_inner<Node>(), root_shift_, h, fresh));
  }

  // Removes the landmark with this id if present.
  bool erase(LandmarkId id) {
    if (find(id) == nullptr) return false;
    root_ = erase_rec(root_, root_shift_, Hash{}(id), id);
    return true;
  }


 private:
  friend Base;
  using Ref = internal::NodeRef;
  using Node = internal::HamtNode;
  static constexpr int kBits = Bits;
  // The 32-bit hash is read from shift kTopShift down to 0, then collision nodes.
  static constexpr int kTopShift = (31 / kBits) * kBits;
  static constexpr std::uint32_t kDigitMask = (1u << kBits) - 1;

  // The scaffold's hooks (persistent_map_base.h).
  // Depth-first walks hold at most 2^kBits references per level, one level per digit plus the collision level.
  static constexpr int kStackSize = (1 << kBits) * (kTopShift / kBits + 2) + 1;
  static constexpr bool kSlotOrderIsIdOrder = Hash::kOrderPreserving;
  static std::span<const Ref> children(const Node* n) { return {n->child, n->count}; }
  static void delete_inner(Node* n) {
    const int count = n->count;
    n->~Node();
    Pool::deallocate(n, bytes(count));
  }
  static std::size_t inner_bytes(const Node* n) { return bytes(n->count); }
  // Every node of the subtree but its root fills one child slot.
  static internal::SubtreeSize subtree_size(const Node* n) {
    const std::size_t slots = std::size_t{n->leaves} + n->inners - 1;
    return {std::size_t{n->leaves} + n->inners,
            n->leaves * sizeof(internal::LeafNode) + n->inners * sizeof(Node) + slots * sizeof(Ref)};
  }

  static bool fits(std::uint32_t h, int shift) { return shift >= kTopShift || (h >> (shift + kBits)) == 0; }
  static int digit(std::uint32_t h, int shift) { return static_cast<int>((h >> shift) & kDigitMask); }
  // The slot of bit among the bitmap's set bits. std::popcount compiled to a libgcc call (1 % of Victoria
  // Park): Debian's x86-64 baseline has no popcnt instruction. The bitmap holds 16 slots, so a 16-bit SWAR
  // count does.
  static int index(std::uint32_t bitmap, std::uint32_t bit) {
    std::uint32_t v = bitmap & (bit - 1);
    v = v - ((v >> 1) & 0x5555u);
    v = (v & 0x3333u) + ((v >> 2) & 0x3333u);
    v = (v + (v >> 4)) & 0x0F0Fu;
    return static_cast<int>((v + (v >> 8)) & 0x1Fu);
  }
  static std::size_t bytes(int count) { return sizeof(Node) + count * sizeof(Ref); }
  static std::uint32_t inners(Ref r) { return !r || r.is_leaf() ? 0 : r.as_inner<Node>()->inners; }

  static Node* new_node(int count) {
    Node* n = new (Pool::allocate(bytes(count))) Node;
    n->count = static_cast<std::uint16_t>(count);
    return n;
  }
  static void copy_header(Node* to, const Node* from) {
    to->bitmap = from->bitmap;
    to->leaves = from->leaves;
    to->inners = from->inners;
    to->box = from->box;
  }
  // n (whose reference the caller owns) made writable at the same size.
  static Node* writable(Node* n) {
    if (internal::ref_unique(n->rc)) {
      own_all(n);
      return n;
    }
    Node* c = copy_of(n);
    acquire_all(children(c));
    release(Ref::inner(n));
    return c;
  }
  // A fresh node with n's header and child references, the references not yet counted.
  static Node* copy_of(const Node* n) {
    Node* c = new_node(n->count);
    copy_header(c, n);
    for (int i = 0; i < n->count; ++i) c->child[i] = n->child[i];
    return c;
  }
  // A copy of n (reference owned by the caller, given up) with one more slot, left empty at `at`. When n was
  // unshared its references move; otherwise they are shared.
  static Node* grown(Node* n, int at) {
    Node* c = new_node(n->count + 1);
    copy_header(c, n);
    const bool unique = internal::ref_unique(n->rc);
    if (unique) own_all(n);
    for (int i = 0; i < n->count; ++i) c->child[i < at ? i : i + 1] = n->child[i];
    if (!unique) acquire_all(children(n));
    if (unique) delete_inner(n);
    else release(Ref::inner(n));
    return c;
  }

  // Writes lm below r; returns the new subtree root. `owned`, the borrowing and the copy: PersistentMapBase::
  // set_inner, which takes one reference per level, to a node it has just read.
  static Ref set_rec(Ref r, bool owned, int shift, std::uint32_t h, const Landmark& lm, const internal::FBox& at) {
    if (r.is_leaf()) return Base::set_leaf(r, owned, lm);
    Node* n = r.as_inner<Node>();
    int i = 0;
    if (shift < 0) {
      while (i < n->count && n->child[i].as_leaf()->id != lm.id) ++i;
      ARBOR_CHECK(i < n->count, "set of absent landmark {}", lm.id);
    } else {
      const std::uint32_t bit = 1u << digit(h, shift);
      ARBOR_CHECK((n->bitmap & bit) != 0, "set of absent landmark {}", lm.id);
      i = index(n->bitmap, bit);
    }
    return Base::set_inner(n, owned, static_cast<std::size_t>(i), at,
                           [&](Ref child, bool own) { return set_rec(child, own, shift - kBits, h, lm, at); });
  }

  // A subtree at `shift` holding the two leaves a and b (distinct ids), references given.
  static Ref merge(Ref a, Ref b, int shift) {
    const internal::LeafNode* la = a.as_leaf();
    const internal::LeafNode* lb = b.as_leaf();
    const std::uint32_t ha = Hash{}(la->id), hb = Hash{}(lb->id);
    Node* n;
    if (shift < 0) {  // all 32 bits equal: collision node sorted by id
      n = new_node(2);
      const bool a_first = la->id < lb->id;
      n->child[0] = a_first ? a : b;
      n->child[1] = a_first ? b : a;
      n->inners = 1;
    } else if (digit(ha, shift) == digit(hb, shift)) {
      Ref sub = merge(a, b, shift - kBits);
      n = new_node(1);
      n->bitmap = static_cast<std::uint16_t>(1u << digit(ha, shift));
      n->child[0] = sub;
      n->inners = inners(sub) + 1;
    } else {
      n = new_node(2);
      const bool a_first = digit(ha, shift) < digit(hb, shift);
      n->bitmap = static_cast<std::uint16_t>((1u << digit(ha, shift)) | (1u << digit(hb, shift)));
      n->child[0] = a_first ? a : b;
      n->child[1] = a_first ? b : a;
      n->inners = 1;
    }
    n->leaves = 2;
    n->box.grow(la->mean);
    n->box.grow(lb->mean);
    return Ref::inner(n);
  }

  // Inserts leaf `fresh` (hash h) below n (reference owned, given up); returns the new subtree root.
  static Node* insert_rec(Node* n, int shift, std::uint32_t h, Ref fresh) {
    const internal::LeafNode* lf = fresh.as_leaf();
    Node* out;
    if (shift < 0) {
      int at = 0;
      while (at < n->count && n->child[at].as_leaf()->id < lf->id) ++at;
      ARBOR_CHECK(at == n->count || n->child[at].as_leaf()->id != lf->id, "insert of present landmark {}",
                  lf->id);
      out = grown(n, at);
      out->child[at] = fresh;
    } else {
      const std::uint32_t bit = 1u << digit(h, shift);
      const int at = index(n->bitmap, bit);
      if ((n->bitmap & bit) == 0) {
        out = grown(n, at);
        out->bitmap |= static_cast<std::uint16_t>(bit);
        out->child[at] = fresh;
      } else {
        out = writable(n);
        Ref& c = out->child[at];
        const std::uint32_t before = inners(c);
        if (c.is_leaf()) {
          ARBOR_CHECK(c.as_leaf()->id != lf->id, "insert of present landmark {}", lf->id);
          c = merge(c, fresh, shift - kBits);
        } else {
          c = Ref::inner(insert_rec(c.as_inner<Node>(), shift - kBits, h, fresh));
        }
        out->inners += inners(c) - before;
      }
    }
    out->leaves += 1;
    out->box.grow(lf->mean);
    return out;
  }

  // Removes id (present) below r (reference owned, given up). Returns the replacement: empty, a single leaf
  // (a node left with one leaf is folded into its parent, keeping entries at their shallowest level), or a node.
  static Ref erase_rec(Ref r, int shift, std::uint32_t h, LandmarkId id) {
    if (r.is_leaf()) {
      release(r);
      return {};
    }
    Node* n = r.as_inner<Node>();
    int at = 0;
    if (shift < 0) {
      while (n->child[at].as_leaf()->id != id) ++at;
    } else {
      at = index(n->bitmap, 1u << digit(h, shift));
    }
    const Ref c = n->child[at];
    if (c.is_leaf()) {
      // Drop the leaf: n shrinks by one slot.
      if (n->count == 1) {
        release(r);
        return {};
      }
      if (n->count == 2 && n->child[1 - at].is_leaf()) {  // fold the survivor into the parent
        Ref survivor = n->child[1 - at];
        acquire(survivor);
        release(r);
        return survivor;
      }
      Ref dropped = c;
      Node* out = resized_drop(n, at);
      release(dropped);
      if (shift >= 0) out->bitmap &= static_cast<std::uint16_t>(~(1u << digit(h, shift)));
      out->leaves -= 1;
      return Ref::inner(out);
    }
    Node* out = writable(n);
    const std::uint32_t before = inners(out->child[at]);
    Ref sub = erase_rec(out->child[at], shift - kBits, h, id);
    if (sub.is_leaf() && out->count == 1) {  // a chain ending in one leaf folds all the way up
      out->child[at] = {};
      release(Ref::inner(out));
      return sub;
    }
    out->child[at] = sub;
    out->leaves -= 1;
    out->inners -= before - inners(sub);
    return Ref::inner(out);
  }
  // n without child `at`; the caller keeps (and later releases) the reference that child[at] held.
  static Node* resized_drop(Node* n, int at) {
    Node* c = new_node(n->count - 1);
    copy_header(c, n);
    const bool unique = internal::ref_unique(n->rc);
    if (unique) own_all(n);
    for (int i = 0, j = 0; i < n->count; ++i) {
      if (i == at) continue;
      c->child[j++] = n->child[i];
      if (!unique) acquire(n->child[i]);
    }
    if (unique) {
      delete_inner(n);
    } else {
      acquire(n->child[at]);  // n keeps its own reference to the dropped child; ours goes back to the caller
      release(Ref::inner(n));
    }
    return c;
  }

  int root_shift_ = 0;
};

static_assert(LandmarkMap<HamtMap<>>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_MAPS_HAMT_MAP_H_
