// Simulated worlds of point landmarks with ground truth (DESIGN.md §6): uniform, clustered, and rooms whose
// walls block sight (the case where distance-based locality is wrong and covisibility is right).
#ifndef ARBOR_EXPERIMENTS_SIM_WORLD_H_
#define ARBOR_EXPERIMENTS_SIM_WORLD_H_

#include <cstdint>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/enum_names.h"
#include "core/types/scenario.h"

namespace arbor {

enum class WorldKind { kUniform, kClustered, kRooms };
template <> inline constexpr EnumNames<WorldKind, 3> kNamesOf<WorldKind>{
    {{WorldKind::kUniform, "uniform"}, {WorldKind::kClustered, "clustered"}, {WorldKind::kRooms, "rooms"}}};

struct WorldOptions {
  WorldKind kind = WorldKind::kUniform;
  int landmarks = 200;
  // Landmarks per square metre. The world's side grows as sqrt(landmarks / density), so the number in view
  // per scan stays the same whatever the map size.
  double density_per_m2 = 0.02;
  double cluster_sigma_m = 3.0;     // clustered: spread of a cluster
  int landmarks_per_cluster = 8;
  double room_size_m = 20.0;        // rooms: square rooms with a doorway in the middle of every wall
  double door_width_m = 5.0;
  double signature_min = 0.1, signature_max = 1.0;  // true signatures (used when the sensor reports them)
  std::uint64_t seed = 1;
};

struct World {
  WorldKind kind = WorldKind::kUniform;
  double side_m = 0.0;  // landmarks lie in [0, side]^2
  double room_size_m = 0.0, door_width_m = 0.0;
  std::vector<TruthLandmark> landmarks;  // id = index
  std::vector<float> signatures;

  // Whether the straight segment a-b crosses no wall (always true outside the rooms world).
  bool line_of_sight(const Vec2& a, const Vec2& b) const;
};

World make_world(const WorldOptions& options);

// Uniform grid over landmark indices, so a scan looks at nearby cells instead of all N landmarks.
class LandmarkGrid {
 public:
  LandmarkGrid(const World& world, double cell_m);
  template <class F>
  void visit_within(const Vec2& center, double radius, F&& f) const {
    const int x0 = cell(center.x() - radius), x1 = cell(center.x() + radius);
    const int y0 = cell(center.y() - radius), y1 = cell(center.y() + radius);
    for (int cy = y0; cy <= y1; ++cy)
      for (int cx = x0; cx <= x1; ++cx) {
        auto it = cells_.find(key(cx, cy));
        if (it == cells_.end()) continue;
        for (int index : it->second) f(index);
      }
  }

 private:
  int cell(double v) const { return static_cast<int>(std::floor(v / cell_m_)); }
  static std::int64_t key(int cx, int cy) { return (static_cast<std::int64_t>(cx) << 32) ^ static_cast<std::uint32_t>(cy); }
  double cell_m_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SIM_WORLD_H_
