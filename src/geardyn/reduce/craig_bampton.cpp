#include "geardyn/reduce/craig_bampton.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"
#include "geardyn/reduce/constrained_modes.hpp"

namespace geardyn::reduce {

using SparseMatrix = Eigen::SparseMatrix<double>;

std::vector<std::string> CraigBamptonOptions::validate() const {
  std::vector<std::string> problems;
  if (n_modes < 0) problems.push_back(fmt::format("n_modes must be >= 0, found {}", n_modes));
  if (!std::isnan(frequency_max_hz)) {
    if (!(std::isfinite(frequency_max_hz) && frequency_max_hz > 0.0))
      problems.push_back(
          fmt::format("frequency_max_hz must be finite and > 0, found {}", frequency_max_hz));
    if (n_modes > 0)
      problems.push_back(
          "n_modes and frequency_max_hz are exclusive (give a mode count or a cut-off)");
  }
  if (dense_limit < 0)
    problems.push_back(fmt::format("dense_limit must be >= 0, found {}", dense_limit));
  if (block_size < 1)
    problems.push_back(fmt::format("block_size must be >= 1, found {}", block_size));
  if (!(mechanism_tolerance > 0.0 && mechanism_tolerance < 1.0))
    problems.push_back(
        fmt::format("mechanism_tolerance must be in (0, 1), found {}", mechanism_tolerance));
  krylov.validate(problems);
  return problems;
}

std::string CraigBamptonOptions::to_json() const {
  nlohmann::json j;
  j["n_modes"] = n_modes;
  j["frequency_max_hz"] =
      std::isnan(frequency_max_hz) ? nlohmann::json(nullptr) : nlohmann::json(frequency_max_hz);
  j["dense_limit"] = dense_limit;
  j["krylov"] = {{"tolerance", krylov.tolerance},
                 {"max_restarts", krylov.max_restarts},
                 {"subspace_size", krylov.subspace_size}};
  j["block_size"] = block_size;
  j["mechanism_tolerance"] = mechanism_tolerance;
  return j.dump();
}

namespace {

constexpr const char* kKey = "reduce.craig_bampton";

std::string component_name(int component) {
  static constexpr const char* kNames[] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  if (component >= 0 && component < 6) return kNames[component];
  if (component == -1) return "modal";
  return fmt::format("component {}", component);
}

std::string describe_dof(const solid::DofInfo& d) {
  return fmt::format("node {} {}", d.node_id, component_name(d.component));
}

std::string utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

// The blocks of a symmetric matrix in the partition [masters b | interior i].
struct Blocks {
  SparseMatrix bb, ib, ii;
};

Blocks partition(const SparseMatrix& A, const std::vector<int>& local,
                 const std::vector<bool>& is_master, Eigen::Index nb, Eigen::Index ni) {
  std::vector<Eigen::Triplet<double>> tbb, tib, tii;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
    const auto cu = static_cast<std::size_t>(c);
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) {
      const auto ru = static_cast<std::size_t>(it.row());
      const int lr = local[ru], lc = local[cu];
      if (is_master[ru] && is_master[cu])
        tbb.emplace_back(lr, lc, it.value());
      else if (!is_master[ru] && is_master[cu])
        tib.emplace_back(lr, lc, it.value());
      else if (!is_master[ru] && !is_master[cu])
        tii.emplace_back(lr, lc, it.value());
    }
  }
  Blocks b;
  b.bb.resize(nb, nb);
  b.ib.resize(ni, nb);
  b.ii.resize(ni, ni);
  b.bb.setFromTriplets(tbb.begin(), tbb.end());
  b.ib.setFromTriplets(tib.begin(), tib.end());
  b.ii.setFromTriplets(tii.begin(), tii.end());
  return b;
}

// max_j K_jj / M_jj over DOFs with both positive: an upper estimate of the spectrum's top
// (Rayleigh quotient of a unit vector bounds it from below, and for FE matrices it is within a
// small factor of lambda_max). Scale for the mechanism test.
double spectrum_scale(const SparseMatrix& K, const SparseMatrix& M) {
  const Eigen::VectorXd kd = K.diagonal(), md = M.diagonal();
  double s = 0.0;
  for (Eigen::Index j = 0; j < kd.size(); ++j)
    if (kd[j] > 0.0 && md[j] > 0.0) s = std::max(s, kd[j] / md[j]);
  return s;
}

