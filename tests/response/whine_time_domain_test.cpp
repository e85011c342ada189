// Gear whine: the frequency-domain response to one mesh order (response/rotor_mesh_response,
// Direct and ModalReduced) against the steady state of a constant-speed time simulation of the
// same linear model (transient/linear_rotor_system + integrator), issue #17 "Validation".
//
// The two are independent computations of one thing. For a linear time-invariant system
//   M q'' + (C(W) + W G + C_modal) q' + K(W) q = F cos(w t) v
// every solution is the steady state Re(Q e^{i w t}), Q = D(w)^{-1} F v with
// D = K(W) - w^2 M + i w (C(W) + W G + C_modal), plus free vibrations that decay when every mode
// is damped (the frequency-response theorem of linear vibration; e.g. L. Meirovitch, Elements
// of Vibration Analysis, 2nd ed., McGraw-Hill, 1986, on the harmonic excitation of damped
// systems). The time integration is the trapezoidal rule (Newmark average acceleration;
// N. M. Newmark, "A method of computation for structural dynamics", J. Eng. Mech. Div. ASCE 85
// (1959) 67-94), run from rest until the free vibration has decayed; the phasor is the
// least-squares fit of a cos + b sin over an integer number of forcing periods.
//
// Model: the two-shaft spur stage of examples/first_model (20/40 teeth, mesh stiffness 2e8
// N/m, rigid-disk gears with gyroscopic terms) with damped bearings, one of them tabulated over
// speed (the speed-dependent bearing path), Rayleigh damping, modal damping (the low-rank term)
// and a flexible annular web joined to the pinion by a rigid spider, Craig-Bampton reduced with
// 4 fixed-interface modes and their own modal damping (assembly/solid_coupling.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <vector>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/response/rotor_mesh_response.hpp"
#include "geardyn/transient/integrator.hpp"
#include "geardyn/transient/linear_rotor_system.hpp"

namespace geardyn::response {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;

constexpr const char* kModel = R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 210e9
poisson_ratio = 0.3
density = 7850

[[shafts]]
name = "input"
material = "steel"
origin = [0, 0, -0.1]
axis = [0, 0, 1]
speed_ratio = 1.0
  [[shafts.elements]]
  length = 0.2
  outer_diameter = 0.03
  divisions = 4

[[shafts]]
name = "output"
material = "steel"
origin = [0.15, 0, -0.1]
axis = [0, 0, 1]
driven_by = "input"
gear_ratio = -0.5
  [[shafts.elements]]
  length = 0.2
  outer_diameter = 0.04
  divisions = 4

[[disks]]
name = "pinion"
node = "input.2"
outer_diameter = 0.10
inner_diameter = 0.03
thickness = 0.03
material = "steel"

[[disks]]
name = "wheel"
node = "output.2"
outer_diameter = 0.20
inner_diameter = 0.04
thickness = 0.03
material = "steel"

[[bearings]]
node = "input.0"
kxx = 1e8
kyy = 1e8
cxx = 2000
cyy = 2000

[[bearings]]
node = "input.4"
kxx = 1e8
kyy = 1.5e8
cxx = 2000
cyy = 2000

[[bearings]]
node = "output.0"
speed_rpm = [0, 3000, 6000]
kxx = [1e8, 1.1e8, 1.2e8]
kyy = [1e8, 1.2e8, 1.3e8]
cxx = [2000, 2200, 2500]
cyy = [2000, 2300, 2600]

[[bearings]]
node = "output.4"
kxx = 1e8
kyy = 1e8
cxx = 2000
cyy = 2000

[[constraints]]
node = "input.0"
dofs = ["uz", "rz"]

[[constraints]]
node = "output.0"
dofs = ["uz"]

[[gear_meshes]]
name = "stage"
gear1 = "input.2"
gear2 = "output.2"
type = "spur"
teeth1 = 20
teeth2 = 40
base_radius1 = 0.04698463103929542
base_radius2 = 0.09396926207859084
pressure_angle_deg = 20
stiffness = 2e8

[damping]
rayleigh_alpha = 40.0
rayleigh_beta = 2e-7
modal_ratio = 0.01

[[solids]]
name = "web"
type = "annular_plate"
material = "steel"
inner_radius = 0.015
outer_radius = 0.045
thickness = 0.004
radial_elements = 2
circumferential_elements = 12
layers = 1
order = 1
coupling_modes = 4
modal_damping_ratio = 0.02
  [[solids.spiders]]
  node_set = "inner"
  node = "input.2"
  kind = "rigid"

[[sensors]]
name = "pinion_x"
node = "input.2"
dof = "ux"

[[sensors]]
name = "pinion_y"
node = "input.2"
dof = "uy"

[[sensors]]
name = "wheel_y"
node = "output.2"
dof = "uy"

[[sensors]]
name = "wheel_rz"
node = "output.2"
dof = "rz"

[[sensors]]
name = "bearing_x"
node = "output.0"
dof = "ux"
)";

