// GCC's -Wnull-dereference false positive inside Eigen's inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of Eigen.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "geardyn/analyses/nonlinear_condensed.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/hbm/condensed_stability.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::analyses {
namespace {

using cd = std::complex<double>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// A mode is a rigid-body mode when w_r^2 <= kRigid w_m^2 (w_m: the highest mode kept): the
/// eigen-solver returns them at round-off of the stiffness's scale, far below this.
constexpr double kRigid = 1e-8;
/// sigma = -kShift w_m^2: the fixed point contracts by < kShift per step on the modes left out.
constexpr double kShift = 1e-4;
/// Converged when a step changes X by <= kSettled ||X||: the next step would change it by kShift
/// times that, below round-off.
constexpr double kSettled = 1e-12;
constexpr int kMaxSteps = 30;

// The elements' placement rows stacked (n_c x n_eq) and the first coordinate of each.
struct Stacked {
  Eigen::MatrixXd B;
  std::vector<int> offset;
};

Stacked stack_elements(const std::vector<BuiltNonlinearElement>& elements, Eigen::Index n_eq) {
  Stacked s;
  Eigen::Index rows = 0;
  for (const auto& e : elements) {
    s.offset.push_back(static_cast<int>(rows));
    rows += e.B.rows();
  }
  s.B.resize(rows, n_eq);
  for (std::size_t e = 0; e < elements.size(); ++e)
    s.B.middleRows(s.offset[e], elements[e].B.rows()) = elements[e].B;
  return s;
}

// The condensed form needs a structure whose damping and stiffness the modes diagonalise.
void check_representable(const fe::LinearSystem& system, const NonlinearResponseSettings& s,
                         const Context& context) {
  const std::string found = "\"condensed\"";
  if (s.speed != 0.0 && system.G.nonZeros() > 0)
    throw context.error(
        "coordinates",
        "\"physical\" or \"modal\" for a rotor at a reference speed (gyroscopic "
        "terms)",
        fmt::format("{} at speed_rpm = {:.6g}", found, s.speed * 60.0 / units::kTwoPi),
        "the gyroscopic coupling is skew, zero on the diagonal of the modes: the "
        "condensed form would drop it");
  if (system.K_loss.nonZeros() > 0)
    throw context.error("coordinates",
                        "\"physical\" or \"modal\" for a model with a hysteretic loss factor",
                        found, "the receptance of the condensed form has viscous modal damping");
  const double asymmetry = linalg::relative_asymmetry(system.K_at(s.speed));
  if (asymmetry > 1e-12)
    throw context.error("coordinates",
                        "\"physical\" or \"modal\" for a non-symmetric stiffness (cross-coupled "
                        "bearings)",
                        fmt::format("{} with ||K - K^T|| / ||K|| = {:.3g}", found, asymmetry));
}

// X = K^+ L restricted to the modes left out (the header comment): one factorisation of
// K - sigma M and a contracting fixed point. `steps` receives the steps taken.
Eigen::MatrixXd flexibility_of_modes_left_out(const fe::SparseMatrix& K, const fe::SparseMatrix& M,
                                              const Eigen::MatrixXd& Phi, double sigma,
                                              const Eigen::MatrixXd& L, const Context& context,
                                              int& steps) {
  const Eigen::MatrixXd MPhi = M * Phi;
  auto orthogonal = [&](Eigen::MatrixXd X) {
    X -= Phi * (MPhi.transpose() * X);
    return X;
  };
  linalg::SymmetricFactorization f;
  const fe::SparseMatrix shifted = K - sigma * M;
  if (f.compute(shifted) != Status::Ok)
    throw NumericalError(context.name(),
                         fmt::format("the residual flexibility: K - sigma M with sigma = {:.6g} "
                                     "could not be factorised ({})",
                                     sigma, f.message()));
  const Eigen::MatrixXd Ld = L - MPhi * (Phi.transpose() * L);
  Eigen::MatrixXd X = orthogonal(f.solve(Ld));
  for (steps = 1; steps <= kMaxSteps; ++steps) {
    Eigen::MatrixXd next = orthogonal(f.solve(Eigen::MatrixXd(Ld - sigma * (M * X))));
    const double change = (next - X).norm();
    X = std::move(next);
    if (change <= kSettled * X.norm()) return X;
  }
  throw NumericalError(context.name(),
                       fmt::format("the residual flexibility did not settle in {} steps: are the "
                                   "rigid-body modes all among the n_modes kept?",
                                   kMaxSteps));
}

// Modal data of the kept modes: w_r (0 for rigid-body modes), zeta_r from the diagonal of
// Phi^T C Phi, which modes are rigid, and the largest relative damping coupling.
struct ModalData {
  Eigen::VectorXd w, zeta;
  std::vector<Eigen::Index> elastic;  ///< indices of the elastic modes
  double top = 0.0;                   ///< w_m^2
  double coupling = 0.0;              ///< max |c_rs| / sqrt(c_rr c_ss), elastic modes
  bool rigid_damped = false;          ///< a rigid-body mode with c_rr > 0 (left out)
};

ModalData modal_data(const NonlinearCoordinates& c, const Context& context) {
  ModalData d;
  const Eigen::VectorXd lambda = c.K.diagonal();
  const Eigen::Index m = lambda.size();
  d.top = lambda.maxCoeff();
  if (!(d.top > 0.0))
    throw context.error("n_modes", "more modes than the structure's rigid-body modes",
                        fmt::format("{}, all at zero frequency", m),
                        "the residual flexibility needs every rigid-body mode among those kept");
  d.w.setZero(m);
  d.zeta.setZero(m);
  const double c_scale = c.C.diagonal().cwiseAbs().maxCoeff();
  for (Eigen::Index r = 0; r < m; ++r) {
    const double crr = std::max(c.C(r, r), 0.0);
    if (lambda[r] <= kRigid * d.top) {
      d.rigid_damped = d.rigid_damped || crr > 1e-12 * c_scale;
      continue;
    }
    d.elastic.push_back(r);
    d.w[r] = std::sqrt(lambda[r]);
    d.zeta[r] = crr / (2.0 * d.w[r]);
  }
  for (Eigen::Index r : d.elastic)
    for (Eigen::Index q : d.elastic) {
      const double diag = c.C(r, r) * c.C(q, q);
      if (r != q && diag > 0.0)
        d.coupling = std::max(d.coupling, std::abs(c.C(r, q)) / std::sqrt(diag));
    }
  return d;
}

Eigen::MatrixXcd complex_columns(const Eigen::MatrixXd& A, const std::vector<Eigen::Index>& cols) {
  Eigen::MatrixXcd out(A.rows(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t k = 0; k < cols.size(); ++k)
    out.col(static_cast<Eigen::Index>(k)) = A.col(cols[k]).cast<cd>();
  return out;
}

Eigen::VectorXd entries(const Eigen::VectorXd& v, const std::vector<Eigen::Index>& at) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(at.size()));
  for (std::size_t k = 0; k < at.size(); ++k) out[static_cast<Eigen::Index>(k)] = v[at[k]];
  return out;
}

