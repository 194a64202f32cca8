// An axis-aligned box in world coordinates [m], the query shape of the maps' spatial searches.
#ifndef ARBOR_CORE_TYPES_BOX2_H_
#define ARBOR_CORE_TYPES_BOX2_H_

#include "core/math/eigen_types.h"

namespace arbor {

struct Box2 {
  Vec2 min;
  Vec2 max;
  bool contains(const Vec2& p) const {
    return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y();
  }
  bool intersects(const Box2& o) const {
    return min.x() <= o.max.x() && o.min.x() <= max.x() && min.y() <= o.max.y() && o.min.y() <= max.y();
  }
};

}  // namespace arbor

#endif  // ARBOR_CORE_TYPES_BOX2_H_
