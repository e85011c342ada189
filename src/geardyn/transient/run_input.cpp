#include "geardyn/transient/run_input.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace geardyn::transient::detail {

void check_run_input(const SecondOrderSystem& system, const std::vector<std::string>& problems,
                     const std::string& what, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  if (!problems.empty()) {
    std::string text = what + ":";
    for (const auto& p : problems) text += " " + p + ";";
    throw std::invalid_argument(text);
  }
  const int n = system.size();
  if (n < 1) throw std::invalid_argument("the system has no unknowns");
  if (q.size() != n || v.size() != n)
    throw std::invalid_argument(fmt::format(
        "initial q and v have sizes {} and {}, the system has {} unknowns", q.size(), v.size(), n));
}

}  // namespace geardyn::transient::detail
