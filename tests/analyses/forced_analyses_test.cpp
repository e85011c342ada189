// The forced responses wired to the model file (analyses/cyclic_forced_response.hpp,
// gear_forced_response.hpp, damper_ring_response.hpp) against the library calls they stand for:
// what the model file says must reach response::* unchanged; and the scalars they offer.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "geardyn/analyses/cyclic_forced_response.hpp"
#include "geardyn/analyses/damper_ring_response.hpp"
#include "geardyn/analyses/gear_forced_response.hpp"
#include "geardyn/analyses/model_file.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/analyses/tooth_force.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/model/parse.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/response/cyclic_forced_response.hpp"
#include "geardyn/response/rotor_mesh_response.hpp"
#include "support/output_tables.hpp"

namespace geardyn {
namespace {

namespace fs = std::filesystem;
using Complex = std::complex<double>;
constexpr double kTwoPi = units::kTwoPi;
constexpr double kDeg = units::kRadPerDegree;

// ---------------------------------------------------------------------------------------------
// cyclic_forced_response

// A small spur gear blank, one tooth per 22.5 deg sector (16 sectors), linear tetrahedra:
// 216 DOFs per sector, so every mode of a nodal diameter can be summed (dense eigen-solver).
//
//        tooth (excitation node on its +theta flank, pitch radius, mid-face)
//       _/\_
//      |rim |   r = 22 .. 26.6 mm
//      |web |   4 mm thick
//      |hub |   bore r = 6 mm clamped
const std::string kGearModel = R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 206e9
poisson_ratio = 0.3
density = 7850
[[gear_pairs]]
name = "spur"
teeth1 = 16
teeth2 = 30
module = 0.004
face_width = 0.01
profile_shift1 = 0.3
profile_shift2 = -0.3
torque = 50
[[solids]]
name = "gear"
type = "gear_sector"
material = "steel"
sectors = 16
teeth = 16
module = 0.004
pressure_angle_deg = 20
face_width = 0.01
bore_radius = 0.006
hub_radius = 0.012
hub_width = 0.012
web_thickness = 0.004
rim_inner_radius = 0.022
element_size = 0.01
tooth_element_size = 0.008
order = 1
fixed_sets = ["bore"]
)";

std::string cyclic_analysis(long tip_node, const std::string& reduction) {
  return fmt::format(R"(
[[analyses]]
name = "forced"
type = "cyclic_forced_response"
solid = "gear"
pair = "spur"
model = "infinite_inertia"
nodal_diameters = [2, 3]
n_modes = 10000
damping_ratio = 1e-9
sensor_sets = ["excitation"]
sensor_nodes = [{}]
speed_rpm = [1000, 7000, 23000]
{})",
                     tip_node, reduction);
}

/// Complex response of one (h, k) and sensor from the analysis' response table.
Eigen::VectorXcd table_response(const AnalysisOutput& out, const std::string& sensor, int h,
                                int k) {
  for (const Table& t : out.tables) {
    if (t.name != "cyclic_forced_response") continue;
    const std::string base = fmt::format("{}_h{}_k{}", sensor, h, k);
    const auto& a = t.column(base + "_amplitude_m").numbers;
    const auto& p = t.column(base + "_phase_deg").numbers;
    Eigen::VectorXcd u(static_cast<Eigen::Index>(a.size()));
    for (std::size_t i = 0; i < a.size(); ++i)
      u[static_cast<Eigen::Index>(i)] = std::polar(a[i], p[i] * kDeg);
    return u;
  }
  ADD_FAILURE() << "no cyclic_forced_response table";
  return {};
}

/// Runs the cyclic forced response `a` of `m` on the prebuilt `solid` (as the runner does).
AnalysisOutput run_cyclic(const model::Model& m, const model::Analysis& a,
                          const assembly::SolidComponent& solid) {
  assembly::SolidComponents solids;
  solids.emplace("gear", solid);
  analyses::Context context(m, a);
  context.with_solids(&solids);
  const auto& s = a.settings_of<analyses::CyclicForcedResponseSettings>();
  const analyses::CyclicForcedResponseResult r =
      analyses::run_cyclic_forced_response(m, s, context);
  return analyses::cyclic_forced_response_output(m, s, r, context);
}

struct CyclicCase {
  model::Model model;
  assembly::SolidComponent solid;
  long excitation_id = 0, tip_id = 0;
};

CyclicCase cyclic_case(const std::string& reduction) {
  const model::Model base = analyses::parse_model(kGearModel, "gear.toml");
  assembly::SolidComponent solid = assembly::build_solid(base, base.solids.front());
  const long excitation_id =
      solid.mesh.node_ids[static_cast<std::size_t>(solid.mesh.node_sets.at("excitation").front())];
  const long tip_id =
      solid.mesh.node_ids[static_cast<std::size_t>(solid.mesh.node_sets.at("tooth_tip").front())];
  return {analyses::parse_model(kGearModel + cyclic_analysis(tip_id, reduction), "gear.toml"),
          std::move(solid), excitation_id, tip_id};
}

