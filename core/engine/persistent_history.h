// What a particle remembers of its past (its poses, its association decisions) as a persistent singly linked
// list, newest entry first. Recording prepends one node (O(1)); resampled particles share their common past,
// so a copy is one reference-count increment instead of an O(T) vector copy (DESIGN.md §2).
#ifndef ARBOR_CORE_ENGINE_PERSISTENT_HISTORY_H_
#define ARBOR_CORE_ENGINE_PERSISTENT_HISTORY_H_

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <new>
#include <span>
#include <utility>
#include <vector>

#include "core/memory/node_pool.h"
#include "core/types/step_decisions.h"
#include "core/types/timed_pose.h"

namespace arbor {

template <typename Entry>
class PersistentHistory {
 public:
  PersistentHistory() = default;
  PersistentHistory(const PersistentHistory& o) : head_(o.head_) { retain(head_); }
  PersistentHistory(PersistentHistory&& o) noexcept : head_(std::exchange(o.head_, nullptr)) {}
  PersistentHistory& operator=(PersistentHistory o) noexcept {
    std::swap(head_, o.head_);
    return *this;
  }
  ~PersistentHistory() { release(head_); }

  // Prepends an entry; shares every older node with the histories this one was copied from.
  void push(Entry entry) { head_ = make_node(head_, std::move(entry)); }

  // Replaces the newest entry (a relocalised particle's pose for the step that recorded the lost one); the
  // older entries stay shared. The history must not be empty.
  void replace_newest(Entry entry) {
    Node* old = head_;
    retain(old->parent);
    head_ = make_node(old->parent, std::move(entry));
    release(old);
  }

  // The newest n entries (or all there are), newest first; O(n).
  std::vector<Entry> newest_entries(std::size_t n) const {
    std::vector<Entry> out;
    for (const Node* node = head_; node && out.size() < n; node = node->parent) out.push_back(node->entry);
    return out;
  }
  // Drops the newest n entries (a revised path is pushed again); the older ones stay shared.
  void drop_newest(std::size_t n) {
    Node* old = head_;
    for (std::size_t i = 0; i < n && head_; ++i) head_ = head_->parent;
    retain(head_);
    release(old);
  }

  bool empty() const { return head_ == nullptr; }
  // The history must not be empty.
  const Entry& newest() const { return head_->entry; }
  // Oldest first; O(T).
  std::vector<Entry> to_vector() const {
    std::vector<Entry> out;
    for (const Node* n = head_; n; n = n->parent) out.push_back(n->entry);
    return {out.rbegin(), out.rend()};
  }
  // The newest entry every history in `histories` shares, or null where they share none (each particle's
  // history starts at its own draw of the initial pose). The histories must be equally long, as the particles'
  // are (every particle records at the same steps); O(n * the depth of the shared entry).
  static const Entry* newest_shared_entry(std::span<const PersistentHistory* const> histories) {
    std::vector<const Node*> nodes;
    for (const PersistentHistory* h : histories) nodes.push_back(h->head_);
    while (!nodes.empty() && nodes.front()) {
      if (std::all_of(nodes.begin(), nodes.end(), [&](const Node* n) { return n == nodes.front(); })) return &nodes.front()->entry;
      for (const Node*& n : nodes) n = n ? n->parent : nullptr;
    }
    return nullptr;
  }
  // Nodes ever allocated minus freed, all histories of this entry type together: the leak check of the tests.
  static std::int64_t live_nodes() { return Pool::live_nodes(); }

 private:
  struct Node {
    std::atomic<std::int32_t> refs;
    Node* parent;
    Entry entry;
  };

  // Every particle pushes at every step, and a node is often freed on another thread than the one that made
  // it (its particle was resampled away there): the back ends' pool, with its per-thread bins and tallies,
  // where the global heap and one shared counter cost 5 % of a Victoria Park run in locks and cache-line
  // transfers (results/engine/b0ab821_vm_gcc-12.2.0/).
  using Pool = internal::NodePool<Node>;
  static Node* make_node(Node* parent, Entry entry) {
    return new (Pool::allocate(sizeof(Node))) Node{{1}, parent, std::move(entry)};
  }
  static void retain(Node* n) {
    if (n) n->refs.fetch_add(1, std::memory_order_relaxed);
  }
  // Frees the nodes whose count drops to zero, walking towards the root iteratively: a 60,000-pose history
  // released by recursion would overflow the stack.
  static void release(Node* n) {
    while (n && n->refs.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      Node* parent = n->parent;
      n->~Node();
      Pool::deallocate(n, sizeof(Node));
      n = parent;
    }
  }

  Node* head_ = nullptr;
};

using PoseHistory = PersistentHistory<TimedPose>;
using DecisionHistory = PersistentHistory<StepDecisions>;

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_PERSISTENT_HISTORY_H_
