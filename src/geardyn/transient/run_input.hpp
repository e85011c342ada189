#pragma once
// The input checks every integrator of a SecondOrderSystem makes before it starts (internal to
// the transient module).
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/transient/second_order_system.hpp"

namespace geardyn::transient::detail {

/// Throws std::invalid_argument listing `problems` (the options' validate(), introduced by
/// `what`), for a system without unknowns, or for initial q, v whose sizes are not the system's.
void check_run_input(const SecondOrderSystem& system, const std::vector<std::string>& problems,
                     const std::string& what, const Eigen::VectorXd& q, const Eigen::VectorXd& v);

}  // namespace geardyn::transient::detail
