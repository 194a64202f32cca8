// Reading MemAvailable and refusing what cannot fit; see memory_budget.h.
#include "core/io/memory_budget.h"

#include <fstream>
#include <sstream>
#include <string>

#include <fmt/core.h>

#include "core/io/input_error.h"

namespace arbor {

std::optional<std::int64_t> available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string name;
    std::int64_t kib = 0;
    if (fields >> name >> kib && name == "MemAvailable:") return kib * 1024;
  }
  return std::nullopt;
}

void require_memory(double count, double bytes_each, const std::string& field, const std::string& items) {
  const auto available = available_memory_bytes();
  const double needed = count * bytes_each;
  if (!available || needed <= static_cast<double>(*available)) return;
  throw InputError("", 0, field,
                   fmt::format("{:.0f} {} need at least {:.1f} GB ({:.0f} bytes each, measured), but {:.1f} GB is "
                               "available",
                               count, items, needed / 1e9, bytes_each, static_cast<double>(*available) / 1e9));
}

}  // namespace arbor
