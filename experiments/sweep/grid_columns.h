// The sweep's grid columns (the parameters of a run, before its options and metrics), listed once in
// grid_columns.inc, which the analysis reads as it is.
#ifndef ARBOR_EXPERIMENTS_SWEEP_GRID_COLUMNS_H_
#define ARBOR_EXPERIMENTS_SWEEP_GRID_COLUMNS_H_

#include <string_view>

namespace arbor {

struct GridColumn {
  std::string_view name;
  std::string_view type;   // text | integer | number
  std::string_view roles;  // space-separated: method, context, scenario
};

inline constexpr GridColumn kGridColumns[] = {
#include "experiments/sweep/grid_columns.inc"
};

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SWEEP_GRID_COLUMNS_H_