// The mesh-order force F cos(w t) v on top of the linear rotor (which has no unbalance here).
class MeshForcedRotor final : public transient::SecondOrderSystem {
 public:
  MeshForcedRotor(transient::LinearRotorSystem& rotor, Eigen::VectorXd load, double force,
                  double omega)
      : rotor_(rotor), load_(std::move(load)), force_(force), omega_(omega) {}
  int size() const override { return rotor_.size(); }
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                const Eigen::VectorXd& a, Eigen::VectorXd& r) override {
    rotor_.residual(t, q, v, a, r);
    r -= force_ * std::cos(omega_ * t) * load_;
  }
  void tangent(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_m, double c_c,
               double c_k, transient::SparseMatrix& S) override {
    rotor_.tangent(t, q, v, c_m, c_c, c_k, S);
  }
  bool tangent_low_rank(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double c_m,
                        double c_c, double c_k, Eigen::MatrixXd& U, Eigen::VectorXd& d) override {
    return rotor_.tangent_low_rank(t, q, v, c_m, c_c, c_k, U, d);
  }
  bool is_linear_time_invariant() const override { return rotor_.is_linear_time_invariant(); }

 private:
  transient::LinearRotorSystem& rotor_;
  Eigen::VectorXd load_;
  double force_, omega_;
};

// Least-squares a cos(w t) + b sin(w t) over the samples: Re(X e^{i w t}) with X = a - i b.
Complex fit_phasor(const std::vector<double>& t, const std::vector<double>& x, double omega) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(t.size()), 2);
  Eigen::VectorXd b(static_cast<Eigen::Index>(t.size()));
  for (std::size_t i = 0; i < t.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    A(r, 0) = std::cos(omega * t[i]);
    A(r, 1) = std::sin(omega * t[i]);
    b[r] = x[i];
  }
  const Eigen::Vector2d ab = A.colPivHouseholderQr().solve(b);
  return {ab[0], -ab[1]};
}

struct SteadyState {
  std::vector<Complex> last, previous;  // phasors of the last two windows, per output
  double decay_bound = 0.0;             // largest |last - previous| / |last| over the outputs
};

// Trapezoidal rule from rest over `periods_total` forcing periods with `steps_per_period`
// steps each; phasors over the last two windows of `window` periods.
SteadyState simulate(const model::Model& model, const fe::LinearSystem& system,
                     const Eigen::VectorXd& load, double force, double speed, double omega,
                     const std::vector<int>& outputs, int periods_total, int steps_per_period,
                     int window) {
  transient::LinearRotorSystem rotor(model, system, transient::SpeedProfile::constant(speed));
  MeshForcedRotor forced(rotor, load, force, omega);
  const double period = 2.0 * kPi / omega;
  transient::IntegratorOptions o;
  o.scheme = transient::Scheme::Newmark;
  o.time_step = period / steps_per_period;
  o.num_steps = periods_total * steps_per_period;
  const int first_previous = (periods_total - 2 * window) * steps_per_period;
  const int first_last = (periods_total - window) * steps_per_period;
  std::vector<double> t0, t1;
  std::vector<std::vector<double>> x0(outputs.size()), x1(outputs.size());
  Eigen::VectorXd q = Eigen::VectorXd::Zero(system.size()), v = q;
  const auto summary = transient::integrate(
      forced, o, q, v,
      [&](int step, double t, const Eigen::VectorXd& qs, const Eigen::VectorXd&,
          const Eigen::VectorXd&) {
        // Windows [first, first + window periods): the sample at the window's end belongs to
        // the next one, so each window holds exactly window x steps_per_period samples.
        if (step >= first_previous && step < first_last) {
          t0.push_back(t);
          for (std::size_t i = 0; i < outputs.size(); ++i) x0[i].push_back(qs[outputs[i]]);
        } else if (step >= first_last && step < o.num_steps) {
          t1.push_back(t);
          for (std::size_t i = 0; i < outputs.size(); ++i) x1[i].push_back(qs[outputs[i]]);
        }
      },
      null_progress());
  EXPECT_EQ(summary.status, Status::Ok) << summary.brief_report();
  EXPECT_EQ(summary.factorizations, 1) << "constant speed: one factorisation for the run";
  SteadyState s;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    s.previous.push_back(fit_phasor(t0, x0[i], omega));
    s.last.push_back(fit_phasor(t1, x1[i], omega));
    s.decay_bound = std::max(s.decay_bound,
                             std::abs(s.last.back() - s.previous.back()) / std::abs(s.last.back()));
  }
  return s;
}

