// Massless shafts (density = 0) through the model file and the geardyn program: the Jeffcott
// (Laval) rotor and a torsional two-disk system, against their closed forms.
//
// Jeffcott rotor: a massless, simply supported Euler-Bernoulli shaft of length L with a rigid
// disk (mass m, polar inertia Ip, diametral inertia Id) at mid-span and a viscous damper c on
// the disk. The mid-span stiffness is k = 48 E I / L^3, so
//   omega_n = sqrt(k / m);
// the disk's tilt at mid-span is uncoupled from its translation (symmetry) with the stiffness
// k_t = 12 E I / L, and its gyroscopic moment splits it at spin W into
//   omega_{f,b} = ( +- (Ip / Id) W + sqrt((Ip W / Id)^2 + 4 k_t / Id) ) / 2;
// the unbalance m e turning with the shaft gives the circular forward orbit of radius
//   |x| = m e W^2 / |k - m W^2 + i c W|.
// Sources: H. H. Jeffcott, "The lateral vibration of loaded shafts in the neighbourhood of a
// whirling speed", Phil. Mag. 37 (1919) 304-314; M. I. Friswell, J. E. T. Penny, S. D. Garvey,
// A. W. Lees, "Dynamics of Rotating Machines", Cambridge University Press 2010, sec. 3.4-3.6
// (Jeffcott rotor, gyroscopic disk) and sec. 5.4 (beam stiffness). The beam element's shape
// functions are exact for a massless Euler-Bernoulli beam under end loads, so the FE stiffness at
// mid-span is 48 E I / L^3 to rounding: the tolerances below are round-off sized.
//
// Torsional two-disk system: disks J1, J2 at the ends of a massless shaft of torsional stiffness
// k_t = G J_p / L (J_p = pi d^4 / 32): one rigid-body mode and
//   omega = sqrt(k_t (J1 + J2) / (J1 J2))
// (W. T. Thomson, M. D. Dahleh, "Theory of Vibration with Applications", 5th ed., 1998, sec.
// 5.4, the two-rotor torsional system). The linear twist of the element is exact too.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <fstream>
#include <numbers>
#include <string>

#include "cli/cli_support.hpp"

namespace {

using namespace geardyn::cli_test;

constexpr double kPi = std::numbers::pi;
constexpr double kE = 2.0e11, kG = 8.0e10, kLength = 0.6, kDiameter = 0.02;
constexpr double kMass = 10.0, kIp = 0.05, kId = 0.025, kDamping = 300.0, kMe = 1e-4;

double second_moment() { return kPi * std::pow(kDiameter, 4) / 64.0; }
double lateral_stiffness() { return 48.0 * kE * second_moment() / std::pow(kLength, 3); }
double omega_n() { return std::sqrt(lateral_stiffness() / kMass); }
double tilt_stiffness() { return 12.0 * kE * second_moment() / kLength; }
double tilt_frequency(double spin, double sign) {
  const double g = kIp * spin / kId;
  return 0.5 * (sign * g + std::sqrt(g * g + 4.0 * tilt_stiffness() / kId));
}
double unbalance_radius(double spin) {
  const std::complex<double> d(lateral_stiffness() - kMass * spin * spin, kDamping * spin);
  return kMe * spin * spin / std::abs(d);
}

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

std::string jeffcott_model(const std::string& dofs) {
  return R"(version = 1
title = "Jeffcott rotor on a massless shaft"
dofs = ")" +
         dofs + R"("

[[materials]]
name = "massless_steel"
youngs_modulus = 2.0e11
shear_modulus = 8.0e10
density = 0

[[shafts]]
name = "s"
material = "massless_steel"
theory = "euler_bernoulli"
  [[shafts.elements]]
  length = 0.6
  outer_diameter = 0.02
  divisions = 4

[[disks]]
name = "disk"
node = "s.2"
mass = 10.0
polar_inertia = 0.05
diametral_inertia = 0.025

[[bearings]]
name = "damper"
node = "s.2"
cxx = 300.0
cyy = 300.0

[[constraints]]
node = "s.0"
dofs = ["ux", "uy"]

[[constraints]]
node = "s.4"
dofs = ["ux", "uy"]

[[sensors]]
name = "disk_x"
node = "s.2"
dof = "ux"

[[sensors]]
name = "disk_y"
node = "s.2"
dof = "uy"
)";
}

