// Conformance suite for every map back end: each must answer exactly like a std::map reference for seeded
// random sequences of insert/set/erase/copy, keep copies independent, answer visit_near like a brute-force
// scan (same landmarks, same order) and free every node when the last map dies.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "core/engine/rng.h"
#include "core/engine/map_concept.h"
#include "core/types/box2.h"
#include "variants/maps/hamt_map.h"
#include "variants/maps/persistent_tree_map.h"
#include "variants/registry.h"

namespace arbor {
namespace {

using Reference = std::map<LandmarkId, Landmark>;

// Every back end in the registry, plus the trie with hashes that exercise other code paths (no id order,
// collision nodes) and with 8-way nodes (the fan-out is a template parameter).
template <class List>
struct WithExtraHashes;
template <class... Maps>
struct WithExtraHashes<TypeList<Maps...>> {
  using type = ::testing::Types<Maps..., HamtMap<HamtMixHash>, HamtMap<HamtCollidingHash>,
                                HamtMap<HamtIdentityHash, 3>>;
};
using Backends = WithExtraHashes<MapBackends>::type;

template <class M>
std::int64_t live_nodes() {
  if constexpr (requires { M::live_nodes(); }) return M::live_nodes();
  else return 0;
}

template <class M>
std::int64_t live_bytes() {
  if constexpr (requires { M::live_bytes(); }) return M::live_bytes();
  else return 0;
}
template <class M>
constexpr bool kCountsNodes = requires { M::live_nodes(); };

Landmark random_landmark(LandmarkId id, std::mt19937_64& rng, Vec2 centre = Vec2::Zero(), double spread = 50.0) {
  std::normal_distribution<double> n(0.0, 1.0);
  Landmark lm;
  lm.id = id;
  lm.mean = centre + spread * draw_vec2([&] { return n(rng); });
  const double a = 0.1 + std::abs(n(rng)), b = 0.1 + std::abs(n(rng)), c = 0.05 * n(rng);
  lm.cov << a, c, c, b;
  lm.log_odds = static_cast<float>(n(rng));
  lm.truth_label = static_cast<std::int32_t>(rng() % 1000);
  for (int k = 0; k < 3; ++k) lm.locality.add(static_cast<LandmarkId>(rng() % 5000));
  return lm;
}

// Inserts landmarks 0 .. count - 1, drawn from rng, into map and the reference alike.
template <class M>
void insert_random(LandmarkId count, std::mt19937_64& rng, M* map, Reference* ref) {
  for (LandmarkId id = 0; id < count; ++id) {
    Landmark lm = random_landmark(id, rng);
    map->insert(lm);
    (*ref)[id] = lm;
  }
}

template <class M>
void expect_same(const M& map, const Reference& ref) {
  ASSERT_EQ(map.size(), ref.size());
  std::vector<Landmark> seen;
  map.for_each([&](const Landmark& lm) { seen.push_back(lm); });
  ASSERT_EQ(seen.size(), ref.size());
  auto it = ref.begin();
  for (const Landmark& lm : seen) {
    ASSERT_EQ(lm.id, it->first);
    ASSERT_TRUE(lm == it->second) << "landmark " << lm.id;
    const Landmark* found = map.find(lm.id);
    ASSERT_NE(found, nullptr);
    ASSERT_TRUE(*found == it->second);
    ++it;
  }
}

template <class M>
class MapConformance : public ::testing::Test {};
TYPED_TEST_SUITE(MapConformance, Backends);

TYPED_TEST(MapConformance, EmptyMap) {
  TypeParam m;
  EXPECT_EQ(m.size(), 0u);
  EXPECT_EQ(m.find(0), nullptr);
  EXPECT_FALSE(m.erase(3));
  int calls = 0;
  m.for_each([&](const Landmark&) { ++calls; });
  m.visit_near(Box2{Vec2(-1e9, -1e9), Vec2(1e9, 1e9)}, [&](const Landmark&) { ++calls; });
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(m.memory_stats().shared_nodes, 0u);
  if (kCountsNodes<TypeParam>) {
    EXPECT_EQ(m.memory_stats().nodes, 0u);
  }
}

// Random insert/set/erase/copy/drop over a small population of maps, each checked against its reference.
TYPED_TEST(MapConformance, RandomSequencesMatchReference) {
  const std::int64_t baseline = live_nodes<TypeParam>();
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    std::mt19937_64 rng(seed);
    std::vector<TypeParam> maps(1);
    std::vector<Reference> refs(1);
    LandmarkId next_id = 0;
    for (int step = 0; step < 4000; ++step) {
      const std::size_t k = rng() % maps.size();
      TypeParam& m = maps[k];
      Reference& ref = refs[k];
      const int op = static_cast<int>(rng() % 100);
      if (op < 35) {  // insert: mostly the next serial id, sometimes an arbitrary unused one
        LandmarkId id = (rng() % 4 != 0) ? next_id++ : static_cast<LandmarkId>(rng() % 100000) + 1000000;
        if (ref.count(id)) continue;
        Landmark lm = random_landmark(id, rng);
        m.insert(lm);
        ref[id] = lm;
      } else if (op < 70 && !ref.empty()) {  // set an existing landmark
        auto it = ref.begin();
        std::advance(it, rng() % ref.size());
        Landmark lm = random_landmark(it->first, rng);
        m.set(lm);
        it->second = lm;
      } else if (op < 85) {  // erase, present or not
        LandmarkId id = static_cast<LandmarkId>(rng() % (next_id + 1));
        const bool present = ref.erase(id) > 0;
        ASSERT_EQ(m.erase(id), present);
      } else if (op < 95 && maps.size() < 6) {  // copy
        maps.push_back(maps[k]);
        refs.push_back(refs[k]);
      } else if (maps.size() > 1) {  // drop a map
        maps.erase(maps.begin() + k);
        refs.erase(refs.begin() + k);
      }
      if (step % 97 == 0) {
        for (std::size_t i = 0; i < maps.size(); ++i) expect_same(maps[i], refs[i]);
      }
      const LandmarkId probe = static_cast<LandmarkId>(rng() % (next_id + 2));
      const Landmark* got = maps[0].find(probe);
      auto want = refs[0].find(probe);
      ASSERT_EQ(got != nullptr, want != refs[0].end());
      if (got) {
        ASSERT_TRUE(*got == want->second);
      }
    }
    for (std::size_t i = 0; i < maps.size(); ++i) expect_same(maps[i], refs[i]);
  }
  EXPECT_EQ(live_nodes<TypeParam>(), baseline);
}

TYPED_TEST(MapConformance, CopyIsUnaffectedByLaterChangesToItsSource) {
  std::mt19937_64 rng(7);
  TypeParam source;
  Reference ref;
  insert_random(500, rng, &source, &ref);
  const TypeParam copy = source;
  for (LandmarkId id = 0; id < 500; id += 3) source.set(random_landmark(id, rng));
  for (LandmarkId id = 1; id < 500; id += 7) source.erase(id);
  for (LandmarkId id = 500; id < 700; ++id) source.insert(random_landmark(id, rng));
  expect_same(copy, ref);
  // And the other way round: writing the copy leaves the source alone.
  TypeParam copy2 = copy;
  const Reference before = ref;
  copy2.set(random_landmark(10, rng));
  copy2.erase(11);
  expect_same(copy, before);
}

TYPED_TEST(MapConformance, VisitNearEqualsBruteForceScan) {
  std::mt19937_64 rng(11);
  TypeParam m;
  // Landmarks laid along a random walk, as a robot creates them, plus scattered ones.
  Vec2 robot = Vec2::Zero();
  std::normal_distribution<double> n(0.0, 1.0);
  for (LandmarkId id = 0; id < 3000; ++id) {
    robot += draw_vec2([&] { return n(rng); }) * 2.0;
    m.insert(random_landmark(id, rng, robot, id % 10 == 0 ? 100.0 : 5.0));
  }
  for (LandmarkId id = 0; id < 3000; id += 5) m.erase(id);
  for (LandmarkId id = 1; id < 3000; id += 5) m.set(random_landmark(id, rng, robot, 40.0));
  std::uniform_real_distribution<double> u(-150.0, 150.0);
  for (int q = 0; q < 200; ++q) {
    const Vec2 c = draw_vec2([&] { return u(rng); });
    const double half = 1.0 + std::abs(u(rng)) / 5.0;
    const Box2 box{c - Vec2(half, half), c + Vec2(half, half)};
    std::vector<LandmarkId> brute, got;
    m.for_each([&](const Landmark& lm) {
      if (box.contains(lm.mean)) brute.push_back(lm.id);
    });
    m.visit_near(box, [&](const Landmark& lm) { got.push_back(lm.id); });
    ASSERT_EQ(got, brute) << "query " << q;
  }
  // A point box on an exact mean finds it (float boxes are rounded outward).
  const Landmark* lm = m.find(1);
  ASSERT_NE(lm, nullptr);
  int hits = 0;
  m.visit_near(Box2{lm->mean, lm->mean}, [&](const Landmark& x) { hits += x.id == 1; });
  EXPECT_EQ(hits, 1);
}

TYPED_TEST(MapConformance, LiveNodesReturnToZeroWhenTheLastMapDies) {
  const std::int64_t baseline = live_nodes<TypeParam>();
  {
    std::mt19937_64 rng(5);
    TypeParam a;
    for (LandmarkId id = 0; id < 1000; ++id) a.insert(random_landmark(id, rng));
    std::vector<TypeParam> copies(8, a);
    for (std::size_t i = 0; i < copies.size(); ++i) {
      for (int j = 0; j < 20; ++j) copies[i].set(random_landmark(static_cast<LandmarkId>(rng() % 1000), rng));
      copies[i].erase(static_cast<LandmarkId>(i * 100));
    }
    a = TypeParam();  // drop the parent first: its nodes live on in the copies
    if (kCountsNodes<TypeParam>) {
      EXPECT_GT(live_nodes<TypeParam>(), baseline);
    }
    copies.resize(3);
    a = copies[1];
  }
  EXPECT_EQ(live_nodes<TypeParam>(), baseline);
}

// Particles update their copies on several threads; nodes allocated on one thread die on another.
TYPED_TEST(MapConformance, ParallelUpdatesOfSharedMapsAreIndependentAndLeakFree) {
  const std::int64_t baseline = live_nodes<TypeParam>();
  {
    std::mt19937_64 rng(9);
    TypeParam parent;
    Reference ref;
    insert_random(2000, rng, &parent, &ref);
    constexpr int kParticles = 64;
    std::vector<TypeParam> particles(kParticles, parent);
    tbb::parallel_for(0, kParticles, [&](int p) {
      std::mt19937_64 local(100 + p);
      for (int j = 0; j < 50; ++j) {
        Landmark lm = random_landmark(static_cast<LandmarkId>(local() % 2000), local);
        lm.truth_label = p;
        particles[p].set(lm);
      }
      particles[p].erase(p);
      particles[p].insert(random_landmark(5000 + p, local));
    });
    expect_same(parent, ref);
    for (int p = 0; p < kParticles; ++p) {
      ASSERT_EQ(particles[p].size(), 2000u);
      ASSERT_EQ(particles[p].find(p), nullptr);
      ASSERT_NE(particles[p].find(5000 + p), nullptr);
    }
    parent = TypeParam();
    tbb::parallel_for(0, kParticles, [&](int p) { particles[p] = TypeParam(); });
  }
  EXPECT_EQ(live_nodes<TypeParam>(), baseline);
}

// The point of the persistent back ends: a set on a map shared with its parent allocates O(log N) nodes,
// and a set on an unshared map allocates none.
TYPED_TEST(MapConformance, SetOnSharedMapAllocatesOnlyAPath) {
  if (!kCountsNodes<TypeParam>) GTEST_SKIP() << "the back end does not count nodes";
  std::mt19937_64 rng(3);
  for (int n : {100, 5000, 40000}) {
    TypeParam parent;
    for (LandmarkId id = 0; id < n; ++id) parent.insert(random_landmark(id, rng));
    const double bound = 1.5 * std::log2(static_cast<double>(n)) + 4.0;  // AVL: 1.44 log2 N; trie: log16 N
    std::int64_t worst = 0;
    for (int k = 0; k < 50; ++k) {
      const LandmarkId id = static_cast<LandmarkId>(rng() % n);
      TypeParam c = parent;
      const std::int64_t before = live_nodes<TypeParam>();
      c.set(random_landmark(id, rng));
      worst = std::max(worst, live_nodes<TypeParam>() - before);
    }
    EXPECT_LE(worst, bound) << "n=" << n;
    EXPECT_GE(worst, 2) << "a shared set must copy at least the root and the leaf";
    // Unshared: written in place.
    TypeParam own = parent;
    parent = TypeParam();
    own.set(random_landmark(1, rng));
    const std::int64_t before = live_nodes<TypeParam>();
    for (int k = 0; k < 50; ++k) own.set(random_landmark(static_cast<LandmarkId>(rng() % n), rng));
    EXPECT_EQ(live_nodes<TypeParam>(), before) << "n=" << n;
  }
}

TYPED_TEST(MapConformance, MemoryStatsCountOwnedAndSharedNodes) {
  if (!kCountsNodes<TypeParam>) GTEST_SKIP() << "the back end does not count nodes";
  std::mt19937_64 rng(4);
  const std::int64_t nodes0 = live_nodes<TypeParam>(), bytes0 = live_bytes<TypeParam>();
  TypeParam a;
  for (LandmarkId id = 0; id < 3000; ++id) a.insert(random_landmark(id, rng));
  for (LandmarkId id = 0; id < 3000; id += 4) a.erase(id);
  MapMemoryStats s = a.memory_stats();
  EXPECT_EQ(static_cast<std::int64_t>(s.nodes), live_nodes<TypeParam>() - nodes0);
  EXPECT_EQ(static_cast<std::int64_t>(s.bytes), live_bytes<TypeParam>() - bytes0);
  EXPECT_EQ(s.shared_nodes, 0u);
  TypeParam b = a;
  s = a.memory_stats();
  EXPECT_EQ(s.shared_nodes, s.nodes);  // the root is shared, so everything is
  EXPECT_EQ(s.shared_bytes, s.bytes);
  const std::int64_t before = live_nodes<TypeParam>(), before_bytes = live_bytes<TypeParam>();
  b.set(random_landmark(1001, rng));
  const MapMemoryStats sb = b.memory_stats();
  EXPECT_EQ(static_cast<std::int64_t>(sb.nodes - sb.shared_nodes), live_nodes<TypeParam>() - before);
  EXPECT_EQ(static_cast<std::int64_t>(sb.bytes - sb.shared_bytes), live_bytes<TypeParam>() - before_bytes);
  EXPECT_EQ(sb.nodes, a.memory_stats().nodes);
  EXPECT_EQ(sb.bytes, a.memory_stats().bytes);
}

// A path copy borrows its original's other children (PersistentMapBase::derive) and so keeps the original
// alive. Once the copy has rewritten everything it borrowed, that hold must end: after the source dies, the
// nodes alive are exactly the ones the copy reaches.
TYPED_TEST(MapConformance, ACopyThatRewroteEverythingHoldsNothingOfItsSource) {
  if (!kCountsNodes<TypeParam>) GTEST_SKIP() << "the back end does not count nodes";
  std::mt19937_64 rng(6);
  const std::int64_t nodes0 = live_nodes<TypeParam>();
  {
    TypeParam a;
    for (LandmarkId id = 0; id < 700; ++id) a.insert(random_landmark(id, rng));
    TypeParam b = a;
    b.set(random_landmark(350, rng));  // shared: a path copy that borrows
    a = TypeParam();
    for (LandmarkId id = 0; id < 700; ++id) b.set(random_landmark(id, rng));
    EXPECT_EQ(static_cast<std::int64_t>(b.memory_stats().nodes), live_nodes<TypeParam>() - nodes0);
    EXPECT_EQ(b.memory_stats().shared_nodes, 0u);
  }
  EXPECT_EQ(live_nodes<TypeParam>(), nodes0);
}

TEST(PersistentTreeMap, StaysAvlBalancedUnderSerialInsertsAndRandomErases) {
  std::mt19937_64 rng(2);
  PersistentTreeMap m;
  constexpr int kN = 30000;
  for (LandmarkId id = 0; id < kN; ++id) m.insert(random_landmark(id, rng));
  EXPECT_LE(m.height(), 1.4405 * std::log2(kN + 2.0));
  for (int k = 0; k < kN / 2; ++k) m.erase(static_cast<LandmarkId>(rng() % kN));
  EXPECT_LE(m.height(), 1.4405 * std::log2(m.size() + 2.0));
}

}  // namespace
}  // namespace arbor
