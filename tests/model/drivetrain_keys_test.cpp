// The model keys of the nonlinear drivetrain (schema_drivetrain.cpp, drivetrain_spec.hpp):
// every section read into its struct with its units converted to SI, the declared defaults, the
// contact laws and their per-type keys, the optional tooth contact of a gear mesh, the
// cross-reference checks of parse.cpp (nodes, ends, DOFs, gear pairs, unique names) with their
// located messages, and an override of a new key.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/model/parse.hpp"

namespace geardyn::model {
namespace {

// Two shafts (input.0 .. input.4 and the lateral-only output.0 .. output.2), a housing node with
// mass, a spinning web node, a massless node, a gear mesh and a gear pair.
const std::string kBase = R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 2.1e11
poisson_ratio = 0.3
density = 7850
[[shafts]]
name = "input"
material = "steel"
[[shafts.elements]]
length = 0.4
outer_diameter = 0.04
divisions = 4
[[shafts]]
name = "output"
material = "steel"
origin = [0.0, 0.15, 0.0]
dofs = "lateral"
[[shafts.elements]]
length = 0.2
outer_diameter = 0.05
divisions = 2
[[nodes]]
name = "housing"
position = [0.0, 0.0, -0.1]
[[point_masses]]
node = "housing"
mass = 5.0
[[nodes]]
name = "web"
position = [0.0, 0.0, 0.2]
spin_of = "input"
[[nodes]]
name = "loose"
position = [0.0, 0.3, 0.0]
[[constraints]]
node = "input.4"
dofs = ["rz"]
[[gear_pairs]]
name = "spur"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = 100
[[gear_meshes]]
name = "mesh"
gear1 = "input.2"
gear2 = "output.1"
base_radius1 = 0.028
base_radius2 = 0.056
stiffness = 2e8
)";

int base_lines() { return static_cast<int>(std::count(kBase.begin(), kBase.end(), '\n')); }

Model parse(const std::string& snippet) {
  return analyses::parse_model(kBase + snippet, "model.toml");
}

std::optional<InputError> error_of(const std::string& snippet) {
  try {
    (void)parse(snippet);
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

constexpr double kRpm = units::kRadPerSecondPerRpm;
constexpr double kDeg = units::kRadPerDegree;

// Values written in the file come back exactly or through one unit factor: 1e-15 relative is a
// few ulps of that multiplication.
void expect_near_rel(double actual, double expected) {
  EXPECT_NEAR(actual, expected, 1e-15 * std::abs(expected)) << "expected " << expected;
}

TEST(DrivetrainKeys, ContactsBoltsAndBushingsAreReadWithTheirUnits) {
  const Model m = parse(R"(
[[contacts]]
name = "stop"
node1 = "housing"
node2 = "input.0"
direction = [0.0, 3.0, 4.0]
gap = -1e-5
[contacts.law]
type = "impact"
stiffness = 1e9
exponent = 2.2
max_damping = 400
penetration_depth = 1e-4
tension = "clipped"
[[contacts]]
name = "play"
node2 = "input.1"
type = "end_play"
motion = "rotation"
direction = [0.0, 0.0, 2.0]
backlash = 0.01
[contacts.law]
type = "penalty"
stiffness = 5e6
stiffness_exponent = 1.5
damping = 20
rate_exponent = 0.5
damping_exponent = 1.0
penetration_regularisation = 1e-8
rate_regularisation = 1e-5
[[bolts]]
name = "b1"
node1 = "housing"
node2 = "input.0"
axis = [2.0, 0.0, 0.0]
bolt_stiffness = 4e8
clamp_stiffness = 1.2e9
preload = 2e4
load_introduction = 0.5
axial_damping = 100
shear_stiffness = 1e8
shear_damping = 50
activation_time = 0.02
preload_ramp = 0.005
inactive_stiffness = 1e3
[[bushings]]
name = "mount"
node1 = "housing"
node2 = "input.3"
x_axis = [0.0, 2.0, 0.0]
z_axis = [1.0, 0.0, 0.0]
kxx = 1e6
kyy = 2e6
ktzz = 300
cxx = 10
ctyy = 0.5
preload = [1.0, 2.0, 3.0, 0.1, 0.2, 0.3]
[[bushings.tables]]
direction = "ry"
deflection = [-0.01, 0.0, 0.02]
force = [-50.0, 0.0, 300.0]
interpolation = "linear"
)");
  ASSERT_EQ(m.contacts.size(), 2u);
  const ContactSpec& stop = m.contacts[0];
  EXPECT_EQ(stop.name, "stop");
  EXPECT_EQ(stop.node1, "housing");
  EXPECT_EQ(stop.node2, "input.0");
  expect_near_rel(stop.direction[1], 0.6);  // normalised (0, 3, 4) / 5
  expect_near_rel(stop.direction[2], 0.8);
  EXPECT_EQ(stop.direction[0], 0.0);
  EXPECT_EQ(stop.kind, ContactKind::Stop);
  EXPECT_EQ(stop.motion, ContactMotion::Translation);
  EXPECT_EQ(stop.gap, -1e-5);
  EXPECT_EQ(stop.law.type, ContactLawKind::Impact);
  EXPECT_EQ(stop.law.stiffness, 1e9);
  EXPECT_EQ(stop.law.exponent, 2.2);
  EXPECT_EQ(stop.law.max_damping, 400.0);
  EXPECT_EQ(stop.law.penetration_depth, 1e-4);
  EXPECT_TRUE(stop.law.clip_tension);
  EXPECT_EQ(stop.where.line, base_lines() + 2);
  EXPECT_EQ(stop.law.where.line, base_lines() + 8);

  const ContactSpec& play = m.contacts[1];
  EXPECT_TRUE(play.node1.empty());  // ground
  EXPECT_EQ(play.kind, ContactKind::EndPlay);
  EXPECT_EQ(play.motion, ContactMotion::Rotation);
  EXPECT_EQ(play.direction, (DrivetrainVec3{0.0, 0.0, 1.0}));
  EXPECT_EQ(play.backlash, 0.01);
  EXPECT_EQ(play.law.type, ContactLawKind::Penalty);
  EXPECT_EQ(play.law.stiffness, 5e6);
  EXPECT_EQ(play.law.stiffness_exponent, 1.5);
  EXPECT_EQ(play.law.damping, 20.0);
  EXPECT_EQ(play.law.rate_exponent, 0.5);
  EXPECT_EQ(play.law.damping_exponent, 1.0);
  EXPECT_EQ(play.law.penetration_regularisation, 1e-8);
  EXPECT_EQ(play.law.rate_regularisation, 1e-5);
  EXPECT_FALSE(play.law.clip_tension);

  ASSERT_EQ(m.bolts.size(), 1u);
  const BoltSpec& b = m.bolts[0];
  EXPECT_EQ(b.node1, "housing");
  EXPECT_EQ(b.axis, (DrivetrainVec3{1.0, 0.0, 0.0}));
  EXPECT_EQ(b.bolt_stiffness, 4e8);
  EXPECT_EQ(b.clamp_stiffness, 1.2e9);
  EXPECT_EQ(b.preload, 2e4);
  EXPECT_EQ(b.load_introduction, 0.5);
  EXPECT_EQ(b.axial_damping, 100.0);
  EXPECT_EQ(b.shear_stiffness, 1e8);
  EXPECT_EQ(b.shear_damping, 50.0);
  EXPECT_EQ(b.activation_time, 0.02);
  EXPECT_EQ(b.preload_ramp, 0.005);
  EXPECT_EQ(b.inactive_stiffness, 1e3);

  ASSERT_EQ(m.bushings.size(), 1u);
  const BushingSpec& k = m.bushings[0];
  EXPECT_EQ(k.x_axis, (DrivetrainVec3{0.0, 1.0, 0.0}));
  EXPECT_EQ(k.z_axis, (DrivetrainVec3{1.0, 0.0, 0.0}));
  EXPECT_EQ(k.stiffness[0], 1e6);     // (x, x)
  EXPECT_EQ(k.stiffness[7], 2e6);     // (y, y)
  EXPECT_EQ(k.stiffness[35], 300.0);  // (rz, rz)
  EXPECT_EQ(k.stiffness[14], 0.0);    // kzz not given
  EXPECT_EQ(k.stiffness[1], 0.0);     // off-diagonal
  EXPECT_EQ(k.damping[0], 10.0);
  EXPECT_EQ(k.damping[28], 0.5);  // (ry, ry)
  EXPECT_EQ(k.preload, (std::array<double, 6>{1.0, 2.0, 3.0, 0.1, 0.2, 0.3}));
  ASSERT_EQ(k.tables.size(), 1u);
  EXPECT_EQ(k.tables[0].direction, 4);
  EXPECT_EQ(k.tables[0].deflection, (std::vector<double>{-0.01, 0.0, 0.02}));
  EXPECT_EQ(k.tables[0].force, (std::vector<double>{-50.0, 0.0, 300.0}));
  EXPECT_TRUE(k.tables[0].linear);
}

TEST(DrivetrainKeys, BearingsDriversLoadsClutchesAndSensorsAreReadWithTheirUnits) {
  const Model m = parse(R"(
[[rolling_bearings]]
name = "deep_groove"
node = "web"
housing = "housing"
elements = 9
stiffness_constant = 8e9
exponent = 1.1111111111
radial_clearance = 2e-5
axial_clearance = -1e-6
contact_angle_deg = 15
pitch_diameter = 0.05
element_diameter = 0.008
cage_angle_deg = 20
radial_damping = 300
axial_damping = 200
[[drivers]]
name = "motor"
node = "input.0"
type = "motor"
motor_speed_rpm = [0.0, 3000.0, 6000.0]
motor_torque = [50.0, 50.0, 0.0]
inertia = 2e-3
[[drivers]]
name = "ramp"
node = "input.3"
type = "speed"
time = [0.0, 0.5]
speed_rpm = [0.0, 1500.0]
[[loads]]
name = "fan"
node = "input.1"
torque = -10
speed_rpm = [0.0, 1000.0]
table_torque = [0.0, -5.0]
drag = 1e-4
[[loads]]
name = "step"
node = "input.2"
time = [0.0, 0.1, 0.2]
table_torque = [0.0, 0.0, -20.0]
[[clutches]]
name = "brake"
node2 = "input.2"
max_torque = 80
slip_speed = 0.5
engage_time = 0.3
[[virtual_sensors]]
name = "acc_y"
node = "housing"
dof = "uy"
[[virtual_sensors]]
name = "normal"
node = "housing"
direction = [1.0, 1.0, 0.0]
rotation = true
)");
  ASSERT_EQ(m.rolling_bearings.size(), 1u);
  const RollingBearingSpec& r = m.rolling_bearings[0];
  EXPECT_EQ(r.node, "web");
  EXPECT_EQ(r.housing, "housing");
  EXPECT_EQ(r.elements, 9);
  EXPECT_EQ(r.stiffness_constant, 8e9);
  EXPECT_EQ(r.exponent, 1.1111111111);
  EXPECT_EQ(r.radial_clearance, 2e-5);
  EXPECT_EQ(r.axial_clearance, -1e-6);
  expect_near_rel(r.contact_angle, 15.0 * kDeg);
  EXPECT_EQ(r.pitch_diameter, 0.05);
  EXPECT_EQ(r.element_diameter, 0.008);
  expect_near_rel(r.cage_angle, 20.0 * kDeg);
  EXPECT_EQ(r.radial_damping, 300.0);
  EXPECT_EQ(r.axial_damping, 200.0);

  ASSERT_EQ(m.drivers.size(), 2u);
  const DriverSpec& motor = m.drivers[0];
  EXPECT_EQ(motor.kind, DriverKind::Motor);
  ASSERT_EQ(motor.motor_speeds.size(), 3u);
  EXPECT_EQ(motor.motor_speeds[0], 0.0);
  expect_near_rel(motor.motor_speeds[1], 3000.0 * kRpm);
  expect_near_rel(motor.motor_speeds[2], 6000.0 * kRpm);
  EXPECT_EQ(motor.motor_torques, (std::vector<double>{50.0, 50.0, 0.0}));
  EXPECT_EQ(motor.inertia, 2e-3);
  EXPECT_TRUE(motor.times.empty());
  const DriverSpec& ramp = m.drivers[1];
  EXPECT_EQ(ramp.kind, DriverKind::Speed);
  EXPECT_EQ(ramp.times, (std::vector<double>{0.0, 0.5}));
  ASSERT_EQ(ramp.speeds.size(), 2u);
  expect_near_rel(ramp.speeds[1], 1500.0 * kRpm);  // 157.08 rad/s

  ASSERT_EQ(m.loads.size(), 2u);
  const LoadTorqueSpec& fan = m.loads[0];
  EXPECT_EQ(fan.torque, -10.0);
  EXPECT_EQ(fan.table_over, LoadTableOver::Speed);
  ASSERT_EQ(fan.table_x.size(), 2u);
  expect_near_rel(fan.table_x[1], 1000.0 * kRpm);
  EXPECT_EQ(fan.table_torque, (std::vector<double>{0.0, -5.0}));
  EXPECT_EQ(fan.drag, 1e-4);
  const LoadTorqueSpec& step = m.loads[1];
  EXPECT_EQ(step.table_over, LoadTableOver::Time);
  EXPECT_EQ(step.table_x, (std::vector<double>{0.0, 0.1, 0.2}));
  EXPECT_EQ(step.torque, 0.0);

  ASSERT_EQ(m.clutches.size(), 1u);
  EXPECT_TRUE(m.clutches[0].node1.empty());  // a brake
  EXPECT_EQ(m.clutches[0].node2, "input.2");
  EXPECT_EQ(m.clutches[0].max_torque, 80.0);
  EXPECT_EQ(m.clutches[0].slip_speed, 0.5);
  EXPECT_EQ(m.clutches[0].engage_time, 0.3);

  ASSERT_EQ(m.virtual_sensors.size(), 2u);
  EXPECT_EQ(m.virtual_sensors[0].component, 1);
  EXPECT_FALSE(m.virtual_sensors[0].direction.has_value());
  EXPECT_FALSE(m.virtual_sensors[0].rotation);
  EXPECT_EQ(m.virtual_sensors[1].component, -1);
  ASSERT_TRUE(m.virtual_sensors[1].direction.has_value());
  expect_near_rel((*m.virtual_sensors[1].direction)[0], 1.0 / std::sqrt(2.0));
  expect_near_rel((*m.virtual_sensors[1].direction)[1], 1.0 / std::sqrt(2.0));
  EXPECT_TRUE(m.virtual_sensors[1].rotation);
}

TEST(DrivetrainKeys, DefaultsAreTheDeclaredOnes) {
  const Model m = parse(R"(
[[contacts]]
name = "c"
node2 = "input.0"
[contacts.law]
stiffness = 1e8
penetration_depth = 1e-5
[[bolts]]
name = "b"
node1 = "housing"
node2 = "input.0"
bolt_stiffness = 1e8
clamp_stiffness = 3e8
[[bushings]]
name = "k"
node2 = "input.1"
kxx = 1.0
[[rolling_bearings]]
name = "r"
node = "input.2"
elements = 8
stiffness_constant = 1e10
pitch_diameter = 0.04
element_diameter = 0.006
[[drivers]]
name = "d"
node = "input.0"
type = "speed"
time = [0.0]
speed_rpm = [1000.0]
[[loads]]
name = "l"
node = "input.1"
[[clutches]]
name = "c"
node1 = "input.1"
node2 = "input.2"
max_torque = 10
)");
  const ContactSpec& c = m.contacts[0];
  EXPECT_TRUE(c.node1.empty());
  EXPECT_EQ(c.direction, (DrivetrainVec3{1.0, 0.0, 0.0}));
  EXPECT_EQ(c.motion, ContactMotion::Translation);
  EXPECT_EQ(c.kind, ContactKind::Stop);
  EXPECT_EQ(c.gap, 0.0);
  EXPECT_EQ(c.law.type, ContactLawKind::Impact);
  EXPECT_EQ(c.law.exponent, 1.5);
  EXPECT_EQ(c.law.max_damping, 0.0);
  EXPECT_FALSE(c.law.clip_tension);

  const BoltSpec& b = m.bolts[0];
  EXPECT_EQ(b.axis, (DrivetrainVec3{0.0, 0.0, 1.0}));
  EXPECT_EQ(b.preload, 0.0);
  EXPECT_EQ(b.load_introduction, 1.0);
  EXPECT_EQ(b.shear_stiffness, 0.0);
  EXPECT_EQ(b.activation_time, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(b.preload_ramp, 0.0);
  EXPECT_EQ(b.inactive_stiffness, 0.0);

  const BushingSpec& k = m.bushings[0];
  EXPECT_EQ(k.x_axis, (DrivetrainVec3{1.0, 0.0, 0.0}));
  EXPECT_EQ(k.z_axis, (DrivetrainVec3{0.0, 0.0, 1.0}));
  EXPECT_EQ(k.stiffness[0], 1.0);
  for (std::size_t i = 1; i < 36; ++i) EXPECT_EQ(k.stiffness[i], 0.0) << i;
  for (double x : k.damping) EXPECT_EQ(x, 0.0);
  for (double x : k.preload) EXPECT_EQ(x, 0.0);
  EXPECT_TRUE(k.tables.empty());

  const RollingBearingSpec& r = m.rolling_bearings[0];
  EXPECT_TRUE(r.housing.empty());
  EXPECT_EQ(r.exponent, 1.5);
  EXPECT_EQ(r.radial_clearance, 0.0);
  EXPECT_EQ(r.axial_clearance, 0.0);
  EXPECT_EQ(r.contact_angle, 0.0);
  EXPECT_EQ(r.cage_angle, 0.0);
  EXPECT_EQ(r.radial_damping, 0.0);

  EXPECT_EQ(m.drivers[0].times, (std::vector<double>{0.0}));
  EXPECT_EQ(m.drivers[0].inertia, 0.0);
  EXPECT_EQ(m.loads[0].torque, 0.0);
  EXPECT_EQ(m.loads[0].table_over, LoadTableOver::None);
  EXPECT_TRUE(m.loads[0].table_x.empty());
  EXPECT_EQ(m.loads[0].drag, 0.0);
  EXPECT_EQ(m.clutches[0].slip_speed, 1e-2);
  EXPECT_EQ(m.clutches[0].engage_time, 0.0);

  // A gear mesh without [gear_meshes.contact] has none; the linear analyses' model is unchanged.
  ASSERT_EQ(m.gear_meshes.size(), 1u);
  EXPECT_FALSE(m.gear_meshes[0].contact.has_value());
}

TEST(DrivetrainKeys, EachLawTypeTakesItsOwnKeys) {
  const Model m = parse(R"(
[[contacts]]
name = "linear"
node2 = "input.0"
[contacts.law]
type = "linear"
stiffness = 1e8
damping = 30
[[contacts]]
name = "hertz"
node2 = "input.1"
[contacts.law]
type = "hertz"
stiffness = 1e10
exponent = 1.1111
damping = 0.2
)");
  const ContactLawSpec& lin = m.contacts[0].law;
  EXPECT_EQ(lin.type, ContactLawKind::Linear);
  EXPECT_EQ(lin.damping, 30.0);
  const ContactLawSpec& hertz = m.contacts[1].law;
  EXPECT_EQ(hertz.type, ContactLawKind::Hertz);
  EXPECT_EQ(hertz.exponent, 1.1111);
  EXPECT_EQ(hertz.damping, 0.2);                      // Hunt-Crossley chi [s/m]
  EXPECT_EQ(hertz.penetration_regularisation, 1e-9);  // the struct's default, unused by Hertz
}

TEST(DrivetrainKeys, GearMeshContactWithAndWithoutItsLaw) {
  const std::string mesh_contact = R"(
[gear_meshes.contact]
gear_pair = "spur"
backlash = 1e-4
vary_stiffness = false
friction = 0.05
[gear_meshes.contact.law]
type = "impact"
stiffness = 2e8
exponent = 1.0
max_damping = 500
penetration_depth = 1e-6
)";
  const Model m = parse(mesh_contact);
  ASSERT_TRUE(m.gear_meshes[0].contact.has_value());
  const MeshContactSpec& c = *m.gear_meshes[0].contact;
  EXPECT_EQ(c.gear_pair, "spur");
  EXPECT_EQ(c.backlash, 1e-4);
  EXPECT_FALSE(c.vary_stiffness);
  EXPECT_EQ(c.friction, 0.05);
  EXPECT_EQ(c.where.line, base_lines() + 2);
  ASSERT_TRUE(c.law.has_value());
  EXPECT_EQ(c.law->type, ContactLawKind::Impact);
  EXPECT_EQ(c.law->stiffness, 2e8);
  EXPECT_EQ(c.law->exponent, 1.0);
  EXPECT_EQ(c.law->max_damping, 500.0);
  EXPECT_EQ(c.law->penetration_depth, 1e-6);

  const Model plain = parse("[gear_meshes.contact]\n");
  ASSERT_TRUE(plain.gear_meshes[0].contact.has_value());
  EXPECT_TRUE(plain.gear_meshes[0].contact->gear_pair.empty());
  EXPECT_TRUE(std::isnan(plain.gear_meshes[0].contact->backlash));  // no back flank
  EXPECT_TRUE(plain.gear_meshes[0].contact->vary_stiffness);
  EXPECT_EQ(plain.gear_meshes[0].contact->friction, 0.0);
  EXPECT_FALSE(plain.gear_meshes[0].contact->law.has_value());  // the maps' law
}

TEST(DrivetrainKeys, OverridesReachTheNewKeys) {
  ModelDocument doc = analyses::parse_document(kBase + R"(
[[bolts]]
name = "b0"
node1 = "housing"
node2 = "input.0"
bolt_stiffness = 1e8
clamp_stiffness = 3e8
[[bolts]]
name = "b1"
node1 = "housing"
node2 = "input.1"
bolt_stiffness = 1e8
clamp_stiffness = 3e8
[[bolts]]
name = "b2"
node1 = "housing"
node2 = "input.2"
bolt_stiffness = 1e8
clamp_stiffness = 3e8
preload = 1000
[[drivers]]
name = "d"
node = "input.0"
type = "speed"
time = [0.0]
speed_rpm = [1000.0]
)",
                                               "model.toml");
  apply_override(doc, "bolts[2].preload=2.5e4");
  apply_override(doc, "drivers[0].speed_rpm=[3000.0]");  // rpm -> rad/s
  // A table the file does not have: the tooth contact of the mesh and its law.
  apply_override(doc, "gear_meshes[0].contact.backlash=2e-4");
  apply_override(doc, "gear_meshes[0].contact.law.stiffness=3e8");
  apply_override(doc, "gear_meshes[0].contact.law.penetration_depth=1e-6");
  const Model m = build_model(doc);
  EXPECT_EQ(m.bolts[2].preload, 2.5e4);
  EXPECT_EQ(m.bolts[1].preload, 0.0);
  expect_near_rel(m.drivers[0].speeds.at(0), 3000.0 * kRpm);
  ASSERT_TRUE(m.gear_meshes[0].contact.has_value());
  EXPECT_EQ(m.gear_meshes[0].contact->backlash, 2e-4);
  ASSERT_TRUE(m.gear_meshes[0].contact->law.has_value());
  EXPECT_EQ(m.gear_meshes[0].contact->law->stiffness, 3e8);

  // A bad value through --set is reported at the assignment.
  ModelDocument bad = doc;
  apply_override(bad, "bolts[2].load_introduction=1.5");
  try {
    (void)build_model(bad);
    FAIL() << "no error for load_introduction = 1.5";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "--set bolts[2].load_introduction=1.5");
    EXPECT_EQ(e.key_path(), "bolts[2].load_introduction");
    EXPECT_NE(e.expected().find("in (0, 1]"), std::string::npos) << e.expected();
  }
}

// ---------------------------------------------------------------------------------------------
// Bad input: file:line:column, key path, expected, found (and hint).

struct ErrorCase {
  const char* name;
  std::string text;  ///< appended to kBase
  int line;          ///< line in the snippet (1 = its first line, the empty one after kBase)
  std::string key;
  std::string expected;
  std::string found;
  std::string hint = {};
};

class DrivetrainErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(DrivetrainErrors, MessageNamesWhereWhatAndWhy) {
  const ErrorCase& c = GetParam();
  const auto e = error_of(c.text);
  ASSERT_TRUE(e.has_value()) << "no error for:\n" << c.text;
  const std::string message = e->what();
  SCOPED_TRACE(message);
  const int line = base_lines() + c.line;
  EXPECT_EQ(e->where().file, "model.toml");
  EXPECT_EQ(e->where().line, line);
  EXPECT_NE(message.find(fmt::format("model.toml:{}:", line)), std::string::npos);
  EXPECT_EQ(e->key_path(), c.key);
  EXPECT_NE(e->expected().find(c.expected), std::string::npos) << "expected: " << e->expected();
  EXPECT_NE(e->found().find(c.found), std::string::npos) << "found: " << e->found();
  EXPECT_NE(e->hint().find(c.hint), std::string::npos) << "hint: " << e->hint();
  EXPECT_NE(message.find(c.expected), std::string::npos);
  EXPECT_NE(message.find(c.found), std::string::npos);
}

const std::string kContactHead = R"(
[[contacts]]
name = "c"
node2 = "input.0"
[contacts.law]
)";

