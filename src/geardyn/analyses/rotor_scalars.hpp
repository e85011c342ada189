#pragma once
// Scalar outputs of the rotor analyses read from their typed results (modal, campbell,
// harmonic, unbalance, transient): the n-th entry of a list of modes, and the peak, its
// location and the amplitude at a point of a sensor's response curve.
#include <fmt/format.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "geardyn/analyses/registry.hpp"

namespace geardyn::analyses {

/// Entry `mode` (1-based) of `items`; std::runtime_error ("mode 4 requested, 3 found") beyond
/// the end.
template <class T>
const T& nth_mode(const std::vector<T>& items, int mode) {
  if (mode < 1 || static_cast<std::size_t>(mode) > items.size())
    throw std::runtime_error(fmt::format("mode {} requested, {} found", mode, items.size()));
  return items[static_cast<std::size_t>(mode - 1)];
}

/// A sensor's amplitude over a speed or frequency axis, as its result table lists it: rows in
/// table order, split into groups (one per excitation order) along each of which x increases.
struct ResponseCurve {
  std::vector<double> x;                         ///< abscissa in the table's unit (Hz or rpm)
  std::vector<double> amplitude;                 ///< in amplitude_unit
  std::vector<std::vector<std::size_t>> groups;  ///< rows of each order (one group: all rows)
  std::string x_unit;                            ///< "Hz" or "rpm"
  std::string amplitude_unit;
  double per_rad_s = 1.0;  ///< factor from rad/s (a request's `at`) to x's unit
};

/// "peak_amplitude" (largest amplitude over all rows, the first of equal ones; NaN for no rows),
/// "peak_location" (its x) or "amplitude_at" (linear interpolation in x along each group at
/// `at` x per_rad_s, the largest over groups; std::runtime_error outside the range). Sets `unit`.
double response_scalar(const ResponseCurve& curve, const ScalarRequest& request, std::string& unit);

/// std::runtime_error naming an unknown scalar.
[[noreturn]] void unknown_scalar(const std::string& type, const std::string& quantity);

}  // namespace geardyn::analyses