// Out of line: GCC 12's -Wnull-dereference misfires on Eigen's sparse-to-dense conversion when
// it is inlined into a long test body.
[[gnu::noinline]] Eigen::MatrixXd dense(const fe::SparseMatrix& X) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(X.rows(), X.cols());
  for (Eigen::Index j = 0; j < X.outerSize(); ++j)
    for (fe::SparseMatrix::InnerIterator it(X, j); it; ++it) d(it.row(), it.col()) += it.value();
  return d;
}

[[gnu::noinline]] double max_abs(const Eigen::MatrixXcd& X) { return X.cwiseAbs().maxCoeff(); }

class WhineTimeDomain : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = analyses::parse_model(kModel, "whine_validation.toml");
    system_ = assembly::build_system(model_);
    mesh_ = find_gear_mesh(model_, "stage");
    load_ = mesh_load(model_, system_, mesh_);
    per_speed_ = mesh_frequency_per_speed(model_, system_, mesh_);
    sensors_ = rotor_sensors(model_, system_);
    for (const RotorSensor& s : sensors_) outputs_.push_back(s.equation);
    // The web's first modal coordinate (a generalised coordinate of the joined solid).
    ASSERT_EQ(system_.dofs.generalized().size(), 1u);
    outputs_.push_back(system_.dofs.generalized().front().first);
  }

  model::Model model_;
  fe::LinearSystem system_;
  int mesh_ = -1;
  Eigen::VectorXd load_;
  double per_speed_ = 0.0;
  std::vector<RotorSensor> sensors_;
  std::vector<int> outputs_;
};

