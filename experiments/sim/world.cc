// World generation and the rooms' line-of-sight test.
#include "experiments/sim/world.h"

#include <algorithm>
#include <cmath>

#include "core/engine/rng.h"

namespace arbor {

World make_world(const WorldOptions& o) {
  World w;
  w.kind = o.kind;
  w.side_m = std::sqrt(o.landmarks / o.density_per_m2);
  w.room_size_m = o.room_size_m;
  w.door_width_m = o.door_width_m;
  RandomStream rng(o.seed, 0, 0, RandomPurpose::kWorld);
  w.landmarks.reserve(o.landmarks);
  std::vector<Vec2> centres;
  if (o.kind == WorldKind::kClustered) {
    const int clusters = std::max(1, o.landmarks / o.landmarks_per_cluster);
    for (int c = 0; c < clusters; ++c) centres.push_back(draw_vec2([&] { return rng.uniform(); }) * w.side_m);
  }
  for (int i = 0; i < o.landmarks; ++i) {
    Vec2 p;
    if (o.kind == WorldKind::kClustered) {
      const Vec2& c = centres[i % centres.size()];
      p = c + o.cluster_sigma_m * draw_vec2([&] { return rng.normal(); });
      p = p.cwiseMax(0.0).cwiseMin(w.side_m);
    } else {
      p = {rng.uniform() * w.side_m, rng.uniform() * w.side_m};
    }
    w.landmarks.push_back({i, p});
    w.signatures.push_back(static_cast<float>(o.signature_min + (o.signature_max - o.signature_min) * rng.uniform()));
  }
  return w;
}

bool World::line_of_sight(const Vec2& a, const Vec2& b) const {
  if (kind != WorldKind::kRooms) return true;
  const double s = room_size_m, half_door = 0.5 * door_width_m;
  // A wall on the line x = k s (or y = k s) blocks unless the crossing lies within its doorway, which is
  // centred in the wall segment of each room.
  for (int axis = 0; axis < 2; ++axis) {
    const double a0 = a[axis], b0 = b[axis];
    const int k0 = static_cast<int>(std::floor(std::min(a0, b0) / s)) + 1;
    const int k1 = static_cast<int>(std::floor(std::max(a0, b0) / s));
    for (int k = k0; k <= k1; ++k) {
      const double wall = k * s;
      if (wall == a0 || wall == b0) continue;
      const double t = (wall - a0) / (b0 - a0);
      const double along = a[1 - axis] + t * (b[1 - axis] - a[1 - axis]);
      const double offset = along - (std::floor(along / s) + 0.5) * s;
      if (std::abs(offset) > half_door) return false;
    }
  }
  return true;
}

LandmarkGrid::LandmarkGrid(const World& world, double cell_m) : cell_m_(cell_m) {
  for (const auto& lm : world.landmarks) cells_[key(cell(lm.position.x()), cell(lm.position.y()))].push_back(lm.id);
}

}  // namespace arbor