// One free motion in words: how much of it is rigid-body motion of the nodes it moves, which
// rigid-body components dominate, and where it is largest.
std::string describe_motion(const Eigen::VectorXd& phi, const std::vector<solid::DofInfo>& info) {
  const double largest = phi.cwiseAbs().maxCoeff();
  Eigen::Index peak = 0;
  phi.cwiseAbs().maxCoeff(&peak);
  // DOFs of the nodes that move (1e-3 of the peak): the support of the motion.
  std::set<long> nodes;
  for (Eigen::Index j = 0; j < phi.size(); ++j)
    if (std::abs(phi[j]) >= 1e-3 * largest) nodes.insert(info[static_cast<std::size_t>(j)].node_id);
  std::vector<Eigen::Index> support;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  int n_centre = 0;
  for (Eigen::Index j = 0; j < phi.size(); ++j) {
    const auto& d = info[static_cast<std::size_t>(j)];
    if (!nodes.count(d.node_id) || d.component < 0 || d.component > 5) continue;
    support.push_back(j);
    centre += d.x;
    ++n_centre;
  }
  std::string rigid_text = "a mechanism";
  if (!support.empty()) {
    centre /= n_centre;
    // Rigid-body basis on the support: translations e_k, rotations e_k x (x - c) on
    // translational DOFs and e_k on rotational DOFs.
    const auto ns = static_cast<Eigen::Index>(support.size());
    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(ns, 6);
    Eigen::VectorXd y(ns);
    for (Eigen::Index r = 0; r < ns; ++r) {
      const auto& d = info[static_cast<std::size_t>(support[static_cast<std::size_t>(r)])];
      y[r] = phi[support[static_cast<std::size_t>(r)]];
      const Eigen::Vector3d arm = d.x - centre;
      if (d.component < 3) {
        R(r, d.component) = 1.0;
        for (int k = 0; k < 3; ++k) R(r, 3 + k) = Eigen::Vector3d::Unit(k).cross(arm)[d.component];
      } else {
        R(r, d.component) = 1.0;
      }
    }
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(R);
    const Eigen::VectorXd a = cod.solve(y);
    const double fit = (R * a).norm(), total = y.norm();
    const double rigid_share = total > 0.0 ? fit / total : 0.0;
    static constexpr const char* kRigid[] = {"translation along x", "translation along y",
                                             "translation along z", "rotation about x",
                                             "rotation about y",    "rotation about z"};
    Eigen::VectorXd part(6);
    for (int k = 0; k < 6; ++k) part[k] = (R.col(k) * a[k]).norm();
    const double part_max = part.maxCoeff();
    std::vector<std::string> dominant;
    for (int k = 0; k < 6; ++k)
      if (part_max > 0.0 && part[k] >= 0.1 * part_max) dominant.push_back(kRigid[k]);
    std::string names;
    for (std::size_t k = 0; k < dominant.size(); ++k)
      names += (k == 0 ? "" : (k + 1 == dominant.size() ? " and " : ", ")) + dominant[k];
    if (rigid_share >= 0.9)
      rigid_text = fmt::format("rigid-body {} ({:.1f} % rigid)", names, 100.0 * rigid_share);
    else
      rigid_text =
          fmt::format("a mechanism that is not a rigid-body motion ({:.1f} % rigid, nearest {})",
                      100.0 * rigid_share, names.empty() ? "none" : names);
  }
  std::string ids;
  int listed = 0;
  for (long id : nodes) {
    if (listed == 8) {
      ids += ", ...";
      break;
    }
    ids += fmt::format("{}{}", listed == 0 ? "" : ", ", id);
    ++listed;
  }
  return fmt::format("{} of {} node(s) (ids {}), largest at {}", rigid_text, nodes.size(), ids,
                     describe_dof(info[static_cast<std::size_t>(peak)]));
}

// The fixed-interface eigen-solve: eig::solve_symmetric on (K_ii, M_ii), or solve_constrained
// with the interface constraints.
using EigenSolve = std::function<eig::SymmetricEigenResult(const eig::SymmetricEigenOptions&)>;

