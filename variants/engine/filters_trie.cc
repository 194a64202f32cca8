// FastSLAM engine instantiations for the hash array mapped trie back end.
#include "variants/registry_impl.h"

ARBOR_INSTANTIATE_FILTERS(arbor::HamtMap<>)