/// The tooth load of order k on the excitation node, as the header of cyclic_forced_response.hpp
/// states it: tangential -e_theta, radial -e_r, axial +z, from the pair's tooth-force harmonic.
std::vector<response::ToothLoad> tooth_loads(const CyclicCase& c, int k) {
  const analyses::PairModel pm = analyses::build_pair_model(c.model, 0);
  analyses::ToothForceOptions o;
  o.model = analyses::MeshForceModel::InfiniteInertia;
  o.speed = 100.0;
  const gear::HarmonicComponents f =
      analyses::tooth_force_over_revolution(pm, o, "test").components({k}).front();
  const int node = c.solid.mesh.node_sets.at("excitation").front();
  const Eigen::Vector3d x = c.solid.mesh.coords[static_cast<std::size_t>(node)];
  const Eigen::Vector3d e_r = Eigen::Vector3d(x.x(), x.y(), 0.0).normalized();
  const Eigen::Vector3d e_theta = Eigen::Vector3d::UnitZ().cross(e_r);
  response::ToothLoad l;
  l.node_id = c.excitation_id;
  l.force = f.tangential * (-e_theta).cast<Complex>() + f.radial * (-e_r).cast<Complex>() +
            f.axial * Eigen::Vector3d::UnitZ().cast<Complex>();
  return {l};
}

std::vector<response::CyclicSensor> sensors(const CyclicCase& c) {
  std::vector<response::CyclicSensor> out;
  for (int comp = 0; comp < 3; ++comp)
    out.push_back(
        {fmt::format("excitation_{}", model::kComponentNames[comp]), c.excitation_id, comp});
  for (int comp = 0; comp < 3; ++comp)
    out.push_back(
        {fmt::format("node{}_{}", c.tip_id, model::kComponentNames[comp]), c.tip_id, comp});
  return out;
}

double compare(const AnalysisOutput& out, const std::vector<response::CyclicSensor>& sensors, int h,
               int k, const Eigen::MatrixXcd& reference) {
  double worst = 0.0;
  for (std::size_t s = 0; s < sensors.size(); ++s) {
    const Eigen::VectorXcd u = table_response(out, sensors[s].name, h, k);
    worst =
        std::max(worst, (u - reference.col(static_cast<Eigen::Index>(s))).cwiseAbs().maxCoeff());
  }
  return worst / reference.cwiseAbs().maxCoeff();
}

// Oracle: the direct sparse solve of the sector (response::cyclic_direct_response), undamped, for
// the loads the model file implies. The analysis sums every mode of the nodal diameter with
// zeta = 1e-9, which is the same solution to the eigen-solver's accuracy (backward error
// ~1e-13, amplified by at most 1 / |1 - (k W / w_r)^2| ~ 1e2 at these speeds) plus the damping
// term O(zeta) = 1e-9: 1e-7 relative to the largest response is a safe bound, and far below any
// wiring error (a wrong direction, order, node or sign changes the response by O(1)).
TEST(ForcedWiring, CyclicModelFileEqualsDirectSectorSolve) {
  const CyclicCase c = cyclic_case("");
  const AnalysisOutput out = run_cyclic(c.model, c.model.analyses.front(), c.solid);
  ASSERT_EQ(out.status, Status::Ok) << out.message;
  cyclic::InterfaceOptions io;
  io.n_sectors = 16;
  const cyclic::CyclicSector sector(c.solid.dofs(), cyclic::find_interfaces(c.solid.dofs(), io));
  Eigen::VectorXd speeds(3);
  speeds << 1000, 7000, 23000;
  speeds *= kTwoPi / 60.0;
  const Eigen::SparseMatrix<double> none;
  for (const auto& [h, k] : std::vector<std::pair<int, int>>{{2, 2}, {2, 14}, {3, 3}, {3, 13}}) {
    const Eigen::MatrixXcd reference =
        response::cyclic_direct_response(c.solid.stiffness(), c.solid.mass(), none, sector, h, k,
                                         tooth_loads(c, k), sensors(c), speeds);
    const double error = compare(out, sensors(c), h, k, reference);
    std::printf("h = %d, k = %d: largest difference %.2e of the largest response %.3e m\n", h, k,
                error, reference.cwiseAbs().maxCoeff());
    EXPECT_LT(error, 1e-7) << "h = " << h << ", k = " << k;
  }
}

// groove_element_size meshes the groove and ring finer than the teeth (it sets how many contact
// pairs a damper ring has) and leaves the teeth alone: the contact faces get more nodes, the tooth
// tip keeps its count. Without it the groove takes tooth_element_size.
TEST(ForcedWiring, GrooveElementSizeRefinesTheGrooveOnly) {
  const std::string groove =
      "groove = true\ngroove_position = 0.0035\ngroove_width = 0.0028\ngroove_depth = 0.0015\n"
      "ring_width = 0.002\nring_thickness = 0.0015\nring_material = \"steel\"\n";
  auto solid_with = [&](const std::string& extra) {
    std::string text = kGearModel;
    const std::string at = "order = 1\n";
    text.insert(text.find(at), groove + extra);
    const model::Model m = analyses::parse_model(text, "gear.toml");
    return assembly::build_solid(m, m.solids.front());
  };
  const assembly::SolidComponent coarse = solid_with("");
  const assembly::SolidComponent fine = solid_with("groove_element_size = 0.001\n");
  const auto count = [](const assembly::SolidComponent& c, const char* set) {
    return c.mesh.node_sets.at(set).size();
  };
  EXPECT_GT(count(fine, "ring_contact"), 2 * count(coarse, "ring_contact"));
  EXPECT_EQ(count(fine, "ring_contact"), count(fine, "groove_contact"));
  EXPECT_EQ(count(fine, "tooth_tip"), count(coarse, "tooth_tip"));
  EXPECT_NE(fine.description, coarse.description);
}

