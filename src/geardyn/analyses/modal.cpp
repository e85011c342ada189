#include "geardyn/analyses/modal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "geardyn/assembly/system_pencil.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"

namespace geardyn::analyses {

namespace {

using units::kTwoPi;
constexpr double kRpmPerRadS = 60.0 / kTwoPi;
constexpr std::size_t kPlottedModes = 6;
/// Modes with less lateral energy than this are left out of the lateral mode-shape plots.
constexpr double kPlottedLateralFraction = 0.2;

}  // namespace

eig::Method to_eig_method(EigenMethod method) {
  switch (method) {
    case EigenMethod::Auto:
      return eig::Method::Auto;
    case EigenMethod::Dense:
      return eig::Method::Dense;
    case EigenMethod::Sparse:
      return eig::Method::Sparse;
  }
  return eig::Method::Auto;
}

double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
  return mac(a, a.squaredNorm(), b, b.squaredNorm());
}

double mac(const Eigen::VectorXcd& a, double a_norm2, const Eigen::VectorXcd& b, double b_norm2) {
  if (a_norm2 == 0.0 || b_norm2 == 0.0) return 0.0;
  return std::norm(a.dot(b)) / (a_norm2 * b_norm2);
}

RigidBodyTest::RigidBodyTest(const fe::LinearSystem& system, double speed,
                             const eig::QuadraticPencil* pencil)
    : system_(&system),
      pencil_(pencil),
      space_(eig::rigid_body_space(system.K_at(speed), system.M,
                                   fe::rigid_body_candidates(system.dofs))) {}

bool RigidBodyTest::operator()(std::complex<double> lambda, const Eigen::VectorXcd& shape) const {
  if (space_.dimension() == 0) return false;
  if (eig::rigid_body_fraction(space_, system_->M, shape) < kRigidEnergyFraction) return false;
  if (pencil_ == nullptr) return true;
  const std::complex<double> m = shape.dot(system_->M * shape);
  const std::complex<double> d = shape.dot(pencil_->apply_damping(shape));
  const std::complex<double> lambda_d = std::abs(m) > 0.0 ? -d / m : 0.0;
  return std::abs(lambda - lambda_d) >= 0.5 * std::abs(lambda);
}

ModeKind mode_kind(const fe::ModeFamilies& f) {
  if (f.lateral > kKindFraction) return ModeKind::Lateral;
  if (f.torsional > kKindFraction) return ModeKind::Torsional;
  if (f.axial > kKindFraction) return ModeKind::Axial;
  if (f.body > kKindFraction) return ModeKind::Solid;
  return ModeKind::Coupled;
}

Whirl whirl_direction(const fe::LinearSystem& system, const Eigen::VectorXcd& shape,
                      std::complex<double> lambda, double speed, const fe::ModeFamilies* families) {
  if (lambda.imag() == 0.0) return Whirl::None;  // a real root does not oscillate
  const double lateral =
      families != nullptr ? families->lateral : fe::mode_families(system, shape).lateral;
  if (lateral < 0.01) return Whirl::None;
  const fe::DofMap& dofs = system.dofs;
  auto value = [&](int node, model::Component c) -> std::complex<double> {
    const int e = dofs.dof(node, c);
    return e >= 0 ? shape[e] : std::complex<double>(0.0, 0.0);
  };
  // The orbit of the node that moves most laterally. When no node translates (a disk that
  // only tilts), the orbit of the spin axis' tip, (theta_y, -theta_x) per unit length, of the
  // node that tilts most; its sense is Im(theta_x conj(theta_y)).
  int best = -1;
  double best_amplitude = 0.0;
  bool tilt = false;
  for (int pass = 0; pass < 2 && best < 0; ++pass) {
    const auto cx = pass == 0 ? model::Component::Ux : model::Component::Rx;
    const auto cy = pass == 0 ? model::Component::Uy : model::Component::Ry;
    for (int node = 0; node < dofs.num_nodes(); ++node) {
      const double a = std::norm(value(node, cx)) + std::norm(value(node, cy));
      if (a > best_amplitude) {
        best_amplitude = a;
        best = node;
      }
    }
    tilt = pass == 1;
  }
  if (best < 0) return Whirl::None;
  const std::complex<double> X = value(best, tilt ? model::Component::Rx : model::Component::Ux);
  const std::complex<double> Y = value(best, tilt ? model::Component::Ry : model::Component::Uy);
  // Orbit for the member of the pair with Im lambda > 0; for Im lambda < 0 the sense flips.
  const double sense = std::imag(X * std::conj(Y)) * (lambda.imag() > 0.0 ? 1.0 : -1.0);
  const double circularity = 2.0 * std::abs(sense) / (std::norm(X) + std::norm(Y));
  if (circularity < 1e-4) return Whirl::None;
  const double ratio = dofs.node(best).speed_ratio;
  const double spin = (ratio < 0.0 ? -1.0 : 1.0) * (speed < 0.0 ? -1.0 : 1.0);
  return sense * spin > 0.0 ? Whirl::Forward : Whirl::Backward;
}

