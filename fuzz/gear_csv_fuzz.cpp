// libFuzzer target: arbitrary bytes -> the STE reader (parse_ste_csv, then at_torque), the
// measured-response reader (parse_measured_response_csv, then estimate_peak) and the TE rig
// reader (parse_te_rig_csv, then compare_te).
//
// Bad input must end in geardyn::InputError; any other exception, crash, leak or sanitizer
// report is a bug. The first byte chooses the reader options (tooth count, abscissa period,
// resampling, shift, interpolation) so that the option-dependent paths are explored too; the
// rest is the CSV text. Seeds: fuzz/corpus/gear_csv/.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/gear/correlation.hpp"
#include "geardyn/gear/ste.hpp"
#include "geardyn/gear/te_rig_csv.hpp"

namespace {

void run_ste(const std::string& text, std::uint8_t knobs) {
  geardyn::gear::SteReadOptions options;
  options.teeth = 1 + (knobs & 0x1f);
  options.mesh_period_s = 1e-3;
  options.base_radius_m = (knobs & 0x20) ? 0.05 : std::numeric_limits<double>::quiet_NaN();
  options.samples = (knobs & 0x40) ? 16 : 0;
  options.shift = (knobs & 0x80) ? 0.25 : 0.0;
  options.interpolation = (knobs & 0x01) ? geardyn::gear::SteInterpolation::Hold
                                         : geardyn::gear::SteInterpolation::Linear;
  const geardyn::gear::SteTable table = geardyn::gear::parse_ste_csv(text, "fuzz.csv", options);
  for (const double torque : {0.0, 150.0, 1e4}) {
    try {
      const geardyn::gear::SteCurve curve = table.at_torque(torque, (knobs & 0x02) != 0);
      (void)curve.mean_inverse_elastic_per_m();
      (void)curve.shifted(0.5);
    } catch (const geardyn::InputError&) {
    }
  }
}

void run_measured(const std::string& text) {
  const geardyn::gear::MeasuredResponse r =
      geardyn::gear::parse_measured_response_csv(text, "fuzz.csv");
  (void)geardyn::gear::estimate_peak(r.x, r.amplitude);
}

void run_te_rig(const std::string& text) {
  const geardyn::gear::TeRigFile rig = geardyn::gear::parse_te_rig_csv(text, "fuzz.csv");
  const std::vector<double> torques{50.0, 100.0, 400.0};
  const std::vector<std::vector<double>> harmonics(3, std::vector<double>{1e-6, 0.5e-6, 0.0});
  (void)geardyn::gear::compare_te(rig, torques, harmonics, 0.03);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t knobs = data[0];
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    run_ste(text, knobs);
  } catch (const geardyn::InputError&) {
  }
  try {
    run_measured(text);
  } catch (const geardyn::InputError&) {
  }
  try {
    run_te_rig(text);
  } catch (const geardyn::InputError&) {
  }
  return 0;
}