// Craig-Bampton: the analysis keeps the interfaces, the excitation and the sensor nodes as
// masters (docs/theory.md §9) and sums every mode of the reduced sector. Oracle: the direct solve
// of the same reduced sector (masters as documented, 12 fixed-interface modes), on which loads and
// sensors are physical DOFs; same tolerance argument as above.
TEST(ForcedWiring, CyclicCraigBamptonKeepsExcitationAndSensorsAsMasters) {
  const CyclicCase c = cyclic_case("reduction = \"craig_bampton\"\nreduced_modes = 12");
  const AnalysisOutput out = run_cyclic(c.model, c.model.analyses.front(), c.solid);
  ASSERT_EQ(out.status, Status::Ok) << out.message;
  cyclic::InterfaceOptions io;
  io.n_sectors = 16;
  const cyclic::SectorInterfaces faces = cyclic::find_interfaces(c.solid.dofs(), io);
  std::vector<long> ids;
  for (const auto& p : faces.pairs) {
    ids.push_back(p.left_node_id);
    ids.push_back(p.right_node_id);
  }
  ids.push_back(c.excitation_id);
  ids.push_back(c.tip_id);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  reduce::CraigBamptonOptions o;
  o.n_modes = 12;
  const reduce::ReducedComponent cb =
      reduce::craig_bampton(c.solid.stiffness(), c.solid.mass(), c.solid.dofs(),
                            reduce::select_dofs(c.solid.dofs(), ids), o);
  const std::vector<solid::DofInfo> dofs = cb.reduced_dofs();
  const cyclic::CyclicSector sector(dofs, cyclic::find_interfaces(dofs, io));
  Eigen::VectorXd speeds(3);
  speeds << 1000, 7000, 23000;
  speeds *= kTwoPi / 60.0;
  const Eigen::SparseMatrix<double> K = cb.K.sparseView(), M = cb.M.sparseView(), none;
  for (const auto& [h, k] : std::vector<std::pair<int, int>>{{2, 14}, {3, 3}}) {
    const Eigen::MatrixXcd reference = response::cyclic_direct_response(
        K, M, none, sector, h, k, tooth_loads(c, k), sensors(c), speeds);
    const double error = compare(out, sensors(c), h, k, reference);
    std::printf("Craig-Bampton, h = %d, k = %d: largest difference %.2e\n", h, k, error);
    EXPECT_LT(error, 1e-7) << "h = " << h << ", k = " << k;
  }
}

TEST(ForcedWiring, CyclicInputErrorsNameTheKey) {
  const model::Model base = analyses::parse_model(kGearModel, "gear.toml");
  const assembly::SolidComponent solid = assembly::build_solid(base, base.solids.front());
  auto expect_key = [&](const std::string& analysis, const std::string& key) {
    try {
      const model::Model m = analyses::parse_model(kGearModel + analysis, "gear.toml");
      assembly::SolidComponents solids;
      solids.emplace("gear", solid);
      analyses::check_inputs(m, solids);
      ADD_FAILURE() << "no error for " << key;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key_path(), key) << e.what();
    }
  };
  const std::string head = R"(
[[analyses]]
name = "forced"
type = "cyclic_forced_response"
solid = "gear"
speed_rpm = [1000]
q_factor = 30
)";
  expect_key(head + "force_amplitude = 1.0\nsensor_sets = [\"rim\"]\n",
             "analyses[0].sensor_sets[0]");
  expect_key(head + "force_amplitude = 1.0\nsensor_nodes = [999999]\n",
             "analyses[0].sensor_nodes[0]");
  expect_key(head +
                 "force_amplitude = 1.0\nsensor_sets = [\"excitation\"]\n"
                 "excitation_set = \"bore\"\n",
             "analyses[0].excitation_set");
  expect_key(head +
                 "force_amplitude = 1.0\nsensor_sets = [\"excitation\"]\n"
                 "sensor_components = [\"rx\"]\n",
             "analyses[0].sensor_components");
  // The parser: k = 5 is not +-2 (mod 16); one tooth per sector with a gear pair; the damping.
  auto expect_parse = [&](const std::string& analysis, const std::string& key) {
    try {
      (void)analyses::parse_model(kGearModel + analysis, "gear.toml");
      ADD_FAILURE() << "no error for " << key;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key_path(), key) << e.what();
    }
  };
  expect_parse(head +
                   "force_amplitude = 1.0\nsensor_sets = [\"excitation\"]\n"
                   "nodal_diameters = [2]\nengine_orders = [2, 5]\n",
               "analyses[0].engine_orders[1]");
  expect_parse(head +
                   "force_amplitude = [1.0, 2.0]\nsensor_sets = [\"excitation\"]\n"
                   "engine_orders = [2]\n",
               "analyses[0].force_amplitude");
  // Neither pair nor force_amplitude: reported at the analysis table.
  expect_parse(head + "sensor_sets = [\"excitation\"]\n", "analyses[0]");
  expect_parse(head + "pair = \"spur\"\nsensor_sets = [\"excitation\"]\n",
               "analyses[0].harmonics_rpm");
}

const Table& table_named(const AnalysisOutput& out, const std::string& name) {
  return geardyn::test::table(out, name);
}