Mode describe_mode(const fe::LinearSystem& system, std::complex<double> lambda,
                   const Eigen::VectorXcd& shape, double residual, double speed,
                   const RigidBodyTest& rigid) {
  Mode m;
  m.eigenvalue = lambda;
  m.shape = shape;
  Eigen::Index imax = 0;
  const double largest = shape.size() > 0 ? shape.cwiseAbs2().maxCoeff(&imax) : 0.0;
  if (largest > 0.0) m.shape /= shape[imax];
  m.residual = residual;
  m.rigid_body = rigid(lambda, m.shape);
  if (m.rigid_body) {
    m.frequency_hz = 0.0;
    m.damped_frequency_hz = 0.0;
    m.damping_ratio = 0.0;
  } else {
    m.frequency_hz = std::abs(lambda) / kTwoPi;
    m.damped_frequency_hz = std::abs(lambda.imag()) / kTwoPi;
    m.damping_ratio = eig::damping_ratio(lambda);
  }
  m.families = fe::mode_families(system, m.shape);
  m.kind = m.rigid_body ? ModeKind::Rigid : mode_kind(m.families);
  m.whirl =
      m.rigid_body ? Whirl::None : whirl_direction(system, m.shape, lambda, speed, &m.families);
  return m;
}

double ModalResult::max_residual() const {
  double r = 0.0;
  for (const auto& m : undamped) r = std::max(r, m.residual);
  for (const auto& m : complex) r = std::max(r, m.residual);
  return r;
}

bool is_unstable(const Mode& mode) {
  return !mode.rigid_body && mode.damping_ratio < -kUnstableDampingRatio;
}

double log_decrement(double damping_ratio) {
  if (!(std::abs(damping_ratio) < 1.0)) return std::numeric_limits<double>::quiet_NaN();
  return kTwoPi * damping_ratio / std::sqrt(1.0 - damping_ratio * damping_ratio);
}