// Builds the error for a singular (or indefinite) K_ii from the lowest fixed-interface modes.
[[noreturn]] void throw_free_motion(const EigenSolve& solve,
                                    const std::vector<solid::DofInfo>& info, double threshold,
                                    const CraigBamptonOptions& options) {
  eig::SymmetricEigenOptions eo;
  eo.n_modes = static_cast<int>(std::min<std::size_t>(12, info.size()));
  eo.dense_limit = options.dense_limit;
  eo.krylov = options.krylov;
  const auto r = solve(eo);
  const std::string hint =
      "make DOFs of the free part masters (or constrain them), or connect the part to the rest "
      "of the model";
  const std::string expected =
      "masters that hold every motion of the interior (K_ii positive definite)";
  if (r.eigenvalues.size() == 0 || (r.status != Status::Ok && r.status != Status::NotConverged))
    throw InputError({}, std::string(kKey) + ".master_dofs", expected,
                     fmt::format("K_ii (stiffness with the masters held) is singular, and its free "
                                 "motions could not be computed: {}",
                                 r.brief_report()),
                     hint);
  std::string found;
  int count = 0;
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
    const double lambda = r.eigenvalues[k];
    if (lambda > threshold) break;
    ++count;
    if (count > 6) continue;
    found += fmt::format("; free motion {} (lambda = {:.3e} rad^2/s^2{}): {}", count, lambda,
                         lambda < -threshold ? ", negative: the stiffness is indefinite" : "",
                         describe_motion(r.eigenvectors.col(k), info));
  }
  if (count == 0)
    throw NumericalError(
        "craig_bampton",
        fmt::format("the Cholesky factorisation of K_ii failed, yet its lowest fixed-interface "
                    "eigenvalue {:.6e} rad^2/s^2 is above the mechanism threshold {:.3e}; the "
                    "stiffness matrix is probably indefinite or badly scaled",
                    r.eigenvalues[0], threshold));
  throw InputError({}, std::string(kKey) + ".master_dofs", expected,
                   fmt::format("K_ii (the stiffness with the masters held) is singular: {} free "
                               "motion(s) with lambda <= {:.3e} rad^2/s^2{}",
                               count, threshold, found),
                   hint);
}

}  // namespace

