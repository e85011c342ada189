// libFuzzer target: arbitrary bytes -> parse_document -> build_model -> fe::assemble.
//
// Bad input must end in geardyn::InputError (or, from assembly, a NumericalError such as modal
// damping requested on a singular system, which is the documented way to report that). Any
// other exception, crash, leak or sanitizer report is a bug.
//
// Lines of the form `#--set key.path=value` are TOML comments; the harness applies them with
// apply_override before build_model, so the fuzzer also explores overrides.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/model/parse.hpp"
#include "geardyn/model/schema.hpp"
#if GEARDYN_FUZZ_ASSEMBLE
#include "geardyn/fe/linear_system.hpp"
#endif

namespace {

// Assembly cost grows with the model; past this many nodes a case says nothing new about
// correctness and only slows the fuzzer down.
constexpr std::size_t kMaxNodes = 400;

std::size_t count_nodes(const geardyn::model::Model& model) {
  std::size_t n = model.nodes.size();
  for (const auto& shaft : model.shafts) {
    n += 1;
    for (const auto& e : shaft.elements) n += static_cast<std::size_t>(e.divisions);
  }
  return n;
}

void run(const std::string& text) {
  // The model's own sections; the analysis types' keys live in the analyses module, which this
  // light target does not link (their checks are covered by tests/model and tests/analyses).
  static const geardyn::model::Section schema = geardyn::model::make_model_schema({});
  geardyn::model::ModelDocument doc = geardyn::model::parse_document(text, "fuzz.toml", schema);
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line))
    if (line.rfind("#--set ", 0) == 0) geardyn::model::apply_override(doc, line.substr(7));
  const geardyn::model::Model model = geardyn::model::build_model(doc);
  if (count_nodes(model) > kMaxNodes) return;
#if GEARDYN_FUZZ_ASSEMBLE
  (void)geardyn::fe::assemble(model);
#endif
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    run(text);
  } catch (const geardyn::InputError&) {
  } catch (const geardyn::NumericalError&) {
  }
  return 0;
}