ModalResult run_modal(const model::Model& /*model*/, const ModalSettings& settings,
                      const Context& context) {
  if (settings.n_modes < 1)
    throw context.error("n_modes", "at least 1", fmt::format("{}", settings.n_modes));
  if (!std::isfinite(settings.speed))
    throw context.error("speed_rpm", "a finite speed",
                        fmt::format("{}", settings.speed * kRpmPerRadS));
  if (!(std::isfinite(settings.shift) && settings.shift >= 0.0))
    throw context.error("shift_hz", "a finite frequency >= 0",
                        fmt::format("{}", settings.shift / kTwoPi));
  const fe::LinearSystem& system = context.system();
  if (system.size() == 0)
    throw InputError(context.where(), "model", "at least one unconstrained DOF",
                     "a system without DOFs");
  Progress& progress = context.progress();

  const auto start = std::chrono::steady_clock::now();
  ModalResult result;
  result.speed = settings.speed;
  result.complex_requested = settings.complex_modes;
  progress.start("modal", settings.complex_modes ? 2 : 1);

  // Undamped, non-gyroscopic modes with the stiffness at the analysis speed.
  // More modes than DOFs cannot exist: the undamped problem has n, the quadratic one at most 2n
  // roots (n pairs when all oscillate). Those that exist are returned with a note.
  const int n = static_cast<int>(system.size());
  eig::SymmetricEigenOptions so;
  so.n_modes = std::min(settings.n_modes, n);
  so.method = to_eig_method(settings.method);
  if (settings.shift > 0.0) so.shift = settings.shift * settings.shift;
  const eig::SymmetricEigenResult real =
      eig::solve_symmetric(system.K_at(settings.speed), system.M, so);
  const RigidBodyTest rigid_undamped(system, settings.speed);
  result.undamped_report = real.brief_report();
  result.stiffness_asymmetry = real.asymmetry;
  for (Eigen::Index j = 0; j < real.eigenvalues.size(); ++j) {
    const double omega = std::sqrt(std::max(real.eigenvalues[j], 0.0));
    result.undamped.push_back(describe_mode(system, {0.0, omega},
                                            real.eigenvectors.col(j).cast<std::complex<double>>(),
                                            real.residuals[j], settings.speed, rigid_undamped));
  }
  // A dense solve computes every eigenvalue: fewer than asked is all the model has.
  auto complete = [](Status st, eig::Method used) {
    return st == Status::FewerModes && used == eig::Method::Dense;
  };
  Status status = complete(real.status, real.method_used) ? Status::Ok : real.status;
  std::string message = status == Status::Ok ? "" : "undamped modes: " + real.message;
  if (settings.n_modes > n || complete(real.status, real.method_used))
    result.fewer_modes_note = fmt::format(
        "n_modes = {} asks for more modes than the model has ({} unconstrained DOFs): {} undamped "
        "modes are returned",
        settings.n_modes, n, real.eigenvalues.size());
  progress.update(1);

  if (settings.complex_modes) {
    eig::QuadraticEigenOptions qo;
    qo.n_modes = settings.n_modes;
    qo.method = to_eig_method(settings.method);
    if (settings.shift > 0.0) qo.target = {0.0, settings.shift};
    const eig::QuadraticPencil pencil = assembly::pencil_at(system, settings.speed);
    const eig::QuadraticEigenResult cx = eig::solve_quadratic(pencil, qo);
    const RigidBodyTest rigid(system, settings.speed, &pencil);
    result.complex_report = cx.brief_report();
    for (Eigen::Index j = 0; j < cx.eigenvalues.size(); ++j)
      result.complex.push_back(describe_mode(system, cx.eigenvalues[j], cx.eigenvectors.col(j),
                                             cx.residuals[j], settings.speed, rigid));
    if (complete(cx.status, cx.method_used)) {
      result.fewer_modes_note +=
          fmt::format("{}{} complex modes exist (each conjugate pair once) and are returned",
                      result.fewer_modes_note.empty()
                          ? fmt::format("n_modes = {} asks for more modes than the model has: ",
                                        settings.n_modes)
                          : "; ",
                      cx.eigenvalues.size());
    } else if (cx.status != Status::Ok) {
      status = worse(status, cx.status);
      message += (message.empty() ? "" : "; ") + std::string("complex modes: ") + cx.message;
    }
    progress.update(2);
  }
  progress.finish();
  result.status = status;
  result.message = message;
  result.run_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

// ---------------------------------------------------------------------------------------------
// Output

namespace {

// Relative amplitude of each sensor in each mode: |phi at the sensor| divided by the largest
// amplitude of the same kind (translation or rotation, whose units differ) anywhere in the
// mode. It answers "which modes carry this DOF" (e.g. the swing of a driven gear, as in J. Hong,
// L. Jiang, X. Xu, Y. Ma, "High cycle fatigue failure with radial cracks in gears of
// aero-engines", Chinese Journal of Aeronautics, 2020, Table 3). A constrained sensor DOF
// reads 0.
void add_sensor_columns(Table& t, const model::Model& model, const fe::LinearSystem& system,
                        const std::vector<Mode>& modes) {
  const auto& dofs = system.dofs;
  for (const auto& sensor : model.sensors) {
    const int node = dofs.find_node(sensor.node);
    if (node < 0) continue;
    const int eq = dofs.dof(node, sensor.dof);
    const bool rotation = static_cast<int>(sensor.dof) >= 3;
    std::vector<double> relative;
    for (const Mode& m : modes) {
      double largest = 0.0;
      for (int k = 0; k < m.shape.size(); ++k)
        if (!dofs.is_generalized(k) && (static_cast<int>(dofs.dof_component(k)) >= 3) == rotation)
          largest = std::max(largest, std::abs(m.shape[k]));
      relative.push_back(eq < 0 || largest == 0.0 ? 0.0 : std::abs(m.shape[eq]) / largest);
    }
    t.add(sensor.name + "_relative", "", relative);
  }
}

Table modes_table(const ModalResult& r) {
  Table t;
  t.name = "modes";
  const bool cx = r.complex_requested;
  t.title = cx ? fmt::format("Complex modes at {:.6g} rpm", r.speed * kRpmPerRadS)
               : fmt::format("Undamped modes at {:.6g} rpm", r.speed * kRpmPerRadS);
  std::vector<double> mode, f, fd, zeta, delta, re, im, res;
  std::vector<std::string> whirl, kind, stable;
  const auto& modes = r.primary();
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const Mode& m = modes[i];
    mode.push_back(static_cast<double>(i + 1));
    f.push_back(m.frequency_hz);
    fd.push_back(m.damped_frequency_hz);
    zeta.push_back(m.damping_ratio);
    delta.push_back(log_decrement(m.damping_ratio));
    stable.emplace_back(is_unstable(m) ? "no" : "yes");
    re.push_back(m.eigenvalue.real());
    im.push_back(m.eigenvalue.imag());
    whirl.emplace_back(to_string(m.whirl));
    kind.emplace_back(to_string(m.kind));
    res.push_back(m.residual);
  }
  t.add("mode", "", mode);
  t.add("frequency_hz", "Hz", f);
  t.add("damped_frequency_hz", "Hz", fd);
  t.add("damping_ratio", "", zeta);
  t.add("log_decrement", "", delta);
  t.add_text("stable", stable);
  t.add("real", "rad/s", re);
  t.add("imag", "rad/s", im);
  t.add_text("whirl", whirl);
  t.add_text("kind", kind);
  t.add("residual", "", res);
  return t;
}

Table undamped_table(const ModalResult& r) {
  Table t;
  t.name = "undamped_modes";
  t.title = fmt::format("Undamped modes (no damping, no gyroscopic terms) at {:.6g} rpm",
                        r.speed * kRpmPerRadS);
  std::vector<double> mode, f, res;
  std::vector<std::string> kind;
  for (std::size_t i = 0; i < r.undamped.size(); ++i) {
    mode.push_back(static_cast<double>(i + 1));
    f.push_back(r.undamped[i].frequency_hz);
    kind.emplace_back(to_string(r.undamped[i].kind));
    res.push_back(r.undamped[i].residual);
  }
  t.add("mode", "", mode);
  t.add("frequency_hz", "Hz", f);
  t.add_text("kind", kind);
  t.add("residual", "", res);
  return t;
}

Table shapes_table(const model::Model& model, const fe::LinearSystem& system,
                   const std::vector<Mode>& modes) {
  Table t;
  t.name = "mode_shapes";
  t.title =
      "Mode shapes: amplitude of each node DOF; translations normalised to the largest "
      "translation of the mode, rotations to the largest rotation";
  std::vector<double> mode, position;
  std::vector<std::string> node, shaft;
  std::array<std::vector<double>, 6> amplitude;
  const fe::DofMap& dofs = system.dofs;
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const Eigen::VectorXcd& s = modes[i].shape;
    // Translations and rotations have different units: each group is normalised to its own
    // largest amplitude in the mode.
    double scale_t = 0.0, scale_r = 0.0;
    for (Eigen::Index e = 0; e < s.size(); ++e) {
      // Generalised coordinates (modal coordinates of coupled solids) are not node DOFs.
      if (dofs.is_generalized(static_cast<int>(e))) continue;
      const bool rotation = static_cast<int>(dofs.dof_component(static_cast<int>(e))) >= 3;
      if (rotation)
        scale_r = std::max(scale_r, std::abs(s[e]));
      else
        scale_t = std::max(scale_t, std::abs(s[e]));
    }
    for (int k = 0; k < dofs.num_nodes(); ++k) {
      const fe::NodeInfo& info = dofs.node(k);
      mode.push_back(static_cast<double>(i + 1));
      node.push_back(info.name);
      shaft.push_back(info.shaft >= 0 && static_cast<std::size_t>(info.shaft) < model.shafts.size()
                          ? model.shafts[static_cast<std::size_t>(info.shaft)].name
                          : std::string());
      position.push_back(info.axial_position);
      const auto eq = dofs.node_dofs(k);
      for (std::size_t c = 0; c < 6; ++c) {
        const double scale = c >= 3 ? scale_r : scale_t;
        amplitude[c].push_back(eq[c] >= 0 && scale > 0.0 ? std::abs(s[eq[c]]) / scale : 0.0);
      }
    }
  }
  t.add("mode", "", mode);
  t.add_text("node", node);
  t.add_text("shaft", shaft);
  t.add("axial_position_m", "m", position);
  for (std::size_t c = 0; c < 6; ++c) {
    const bool rotation = c >= 3;
    t.add(model::kComponentNames[c], rotation ? "normalised rotation" : "normalised translation",
          amplitude[c]);
  }
  return t;
}