// Two speeds of the order-1 mesh frequency: at the largest resonance peak of the pinion's lateral
// response below 5000 rpm (found on a fine speed grid by the direct solver), and off resonance at
// 0.62 of that speed. The comparison is on the complex amplitude (amplitude and phase together):
// |Q_time - Q_freq| <= 1 % of |Q_freq| at every output, the issue's tolerance.
// Error budget: the trapezoidal rule's steady state is the exact response at the warped
// frequency (2/h) tan(w h / 2) (its period elongation, (w h)^2 / 12 = 8.2e-5 at 200 steps per
// period), which changes a response of modal damping ratio zeta by about (w h)^2 / 12 / zeta
// at resonance: < 1e-2 for zeta > 0.8 %; the free vibration decays as exp(-alpha t / 2) or
// faster (Rayleigh alpha = 40 1/s): after 0.6 s, < 1e-5, checked by the change between the last
// two 20-period windows (< 1e-3).
TEST_F(WhineTimeDomain, MeshOrderResponseEqualsTimeDomainSteadyState) {
  DirectRotorSolver direct(system_, load_, outputs_);
  const int pinion_x = 0;
  const Eigen::VectorXd grid =
      Eigen::VectorXd::LinSpaced(400, 2 * kPi * 500 / 60.0, 2 * kPi * 5000 / 60.0);
  double peak_speed = grid[0], peak = 0.0;
  for (Eigen::Index i = 0; i < grid.size(); ++i) {
    const double a = std::abs(direct.response(grid[i], per_speed_ * grid[i])(pinion_x, 0));
    if (a > peak) peak = a, peak_speed = grid[i];
  }
  ASSERT_GT(peak_speed, grid[0]);
  ASSERT_LT(peak_speed, grid[grid.size() - 1]) << "the peak must be inside the grid";
  EXPECT_EQ(direct.symbolic_analyses(), 1);
  EXPECT_EQ(direct.numeric_factorizations(), 400);

  // 50 modes and the residual vector (51 of the 61 equations, modes up to 40 kHz): the web's
  // modal coordinate responds quasi-statically through its fixed-interface modes (tens of kHz),
  // which the basis must reach for 1 %; every other output converges with far fewer modes.
  ModalRotorModel modal(system_, load_, outputs_, 50, true);
  std::printf("system %d equations, modal basis %d vectors up to %.0f Hz\n", system_.size(),
              modal.basis_size(), modal.highest_mode() / (2 * kPi));
  const double force = 250.0;  // N along the line of action
  for (const double speed : {0.62 * peak_speed, peak_speed}) {
    const double omega = per_speed_ * speed;
    const Eigen::VectorXcd Qd = force * direct.response(speed, omega).col(0);
    const Eigen::VectorXcd Qm = force * modal.response(speed, omega).col(0);
    // Periods: ~0.6 s of simulated time at least, in whole periods.
    const double period = 2.0 * kPi / omega;
    const int periods = std::max(80, static_cast<int>(std::ceil(0.6 / period)));
    const SteadyState s =
        simulate(model_, system_, load_, force, speed, omega, outputs_, periods, 200, 20);
    std::printf("speed %.1f rpm (mesh %.1f Hz), %d periods: decay bound %.2e\n",
                speed * 60.0 / (2 * kPi), omega / (2 * kPi), periods, s.decay_bound);
    EXPECT_LT(s.decay_bound, 1e-3) << "the transient has not decayed";
    for (std::size_t i = 0; i < outputs_.size(); ++i) {
      const auto r = static_cast<Eigen::Index>(i);
      const double e_direct = std::abs(s.last[i] - Qd[r]) / std::abs(Qd[r]);
      const double e_modal = std::abs(s.last[i] - Qm[r]) / std::abs(Qd[r]);
      std::printf(
          "  output %zu: |Q| %.4e, phase %.2f deg; time %.4e, %.2f deg; error direct "
          "%.2e, modal %.2e\n",
          i, std::abs(Qd[r]), std::arg(Qd[r]) * 180 / kPi, std::abs(s.last[i]),
          std::arg(s.last[i]) * 180 / kPi, e_direct, e_modal);
      EXPECT_LT(e_direct, 1e-2) << "output " << i << " at " << speed << " rad/s";
      EXPECT_LT(e_modal, 1e-2) << "output " << i << " at " << speed << " rad/s";
    }
  }
}

// The per-speed setup and the one symbolic analysis for the whole run change nothing but
// round-off: against a solver whose symbolic analysis is of the point's own matrix (what the
// solver did for every point before), with every term present (speed-dependent bearing,
// gyroscopic, Rayleigh, modal damping by Sherman-Morrison-Woodbury, hysteretic loss factor),
// over speeds and two orders: 1e-12 of the largest response at each point; against a dense LU
// of D from K_at, C_at, G (damping_dense), K_loss: 1e-10 (round-off of two different pivotings
// times the condition of D near resonance). The full q agrees with the outputs, and the run's
// kept coordinates give the same q for both methods.
TEST_F(WhineTimeDomain, SharedSymbolicAnalysisAndFullResponseMatchFreshSolves) {
  model::Model lossy = model_;
  lossy.damping.loss_factor = 0.002;
  const fe::LinearSystem sys = assembly::build_system(lossy);
  ASSERT_GT(sys.K_loss.norm(), 0.0);
  ASSERT_TRUE(sys.has_modal_damping());
  ASSERT_FALSE(sys.speed_bearings.empty());
  DirectRotorSolver direct(sys, load_, outputs_);
  ModalRotorModel modal(sys, load_, outputs_, sys.size(), false);
  const Eigen::MatrixXd Md = dense(sys.M), Ld = dense(sys.K_loss);
  for (const double rpm : {0.0, 1000.0, 2500.0, 4500.0, 7000.0}) {
    const double W = 2 * kPi * rpm / 60.0;
    const DirectRotorSolver::SpeedPoint point = direct.at(W);
    const ModalRotorModel::SpeedPoint mpoint = modal.at(W);
    const Eigen::MatrixXd Kw = dense(sys.K_at(W));
    for (const int order : {1, 3}) {
      const double w = order * per_speed_ * std::max(W, 50.0);
      // Reference: a dense LU of D (independent of the sparse code).
      const Eigen::MatrixXcd D = Kw.cast<Complex>() - Complex(w * w) * Md.cast<Complex>() +
                                 Complex(0.0, w) * sys.damping_dense(W).cast<Complex>() +
                                 Complex(0.0, 1.0) * Ld.cast<Complex>();
      const Eigen::MatrixXcd X = D.partialPivLu().solve(load_.cast<Complex>());
      // A solver of its own for this point: a symbolic analysis of this point's matrix, as the
      // solver did for every point before.
      const DirectRotorSolver fresh(sys, load_, outputs_);
      const Eigen::MatrixXcd X_fresh = fresh.full_response(W, w);

      const Eigen::MatrixXcd q = point.full_response(w);
      const double scale = X.cwiseAbs().maxCoeff();
      EXPECT_LT((q - X_fresh).cwiseAbs().maxCoeff(), 1e-12 * scale) << rpm << " rpm, " << order;
      EXPECT_LT((q - X).cwiseAbs().maxCoeff(), 1e-10 * scale) << rpm << " rpm, order " << order;
      const Eigen::MatrixXcd u = point.response(w);
      for (std::size_t i = 0; i < outputs_.size(); ++i)
        EXPECT_EQ(u(static_cast<Eigen::Index>(i), 0), q(outputs_[i], 0));
      // All modes: the modal path is a change of basis (1e-8 as in rotor_mesh_response_test).
      EXPECT_LT((mpoint.full_response(w) - X).cwiseAbs().maxCoeff(), 1e-8 * scale);
      EXPECT_EQ(mpoint.response(w), modal.response(W, w));
    }
  }
  EXPECT_EQ(direct.symbolic_analyses(), 1);
  EXPECT_EQ(direct.numeric_factorizations(), 5 * 2 * 2);  // full_response and response
}