namespace {

// The checks of the options and of the matrices.
void check_input(const SparseMatrix& K, const SparseMatrix& M,
                 const std::vector<solid::DofInfo>& dofs, const CraigBamptonOptions& options) {
  if (auto problems = options.validate(); !problems.empty()) {
    std::string found;
    for (const auto& p : problems) found += (found.empty() ? "" : "; ") + p;
    throw InputError({}, std::string(kKey) + ".options", "valid Craig-Bampton options", found);
  }
  const Eigen::Index n = K.rows();
  if (K.cols() != n || M.rows() != n || M.cols() != n ||
      static_cast<Eigen::Index>(dofs.size()) != n)
    throw InputError({}, kKey, "square K and M and one DofInfo per DOF, all of the same size",
                     fmt::format("K {}x{}, M {}x{}, {} DofInfo", K.rows(), K.cols(), M.rows(),
                                 M.cols(), dofs.size()));
  for (const auto& [A, name] : {std::pair{&K, "K"}, std::pair{&M, "M"}}) {
    const double asym = linalg::relative_asymmetry(*A);
    if (asym > 1e-10)
      throw InputError({}, fmt::format("{}.{}", kKey, name), "a symmetric matrix",
                       fmt::format("||A - A^T||_F / ||A||_F = {:.3e}", asym),
                       "Craig-Bampton needs symmetric K and M (no gyroscopic or circulatory "
                       "terms); reduce those separately with the same transformation");
  }
}

// Masters and interior DOFs, and the index of each DOF in its group.
struct DofPartition {
  std::vector<bool> is_master;
  std::vector<int> local;
  std::vector<int> interior;
};

DofPartition partition_dofs(Eigen::Index n, const std::vector<solid::DofInfo>& dofs,
                            const std::vector<int>& master_dofs) {
  std::vector<bool> is_master(static_cast<std::size_t>(n), false);
  std::vector<int> local(static_cast<std::size_t>(n), -1);
  std::vector<int> interior;
  for (std::size_t k = 0; k < master_dofs.size(); ++k) {
    const int g = master_dofs[k];
    if (g < 0 || g >= n)
      throw InputError({}, fmt::format("{}.master_dofs[{}]", kKey, k),
                       fmt::format("a DOF index in 0 .. {}", n - 1), std::to_string(g));
    if (is_master[static_cast<std::size_t>(g)])
      throw InputError(
          {}, fmt::format("{}.master_dofs[{}]", kKey, k), "each master once",
          fmt::format("DOF {} ({}) repeated", g, describe_dof(dofs[static_cast<std::size_t>(g)])));
    is_master[static_cast<std::size_t>(g)] = true;
    local[static_cast<std::size_t>(g)] = static_cast<int>(k);
  }
  for (Eigen::Index g = 0; g < n; ++g)
    if (!is_master[static_cast<std::size_t>(g)]) {
      local[static_cast<std::size_t>(g)] = static_cast<int>(interior.size());
      interior.push_back(static_cast<int>(g));
    }
  return DofPartition{std::move(is_master), std::move(local), std::move(interior)};
}

// Fixed-interface modes (into lambda and Phi); with none wanted, the lowest one alone, to test
// for free motions. Returns the free-motion threshold on the eigenvalues.
double fixed_interface_modes(const Blocks& Kp, const Blocks& Mp, const EigenSolve& solve,
                             const std::vector<solid::DofInfo>& interior_info,
                             const CraigBamptonOptions& options, ReducedComponent& rc,
                             Eigen::VectorXd& lambda, Eigen::MatrixXd& Phi) {
  const auto ni = static_cast<Eigen::Index>(interior_info.size());
  const bool band = !std::isnan(options.frequency_max_hz);
  eig::SymmetricEigenOptions eo;
  eo.dense_limit = options.dense_limit;
  eo.krylov = options.krylov;
  if (band) {
    const double omega = units::kTwoPi * options.frequency_max_hz;
    eo.band_max = omega * omega;
    // Below zero as well, so that a free motion computed at -1e-12 is caught, not skipped.
    eo.band_min = -eo.band_max;
    eo.n_modes = static_cast<int>(std::min<Eigen::Index>(20, ni));
  } else {
    eo.n_modes = std::max(options.n_modes, 1);
  }
  const double threshold = options.mechanism_tolerance * spectrum_scale(Kp.ii, Mp.ii);
  const auto er = solve(eo);
  // A free motion first: it also spoils convergence and residuals, and is the real cause.
  if (er.status == Status::Singular ||
      (er.eigenvalues.size() > 0 && er.eigenvalues[0] <= threshold))
    throw_free_motion(solve, interior_info, threshold, options);
  if (er.status != Status::Ok)
    throw NumericalError(
        "craig_bampton",
        fmt::format("fixed-interface modes of the {} interior DOFs: {}", ni, er.brief_report()));
  if (band && er.eigenvalues.size() == 0) {
    // No mode below the cut-off: the band result says nothing about free motions.
    eig::SymmetricEigenOptions check = eo;
    check.band_min = check.band_max = eig::kNaN;
    check.n_modes = 1;
    const auto lowest = solve(check);
    if (lowest.status == Status::Singular ||
        (lowest.eigenvalues.size() > 0 && lowest.eigenvalues[0] <= threshold))
      throw_free_motion(solve, interior_info, threshold, options);
    if (lowest.status != Status::Ok)
      throw NumericalError("craig_bampton", "lowest fixed-interface mode (mechanism check): " +
                                                lowest.brief_report());
  }
  rc.provenance.solver_report = er.brief_report();
  if (band || options.n_modes > 0) {
    lambda = er.eigenvalues;
    Phi = er.eigenvectors;
  } else {
    rc.provenance.solver_report = "mechanism check only: " + rc.provenance.solver_report;
  }
  return threshold;
}

// Constraint modes (into Psi): one Cholesky factorisation of K_ii, block solves.
void constraint_modes(const Blocks& Kp, const EigenSolve& solve,
                      const std::vector<solid::DofInfo>& interior_info, double threshold,
                      const CraigBamptonOptions& options, Progress& progress,
                      Eigen::MatrixXd& Psi) {
  const Eigen::Index nb = Psi.cols();
  linalg::SymmetricFactorization factorization;
  const Status fs = factorization.compute(Kp.ii);
  if (fs != Status::Ok || factorization.kind() != linalg::FactorizationKind::Cholesky)
    throw_free_motion(solve, interior_info, threshold, options);
  const Eigen::Index bs = options.block_size;
  const auto n_blocks = static_cast<std::size_t>((nb + bs - 1) / bs);
  progress.start("craig_bampton: constraint modes", n_blocks);
  for (Eigen::Index c0 = 0, block = 0; c0 < nb; c0 += bs, ++block) {
    const Eigen::Index w = std::min(bs, nb - c0);
    const Eigen::MatrixXd rhs = Eigen::MatrixXd(Kp.ib.middleCols(c0, w));
    Psi.middleCols(c0, w) = -factorization.solve(rhs);
    progress.update(static_cast<std::size_t>(block + 1));
  }
  progress.finish();
}

// T^T A T by blocks, T = [I 0; Psi Phi] (see craig_bampton).
Eigen::MatrixXd project(const Blocks& A, const Eigen::MatrixXd& Psi, const Eigen::MatrixXd& Phi,
                        const CraigBamptonOptions& options) {
  const Eigen::Index nb = Psi.cols(), ni = Psi.rows(), nm = Phi.cols();
  const Eigen::Index m = nb + nm;
  const SparseMatrix bi = A.ib.transpose();
  Eigen::MatrixXd R(m, m);
  const Eigen::Index bs = options.block_size;
  for (Eigen::Index c0 = 0; c0 < nb; c0 += bs) {
    const Eigen::Index w = std::min(bs, nb - c0);
    Eigen::MatrixXd top = Eigen::MatrixXd(A.bb.middleCols(c0, w));
    Eigen::MatrixXd low = Eigen::MatrixXd(A.ib.middleCols(c0, w));
    if (ni > 0) {
      top += bi * Psi.middleCols(c0, w);
      low += A.ii * Psi.middleCols(c0, w);
    }
    R.block(0, c0, nb, w) = top + Psi.transpose() * low;
    if (nm > 0) R.block(nb, c0, nm, w) = Phi.transpose() * low;
  }
  if (nm > 0) {
    const Eigen::MatrixXd low = A.ii * Phi;
    R.block(0, nb, nb, nm) = bi * Phi + Psi.transpose() * low;
    R.block(nb, nb, nm, nm) = Phi.transpose() * low;
  }
  const Eigen::MatrixXd Rt = R.transpose();
  return Eigen::MatrixXd(0.5 * (R + Rt));
}

}  // namespace

