#include "geardyn/response/rotor_mesh_response.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "geardyn/core/error.hpp"
#include "geardyn/core/peak_table.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/fe/gear_mesh_element.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::response {
namespace {

using Complex = std::complex<double>;
constexpr double kRpmPerRadS = 60.0 / units::kTwoPi;

[[noreturn]] void input_error(const std::string& key, const std::string& expected,
                              const std::string& found, const std::string& hint = {}) {
  throw InputError({}, key, expected, found, hint);
}

bool is_empty(const fe::SparseMatrix& X) { return X.rows() == 0 || X.cols() == 0; }

// Phi^T X Phi for a sparse X (zero matrix when X is empty).
Eigen::MatrixXd project(const fe::SparseMatrix& X, const Eigen::MatrixXd& Phi) {
  if (is_empty(X)) return Eigen::MatrixXd::Zero(Phi.cols(), Phi.cols());
  return Phi.transpose() * (X * Phi);
}

void check_outputs(const std::vector<int>& outputs, int n) {
  for (std::size_t i = 0; i < outputs.size(); ++i)
    if (outputs[i] < 0 || outputs[i] >= n)
      input_error(fmt::format("forced.outputs[{}]", i), fmt::format("an equation in 0..{}", n - 1),
                  std::to_string(outputs[i]));
}

int gear_node(const fe::LinearSystem& system, const std::string& name, const std::string& key) {
  const int node = system.dofs.find_node(name);
  if (node < 0) input_error(key, "a node of the model", fmt::format("'{}'", name));
  return node;
}

}  // namespace

int find_gear_mesh(const model::Model& model, const std::string& name) {
  std::string names;
  for (std::size_t i = 0; i < model.gear_meshes.size(); ++i) {
    if (model.gear_meshes[i].name == name) return static_cast<int>(i);
    names += (names.empty() ? "" : ", ") + model.gear_meshes[i].name;
  }
  input_error("forced.gear_mesh", "the name of a gear mesh", fmt::format("'{}'", name),
              names.empty() ? "the model has no gear mesh" : "gear meshes: " + names);
}

Eigen::VectorXd mesh_load(const model::Model& model, const fe::LinearSystem& system,
                          int mesh_index) {
  if (mesh_index < 0 || mesh_index >= static_cast<int>(model.gear_meshes.size()))
    input_error("forced.gear_mesh",
                fmt::format("a gear mesh index in 0..{}", model.gear_meshes.size() - 1),
                std::to_string(mesh_index));
  const model::GearMesh& mesh = model.gear_meshes[static_cast<std::size_t>(mesh_index)];
  const std::string key = fmt::format("gear_meshes[{}]", mesh_index);
  const int n1 = gear_node(system, mesh.gear1, key + ".gear1");
  const int n2 = gear_node(system, mesh.gear2, key + ".gear2");
  const fe::NodeInfo& g1 = system.dofs.node(n1);
  const fe::NodeInfo& g2 = system.dofs.node(n2);
  const fe::GearMeshGeometry geometry = fe::gear_mesh_geometry(mesh, g1, g2, key);
  const fe::Vector12d v = fe::gear_mesh_vector(geometry, g1, g2);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(system.size());
  const auto eq1 = system.dofs.node_dofs(n1);
  const auto eq2 = system.dofs.node_dofs(n2);
  for (int c = 0; c < 6; ++c) {
    if (eq1[static_cast<std::size_t>(c)] >= 0) f[eq1[static_cast<std::size_t>(c)]] += v[c];
    if (eq2[static_cast<std::size_t>(c)] >= 0) f[eq2[static_cast<std::size_t>(c)]] += v[6 + c];
  }
  return f;
}

double mesh_frequency_per_speed(const model::Model& model, const fe::LinearSystem& system,
                                int mesh_index) {
  const model::GearMesh& mesh = model.gear_meshes.at(static_cast<std::size_t>(mesh_index));
  const std::string key = fmt::format("gear_meshes[{}]", mesh_index);
  if (mesh.teeth1 < 1)
    input_error(key + ".teeth1", "the tooth count of gear 1 (for the mesh frequency)",
                std::to_string(mesh.teeth1));
  const double ratio =
      std::abs(system.dofs.node(gear_node(system, mesh.gear1, key + ".gear1")).speed_ratio);
  if (!(ratio > 0.0))
    input_error(key + ".gear1", "a spinning gear (non-zero speed ratio)",
                fmt::format("node '{}' with speed ratio 0", mesh.gear1));
  return mesh.teeth1 * ratio;
}