const std::string kBoltBody = R"(bolt_stiffness = 1e8
clamp_stiffness = 3e8
)";

// The first lines of an error case's entry of array `array`: the empty line 1, the header on
// line 2, `name` on line 3 and the node key on line 4; the case's own keys follow from line 5.
std::string head(const std::string& array, const std::string& name, const std::string& node_key,
                 const std::string& node) {
  return fmt::format("\n[[{}]]\nname = \"{}\"\n{} = \"{}\"\n", array, name, node_key, node);
}

// A bushing "k" on input.0 (lines 1-4) without its keys.
const std::string kBushingHead = head("bushings", "k", "node2", "input.0");

// A speed driver "d" on `node` (line 4) at 100 rpm: its type, time and speed on lines 5-7.
std::string speed_driver(const std::string& node) {
  return head("drivers", "d", "node", node) +
         "type = \"speed\"\ntime = [0.0]\nspeed_rpm = [100.0]\n";
}

// A rolling bearing "r" on `node` (line 4) of 8 elements: elements, stiffness_constant and
// pitch_diameter = 0.04 m on lines 5-7, then `rest` from line 8.
std::string rolling_bearing(const std::string& node,
                            const std::string& rest = "element_diameter = 0.006\n") {
  return head("rolling_bearings", "r", "node", node) +
         "elements = 8\nstiffness_constant = 1e10\npitch_diameter = 0.04\n" + rest;
}

