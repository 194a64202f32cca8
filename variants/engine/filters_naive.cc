// FastSLAM engine instantiations for the naive map back end.
#include "variants/registry_impl.h"

ARBOR_INSTANTIATE_FILTERS(arbor::VectorMap)