TEST_F(WhineTimeDomain, KeptCoordinatesGiveTheFullResponse) {
  model::Model lossy = model_;
  lossy.damping.loss_factor = 0.002;
  const fe::LinearSystem sys = assembly::build_system(lossy);
  DirectRotorSolver direct(sys, load_, outputs_);
  RotorForcedSettings s;
  s.gear_mesh = "stage";
  s.harmonics = {{1, {100.0, 0.0}}, {2, std::polar(30.0, 0.7)}};
  s.sensors = sensors_;
  s.speeds = Eigen::VectorXd::LinSpaced(7, 100.0, 600.0);
  s.keep_coordinates = true;
  s.method = RotorForcedMethod::Direct;
  const RotorForcedResult rd = run_mesh_forced_response(lossy, sys, s);
  s.method = RotorForcedMethod::ModalReduced;
  s.n_modes = sys.size();
  s.residual_vectors = false;
  const RotorForcedResult rm = run_mesh_forced_response(lossy, sys, s);
  ASSERT_EQ(rd.coordinates.size(), 2u);
  EXPECT_EQ(rd.coordinates[0].rows(), sys.size());
  EXPECT_EQ(rm.coordinates[0].rows(), rm.basis_size);
  for (std::size_t h = 0; h < 2; ++h)
    for (Eigen::Index i = 0; i < s.speeds.size(); ++i) {
      const double w = s.harmonics[h].order * per_speed_ * s.speeds[i];
      const Eigen::MatrixXcd expected =
          s.harmonics[h].amplitude * direct.full_response(s.speeds[i], w);
      const Eigen::MatrixXcd qd = rd.full_response(h, i), qm = rm.full_response(h, i);
      const double scale = max_abs(expected);
      EXPECT_LT(max_abs(qd - expected), 1e-12 * scale);
      EXPECT_LT(max_abs(qm - expected), 1e-8 * scale);
      for (std::size_t k = 0; k < sensors_.size(); ++k)
        EXPECT_EQ(rd.displacement[h](i, static_cast<Eigen::Index>(k)), qd(sensors_[k].equation, 0));
    }
  s.keep_coordinates = false;
  const RotorForcedResult plain = run_mesh_forced_response(lossy, sys, s);
  EXPECT_TRUE(plain.coordinates.empty());
  EXPECT_THROW((void)plain.full_response(0, 0), std::logic_error);
  EXPECT_THROW((void)rd.full_response(2, 0), std::out_of_range);
}

}  // namespace
}  // namespace geardyn::response