const std::string kJeffcottAnalyses = R"(
[[unbalances]]
name = "u"
node = "s.2"
mass_eccentricity = 1e-4

[[analyses]]
name = "modes"
type = "modal"
n_modes = 4

[[analyses]]
name = "campbell"
type = "campbell"
speed_start_rpm = 0
speed_stop_rpm = 6000
speed_count = 7
n_modes = 4

[[analyses]]
name = "unbalance"
type = "unbalance"
speed_start_rpm = 500
speed_stop_rpm = 3000
speed_count = 6

[[analyses]]
name = "transient"
type = "transient"
speed_rpm = 1000
duration = 1.5
time_step = 2e-4
output_every = 5
)";

fs::path run_model(const std::string& name, const std::string& text) {
  const fs::path dir = fresh_dir(name);
  write(dir / "model.toml", text);
  const ProcessResult r =
      run("run -q " + (dir / "model.toml").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  return dir / "out";
}

std::vector<double> numbers(const std::vector<std::string>& cells) {
  std::vector<double> v;
  for (const auto& c : cells) v.push_back(std::stod(c));
  return v;
}

TEST(MasslessShaft, JeffcottModalCampbellUnbalanceAndTransient) {
  // Lateral DOFs only (`dofs = "lateral"`): no axial or torsional rigid-body modes; the mass is
  // the disk's, every other node of the shaft is massless.
  const fs::path out =
      run_model("massless_jeffcott", jeffcott_model("lateral") + kJeffcottAnalyses);
  const double wn = omega_n();  // 186.83 rad/s, 29.74 Hz

  // Modal: the two lateral modes at omega_n and the tilt pair at sqrt(k_t / Id). Round-off of a
  // dense eigen-solve of a 4-DOF condensed system: 1e-9 relative leaves a wide margin.
  auto modes = read_csv(out / "modes" / "undamped_modes.csv");
  const std::vector<double> f = numbers(modes["frequency_hz"]);
  ASSERT_EQ(f.size(), 4u);
  EXPECT_NEAR(f[0] * kTwoPi, wn, 1e-9 * wn);
  EXPECT_NEAR(f[1] * kTwoPi, wn, 1e-9 * wn);
  const double wt = tilt_frequency(0.0, 1.0);
  EXPECT_NEAR(f[2] * kTwoPi, wt, 1e-9 * wt);
  EXPECT_NEAR(f[3] * kTwoPi, wt, 1e-9 * wt);

  // Campbell: the translation does not feel the spin; the tilt splits into a forward and a
  // backward whirl by the closed form (same round-off argument, 1e-8 for the damped solve).
  auto c = read_csv(out / "campbell" / "campbell.csv");
  int checked = 0;
  for (std::size_t i = 0; i < c["speed_rpm"].size(); ++i) {
    const double spin = std::stod(c["speed_rpm"][i]) * kTwoPi / 60.0;
    const double w = std::stod(c["frequency_hz"][i]) * kTwoPi;
    if (w < 2.0 * wn) {
      EXPECT_NEAR(w, wn, 1e-8 * wn) << "lateral mode at " << spin << " rad/s";
      continue;
    }
    if (spin == 0.0) continue;
    const std::string whirl = c["whirl"][i];
    ASSERT_TRUE(whirl == "forward" || whirl == "backward") << whirl;
    const double ref = tilt_frequency(spin, whirl == "forward" ? 1.0 : -1.0);
    EXPECT_NEAR(w, ref, 1e-8 * ref) << whirl << " tilt at " << spin << " rad/s";
    ++checked;
  }
  EXPECT_EQ(checked, 12);  // 6 speeds above 0 x (forward, backward)

  // Unbalance: the closed-form Jeffcott orbit. A direct solve of the condensed 4-DOF system:
  // round-off only, 1e-9.
  auto u = read_csv(out / "unbalance" / "response.csv");
  ASSERT_EQ(u["speed_rpm"].size(), 6u);
  for (std::size_t i = 0; i < u["speed_rpm"].size(); ++i) {
    const double spin = std::stod(u["speed_rpm"][i]) * kTwoPi / 60.0;
    const double ref = unbalance_radius(spin);
    EXPECT_NEAR(std::stod(u["disk_x_amplitude_m"][i]), ref, 1e-9 * ref) << spin;
    EXPECT_NEAR(std::stod(u["disk_y_amplitude_m"][i]), ref, 1e-9 * ref) << spin;
    EXPECT_EQ(u["stable"][i], "yes");
  }

  // Transient at 1000 rpm from rest: it starts (the initial acceleration with the massless
  // nodes condensed) and reaches the unbalance steady state. Tolerance 5e-4: the free vibration
  // decays as exp(-zeta w_n t) with zeta w_n = c / (2 m) = 15 1/s, i.e. below 1e-4 after the
  // steady part's start at 0.75 s; the generalised-alpha scheme's amplitude error at
  // W h = 0.021 rad per step is of order (W h)^2 / 12 ~ 4e-5.
  auto orbit = read_csv(out / "transient" / "orbits.csv");
  ASSERT_EQ(orbit["major_m"].size(), 1u);
  const double ref = unbalance_radius(1000.0 * kTwoPi / 60.0);
  EXPECT_NEAR(std::stod(orbit["major_m"][0]), ref, 5e-4 * ref);
  EXPECT_NEAR(std::stod(orbit["minor_m"][0]), ref, 5e-4 * ref);
  EXPECT_EQ(orbit["whirl"][0], "forward");
}

TEST(MasslessShaft, AllDofsGiveTheSameLateralModesAsTheLateralSet) {
  // With every DOF, the massless shaft's torsion and axial motion carry the disk's Ip and m
  // (axial and torsional modes appear) and the s.4 end is free in torsion and axially: held at
  // s.0. At zero speed lateral, axial and torsional motion are uncoupled, so the lateral
  // frequencies are those of the lateral-only model (round-off, 1e-9).
  std::string all = jeffcott_model("all") + R"(
[[constraints]]
node = "s.0"
dofs = ["uz", "rz"]

[[analyses]]
name = "modes"
type = "modal"
n_modes = 6
)";
  const fs::path out = run_model("massless_jeffcott_all", all);
  auto modes = read_csv(out / "modes" / "undamped_modes.csv");
  std::vector<double> lateral;
  double torsional = 0.0, axial = 0.0;
  for (std::size_t i = 0; i < modes["kind"].size(); ++i) {
    const double w = std::stod(modes["frequency_hz"][i]) * kTwoPi;
    if (modes["kind"][i] == "lateral") lateral.push_back(w);
    if (modes["kind"][i] == "torsional") torsional = w;
    if (modes["kind"][i] == "axial") axial = w;
  }
  ASSERT_EQ(lateral.size(), 4u);
  EXPECT_NEAR(lateral[0], omega_n(), 1e-9 * omega_n());
  EXPECT_NEAR(lateral[1], omega_n(), 1e-9 * omega_n());
  EXPECT_NEAR(lateral[2], tilt_frequency(0.0, 1.0), 1e-9 * tilt_frequency(0.0, 1.0));
  // The disk on the massless half-shaft held at s.0: k = G J_p / (L / 2) in torsion and
  // E A / (L / 2) axially (exact for the linear element).
  const double jp = kPi * std::pow(kDiameter, 4) / 32.0, area = kPi * kDiameter * kDiameter / 4;
  const double w_torsion = std::sqrt(kG * jp / (kLength / 2) / kIp);
  const double w_axial = std::sqrt(kE * area / (kLength / 2) / kMass);
  EXPECT_NEAR(torsional, w_torsion, 1e-9 * w_torsion);
  EXPECT_NEAR(axial, w_axial, 1e-9 * w_axial);
}

