#include "geardyn/model/schema_builder.hpp"

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
  for (int i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : static_cast<double>(i) / (n - 1);
    out[static_cast<std::size_t>(i)] =
        log ? std::exp(std::log(a) + t * (std::log(b) - std::log(a))) : a + t * (b - a);
  }
  if (!out.empty()) out.back() = b;  // exact end point whatever the rounding
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
