// libFuzzer target: arbitrary bytes -> meshio::parse_nastran (INCLUDE disabled) -> optionally
// solid::assemble on small results.
//
// Bad input must end in geardyn::InputError (or, from assembly, a NumericalError, the documented
// way to report e.g. a singular rigid-element configuration). Any other exception, crash, leak,
// hang or sanitizer report is a bug. Every second input is also read with
// unsupported_is_error and a selected SPC set, to reach those paths.
#include <cstddef>
#include <cstdint>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/meshio/nastran_reader.hpp"
#if GEARDYN_FUZZ_ASSEMBLE_SOLID
#include "geardyn/solid/assembly.hpp"
#endif

namespace {

#if GEARDYN_FUZZ_ASSEMBLE_SOLID
// Past this size assembly says nothing new about the reader and only slows the fuzzer down.
constexpr int kMaxAssembledNodes = 200;
#endif

void run(const std::string& text, bool strict) {
  geardyn::meshio::NastranOptions options;
  options.allow_include = false;  // no file system access from fuzz input
  options.unsupported_is_error = strict;
  options.spc_set = strict ? 1 : 0;
  const geardyn::meshio::NastranDeck deck =
      geardyn::meshio::parse_nastran(text, "fuzz.bdf", options);
#if GEARDYN_FUZZ_ASSEMBLE_SOLID
  if (deck.mesh.num_nodes() <= kMaxAssembledNodes) (void)geardyn::solid::assemble(deck.mesh);
#else
  (void)deck;
#endif
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    run(text, size % 2 == 1);
  } catch (const geardyn::InputError&) {
  } catch (const geardyn::NumericalError&) {
  }
  return 0;
}