// Weights on the excitation columns [a_0, a_1, b_1] giving the complex amplitude of harmonic n
// (z = a - i b; the mean for n = 0); empty above the fundamental (no excitation there).
Eigen::VectorXcd excitation_weights(int n) {
  if (n == 0) return Eigen::Vector3cd(1.0, 0.0, 0.0);
  if (n == 1) return Eigen::Vector3cd(0.0, 1.0, cd(0.0, -1.0));
  return {};
}

void add_notes(const ModalData& d, Eigen::Index n_c, int steps, double sigma, bool residual,
               std::vector<std::string>& notes) {
  const auto m = d.w.size();
  const auto rigid = m - static_cast<Eigen::Index>(d.elastic.size());
  notes.push_back(fmt::format(
      "Condensed form: the balance on the {} relative coordinates of the nonlinear elements "
      "through the receptance of {} modes (the highest at {:.6g} Hz){}{}.",
      n_c, m, std::sqrt(d.top) / units::kTwoPi,
      rigid > 0 ? fmt::format(", {} of them rigid-body modes (the mean by inertia relief: their "
                              "mean displacement held at zero)",
                              rigid)
                : "",
      residual ? fmt::format(" plus the residual flexibility of the modes left out (one "
                             "factorisation of K - sigma M, sigma = {:.4g} (rad/s)^2, {} "
                             "refinement steps): exact for the static part, the dynamic error of "
                             "the modes left out is (n w / w_r)^2 of their quasi-static term",
                             sigma, steps)
               : " without residual flexibility"));
  notes.push_back(fmt::format(
      "Condensed form damping: modal ratios from the diagonal of Phi^T C Phi; the largest "
      "coupling between modes |c_rs| / sqrt(c_rr c_ss) = {:.3g} is left out (0 for proportional "
      "damping){}.",
      d.coupling, d.rigid_damped ? "; the damping of the rigid-body modes is left out" : ""));
}

