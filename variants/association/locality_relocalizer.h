// The engine's relocaliser (FastSlamOptions::relocalize): the pose-free locality tree over a particle's map.
#ifndef ARBOR_VARIANTS_ASSOCIATION_LOCALITY_RELOCALIZER_H_
#define ARBOR_VARIANTS_ASSOCIATION_LOCALITY_RELOCALIZER_H_

#include "core/association/association_problem.h"
#include "core/engine/relocalization.h"

namespace arbor {

// Answers with the locality tree's verified pose and the number of measurements its answer pairs (after
// its completion at that pose), or 0 when no hypothesis was verified.
Relocalizer make_locality_relocalizer(const AssociationOptions& options);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_LOCALITY_RELOCALIZER_H_
