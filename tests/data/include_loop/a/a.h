// Half of a deliberate include loop for Layering.IncludeGraphFindsALoop (tests/CMakeLists.txt); never compiled.
#include "tests/data/include_loop/b/b.h"