// The force level continuation of the condensed balance: R(X, lambda) = R(X, omega) -
// (lambda - 1) X_lin(omega) at a fixed omega (the receptance's excitation has factor 1),
// dR/dlambda = -X_lin(omega). Solved with the dense Jacobian (n_c (2H + 1) unknowns).
class CondensedLevelSystem final : public hbm::HarmonicSystem {
 public:
  CondensedLevelSystem(const hbm::CondensedHarmonicBalance& hb, double omega)
      : hb_(hb), omega_(omega), linear_(hb.linear_response(omega)) {}
  int size() const override { return hb_.size(); }
  Eigen::VectorXd residual(const Eigen::VectorXd& X, double lambda, Eigen::MatrixXd* J,
                           Eigen::VectorXd* dR) const override {
    Eigen::VectorXd R = hb_.residual(X, omega_, J) - (lambda - 1.0) * linear_;
    if (dR != nullptr) *dR = -linear_;
    return R;
  }
  double residual_scale(const Eigen::VectorXd& X, double /*lambda*/) const override {
    return hb_.residual_scale(X, omega_);
  }

 private:
  const hbm::CondensedHarmonicBalance& hb_;
  double omega_;
  Eigen::VectorXd linear_;
};

// Scales of the arc length: the linear response of the coordinates over the range, the range.
void condensed_scales(const hbm::CondensedHarmonicBalance& hb, const NonlinearResponseSettings& s,
                      hbm::ContinuationOptions& o) {
  double x = 0.0;
  if (s.parameter == ContinuationParameter::Frequency) {
    for (int k = 0; k <= 20; ++k)
      x = std::max(x, hb.linear_response(s.f_start + (s.f_stop - s.f_start) * k / 20.0).norm());
    o.omega_scale = s.f_stop - s.f_start;
  } else {
    x = hb.linear_response(s.frequency).norm() * std::max(std::abs(s.level_stop), 1e-12);
    o.omega_scale = std::abs(s.level_stop - s.level_start);
  }
  o.x_scale = std::isfinite(x) && x > 0.0 ? x : 1.0;
}

// Sensor coefficients (sensors x (2H + 1)) at the solution X, force factor `level`: the
// recovery of hbm/condensed.hpp with the excitation's share scaled by the level (the response is
// linear in it: z(level) = z(1) - (1 - level) z_lin).
Eigen::MatrixXd sensor_coefficients(const hbm::CondensedHarmonicBalance& hb,
                                    const Eigen::VectorXd& X, double omega, double level,
                                    Eigen::Index n_s) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n_s, hb.basis().size());
  if (n_s == 0) return out;
  for (int n = 0; n <= hb.basis().harmonics(); ++n) {
    const hbm::ModalReceptance& h = hb.harmonics()[static_cast<std::size_t>(n)];
    Eigen::VectorXcd z = hb.sensor_response(X, omega, n);
    if (level != 1.0)
      z -= (1.0 - level) * h.sensor_response(n * omega, Eigen::VectorXcd::Zero(hb.coordinates()));
    if (n == 0) {
      out.col(0) = z.real();
      continue;
    }
    out.col(hbm::HarmonicBasis::cos_index(n)) = z.real();
    out.col(hbm::HarmonicBasis::sin_index(n)) = -z.imag();
  }
  return out;
}

