// Parameter sweeps: values against closed forms, and threads give the same answer as serial.
#include "geardyn/analyses/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/core/text.hpp"
#include "geardyn/linalg/blas_library.hpp"
#include "geardyn/model/parse.hpp"

namespace geardyn::analyses {
namespace {

// A point mass m on a lateral spring k (a free node; all other DOFs fixed):
//
//        k
//   |--/\/\/--[ m ]        omega_n = sqrt(k / m)
//
// The sweep varies k (bearing kxx, with kyy linked) and reads the first natural frequency and
// the unbalance-free FRF peak. Closed form: f_n = sqrt(k/m) / (2 pi).
const char* kModel = R"(
version = 1
[[materials]]
name = "steel"
youngs_modulus = 2e11
poisson_ratio = 0.3
density = 7800
[[shafts]]
name = "s"
material = "steel"
  [[shafts.elements]]
  length = 0.1
  outer_diameter = 0.01
[[constraints]]
node = "s.0"
dofs = "all"
[[constraints]]
node = "s.1"
dofs = "all"
[[nodes]]
name = "m"
position = [1, 0, 0]
[[point_masses]]
node = "m"
mass = 10
[[bearings]]
node = "m"
kxx = 1e6
kyy = 1e6
kzz = 1e6
[[constraints]]
node = "m"
dofs = ["rx", "ry", "rz"]
[[sensors]]
name = "x"
node = "m"
dof = "ux"
[[analyses]]
name = "modes"
type = "modal"
n_modes = 3
[[analyses]]
name = "k_sweep"
type = "sweep"
parameter = "bearings[0].kxx"
linked_parameters = ["bearings[0].kyy", "bearings[0].kzz"]
values = [1e4, 1e5, 1e6, 1e7, 1e8]
analysis = "modes"
outputs = [{ quantity = "natural_frequency", mode = 1 }]
)";

TEST(Sweep, NaturalFrequencyFollowsTheClosedForm) {
  const auto doc = analyses::parse_document(kModel, "sweep_test.toml");
  const model::Model m = model::build_model(doc);
  const auto& settings = m.analyses[1].settings_of<analyses::SweepSettings>();
  const SweepResult r = run_sweep(doc, settings, null_progress());
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.outputs.size(), 1u);
  for (std::size_t i = 0; i < r.values.size(); ++i) {
    const double exact = std::sqrt(r.values[i] / 10.0) / (2.0 * std::numbers::pi);
    // Three equal frequencies (x, y, z springs); the eigen-solve is accurate to round-off,
    // so 1e-9 relative leaves room for the conditioning of the stiffest case only.
    EXPECT_NEAR(r.outputs[0][i], exact, 1e-9 * exact) << "k = " << r.values[i];
  }
  EXPECT_EQ(r.units[0], "Hz");
  // The table says what was swept in which unit.
  EXPECT_EQ(r.parameter_unit, "N/m");
  const AnalysisOutput out = sweep_output(r, settings, "k_sweep");
  EXPECT_EQ(out.tables[0].columns[0].name, "value_N_m");
  EXPECT_EQ(out.tables[0].columns[1].name, "natural_frequency_1_Hz");
  EXPECT_EQ(out.plots[0].x_label, "bearings[0].kxx [N/m]");
}

TEST(Sweep, ThreadsGiveTheSerialResultBitForBit) {
  const auto doc = analyses::parse_document(kModel, "sweep_test.toml");
  const model::Model m = model::build_model(doc);
  auto settings = m.analyses[1].settings_of<analyses::SweepSettings>();
  settings.threads = 1;
  const SweepResult serial = run_sweep(doc, settings, null_progress());
  settings.threads = 4;
  const SweepResult parallel = run_sweep(doc, settings, null_progress());
  ASSERT_EQ(serial.outputs.size(), parallel.outputs.size());
  for (std::size_t j = 0; j < serial.outputs.size(); ++j)
    for (std::size_t i = 0; i < serial.values.size(); ++i)
      EXPECT_EQ(serial.outputs[j][i], parallel.outputs[j][i]);  // exact: same work per point
  EXPECT_EQ(parallel.threads_used, 4);
}