namespace {

// The fields every reduction sets before the solves: recovery indices and provenance.
ReducedComponent start_component(const std::vector<solid::DofInfo>& dofs,
                                 const std::vector<int>& master_dofs, const DofPartition& dp,
                                 const CraigBamptonOptions& options,
                                 const std::string& source_sha256,
                                 const std::string& geardyn_version) {
  const bool band = !std::isnan(options.frequency_max_hz);
  ReducedComponent rc;
  rc.full_dofs = dofs;
  rc.master_index = master_dofs;
  rc.interior_index = dp.interior;
  for (int g : master_dofs) rc.masters.push_back(dofs[static_cast<std::size_t>(g)]);
  rc.provenance.method = (band || options.n_modes > 0) ? "craig_bampton" : "guyan";
  rc.provenance.options_json = options.to_json();
  rc.provenance.source_sha256 = source_sha256;
  rc.provenance.geardyn_version = geardyn_version;
  rc.provenance.created_utc = utc_now();
  return rc;
}

void check_mode_count(const CraigBamptonOptions& options, Eigen::Index available,
                      const char* what) {
  if (std::isnan(options.frequency_max_hz) && options.n_modes > available)
    throw InputError({}, std::string(kKey) + ".n_modes",
                     fmt::format("at most {} ({})", available, what),
                     std::to_string(options.n_modes));
}

// A DOF without any stiffness cannot be held by any master: name it directly (the eigen-solve
// could not even run when it has no mass either).
void check_interior_stiffness(const Blocks& Kp, const std::vector<solid::DofInfo>& interior_info) {
  const Eigen::VectorXd kd = Kp.ii.diagonal();
  for (Eigen::Index j = 0; j < kd.size(); ++j)
    if (!(kd[j] > 0.0))
      throw InputError({}, std::string(kKey) + ".master_dofs",
                       "interior DOFs with positive diagonal stiffness",
                       fmt::format("interior DOF {} has K_jj = {:.6g}: it is connected to "
                                   "nothing (or has negative stiffness)",
                                   describe_dof(interior_info[static_cast<std::size_t>(j)]), kd[j]),
                       "make it a master, constrain it or remove it from the model");
}

// K_r = T^T K T and M_r = T^T M T by blocks, T = [I 0; Psi Phi]:
//   K T = [K_bb + K_bi Psi,  K_bi Phi;  K_ib + K_ii Psi,  K_ii Phi]
//   T^T (K T) = [I Psi^T; 0 Phi^T] (K T)
// The interior row block of K T is formed a column block at a time, so no n_interior x m
// temporary beyond Psi itself is needed.
void finish(ReducedComponent& rc, const Blocks& Kp, const Blocks& Mp, Eigen::MatrixXd Psi,
            Eigen::MatrixXd Phi, const Eigen::VectorXd& lambda,
            const CraigBamptonOptions& options) {
  const Eigen::Index nm = Phi.cols();
  rc.K = project(Kp, Psi, Phi, options);
  rc.M = project(Mp, Psi, Phi, options);
  rc.n_modal = static_cast<int>(nm);
  rc.fixed_interface_hz.resize(nm);
  for (Eigen::Index k = 0; k < nm; ++k)
    rc.fixed_interface_hz[k] = std::sqrt(std::max(lambda[k], 0.0)) / units::kTwoPi;
  rc.Psi = std::move(Psi);
  rc.Phi = std::move(Phi);
}

// Constraint modes under interface constraints (into Psi): one factorisation of the saddle-point
// matrix [K_ii A_i^T; A_i 0], block solves with right-hand sides [-K_ib; -A_b].
void constrained_constraint_modes(const Blocks& Kp, const SparseMatrix& Ab, const SparseMatrix& Ai,
                                  const EigenSolve& solve,
                                  const std::vector<solid::DofInfo>& interior_info,
                                  double threshold, const CraigBamptonOptions& options,
                                  Progress& progress, Eigen::MatrixXd& Psi) {
  const Eigen::Index nb = Psi.cols();
  SaddlePointSolver saddle;
  if (saddle.compute(Kp.ii, Ai) != Status::Ok)
    throw_free_motion(solve, interior_info, threshold, options);
  const Eigen::Index bs = options.block_size;
  const auto n_blocks = static_cast<std::size_t>((nb + bs - 1) / bs);
  progress.start("craig_bampton: constraint modes", n_blocks);
  for (Eigen::Index c0 = 0, block = 0; c0 < nb; c0 += bs, ++block) {
    const Eigen::Index w = std::min(bs, nb - c0);
    const Eigen::MatrixXd B = -Eigen::MatrixXd(Kp.ib.middleCols(c0, w));
    const Eigen::MatrixXd C = -Eigen::MatrixXd(Ab.middleCols(c0, w));
    Psi.middleCols(c0, w) = saddle.solve(B, C);
    progress.update(static_cast<std::size_t>(block + 1));
  }
  progress.finish();
}

// The constraint rows A x - u = 0 split into master columns A_b and interior columns A_i.
std::pair<SparseMatrix, SparseMatrix> split_constraints(const SparseMatrix& A,
                                                        const DofPartition& dp, Eigen::Index nb) {
  const Eigen::Index n = A.cols(), r = A.rows();
  const auto ni = static_cast<Eigen::Index>(dp.interior.size());
  std::vector<Eigen::Triplet<double>> tb, ti;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
    const auto cu = static_cast<std::size_t>(c);
    for (SparseMatrix::InnerIterator it(A, c); it; ++it)
      (dp.is_master[cu] ? tb : ti)
          .emplace_back(static_cast<int>(it.row()), dp.local[cu], it.value());
  }
  for (Eigen::Index k = 0; k < r; ++k)
    tb.emplace_back(static_cast<int>(k), dp.local[static_cast<std::size_t>(n + k)], -1.0);
  SparseMatrix Ab(r, nb), Ai(r, ni);
  Ab.setFromTriplets(tb.begin(), tb.end());
  Ai.setFromTriplets(ti.begin(), ti.end());
  return {std::move(Ab), std::move(Ai)};
}

}  // namespace

