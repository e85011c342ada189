#include "geardyn/report/plotly_js.hpp"

#include <cstdint>

#include "geardyn/report/plotly_version.hpp"

// Defined in the generated plotly_embed.S.
extern "C" {
extern const char geardyn_plotly_js[];
extern const std::uint64_t geardyn_plotly_js_size;
}

namespace geardyn::report {

std::string_view plotly_js() {
  return std::string_view(geardyn_plotly_js, static_cast<std::size_t>(geardyn_plotly_js_size));
}

const char* plotly_version() { return kPlotlyVersion; }

}  // namespace geardyn::report