// A sweep whose points factorise (the receptance FRF of the demo's geared rotor: a complex
// UMFPACK LU at every frequency, calling the system BLAS), run on two threads again and again:
// every run must equal the serial one bit for bit. With Debian's sequential OpenBLAS the points
// used to corrupt each other at random (5 to 12 of 12 points "not converged"); such a BLAS now
// gets one thread and a note saying why, a thread-safe one runs both threads.
TEST(Sweep, AFactorisingSweepOnThreadsRepeatsTheSerialResultBitForBit) {
  const std::string path =
      std::string(GEARDYN_SOURCE_DIR) + "/examples/geared_rotor_hcf/model.toml";
  const std::string text = read_file(path) + R"(
[[analyses]]
name = "frf_sweep"
type = "sweep"
parameter = "bearings[0].kxx"
values = [1e6, 3e6, 1e7, 3e7, 1e8, 3e8]
analysis = "frf_driving_gear"
outputs = [{ quantity = "peak_location", sensor = "swing" },
           { quantity = "peak_amplitude", sensor = "swing" }]
)";
  const auto doc = analyses::parse_document(text, path);
  const model::Model m = model::build_model(doc);
  auto settings = m.analyses.back().settings_of<analyses::SweepSettings>();
  settings.threads = 1;
  const SweepResult serial = run_sweep(doc, settings, null_progress());
  ASSERT_EQ(serial.status, Status::Ok) << serial.message;
  const bool safe = linalg::safe_for_concurrent_calls(linalg::loaded_blas());
  settings.threads = 2;
  for (int run = 0; run < 4; ++run) {
    const SweepResult parallel = run_sweep(doc, settings, null_progress());
    ASSERT_EQ(parallel.status, Status::Ok) << "run " << run << ": " << parallel.message;
    EXPECT_EQ(parallel.threads_used, safe ? 2 : 1);
    EXPECT_EQ(parallel.thread_note.empty(), safe) << parallel.thread_note;
    for (std::size_t j = 0; j < serial.outputs.size(); ++j)
      for (std::size_t i = 0; i < serial.values.size(); ++i)
        ASSERT_EQ(serial.outputs[j][i], parallel.outputs[j][i])
            << "run " << run << ", output " << j << ", point " << i;
  }
}

// A point whose system is unstable keeps its numbers (here the FRF peak) and is marked, and
// the sweep says so: a
// mass on a damped isotropic support with cross-coupled stiffness q (kxy = -kyx = q) has
// damping ratio ~ (c w_n - q) / (2 k) on its forward mode, so it is unstable exactly when
// q > c w_n (Friswell et al., "Dynamics of Rotating Machines", 2010, sec. 3.8); here
// c w_n = 100 x sqrt(1e6 / 10) = 31 623 N/m and q = 1e5 N/m. The sweep sets kyx = +1e5 (a
// symmetric, conservative coupling: stable) and -1e5 (the skew coupling: unstable).
TEST(Sweep, AnUnstablePointKeepsItsValueAndIsMarked) {
  std::string text = kModel;
  text.replace(text.find("kzz = 1e6\n"), 10,
               "kzz = 1e6\ncxx = 100\ncyy = 100\nkxy = 1e5\nkyx = 0\n");
  text += R"(
[[analyses]]
name = "frf"
type = "harmonic"
enabled = false
frequency_start_hz = 10
frequency_stop_hz = 100
frequency_count = 50
input_node = "m"
input_dof = "ux"
[[analyses]]
name = "q_sweep"
type = "sweep"
parameter = "bearings[0].kyx"
values = [1e5, -1e5]
analysis = "frf"
outputs = [{ quantity = "peak_amplitude", sensor = "x" }]
)";
  const auto doc = analyses::parse_document(text, "unstable_sweep.toml");
  const model::Model m = model::build_model(doc);
  auto settings = m.analyses.back().settings_of<analyses::SweepSettings>();
  settings.linked_parameters = {};
  const SweepResult r = run_sweep(doc, settings, null_progress());
  EXPECT_EQ(r.point_status[0], Status::Ok) << r.point_message[0];
  EXPECT_EQ(r.point_status[1], Status::Unstable) << r.point_message[1];
  EXPECT_TRUE(std::isfinite(r.outputs[0][0]));
  EXPECT_TRUE(std::isfinite(r.outputs[0][1]));
  EXPECT_EQ(r.status, Status::Unstable);
  EXPECT_NE(r.message.find("1 of 2 points unstable"), std::string::npos) << r.message;
}

