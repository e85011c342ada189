// Reading a complete model: every section lands in the Model with its unit conversion, derived
// values are resolved, defaults come from the schema, and a printed document reads back the same.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/sweep.hpp"
#include "geardyn/analyses/transient.hpp"
#include "geardyn/analyses/unbalance.hpp"
#include "geardyn/model/parse.hpp"
#include "model/model_dump.hpp"

namespace geardyn::model {

using namespace ::geardyn::analyses;  // NOLINT: the settings types of every analysis
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRpm = 2.0 * kPi / 60.0;  // rad/s per rpm
constexpr double kHz = 2.0 * kPi;          // rad/s per Hz
constexpr double kDeg = kPi / 180.0;       // rad per degree

const std::string kFullModel =
    std::string(GEARDYN_SOURCE_DIR) + "/tests/model/data/full_model.toml";

// Relative tolerance for values that went through one multiplication by a unit factor.
constexpr double kTight = 1e-14;

#define EXPECT_REL(actual, expected) \
  EXPECT_NEAR(actual, expected, kTight* std::max(1.0, std::abs(expected)))

template <class T>
const T& settings(const Model& m, const std::string& name) {
  const Analysis* a = m.find_analysis(name);
  EXPECT_NE(a, nullptr) << name;
  return a->settings_of<T>();
}

TEST(ModelParse, FullModelEverySection) {
  const Model m = analyses::load_model(kFullModel);
  EXPECT_EQ(m.version, 1);
  EXPECT_EQ(m.title, "Two-shaft geared rotor, every section");
  EXPECT_EQ(m.source_file, kFullModel);

  // Materials: G from Poisson's ratio, G = E / (2 (1 + nu)).
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_REL(m.materials[0].shear_modulus, 2.1e11 / 2.6);
  EXPECT_EQ(m.materials[1].shear_modulus, 2.6e10);
  EXPECT_EQ(m.materials[1].density, 2700.0);
  EXPECT_EQ(m.materials[0].where.line, 6);

  // Shafts: speed chain input (1) -> output (-0.5 x 1) -> idler (2 x -0.5).
  ASSERT_EQ(m.shafts.size(), 3u);
  const Shaft& input = m.shafts[0];
  EXPECT_EQ(input.speed_ratio, 1.0);
  EXPECT_EQ(input.shear_coefficient, 0.9);
  EXPECT_EQ(input.theory, BeamTheory::Timoshenko);
  EXPECT_TRUE(input.rotary_inertia);
  EXPECT_TRUE(input.gyroscopic);
  ASSERT_EQ(input.elements.size(), 2u);
  EXPECT_EQ(input.elements[0].divisions, 2);
  EXPECT_EQ(input.elements[0].inner_diameter, 0.0);
  EXPECT_EQ(input.elements[0].material, "");
  EXPECT_EQ(input.elements[1].inner_diameter, 0.02);
  EXPECT_EQ(input.elements[1].material, "alu");
  EXPECT_EQ(input.elements[1].loss_factor, 0.002);
  const Shaft& output = m.shafts[1];
  EXPECT_EQ(output.speed_ratio, -0.5);
  EXPECT_EQ(output.driven_by, "input");
  EXPECT_EQ(output.theory, BeamTheory::EulerBernoulli);
  EXPECT_FALSE(output.rotary_inertia);
  EXPECT_FALSE(output.gyroscopic);
  EXPECT_EQ(output.axis, (Vec3{0.0, 0.0, 1.0}));  // [0, 0, 2] normalised
  EXPECT_EQ(output.origin, (Vec3{0.0, 0.1, 0.0}));
  EXPECT_TRUE(std::isnan(output.shear_coefficient));
  EXPECT_EQ(m.shafts[2].speed_ratio, -1.0);

  // Free nodes: spin_of takes the shaft's resolved ratio.
  ASSERT_EQ(m.nodes.size(), 2u);
  EXPECT_EQ(m.nodes[0].speed_ratio, 0.0);
  EXPECT_EQ(m.nodes[1].speed_ratio, -0.5);
  EXPECT_EQ(m.nodes[1].axis, (Vec3{1.0, 0.0, 0.0}));

  // Disks: given inertias, and a steel annulus ro = 0.1, ri = 0.025, h = 0.02:
  // m = rho pi (ro^2 - ri^2) h, Ip = m (ro^2 + ri^2) / 2, Id = m (3 (ro^2 + ri^2) + h^2) / 12.
  ASSERT_EQ(m.disks.size(), 2u);
  EXPECT_EQ(m.disks[0].name, "pinion");
  EXPECT_EQ(m.disks[0].mass, 1.5);
  EXPECT_EQ(m.disks[0].diametral_inertia, 0.001);
  EXPECT_TRUE(std::isnan(m.disks[0].outer_diameter));
  EXPECT_EQ(m.disks[1].name, "disks[1]");
  const double ro = 0.1, ri = 0.025, h = 0.02;
  const double mass = 7850.0 * kPi * (ro * ro - ri * ri) * h;  // 4.6240 kg
  EXPECT_NEAR(mass, 4.6240, 1e-4);
  EXPECT_REL(m.disks[1].mass, mass);
  EXPECT_REL(m.disks[1].polar_inertia, mass * (ro * ro + ri * ri) / 2.0);
  EXPECT_REL(m.disks[1].diametral_inertia, mass * (3.0 * (ro * ro + ri * ri) + h * h) / 12.0);

  ASSERT_EQ(m.point_masses.size(), 1u);
  EXPECT_EQ(m.point_masses[0].name, "point_masses[0]");
  EXPECT_EQ(m.point_masses[0].mass, 10.0);

  // Bearings: constant, tabulated (speed_rpm in rad/s), and full matrices.
  ASSERT_EQ(m.bearings.size(), 3u);
  const Bearing& b1 = m.bearings[0];
  EXPECT_TRUE(b1.speeds.empty());
  ASSERT_EQ(b1.stiffness.size(), 1u);
  ASSERT_EQ(b1.damping.size(), 1u);
  EXPECT_EQ(b1.stiffness[0][0], 1e8);   // kxx
  EXPECT_EQ(b1.stiffness[0][1], -1e6);  // kxy (row x, column y)
  EXPECT_EQ(b1.stiffness[0][6], 0.0);   // kyx
  EXPECT_EQ(b1.stiffness[0][7], 1e8);   // kyy
  EXPECT_EQ(b1.stiffness[0][35], 5.0);  // ktzz
  EXPECT_EQ(b1.damping[0][0], 100.0);
  EXPECT_EQ(b1.node2, "");
  const Bearing& b2 = m.bearings[1];
  ASSERT_EQ(b2.speeds.size(), 3u);
  EXPECT_REL(b2.speeds[1], 3000.0 * kRpm);
  ASSERT_EQ(b2.stiffness.size(), 3u);
  ASSERT_EQ(b2.damping.size(), 3u);
  EXPECT_EQ(b2.stiffness[1][0], 1.2e8);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(b2.stiffness[static_cast<std::size_t>(k)][7], 2e8);
  EXPECT_EQ(b2.damping[2][14], 3.0);  // czz at 6000 rpm
  EXPECT_EQ(b2.node2, "housing");
  const Bearing& b3 = m.bearings[2];
  ASSERT_EQ(b3.stiffness.size(), 1u);
  EXPECT_EQ(b3.stiffness[0][1], 1e6);
  EXPECT_EQ(b3.stiffness[0][6], -1e6);
  EXPECT_EQ(b3.damping[0][14], 10.0);

  // Couplings: 6x6 to ground, 12x12 between nodes, row-major.
  ASSERT_EQ(m.couplings.size(), 2u);
  EXPECT_EQ(m.couplings[0].stiffness.size(), 36u);
  EXPECT_TRUE(m.couplings[0].mass.empty());
  EXPECT_EQ(m.couplings[1].stiffness.size(), 144u);
  EXPECT_EQ(m.couplings[1].stiffness[0 * 12 + 6], -1e7);
  EXPECT_EQ(m.couplings[1].mass[13], 0.5);
  EXPECT_EQ(m.couplings[1].name, "couplings[1]");

  // Gear meshes: degrees to radians.
  ASSERT_EQ(m.gear_meshes.size(), 2u);
  const GearMesh& g = m.gear_meshes[0];
  EXPECT_EQ(g.type, GearType::Helical);
  EXPECT_EQ(g.teeth1, 20);
  EXPECT_EQ(g.teeth2, 40);
  EXPECT_REL(g.pressure_angle, 20.0 * kDeg);
  EXPECT_REL(g.helix_angle, 15.0 * kDeg);
  EXPECT_EQ(g.hand, Hand::Left);
  EXPECT_EQ(g.flank, Flank::Coast);
  EXPECT_EQ(g.damping, 500.0);
  EXPECT_FALSE(g.mesh_direction.has_value());
  const GearMesh& bevel = m.gear_meshes[1];
  EXPECT_EQ(bevel.type, GearType::SpiralBevel);
  EXPECT_REL(bevel.pitch_cone_angle1, 30.0 * kDeg);
  EXPECT_REL(bevel.pitch_cone_angle2, 60.0 * kDeg);
  EXPECT_REL(bevel.pressure_angle, 20.0 * kDeg);  // default 20 deg
  EXPECT_EQ(bevel.hand, Hand::Right);
  EXPECT_EQ(bevel.teeth1, 0);
  ASSERT_TRUE(bevel.mesh_direction.has_value());
  EXPECT_EQ(*bevel.mesh_direction, (Vec3{0.0, 1.0, 0.0}));

  ASSERT_EQ(m.constraints.size(), 2u);
  EXPECT_EQ(m.constraints[0].dofs.size(), 6u);
  EXPECT_EQ(m.constraints[1].dofs, (std::vector<Component>{Component::Uz, Component::Rz}));

  ASSERT_EQ(m.unbalances.size(), 1u);
  EXPECT_REL(m.unbalances[0].phase, kPi / 2.0);
  EXPECT_EQ(m.unbalances[0].mass_eccentricity, 1e-4);
  ASSERT_EQ(m.forces.size(), 1u);
  EXPECT_EQ(m.forces[0].dof, Component::Uy);
  EXPECT_REL(m.forces[0].phase, kPi / 4.0);
  ASSERT_EQ(m.sensors.size(), 2u);
  EXPECT_EQ(m.sensors[1].dof, Component::Rz);

  // Damping: band edges Hz -> rad/s, inf kept.
  EXPECT_EQ(m.damping.rayleigh_alpha, 1.0);
  EXPECT_EQ(m.damping.rayleigh_beta, 1e-6);
  EXPECT_EQ(m.damping.loss_factor, 0.01);
  EXPECT_EQ(m.damping.modal_ratio, 0.02);
  EXPECT_EQ(m.damping.modal_ratios, (std::vector<double>{0.01, 0.015}));
  ASSERT_EQ(m.damping.bands.size(), 2u);
  EXPECT_REL(m.damping.bands[0].f_max, 100.0 * kHz);
  EXPECT_TRUE(std::isinf(m.damping.bands[1].f_max));

  // Analyses.
  ASSERT_EQ(m.analyses.size(), 8u);
  const auto& modal = settings<ModalSettings>(m, "modes");
  EXPECT_REL(modal.speed, 3000.0 * kRpm);
  EXPECT_EQ(modal.n_modes, 12);
  EXPECT_FALSE(modal.complex_modes);
  EXPECT_EQ(modal.method, EigenMethod::Dense);
  EXPECT_REL(modal.shift, 50.0 * kHz);

  const auto& campbell = settings<CampbellSettings>(m, "campbell");
  ASSERT_EQ(campbell.speeds.size(), 7u);
  for (int i = 0; i < 7; ++i)
    EXPECT_NEAR(campbell.speeds[static_cast<std::size_t>(i)], 1000.0 * i * kRpm, 1e-12);
  EXPECT_EQ(campbell.engine_orders, (std::vector<double>{1.0, 2.0}));
  EXPECT_TRUE(campbell.shaft_orders);
  EXPECT_FALSE(campbell.mesh_orders);
  EXPECT_EQ(campbell.mac_threshold, 0.8);
  EXPECT_EQ(campbell.n_modes, 10);  // schema default
  EXPECT_EQ(campbell.method, EigenMethod::Sparse);

  const auto& frf = settings<HarmonicSettings>(m, "frf");
  EXPECT_REL(frf.speed, 1000.0 * kRpm);
  EXPECT_REL(frf.f_min, 10.0 * kHz);
  EXPECT_REL(frf.f_max, 1000.0 * kHz);
  EXPECT_EQ(frf.n_points, 50);
  EXPECT_EQ(frf.spacing, Spacing::Log);
  EXPECT_FALSE(frf.adaptive);
  EXPECT_EQ(frf.input_node, "input.2");
  EXPECT_EQ(frf.input_dof, Component::Uy);
  EXPECT_EQ(frf.sensors, (std::vector<std::string>{"s1"}));
  EXPECT_EQ(frf.quantity, ResponseQuantity::Mobility);

  const auto& forced = settings<HarmonicSettings>(m, "forced");
  EXPECT_FALSE(m.find_analysis("forced")->enabled);
  EXPECT_EQ(forced.forces, (std::vector<std::string>{"f1"}));
  EXPECT_EQ(forced.n_points, 200);
  EXPECT_EQ(forced.speed, 0.0);
  EXPECT_TRUE(forced.sensors.empty());
  EXPECT_EQ(forced.quantity, ResponseQuantity::Receptance);

  const auto& unb = settings<UnbalanceSettings>(m, "unb");
  ASSERT_EQ(unb.speeds.size(), 3u);
  EXPECT_REL(unb.speeds[2], 4000.0 * kRpm);
  EXPECT_EQ(unb.unbalances, (std::vector<std::string>{"u1"}));

  const auto& runup = settings<TransientSettings>(m, "runup");
  EXPECT_EQ(runup.speed, 0.0);
  EXPECT_REL(runup.speed_end, 6000.0 * kRpm);
  EXPECT_EQ(runup.duration, 2.0);
  EXPECT_EQ(runup.time_step, 1e-4);
  EXPECT_EQ(runup.integrator, Integrator::Newmark);
  EXPECT_EQ(runup.rho_infinity, 0.8);
  EXPECT_EQ(runup.steady_fraction, 0.25);
  EXPECT_EQ(runup.output_every, 10);
  EXPECT_EQ(runup.sensors, (std::vector<std::string>{"s1", "s2"}));

  const auto& sweep = settings<SweepSettings>(m, "kxx_sweep");
  EXPECT_EQ(sweep.parameter, "bearings[0].kxx");
  ASSERT_EQ(sweep.values.size(), 4u);
  const double decades[] = {1e6, 1e7, 1e8, 1e9};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(sweep.values[i], decades[i], 1e-12 * decades[i]);
  EXPECT_TRUE(sweep.log_x);
  EXPECT_EQ(sweep.analysis, "modes");
  EXPECT_EQ(sweep.threads, 2);
  ASSERT_EQ(sweep.outputs.size(), 1u);
  EXPECT_EQ(sweep.outputs[0].quantity, "natural_frequency");
  EXPECT_EQ(sweep.outputs[0].mode, 2);
  EXPECT_EQ(sweep.outputs[0].label, "natural_frequency_2");

  const auto& mesh_sweep = settings<SweepSettings>(m, "mesh_sweep");
  EXPECT_EQ(mesh_sweep.values, (std::vector<double>{1e8, 2e8}));
  EXPECT_FALSE(mesh_sweep.log_x);
  EXPECT_EQ(mesh_sweep.threads, 0);
  ASSERT_EQ(mesh_sweep.outputs.size(), 2u);
  EXPECT_EQ(mesh_sweep.outputs[0].label, "peak_amplitude_s1");
  EXPECT_EQ(mesh_sweep.outputs[1].quantity, "amplitude_at");
  EXPECT_REL(mesh_sweep.outputs[1].at, 2000.0 * kRpm);
  EXPECT_EQ(mesh_sweep.outputs[1].label, "s2_at_2000");
}

TEST(ModelParse, PrintedDocumentReadsBackTheSameModel) {
  const ModelDocument doc = analyses::load_document(kFullModel);
  std::ostringstream printed;
  printed << doc.table();
  const Model original = build_model(doc);
  const Model again = analyses::parse_model(printed.str(), "printed.toml");
  EXPECT_EQ(test::dump(original), test::dump(again));
  EXPECT_GT(test::dump(original).size(), 3000u);  // the dump covers the whole model
}

TEST(ModelParse, DefaultsComeFromTheSchema) {
  const Model m = analyses::parse_model(R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 2.1e11
shear_modulus = 8.1e10
density = 7850
[[shafts]]
name = "r"
material = "steel"
[[shafts.elements]]
length = 1
outer_diameter = 0.1
[[gear_meshes]]
gear1 = "r.0"
gear2 = "r.1"
base_radius1 = 0.1
base_radius2 = 0.2
stiffness = 1e8
[[analyses]]
name = "m"
type = "modal"
[[analyses]]
name = "t"
type = "transient"
duration = 1
time_step = 0.001
)",
                                        "defaults.toml");
  EXPECT_EQ(m.title, "");
  EXPECT_EQ(m.shafts[0].origin, (Vec3{0, 0, 0}));
  EXPECT_EQ(m.shafts[0].axis, (Vec3{0, 0, 1}));
  EXPECT_EQ(m.shafts[0].speed_ratio, 1.0);
  EXPECT_EQ(m.shafts[0].elements[0].divisions, 1);
  EXPECT_EQ(m.gear_meshes[0].type, GearType::Spur);
  EXPECT_NEAR(m.gear_meshes[0].pressure_angle, 20.0 * kDeg, 1e-15);
  EXPECT_EQ(m.gear_meshes[0].helix_angle, 0.0);
  EXPECT_EQ(m.gear_meshes[0].name, "gear_meshes[0]");
  EXPECT_EQ(m.damping.rayleigh_alpha, 0.0);
  EXPECT_FALSE(m.damping.any_modal());
  const auto& modal = m.analyses[0].settings_of<analyses::ModalSettings>();
  EXPECT_EQ(modal.speed, 0.0);
  EXPECT_EQ(modal.n_modes, 10);
  EXPECT_TRUE(modal.complex_modes);
  EXPECT_EQ(modal.method, EigenMethod::Auto);
  const auto& t = m.analyses[1].settings_of<analyses::TransientSettings>();
  EXPECT_EQ(t.integrator, Integrator::GeneralizedAlpha);
  EXPECT_EQ(t.rho_infinity, 0.9);
  EXPECT_EQ(t.steady_fraction, 0.5);
  EXPECT_TRUE(std::isnan(t.speed_end));
  EXPECT_TRUE(m.analyses[1].enabled);
}