std::vector<RotorSensor> rotor_sensors(const model::Model& model, const fe::LinearSystem& system,
                                       const std::vector<std::string>& names) {
  std::vector<RotorSensor> out;
  auto add = [&](const model::Sensor& s, const std::string& key) {
    const int node = system.dofs.find_node(s.node);
    if (node < 0) input_error(key + ".node", "a node of the model", fmt::format("'{}'", s.node));
    const int eq = system.dofs.dof(node, s.dof);
    if (eq < 0)
      input_error(key + ".dof", "an unconstrained DOF",
                  fmt::format("{} of '{}', which is constrained",
                              model::kComponentNames[static_cast<std::size_t>(s.dof)], s.node));
    out.push_back({s.name, eq, static_cast<int>(s.dof) >= 3});
  };
  if (names.empty()) {
    for (std::size_t i = 0; i < model.sensors.size(); ++i)
      add(model.sensors[i], fmt::format("sensors[{}]", i));
    return out;
  }
  for (const std::string& name : names) {
    const auto it = std::find_if(model.sensors.begin(), model.sensors.end(),
                                 [&](const model::Sensor& s) { return s.name == name; });
    if (it == model.sensors.end())
      input_error("forced.sensors", "the name of a sensor of the model", fmt::format("'{}'", name));
    add(*it, fmt::format("sensors[{}]", it - model.sensors.begin()));
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Modal basis

ModalRotorModel::ModalRotorModel(const fe::LinearSystem& system, const Eigen::MatrixXd& loads,
                                 const std::vector<int>& outputs, int n_modes,
                                 bool residual_vectors)
    : system_(system) {
  const int n = system.size();
  if (loads.rows() != n)
    input_error("forced.loads", fmt::format("{} rows (one per equation)", n),
                std::to_string(loads.rows()));
  check_outputs(outputs, n);
  if (n_modes < 1 || n_modes > n)
    input_error("forced.n_modes", fmt::format("1..{} modes", n), std::to_string(n_modes));

  const fe::SparseMatrix K0 = system.K_at(0.0);
  eig::SymmetricEigenOptions eo;
  eo.n_modes = n_modes;
  const eig::SymmetricEigenResult modes = eig::solve_symmetric(K0, system.M, eo);
  if (modes.converged == 0 || modes.eigenvectors.cols() == 0)
    throw NumericalError("mesh forced response (modal basis)",
                         "the eigen-solve at zero speed returned no mode: " + modes.message);
  status_ = modes.status;
  message_ = modes.status == Status::Ok ? "" : "modal basis: " + modes.message;
  modes_ = static_cast<int>(modes.eigenvectors.cols());
  highest_ = std::sqrt(std::max(modes.eigenvalues.maxCoeff(), 0.0));
  Phi_ = modes.eigenvectors;

  if (residual_vectors && loads.cols() > 0) {
    // Static correction: x = (K(0) - sigma M)^{-1} f, sigma slightly negative so that rigid-body
    // modes do not make it singular, then M-orthonormalised against the basis (Gram-Schmidt
    // twice, the usual cure for the loss of orthogonality of a single pass).
    const double sigma = eig::automatic_shift(K0, system.M);
    linalg::SparseLU<double> lu;
    const fe::SparseMatrix A = K0 - sigma * system.M;
    if (lu.compute(A) != Status::Ok)
      throw NumericalError("mesh forced response (residual vectors)",
                           "K(0) - sigma M is singular: " + lu.message() +
                               "; set residual_vectors = false or check the constraints");
    const Eigen::MatrixXd X = lu.solve(Eigen::MatrixXd(loads));
    for (Eigen::Index j = 0; j < X.cols(); ++j) {
      Eigen::VectorXd x = X.col(j);
      const double norm0 = std::sqrt(std::max(x.dot(system.M * x), 0.0));
      if (!(norm0 > 0.0)) continue;
      for (int pass = 0; pass < 2; ++pass) x -= Phi_ * (Phi_.transpose() * (system.M * x));
      const double norm = std::sqrt(std::max(x.dot(system.M * x), 0.0));
      // Below 1e-8 of its size the vector is already in the span of the basis: adding it would
      // make the reduced mass matrix numerically singular.
      if (!(norm > 1e-8 * norm0)) continue;
      Phi_.conservativeResize(Eigen::NoChange, Phi_.cols() + 1);
      Phi_.col(Phi_.cols() - 1) = x / norm;
    }
  }

  Kr_ = project(K0, Phi_);
  Mr_ = project(system.M, Phi_);
  Cr_ = project(system.C_at(0.0), Phi_);
  if (system.has_modal_damping()) {
    const Eigen::MatrixXd Br = Phi_.transpose() * system.modal_basis;
    Cr_ += Br * system.modal_coefficients.asDiagonal() * Br.transpose();
  }
  Gr_ = project(system.G, Phi_);
  Lr_ = project(system.K_loss, Phi_);
  Fr_ = Phi_.transpose() * loads;
  Sr_.resize(static_cast<Eigen::Index>(outputs.size()), Phi_.cols());
  for (std::size_t i = 0; i < outputs.size(); ++i)
    Sr_.row(static_cast<Eigen::Index>(i)) = Phi_.row(outputs[i]);
}

Eigen::MatrixXcd ModalRotorModel::response(double speed, double omega) const {
  Eigen::MatrixXd K = Kr_, C = Cr_;
  if (!system_.speed_bearings.empty() && speed != 0.0) {
    // Speed-dependent bearings: the change from zero speed, projected (the difference is
    // non-zero only on the bearing equations, so the product is cheap).
    fe::SparseMatrix dK = system_.K_at(speed) - system_.K_at(0.0);
    fe::SparseMatrix dC = system_.C_at(speed) - system_.C_at(0.0);
    dK.prune(0.0);
    dC.prune(0.0);
    K += project(dK, Phi_);
    C += project(dC, Phi_);
  }
  C += speed * Gr_;
  const Eigen::MatrixXcd D = K.cast<Complex>() - Complex(omega * omega) * Mr_.cast<Complex>() +
                             Complex(0.0, omega) * C.cast<Complex>() +
                             Complex(0.0, 1.0) * Lr_.cast<Complex>();
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(D);
  // PartialPivLU does not flag singularity; the reciprocal condition estimate does.
  const double rcond = lu.rcond();
  if (!(rcond > 1e-14))
    throw NumericalError(
        "mesh forced response (modal)",
        fmt::format("the reduced dynamic stiffness at speed {} rad/s, frequency {} rad/s is "
                    "singular (rcond {:.2e}): an undamped natural frequency was hit; add damping",
                    speed, omega, rcond));
  return Sr_.cast<Complex>() * lu.solve(Fr_.cast<Complex>());
}

// ---------------------------------------------------------------------------------------------
// Direct solver

DirectRotorSolver::DirectRotorSolver(const fe::LinearSystem& system, const Eigen::MatrixXd& loads,
                                     const std::vector<int>& outputs)
    : system_(system), loads_(loads.cast<Complex>()), outputs_(outputs) {
  if (loads.rows() != system.size())
    input_error("forced.loads", fmt::format("{} rows (one per equation)", system.size()),
                std::to_string(loads.rows()));
  check_outputs(outputs, system.size());
}

Eigen::MatrixXcd DirectRotorSolver::response(double speed, double omega) const {
  using CS = fe::ComplexSparseMatrix;
  const fe::SparseMatrix K = system_.K_at(speed);
  fe::SparseMatrix C = system_.C_at(speed);
  if (!is_empty(system_.G)) C = C + speed * system_.G;
  CS A = K.cast<Complex>() - Complex(omega * omega) * system_.M.cast<Complex>() +
         Complex(0.0, omega) * C.cast<Complex>();
  if (!is_empty(system_.K_loss)) A = A + Complex(0.0, 1.0) * system_.K_loss.cast<Complex>();
  A.makeCompressed();
  linalg::SparseLU<Complex> lu;
  if (lu.compute(A) != Status::Ok)
    throw NumericalError("mesh forced response (direct)",
                         fmt::format("the dynamic stiffness at speed {} rad/s, frequency {} rad/s "
                                     "is singular: {}; add damping or move the speed",
                                     speed, omega, lu.message()));
  Eigen::MatrixXcd X = lu.solve(loads_);
  if (system_.has_modal_damping()) {
    // (A + B S B^T)^{-1} F = Z - Y (I + S B^T Y)^{-1} S B^T Z,  Z = A^{-1} F, Y = A^{-1} B,
    // S = i w diag(c) (Sherman-Morrison-Woodbury).
    const Eigen::MatrixXcd B = system_.modal_basis.cast<Complex>();
    const Eigen::MatrixXcd Y = lu.solve(B);
    const Eigen::VectorXcd s = Complex(0.0, omega) * system_.modal_coefficients.cast<Complex>();
    const Eigen::Index r = B.cols();
    const Eigen::MatrixXcd cap =
        Eigen::MatrixXcd::Identity(r, r) + s.asDiagonal() * (B.transpose() * Y);
    X -= Y * cap.partialPivLu().solve(s.asDiagonal() * (B.transpose() * X));
  }
  Eigen::MatrixXcd out(static_cast<Eigen::Index>(outputs_.size()), X.cols());
  for (std::size_t i = 0; i < outputs_.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = X.row(outputs_[i]);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Analysis

std::vector<std::string> RotorForcedSettings::validate() const {
  std::vector<std::string> problems;
  if (gear_mesh.empty()) problems.push_back("gear_mesh: name a gear mesh");
  if (harmonics.empty()) problems.push_back("harmonics: give at least one mesh order");
  std::set<int> seen;
  for (std::size_t i = 0; i < harmonics.size(); ++i) {
    if (harmonics[i].order < 1)
      problems.push_back(
          fmt::format("harmonics[{}].order must be >= 1, is {}", i, harmonics[i].order));
    else if (!seen.insert(harmonics[i].order).second)
      problems.push_back(fmt::format("harmonics[{}].order {} repeats", i, harmonics[i].order));
    if (!std::isfinite(harmonics[i].amplitude.real()) ||
        !std::isfinite(harmonics[i].amplitude.imag()))
      problems.push_back(fmt::format("harmonics[{}].amplitude is not finite", i));
  }
  if (sensors.empty()) problems.push_back("sensors: give at least one sensor");
  if (method == RotorForcedMethod::ModalReduced && n_modes < 1)
    problems.push_back(fmt::format("n_modes must be >= 1, is {}", n_modes));
  for (const std::string& p : peaks.validate()) problems.push_back("peaks: " + p);
  return problems;
}

RotorForcedResult run_mesh_forced_response(const model::Model& model,
                                           const fe::LinearSystem& system,
                                           const RotorForcedSettings& settings,
                                           Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  if (const auto problems = settings.validate(); !problems.empty())
    input_error("forced", "valid mesh forced-response settings", problems.front(),
                problems.size() > 1 ? fmt::format("{} more problems", problems.size() - 1) : "");
  check_speeds(settings.speeds, "forced.speeds");
  const int mesh = find_gear_mesh(model, settings.gear_mesh);

  RotorForcedResult result;
  result.method = settings.method;
  result.gear_mesh = settings.gear_mesh;
  result.mesh_frequency_per_speed = mesh_frequency_per_speed(model, system, mesh);
  result.speeds = settings.speeds;
  result.harmonics = settings.harmonics;
  result.sensors = settings.sensors;
  std::vector<int> outputs;
  for (const RotorSensor& s : settings.sensors) outputs.push_back(s.equation);
  outputs.insert(outputs.end(), settings.extra_outputs.begin(), settings.extra_outputs.end());
  const Eigen::MatrixXd load = mesh_load(model, system, mesh);

  std::unique_ptr<ModalRotorModel> modal;
  std::unique_ptr<DirectRotorSolver> direct;
  if (settings.method == RotorForcedMethod::ModalReduced) {
    modal = std::make_unique<ModalRotorModel>(system, load, outputs, settings.n_modes,
                                              settings.residual_vectors);
    result.status = modal->status();
    result.message = modal->message();
    result.basis_size = modal->basis_size();
    result.highest_mode_hz = modal->highest_mode() / units::kTwoPi;
  } else {
    direct = std::make_unique<DirectRotorSolver>(system, load, outputs);
  }

  const Eigen::Index ns = settings.speeds.size();
  const auto nsens = static_cast<Eigen::Index>(settings.sensors.size());
  const auto nextra = static_cast<Eigen::Index>(settings.extra_outputs.size());
  result.displacement.assign(settings.harmonics.size(), Eigen::MatrixXcd(ns, nsens));
  result.extra.assign(settings.harmonics.size(), Eigen::MatrixXcd(ns, nextra));
  progress.start("mesh forced response", static_cast<std::size_t>(ns));
  for (Eigen::Index i = 0; i < ns; ++i) {
    const double speed = settings.speeds[i];
    for (std::size_t h = 0; h < settings.harmonics.size(); ++h) {
      const double omega = settings.harmonics[h].order * result.mesh_frequency_per_speed * speed;
      const Eigen::MatrixXcd u =
          modal ? modal->response(speed, omega) : direct->response(speed, omega);
      const Complex f = settings.harmonics[h].amplitude;
      result.displacement[h].row(i) = f * u.col(0).head(nsens).transpose();
      result.extra[h].row(i) = f * u.col(0).tail(nextra).transpose();
    }
    progress.update(static_cast<std::size_t>(i + 1));
  }
  progress.finish();

  result.amplitude_sum = Eigen::MatrixXd::Zero(ns, nsens);
  Eigen::MatrixXd squares = Eigen::MatrixXd::Zero(ns, nsens);
  for (std::size_t h = 0; h < result.displacement.size(); ++h) {
    const Eigen::MatrixXd a = result.displacement[h].cwiseAbs();
    result.amplitude_sum += a;
    squares += a.cwiseAbs2();
    append_speed_peaks(result.peaks, settings.speeds, a, static_cast<int>(h), settings.peaks);
  }
  result.amplitude_rms = (0.5 * squares).cwiseSqrt();
  if (result.displacement.size() > 1)
    append_speed_peaks(result.peaks, settings.speeds, result.amplitude_sum, -1, settings.peaks);
  std::stable_sort(result.peaks.begin(), result.peaks.end(),
                   [](const SpeedPeak& a, const SpeedPeak& b) { return a.sensor < b.sensor; });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

Table RotorForcedResult::response_table() const {
  Table t;
  t.name = "mesh_forced_response";
  t.title = fmt::format("Response to the mesh-order forces of gear mesh '{}'", gear_mesh);
  std::vector<double> rpm;
  for (Eigen::Index i = 0; i < speeds.size(); ++i) rpm.push_back(speeds[i] * kRpmPerRadS);
  t.add("speed_rpm", "rpm", rpm);
  const auto unit = [&](std::size_t s) { return sensors[s].rotational ? "rad" : "m"; };
  for (std::size_t h = 0; h < harmonics.size(); ++h)
    for (std::size_t s = 0; s < sensors.size(); ++s) {
      std::vector<double> amp, phase;
      for (Eigen::Index i = 0; i < speeds.size(); ++i) {
        const Complex u = displacement[h](i, static_cast<Eigen::Index>(s));
        amp.push_back(std::abs(u));
        phase.push_back(std::arg(u) * 180.0 / units::kPi);
      }
      const std::string base = fmt::format("{}_p{}", sensors[s].name, harmonics[h].order);
      t.add(fmt::format("{}_amplitude_{}", base, unit(s)), unit(s), amp);
      t.add(base + "_phase_deg", "deg", phase);
    }
  for (std::size_t s = 0; s < sensors.size(); ++s) {
    const auto c = static_cast<Eigen::Index>(s);
    std::vector<double> sum, rms;
    for (Eigen::Index i = 0; i < speeds.size(); ++i) {
      sum.push_back(amplitude_sum(i, c));
      rms.push_back(amplitude_rms(i, c));
    }
    t.add(fmt::format("{}_sum_amplitude_{}", sensors[s].name, unit(s)), unit(s), sum);
    t.add(fmt::format("{}_rms_{}", sensors[s].name, unit(s)), unit(s), rms);
  }
  return t;
}

Table RotorForcedResult::resonance_table() const {
  std::vector<PeakRow> rows;
  for (const SpeedPeak& p : peaks) {
    const RotorSensor& sensor = sensors[static_cast<std::size_t>(p.sensor)];
    PeakRow row;
    row.sensor = sensor.name;
    row.curve = p.curve < 0
                    ? std::string("sum")
                    : fmt::format("order {}", harmonics[static_cast<std::size_t>(p.curve)].order);
    row.location = p.speed * kRpmPerRadS;
    row.amplitude = p.amplitude;
    row.amplitude_unit = sensor.rotational ? "rad" : "m";
    row.half_power_low = p.speed1 * kRpmPerRadS;
    row.half_power_high = p.speed2 * kRpmPerRadS;
    row.q_factor = p.q_factor;
    row.points_in_band = p.points_in_band;
    row.resolved = p.resolved;
    rows.push_back(std::move(row));
  }
  return peak_table("mesh_resonances",
                    "Resonance peaks of the mesh-order responses (curve: the mesh order, or the "
                    "sum over orders); the excitation frequency at a peak is order x "
                    "frequency_per_speed (mesh_order_forces) x speed",
                    speed_axis(), rows);
}

std::string RotorForcedResult::brief_report() const {
  return fmt::format(
      "mesh forced response '{}': {} speeds, {} orders, {} sensors, {}{}, {} peaks, "
      "{:.3f} s, status {}",
      gear_mesh, speeds.size(), harmonics.size(), sensors.size(),
      method == RotorForcedMethod::Direct ? "direct sparse LU" : "modal basis of ",
      method == RotorForcedMethod::Direct
          ? std::string()
          : fmt::format("{} vectors (modes up to {:.1f} Hz)", basis_size, highest_mode_hz),
      peaks.size(), seconds, to_string(status));
}

}  // namespace geardyn::response