// Section 7 of the issue: a measured curve overlaid and compared. The "measurement" here is the
// computed ND 2 / EO 14 curve of a 10 N force times 0.5: a linear model must then report the
// same peak speed and Q, an amplitude mismatch of (1 - 0.5) / 0.5 = +100 %, a force scale of
// 0.5 and an implied force of 5 N, and after scaling reproduce the measured curve. Tolerances:
// the measured file holds 12 significant digits; the peak estimates of both curves use the
// same samples, so they agree to that (1e-9 relative is loose).
TEST(ForcedWiring, MeasuredCurveIsComparedAndTheForceScaled) {
  const fs::path dir = fs::path(GEARDYN_BINARY_DIR) / "tests" / "forcedan" / "measured";
  fs::create_directories(dir);
  const model::Model base = analyses::parse_model(kGearModel, (dir / "gear.toml").string());
  const assembly::SolidComponent solid = assembly::build_solid(base, base.solids.front());
  auto analysis = [](const std::string& speeds, const std::string& extra) {
    return fmt::format(R"(
[[analyses]]
name = "forced"
type = "cyclic_forced_response"
solid = "gear"
force_amplitude = 10.0
engine_orders = [14]
q_factor = 30
sensor_sets = ["excitation"]
sensor_components = ["uz"]
{}
{})",
                       speeds, extra);
  };
  auto run_model = [&](const std::string& text) {
    const model::Model m = analyses::parse_model(text, (dir / "gear.toml").string());
    assembly::SolidComponents solids;
    solids.emplace("gear", solid);
    analyses::check_inputs(m, solids);
    return run_cyclic(m, m.analyses.front(), solid);
  };
  // Where the first ND 2 mode meets EO 14.
  const AnalysisOutput wide = run_model(kGearModel + analysis("speed_rpm = [1000]", ""));
  const double w1 = table_named(wide, "cyclic_resonances").column("resonance_speed_rpm").numbers[0];
  const std::string speeds = fmt::format(
      "speed_start_rpm = {}\nspeed_stop_rpm = {}\nspeed_count = 201", 0.9 * w1, 1.1 * w1);
  const AnalysisOutput plain = run_model(kGearModel + analysis(speeds, ""));
  const Table& response = table_named(plain, "cyclic_forced_response");
  const auto& rpm = response.column("speed_rpm").numbers;
  const auto& amp = response.column("excitation_uz_h2_k14_amplitude_m").numbers;
  {
    std::ofstream csv(dir / "measured.csv");
    csv << "# half the computed response\nspeed_rpm, amplitude_um\n";
    for (std::size_t i = 0; i < rpm.size(); ++i)
      csv << fmt::format("{:.12g}, {:.12g}\n", rpm[i], 0.5e6 * amp[i]);
  }
  const AnalysisOutput out =
      run_model(kGearModel + analysis(speeds,
                                      "measured_file = \"measured.csv\"\nmeasured_engine_order = "
                                      "14\nscale_to_measured = true"));
  ASSERT_EQ(out.status, Status::Ok) << out.message;
  const Table& cmp = table_named(out, "comparison");
  ASSERT_EQ(cmp.rows(), 1u);
  EXPECT_NEAR(cmp.column("x_mismatch_pct").numbers[0], 0.0, 1e-7);
  EXPECT_NEAR(cmp.column("amplitude_mismatch_pct").numbers[0], 100.0, 1e-7);
  EXPECT_NEAR(cmp.column("q_mismatch_pct").numbers[0], 0.0, 1e-7);
  const Table& scaling = table_named(out, "force_scaling");
  EXPECT_NEAR(scaling.column("scale").numbers[0], 0.5, 1e-9);
  EXPECT_NEAR(scaling.column("implied_force_n").numbers[0], 5.0, 1e-8);
  const auto& scaled =
      table_named(out, "cyclic_forced_response").column("excitation_uz_h2_k14_amplitude_m").numbers;
  for (std::size_t i = 0; i < amp.size(); ++i) EXPECT_NEAR(scaled[i], 0.5 * amp[i], 1e-9 * amp[i]);
}

// ---------------------------------------------------------------------------------------------
// gear_forced_response on examples/geared_rotor_hcf (a 40 / 36 spiral bevel mesh)

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// STE e(theta) = e0 (1 - a cos theta) over one mesh cycle (theta = 2 pi x mesh fraction). Then
// k = F_s / e and the blocked force F_s k / k_mean = F_s sqrt(1 - a^2) / (1 - a cos theta)
//   = F_s (1 + 2 sum_p r^p cos p theta),  r = (1 - sqrt(1 - a^2)) / a
// (the Poisson-kernel series, e.g. Gradshteyn & Ryzhik 1.447.3), so the mesh-order harmonic
// is F_p = 2 F_s r^p with zero phase.
constexpr double kSteMean = 20e-6;  // [m]
constexpr double kSteFluctuation = 0.1;
constexpr int kSteRows = 512;