TEST(ModelParse, UnitConversionsAreExact) {
  // 60 rpm = 1 rev/s = 2 pi rad/s; 1 Hz = 2 pi rad/s; 180 deg = pi rad. Checked with exact
  // multiples so a wrong factor (e.g. rpm taken as rev/s, Hz left as is) cannot pass.
  const Model m = analyses::parse_model(R"(version = 1
[[nodes]]
name = "hub"
position = [0, 0, 0]
[[shafts]]
name = "r"
material = "steel"
[[shafts.elements]]
length = 1
outer_diameter = 0.1
[[materials]]
name = "steel"
youngs_modulus = 2e11
shear_modulus = 8e10
density = 7800
[[unbalances]]
node = "r.1"
mass_eccentricity = 1
phase_deg = 180
[[analyses]]
name = "h"
type = "harmonic"
speed_rpm = 60
frequency_start_hz = 1
frequency_stop_hz = 2
input_node = "hub"
[[analyses]]
name = "u"
type = "unbalance"
speed_start_rpm = 60
speed_stop_rpm = 180
speed_count = 3
)",
                                        "units.toml");
  const auto& h = m.analyses[0].settings_of<analyses::HarmonicSettings>();
  EXPECT_DOUBLE_EQ(h.speed, 2.0 * kPi);
  EXPECT_DOUBLE_EQ(h.f_min, 2.0 * kPi);
  EXPECT_DOUBLE_EQ(h.f_max, 4.0 * kPi);
  EXPECT_DOUBLE_EQ(m.unbalances[0].phase, kPi);
  const auto& u = m.analyses[1].settings_of<analyses::UnbalanceSettings>();
  ASSERT_EQ(u.speeds.size(), 3u);
  EXPECT_DOUBLE_EQ(u.speeds[0], 2.0 * kPi);
  EXPECT_DOUBLE_EQ(u.speeds[1], 4.0 * kPi);
  EXPECT_DOUBLE_EQ(u.speeds[2], 6.0 * kPi);
}

