// The filter's arithmetic failed on input within the documented limits: a NaN particle weight, or an
// innovation or landmark covariance that lost positive definiteness. It happens when a scenario's motion noise
// or controls are so large (at the limits of docs/scenario_format.md) that squaring them swamps the
// measurement noise in double precision. The engine throws this instead of aborting, and the run turns it
// into an InputError naming the scenario and the step, since the scenario's figures are the cause. It is
// thrown only where the run would otherwise abort, so valid runs are untouched.
#ifndef ARBOR_CORE_ENGINE_NUMERICAL_BREAKDOWN_H_
#define ARBOR_CORE_ENGINE_NUMERICAL_BREAKDOWN_H_

#include <stdexcept>
#include <string>

namespace arbor {

class NumericalBreakdown : public std::runtime_error {
 public:
  explicit NumericalBreakdown(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_NUMERICAL_BREAKDOWN_H_