std::vector<Plot> shape_plots(const model::Model& model, const fe::LinearSystem& system,
                              const std::vector<Mode>& modes) {
  std::vector<Plot> plots;
  const fe::DofMap& dofs = system.dofs;
  for (std::size_t sh = 0; sh < model.shafts.size(); ++sh) {
    std::vector<int> nodes;
    for (int k = 0; k < dofs.num_nodes(); ++k)
      if (dofs.node(k).shaft == static_cast<int>(sh)) nodes.push_back(k);
    if (nodes.empty()) continue;
    std::sort(nodes.begin(), nodes.end(), [&](int a, int b) {
      return dofs.node(a).axial_position < dofs.node(b).axial_position;
    });
    Plot p;
    p.name = "mode_shapes_" + model.shafts[sh].name;
    p.title = fmt::format(
        "Lateral mode shapes along shaft '{}' (the first {} modes with at least {:.0f} % lateral "
        "energy; rigid-body, torsional and axial modes are in the mode_shapes table)",
        model.shafts[sh].name, kPlottedModes, 100 * kPlottedLateralFraction);
    p.x_label = "axial position [m]";
    p.y_label = "lateral amplitude sqrt(|ux|^2 + |uy|^2) [-]";
    // Only modes that move laterally: a torsional, axial or rigid-body mode has a lateral
    // amplitude made of rounding, which a per-mode normalisation would blow up to full height.
    std::size_t shown = 0;
    for (std::size_t i = 0; i < modes.size() && shown < kPlottedModes; ++i) {
      const Mode& m = modes[i];
      if (m.rigid_body || m.families.lateral < kPlottedLateralFraction) continue;
      ++shown;
      auto lateral = [&](int k) {
        const int ex = dofs.dof(k, model::Component::Ux), ey = dofs.dof(k, model::Component::Uy);
        return std::sqrt((ex >= 0 ? std::norm(m.shape[ex]) : 0.0) +
                         (ey >= 0 ? std::norm(m.shape[ey]) : 0.0));
      };
      // Normalised to the largest lateral amplitude anywhere in the model, so shafts that move
      // less in a mode are drawn smaller.
      double scale = 0.0;
      for (int k = 0; k < dofs.num_nodes(); ++k) scale = std::max(scale, lateral(k));
      Trace tr;
      tr.name =
          fmt::format("mode {}: {:.4g} Hz, {}, {}{}", i + 1, m.frequency_hz, to_string(m.kind),
                      to_string(m.whirl), is_unstable(m) ? ", UNSTABLE" : "");
      tr.mode = Trace::Mode::LinesMarkers;
      for (int k : nodes) {
        tr.x.push_back(dofs.node(k).axial_position);
        tr.y.push_back(scale > 0.0 ? lateral(k) / scale : 0.0);
      }
      p.traces.push_back(std::move(tr));
    }
    plots.push_back(std::move(p));
  }
  return plots;
}

}  // namespace

