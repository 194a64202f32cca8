// The grid columns are listed once (experiments/sweep/grid_columns.inc); RunParams' fields, which the rows
// are made from, must follow that list.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/sweep/grid_columns.h"
#include "experiments/sweep/results_log.h"
#include "experiments/sweep/sweep_spec.h"

namespace arbor {
namespace {

TEST(GridColumns, ARowsParameterCellsAreTheListedColumnsInOrder) {
  RunParams run;
  run.world = "uniform";
  run.filter = "fastslam2";
  run.map = "tree";
  run.assoc = "jcbb";
  run.particles = 10;
  run.run_options = {{"chi2", "0.9"}};
  std::vector<std::string> cells;
  for (const auto& [name, value] : param_cells(run))
    if (name != "key" && name != "chi2" && name != "scenario" && name != "run_dir") cells.push_back(name);
  std::vector<std::string> listed;
  for (const GridColumn& c : kGridColumns) listed.emplace_back(c.name);
  EXPECT_EQ(cells, listed);
  const std::vector<std::string> columns = result_columns({}, {"chi2"});
  for (const std::string& name : listed) EXPECT_NE(std::find(columns.begin(), columns.end(), name), columns.end());
}

TEST(GridColumns, EveryColumnHasAKnownTypeAndRoles) {
  for (const GridColumn& c : kGridColumns) {
    EXPECT_TRUE(c.type == "text" || c.type == "integer" || c.type == "number") << c.name;
    for (std::string_view roles = c.roles; !roles.empty();) {
      const auto space = roles.find(' ');
      const std::string_view role = roles.substr(0, space);
      EXPECT_TRUE(role == "method" || role == "context" || role == "scenario") << c.name << ": " << role;
      roles = space == std::string_view::npos ? std::string_view() : roles.substr(space + 1);
    }
  }
}

}  // namespace
}  // namespace arbor