const ErrorCase kCases[] = {
    // --- contacts and laws ---
    {"ContactZeroDirection",
     "\n[[contacts]]\nname = \"c\"\nnode2 = \"input.0\"\ndirection = [0.0, 0.0, "
     "0.0]\n[contacts.law]\nstiffness = 1\npenetration_depth = 1e-5\n",
     5, "contacts[0].direction", "not all zero", "[0, 0, 0]"},
    {"ContactUnknownNode",
     "\n[[contacts]]\nname = \"c\"\nnode2 = \"input.9\"\n[contacts.law]\nstiffness = "
     "1\npenetration_depth = 1e-5\n",
     4, "contacts[0].node2", "a station of shaft 'input'", "\"input.9\""},
    {"ContactSameNodeTwice",
     "\n[[contacts]]\nname = \"c\"\nnode1 = \"input.0\"\nnode2 = \"input.0\"\n[contacts.law]\n"
     "stiffness = 1\npenetration_depth = 1e-5\n",
     5, "contacts[0].node2", "a node other than `node1`", "\"input.0\" again",
     "leave node1 out for an element to ground"},
    {"ContactWithoutLaw", "\n[[contacts]]\nname = \"c\"\nnode2 = \"input.0\"\n", 2,
     "contacts[0].law.stiffness", "the key 'stiffness'", "without it"},
    {"ImpactLawWithoutDepth", kContactHead + "stiffness = 1e8\n", 5,
     "contacts[0].law.penetration_depth", "the key 'penetration_depth'",
     "[contacts.law] with type = \"impact\" table without it"},
    {"LawKeyOfAnotherType", kContactHead + "type = \"linear\"\nstiffness = 1e8\nmax_damping = 5\n",
     8, "contacts[0].law.max_damping",
     "a key of [contacts.law] with type = \"linear\": 'type', 'stiffness', 'tension', 'damping'",
     "the unknown key 'max_damping'", "'max_damping' is a key of type = \"impact\" only"},
    {"HertzExponentBelowOne", kContactHead + "type = \"hertz\"\nstiffness = 1e8\nexponent = 0.5\n",
     8, "contacts[0].law.exponent", ">= 1", "0.5"},
    {"LawStiffnessNotPositive", kContactHead + "type = \"linear\"\nstiffness = 0\n", 7,
     "contacts[0].law.stiffness", "> 0", "0"},
    {"PenaltyNegativeExponent",
     kContactHead + "type = \"penalty\"\nstiffness = 1e8\nrate_exponent = -1\n", 8,
     "contacts[0].law.rate_exponent", ">= 0", "-1"},
    {"UnknownLawType", kContactHead + "type = \"kelvin\"\nstiffness = 1e8\n", 6,
     "contacts[0].law.type", "\"linear\"", "\"kelvin\""},
    {"GapOfAnEndPlay",
     "\n[[contacts]]\nname = \"c\"\nnode2 = \"input.0\"\ntype = \"end_play\"\ngap = 1e-3\n", 6,
     "contacts[0].gap", "a key of [[contacts]] with type = \"end_play\"", "'gap'",
     "'gap' is a key of type = \"stop\" only"},
    {"NegativeBacklash",
     "\n[[contacts]]\nname = \"c\"\nnode2 = \"input.0\"\ntype = \"end_play\"\nbacklash = -1e-3\n",
     6, "contacts[0].backlash", ">= 0", "-0.001"},
    {"DuplicateContactName",
     kContactHead +
         "stiffness = 1\npenetration_depth = 1e-5\n[[contacts]]\nname = \"c\"\n"
         "node2 = \"input.1\"\n[contacts.law]\nstiffness = 1\npenetration_depth = 1e-5\n",
     9, "contacts[1].name", "a name not used by another of [[contacts]]",
     "\"c\", already the name of contacts[0]"},
    // --- bolts ---
    {"BoltWithoutNode2", head("bolts", "b", "node1", "housing") + kBoltBody, 2, "bolts[0].node2",
     "the key 'node2'", "without it"},
    {"BoltOnAMasslessNode",
     head("bolts", "b", "node1", "loose") + "node2 = \"input.0\"\n" + kBoltBody, 4,
     "bolts[0].node1", "a node on a body", "\"loose\", a node without mass that no body holds",
     "[[solids.spiders]]"},
    {"BoltLoadIntroductionAboveOne",
     head("bolts", "b", "node2", "input.0") + "load_introduction = 1.2\n" + kBoltBody, 5,
     "bolts[0].load_introduction", "in (0, 1]", "1.2"},
    {"BoltMissingStiffness", head("bolts", "b", "node2", "input.0"), 2, "bolts[0].bolt_stiffness",
     "the key 'bolt_stiffness'", "without it"},
    // --- bushings ---
    {"BushingAxesNotOrthogonal",
     kBushingHead + "x_axis = [1.0, 0.0, 0.0]\n"
                    "z_axis = [1.0, 0.0, 1.0]\nkxx = 1\n",
     6, "bushings[0].z_axis", "orthogonal to x_axis", "at 45 deg to x_axis"},
    {"BushingMatrixAndKeys",
     kBushingHead +
         "kxx = 1\nstiffness = [[1.0, 0.0, 0.0, "
         "0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0, 0.0, 0.0], [0.0, "
         "0.0, "
         "0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 1.0]]\n",
     6, "bushings[0].stiffness", "only one of (kxx, kyy, kzz, ktxx, ktyy, ktzz) or stiffness",
     "both 'kxx' and 'stiffness'"},
    {"BushingAsymmetricMatrix",
     kBushingHead + "stiffness = [[1.0, 0.5, 0.0, 0.0, 0.0, "
                    "0.0], [0.0, 1.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0, 0.0, 0.0], [0.0, "
                    "0.0, 0.0, 1.0, "
                    "0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 1.0]]\n",
     5, "bushings[0].stiffness", "a symmetric 6x6 matrix", "stiffness[0][1] = 0.5"},
    {"BushingPreloadSize", kBushingHead + "preload = [1.0, 2.0]\n", 5, "bushings[0].preload",
     "6 values", "2 values"},
    {"BushingTableWithoutZero",
     kBushingHead + "[[bushings.tables]]\ndirection = \"x\"\n"
                    "deflection = [0.001, 0.002]\nforce = [1.0, 2.0]\n",
     7, "bushings[0].tables[0].deflection", "a point at deflection 0 with force 0", "without 0",
     "preload"},
    {"BushingTableForceDecreasing",
     kBushingHead + "[[bushings.tables]]\ndirection = \"x\"\n"
                    "deflection = [0.0, 0.002]\nforce = [0.0, -2.0]\n",
     8, "bushings[0].tables[0].force", "non-decreasing", "0 then -2"},
    {"BushingTableLengths",
     kBushingHead + "[[bushings.tables]]\ndirection = \"x\"\n"
                    "deflection = [0.0, 0.002]\nforce = [0.0, 2.0, 3.0]\n",
     8, "bushings[0].tables[0].force", "2 values, one per 'deflection' entry", "3 values"},
    {"BushingTwoTablesOneDirection",
     kBushingHead +
         "[[bushings.tables]]\ndirection = \"rz\"\n"
         "deflection = [0.0, 0.1]\nforce = [0.0, 2.0]\n[[bushings.tables]]\ndirection = \"rz\"\n"
         "deflection = [0.0, 0.1]\nforce = [0.0, 3.0]\n",
     9, "bushings[0].tables[1].direction", "one table per direction", "\"rz\" again"},
    // --- rolling bearings ---
    {"RollingBearingOnANodeWithoutSpin", rolling_bearing("housing"), 4, "rolling_bearings[0].node",
     "a node with a spin axis", "\"housing\", a [[nodes]] entry that does not spin", "spin_of"},
    {"RollingBearingElementTooLarge", rolling_bearing("input.1", "element_diameter = 0.05\n"), 8,
     "rolling_bearings[0].element_diameter", "< pitch_diameter = 0.04 m", "0.05"},
    {"RollingBearingHousingIsTheNode",
     rolling_bearing("input.1", "element_diameter = 0.006\nhousing = \"input.1\"\n"), 4,
     "rolling_bearings[0].node", "a node other than `housing`", "\"input.1\" again"},
    {"RollingBearingExponent",
     rolling_bearing("input.1", "element_diameter = 0.006\nexponent = 3\n"), 9,
     "rolling_bearings[0].exponent", "in [1, 2]", "3"},
    // --- drivers, loads, clutches ---
    {"DriverOnAConstrainedDof", speed_driver("input.4"), 4, "drivers[0].node",
     "a node whose rz is free (not fixed by [[constraints]]), for a driver",
     "\"input.4\", whose rz constraints[0] fixes: a driver on a constrained DOF",
     "remove \"rz\" from constraints[0].dofs"},
    {"DriverOnAShaftWithoutTorsion", speed_driver("output.1"), 4, "drivers[0].node",
     "rotation about its spin axis (rz) is a DOF, for a driver",
     "\"output.1\", whose DOFs are \"lateral\" (no torsion)", "set the `dofs` of shaft \"output\""},
    {"TwoDriversOnOneNode",
     speed_driver("input.0") + "[[drivers]]\nname = \"e\"\nnode = \"input.0\"\ntype = \"motor\"\n"
                               "motor_speed_rpm = [0.0]\nmotor_torque = [1.0]\n",
     10, "drivers[1].node", "a node that no other driver drives",
     "\"input.0\", already driven by drivers[0] (\"d\")"},
    {"DriverSpeedTableLengths",
     head("drivers", "d", "node", "input.0") + "type = \"speed\"\ntime = [0.0, 1.0]\n"
                                               "speed_rpm = [100.0]\n",
     7, "drivers[0].speed_rpm", "2 values, one per 'time' entry", "1 value"},
    {"DriverTimesNotIncreasing",
     head("drivers", "d", "node", "input.0") + "type = \"speed\"\ntime = [0.0, 1.0, 0.5]\n"
                                               "speed_rpm = [1.0, 2.0, 3.0]\n",
     6, "drivers[0].time[2]", "values must increase", "0.5"},
    {"DriverWithoutType", head("drivers", "d", "node", "input.0"), 2, "drivers[0].type",
     "the key 'type'", "without it"},
    {"MotorKeyInASpeedDriver", speed_driver("input.0") + "inertia = 1e-3\n", 8,
     "drivers[0].inertia", "a key of [[drivers]] with type = \"speed\"", "'inertia'",
     "'inertia' is a key of type = \"motor\" only"},
    {"LoadOnANodeWithoutRz", "\n[[loads]]\nname = \"l\"\nnode = \"output.0\"\ntorque = 5\n", 4,
     "loads[0].node", "rz) is a DOF, for a load torque", "\"output.0\""},
    {"LoadTableWithoutAbscissa",
     "\n[[loads]]\nname = \"l\"\nnode = \"input.0\"\ntable_torque = [1.0, 2.0]\n", 5,
     "loads[0].table_torque", "speed_rpm = [...]", "table_torque without speed_rpm or time"},
    {"LoadTableOverSpeedAndTime",
     "\n[[loads]]\nname = \"l\"\nnode = \"input.0\"\nspeed_rpm = [0.0, 1.0]\ntime = [0.0, "
     "1.0]\ntable_torque = [1.0, 2.0]\n",
     6, "loads[0].time", "only one of speed_rpm or time", "both 'speed_rpm' and 'time'"},
    {"LoadAbscissaWithoutTorques",
     "\n[[loads]]\nname = \"l\"\nnode = \"input.0\"\ntime = [0.0, 1.0]\n", 2,
     "loads[0].table_torque", "table_torque = [...]", "'time' without 'table_torque'"},
    {"ClutchSameNodes",
     "\n[[clutches]]\nname = \"c\"\nnode1 = \"input.1\"\nnode2 = \"input.1\"\nmax_torque = 5\n", 5,
     "clutches[0].node2", "a node other than `node1`", "\"input.1\" again"},
    {"BrakeOnANodeWithoutRz",
     "\n[[clutches]]\nname = \"c\"\nnode2 = \"output.1\"\nmax_torque = 5\n", 4, "clutches[0].node2",
     "for a brake", "\"output.1\""},
    {"ClutchSlipSpeedZero",
     "\n[[clutches]]\nname = \"c\"\nnode2 = \"input.1\"\nmax_torque = 5\nslip_speed = 0\n", 6,
     "clutches[0].slip_speed", "> 0", "0"},
    // --- virtual sensors, gear mesh contact ---
    {"SensorWithDofAndDirection",
     "\n[[virtual_sensors]]\nname = \"s\"\nnode = \"housing\"\ndof = \"ux\"\ndirection = [1.0, "
     "0.0, 0.0]\n",
     6, "virtual_sensors[0].direction", "only one of dof or (direction, rotation)",
     "both 'dof' and 'direction'"},
    {"SensorWithNeitherDofNorDirection",
     "\n[[virtual_sensors]]\nname = \"s\"\nnode = \"housing\"\n", 2, "virtual_sensors[0]",
     "one of dof or (direction, rotation)", "none of them"},
    {"SensorUnknownNode", "\n[[virtual_sensors]]\nname = \"s\"\nnode = \"housng\"\ndof = \"ux\"\n",
     4, "virtual_sensors[0].node", "a node", "\"housng\"", "did you mean 'housing'?"},
    {"MeshContactUnknownGearPair", "\n[gear_meshes.contact]\ngear_pair = \"spurr\"\n", 3,
     "gear_meshes[0].contact.gear_pair", "a gear pair name ('spur')", "\"spurr\"",
     "did you mean 'spur'?"},
    {"MeshContactLawOfAnotherType",
     "\n[gear_meshes.contact]\n[gear_meshes.contact.law]\ntype = \"hertz\"\nstiffness = "
     "1e9\npenetration_depth = 1e-6\n",
     6, "gear_meshes[0].contact.law.penetration_depth", "'exponent'",
     "the unknown key 'penetration_depth'", "type = \"impact\" only"},
    {"MeshContactFrictionAboveOne", "\n[gear_meshes.contact]\nfriction = 1.5\n", 3,
     "gear_meshes[0].contact.friction", "in [0, 1]", "1.5"},
};

INSTANTIATE_TEST_SUITE_P(Cases, DrivetrainErrors, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<ErrorCase>& p) {
                           return std::string(p.param.name);
                         });

}  // namespace
}  // namespace geardyn::model