ReducedComponent craig_bampton(const SparseMatrix& K, const SparseMatrix& M,
                               const std::vector<solid::DofInfo>& dofs,
                               const std::vector<int>& master_dofs,
                               const CraigBamptonOptions& options, const std::string& source_sha256,
                               const std::string& geardyn_version, Progress& progress) {
  check_input(K, M, dofs, options);
  const Eigen::Index n = K.rows();

  const DofPartition dp = partition_dofs(n, dofs, master_dofs);
  const auto nb = static_cast<Eigen::Index>(master_dofs.size());
  const auto ni = static_cast<Eigen::Index>(dp.interior.size());
  check_mode_count(options, ni, "the number of interior DOFs");

  const Blocks Kp = partition(K, dp.local, dp.is_master, nb, ni);
  const Blocks Mp = partition(M, dp.local, dp.is_master, nb, ni);
  std::vector<solid::DofInfo> interior_info;
  interior_info.reserve(static_cast<std::size_t>(ni));
  for (int g : dp.interior) interior_info.push_back(dofs[static_cast<std::size_t>(g)]);

  ReducedComponent rc =
      start_component(dofs, master_dofs, dp, options, source_sha256, geardyn_version);
  Eigen::MatrixXd Psi = Eigen::MatrixXd::Zero(ni, nb);
  Eigen::MatrixXd Phi(ni, 0);
  Eigen::VectorXd lambda(0);
  if (ni > 0) {
    check_interior_stiffness(Kp, interior_info);
    const EigenSolve solve = [&](const eig::SymmetricEigenOptions& eo) {
      return eig::solve_symmetric(Kp.ii, Mp.ii, eo);
    };
    const double threshold =
        fixed_interface_modes(Kp, Mp, solve, interior_info, options, rc, lambda, Phi);
    constraint_modes(Kp, solve, interior_info, threshold, options, progress, Psi);
  } else {
    rc.provenance.solver_report = "no interior DOFs";
  }
  finish(rc, Kp, Mp, std::move(Psi), std::move(Phi), lambda, options);
  return rc;
}

