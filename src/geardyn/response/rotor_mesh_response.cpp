// GCC's -Wnull-dereference reports a false positive inside Eigen's SparseCompressedBase once it
// is inlined into UmfPackLU's matrix reference (see linalg/sparse_factorization.cpp); the pragma
// must precede the first Eigen include.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Sparse>
#include <Eigen/UmfPackSupport>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <stdexcept>
#include <type_traits>

#include "geardyn/core/error.hpp"
#include "geardyn/core/peak_table.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/fe/gear_mesh_element.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"
#include "geardyn/response/rotor_mesh_response.hpp"

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

ModalRotorModel::SpeedPoint::SpeedPoint(const ModalRotorModel& model, double speed)
    : model_(&model), speed_(speed), K_(model.Kr_), C_(model.Cr_) {
  const fe::LinearSystem& system = model.system_;
  if (!system.speed_bearings.empty() && speed != 0.0) {
    // Speed-dependent bearings: the change from zero speed, projected (the difference is
    // non-zero only on the bearing equations, so the product is cheap).
    fe::SparseMatrix dK = system.K_at(speed) - system.K_at(0.0);
    fe::SparseMatrix dC = system.C_at(speed) - system.C_at(0.0);
    dK.prune(0.0);
    dC.prune(0.0);
    K_ += project(dK, model.Phi_);
    C_ += project(dC, model.Phi_);
  }
  C_ += speed * model.Gr_;
}

Eigen::MatrixXcd ModalRotorModel::SpeedPoint::coordinates(double omega) const {
  const ModalRotorModel& m = *model_;
  const Eigen::MatrixXcd D = K_.cast<Complex>() - Complex(omega * omega) * m.Mr_.cast<Complex>() +
                             Complex(0.0, omega) * C_.cast<Complex>() +
                             Complex(0.0, 1.0) * m.Lr_.cast<Complex>();
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(D);
  // PartialPivLU does not flag singularity; the reciprocal condition estimate does.
  const double rcond = lu.rcond();
  if (!(rcond > 1e-14))
    throw NumericalError(
        "mesh forced response (modal)",
        fmt::format("the reduced dynamic stiffness at speed {} rad/s, frequency {} rad/s is "
                    "singular (rcond {:.2e}): an undamped natural frequency was hit; add damping",
                    speed_, omega, rcond));
  return lu.solve(m.Fr_.cast<Complex>());
}

Eigen::MatrixXcd ModalRotorModel::SpeedPoint::response(double omega) const {
  return model_->Sr_.cast<Complex>() * coordinates(omega);
}

Eigen::MatrixXcd ModalRotorModel::SpeedPoint::full_response(double omega) const {
  return model_->Phi_.cast<Complex>() * coordinates(omega);
}

// ---------------------------------------------------------------------------------------------
// Direct solver

// The dynamic stiffness on one fixed sparsity pattern: the values of each matrix on it are
// scattered once, and D(W, w) is a linear combination of value arrays. UMFPACK keeps a pointer
// to the matrix it factorised (its refinement reads it again), so A lives here.
struct DirectRotorSolver::Factorization {
  fe::ComplexSparseMatrix A;      // the pattern; values set per (speed, frequency)
  Eigen::VectorXd m, k, c, g, l;  // M, K, C, G, K_loss on the pattern
  Eigen::UmfPackLU<fe::ComplexSparseMatrix> lu;
  bool analysed = false;
  int symbolic = 0, numeric = 0;

  // Index of entry (row, col) in A's value array (it is in the pattern by construction).
  Eigen::Index position(int row, int col) const {
    const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[col];
    const int* end = A.innerIndexPtr() + A.outerIndexPtr()[col + 1];
    const int* it = std::lower_bound(begin, end, row);
    if (it == end || *it != row)
      throw std::logic_error("DirectRotorSolver: an entry outside the dynamic stiffness pattern");
    return static_cast<Eigen::Index>(it - A.innerIndexPtr());
  }
  Eigen::VectorXd values_of(const fe::SparseMatrix& X) const {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(A.nonZeros());
    for (Eigen::Index j = 0; j < X.outerSize(); ++j)
      for (fe::SparseMatrix::InnerIterator it(X, j); it; ++it)
        v[position(static_cast<int>(it.row()), static_cast<int>(it.col()))] += it.value();
    return v;
  }
  void add_triplets(const std::vector<Eigen::Triplet<double>>& t, Eigen::VectorXd& v) const {
    for (const Eigen::Triplet<double>& e : t) v[position(e.row(), e.col())] += e.value();
  }
};