TEST(ModelParse, InlineTablesAndCommentsAreFine) {
  const Model m = analyses::parse_model(R"(version = 1  # format
nodes = [ { name = "a", position = [0, 0, 0] }, { name = "b", position = [1, 0, 0] } ]
couplings = [ { node1 = "a", node2 = "b", stiffness = [
  [1, 0, 0, 0, 0, 0, -1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0, 0, -1, 0, 0, 0, 0],
  [0, 0, 1, 0, 0, 0, 0, 0, -1, 0, 0, 0], [0, 0, 0, 1, 0, 0, 0, 0, 0, -1, 0, 0],
  [0, 0, 0, 0, 1, 0, 0, 0, 0, 0, -1, 0], [0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, -1],
  [-1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0], [0, -1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0],
  [0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 0, 0], [0, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 0],
  [0, 0, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, -1, 0, 0, 0, 0, 0, 1] ] } ]
)",
                                        "inline.toml");
  ASSERT_EQ(m.couplings.size(), 1u);
  EXPECT_EQ(m.couplings[0].stiffness[6], -1.0);
  EXPECT_EQ(m.nodes[1].position[0], 1.0);
}

TEST(ModelParse, AByteOrderMarkIsAccepted) {
  // Windows editors start UTF-8 files with EF BB BF; it is not part of the TOML text.
  const Model m = analyses::parse_model(
      "\xEF\xBB\xBFversion = 1\ntitle = \"bom\"\n"
      "[[nodes]]\nname = \"a\"\nposition = [0, 0, 0]\n",
      "bom.toml");
  EXPECT_EQ(m.title, "bom");
}

