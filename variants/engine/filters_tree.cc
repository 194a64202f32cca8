// FastSLAM engine instantiations for the persistent tree map back end.
#include "variants/registry_impl.h"

ARBOR_INSTANTIATE_FILTERS(arbor::PersistentTreeMap)
