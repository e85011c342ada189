#include "geardyn/analyses/campbell.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/assembly/system_pencil.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/eig/projected_quadratic.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"

namespace geardyn::analyses {

namespace {

using units::kTwoPi;
constexpr double kRpmPerRadS = 60.0 / kTwoPi;
/// Eigenvalues closer than this (relative) count as one repeated eigenvalue when tracking.
constexpr double kRepeatedTolerance = 1e-6;

void add_line(std::vector<EngineOrderLine>& lines, const std::string& label, double order) {
  for (auto& l : lines) {
    if (std::abs(l.order - order) <= 1e-9 * std::max(1.0, order)) {
      l.label += " / " + label;
      return;
    }
  }
  lines.push_back({label, order});
}

std::string format_order(double order) { return fmt::format("{:.6g}", order); }

// Squared norm of the projection of c onto span(Q) relative to ||c||^2, Q orthonormal columns.
double subspace_mac(const Eigen::MatrixXcd& Q, const Eigen::VectorXcd& c) {
  const double nc = c.squaredNorm();
  if (nc == 0.0) return 0.0;
  return (Q.adjoint() * c).squaredNorm() / nc;
}

}  // namespace

std::vector<EngineOrderLine> engine_order_lines(const model::Model& model,
                                                const fe::LinearSystem& system,
                                                const CampbellSettings& settings) {
  std::vector<EngineOrderLine> lines;
  for (double eo : settings.engine_orders) add_line(lines, "EO " + format_order(eo), eo);
  if (settings.shaft_orders) {
    for (const auto& shaft : model.shafts) {
      const double r = std::abs(shaft.speed_ratio);
      if (r > 0.0) add_line(lines, fmt::format("{} 1x ({})", shaft.name, format_order(r)), r);
    }
  }
  if (settings.mesh_orders) {
    for (const auto& mesh : model.gear_meshes) {
      auto order_of = [&](const std::string& gear, int teeth) {
        const int node = system.dofs.find_node(gear);
        if (teeth <= 0 || node < 0) return 0.0;
        return teeth * std::abs(system.dofs.node(node).speed_ratio);
      };
      double order = order_of(mesh.gear1, mesh.teeth1);
      if (order == 0.0) order = order_of(mesh.gear2, mesh.teeth2);
      if (order > 0.0)
        add_line(lines, fmt::format("{} mesh ({})", mesh.name, format_order(order)), order);
    }
  }
  return lines;
}

std::vector<int> best_assignment(const Eigen::MatrixXd& score) {
  // Hungarian method with potentials (the O(n^2 m) shortest augmenting path form) on the cost
  // -score; rows and columns are 1-based inside, index 0 is the virtual start column.
  const int n = static_cast<int>(score.rows()), m = static_cast<int>(score.cols());
  if (n > m) throw std::invalid_argument("best_assignment: more rows than columns");
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(static_cast<std::size_t>(n + 1), 0.0),
      v(static_cast<std::size_t>(m + 1), 0.0);
  std::vector<int> p(static_cast<std::size_t>(m + 1), 0), way(static_cast<std::size_t>(m + 1), 0);
  auto at = [](auto& vec, int i) -> auto& { return vec[static_cast<std::size_t>(i)]; };
  for (int i = 1; i <= n; ++i) {
    at(p, 0) = i;
    int j0 = 0;
    std::vector<double> minv(static_cast<std::size_t>(m + 1), inf);
    std::vector<char> used(static_cast<std::size_t>(m + 1), 0);
    do {
      at(used, j0) = 1;
      const int i0 = at(p, j0);
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (at(used, j)) continue;
        const double cur = -score(i0 - 1, j - 1) - at(u, i0) - at(v, j);
        if (cur < at(minv, j)) {
          at(minv, j) = cur;
          at(way, j) = j0;
        }
        if (at(minv, j) < delta) {
          delta = at(minv, j);
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (at(used, j)) {
          at(u, at(p, j)) += delta;
          at(v, j) -= delta;
        } else {
          at(minv, j) -= delta;
        }
      }
      j0 = j1;
    } while (at(p, j0) != 0);
    do {
      const int j1 = at(way, j0);
      at(p, j0) = at(p, j1);
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> assignment(static_cast<std::size_t>(n), -1);
  for (int j = 1; j <= m; ++j)
    if (at(p, j) != 0) assignment[static_cast<std::size_t>(at(p, j) - 1)] = j - 1;
  return assignment;
}

namespace {

void validate(const CampbellSettings& settings, const fe::LinearSystem& system,
              const Context& context) {
  if (settings.speeds.empty())
    throw context.error("speed_rpm", "at least one speed", "an empty list");
  for (std::size_t i = 0; i < settings.speeds.size(); ++i) {
    const double s = settings.speeds[i];
    if (!std::isfinite(s) || s < 0.0)
      throw context.error(fmt::format("speed_rpm[{}]", i), "a finite speed >= 0",
                          fmt::format("{}", s * kRpmPerRadS));
    if (i > 0 && !(s > settings.speeds[i - 1]))
      throw context.error(
          fmt::format("speed_rpm[{}]", i), "strictly increasing speeds",
          fmt::format("{} after {}", s * kRpmPerRadS, settings.speeds[i - 1] * kRpmPerRadS));
  }
  if (settings.n_modes < 1)
    throw context.error("n_modes", "at least 1", fmt::format("{}", settings.n_modes));
  if (!(settings.mac_threshold >= 0.0 && settings.mac_threshold <= 1.0))
    throw context.error("mac_threshold", "a value in [0, 1]",
                        fmt::format("{}", settings.mac_threshold));
  for (double eo : settings.engine_orders)
    if (!(std::isfinite(eo) && eo > 0.0))
      throw context.error("engine_orders", "orders > 0", fmt::format("{}", eo));
  if (system.size() == 0)
    throw InputError(context.where(), "model", "at least one unconstrained DOF",
                     "a system without DOFs");
}

// Counts the solves the projection could not certify, and keeps where and why the first was.
void add_fallback(CampbellResult& result, const std::string& reason) {
  if (reason.empty()) return;
  ++result.projection_fallbacks;
  if (result.first_fallback.empty()) result.first_fallback = reason;
}

// The eigen-solves of a sweep. Method Auto on models above kProjectionMinDofs: the projection
// onto one speed-independent basis (eig/projected_quadratic.hpp), kept and enriched from speed to
// speed; a speed where it cannot certify every mode (NotConverged, FewerModes, a failed basis) is
// solved again by solve_quadratic, the reference path. Dense / Sparse: the reference path only.
// Not thread-safe (the basis grows): one per thread.
class ModeSolver {
 public:
  ModeSolver(const fe::LinearSystem& system, const CampbellSettings& settings)
      : system_(system), settings_(settings) {
    if (projects(system, settings)) projection_.emplace(assembly::pencil_parts(system));
  }

  static bool projects(const fe::LinearSystem& system, const CampbellSettings& settings) {
    return settings.method == EigenMethod::Auto && system.size() > kProjectionMinDofs;
  }

  // The modes of `pencil` (= assembly::pencil_at(system, speed)); `label` gets the method used,
  // `fallback` where and why the projection could not certify them (empty when it could).
  eig::QuadraticEigenResult solve(const eig::QuadraticPencil& pencil, double speed,
                                  const eig::QuadraticEigenOptions& qo, std::string& label,
                                  std::string& fallback) {
    fallback.clear();
    if (projection_) {
      if (!settings_.warm_start) projection_.emplace(assembly::pencil_parts(system_));
      const assembly::SpeedIncrements inc = assembly::speed_increments(system_, speed);
      eig::QuadraticEigenResult r = projection_->solve(pencil, speed, inc.dK, inc.dC, qo);
      if (r.status == Status::Ok) {
        label = "projected";
        return r;
      }
      fallback = fmt::format("at {:.6g} rpm: {}", speed * kRpmPerRadS, r.message);
    }
    eig::QuadraticEigenOptions reference = qo;
    reference.method = to_eig_method(settings_.method);
    eig::QuadraticEigenResult r = eig::solve_quadratic(pencil, reference);
    label = std::string(eig::to_string(r.method_used));
    return r;
  }
  // The basis the chunks start from (no-ops without a kept projection: cold start, no projection).
  void keep_basis() {
    if (projection_ && settings_.warm_start) projection_->keep_basis();
  }
  void restore_basis() {
    if (projection_ && settings_.warm_start) projection_->restore_basis();
  }
  Eigen::Index basis_size() const { return projection_ ? projection_->basis_size() : 0; }

 private:
  // Below this size the full dense solve is as cheap as the projected one.
  static constexpr int kProjectionMinDofs = 30;
  const fe::LinearSystem& system_;
  const CampbellSettings& settings_;
  std::optional<eig::ProjectedQuadratic> projection_;
};

// The modes computed at one speed (phase (a) of run_campbell), and how the solve went.
struct SpeedSolve {
  std::vector<Mode> candidates;  // every elastic mode computed, in the solver's order
  Status status = Status::Ok;    // the solver's; FewerModes is judged by the tracker
  std::string message;
  int converged = 0;      // roots returned, rigid-body roots included
  int rigid_roots = 0;    // rigid-body roots among them
  bool complete = false;  // a dense solve: every root the model has was computed
  std::string method;     // "projected", "dense", "sparse"
  int operations = 0;
  std::vector<std::string> fallbacks;  // solves the projection could not certify
  Eigen::Index basis_size = 0;         // projection basis after the solve
};

// One worker's solver over chunks of speeds (phase (a) of run_campbell): the ModeSolver, the
// rigid-body test and what is carried from speed to speed within a chunk (the Arnoldi start
// vector, the room made for rigid-body roots), all returned to the seed at the start of every
// chunk. Not copyable: the rigid-body test points at pencil_.
class SpeedSolver {
 public:
  SpeedSolver(const fe::LinearSystem& system, const CampbellSettings& settings, int n_candidates)
      : system_(system),
        settings_(settings),
        n_candidates_(n_candidates),
        modes_(system, settings) {
    // Without speed-dependent bearings K(Omega) = K: the rigid-body space (rigid_body_space of
    // K, the costly part of the test) is the same at every speed and is built once; the test
    // reads the damping of the current speed's pencil through its pointer to pencil_.
    if (system.speed_bearings.empty())
      fixed_rigid_.emplace(system, settings.speeds.front(), &pencil_);
  }
  SpeedSolver(const SpeedSolver&) = delete;
  SpeedSolver& operator=(const SpeedSolver&) = delete;

  // The same on every instance: solves the first speed (which finds the rigid-body roots) and,
  // on large models, the fastest one (whose gyroscopic directions every chunk would otherwise
  // add again by enrichment, a full-size solve per vector), then keeps the basis so built. Runs
  // once. On small models the larger basis costs more in every projected solve than the
  // enrichment saves. Measured (BM_Campbell100, ROSS rotors of bench/ross, idle, 2026-11-27):
  // 294 DOFs 0.14 s without vs 0.22 s with, 6 006 DOFs 3.42 vs 3.67 s, 60 006 DOFs 30.5 vs
  // 27.0 s.
  static constexpr Eigen::Index kTopSpeedSeedDofs = 20000;
  void seed() {
    if (seeded_) return;
    seed_operations_ = solve(settings_.speeds.front()).operations;
    const double top =
        *std::max_element(settings_.speeds.begin(), settings_.speeds.end(),
                          [](double a, double b) { return std::abs(a) < std::abs(b); });
    if (system_.size() > kTopSpeedSeedDofs && top != settings_.speeds.front())
      seed_operations_ += solve(top).operations;
    seed_rigid_roots_ = rigid_roots_;
    modes_.keep_basis();
    seeded_ = true;
  }
  // Back to the seed: the kept basis, no start vector, the seed's rigid-body roots.
  void start_chunk() {
    seed();
    modes_.restore_basis();
    start_vector_.resize(0);
    rigid_roots_ = seed_rigid_roots_;
  }
  SpeedSolve solve(double speed);
  ModeSolver& modes() { return modes_; }
  int seed_operations() const { return seed_operations_; }

 private:
  std::vector<Mode> describe(const eig::QuadraticEigenResult& cx, double speed,
                             const RigidBodyTest& rigid, int& found_rigid) const;

  const fe::LinearSystem& system_;
  const CampbellSettings& settings_;
  int n_candidates_ = 0;
  ModeSolver modes_;
  eig::QuadraticPencil pencil_;  // of the speed being solved
  std::optional<RigidBodyTest> fixed_rigid_;
  Eigen::VectorXd start_vector_;
  // Rigid-body roots (lambda = 0, e.g. free torsion: a double root per rigid-body motion) have
  // no frequency to track; they are solved for, counted and left out of the tracking, and the
  // request grows by their number so that n_candidates elastic modes remain.
  int rigid_roots_ = 0;
  int seed_rigid_roots_ = 0;
  int seed_operations_ = 0;
  bool seeded_ = false;
};

std::vector<Mode> SpeedSolver::describe(const eig::QuadraticEigenResult& cx, double speed,
                                        const RigidBodyTest& rigid, int& found_rigid) const {
  std::vector<Mode> modes;
  modes.reserve(static_cast<std::size_t>(cx.eigenvalues.size()));
  found_rigid = 0;
  for (Eigen::Index j = 0; j < cx.eigenvalues.size(); ++j) {
    modes.push_back(describe_mode(system_, cx.eigenvalues[j], cx.eigenvectors.col(j),
                                  cx.residuals[j], speed, rigid));
    if (modes.back().rigid_body) ++found_rigid;
  }
  return modes;
}

SpeedSolve SpeedSolver::solve(double speed) {
  pencil_ = assembly::pencil_at(system_, speed);
  std::optional<RigidBodyTest> at_speed;
  if (!fixed_rigid_) at_speed.emplace(system_, speed, &pencil_);
  const RigidBodyTest& rigid = fixed_rigid_ ? *fixed_rigid_ : *at_speed;
  eig::QuadraticEigenOptions qo;
  qo.method = to_eig_method(settings_.method);
  qo.start = start_vector_;
  SpeedSolve out;
  eig::QuadraticEigenResult cx;
  std::vector<Mode> modes;
  for (int attempt = 0; attempt < 2; ++attempt) {
    qo.n_modes = n_candidates_ + rigid_roots_;
    std::string fallback;
    cx = modes_.solve(pencil_, speed, qo, out.method, fallback);
    if (!fallback.empty()) out.fallbacks.push_back(std::move(fallback));
    out.operations += cx.operations;
    modes = describe(cx, speed, rigid, out.rigid_roots);
    if (out.rigid_roots <= rigid_roots_) break;
    rigid_roots_ = out.rigid_roots;  // one more solve with room for the rigid-body roots
  }
  out.status = cx.status;
  out.message = cx.message;
  out.converged = cx.converged;
  out.complete = out.method == "dense";
  out.basis_size = modes_.basis_size();
  if (out.method == "sparse" && settings_.warm_start) start_vector_ = eig::start_vector(cx);
  out.candidates.reserve(modes.size());
  for (Mode& m : modes)
    if (!m.rigid_body) out.candidates.push_back(std::move(m));
  return out;
}

// Tracks modes from speed to speed (phase (b) of run_campbell), in speed order, and gathers
// what the speeds' solves report into the result.
class Tracker {
 public:
  Tracker(const fe::LinearSystem& system, const CampbellSettings& settings, int n_candidates,
          CampbellResult& result)
      : system_(system), settings_(settings), result_(result) {
    n_tracks_ = settings.n_modes;
    result_.candidates_per_speed = n_candidates;
  }

  // Extends every track by the modes solved at speeds[i]; called for i = 0, 1, ... in order.
  void track(std::size_t i, SpeedSolve& solved);
  // The status, message and methods of the sweep.
  void finish();

 private:
  void start_tracks(const SpeedSolve& solved);
  void gather(std::size_t i, SpeedSolve& solved);
  const Eigen::VectorXcd& reference(std::size_t t) const {
    return reference_index_[t] >= 0 ? previous_[static_cast<std::size_t>(reference_index_[t])].shape
                                    : stale_[t];
  }
  Eigen::MatrixXd score(const std::vector<Mode>& candidates, const std::vector<double>& norms,
                        bool first) const;
  std::vector<int> assign(const Eigen::MatrixXd& score, int n_cand, bool first) const;
  void record(std::size_t i, double speed, const std::vector<Mode>& candidates,
              const std::vector<int>& assigned, const Eigen::MatrixXd& score, bool first);

  const fe::LinearSystem& system_;
  const CampbellSettings& settings_;
  CampbellResult& result_;
  int n_tracks_ = 0;
  // The reference of each track is its last assigned shape: the candidate reference_index_ of
  // the previous speed (previous_), or stale_ when the track had no candidate there.
  std::vector<int> reference_index_;
  std::vector<Eigen::VectorXcd> stale_;
  std::vector<std::complex<double>> reference_l_;  // and its eigenvalue
  std::vector<bool> has_reference_;
  std::vector<Mode> previous_;          // every elastic mode computed at the previous speed
  std::vector<double> previous_norms_;  // their squared norms
  std::vector<std::string> methods_;
  Status status_ = Status::Ok;
  std::string first_problem_;
  int problem_speeds_ = 0;
};

// Score of every (track, candidate) pair: the MAC with the track's last shape.
Eigen::MatrixXd Tracker::score(const std::vector<Mode>& candidates,
                               const std::vector<double>& norms, bool first) const {
  const int n_cand = static_cast<int>(candidates.size());
  Eigen::MatrixXd score = Eigen::MatrixXd::Zero(n_tracks_, n_cand);
  if (first) return score;
  for (int t = 0; t < n_tracks_; ++t) {
    const auto ut = static_cast<std::size_t>(t);
    if (!has_reference_[ut]) continue;
    // A track whose previous eigenvalue is repeated (e.g. the two whirl directions of an
    // isotropic rotor at rest) owns only the subspace of that eigenvalue, since any basis of
    // it is as good as the solver's; score candidates against the whole subspace, spanned by
    // every mode computed at the previous speed with that eigenvalue, tracked or spare.
    std::vector<const Eigen::VectorXcd*> group;
    if (reference_index_[ut] >= 0) {
      for (const Mode& p : previous_)
        if (std::abs(p.eigenvalue - reference_l_[ut]) <=
            kRepeatedTolerance * std::max(std::abs(reference_l_[ut]), 1e-300))
          group.push_back(&p.shape);
    }
    const Eigen::VectorXcd& ref = reference(ut);
    if (group.size() > 1) {
      Eigen::MatrixXcd basis(ref.size(), static_cast<Eigen::Index>(group.size()));
      for (std::size_t g = 0; g < group.size(); ++g)
        basis.col(static_cast<Eigen::Index>(g)) = *group[g];
      const Eigen::HouseholderQR<Eigen::MatrixXcd> qr(basis);
      const Eigen::MatrixXcd Q =
          qr.householderQ() * Eigen::MatrixXcd::Identity(basis.rows(), basis.cols());
      for (int c = 0; c < n_cand; ++c)
        score(t, c) = subspace_mac(Q, candidates[static_cast<std::size_t>(c)].shape);
    } else {
      const double nr = reference_index_[ut] >= 0
                            ? previous_norms_[static_cast<std::size_t>(reference_index_[ut])]
                            : ref.squaredNorm();
      for (int c = 0; c < n_cand; ++c) {
        const auto uc = static_cast<std::size_t>(c);
        score(t, c) = mac(ref, nr, candidates[uc].shape, norms[uc]);
      }
    }
  }
  return score;
}

// The candidate of each track (-1: none). At the first speed the lowest modes start the tracks
// in order of frequency.
std::vector<int> Tracker::assign(const Eigen::MatrixXd& score, int n_cand, bool first) const {
  std::vector<int> assigned(static_cast<std::size_t>(n_tracks_), -1);
  if (first) {
    for (int t = 0; t < n_tracks_ && t < n_cand; ++t) assigned[static_cast<std::size_t>(t)] = t;
  } else if (n_cand >= n_tracks_) {
    assigned = best_assignment(score);
  } else if (n_cand > 0) {
    const std::vector<int> by_candidate = best_assignment(score.transpose());
    for (int c = 0; c < n_cand; ++c)
      assigned[static_cast<std::size_t>(by_candidate[static_cast<std::size_t>(c)])] = c;
  }
  return assigned;
}

void Tracker::record(std::size_t i, double speed, const std::vector<Mode>& candidates,
                     const std::vector<int>& assigned, const Eigen::MatrixXd& score, bool first) {
  for (int t = 0; t < n_tracks_; ++t) {
    const auto ut = static_cast<std::size_t>(t);
    TrackPoint& pt = result_.tracks[ut][i];
    pt.speed = speed;
    const int c = assigned[ut];
    if (c < 0) {
      // The reference stays the last assigned shape: copied out of the previous speed's modes,
      // which the current ones replace.
      if (reference_index_[ut] >= 0) stale_[ut] = reference(ut);
      reference_index_[ut] = -1;
      pt.ambiguous = true;
      ++result_.ambiguous_points;
      continue;
    }
    const Mode& m = candidates[static_cast<std::size_t>(c)];
    pt.eigenvalue = m.eigenvalue;
    pt.frequency_hz = m.frequency_hz;
    pt.damped_frequency_hz = m.damped_frequency_hz;
    pt.damping_ratio = m.damping_ratio;
    pt.whirl = m.whirl;
    pt.kind = m.kind;
    pt.residual = m.residual;
    pt.mac = first || !has_reference_[ut] ? 1.0 : score(t, c);
    pt.ambiguous = pt.mac < settings_.mac_threshold;
    if (pt.ambiguous) ++result_.ambiguous_points;
    reference_index_[ut] = c;
    stale_[ut].resize(0);
    reference_l_[ut] = m.eigenvalue;
    has_reference_[ut] = true;
  }
}

// At the first speed: the tracks, fewer when the model has fewer modes than asked.
void Tracker::start_tracks(const SpeedSolve& solved) {
  if (solved.complete && static_cast<int>(solved.candidates.size()) < n_tracks_) {
    result_.fewer_modes_note = fmt::format(
        "n_modes = {} asks for more modes than the model has: {} elastic modes exist ({} "
        "unconstrained DOFs) and are tracked",
        n_tracks_, solved.candidates.size(), system_.size());
    n_tracks_ = static_cast<int>(solved.candidates.size());
  }
  const auto n = static_cast<std::size_t>(n_tracks_);
  result_.tracks.assign(n, std::vector<TrackPoint>(settings_.speeds.size()));
  reference_index_.assign(n, -1);
  stale_.assign(n, Eigen::VectorXcd());
  reference_l_.assign(n, {0.0, 0.0});
  has_reference_.assign(n, false);
}

// What the solve at speeds[i] reports: status, method, operations, fallbacks, residuals.
void Tracker::gather(std::size_t i, SpeedSolve& solved) {
  result_.total_operations += solved.operations;
  result_.rigid_body_roots = std::max(result_.rigid_body_roots, solved.rigid_roots);
  result_.projection_basis =
      std::max(result_.projection_basis, static_cast<int>(solved.basis_size));
  for (const std::string& f : solved.fallbacks) add_fallback(result_, f);
  if (std::find(methods_.begin(), methods_.end(), solved.method) == methods_.end())
    methods_.push_back(solved.method);
  for (const Mode& m : solved.candidates)
    result_.max_residual = std::max(result_.max_residual, m.residual);
  // The spares are optional: fewer modes only matters below the number of tracks.
  if (solved.status == Status::FewerModes &&
      (solved.converged - solved.rigid_roots >= n_tracks_ || solved.complete))
    solved.status = Status::Ok;
  if (solved.status != Status::Ok) {
    ++problem_speeds_;
    status_ = worse(status_, solved.status);
    if (first_problem_.empty())
      first_problem_ =
          fmt::format("at {:.6g} rpm: {}", settings_.speeds[i] * kRpmPerRadS, solved.message);
  }
}

void Tracker::track(std::size_t i, SpeedSolve& solved) {
  if (result_.tracks.empty()) start_tracks(solved);
  gather(i, solved);
  std::vector<double> norms(solved.candidates.size());
  for (std::size_t c = 0; c < norms.size(); ++c)
    norms[c] = solved.candidates[c].shape.squaredNorm();
  const bool first =
      std::none_of(has_reference_.begin(), has_reference_.end(), [](bool b) { return b; });
  const Eigen::MatrixXd s = score(solved.candidates, norms, first);
  const std::vector<int> assigned = assign(s, static_cast<int>(solved.candidates.size()), first);
  record(i, settings_.speeds[i], solved.candidates, assigned, s, first);
  previous_ = std::move(solved.candidates);
  previous_norms_ = std::move(norms);
  solved.candidates.clear();
}

void Tracker::finish() {
  for (const auto& m : methods_) result_.method += (result_.method.empty() ? "" : ", ") + m;
  result_.status = status_;
  if (status_ != Status::Ok)
    result_.message = fmt::format("eigen-solve trouble at {} of {} speeds; first {}",
                                  problem_speeds_, settings_.speeds.size(), first_problem_);
}

// A root of a function of the speed, followed between two grid speeds where it changes sign.
struct Bracket {
  double speed = 0.0;
  std::complex<double> lambda;
  double g = 0.0;
};

// Solves the quadratic problem at one speed for the root that continues a tracked mode: the root
// nearest a predicted eigenvalue, accepted only when the next nearest is at least twice as far
// (otherwise another mode is too close to tell them apart by eigenvalue).
class RootProbe {
 public:
  // Counts its solves, their operations and fallbacks in `result`.
  RootProbe(const fe::LinearSystem& system, const CampbellSettings& settings, ModeSolver& solver,
            CampbellResult& result)
      : system_(system), settings_(settings), solver_(solver), result_(result) {}

  bool enabled() const { return settings_.refine_crossings; }

  bool at(double speed, std::complex<double> predicted, Mode& out) const {
    const eig::QuadraticPencil pencil = assembly::pencil_at(system_, speed);
    eig::QuadraticEigenOptions qo;
    qo.method = to_eig_method(settings_.method);
    qo.n_modes = std::min<int>(3, static_cast<int>(system_.size()));
    qo.target = predicted;
    std::string method, fallback;
    const eig::QuadraticEigenResult cx = solver_.solve(pencil, speed, qo, method, fallback);
    ++result_.refinement_solves;
    result_.total_operations += cx.operations;
    add_fallback(result_, fallback);
    const double inf = std::numeric_limits<double>::infinity();
    double nearest = inf, second = inf;
    Eigen::Index best = -1;
    for (Eigen::Index j = 0; j < cx.eigenvalues.size(); ++j) {
      // Each conjugate pair is listed once; compare in the upper half plane.
      const std::complex<double> l = cx.eigenvalues[j];
      const double d = std::abs(std::complex<double>(l.real(), std::abs(l.imag())) - predicted);
      if (d < nearest) {
        second = nearest;
        nearest = d;
        best = j;
      } else if (d < second) {
        second = d;
      }
    }
    if (best < 0 || !(second >= 2.0 * nearest)) return false;
    out = Mode{};
    out.eigenvalue = cx.eigenvalues[best];
    if (out.eigenvalue.imag() < 0.0) out.eigenvalue = std::conj(out.eigenvalue);
    out.shape = out.eigenvalue == cx.eigenvalues[best]
                    ? Eigen::VectorXcd(cx.eigenvectors.col(best))
                    : Eigen::VectorXcd(cx.eigenvectors.col(best).conjugate());
    out.frequency_hz = std::abs(out.eigenvalue) / kTwoPi;
    out.damped_frequency_hz = std::abs(out.eigenvalue.imag()) / kTwoPi;
    out.damping_ratio = eig::damping_ratio(out.eigenvalue);
    out.residual = cx.residuals[best];
    out.families = fe::mode_families(system_, out.shape);
    out.kind = mode_kind(out.families);
    out.whirl = whirl_direction(system_, out.shape, out.eigenvalue, speed, &out.families);
    return true;
  }

 private:
  const fe::LinearSystem& system_;
  const CampbellSettings& settings_;
  ModeSolver& solver_;
  CampbellResult& result_;
};

// Root of g(mode(Omega), Omega) between lo and hi (g of opposite signs) by regula falsi with the
// Illinois modification (M. Dowell, P. Jarratt, "A modified regula falsi method for computing
// the root of an equation", BIT 11, 1971), each evaluation a solve at that speed for the root
// predicted by linear interpolation of lambda between the current bracket ends. Stops when a step
// or the bracket is below 1e-13 of the speed, when |g| has fallen below 1e-12 of its values at
// the grid speeds (the eigenvalues themselves are good to about 1e-13 relative on small models,
// less on very fine meshes), or after 20 evaluations (superlinear convergence needs about 6-10);
// false when the root could not be followed (the caller keeps the linear estimate).
template <class G>
bool refine_root(const RootProbe& probe, Bracket lo, Bracket hi, const G& g, double& root,
                 Mode& at_root) {
  int side = 0;
  double previous = std::numeric_limits<double>::quiet_NaN();
  const double g_small = 1e-12 * std::max(std::abs(lo.g), std::abs(hi.g));
  for (int iteration = 0; iteration < 20; ++iteration) {
    double c = (lo.speed * hi.g - hi.speed * lo.g) / (hi.g - lo.g);
    const double left = std::min(lo.speed, hi.speed), right = std::max(lo.speed, hi.speed);
    if (!(c > left && c < right)) c = 0.5 * (left + right);
    const double w = (c - lo.speed) / (hi.speed - lo.speed);
    Mode m;
    if (!probe.at(c, lo.lambda + w * (hi.lambda - lo.lambda), m)) return false;
    const double gc = g(m, c);
    root = c;
    at_root = m;
    const double tol = 1e-13 * std::max(std::abs(c), 1e-300);
    if (std::abs(gc) <= g_small || std::abs(c - previous) <= tol || right - left <= 2.0 * tol)
      return true;
    previous = c;
    if ((gc < 0.0) == (lo.g < 0.0)) {
      lo = {c, m.eigenvalue, gc};
      if (side == -1) hi.g *= 0.5;
      side = -1;
    } else {
      hi = {c, m.eigenvalue, gc};
      if (side == 1) lo.g *= 0.5;
      side = 1;
    }
  }
  return true;  // 20 steps of a superlinear method: as close as the eigenvalues allow
}

bool oscillates(const TrackPoint& p) {
  return std::isfinite(p.frequency_hz) && p.frequency_hz > 0.0 && p.eigenvalue.imag() > 0.0;
}

// Critical speeds: sign changes of g(Omega) = f(Omega) - order Omega / 2pi between grid speeds,
// each refined by root-finding on the eigenvalue curve (linear interpolation when the root
// cannot be followed). Real roots (no oscillation) are skipped. Ordered by speed.
std::vector<CriticalSpeed> find_critical_speeds(const CampbellResult& result,
                                                const RootProbe& probe) {
  std::vector<CriticalSpeed> found;
  for (std::size_t t = 0; t < result.tracks.size(); ++t) {
    const auto& track = result.tracks[t];
    for (const auto& line : result.lines) {
      auto g = [&](const TrackPoint& p) { return p.frequency_hz - line.order * p.speed / kTwoPi; };
      auto record = [&](const TrackPoint& a, const TrackPoint& b, double w) {
        CriticalSpeed cs;
        cs.mode = static_cast<int>(t) + 1;
        cs.order = line.order;
        cs.line = line.label;
        cs.speed = a.speed + w * (b.speed - a.speed);
        cs.frequency_hz = a.frequency_hz + w * (b.frequency_hz - a.frequency_hz);
        cs.damping_ratio = a.damping_ratio + w * (b.damping_ratio - a.damping_ratio);
        cs.whirl = w <= 0.5 ? a.whirl : b.whirl;
        cs.kind = w <= 0.5 ? a.kind : b.kind;
        cs.ambiguous = a.ambiguous || b.ambiguous;
        cs.refined = w == 0.0 || w == 1.0;  // on a grid speed: exact
        if (!cs.refined && probe.enabled()) {
          double root = cs.speed;
          Mode m;
          auto gm = [&](const Mode& mode, double speed) {
            return mode.frequency_hz - line.order * speed / kTwoPi;
          };
          if (refine_root(probe, {a.speed, a.eigenvalue, g(a)}, {b.speed, b.eigenvalue, g(b)}, gm,
                          root, m)) {
            cs.refined = true;
            cs.speed = root;
            cs.frequency_hz = m.frequency_hz;
            cs.damping_ratio = m.damping_ratio;
            cs.whirl = m.whirl;
            cs.kind = m.kind;
          }
        }
        found.push_back(cs);
      };
      if (!track.empty() && oscillates(track[0]) && track[0].speed > 0.0 && g(track[0]) == 0.0)
        record(track[0], track[0], 0.0);
      for (std::size_t i = 0; i + 1 < track.size(); ++i) {
        const TrackPoint &a = track[i], &b = track[i + 1];
        if (!oscillates(a) || !oscillates(b)) continue;
        const double ga = g(a), gb = g(b);
        if (gb == 0.0)
          record(a, b, 1.0);
        else if (ga * gb < 0.0)
          record(a, b, ga / (ga - gb));
      }
    }
  }
  std::stable_sort(found.begin(), found.end(), [](const CriticalSpeed& a, const CriticalSpeed& b) {
    return a.speed < b.speed;
  });
  return found;
}

// Onsets of instability: where a track's damping ratio goes from >= 0 to below
// -kUnstableDampingRatio, the root of zeta(Omega) = 0 between the grid speeds (the earlier grid
// speed when zeta there is already slightly negative, within the neutral margin); the first
// speed when the track is unstable there. Ordered by speed.
std::vector<InstabilityOnset> find_onsets(const CampbellResult& result, const RootProbe& probe) {
  std::vector<InstabilityOnset> found;
  for (std::size_t t = 0; t < result.tracks.size(); ++t) {
    const auto& track = result.tracks[t];
    double lowest = std::numeric_limits<double>::quiet_NaN(), at = lowest;
    for (const auto& p : track)
      if (std::isfinite(p.damping_ratio) && !(p.damping_ratio >= lowest)) {
        lowest = p.damping_ratio;
        at = p.speed;
      }
    for (std::size_t i = 0; i < track.size(); ++i) {
      const TrackPoint& b = track[i];
      if (!is_unstable(b)) continue;
      const TrackPoint* a = i > 0 ? &track[i - 1] : nullptr;
      if (a != nullptr && (is_unstable(*a) || !std::isfinite(a->damping_ratio))) continue;
      InstabilityOnset o;
      o.mode = static_cast<int>(t) + 1;
      o.min_damping_ratio = lowest;
      o.speed_of_min = at;
      o.at_first_speed = a == nullptr;
      const TrackPoint& from = a == nullptr ? b : *a;
      o.speed = from.speed;
      o.frequency_hz = from.frequency_hz;
      o.whirl = from.whirl;
      o.kind = from.kind;
      if (a != nullptr && a->damping_ratio > 0.0) {
        // Linear estimate first, then (when enabled) the root on the eigenvalue curve.
        o.speed = a->speed +
                  a->damping_ratio / (a->damping_ratio - b.damping_ratio) * (b.speed - a->speed);
        double root = o.speed;
        Mode m;
        auto zeta = [](const Mode& mode, double) { return mode.damping_ratio; };
        if (probe.enabled() &&
            refine_root(probe, {a->speed, a->eigenvalue, a->damping_ratio},
                        {b.speed, b.eigenvalue, b.damping_ratio}, zeta, root, m)) {
          o.refined = true;
          o.speed = root;
          o.frequency_hz = m.frequency_hz;
          o.whirl = m.whirl;
          o.kind = m.kind;
        }
      }
      found.push_back(o);
    }
  }
  std::stable_sort(
      found.begin(), found.end(),
      [](const InstabilityOnset& x, const InstabilityOnset& y) { return x.speed < y.speed; });
  return found;
}

}  // namespace

namespace {

// The path whose BLAS rule applies (sweep_threads): the projection (CHOLMOD / UMFPACK for its
// basis and checks), Arnoldi (UMFPACK) and the condensation of DOFs without mass (UMFPACK) call
// the system BLAS (FactorPath::Sparse); the dense solve of a pencil with mass on every DOF runs
// on Eigen alone (FactorPath::Banded: no system BLAS).
FactorPath blas_path(const fe::LinearSystem& system, const CampbellSettings& settings) {
  const eig::QuadraticEigenOptions defaults;
  const bool dense =
      !ModeSolver::projects(system, settings) &&
      (settings.method == EigenMethod::Dense ||
       (settings.method == EigenMethod::Auto && system.size() <= defaults.dense_limit));
  const bool mass_everywhere = system.M.rows() > 0 && system.M.diagonal().minCoeff() > 0.0;
  return dense && mass_everywhere ? FactorPath::Banded : FactorPath::Sparse;
}

// Phases (a) and (b) of run_campbell over every speed: batches of one chunk per thread, each
// chunk solved by one thread from the seed, then the batch tracked in speed order.
void sweep_speeds(const CampbellSettings& settings, std::size_t chunk,
                  std::vector<std::unique_ptr<SpeedSolver>>& solvers, Tracker& tracker,
                  Progress& progress) {
  const std::size_t n_speeds = settings.speeds.size();
  const std::size_t n_chunks = (n_speeds + chunk - 1) / chunk;
  std::atomic<std::size_t> solved_speeds{0};
  for (std::size_t c0 = 0; c0 < n_chunks; c0 += solvers.size()) {
    const std::size_t c1 = std::min(n_chunks, c0 + solvers.size());
    const std::size_t first = c0 * chunk;
    const std::size_t last = std::min(n_speeds, c1 * chunk);
    std::vector<SpeedSolve> batch(last - first);
    auto solve_chunk = [&](std::size_t c, unsigned t) {
      SpeedSolver& solver = *solvers[t];
      solver.start_chunk();
      const std::size_t end = std::min(n_speeds, (c + 1) * chunk);
      for (std::size_t i = c * chunk; i < end; ++i) {
        batch[i - first] = solver.solve(settings.speeds[i]);
        ++solved_speeds;
      }
    };
    for_each_point(c0, c1, static_cast<unsigned>(c1 - c0), solve_chunk,
                   [&](std::size_t) { progress.update(solved_speeds.load()); });
    for (std::size_t i = first; i < last; ++i) tracker.track(i, batch[i - first]);
  }
}

}  // namespace

std::size_t campbell_chunk_speeds(std::size_t n_speeds, std::size_t n_dofs,
                                  std::size_t n_candidates) {
  const double shape_bytes =
      static_cast<double>(std::max<std::size_t>(n_dofs * n_candidates, 1)) * 16.0;
  const auto by_memory = static_cast<std::size_t>(kCampbellChunkBytes / shape_bytes);
  const std::size_t sixteenth = (n_speeds + 15) / 16;
  return std::max(kCampbellMinChunkSpeeds, std::min(sixteenth, by_memory));
}

CampbellResult run_campbell(const model::Model& model, const CampbellSettings& settings,
                            const Context& context) {
  const fe::LinearSystem& system = context.system();
  validate(settings, system, context);
  Progress& progress = context.progress();

  const auto start = std::chrono::steady_clock::now();
  CampbellResult result;
  result.speeds = settings.speeds;
  result.lines = engine_order_lines(model, system, settings);
  const std::size_t n_speeds = settings.speeds.size();
  // Spare modes give the tracking room when a mode climbs out of the computed window.
  const int n_candidates = settings.n_modes + std::max(2, settings.n_modes / 2);
  const std::size_t chunk = campbell_chunk_speeds(n_speeds, static_cast<std::size_t>(system.size()),
                                                  static_cast<std::size_t>(n_candidates));
  const std::size_t n_chunks = (n_speeds + chunk - 1) / chunk;
  const unsigned threads =
      sweep_threads(settings.threads, n_chunks, blas_path(system, settings), result.thread_note);
  result.threads_used = static_cast<int>(threads);
  std::vector<std::unique_ptr<SpeedSolver>> solvers;
  for (unsigned t = 0; t < threads; ++t)
    solvers.push_back(std::make_unique<SpeedSolver>(system, settings, n_candidates));
  Tracker tracker(system, settings, n_candidates, result);
  progress.start("campbell", n_speeds);
  sweep_speeds(settings, chunk, solvers, tracker, progress);
  progress.finish();
  tracker.finish();

  // The refinements, in order, on one solver returned to the seed (the seed solves, the same on
  // every thread, are counted once).
  SpeedSolver& refiner = *solvers.front();
  refiner.start_chunk();
  result.total_operations += refiner.seed_operations();
  const RootProbe probe(system, settings, refiner.modes(), result);
  result.critical_speeds = find_critical_speeds(result, probe);
  result.onsets = find_onsets(result, probe);
  result.projection_basis =
      std::max(result.projection_basis, static_cast<int>(refiner.modes().basis_size()));
  result.run_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

bool is_unstable(const TrackPoint& point) { return point.damping_ratio < -kUnstableDampingRatio; }

double instability_onset_speed(const CampbellResult& result) {
  double onset = std::numeric_limits<double>::quiet_NaN();
  for (const auto& o : result.onsets)
    if (!(o.speed >= onset)) onset = o.speed;
  return onset;
}

// ---------------------------------------------------------------------------------------------
// Output

namespace {

Table campbell_table(const CampbellResult& result) {
  Table t;
  t.name = "campbell";
  t.title = "Tracked complex modes versus speed";
  std::vector<double> rpm, mode, f, fd, zeta, delta, macs, amb, res;
  std::vector<std::string> whirl, kind, stable;
  for (std::size_t i = 0; i < result.speeds.size(); ++i) {
    for (std::size_t k = 0; k < result.tracks.size(); ++k) {
      const TrackPoint& p = result.tracks[k][i];
      rpm.push_back(result.speeds[i] * kRpmPerRadS);
      mode.push_back(static_cast<double>(k + 1));
      f.push_back(p.frequency_hz);
      fd.push_back(p.damped_frequency_hz);
      zeta.push_back(p.damping_ratio);
      delta.push_back(log_decrement(p.damping_ratio));
      stable.emplace_back(is_unstable(p) ? "no" : "yes");
      whirl.emplace_back(to_string(p.whirl));
      kind.emplace_back(to_string(p.kind));
      macs.push_back(p.mac);
      amb.push_back(p.ambiguous ? 1.0 : 0.0);
      res.push_back(p.residual);
    }
  }
  t.add("speed_rpm", "rpm", rpm);
  t.add("mode", "", mode);
  t.add("frequency_hz", "Hz", f);
  t.add("damping_ratio", "", zeta);
  t.add("log_decrement", "", delta);
  t.add_text("stable", stable);
  t.add_text("whirl", whirl);
  t.add("mac", "", macs);
  t.add("ambiguous", "", amb);
  t.add("damped_frequency_hz", "Hz", fd);
  t.add_text("kind", kind);
  t.add("residual", "", res);
  return t;
}

// "lateral_forward" / "lateral_backward" for lateral modes with a whirl, else the mode kind.
std::string crossing_kind(ModeKind kind, Whirl whirl) {
  if (kind == ModeKind::Lateral && whirl != Whirl::None)
    return fmt::format("lateral_{}", to_string(whirl));
  return std::string(to_string(kind));
}

Table critical_speeds_table(const CampbellResult& result) {
  Table t;
  t.name = "critical_speeds";
  t.title = "Critical speeds: tracked modes meeting engine-order lines";
  std::vector<double> mode, order, rpm, f, zeta, amb, refined;
  std::vector<std::string> whirl, line, kind;
  for (const auto& c : result.critical_speeds) {
    mode.push_back(c.mode);
    order.push_back(c.order);
    rpm.push_back(c.speed * kRpmPerRadS);
    f.push_back(c.frequency_hz);
    whirl.emplace_back(to_string(c.whirl));
    zeta.push_back(c.damping_ratio);
    line.push_back(c.line);
    amb.push_back(c.ambiguous ? 1.0 : 0.0);
    kind.push_back(crossing_kind(c.kind, c.whirl));
    refined.push_back(c.refined ? 1.0 : 0.0);
  }
  t.add("mode", "", mode);
  t.add("order", "", order);
  t.add("speed_rpm", "rpm", rpm);
  t.add("frequency_hz", "Hz", f);
  t.add_text("whirl", whirl);
  t.add("damping_ratio", "", zeta);
  t.add_text("line", line);
  t.add("ambiguous", "", amb);
  t.add_text("kind", kind);
  t.add("refined", "", refined);
  return t;
}

Table instability_table(const CampbellResult& result) {
  Table t;
  t.name = "instability";
  t.title = "Onset of instability: speeds where a tracked mode's damping ratio crosses zero";
  std::vector<double> mode, rpm, f, refined, first, zmin, rpm_min;
  std::vector<std::string> whirl, kind;
  for (const auto& o : result.onsets) {
    mode.push_back(o.mode);
    rpm.push_back(o.speed * kRpmPerRadS);
    f.push_back(o.frequency_hz);
    whirl.emplace_back(to_string(o.whirl));
    kind.push_back(crossing_kind(o.kind, o.whirl));
    refined.push_back(o.refined ? 1.0 : 0.0);
    first.push_back(o.at_first_speed ? 1.0 : 0.0);
    zmin.push_back(o.min_damping_ratio);
    rpm_min.push_back(o.speed_of_min * kRpmPerRadS);
  }
  t.add("mode", "", mode);
  t.add("onset_speed_rpm", "rpm", rpm);
  t.add("frequency_hz", "Hz", f);
  t.add_text("whirl", whirl);
  t.add_text("kind", kind);
  t.add("refined", "", refined);
  t.add("unstable_at_first_speed", "", first);
  t.add("min_damping_ratio", "", zmin);
  t.add("speed_of_min_damping_rpm", "rpm", rpm_min);
  return t;
}

Table engine_orders_table(const CampbellResult& result) {
  Table t;
  t.name = "engine_orders";
  t.title = "Engine-order lines (orders per revolution of the reference shaft)";
  std::vector<std::string> label;
  std::vector<double> order;
  for (const auto& l : result.lines) {
    label.push_back(l.label);
    order.push_back(l.order);
  }
  t.add_text("line", label);
  t.add("order", "", order);
  return t;
}

// One trace per track in the Campbell diagram (frequency) and the damping plot, named by the
// track's kind and whirl (forward / backward in the name, not only in the colour); points where
// the track is unstable again as a marker-only trace "mode k UNSTABLE".
void add_track_traces(const CampbellResult& result, Plot& campbell, Plot& damping) {
  for (std::size_t k = 0; k < result.tracks.size(); ++k) {
    const auto& track = result.tracks[k];
    const TrackPoint* last = nullptr;
    for (const auto& p : track)
      if (std::isfinite(p.frequency_hz)) last = &p;
    const std::string name =
        last ? fmt::format("mode {} ({})", k + 1, crossing_kind(last->kind, last->whirl))
             : fmt::format("mode {}", k + 1);
    Trace tf, tz, uf, uz;
    tf.name = tz.name = name;
    tf.mode = tz.mode = Trace::Mode::LinesMarkers;
    uf.name = uz.name = fmt::format("mode {} UNSTABLE", k + 1);
    uf.mode = uz.mode = Trace::Mode::Markers;
    for (std::size_t i = 0; i < track.size(); ++i) {
      const TrackPoint& p = track[i];
      if (!std::isfinite(p.frequency_hz)) continue;
      const double rpm = result.speeds[i] * kRpmPerRadS;
      const std::string hover =
          fmt::format("{}, zeta {:.3g}, MAC {:.3f}{}{}", to_string(p.whirl), p.damping_ratio, p.mac,
                      p.ambiguous ? ", ambiguous" : "", is_unstable(p) ? ", UNSTABLE" : "");
      tf.x.push_back(rpm);
      tf.y.push_back(p.frequency_hz);
      tf.hover.push_back(hover);
      tz.x.push_back(rpm);
      tz.y.push_back(p.damping_ratio);
      tz.hover.push_back(hover);
      if (is_unstable(p)) {
        uf.x.push_back(rpm);
        uf.y.push_back(p.frequency_hz);
        uf.hover.push_back(hover);
        uz.x.push_back(rpm);
        uz.y.push_back(p.damping_ratio);
        uz.hover.push_back(hover);
      }
    }
    campbell.traces.push_back(std::move(tf));
    damping.traces.push_back(std::move(tz));
    if (!uf.x.empty()) {
      campbell.traces.push_back(std::move(uf));
      damping.traces.push_back(std::move(uz));
    }
  }
}

// Markers at the onsets of instability (frequency on the Campbell diagram, zero damping on the
// damping plot).
void add_onset_traces(const CampbellResult& result, Plot& campbell, Plot& damping) {
  if (result.onsets.empty()) return;
  Trace tf, tz;
  tf.name = tz.name = "instability onset";
  tf.mode = tz.mode = Trace::Mode::Markers;
  for (const auto& o : result.onsets) {
    const std::string hover = fmt::format("mode {} ({}) unstable from {:.1f} rpm{}", o.mode,
                                          crossing_kind(o.kind, o.whirl), o.speed * kRpmPerRadS,
                                          o.at_first_speed ? " (or below: the first speed)" : "");
    tf.x.push_back(o.speed * kRpmPerRadS);
    tf.y.push_back(o.frequency_hz);
    tf.hover.push_back(hover);
    tz.x.push_back(o.speed * kRpmPerRadS);
    tz.y.push_back(0.0);
    tz.hover.push_back(hover);
  }
  campbell.traces.push_back(std::move(tf));
  damping.traces.push_back(std::move(tz));
}

// Dashed engine-order lines up to a little above the highest mode, so steep mesh orders do not
// squash the modes into the bottom of the plot, and markers at the critical speeds.
void add_order_traces(const CampbellResult& result, Plot& campbell) {
  const double rpm_min = result.speeds.empty() ? 0.0 : result.speeds.front() * kRpmPerRadS;
  const double rpm_max = result.speeds.empty() ? 0.0 : result.speeds.back() * kRpmPerRadS;
  double f_max = 0.0;
  for (const auto& track : result.tracks)
    for (const auto& p : track)
      if (std::isfinite(p.frequency_hz)) f_max = std::max(f_max, p.frequency_hz);
  const double y_top = f_max > 0.0 ? 1.2 * f_max : 1.0;
  for (const auto& l : result.lines) {
    Trace tr;
    tr.name = l.label;
    tr.dash = "dash";
    const double rpm_end = std::min(rpm_max, y_top * 60.0 / l.order);
    if (!(rpm_end > rpm_min)) continue;
    tr.x = {rpm_min, rpm_end};
    tr.y = {l.order * rpm_min / 60.0, l.order * rpm_end / 60.0};
    campbell.traces.push_back(std::move(tr));
  }
  if (!result.critical_speeds.empty()) {
    Trace tr;
    tr.name = "critical speeds (hover: mode, line, speed)";
    tr.mode = Trace::Mode::Markers;
    for (const auto& c : result.critical_speeds) {
      tr.x.push_back(c.speed * kRpmPerRadS);
      tr.y.push_back(c.frequency_hz);
      tr.hover.push_back(fmt::format("mode {} x {}: {:.1f} rpm, {}", c.mode, c.line,
                                     c.speed * kRpmPerRadS, crossing_kind(c.kind, c.whirl)));
    }
    campbell.traces.push_back(std::move(tr));
  }
}

std::vector<std::string> campbell_notes(const CampbellResult& result) {
  std::vector<std::string> notes;
  notes.push_back(fmt::format(
      "{} speeds, {} tracked modes ({} elastic modes computed per speed{}), method {}; largest "
      "backward error {:.2e}.",
      result.speeds.size(), result.tracks.size(), result.candidates_per_speed,
      result.rigid_body_roots > 0
          ? fmt::format(", plus {} rigid-body roots at 0 Hz that are not tracked",
                        result.rigid_body_roots)
          : std::string(),
      result.method, result.max_residual));
  notes.push_back(fmt::format(
      "Modes are tracked by shape (MAC, optimal one-to-one assignment), not by frequency order; "
      "{} of {} points have a MAC below the threshold and are flagged ambiguous (veering, or a "
      "mode leaving the computed window): refine the speed steps there.",
      result.ambiguous_points, result.speeds.size() * result.tracks.size()));
  int unrefined = 0;
  for (const auto& c : result.critical_speeds) unrefined += c.refined ? 0 : 1;
  if (result.refinement_solves == 0 && !result.critical_speeds.empty() &&
      std::none_of(result.critical_speeds.begin(), result.critical_speeds.end(),
                   [](const CriticalSpeed& c) { return c.refined; }))
    notes.push_back(
        "Critical speeds: linear interpolation of f(Omega) - order Omega / 2pi between speeds "
        "(refinement off); their accuracy is that of the speed grid.");
  else
    notes.push_back(fmt::format(
        "Critical speeds: roots of f(Omega) - order Omega / 2pi found on the eigenvalue curve "
        "between the grid speeds (regula falsi, {} extra eigen-solves), to about 1e-12 relative "
        "whatever the grid{}. Column kind: lateral_forward / lateral_backward / torsional / axial "
        "/ "
        "coupled. Frequencies are |lambda|/2pi.",
        result.refinement_solves,
        unrefined > 0 ? fmt::format("; {} could not be followed between grid speeds (another mode "
                                    "too close) and are linear interpolations (refined = 0)",
                                    unrefined)
                      : std::string()));
  if (result.projection_basis > 0)
    notes.push_back(fmt::format(
        "Projection onto {} speed-independent vectors (undamped modes at rest, enriched until "
        "every returned mode passes the full-size residual checks){}.",
        result.projection_basis,
        result.projection_fallbacks > 0
            ? fmt::format("; {} solves it could not certify were redone by the full solver, "
                          "first {}",
                          result.projection_fallbacks, result.first_fallback)
            : std::string()));
  if (!result.fewer_modes_note.empty()) notes.push_back(result.fewer_modes_note + ".");
  if (!result.thread_note.empty()) notes.push_back(result.thread_note);
  if (!result.onsets.empty()) {
    std::string list;
    for (const auto& o : result.onsets)
      list += fmt::format(
          "{}mode {} ({}, {:.6g} Hz) from {:.6g} rpm{}, lowest damping ratio "
          "{:.3g} at {:.6g} rpm",
          list.empty() ? "" : "; ", o.mode, crossing_kind(o.kind, o.whirl), o.frequency_hz,
          o.speed * kRpmPerRadS, o.at_first_speed ? " (or below: the first speed)" : "",
          o.min_damping_ratio, o.speed_of_min * kRpmPerRadS);
    notes.insert(notes.begin(),
                 fmt::format("UNSTABLE: {}. Table 'instability' lists the onset speeds (damping "
                             "ratio crossing zero, refined between grid speeds); steady-state "
                             "responses above them are not what the machine reaches.",
                             list));
  }
  notes.push_back(
      "Column 'log_decrement': 2 pi zeta / sqrt(1 - zeta^2), negative for a growing mode; "
      "'stable' is 'no' below a damping ratio of -1e-5 (rounding of the eigen-solves stays "
      "below that).");
  return notes;
}

}  // namespace

AnalysisOutput campbell_output(const model::Model& /*model*/, const CampbellSettings& /*settings*/,
                               const CampbellResult& result, const Context& context) {
  AnalysisOutput out;
  out.name = context.name();
  out.type = "campbell";
  out.status = result.status;
  out.message = result.message;
  out.run_time_s = result.run_time_s;
  out.tables.push_back(campbell_table(result));
  out.tables.push_back(critical_speeds_table(result));
  out.tables.push_back(engine_orders_table(result));
  out.tables.push_back(instability_table(result));

  Plot campbell;
  campbell.name = "campbell";
  campbell.title = "Campbell diagram";
  campbell.x_label = "speed [rpm]";
  campbell.y_label = "natural frequency |lambda|/2pi [Hz]";
  Plot damping;
  damping.name = "campbell_damping";
  damping.title = "Damping ratio versus speed";
  damping.x_label = "speed [rpm]";
  damping.y_label = "damping ratio [-]";
  add_track_traces(result, campbell, damping);
  add_order_traces(result, campbell);
  add_onset_traces(result, campbell, damping);
  out.plots.push_back(std::move(campbell));
  out.plots.push_back(std::move(damping));
  out.notes = campbell_notes(result);
  return out;
}

}  // namespace geardyn::analyses