TEST(ModelParse, ADirectoryIsNotAModelFile) {
  try {
    (void)analyses::load_document(std::string(GEARDYN_SOURCE_DIR) + "/examples/damper_ring");
    ADD_FAILURE() << "a directory was read as a model";
  } catch (const InputError& e) {
    EXPECT_EQ(e.found(), "a directory");
    EXPECT_NE(e.hint().find("model.toml"), std::string::npos) << e.what();
  }
}

TEST(ModelParse, NonAsciiTextInStringsAndComments) {
  const Model m = analyses::parse_model(
      "version = 1  # Drehzahl in 1/min, \xc3\xbc\n"
      "title = \"Getriebe \xe2\x80\x93 Stufe 1 (\xc2\xb0)\"\n"
      "[[nodes]]\nname = \"a\"\nposition = [0, 0, 0]\n",
      "utf8.toml");
  EXPECT_EQ(m.title, "Getriebe \xe2\x80\x93 Stufe 1 (\xc2\xb0)");
}

TEST(ModelParse, QuotedPartsOfDottedKeysAreFine) {
  // The text check refuses a quote after a value's '.' (x = 0."...", a toml++ 3.3 hazard) but
  // must keep accepting dotted keys with quoted parts, in tables and inline tables.
  const Model m = analyses::parse_model(
      "version = 1\n"
      "damping.\"rayleigh_alpha\" = 2.5  # a quoted part of a dotted key\n"
      "\"damping\".'loss_factor' = 0.01\n"
      "nodes = [ { \"name\" = \"a\", position = [0.5, 0, 0] } ]\n",
      "dotted.toml");
  EXPECT_EQ(m.damping.rayleigh_alpha, 2.5);
  EXPECT_EQ(m.damping.loss_factor, 0.01);
  EXPECT_EQ(m.nodes[0].position[0], 0.5);
}