DirectRotorSolver::DirectRotorSolver(const fe::LinearSystem& system, const Eigen::MatrixXd& loads,
                                     const std::vector<int>& outputs)
    : system_(system), loads_(loads.cast<Complex>()), outputs_(outputs) {
  const int n = system.size();
  if (loads.rows() != n)
    input_error("forced.loads", fmt::format("{} rows (one per equation)", n),
                std::to_string(loads.rows()));
  check_outputs(outputs, n);
  // The pattern: every entry of K, M, C, G, K_loss and every pair of equations of a
  // speed-dependent bearing (zero at some speeds, not at others).
  std::vector<Eigen::Triplet<Complex>> entries;
  for (const fe::SparseMatrix* X : {&system.K, &system.M, &system.C, &system.G, &system.K_loss}) {
    if (is_empty(*X)) continue;
    for (Eigen::Index j = 0; j < X->outerSize(); ++j)
      for (fe::SparseMatrix::InnerIterator it(*X, j); it; ++it)
        entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), 0.0);
  }
  for (const fe::SpeedDependentBearing& b : system.speed_bearings)
    for (int row : b.equations)
      for (int col : b.equations)
        if (row >= 0 && col >= 0) entries.emplace_back(row, col, 0.0);
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 0.0);
  lu_ = std::make_unique<Factorization>();
  lu_->A.resize(n, n);
  lu_->A.setFromTriplets(entries.begin(), entries.end());
  lu_->A.makeCompressed();
  const auto values = [&](const fe::SparseMatrix& X) {
    return is_empty(X) ? Eigen::VectorXd(Eigen::VectorXd::Zero(lu_->A.nonZeros()))
                       : lu_->values_of(X);
  };
  lu_->m = values(system.M);
  lu_->k = values(system.K);
  lu_->c = values(system.C);
  lu_->g = values(system.G);
  lu_->l = values(system.K_loss);
}

DirectRotorSolver::~DirectRotorSolver() = default;

int DirectRotorSolver::symbolic_analyses() const { return lu_->symbolic; }
int DirectRotorSolver::numeric_factorizations() const { return lu_->numeric; }

DirectRotorSolver::SpeedPoint::SpeedPoint(const DirectRotorSolver& solver, double speed)
    : solver_(&solver), speed_(speed) {
  const Factorization& f = *solver.lu_;
  k_ = f.k;
  c_ = f.c + speed * f.g;
  // K_at / C_at: the bearing blocks interpolated at this speed.
  std::vector<Eigen::Triplet<double>> stiffness, damping;
  for (const fe::SpeedDependentBearing& b : solver.system_.speed_bearings) {
    b.add_tangent(speed, 1.0, 0.0, stiffness);
    b.add_tangent(speed, 0.0, 1.0, damping);
  }
  f.add_triplets(stiffness, k_);
  f.add_triplets(damping, c_);
}

Eigen::MatrixXcd DirectRotorSolver::SpeedPoint::full_response(double omega) const {
  return solver_->solve(*this, omega);
}