TEST(ForcedWiring, RotorModelFileEqualsLibraryAndAnalyticBlockedForce) {
  const fs::path dir = fs::path(GEARDYN_BINARY_DIR) / "tests" / "forcedan" / "rotor";
  fs::create_directories(dir);
  {
    std::ofstream ste(dir / "ste.csv");
    ste << "angle_deg, ste_um\n";
    for (int j = 0; j < kSteRows; ++j) {
      const double u = static_cast<double>(j) / kSteRows;
      ste << fmt::format("{:.12g}, {:.12g}\n", 9.0 * u,
                         1e6 * kSteMean * (1.0 - kSteFluctuation * std::cos(kTwoPi * u)));
    }
  }
  const std::string text =
      read_text(fs::path(GEARDYN_SOURCE_DIR) / "examples" / "geared_rotor_hcf" / "model.toml") +
      R"(
[[gear_pairs]]
name = "central"
type = "spiral_bevel"
teeth1 = 40
teeth2 = 36
module = 0.003
face_width = 0.02
helix_angle_deg = 35
hand = "left"
torque = 300
ste_file = "ste.csv"

[[analyses]]
name = "mesh_given"
type = "gear_forced_response"
force_amplitude = [100.0, 40.0]
speed_rpm = [3000, 9000, 20000, 36900]
n_modes = 20

[[analyses]]
name = "mesh_pair"
type = "gear_forced_response"
pair = "central"
max_mesh_order = 3
speed_rpm = [3000, 9000, 20000, 36900]
n_modes = 20
)";
  const model::Model m = analyses::parse_model(text, (dir / "model.toml").string());
  analyses::check_inputs(m, {});
  const fe::LinearSystem system = assembly::build_system(m);

  // The blocked force of the pair: analytic series (tolerance: the mesh model evaluates k at
  // the 512 samples, exact; k_mean is the time mean of F_s / e over the linearly interpolated
  // STE, within O((2 pi / 512)^2 a) ~ 1e-5 of the sample mean the series assumes).
  const double fs_n = analyses::build_pair_model(m, 0).static_force_n;
  const double r = (1.0 - std::sqrt(1.0 - kSteFluctuation * kSteFluctuation)) / kSteFluctuation;
  const std::vector<Complex> f =
      analyses::blocked_mesh_force_harmonics(analyses::build_pair_model(m, 0), 3);
  for (int p = 1; p <= 3; ++p) {
    const double expected = 2.0 * fs_n * std::pow(r, p);
    EXPECT_NEAR(std::abs(f[static_cast<std::size_t>(p - 1)]), expected, 1e-4 * expected) << p;
    EXPECT_NEAR(std::arg(f[static_cast<std::size_t>(p - 1)]), 0.0, 1e-6) << p;
  }

  // Each analysis against the library call with the forces it states (same computation: only
  // round-off of the CSV-free path, 1e-12).
  for (const model::Analysis& a : m.analyses) {
    const auto* s = a.settings_as<analyses::GearForcedResponseSettings>();
    if (s == nullptr) continue;
    const analyses::Context context = analyses::Context(m, a).with_system(&system);
    const AnalysisOutput out = analyses::gear_forced_response_output(
        m, *s, analyses::run_gear_forced_response(m, *s, context), context);
    ASSERT_EQ(out.status, Status::Ok) << out.message;
    response::RotorForcedSettings rs;
    rs.gear_mesh = "central_bevel_pair";
    if (s->pair.empty()) {
      rs.harmonics = {{1, Complex(100.0, 0.0)}, {2, Complex(40.0, 0.0)}};
    } else {
      for (int p = 1; p <= 3; ++p) rs.harmonics.push_back({p, f[static_cast<std::size_t>(p - 1)]});
    }
    rs.sensors = response::rotor_sensors(m, system);
    rs.speeds = Eigen::Map<const Eigen::VectorXd>(s->speeds.data(),
                                                  static_cast<Eigen::Index>(s->speeds.size()));
    rs.n_modes = 20;
    const response::RotorForcedResult ref = response::run_mesh_forced_response(m, system, rs);
    const Table reference = ref.response_table();
    const Table* table = nullptr;
    for (const Table& t : out.tables)
      if (t.name == reference.name) table = &t;
    ASSERT_NE(table, nullptr) << a.name;
    ASSERT_EQ(table->columns.size(), reference.columns.size()) << a.name;
    for (const Column& col : reference.columns)
      for (std::size_t i = 0; i < col.numbers.size(); ++i)
        EXPECT_NEAR(table->column(col.name).numbers[i], col.numbers[i],
                    1e-12 * std::max(1.0, std::abs(col.numbers[i])))
            << a.name << " " << col.name;
    // The forces table states the amplitudes used.
    for (const Table& t : out.tables) {
      if (t.name != "mesh_order_forces") continue;
      for (std::size_t p = 0; p < rs.harmonics.size(); ++p)
        EXPECT_NEAR(t.column("amplitude_n").numbers[p], std::abs(rs.harmonics[p].amplitude),
                    1e-12 * std::abs(rs.harmonics[p].amplitude));
    }
  }
}