TEST(MasslessShaft, ModalDampingUsesTheFiniteModes) {
  // Modal damping on a massless shaft: the undamped modes that carry it are the rank(M) = 4
  // finite ones (the disk's), not the default 20, and each gets its ratio: the damped modes
  // of the undamped-modal basis have zeta = 0.02 exactly (the damping is diagonal in that basis;
  // round-off, 1e-9).
  std::string text = jeffcott_model("lateral") + R"(
[damping]
modal_ratio = 0.02

[[analyses]]
name = "modes"
type = "modal"
n_modes = 4
)";
  const std::string damper = "cxx = 300.0\ncyy = 300.0";
  text.replace(text.find(damper), damper.size(), "cxx = 0.0\ncyy = 0.0");
  const fs::path out = run_model("massless_modal_damping", text);
  auto modes = read_csv(out / "modes" / "modes.csv");
  ASSERT_EQ(modes["damping_ratio"].size(), 4u);
  for (const auto& zeta : modes["damping_ratio"]) EXPECT_NEAR(std::stod(zeta), 0.02, 1e-9);
}

std::string two_disk_model(const std::string& dofs_line, const std::string& supports) {
  return R"(version = 1
title = "two disks on a massless shaft"
)" + dofs_line +
         R"(

[[materials]]
name = "massless"
youngs_modulus = 2.0e11
shear_modulus = 8.0e10
density = 0