TEST(Sweep, APointThatFailsIsReportedNotDropped) {
  // k = 0 leaves the mass free: its "natural frequency" is a rigid-body 0 Hz, which is a valid
  // result; an out-of-range value (negative stiffness) is bad input and aborts the sweep.
  const auto doc = analyses::parse_document(kModel, "sweep_test.toml");
  const model::Model m = model::build_model(doc);
  auto settings = m.analyses[1].settings_of<analyses::SweepSettings>();
  settings.values = {1e6, -1.0};
  EXPECT_THROW(run_sweep(doc, settings, null_progress()), InputError);
}

// A sweep of an analysis without a rotor (a gear pair alone: no shafts, no nodes) over an
// integer key. The total contact ratio of a standard spur pair (no profile shift, addendum m)
// has the closed form eps_alpha = (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a sin alpha) /
// (pi m cos alpha), ra = m (z / 2 + 1), rb = m z cos(alpha) / 2, a = m (z1 + z2) / 2 (ISO 21771;
// any gear text). The geometry is evaluated in closed form too, so 1e-12 relative allows only
// round-off.
TEST(Sweep, AGearPairWithoutARotorIsSweptOverItsTeeth) {
  const char* model = R"(version = 1
[[gear_pairs]]
name = "spur"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = 100
[[analyses]]
name = "pair"
type = "gear_pair"
[[analyses]]
name = "teeth_sweep"
type = "sweep"
parameter = "gear_pairs[0].teeth1"
values = [17, 20, 25, 31]
analysis = "pair"
outputs = [{ quantity = "contact_ratio" }]
)";
  const auto doc = analyses::parse_document(model, "gear_sweep.toml");
  const model::Model m = model::build_model(doc);
  const auto& settings = m.analyses[1].settings_of<analyses::SweepSettings>();
  ASSERT_EQ(settings.outputs.size(), 1u);
  EXPECT_EQ(settings.outputs[0].label, "contact_ratio_1");  // the pair's number (mode = 1)
  const SweepResult r = run_sweep(doc, settings, null_progress());
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const double mod = 0.003, z2 = 40.0, alpha = 20.0 * std::numbers::pi / 180.0;
  for (std::size_t i = 0; i < r.values.size(); ++i) {
    ASSERT_EQ(r.point_status[i], Status::Ok) << r.point_message[i];
    const double z1 = r.values[i];
    auto leg = [&](double z) {
      const double ra = mod * (z / 2.0 + 1.0), rb = mod * z * std::cos(alpha) / 2.0;
      return std::sqrt(ra * ra - rb * rb);
    };
    const double a = mod * (z1 + z2) / 2.0;
    const double exact =
        (leg(z1) + leg(z2) - a * std::sin(alpha)) / (std::numbers::pi * mod * std::cos(alpha));
    EXPECT_NEAR(r.outputs[0][i], exact, 1e-12 * exact) << "z1 = " << z1;
  }
  EXPECT_LT(r.outputs[0][0], r.outputs[0][3]);  // more teeth, longer path of contact
}

}  // namespace
}  // namespace geardyn::analyses
