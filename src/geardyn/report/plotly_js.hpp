#pragma once
// plotly.js, embedded in the library at build time (see CMakeLists.txt: assembler .incbin of the
// pinned node_modules/plotly.js-dist-min/plotly.min.js).
#include <string_view>

namespace geardyn::report {

/// The complete text of plotly.min.js.
std::string_view plotly_js();

/// Its version, from the npm package ("2.35.2").
const char* plotly_version();

}  // namespace geardyn::report