// The elements as element-local forces on their stacked coordinates.
std::vector<hbm::LocalForce> local_forces(const std::vector<BuiltNonlinearElement>& elements,
                                          const Stacked& st) {
  std::vector<hbm::LocalForce> out;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    hbm::LocalForce f;
    for (Eigen::Index k = 0; k < elements[e].B.rows(); ++k)
      f.coordinates.push_back(st.offset[e] + static_cast<int>(k));
    f.evaluate = [law = elements[e].element](
                     const hbm::HarmonicBasis& basis, const Eigen::VectorXd& w, double omega,
                     Eigen::VectorXd& force, Eigen::MatrixXd* J, Eigen::VectorXd* df_domega) {
      law->harmonic_force(basis, w, omega, force, J, df_domega);
    };
    out.push_back(std::move(f));
  }
  return out;
}

// Element e's coefficients in the condensed unknowns (coordinate-major, contiguous).
Eigen::VectorXd element_coefficients(const hbm::CondensedHarmonicBalance& hb, const Stacked& st,
                                     const std::vector<BuiltNonlinearElement>& elements,
                                     const Eigen::VectorXd& X, std::size_t e) {
  const int s = hb.basis().size();
  return X.segment(static_cast<Eigen::Index>(st.offset[e]) * s, elements[e].B.rows() * s);
}

void condensed_statistics(const hbm::CondensedHarmonicBalance& hb, const Stacked& st,
                          const std::vector<BuiltNonlinearElement>& elements,
                          const std::vector<hbm::ContinuationPoint>& points,
                          NonlinearResponseResult& r) {
  const auto np = static_cast<Eigen::Index>(points.size());
  const auto ne = static_cast<Eigen::Index>(elements.size());
  r.energy.setConstant(np, ne, kNaN);
  r.stick = r.slip = r.open = r.energy;
  for (Eigen::Index i = 0; i < np; ++i)
    for (Eigen::Index e = 0; e < ne; ++e) {
      const auto ei = static_cast<std::size_t>(e);
      const hbm::ElementLoop loop = elements[ei].element->loop(
          hb.basis(),
          element_coefficients(hb, st, elements, points[static_cast<std::size_t>(i)].X, ei),
          r.frequency[static_cast<std::size_t>(i)]);
      r.energy(i, e) = loop.energy_per_cycle;
      r.stick(i, e) = loop.stick_fraction;
      r.slip(i, e) = loop.slip_fraction;
      r.open(i, e) = loop.open_fraction;
    }
}

void condensed_stability(const hbm::CondensedHarmonicBalance& hb,
                         const NonlinearResponseSettings& s,
                         const std::vector<hbm::ContinuationPoint>& points,
                         NonlinearResponseResult& r) {
  const std::size_t np = points.size();
  r.max_real_exponent.assign(np, kNaN);
  r.instability.assign(np, "");
  if (s.stability == NonlinearStability::Fold) {
    r.unstable = unstable_after(r.turning_points, np);
    for (std::size_t i = 0; i < np; ++i) r.instability[i] = r.unstable[i] ? "fold" : "none";
    return;
  }
  r.unstable.assign(np, 0);
  for (std::size_t i = 0; i < np; ++i)
    record_floquet(hbm::condensed_hill_stability(hb, points[i].X, r.frequency[i]), i, r);
}

