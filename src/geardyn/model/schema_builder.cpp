#include "geardyn/model/schema_builder.hpp"

#include <cmath>

#include "geardyn/model/schema_sections.hpp"

namespace geardyn::model {

namespace keys {

std::string value_text(double x) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (std::isnan(x)) return fmt::format("{}", x);
  return fmt::format("{:.12g}", x);
}

std::vector<double> spaced(double a, double b, int n, bool log) {
  std::vector<double> out(static_cast<std::size_t>(n));
  // Weighted means (a (n-1-i) + b i) / (n-1) rather than a + t (b - a): the numerator is exact
  // for integer-valued ends, so a grid point that is a round number (3000 rpm on 0..45000 in
  // 16 points) comes out exactly; on a log scale the same in decades (10^7 between 1e6 and 1e8).
  const double la = log ? std::log10(a) : 0.0, lb = log ? std::log10(b) : 0.0;
  for (int i = 0; i < n; ++i) {
    const double wa = n == 1 ? 1.0 : static_cast<double>(n - 1 - i);
    const double wb = n == 1 ? 0.0 : static_cast<double>(i);
    const double den = n == 1 ? 1.0 : static_cast<double>(n - 1);
    out[static_cast<std::size_t>(i)] =
        log ? std::pow(10.0, (la * wa + lb * wb) / den) : (a * wa + b * wb) / den;
  }
  if (!out.empty()) {  // exact end points whatever the rounding
    out.front() = a;
    out.back() = b;
  }
  return out;
}

}  // namespace keys

std::vector<Field> join_fields(std::vector<std::vector<Field>> parts) {
  std::vector<Field> out;
  for (auto& part : parts)
    for (auto& f : part) out.push_back(std::move(f));
  return out;
}

}  // namespace geardyn::model