Eigen::MatrixXcd DirectRotorSolver::SpeedPoint::response(double omega) const {
  const Eigen::MatrixXcd X = solver_->solve(*this, omega);
  const std::vector<int>& outputs = solver_->outputs_;
  Eigen::MatrixXcd out(static_cast<Eigen::Index>(outputs.size()), X.cols());
  for (std::size_t i = 0; i < outputs.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = X.row(outputs[i]);
  return out;
}

Eigen::MatrixXcd DirectRotorSolver::solve(const SpeedPoint& point, double omega) const {
  Factorization& f = *lu_;
  // D = K(W) - w^2 M + i (w (C(W) + W G) + K_loss) on the pattern.
  Complex* a = f.A.valuePtr();
  for (Eigen::Index i = 0; i < f.A.nonZeros(); ++i)
    a[i] = Complex(point.k_[i] - omega * omega * f.m[i], omega * point.c_[i] + f.l[i]);
  const auto singular = [&](const std::string& what) {
    return NumericalError("mesh forced response (direct)",
                          fmt::format("the dynamic stiffness at speed {} rad/s, frequency {} "
                                      "rad/s is singular: {}; add damping or move the speed",
                                      point.speed(), omega, what));
  };
  if (!f.analysed) {
    f.lu.analyzePattern(f.A);
    ++f.symbolic;
    if (f.lu.info() != Eigen::Success) throw singular("UMFPACK's symbolic analysis failed");
    f.analysed = true;
  }
  f.lu.factorize(f.A);
  ++f.numeric;
  if (f.lu.info() != Eigen::Success)
    throw singular(fmt::format("UMFPACK LU found the matrix singular (return code {})",
                               f.lu.umfpackFactorizeReturncode()));
  Eigen::MatrixXcd X = f.lu.solve(loads_);
  if (system_.has_modal_damping()) {
    // (A + B S B^T)^{-1} F = Z - Y (I + S B^T Y)^{-1} S B^T Z,  Z = A^{-1} F, Y = A^{-1} B,
    // S = i w diag(c) (Sherman-Morrison-Woodbury).
    const Eigen::MatrixXcd B = system_.modal_basis.cast<Complex>();
    const Eigen::MatrixXcd Y = f.lu.solve(B);
    const Eigen::VectorXcd s = Complex(0.0, omega) * system_.modal_coefficients.cast<Complex>();
    const Eigen::Index r = B.cols();
    const Eigen::MatrixXcd cap =
        Eigen::MatrixXcd::Identity(r, r) + s.asDiagonal() * (B.transpose() * Y);
    X -= Y * cap.partialPivLu().solve(s.asDiagonal() * (B.transpose() * X));
  }
  return X;
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
  const Eigen::Index nsens = static_cast<Eigen::Index>(outputs.size());
  result.displacement.assign(settings.harmonics.size(), Eigen::MatrixXcd(ns, nsens));
  progress.start("mesh forced response", static_cast<std::size_t>(ns));
  if (settings.keep_coordinates) {
    const Eigen::Index nc = modal ? modal->basis_size() : system.size();
    result.coordinates.assign(settings.harmonics.size(), Eigen::MatrixXcd(nc, ns));
    if (modal) result.basis = modal->basis();
  }
  // One setup per speed (the speed-dependent matrices), reused for every order.
  const auto solve_speed = [&](const auto& point, Eigen::Index i) {
    for (std::size_t h = 0; h < settings.harmonics.size(); ++h) {
      const Complex F = settings.harmonics[h].amplitude;
      const double omega =
          settings.harmonics[h].order * result.mesh_frequency_per_speed * point.speed();
      if (settings.keep_coordinates) {
        Eigen::MatrixXcd x;
        if constexpr (std::is_same_v<std::decay_t<decltype(point)>, ModalRotorModel::SpeedPoint>)
          x = point.coordinates(omega);
        else
          x = point.full_response(omega);
        result.coordinates[h].col(i) = F * x.col(0);
        const Eigen::MatrixXd& basis = result.basis;
        for (std::size_t k = 0; k < outputs.size(); ++k) {
          const auto row = static_cast<Eigen::Index>(outputs[k]);
          result.displacement[h](i, static_cast<Eigen::Index>(k)) =
              modal ? F * (basis.row(row).cast<Complex>() * x.col(0)).value() : F * x(row, 0);
        }
      } else {
        result.displacement[h].row(i) = F * point.response(omega).col(0).transpose();
      }
    }
  };
  for (Eigen::Index i = 0; i < ns; ++i) {
    if (modal)
      solve_speed(modal->at(settings.speeds[i]), i);
    else
      solve_speed(direct->at(settings.speeds[i]), i);
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

Eigen::VectorXcd RotorForcedResult::full_response(std::size_t harmonic, Eigen::Index speed) const {
  if (coordinates.empty())
    throw std::logic_error(
        "RotorForcedResult::full_response: run with RotorForcedSettings::keep_coordinates");
  if (harmonic >= coordinates.size() || speed < 0 || speed >= coordinates[harmonic].cols())
    throw std::out_of_range(fmt::format(
        "RotorForcedResult::full_response: harmonic {} of {}, "
        "speed index {} of {}",
        harmonic, coordinates.size(), speed, coordinates.empty() ? 0 : coordinates[0].cols()));
  const Eigen::VectorXcd x = coordinates[harmonic].col(speed);
  if (basis.size() == 0) return x;
  return basis.cast<Complex>() * x;
}

}  // namespace geardyn::response