ReducedComponent craig_bampton(const SparseMatrix& K, const SparseMatrix& M,
                               const std::vector<solid::DofInfo>& dofs,
                               const InterfaceConstraints& constraints,
                               const std::vector<int>& master_dofs,
                               const CraigBamptonOptions& options, const std::string& source_sha256,
                               const std::string& geardyn_version, Progress& progress) {
  const Eigen::Index r = constraints.A.rows();
  if (r == 0)
    return craig_bampton(K, M, dofs, master_dofs, options, source_sha256, geardyn_version,
                         progress);
  check_input(K, M, dofs, options);
  const Eigen::Index n = K.rows();
  if (constraints.A.cols() != n || static_cast<Eigen::Index>(constraints.dofs.size()) != r)
    throw InputError({}, std::string(kKey) + ".constraints",
                     "constraint rows A with one column per DOF and one DofInfo per row",
                     fmt::format("A {}x{} for {} DOFs, {} DofInfo", r, constraints.A.cols(), n,
                                 constraints.dofs.size()));
  std::vector<solid::DofInfo> all = dofs;
  all.insert(all.end(), constraints.dofs.begin(), constraints.dofs.end());
  const DofPartition dp = partition_dofs(n + r, all, master_dofs);
  for (Eigen::Index k = 0; k < r; ++k)
    if (!dp.is_master[static_cast<std::size_t>(n + k)])
      throw InputError({}, std::string(kKey) + ".master_dofs",
                       "every constrained coordinate u among the masters",
                       fmt::format("u {} ({}) missing", k,
                                   describe_dof(constraints.dofs[static_cast<std::size_t>(k)])));
  const auto nb = static_cast<Eigen::Index>(master_dofs.size());
  const auto ni = static_cast<Eigen::Index>(dp.interior.size());
  if (ni < r)
    throw InputError({}, std::string(kKey) + ".constraints",
                     fmt::format("at most {} constraint rows (the interior DOFs)", ni),
                     std::to_string(r));
  check_mode_count(options, ni - r, "the interior DOFs less the constraint rows");

  // The coordinates u have no stiffness or mass of their own: K and M padded with zeros.
  SparseMatrix Kx = K, Mx = M;
  Kx.conservativeResize(n + r, n + r);
  Mx.conservativeResize(n + r, n + r);
  const Blocks Kp = partition(Kx, dp.local, dp.is_master, nb, ni);
  const Blocks Mp = partition(Mx, dp.local, dp.is_master, nb, ni);
  const auto [Ab, Ai] = split_constraints(constraints.A, dp, nb);
  std::vector<solid::DofInfo> interior_info;
  interior_info.reserve(static_cast<std::size_t>(ni));
  for (int g : dp.interior) interior_info.push_back(all[static_cast<std::size_t>(g)]);

  ReducedComponent rc =
      start_component(all, master_dofs, dp, options, source_sha256, geardyn_version);
  Eigen::MatrixXd Psi = Eigen::MatrixXd::Zero(ni, nb);
  Eigen::MatrixXd Phi(ni, 0);
  Eigen::VectorXd lambda(0);
  check_interior_stiffness(Kp, interior_info);
  const EigenSolve solve = [&](const eig::SymmetricEigenOptions& eo) {
    return solve_constrained(Kp.ii, Mp.ii, Ai, eo);
  };
  const double threshold =
      fixed_interface_modes(Kp, Mp, solve, interior_info, options, rc, lambda, Phi);
  constrained_constraint_modes(Kp, Ab, Ai, solve, interior_info, threshold, options, progress, Psi);
  finish(rc, Kp, Mp, std::move(Psi), std::move(Phi), lambda, options);
  return rc;
}