// Refusals of settings the condensed form does not support.
void check_settings(const NonlinearResponseSettings& s, const Context& context) {
  if (s.parameter != ContinuationParameter::Frequency &&
      s.parameter != ContinuationParameter::ForceLevel)
    throw context.error("parameter",
                        "\"frequency\" or \"force_level\" with coordinates = "
                        "\"condensed\"",
                        "another parameter",
                        "the receptance is built once at the reference speed: use coordinates "
                        "= \"modal\" or \"physical\"");
  if (s.stability == NonlinearStability::Monodromy)
    throw context.error("stability", "\"fold\" or \"hill\" with coordinates = \"condensed\"",
                        "\"monodromy\"",
                        "the time march needs the structure's matrices; the condensed form "
                        "knows its receptance only");
  if (s.n_modes < 1)
    throw context.error("n_modes", "at least 1 mode with coordinates = \"condensed\"",
                        std::to_string(s.n_modes));
}

hbm::ContinuationResult trace(const hbm::CondensedHarmonicBalance& hb,
                              const NonlinearResponseSettings& s, const Context& context,
                              hbm::ContinuationOptions& o) {
  const bool frequency = s.parameter == ContinuationParameter::Frequency;
  o.omega_start = frequency ? s.f_start : s.level_start;
  o.omega_end = frequency ? s.f_stop : s.level_stop;
  o.step = s.step;
  o.max_step = s.max_step;
  o.max_points = s.max_points;
  o.tolerance = s.tolerance;
  condensed_scales(hb, s, o);
  const Eigen::VectorXd X0 = Eigen::VectorXd::Zero(hb.size());
  hbm::ContinuationResult curve;
  if (frequency) {
    curve = hbm::continue_in_frequency(hb, X0, o);
    if (curve.status == Status::Ok) land_on_end(hb, o.omega_end, o.tolerance, curve.points);
  } else {
    const CondensedLevelSystem level(hb, s.frequency);
    curve = hbm::continue_in_frequency(level, X0, o);
    if (curve.status == Status::Ok) land_on_end(level, o.omega_end, o.tolerance, curve.points);
  }
  if (curve.points.empty())
    throw NumericalError(
        context.name(),
        fmt::format("the condensed harmonic balance could not start at {}: {}. Start where the "
                    "response is nearly linear, or give the mean loads that close the contacts.",
                    frequency ? fmt::format("{:.6g} Hz", s.f_start / units::kTwoPi)
                              : fmt::format("force factor {:.6g}", s.level_start),
                    curve.message));
  return curve;
}

}  // namespace

std::vector<hbm::ModalReceptance> condensed_receptances(const NonlinearProblem& p,
                                                        const NonlinearResponseSettings& s,
                                                        const CondensedFormOptions& options,
                                                        const Context& context,
                                                        std::vector<std::string>& notes) {
  check_representable(p.system, s, context);
  const NonlinearCoordinates& c = p.modes;
  const ModalData d = modal_data(c, context);
  const Eigen::MatrixXd& Phi = c.basis;
  const Stacked st = stack_elements(p.elements, p.system.size());
  const Eigen::MatrixXd& S = p.sensors.rows;
  const Eigen::MatrixXd& F = p.excitation;
  const Eigen::Index n_c = st.B.rows(), m = d.w.size();
  if (F.cols() != 3) throw std::logic_error("condensed form: excitation columns a_0, a_1, b_1");
  const Eigen::MatrixXd U = st.B * Phi, Us = S * Phi;

  // Residual flexibility on the columns [B^T, F]: R = B Y, sensors S Y.
  Eigen::MatrixXd R, Rs;
  int steps = 0;
  const double sigma = -kShift * d.top;
  if (options.residual_flexibility) {
    Eigen::MatrixXd L(p.system.size(), n_c + F.cols());
    L << st.B.transpose(), F;
    const Eigen::MatrixXd Y = flexibility_of_modes_left_out(p.system.K_at(s.speed), p.system.M, Phi,
                                                            sigma, L, context, steps);
    R = st.B * Y;
    Rs = S * Y;
  }
  std::vector<Eigen::Index> all(static_cast<std::size_t>(m));
  for (Eigen::Index r = 0; r < m; ++r) all[static_cast<std::size_t>(r)] = r;

  std::vector<hbm::ModalReceptance> out(static_cast<std::size_t>(s.harmonics) + 1);
  for (int n = 0; n <= s.harmonics; ++n) {
    hbm::ModalReceptance& h = out[static_cast<std::size_t>(n)];
    const std::vector<Eigen::Index>& modes = n == 0 ? d.elastic : all;
    h.natural_frequency = entries(d.w, modes);
    h.damping_ratio = entries(d.zeta, modes);
    h.left = complex_columns(U, modes);
    h.right = h.left;
    h.sensor_left = complex_columns(Us, modes);
    if (R.size() > 0) {
      h.residual = R.leftCols(n_c).cast<cd>();
      h.sensor_residual = Rs.leftCols(n_c).cast<cd>();
    }
    const Eigen::VectorXcd weights = excitation_weights(n);
    if (weights.size() == 0) continue;
    h.modal_excitation = complex_columns(Phi, modes).transpose() * (F.cast<cd>() * weights);
    if (R.size() > 0) {
      h.residual_excitation = R.rightCols(F.cols()).cast<cd>() * weights;
      h.sensor_residual_excitation = Rs.rightCols(F.cols()).cast<cd>() * weights;
    }
  }
  add_notes(d, n_c, steps, sigma, options.residual_flexibility, notes);
  return out;
}

