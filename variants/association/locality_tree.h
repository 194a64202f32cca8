// Locality interpretation tree (Grimson's interpretation tree with the locality restriction of Ge & Lewis
// 2006, ch. 9): pose-free association for relocalisation, loop closing and as a per-particle strategy.
#ifndef ARBOR_VARIANTS_ASSOCIATION_LOCALITY_TREE_H_
#define ARBOR_VARIANTS_ASSOCIATION_LOCALITY_TREE_H_

#include <string_view>

#include "core/association/association_problem.h"
#include "variants/association/tree_strategy.h"

namespace arbor {

// Once a measurement is paired with feature f (the anchor, the first pairing), the remaining measurements may
// pair only with features in f's locality (covisibility) set, or stay unpaired. Why the anchor's set rather
// than the union or the intersection over all paired features: the bound n((c+1)^m - 1)/c + 1 is derived
// from exactly c + 1 branches per level after the first pairing; a union grows to m c features and loses the
// bound (and linearity in n); an intersection keeps the bound but, with capped locality sets, drops true
// features that are not in each other's capped set. Measured on generated problems (n = 150, m = 8 + 2
// clutter, kidnapped): anchor 26/30 correct, intersection 25/30; TreeSettings::anchor_only selects it.
// Needs no pose prior: candidates' world positions and the measured points in the robot frame only. The
// best hypotheses (most pairings) are verified by a closed-form pose and a joint chi-square test.
using LocalityTree = TreeStrategy<true>;

static_assert(AssociationStrategy<LocalityTree>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_LOCALITY_TREE_H_
