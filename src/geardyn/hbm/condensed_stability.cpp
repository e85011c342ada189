// GCC's -Wnull-dereference reports false positives inside Eigen's dense complex kernels once
// inlined here; the pragma must precede the first Eigen include.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/hbm/condensed_stability.hpp"

namespace geardyn::hbm {

namespace {

using cd = std::complex<double>;

/// One balanced harmonic component k of the perturbation and its modal receptance.
struct Block {
  int k = 0;
  Eigen::MatrixXcd U, V, R;  // coordinates x modes, coordinates x coordinates (empty: none)
  Eigen::VectorXd w, zeta;   // per modal column
};

bool balanced(const ModalReceptance& r) { return r.modes() > 0 || r.residual.size() > 0; }

std::vector<Block> blocks_of(const CondensedHarmonicBalance& hb) {
  std::vector<Block> out;
  const int H = hb.basis().harmonics();
  for (int k = -H; k <= H; ++k) {
    const ModalReceptance& r = hb.harmonics()[static_cast<std::size_t>(std::abs(k))];
    if (!balanced(r)) continue;
    Block b;
    b.k = k;
    if (k == 0) {
      // The mean is real: G_0 = Re(U D V^H) + Re(R) = U_r D V_r^T + U_i D V_i^T + R_r.
      const bool complex_shapes = r.left.imag().norm() > 0.0 || r.right.imag().norm() > 0.0;
      const Eigen::Index m = r.modes();
      const Eigen::Index cols = complex_shapes ? 2 * m : m;
      b.U.resize(r.coordinates(), cols);
      b.V.resize(r.coordinates(), cols);
      b.w.resize(cols);
      b.zeta.resize(cols);
      b.U.leftCols(m) = r.left.real().cast<cd>();
      b.V.leftCols(m) = r.right.real().cast<cd>();
      b.w.head(m) = r.natural_frequency;
      b.zeta.head(m) = r.damping_ratio;
      if (complex_shapes) {
        b.U.rightCols(m) = r.left.imag().cast<cd>();
        b.V.rightCols(m) = r.right.imag().cast<cd>();
        b.w.tail(m) = r.natural_frequency;
        b.zeta.tail(m) = r.damping_ratio;
      }
      if (r.residual.size()) b.R = r.residual.real().cast<cd>();
    } else {
      b.U = k > 0 ? Eigen::MatrixXcd(r.left) : Eigen::MatrixXcd(r.left.conjugate());
      b.V = k > 0 ? Eigen::MatrixXcd(r.right) : Eigen::MatrixXcd(r.right.conjugate());
      if (r.residual.size())
        b.R = k > 0 ? Eigen::MatrixXcd(r.residual) : Eigen::MatrixXcd(r.residual.conjugate());
      b.w = r.natural_frequency;
      b.zeta = r.damping_ratio;
    }
    out.push_back(std::move(b));
  }
  return out;
}

/// True when the perturbation's components are shifts of one another (Hill's families): every
/// balanced harmonic has the same real modes (an ordinary structure, or a cyclic one at a
/// standing nodal diameter). Complex (travelling-wave) shapes or a different pattern per harmonic
/// make every exponent a distinct one.
bool shift_families(const CondensedHarmonicBalance& hb) {
  const ModalReceptance* first = nullptr;
  for (const ModalReceptance& r : hb.harmonics()) {
    if (!balanced(r)) continue;
    if (r.left.imag().norm() > 0.0 || r.right.imag().norm() > 0.0) return false;
    if (!first) {
      first = &r;
      continue;
    }
    if (r.natural_frequency != first->natural_frequency ||
        r.damping_ratio != first->damping_ratio || r.left != first->left || r.right != first->right)
      return false;
  }
  return first != nullptr;
}

}  // namespace

int condensed_hill_size(const CondensedHarmonicBalance& hb) {
  return hb.coordinates() * static_cast<int>(blocks_of(hb).size());
}

FloquetResult condensed_hill_stability(const CondensedHarmonicBalance& hb, const Eigen::VectorXd& X,
                                       double omega, const HillOptions& options) {
  options.validate();
  if (!(std::isfinite(omega) && omega > 0.0))
    throw InputError({}, "hbm.condensed_hill_stability.omega", "a finite frequency > 0",
                     fmt::format("{}", omega));
  FloquetResult out;
  const Eigen::MatrixXd Jn = hb.nonlinear_jacobian(X, omega);  // checks the size of X
  const std::vector<Block> blocks = blocks_of(hb);
  const int n_c = hb.coordinates(), s = hb.basis().size();
  const auto nb = static_cast<Eigen::Index>(blocks.size());
  const Eigen::Index n_k = nb * n_c;  // complex coefficients of the perturbation
  Eigen::Index n_m = 0;               // modal coordinates
  for (const Block& b : blocks) n_m += b.w.size();
  if (n_m == 0) {
    out.status = Status::Failed;
    out.message = "no modes in the receptance: the perturbation has no dynamics to assess";
    return out;
  }

  // T (complex coefficients from real ones) and S = T^-1 on the balanced components.
  Eigen::MatrixXcd T = Eigen::MatrixXcd::Zero(n_k, hb.size());
  Eigen::MatrixXcd S = Eigen::MatrixXcd::Zero(hb.size(), n_k);
  const cd i(0.0, 1.0);
  for (Eigen::Index bi = 0; bi < nb; ++bi) {
    const int k = blocks[static_cast<std::size_t>(bi)].k, n = std::abs(k);
    for (int d = 0; d < n_c; ++d) {
      const Eigen::Index row = bi * n_c + d;
      if (k == 0) {
        T(row, d * s) = 1.0;
        S(d * s, row) = 1.0;
        continue;
      }
      const Eigen::Index a = d * s + HarmonicBasis::cos_index(n),
                         b = d * s + HarmonicBasis::sin_index(n);
      const double sign = k > 0 ? 1.0 : -1.0;  // c_k = (a - i b) / 2, c_-k = (a + i b) / 2
      T(row, a) = 0.5;
      T(row, b) = -0.5 * sign * i;
      S(a, row) = 1.0;
      S(b, row) = sign * i;  // b = i (c_k - c_-k)
    }
  }
  const Eigen::MatrixXcd Jc = T * Jn.cast<cd>() * S;

  // P = (I + R J_c)^-1 U and the modal coupling V^H J_c P.
  Eigen::MatrixXcd U = Eigen::MatrixXcd::Zero(n_k, n_m), V = Eigen::MatrixXcd::Zero(n_k, n_m);
  Eigen::MatrixXcd A = Eigen::MatrixXcd::Identity(n_k, n_k);
  Eigen::VectorXcd damping(n_m), stiffness(n_m);
  Eigen::Index col = 0;
  for (Eigen::Index bi = 0; bi < nb; ++bi) {
    const Block& b = blocks[static_cast<std::size_t>(bi)];
    const Eigen::Index m = b.w.size(), row = bi * n_c;
    U.block(row, col, n_c, m) = b.U;
    V.block(row, col, n_c, m) = b.V;
    if (b.R.size()) A.middleRows(row, n_c) += b.R * Jc.middleRows(row, n_c);
    const double kw = b.k * omega;
    for (Eigen::Index r = 0; r < m; ++r) {
      const double wr = b.w[r], z = b.zeta[r];
      damping[col + r] = cd(2.0 * z * wr, 2.0 * kw);
      stiffness[col + r] = cd(wr * wr - kw * kw, 2.0 * z * wr * kw);
    }
    col += m;
  }
  const Eigen::MatrixXcd P = A.partialPivLu().solve(U);
  Eigen::MatrixXcd K = V.adjoint() * Jc * P;
  K.diagonal() += stiffness;

  // First-order form [0 I; -K -C] z = lambda z.
  Eigen::MatrixXcd L = Eigen::MatrixXcd::Zero(2 * n_m, 2 * n_m);
  L.topRightCorner(n_m, n_m).setIdentity();
  L.bottomLeftCorner(n_m, n_m) = -K;
  L.bottomRightCorner(n_m, n_m).diagonal() = -damping;
  if (!L.allFinite()) {
    out.message = "the linearised system is not finite (a non-finite Jacobian of the forces)";
    return out;
  }
  const bool select = shift_families(hb);
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> eig(L, select);
  if (eig.info() != Eigen::Success) {
    out.message = "the eigenvalue solve of the Hill matrix did not converge";
    return out;
  }
  std::vector<Eigen::Index> kept(static_cast<std::size_t>(2 * n_m));
  for (Eigen::Index j = 0; j < 2 * n_m; ++j) kept[static_cast<std::size_t>(j)] = j;
  const Eigen::VectorXcd& all = eig.eigenvalues();
  if (select) {
    // One representative per family: the eigenvector most concentrated on the central
    // components (harmonic centroid kappa of its modal part), ties by the smallest |Im|.
    std::vector<double> kappa(kept.size());
    for (Eigen::Index j = 0; j < 2 * n_m; ++j) {
      double weight = 0.0, moment = 0.0;
      Eigen::Index c0 = 0;
      for (const Block& b : blocks) {
        const double w = eig.eigenvectors().col(j).segment(c0, b.w.size()).squaredNorm();
        weight += w;
        moment += b.k * w;
        c0 += b.w.size();
      }
      kappa[static_cast<std::size_t>(j)] = weight > 0.0 ? std::abs(moment / weight) : 0.0;
    }
    std::vector<Eigen::Index> order = kept;
    std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
      const double ka = kappa[static_cast<std::size_t>(a)], kb = kappa[static_cast<std::size_t>(b)];
      if (std::abs(ka - kb) > 1e-6) return ka < kb;
      return std::abs(all[a].imag()) < std::abs(all[b].imag());
    });
    // Accept in that order, skipping members of an accepted family (lambda + i j omega): with
    // the mean held, both members of components +-1 are equally central.
    const double band = options.kind_tolerance * omega;
    auto same_family = [&](cd a, cd b) {
      const cd d = a - b;
      return std::abs(d.real()) <= band &&
             std::abs(d.imag() - omega * std::round(d.imag() / omega)) <= band;
    };
    const auto n_keep = static_cast<std::size_t>(2 * blocks.front().w.size());
    kept.clear();
    for (const Eigen::Index j : order) {
      if (kept.size() == n_keep) break;
      bool duplicate = false;
      for (const Eigen::Index a : kept) duplicate = duplicate || same_family(all[a], all[j]);
      if (!duplicate) kept.push_back(j);
    }
  }
  Eigen::VectorXcd lambda(static_cast<Eigen::Index>(kept.size()));
  for (std::size_t j = 0; j < kept.size(); ++j) lambda[static_cast<Eigen::Index>(j)] = all[kept[j]];
  std::sort(lambda.data(), lambda.data() + lambda.size(), [](cd a, cd b) {
    if (a.real() != b.real()) return a.real() > b.real();
    return a.imag() > b.imag();
  });
  const double period = units::kTwoPi / omega;
  out.exponents = lambda;
  out.multipliers = (lambda * period).array().exp().matrix();
  out.max_real_part = lambda[0].real();
  out.stable = out.max_real_part <= options.stability_tolerance * omega;
  if (!out.stable) out.kind = instability_kind(lambda[0], omega, options.kind_tolerance);
  out.status = Status::Ok;
  return out;
}

}  // namespace geardyn::hbm
