// Solids joined to the rotor: model keys ([[solids.spiders]], solid sensors), what bad input
// reports, and that the analyses work on a system with generalised coordinates.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cstdio>
#include <string>

#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/transient.hpp"
#include "geardyn/assembly/solid_coupling.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/model/parse.hpp"
#include "spider_test_support.hpp"

namespace geardyn {
namespace {

using test::spider_plate;
using test::spider_rotor;

model::Model parse(const std::string& text) { return analyses::parse_model(text, "spider.toml"); }

// The InputError thrown by f, or a failure.
template <class F>
InputError input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError({}, "", "", "");
}

TEST(SpiderModel, KeysAreRead) {
  const model::Model m = parse(spider_rotor(spider_plate("steel", 7, "averaging") + R"(
[[sensors]]
name = "rim_z"
solid = "disk"
node_set = "outer"
dof = "uz"
)"));
  ASSERT_EQ(m.solids.size(), 1u);
  const model::Solid& s = m.solids[0];
  EXPECT_EQ(s.coupling_modes, 7);
  ASSERT_EQ(s.spiders.size(), 1u);
  EXPECT_EQ(s.spiders[0].node_set, "inner");
  EXPECT_EQ(s.spiders[0].node, "s.2");
  EXPECT_EQ(s.spiders[0].kind, model::SpiderKind::Averaging);
  ASSERT_EQ(m.sensors.size(), 1u);
  EXPECT_EQ(m.sensors[0].node, "disk/outer");
  EXPECT_EQ(m.sensors[0].dof, model::Component::Uz);
}

TEST(SpiderModel, ParserErrors) {
  // A spider to a rotor node that does not exist.
  {
    std::string text = spider_rotor(spider_plate("steel", 5));
    text.replace(text.find("node = \"s.2\""), 12, "node = \"s.9\"");
    const InputError e = input_error([&] { (void)parse(text); });
    EXPECT_EQ(e.key_path(), "solids[0].spiders[0].node");
    EXPECT_NE(e.expected().find("\"s.0\" to \"s.4\""), std::string::npos) << e.what();
  }
  // A sensor on a solid that is not joined to the rotor.
  {
    const InputError e = input_error([] {
      (void)parse(spider_rotor(R"(
[[solids]]
name = "free"
type = "annular_plate"
material = "steel"
inner_radius = 0.02
outer_radius = 0.15
thickness = 0.01
[[sensors]]
name = "x"
solid = "free"
node_set = "outer"
dof = "ux"
)"));
    });
    EXPECT_EQ(e.key_path(), "sensors[0].solid");
    EXPECT_NE(e.found().find("no spiders"), std::string::npos) << e.what();
  }
  // A solid sensor measures translations only.
  {
    const InputError e = input_error([] {
      (void)parse(spider_rotor(spider_plate("steel", 5) + R"(
[[sensors]]
name = "x"
solid = "disk"
node_set = "outer"
dof = "rx"
)"));
    });
    EXPECT_EQ(e.key_path(), "sensors[0].dof");
  }
  // A node and a solid in one sensor.
  EXPECT_THROW((void)parse(spider_rotor(spider_plate("steel", 5) + R"(
[[sensors]]
name = "x"
node = "s.1"
solid = "disk"
node_set = "outer"
dof = "ux"
)")),
               InputError);
  // Spiders need the whole body, not a sector.
  {
    std::string text = spider_rotor(spider_plate("steel", 5));
    text.replace(text.find("coupling_modes"), 0, "sectors = 4\n");
    const InputError e = input_error([&] { (void)parse(text); });
    EXPECT_EQ(e.key_path(), "solids[0].sectors");
  }
  // A reduced component has no mesh to join: the key is not allowed there.
  EXPECT_THROW((void)parse(spider_rotor(R"(
[[solids]]
name = "r"
type = "reduced"
reduced_file = "r.h5"
  [[solids.spiders]]
  node_set = "inner"
  node = "s.2"
)")),
               InputError);
  // A spider needs a rotor: a model of solids only has no node to join.
  {
    const InputError e = input_error([] {
      (void)parse(R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 2.1e11
poisson_ratio = 0.3
density = 7800.0
)" + spider_plate("steel", 5));
    });
    EXPECT_EQ(e.key_path(), "solids[0].spiders[0].node");
  }
}

TEST(SpiderCoupling, UnknownNodeSetListsTheSets) {
  const model::Model m = parse(spider_rotor(spider_plate("steel", 5, "rigid", "hub")));
  const InputError e = input_error([&] { (void)assembly::build_system(m); });
  EXPECT_EQ(e.key_path(), "solids[0].spiders[0].node_set");
  for (const char* set : {"\"inner\"", "\"outer\"", "\"top\"", "\"bottom\""})
    EXPECT_NE(e.expected().find(set), std::string::npos) << e.what();
  EXPECT_EQ(e.found(), "\"hub\"");
}

TEST(SpiderCoupling, UnknownSensorSetListsTheSets) {
  const model::Model m = parse(spider_rotor(spider_plate("steel", 5) + R"(
[[sensors]]
name = "x"
solid = "disk"
node_set = "rim"
dof = "ux"
)"));
  const InputError e = input_error([&] { (void)assembly::build_system(m); });
  EXPECT_EQ(e.key_path(), "sensors[0].node_set");
  EXPECT_NE(e.expected().find("\"outer\""), std::string::npos) << e.what();
}

// A sensor on the rigidly joined set moves with the rotor node: it is not a motion of its own.
TEST(SpiderCoupling, SensorOnARigidlyJoinedSetIsRefused) {
  const model::Model m = parse(spider_rotor(spider_plate("steel", 5) + R"(
[[sensors]]
name = "x"
solid = "disk"
node_set = "inner"
dof = "ux"
)"));
  const InputError e = input_error([&] { (void)assembly::build_system(m); });
  EXPECT_EQ(e.key_path(), "sensors[0].node_set");
  EXPECT_NE(e.hint().find("rotor node"), std::string::npos) << e.what();
}

// Joints that do not hold the body: a rigid spider on one node (no rotational stiffness at the
// reference point), and two averaging spiders on the same set (the second fixes nothing new).
TEST(SpiderCoupling, JointsThatDoNotHold) {
  model::Model m = parse(spider_rotor(spider_plate("steel", 5)));
  assembly::SolidComponent built = assembly::build_solid(m, m.solids[0]);
  built.mesh.node_sets["one"] = {built.mesh.node_sets.at("outer").front()};
  m.solids[0].spiders[0].node_set = "one";
  {
    // The reference point's rotation about the line to the node is free: a mechanism, named.
    const InputError e = input_error([&] { (void)assembly::couple_solid(m, m.solids[0], built); });
    EXPECT_EQ(e.key_path(), "solids[0].spiders");
    std::printf("%s\n", e.what());
  }
  m.solids[0].spiders[0].node_set = "outer";
  m.solids[0].spiders[0].kind = model::SpiderKind::Averaging;
  m.solids[0].spiders.push_back(m.solids[0].spiders[0]);
  {
    const InputError e = input_error([&] { (void)assembly::couple_solid(m, m.solids[0], built); });
    EXPECT_EQ(e.key_path(), "solids[0].spiders[1].node_set");
    std::printf("%s\n", e.what());
  }
}

// More modes than the solid has interior DOFs is an error, not a silent cap.
TEST(SpiderCoupling, TooManyModes) {
  const model::Model m = parse(spider_rotor(spider_plate("steel", 10000)));
  const InputError e = input_error([&] { (void)assembly::build_system(m); });
  EXPECT_EQ(e.key_path(), "solids[0].coupling_modes");
}

// An averaging spider alone holds a free plate: six constraints fix its rigid-body motion, the
// plate keeps its flexibility. The system is positive definite (the plate's rigid motions are
// the rotor node's) and Ip of the plate gives the gyroscopic matrix.
TEST(SpiderCoupling, AveragingSpiderAloneHoldsAFreePlate) {
  const model::Model m = parse(spider_rotor(spider_plate("steel", 6, "averaging")));
  const fe::LinearSystem s = assembly::build_system(m);
  EXPECT_EQ(s.dofs.num_generalized(), 6);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(s.K);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  EXPECT_TRUE((ldlt.vectorD().array() > 0.0).all());
  const int rx = s.dofs.dof(s.dofs.node_index("s.2"), model::Component::Rx);
  const int ry = s.dofs.dof(s.dofs.node_index("s.2"), model::Component::Ry);
  const double Ip = test::plate_inertia().polar;
  // G(rx, ry) = Ip of the plate plus the shaft's own small share.
  EXPECT_NEAR(s.G.coeff(rx, ry), Ip, 0.02 * Ip);
  EXPECT_NEAR(s.G.coeff(ry, rx), -s.G.coeff(rx, ry), 1e-12 * Ip);
}

// The analyses on a system with generalised coordinates and a solid sensor point: modal tables
// (node DOFs only in the shapes), mode kinds, and a harmonic response at the solid sensor.
TEST(SpiderCoupling, AnalysesRunWithSolidSensors) {
  const model::Model m = parse(spider_rotor(spider_plate("steel", 10) + R"(
[[sensors]]
name = "rim_z"
solid = "disk"
node_set = "outer"
dof = "uz"

[[sensors]]
name = "hub_x"
node = "s.2"
dof = "ux"
)"));
  const fe::LinearSystem s = assembly::build_system(m);
  const int rim = s.dofs.find_node("disk/outer");
  ASSERT_GE(rim, 0);
  EXPECT_GE(s.dofs.dof(rim, model::Component::Uz), 0);
  EXPECT_EQ(s.dofs.dof(rim, model::Component::Rx), -1);
  EXPECT_NEAR(s.dofs.node(rim).position.norm(), 0.0, 1e-12);  // centroid of the outer ring

  analyses::ModalSettings ms;
  ms.n_modes = 12;
  ms.speed = 300.0;
  const analyses::ModalResult r =
      analyses::run_modal(m, ms, analyses::Context("modal").with_system(&s));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const AnalysisOutput out =
      analyses::modal_output(m, ms, r, analyses::Context("modal").with_system(&s));
  const bool any_plate_mode =
      std::any_of(r.undamped.begin(), r.undamped.end(),
                  [](const analyses::Mode& mode) { return mode.families.body > 0.5; });
  EXPECT_TRUE(any_plate_mode);
  const auto shapes = std::find_if(out.tables.begin(), out.tables.end(),
                                   [](const Table& t) { return t.name == "mode_shapes"; });
  ASSERT_NE(shapes, out.tables.end());

  analyses::HarmonicSettings hs;
  hs.f_min = 2 * 3.14159 * 50;
  hs.f_max = 2 * 3.14159 * 2000;
  hs.n_points = 40;
  hs.adaptive = false;
  hs.input_node = "s.2";
  hs.input_dof = model::Component::Uz;
  const analyses::FrfResult frf =
      analyses::run_harmonic(m, hs, analyses::Context("harmonic").with_system(&s));
  ASSERT_EQ(frf.sensors.size(), 2u);
  EXPECT_EQ(frf.sensors[0].name, "rim_z");
  EXPECT_GT(frf.displacement.col(0).cwiseAbs().maxCoeff(), 0.0);
}

// Time integration of a system with a joined solid: an unbalance at the node spinning a stiff
// plate; the mean lateral motion of its outer ring (centroid on the axis) follows the node.
TEST(SpiderCoupling, TransientWithASolidSensor) {
  const model::Model m = parse(spider_rotor(spider_plate("stiff", 4) + R"(
[[unbalances]]
node = "s.2"
mass_eccentricity = 1e-4

[[sensors]]
name = "rim_x"
solid = "disk"
node_set = "outer"
dof = "ux"

[[sensors]]
name = "hub_x"
node = "s.2"
dof = "ux"
)"));
  const fe::LinearSystem s = assembly::build_system(m);
  analyses::TransientSettings ts;
  ts.speed = 500.0;
  ts.duration = 0.05;
  ts.time_step = 1e-4;
  const analyses::TransientResult r =
      analyses::run_transient(m, ts, analyses::Context("transient").with_system(&s));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.sensor_names.size(), 2u);
  const double hub = r.values.col(1).cwiseAbs().maxCoeff();
  EXPECT_GT(hub, 0.0);
  EXPECT_LT((r.values.col(0) - r.values.col(1)).cwiseAbs().maxCoeff(), 1e-3 * hub);
}

}  // namespace
}  // namespace geardyn