NonlinearResponseResult run_nonlinear_condensed(const NonlinearProblem& p,
                                                const NonlinearResponseSettings& s,
                                                const Context& context,
                                                const CondensedFormOptions& options) {
  check_settings(s, context);
  NonlinearResponseResult r;
  r.parameter = s.parameter;
  r.condensed = true;
  r.sensors = p.sensors.names;
  r.sensor_rotational = p.sensors.rotational;
  for (const auto& e : p.elements) {
    r.elements.push_back(e.name);
    r.element_kinds.push_back(e.kind);
  }
  r.highest_mode_hz = p.modes.highest_mode / units::kTwoPi;
  r.harmonics = s.harmonics;
  r.time_samples = s.time_samples > 0 ? s.time_samples : hbm::default_time_samples(s.harmonics);
  const Stacked st = stack_elements(p.elements, p.system.size());
  r.coordinates = static_cast<int>(st.B.rows());
  const hbm::CondensedHarmonicBalance hb(
      r.coordinates, hbm::HarmonicBasis(s.harmonics, r.time_samples),
      condensed_receptances(p, s, options, context, r.notes), local_forces(p.elements, st));

  hbm::ContinuationOptions o;
  const hbm::ContinuationResult curve = trace(hb, s, context, o);
  const bool frequency = s.parameter == ContinuationParameter::Frequency;
  const Eigen::Index n_s = p.sensors.rows.rows();
  for (const auto& point : curve.points) {
    const double omega = frequency ? point.omega : s.frequency;
    const double level = frequency ? 1.0 : point.omega;
    r.sensor_coefficients.push_back(sensor_coefficients(hb, point.X, omega, level, n_s));
    r.frequency.push_back(omega);
    r.level.push_back(level);
    r.speed.push_back(s.speed);
    r.iterations.push_back(point.iterations);
    r.residual.push_back(point.residual / hb.residual_scale(point.X, omega));
  }
  condensed_statistics(hb, st, p.elements, curve.points, r);
  r.turning_points = turning_points(frequency ? r.frequency : r.level,
                                    1e-3 * std::abs(o.omega_end - o.omega_start));
  condensed_stability(hb, s, curve.points, r);
  r.loop_point = largest_point(r);
  if (r.loop_point >= 0) {
    const auto at = static_cast<std::size_t>(r.loop_point);
    for (std::size_t e = 0; e < p.elements.size(); ++e)
      r.loops.push_back(p.elements[e].element->loop(
          hb.basis(), element_coefficients(hb, st, p.elements, curve.points[at].X, e),
          r.frequency[at]));
  }
  mark_ended_early(curve, r);
  return r;
}

}  // namespace geardyn::analyses