[[shafts]]
name = "s"
material = "massless"
  [[shafts.elements]]
  length = 0.5
  outer_diameter = 0.03
  divisions = 5

[[disks]]
name = "j1"
node = "s.0"
mass = 5.0
polar_inertia = 0.02
diametral_inertia = 0.01

[[disks]]
name = "j2"
node = "s.5"
mass = 8.0
polar_inertia = 0.05
diametral_inertia = 0.025
)" + supports +
         R"(
[[analyses]]
name = "modes"
type = "modal"
n_modes = 12
)";
}

double two_disk_frequency() {
  const double kt = kG * kPi * std::pow(0.03, 4) / 32.0 / 0.5;
  return std::sqrt(kt * (0.02 + 0.05) / (0.02 * 0.05));
}

// The torsional modes of a modes.csv, as (frequency_hz, rad/s) above 1e-6 of the highest.
std::vector<double> torsional_modes(const fs::path& csv) {
  auto modes = read_csv(csv);
  std::vector<double> out;
  for (std::size_t i = 0; i < modes["kind"].size(); ++i)
    if (modes["kind"][i] == "torsional" && std::stod(modes["frequency_hz"][i]) > 1e-3)
      out.push_back(std::stod(modes["frequency_hz"][i]) * kTwoPi);
  return out;
}

TEST(DofSets, TorsionOnlyModelMatchesTheFullModelAndTheTwoDiskClosedForm) {
  // Torsion only, written without a single [[constraints]] table: one rigid-body rotation and
  // the two-disk mode.
  const fs::path torsion = run_model("dofs_torsional", two_disk_model("dofs = \"torsional\"", ""));
  // The same shaft with all six DOFs, held laterally and axially by bearings at both disks
  // (they do not act in torsion).
  const std::string bearings = R"(
[[bearings]]
node = "s.0"
kxx = 1e7
kyy = 1e7
kzz = 1e7

[[bearings]]
node = "s.5"
kxx = 1e7
kyy = 1e7
)";
  const fs::path all = run_model("dofs_all", two_disk_model("", bearings));
  const std::vector<double> t = torsional_modes(torsion / "modes" / "undamped_modes.csv");
  const std::vector<double> a = torsional_modes(all / "modes" / "undamped_modes.csv");
  ASSERT_EQ(t.size(), 1u);
  ASSERT_EQ(a.size(), 1u);
  const double ref = two_disk_frequency();
  // Exact element, dense eigen-solve of the condensed 2-DOF system: round-off, 1e-9.
  EXPECT_NEAR(t[0], ref, 1e-9 * ref);
  EXPECT_NEAR(a[0], ref, 1e-9 * ref);
  // The torsion-only model has just the two torsional modes (rigid rotation and the mode).
  auto modes = read_csv(torsion / "modes" / "undamped_modes.csv");
  EXPECT_EQ(modes["kind"].size(), 2u);
}