// The measured overlay of gear_forced_response. The "measurement" is the computed response of
// the same analysis doubled, so the comparison is known exactly: peaks at the same speeds
// (mismatch 0), amplitude mismatch (A - 2A) / 2A = -50 %, equal Q, and scale_to_measured must
// find the scale 2 and an implied force of 2 x 100 N. Tolerance 1e-9: the peak search works on
// the same grid for both curves, so only round-off separates them.
TEST(ForcedWiring, RotorResponseAgainstAMeasuredCurve) {
  const fs::path dir = fs::path(GEARDYN_BINARY_DIR) / "tests" / "forcedan" / "rotor_measured";
  fs::create_directories(dir);
  const std::string base =
      read_text(fs::path(GEARDYN_SOURCE_DIR) / "examples" / "geared_rotor_hcf" / "model.toml") +
      R"(
[[analyses]]
name = "mesh"
type = "gear_forced_response"
force_amplitude = [100.0]
speed_start_rpm = 1000
speed_stop_rpm = 40000
speed_count = 400
n_modes = 20
)";
  const model::Model plain = analyses::parse_model(base, (dir / "model.toml").string());
  const fe::LinearSystem system = assembly::build_system(plain);
  auto run = [&](const model::Model& m) {
    const model::Analysis& a = m.analyses.back();
    const auto& s = a.settings_of<analyses::GearForcedResponseSettings>();
    const analyses::Context context = analyses::Context(m, a).with_system(&system);
    return analyses::gear_forced_response_output(
        m, s, analyses::run_gear_forced_response(m, s, context), context);
  };
  const AnalysisOutput reference = run(plain);
  const Table* response = nullptr;
  for (const Table& t : reference.tables)
    if (t.name == "mesh_forced_response") response = &t;
  ASSERT_NE(response, nullptr);
  const std::vector<double>& rpm = response->column("speed_rpm").numbers;
  const std::vector<double>& amplitude = response->column("turbine_x_p1_amplitude_m").numbers;
  {
    std::ofstream csv(dir / "measured.csv");
    csv << "speed_rpm, amplitude_m\n";
    for (std::size_t i = 0; i < rpm.size(); ++i)
      csv << fmt::format("{:.17g}, {:.17g}\n", rpm[i], 2.0 * amplitude[i]);
  }
  const model::Model m = analyses::parse_model(
      base +
          "measured_file = \"measured.csv\"\nmeasured_sensor = \"turbine_x\"\n"
          "measured_mesh_order = 1\nscale_to_measured = true\n",
      (dir / "model.toml").string());
  analyses::check_inputs(m, {});
  const AnalysisOutput out = run(m);
  ASSERT_EQ(out.status, Status::Ok) << out.message;
  const Table* comparison = nullptr;
  const Table* scaling = nullptr;
  for (const Table& t : out.tables) {
    if (t.name == "comparison") comparison = &t;
    if (t.name == "force_scaling") scaling = &t;
  }
  ASSERT_NE(comparison, nullptr);
  ASSERT_NE(scaling, nullptr);
  ASSERT_GE(comparison->rows(), 1u);
  for (std::size_t k = 0; k < comparison->rows(); ++k) {
    EXPECT_NEAR(comparison->column("x_mismatch_pct").numbers[k], 0.0, 1e-9) << k;
    EXPECT_NEAR(comparison->column("amplitude_mismatch_pct").numbers[k], -50.0, 1e-9) << k;
  }
  EXPECT_NEAR(scaling->column("scale").numbers[0], 2.0, 1e-9);
  EXPECT_NEAR(scaling->column("implied_force_n").numbers[0], 200.0, 1e-7);
  const auto overlay = std::find_if(out.plots.begin(), out.plots.end(),
                                    [](const Plot& p) { return p.name == "measured_overlay"; });
  ASSERT_NE(overlay, out.plots.end());
  EXPECT_EQ(overlay->traces.size(), 3u);  // measured, computed, computed scaled

  // A sensor the analysis does not have, and a mesh order beyond max_mesh_order.
  const model::Model wrong = analyses::parse_model(
      base + "measured_file = \"measured.csv\"\nmeasured_sensor = \"nowhere\"\n",
      (dir / "model.toml").string());
  EXPECT_THROW((void)run(wrong), InputError);
  EXPECT_THROW((void)analyses::parse_model(base + "measured_file = \"measured.csv\"\n"
                                                  "measured_mesh_order = 2\n",
                                           (dir / "model.toml").string()),
               InputError);
}

// ---------------------------------------------------------------------------------------------
// Scalar outputs (what a sweep reads): each from the typed result, checked against the table the
// same run prints and against an independent estimate.

/// Runs analysis `a` of `m` through its registry entry and reads scalar `quantity`.
struct ScalarRun {
  analyses::Outcome outcome;
  const analyses::AnalysisType* type = nullptr;
  double operator()(const std::string& quantity, const std::string& sensor = {},
                    double at_rpm = 0.0, std::string* unit = nullptr) const {
    analyses::ScalarRequest q;
    q.quantity = quantity;
    q.sensor = sensor;
    q.at = at_rpm * kTwoPi / 60.0;
    std::string u;
    const double v = type->scalar(outcome, q, u);
    if (unit != nullptr) *unit = u;
    return v;
  }
};

ScalarRun run_type(const model::Model& m, const model::Analysis& a,
                   const analyses::Context& context) {
  ScalarRun r;
  r.type = analyses::find_analysis_type(a.type);
  EXPECT_NE(r.type, nullptr);
  r.outcome = r.type->run(m, a, context);
  // Every scalar offered is answered for the first sensor.
  for (const auto& s : r.type->scalars)
    if (s.name != "amplitude_at") {
      EXPECT_TRUE(std::isfinite(r(s.name))) << s.name;
    }
  return r;
}

double column_max(const Table& t, const std::string& column) {
  const auto& v = t.column(column).numbers;
  return *std::max_element(v.begin(), v.end());
}

std::size_t peak_row(const Table& peaks, const std::string& sensor, const std::string& curve) {
  for (std::size_t i = 0; i < peaks.rows(); ++i)
    if (peaks.column("sensor").texts[i] == sensor && peaks.column("curve").texts[i] == curve)
      return i;
  ADD_FAILURE() << "no peak of " << sensor << " " << curve;
  return 0;
}

