#include "geardyn/reduce/frequency_comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::reduce {

double frequency_hz(double lambda) { return std::sqrt(std::max(lambda, 0.0)) / units::kTwoPi; }

double frequency_error_pct(double full_hz, double reduced_hz, double floor_hz) {
  return 100.0 * (reduced_hz - full_hz) / std::max(full_hz, floor_hz);
}

Table compare_frequencies(const Eigen::VectorXd& full_eigenvalues,
                          const Eigen::VectorXd& reduced_eigenvalues, double floor_hz) {
  if (!(floor_hz > 0.0))
    throw InputError({}, "reduce.compare_frequencies.floor_hz", "> 0", fmt::format("{}", floor_hz));
  const Eigen::Index rows = std::min(full_eigenvalues.size(), reduced_eigenvalues.size());
  std::vector<double> mode, full, reduced, error;
  for (Eigen::Index k = 0; k < rows; ++k) {
    mode.push_back(static_cast<double>(k + 1));
    full.push_back(frequency_hz(full_eigenvalues[k]));
    reduced.push_back(frequency_hz(reduced_eigenvalues[k]));
    error.push_back(frequency_error_pct(full.back(), reduced.back(), floor_hz));
  }
  Table t;
  t.name = "reduction_frequencies";
  t.title = "Natural frequencies: full model versus reduced component";
  t.add("mode", "", std::move(mode));
  t.add("full_hz", "Hz", std::move(full));
  t.add("reduced_hz", "Hz", std::move(reduced));
  t.add("error_pct", "%", std::move(error));
  return t;
}

Table convergence_table(const ReducedComponent& rc, const Eigen::VectorXd& full_eigenvalues,
                        const std::vector<int>& n_modes_list, int n_compare,
                        const std::vector<int>& fixed_masters, double floor_hz) {
  if (n_compare < 1 || n_compare > full_eigenvalues.size())
    throw InputError({}, "reduce.convergence_table.n_compare",
                     fmt::format("1 .. {} (the full eigenvalues given)", full_eigenvalues.size()),
                     std::to_string(n_compare));
  std::vector<double> counts, sizes, max_error, worst;
  for (std::size_t k = 0; k < n_modes_list.size(); ++k) {
    const int nm = n_modes_list[k];
    if (nm < 0 || nm > rc.n_modal)
      throw InputError({}, fmt::format("reduce.convergence_table.n_modes_list[{}]", k),
                       fmt::format("0 .. {} (the modes of the component)", rc.n_modal),
                       std::to_string(nm));
    const Eigen::VectorXd lambda = reduced_eigenvalues(truncate(rc, nm), fixed_masters);
    if (lambda.size() < n_compare)
      throw InputError({}, fmt::format("reduce.convergence_table.n_modes_list[{}]", k),
                       fmt::format("a reduced model with at least {} modes", n_compare),
                       fmt::format("{} modes with {} fixed-interface modes", lambda.size(), nm));
    double worst_error = 0.0;
    int worst_mode = 1;
    for (int j = 0; j < n_compare; ++j) {
      const double e = std::abs(frequency_error_pct(frequency_hz(full_eigenvalues[j]),
                                                    frequency_hz(lambda[j]), floor_hz));
      if (e > worst_error) {
        worst_error = e;
        worst_mode = j + 1;
      }
    }
    counts.push_back(nm);
    sizes.push_back(static_cast<double>(lambda.size()));
    max_error.push_back(worst_error);
    worst.push_back(worst_mode);
  }
  Table t;
  t.name = "reduction_convergence";
  t.title =
      fmt::format("Craig-Bampton convergence: largest error of the first {} modes", n_compare);
  t.add("n_modes", "", std::move(counts));
  t.add("reduced_size", "", std::move(sizes));
  t.add("max_error_pct", "%", std::move(max_error));
  t.add("worst_mode", "", std::move(worst));
  return t;
}

}  // namespace geardyn::reduce