std::vector<int> select_dofs(const std::vector<solid::DofInfo>& dofs,
                             const std::vector<long>& node_ids, const ComponentMask& components) {
  const std::set<long> wanted(node_ids.begin(), node_ids.end());
  std::set<long> seen;
  std::vector<int> out;
  for (std::size_t j = 0; j < dofs.size(); ++j) {
    const auto& d = dofs[j];
    if (!wanted.count(d.node_id) || d.component < 0 || d.component > 5 ||
        !components[static_cast<std::size_t>(d.component)])
      continue;
    out.push_back(static_cast<int>(j));
    seen.insert(d.node_id);
  }
  for (long id : node_ids)
    if (!seen.count(id))
      throw InputError({}, "reduce.select_dofs.node_ids",
                       "node ids that have DOFs of the selected components",
                       fmt::format("node {} has none", id));
  return out;
}

std::vector<int> select_dofs(const solid::Mesh& mesh, const std::vector<solid::DofInfo>& dofs,
                             const std::vector<int>& node_indices,
                             const ComponentMask& components) {
  std::vector<long> ids;
  ids.reserve(node_indices.size());
  for (int i : node_indices) {
    if (i < 0 || i >= mesh.num_nodes() || static_cast<std::size_t>(i) >= mesh.node_ids.size())
      throw InputError({mesh.source}, "reduce.select_dofs.node_indices",
                       fmt::format("node indices 0 .. {}", mesh.num_nodes() - 1),
                       std::to_string(i));
    ids.push_back(mesh.node_ids[static_cast<std::size_t>(i)]);
  }
  return select_dofs(dofs, ids, components);
}

std::vector<int> select_dofs(const solid::Mesh& mesh, const std::vector<solid::DofInfo>& dofs,
                             const std::string& node_set, const ComponentMask& components) {
  const auto it = mesh.node_sets.find(node_set);
  if (it == mesh.node_sets.end()) {
    std::string names;
    for (const auto& [name, nodes] : mesh.node_sets) names += (names.empty() ? "" : ", ") + name;
    throw InputError({mesh.source}, "reduce.select_dofs.node_set", "the name of a node set",
                     "'" + node_set + "'",
                     names.empty() ? "the mesh has no node sets" : "the mesh has: " + names);
  }
  return select_dofs(mesh, dofs, it->second, components);
}

std::vector<int> merge_dofs(const std::vector<std::vector<int>>& lists) {
  std::set<int> all;
  for (const auto& l : lists) all.insert(l.begin(), l.end());
  return {all.begin(), all.end()};
}

}  // namespace geardyn::reduce