// gear_forced_response on examples/geared_rotor_hcf, two mesh orders. peak_amplitude is the
// largest sample of the summed curve: exactly the maximum of the printed <sensor>_sum column; the
// "sum" row of mesh_resonances refines that peak by a parabola through the three samples around
// it, so it lies within one grid step (98.5 rpm) in speed and within 2 % in amplitude of the
// sample (the response changes by at most that between neighbours at this grid near a peak
// with Q < 100). amplitude_at on a grid speed is the printed value, half-way between two speeds
// the mean of the two (linear interpolation; 1e-12 round-off).
TEST(ForcedScalars, GearForcedResponse) {
  const std::string text =
      read_text(fs::path(GEARDYN_SOURCE_DIR) / "examples" / "geared_rotor_hcf" / "model.toml") +
      R"(
[[analyses]]
name = "mesh_scalars"
type = "gear_forced_response"
force_amplitude = [100.0, 40.0]
speed_start_rpm = 1000
speed_stop_rpm = 40000
speed_count = 397
n_modes = 20
)";
  const model::Model m = analyses::parse_model(text, "model.toml");
  const fe::LinearSystem system = assembly::build_system(m);
  const model::Analysis& a = m.analyses.back();
  const ScalarRun run = run_type(m, a, analyses::Context(m, a).with_system(&system));
  ASSERT_EQ(run.outcome.output.status, Status::Ok) << run.outcome.output.message;
  const auto& r = analyses::result_of<analyses::GearForcedResponseResult>(run.outcome);
  const Table& response = table_named(run.outcome.output, "mesh_forced_response");
  const Table& peaks = table_named(run.outcome.output, "mesh_resonances");
  const auto& rpm = response.column("speed_rpm").numbers;
  int located = 0;
  for (const auto& sensor : r.response.sensors) {
    const std::string sum =
        sensor.name + (sensor.rotational ? "_sum_amplitude_rad" : "_sum_amplitude_m");
    std::string unit;
    const double peak = run("peak_amplitude", sensor.name, 0.0, &unit);
    EXPECT_EQ(unit, sensor.rotational ? "rad" : "m");
    EXPECT_EQ(peak, r.peak_amplitude(r.sensor_index(sensor.name)));
    EXPECT_EQ(peak, column_max(response, sum)) << sensor.name;
    const double at = run("peak_location", sensor.name, 0.0, &unit);
    EXPECT_EQ(unit, "rpm");
    const std::size_t i = peak_row(peaks, sensor.name, "sum");
    // The largest resonance of the summed curve is the one peak_amplitude finds (the curve may
    // also rise at the range's end, where no peak is detected: then skip the comparison).
    double largest = 0.0;
    for (std::size_t j = 0; j < peaks.rows(); ++j)
      if (peaks.column("sensor").texts[j] == sensor.name && peaks.column("curve").texts[j] == "sum")
        largest = std::max(largest, peaks.column("amplitude").numbers[j]);
    if (largest == peaks.column("amplitude").numbers[i] && std::abs(largest - peak) < 0.02 * peak) {
      ++located;
      EXPECT_NEAR(at, peaks.column("speed_rpm").numbers[i], rpm[1] - rpm[0]) << sensor.name;
    }
    // amplitude_at on and between grid speeds.
    const auto& a_sum = response.column(sum).numbers;
    EXPECT_NEAR(run("amplitude_at", sensor.name, rpm[100]), a_sum[100], 1e-12 * a_sum[100]);
    EXPECT_NEAR(run("amplitude_at", sensor.name, 0.5 * (rpm[100] + rpm[101])),
                0.5 * (a_sum[100] + a_sum[101]), 1e-12 * a_sum[100]);
  }
  EXPECT_GT(located, 0);
  EXPECT_THROW(run("peak_amplitude", "nowhere"), std::runtime_error);
  EXPECT_THROW(run("amplitude_at", "", 50000.0), std::runtime_error);
}