TEST(DofSets, PerShaftSetOverridesTheModelAndBadValuesAreLocated) {
  // The shaft's own `dofs` overrides the model's (here "all", the default).
  std::string text = two_disk_model("", "");
  const std::string anchor = "material = \"massless\"\n  [[shafts.elements]]";
  text.replace(text.find(anchor), anchor.size(),
               "material = \"massless\"\ndofs = \"torsional\"\n  [[shafts.elements]]");
  const fs::path out = run_model("dofs_per_shaft", text);
  const std::vector<double> t = torsional_modes(out / "modes" / "undamped_modes.csv");
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t[0], two_disk_frequency(), 1e-9 * two_disk_frequency());

  for (const auto& [bad, key] : std::vector<std::pair<std::string, std::string>>{
           {two_disk_model("dofs = \"twist\"", ""), "'dofs'"},
           {two_disk_model("dofs = 6", ""), "'dofs'"},
           {text.replace(text.find("dofs = \"torsional\""), 18, "dofs = \"torsion\""),
            "'shafts[0].dofs'"}}) {
    const fs::path dir = fresh_dir("dofs_bad");
    write(dir / "model.toml", bad);
    const ProcessResult r = run("check " + (dir / "model.toml").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(key), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("model.toml:"), std::string::npos) << r.err;        // file and line
    EXPECT_NE(r.err.find("lateral+torsional"), std::string::npos) << r.err;  // the choices
  }
}

TEST(DofSets, GearMeshCouplesTorsionOnlyShafts) {
  // Two massless shafts in torsion only, a gear disk on each, joined by a spur mesh of
  // stiffness k along the line of action: omega^2 = k (r_b1^2 / J1 + r_b2^2 / J2) (Thomson &
  // Dahleh 1998, geared systems), plus the rigid-body rotation of the train. The far ends of
  // the shafts are massless and free: condensed. Round-off only, 1e-9.
  const std::string text = R"(version = 1
dofs = "torsional"

[[materials]]
name = "massless"
youngs_modulus = 2.0e11
shear_modulus = 8.0e10
density = 0

[[shafts]]
name = "input"
material = "massless"
  [[shafts.elements]]
  length = 0.2
  outer_diameter = 0.03

[[shafts]]
name = "output"
material = "massless"
origin = [0.15, 0, 0]
driven_by = "input"
gear_ratio = -0.5
  [[shafts.elements]]
  length = 0.2
  outer_diameter = 0.04

[[disks]]
name = "pinion"
node = "input.1"
mass = 1.0
polar_inertia = 2e-3
diametral_inertia = 1e-3

[[disks]]
name = "wheel"
node = "output.1"
mass = 4.0
polar_inertia = 2e-2
diametral_inertia = 1e-2

[[gear_meshes]]
gear1 = "input.1"
gear2 = "output.1"
type = "spur"
teeth1 = 20
teeth2 = 40
base_radius1 = 0.04698463103929542
base_radius2 = 0.09396926207859084
pressure_angle_deg = 20
stiffness = 2e8

[[analyses]]
name = "modes"
type = "modal"
n_modes = 4
)";
  const fs::path out = run_model("dofs_gear_torsion", text);
  const double rb1 = 0.04698463103929542, rb2 = 0.09396926207859084;
  const double ref = std::sqrt(2e8 * (rb1 * rb1 / 2e-3 + rb2 * rb2 / 2e-2));
  const std::vector<double> t = torsional_modes(out / "modes" / "undamped_modes.csv");
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t[0], ref, 1e-9 * ref);
}

}  // namespace
