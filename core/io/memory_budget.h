// What a job may still allocate on this machine, checked before a large run or simulation starts: asked for
// ten times the memory there is, `arbor run --particles 1000000` grew to 2 GB and ended in std::bad_alloc,
// naming no option (issue 45). The checks use measured floors (what a job needs at the least), so they refuse
// only what cannot fit.
#ifndef ARBOR_CORE_IO_MEMORY_BUDGET_H_
#define ARBOR_CORE_IO_MEMORY_BUDGET_H_

#include <cstdint>
#include <optional>
#include <string>

namespace arbor {

// MemAvailable of /proc/meminfo in bytes; nullopt where it cannot be read (the checks then pass).
std::optional<std::int64_t> available_memory_bytes();

// Throws InputError(field) when count items of at least bytes_each bytes ("particles", measured) exceed the
// available memory, with both figures in the message.
void require_memory(double count, double bytes_each, const std::string& field, const std::string& items);

}  // namespace arbor

#endif  // ARBOR_CORE_IO_MEMORY_BUDGET_H_