// cyclic_forced_response: one engine order (14, ND 2) of a 10 N force across the first ND 2
// resonance, Q = 30. peak_amplitude is the largest sample of the summed curve (here the one
// order): exactly the maximum of its printed column; its speed is the resonance speed w_r / k of
// cyclic_resonances to within one grid step (0.1 % of w_r) plus the shift of a damped peak,
// w_r (1 - 1 / (8 Q^2)) ~ 1.4e-4 relative: 0.12 % in all (at uz, the direction of that mode).
TEST(ForcedScalars, CyclicForcedResponse) {
  auto analysis = [](const std::string& speeds) {
    return kGearModel + fmt::format(R"(
[[analyses]]
name = "forced"
type = "cyclic_forced_response"
solid = "gear"
force_amplitude = 10.0
engine_orders = [14]
q_factor = 30
sensor_sets = ["excitation"]
sensor_components = ["uz", "uy"]
{}
)",
                                    speeds);
  };
  auto run_model = [](const model::Model& m) {
    return run_type(m, m.analyses.front(), analyses::Context(m, m.analyses.front()));
  };
  const model::Model wide = analyses::parse_model(analysis("speed_rpm = [1000]"), "gear.toml");
  const ScalarRun first = run_model(wide);
  const double w1 = table_named(first.outcome.output, "cyclic_resonances")
                        .column("resonance_speed_rpm")
                        .numbers[0];
  const model::Model m = analyses::parse_model(
      analysis(fmt::format("speed_start_rpm = {}\nspeed_stop_rpm = {}\nspeed_count = 201", 0.9 * w1,
                           1.1 * w1)),
      "gear.toml");
  const ScalarRun run = run_model(m);
  ASSERT_EQ(run.outcome.output.status, Status::Ok) << run.outcome.output.message;
  const auto& r = analyses::result_of<analyses::CyclicForcedResponseResult>(run.outcome);
  const Table& response = table_named(run.outcome.output, "cyclic_forced_response");
  const auto& rpm = response.column("speed_rpm").numbers;
  for (const std::string sensor : {"excitation_uz", "excitation_uy"}) {
    const double peak = run("peak_amplitude", sensor);
    EXPECT_EQ(peak, column_max(response, sensor + "_sum_amplitude_m")) << sensor;
    const std::vector<double> curve = r.sum_curve(r.sensor_index(sensor));
    EXPECT_EQ(peak, *std::max_element(curve.begin(), curve.end()));
    // The axial response (uz) is the one at the ND 2 mode excited; uy rises towards others.
    if (sensor == "excitation_uz") {
      EXPECT_NEAR(run("peak_location", sensor), w1, 1.2e-3 * w1);
    }
    const auto& a_sum = response.column(sensor + "_sum_amplitude_m").numbers;
    EXPECT_NEAR(run("amplitude_at", sensor, 0.5 * (rpm[10] + rpm[11])),
                0.5 * (a_sum[10] + a_sum[11]), 1e-12 * a_sum[10]);
  }
  EXPECT_EQ(run("peak_amplitude"), run("peak_amplitude", "excitation_uz"));  // the first sensor
  EXPECT_THROW(run("peak_location", "excitation_ux"), std::runtime_error);
  EXPECT_THROW(run("amplitude_at", "", 0.5 * w1), std::runtime_error);
}

// damper_ring_response on examples/damper_ring (its first analysis without the performance
// curve, two sensors). For sensor 0 the scalars are the damped row of the resonance table
// (the same peak: exact; the speed converted to rpm in another order: 1e-12). Independent
// estimates: each damped peak is the largest continuation point of its printed curve refined by a
// parabola (within 1 % of it: the continuation steps 1 % of the range and the peak is flat
// there), and the free peak behind amplitude_vs_free is at least the largest sample of the
// printed free curve and within 5 % of it (201 speeds over 2000 rpm: 10 rpm steps against a
// half-power width of 2 zeta W ~ 70 rpm). At sensor 0 (uy, the mode's direction) the ring damps
// the resonance: amplitude_vs_free < 1.
TEST(ForcedScalars, DamperRingResponse) {
  std::string text =
      read_text(fs::path(GEARDYN_SOURCE_DIR) / "examples" / "damper_ring" / "model.toml");
  const std::size_t second = text.find("[[analyses]]", text.find("name = \"damper\""));
  text = text.substr(0, second);
  for (const std::string key : {"performance_parameter", "performance_values"}) {
    const std::size_t at = text.find(key);
    ASSERT_NE(at, std::string::npos);
    text.erase(at, text.find('\n', at) - at);
  }
  const std::string one = "sensor_components = [\"uy\"]";
  text.replace(text.find(one), one.size(), "sensor_components = [\"uy\", \"uz\"]");
  const model::Model m = analyses::parse_model(
      text, (fs::path(GEARDYN_SOURCE_DIR) / "examples" / "damper_ring" / "model.toml").string());
  const model::Analysis& a = m.analyses.front();
  ASSERT_EQ(a.type, "damper_ring_response");
  const ScalarRun run = run_type(m, a, analyses::Context(m, a));
  ASSERT_EQ(run.outcome.output.status, Status::Ok) << run.outcome.output.message;
  const Table& resonance = table_named(run.outcome.output, "resonance");
  EXPECT_EQ(run("peak_amplitude"), resonance.column("peak_amplitude_m").numbers[0]);
  EXPECT_NEAR(run("peak_location"), resonance.column("peak_speed_rpm").numbers[0],
              1e-12 * resonance.column("peak_speed_rpm").numbers[0]);
  EXPECT_EQ(run("amplitude_vs_free"), resonance.column("amplitude_vs_free").numbers[0]);
  const Table& damped = table_named(run.outcome.output, "damped_response");
  const Table& linear = table_named(run.outcome.output, "linear_response");
  for (const std::string sensor : {"excitation_uy", "excitation_uz"}) {
    const double peak = run("peak_amplitude", sensor);
    const double sampled = column_max(damped, sensor + "_amplitude_m");
    EXPECT_NEAR(peak, sampled, 0.01 * sampled) << sensor;
    const double free = peak / run("amplitude_vs_free", sensor);
    const double free_sampled = column_max(linear, sensor + "_free_m");
    EXPECT_GE(free, free_sampled * (1.0 - 1e-12)) << sensor;
    EXPECT_LE(free, 1.05 * free_sampled) << sensor;
  }
  EXPECT_LT(run("amplitude_vs_free"), 1.0);  // the ring damps the resonance at sensor 0
  EXPECT_THROW(run("peak_amplitude", "nowhere"), std::runtime_error);
}

}  // namespace
}  // namespace geardyn