TEST(ModelParse, FuzzSeedsAreValidModels) {
  // The seed corpus of fuzz/model_fuzz must stay valid, or the fuzzer starts from errors only.
  // Lines "#--set key=value" are overrides applied by the fuzz harness.
  const std::string dir = std::string(GEARDYN_SOURCE_DIR) + "/fuzz/corpus/model";
  int seeds = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    SCOPED_TRACE(entry.path().string());
    ModelDocument doc = analyses::load_document(entry.path().string());
    std::ifstream in(entry.path());
    for (std::string line; std::getline(in, line);)
      if (line.rfind("#--set ", 0) == 0) apply_override(doc, line.substr(7));
    EXPECT_NO_THROW((void)build_model(doc));
    ++seeds;
  }
  EXPECT_GE(seeds, 2);
}

TEST(ModelParse, FuzzRegressionInputsAreRefusedWithASyntaxError) {
  // Inputs on which fuzz/model_fuzz once found undefined behaviour inside toml++ 3.3 (its
  // whitespace table reaches an unreachable branch for some non-ASCII code points after a
  // backslash or in a bare value): geardyn's text check must refuse them before toml++ runs.
  const std::string dir = std::string(GEARDYN_SOURCE_DIR) + "/fuzz/regressions/model";
  int inputs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    SCOPED_TRACE(entry.path().string());
    try {
      (void)analyses::load_document(entry.path().string());
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key_path(), "(syntax)");
      EXPECT_GE(e.where().line, 1);
    }
    ++inputs;
  }
  EXPECT_GE(inputs, 2);
}

TEST(ModelParse, BenchmarkModelsAreValid) {
  // bench/ runs these outside the test suite; they must not rot.
  int models = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(GEARDYN_SOURCE_DIR) + "/bench/data")) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW((void)analyses::load_model(entry.path().string()));
    ++models;
  }
  EXPECT_GE(models, 1);
}

TEST(ModelParse, StationNames) { EXPECT_EQ(station_name("rotor", 3), "rotor.3"); }

}  // namespace
}  // namespace geardyn::model