AnalysisOutput modal_output(const model::Model& model, const ModalSettings& /*settings*/,
                            const ModalResult& result, const Context& context) {
  const fe::LinearSystem& system = context.system();
  AnalysisOutput out;
  out.name = context.name();
  out.type = "modal";
  out.status = result.status;
  out.message = result.message;
  out.run_time_s = result.run_time_s;
  out.tables.push_back(modes_table(result));
  add_sensor_columns(out.tables.back(), model, system, result.primary());
  out.tables.push_back(undamped_table(result));
  out.tables.push_back(shapes_table(model, system, result.primary()));
  out.plots = shape_plots(model, system, result.primary());

  if (!result.fewer_modes_note.empty()) out.notes.push_back(result.fewer_modes_note + ".");
  std::string unstable;
  const auto& primary = result.primary();
  for (std::size_t i = 0; i < primary.size(); ++i) {
    const Mode& m = primary[i];
    if (!is_unstable(m)) continue;
    unstable +=
        fmt::format("{}mode {} ({}, {}, {:.6g} Hz): damping ratio {:.3g}, log decrement {:.3g}",
                    unstable.empty() ? "" : "; ", i + 1, to_string(m.kind), to_string(m.whirl),
                    m.frequency_hz, m.damping_ratio, log_decrement(m.damping_ratio));
  }
  if (!unstable.empty())
    out.notes.push_back(fmt::format(
        "UNSTABLE at {:.6g} rpm: {}. A mode with negative damping grows; a steady-state "
        "response at this speed is not what the machine reaches (check cross-coupled bearing or "
        "seal coefficients and damping).",
        result.speed * kRpmPerRadS, unstable));
  out.notes.push_back(fmt::format("Undamped modes: {}.", result.undamped_report));
  if (!model.sensors.empty())
    out.notes.push_back(
        "Columns <sensor>_relative: the sensor's amplitude in the mode divided by the largest "
        "amplitude of the same kind (translation or rotation) in that mode.");
  if (result.complex_requested)
    out.notes.push_back(fmt::format("Complex modes at {:.6g} rpm: {}.", result.speed * kRpmPerRadS,
                                    result.complex_report));
  // Backward error of a polynomial eigenpair: F. Tisseur, "Backward error and condition of
  // polynomial eigenvalue problems", Linear Algebra and its Applications, 2000.
  out.notes.push_back(fmt::format(
      "Largest backward error of any mode {:.2e} (column 'residual': ||P(lambda) x|| relative to "
      "the matrix norms, Tisseur 2000); a mode's relative frequency error is at most about its "
      "condition number times this.",
      result.max_residual()));
  if (result.stiffness_asymmetry > 1e-12)
    out.notes.push_back(fmt::format(
        "K is not symmetric (cross-coupled bearings, ||K - K^T|| / ||K|| = {:.2e}): the undamped "
        "modes use its symmetric part; the complex modes use K as it is.",
        result.stiffness_asymmetry));
  if (system.has_modal_damping())
    out.notes.push_back(fmt::format(
        "Modal damping acts through {} undamped modes at zero speed; modes above them get none.",
        system.modal_coefficients.size()));
  if (result.speed == 0.0 && result.complex_requested)
    out.notes.push_back(
        "At zero speed the two lateral modes of each pair of an axisymmetric rotor have the same "
        "frequency; any combination of them is a mode, so their whirl labels are arbitrary.");
  out.notes.push_back(
      "Whirl: orbit sense at the node with the largest lateral amplitude relative to its spin; "
      "'none' for real roots, non-lateral modes and straight-line orbits. Kind: energy fraction "
      "above 0.8 in one DOF family, else coupled. Column 'log_decrement': 2 pi zeta / "
      "sqrt(1 - zeta^2), negative for a growing mode; 'stable' is 'no' when the damping ratio is "
      "below -1e-5 (rounding of the eigen-solve stays below that). Rigid-body roots (kind 'rigid') "
      "are reported "
      "at 0 Hz: a root is rigid when 99 % of its kinetic energy lies in the rigid-body motions "
      "(translations, rotations, spins) that the stiffness leaves unstrained and it is the zero "
      "root of that motion; the test is on the shape, so it holds on any mesh.");
  return out;
}

}  // namespace geardyn::analyses
