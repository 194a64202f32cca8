// The other half of the deliberate include loop (see a/a.h); never compiled.
#include "tests/data/include_loop/a/a.h"
