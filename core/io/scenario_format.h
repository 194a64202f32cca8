// Reading and writing the scenario text format (docs/scenario_format.md): one path into the engine for
// simulated and real data alike.
#ifndef ARBOR_CORE_IO_SCENARIO_FORMAT_H_
#define ARBOR_CORE_IO_SCENARIO_FORMAT_H_

#include <string>

#include "core/io/field_limits.h"
#include "core/types/scenario.h"

namespace arbor {

// The physical limits (scenario_limits) live in core/io/field_limits.h, shared with the dataset readers.

// Throws InputError naming file, line and field on anything malformed: truncation, non-numeric or
// non-finite values, values outside scenario_limits, negative ranges, times going backwards, unknown line
// types, missing or repeated one-off lines.
Scenario read_scenario(const std::string& path);

// Writes with shortest round-trip number formatting, so read_scenario(write_scenario(s)) == s exactly.
// The file is written to a temporary name and renamed, so a crash never leaves a partial scenario. The text
// is read back with read_scenario before the rename: a writer never emits a file its reader rejects, and
// throws that InputError (naming path, the line of the text and the field) instead.
void write_scenario(const Scenario& scenario, const std::string& path);

}  // namespace arbor

#endif  // ARBOR_CORE_IO_SCENARIO_FORMAT_H_
