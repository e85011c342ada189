#include "geardyn/analyses/harmonic.hpp"

#include <fmt/format.h>
#include <umfpack.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <thread>

#include "geardyn/core/error.hpp"
#include "geardyn/core/peak_table.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/linalg/banded_lu.hpp"
#include "geardyn/linalg/blas_library.hpp"
#include "geardyn/signal/half_power.hpp"

namespace geardyn::analyses {
namespace {

using Complex = std::complex<double>;
using units::kPi;
constexpr double kHzPerRadS = 1.0 / units::kTwoPi;
constexpr double kRpmPerRadS = 60.0 / units::kTwoPi;

// UMFPACK scales each row by the sum of its absolute values before factorising, so its pivot
// ratio min|U_ii| / max|U_ii| compares pivots of a matrix with unit-size rows. A matrix that is
// singular in exact arithmetic (a rigid-body mode at w = 0) leaves a pivot made of round-off,
// a few eps (~1e-16 .. 1e-15) relative to the largest; a genuinely ill-conditioned but regular
// rotor model (stiff bearings on soft shafts, 1e-3 .. 1e-10) stays far above. 1e-13 separates
// the two with two decades of margin on either side.
constexpr double kSingularPivotRatio = 1e-13;

// FactorPath::Automatic takes the banded LU when its band storage n (2 kl + ku + 1) is at most
// this multiple of UMFPACK's estimate of nnz(L + U). The banded elimination runs in tight loops
// with no indirection, so per entry it is several times faster than UMFPACK's frontal kernels
// on the small fronts of a shaft line (measured on bench/rotor_bench.cpp's rotor, see
// docs/performance.md, issue #19); a wider band (branched gear trains) goes to UMFPACK.
constexpr double kBandedFillRatio = 4.0;

// Complex LU by UMFPACK (called directly: the symbolic analysis is kept across frequencies and
// the pivot ratio is read from its Info array). Complex values are passed packed (re, im), which
// std::complex<double> arrays are by the standard's layout guarantee.
class UmfpackLu {
 public:
  UmfpackLu() { umfpack_zi_defaults(control_); }
  ~UmfpackLu() { release(); }
  UmfpackLu(const UmfpackLu&) = delete;
  UmfpackLu& operator=(const UmfpackLu&) = delete;

  /// UMFPACK status of the symbolic analysis (UMFPACK_OK on success).
  int analyze(const fe::ComplexSparseMatrix& A) {
    release();
    const int n = static_cast<int>(A.rows());
    return umfpack_zi_symbolic(n, n, A.outerIndexPtr(), A.innerIndexPtr(), values(A), nullptr,
                               &symbolic_, control_, info_);
  }
  /// UMFPACK status of the numeric factorisation (UMFPACK_WARNING_singular_matrix when a pivot
  /// is exactly zero).
  int factorize(const fe::ComplexSparseMatrix& A) {
    if (numeric_ != nullptr) umfpack_zi_free_numeric(&numeric_);
    const int status = umfpack_zi_numeric(A.outerIndexPtr(), A.innerIndexPtr(), values(A), nullptr,
                                          symbolic_, &numeric_, control_, info_);
    pivot_ratio_ = info_[UMFPACK_RCOND];
    return status;
  }
  /// Solves A x = b column by column (with UMFPACK's iterative refinement against A).
  bool solve(const fe::ComplexSparseMatrix& A, const Eigen::MatrixXcd& b,
             Eigen::MatrixXcd& x) const {
    x.resize(b.rows(), b.cols());
    for (Eigen::Index j = 0; j < b.cols(); ++j) {
      const int status = umfpack_zi_solve(
          UMFPACK_A, A.outerIndexPtr(), A.innerIndexPtr(), values(A), nullptr,
          reinterpret_cast<double*>(x.col(j).data()), nullptr,
          reinterpret_cast<const double*>(b.col(j).data()), nullptr, numeric_, control_, info_);
      if (status != UMFPACK_OK) return false;
    }
    return true;
  }
  double pivot_ratio() const { return pivot_ratio_; }
  /// min |u_ii| and max |u_ii| of the last factor (row-scaled matrix).
  double smallest_pivot() const { return info_[UMFPACK_UMIN]; }
  double largest_pivot() const { return info_[UMFPACK_UMAX]; }
  /// UMFPACK's estimate (after analyze) of the entries of L + U.
  double factor_entries_estimate() const {
    return info_[UMFPACK_LNZ_ESTIMATE] + info_[UMFPACK_UNZ_ESTIMATE];
  }

 private:
  static const double* values(const fe::ComplexSparseMatrix& A) {
    return reinterpret_cast<const double*>(A.valuePtr());
  }
  void release() {
    if (numeric_ != nullptr) umfpack_zi_free_numeric(&numeric_);
    if (symbolic_ != nullptr) umfpack_zi_free_symbolic(&symbolic_);
  }
  double control_[UMFPACK_CONTROL];
  mutable double info_[UMFPACK_INFO];
  void* symbolic_ = nullptr;
  void* numeric_ = nullptr;
  double pivot_ratio_ = 0.0;
};

// Per-entry real coefficients of the terms of D on a pattern (0 where a term has no entry):
//   d_k = stiffness_k - w^2 mass_k + i (w s0 mass_k + w damping_k + w W gyroscopic_k + loss_k).
struct Coefficients {
  std::vector<double> mass, stiffness, damping, gyroscopic, loss;
};

bool is_empty(const fe::SparseMatrix& X) { return X.rows() == 0 && X.cols() == 0; }

void check_square(const fe::SparseMatrix& X, int n, const char* name) {
  if (!is_empty(X) && (X.rows() != n || X.cols() != n))
    throw std::logic_error(
        fmt::format("LinearSystem::{} is {}x{}, expected {}x{}", name, X.rows(), X.cols(), n, n));
}

void add_pattern(const fe::SparseMatrix& X, std::vector<Eigen::Triplet<double>>& triplets) {
  if (is_empty(X)) return;
  // Stored zeros (element blocks assembled whole) are left out: they would couple the lateral,
  // axial and torsional DOFs of a shaft line in the pattern, join its blocks and widen its band.
  for (Eigen::Index k = 0; k < X.outerSize(); ++k)
    for (fe::SparseMatrix::InnerIterator it(X, k); it; ++it)
      if (it.value() != 0.0)
        triplets.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), 0.0);
}

// Every entry a speed-dependent bearing can give at any speed: K_b(W), C_b(W) interpolate their
// tables linearly, so an entry is non-zero at some speed only if it is in some table point.
void add_speed_bearing_pattern(const fe::LinearSystem& system,
                               std::vector<Eigen::Triplet<double>>& triplets) {
  for (const fe::SpeedDependentBearing& b : system.speed_bearings)
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) {
        const int r = b.equations[static_cast<std::size_t>(i)];
        const int c = b.equations[static_cast<std::size_t>(j)];
        if (r < 0 || c < 0) continue;
        bool used = false;
        for (const auto* table : {&b.stiffness, &b.damping})
          for (const auto& point : *table) used = used || point(i, j) != 0.0;
        if (used) triplets.emplace_back(r, c, 0.0);
      }
}

// coefficient[slot of (i, j) in the pattern] = x_ij for the non-zero entries of X; throws if X
// has a non-zero entry outside the pattern (the pattern is the union of every term).
void map_term(const fe::SparseMatrix& X, const fe::SparseMatrix& pattern,
              std::vector<double>& coefficient) {
  coefficient.assign(static_cast<std::size_t>(pattern.nonZeros()), 0.0);
  if (is_empty(X)) return;
  const int* outer = pattern.outerIndexPtr();
  const int* inner = pattern.innerIndexPtr();
  for (Eigen::Index k = 0; k < X.outerSize(); ++k) {
    const int* begin = inner + outer[k];
    const int* end = inner + outer[k + 1];
    for (fe::SparseMatrix::InnerIterator it(X, k); it; ++it) {
      if (it.value() == 0.0) continue;  // not in the pattern (add_pattern)
      const int* pos = std::lower_bound(begin, end, static_cast<int>(it.row()));
      if (pos == end || *pos != it.row())
        throw std::logic_error("DynamicStiffness: pattern union misses an entry");
      coefficient[static_cast<std::size_t>(pos - inner)] = it.value();
    }
  }
}

// Absolute row sums of a real sparse matrix (zero vector for an empty one).
Eigen::VectorXd abs_row_sums(const fe::SparseMatrix& X, int n) {
  Eigen::VectorXd sums = Eigen::VectorXd::Zero(n);
  if (is_empty(X)) return sums;
  for (Eigen::Index k = 0; k < X.outerSize(); ++k)
    for (fe::SparseMatrix::InnerIterator it(X, k); it; ++it) sums[it.row()] += std::abs(it.value());
  return sums;
}

// Connected components of the (symmetrised) pattern by union-find: label[i] = component of
// equation i, components numbered by their smallest equation.
std::vector<int> component_labels(const fe::SparseMatrix& pattern, int& count) {
  const auto n = static_cast<std::size_t>(pattern.rows());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      int& p = parent[static_cast<std::size_t>(i)];
      p = parent[static_cast<std::size_t>(p)];  // path halving
      i = p;
    }
    return i;
  };
  for (Eigen::Index j = 0; j < pattern.outerSize(); ++j)
    for (fe::SparseMatrix::InnerIterator it(pattern, j); it; ++it) {
      const int a = root(static_cast<int>(it.row())), b = root(static_cast<int>(j));
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  std::vector<int> label(n, -1);
  count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto r = static_cast<std::size_t>(root(static_cast<int>(i)));
    if (label[r] < 0) label[r] = count++;
    label[i] = label[r];
  }
  return label;
}

// One connected component of D's pattern: D is block diagonal over these (after a symmetric
// permutation) at every frequency and speed, so each block is factorised on its own.
struct Block {
  std::vector<int> dofs;          ///< global equation of each local one (RCM order)
  fe::ComplexSparseMatrix A;      ///< D on the block (local numbering), compressed
  std::vector<std::size_t> slot;  ///< entry of the global pattern behind each entry of A
  Coefficients terms;             ///< per entry of A
  Eigen::VectorXd row_sum;        ///< absolute row sums of A's last values
  std::unique_ptr<UmfpackLu> lu;  ///< when this block takes the sparse path
  linalg::BandedLU banded;        ///< when it takes the banded path
  bool banded_path = false;
  bool active = true;             ///< factorised at the last factorize
  bool assembled = false;         ///< A's values are those of the last factorize
  bool identity = false;          ///< the whole system in its own numbering (no gather needed)
  mutable Eigen::MatrixXcd b, x;  ///< gathered load and solution (sparse path)
  mutable Eigen::VectorXcd work;  ///< banded solve workspace
  Eigen::MatrixXcd load;          ///< restrict_to's load on this block (local numbering)

  int size() const { return static_cast<int>(dofs.size()); }

  /// Absolute row sums of the last factorised values (local numbering).
  const double* row_sums() const {
    return banded_path && !assembled ? banded.row_sums() : row_sum.data();
  }

  // The banded factor takes D as a combination of its real terms (K, M, C, G, K_loss; the
  // weights are in factor_blocks) and assembles it itself.
  // Its columns are scaled by |K_ii|^(-1/2) (|M_ii|^(-1/2) when some K_ii is zero; none when
  // some M_ii is zero too): a beam's rotations and displacements then weigh alike, and the
  // pivots stay on the diagonal however fine the mesh.
  void set_banded_terms() {
    const auto data = [](const std::vector<double>& v) { return v.empty() ? nullptr : v.data(); };
    banded.set_terms({data(terms.stiffness), data(terms.mass), data(terms.damping),
                      data(terms.gyroscopic), data(terms.loss)});
    std::vector<double> scale(static_cast<std::size_t>(size()), 0.0);
    const auto diagonal_scale = [&](const std::vector<double>& term) {
      if (term.empty()) return false;
      for (int j = 0; j < size(); ++j) {
        double d = 0.0;
        for (int k = A.outerIndexPtr()[j]; k < A.outerIndexPtr()[j + 1]; ++k)
          if (A.innerIndexPtr()[k] == j) d = std::abs(term[static_cast<std::size_t>(k)]);
        if (!(d > 0.0)) return false;
        scale[static_cast<std::size_t>(j)] = 1.0 / std::sqrt(d);
      }
      return true;
    };
    const bool scaled = diagonal_scale(terms.stiffness) || diagonal_scale(terms.mass);
    banded.set_column_scale(scaled ? scale.data() : nullptr);
  }

  // Values of A (and their row sums of |Re| + |Im|) at frequency w, speed W and modal shift w s0.
  void assemble(double w, double speed, double shift, Complex* values, double* sums) const {
    const double w2 = w * w, ww = w * speed;
    std::fill(sums, sums + size(), 0.0);
    const int* inner = A.innerIndexPtr();
    // A term that is zero on the whole block is stored empty and not read (memory traffic is
    // most of this loop's cost); the additions keep their order otherwise.
    const auto data = [](const std::vector<double>& v) { return v.empty() ? nullptr : v.data(); };
    const double* K = data(terms.stiffness);
    const double* Ms = data(terms.mass);
    const double* C = data(terms.damping);
    const double* G = data(terms.gyroscopic);
    const double* L = data(terms.loss);
    for (std::size_t k = 0; k < slot.size(); ++k) {
      double re = K != nullptr ? K[k] : 0.0, im = 0.0;
      if (Ms != nullptr) {
        re -= w2 * Ms[k];
        im = shift * Ms[k];
      }
      if (C != nullptr) im += w * C[k];
      if (G != nullptr) im += ww * G[k];
      if (L != nullptr) im += L[k];
      values[k] = Complex(re, im);
      sums[inner[k]] += std::abs(re) + std::abs(im);  // |z|_1, as the banded factor's
    }
  }
};

// The blocks of `pattern`, each with its local compressed-column pattern, numbered in
// reverse Cuthill-McKee order: the banded LU then keeps that order, and its band is filled
// column after column from values stored in the same order (a stream, not a scatter).
std::vector<Block> split_blocks(const fe::SparseMatrix& pattern) {
  int count = 0;
  const std::vector<int> label = component_labels(pattern, count);
  std::vector<Block> blocks(static_cast<std::size_t>(count));
  std::vector<int> local(label.size());
  for (std::size_t i = 0; i < label.size(); ++i) {
    std::vector<int>& dofs = blocks[static_cast<std::size_t>(label[i])].dofs;
    local[i] = static_cast<int>(dofs.size());
    dofs.push_back(static_cast<int>(i));
  }
  const int* outer = pattern.outerIndexPtr();
  const int* inner = pattern.innerIndexPtr();
  for (Block& b : blocks) {
    // The block's pattern in increasing global order, each entry valued by its slot + 1.
    std::vector<Eigen::Triplet<double>> triplets;
    for (int j : b.dofs)
      for (int k = outer[j]; k < outer[j + 1]; ++k)
        triplets.emplace_back(local[static_cast<std::size_t>(inner[k])],
                              local[static_cast<std::size_t>(j)], static_cast<double>(k + 1));
    fe::SparseMatrix slots(b.size(), b.size());
    slots.setFromTriplets(triplets.begin(), triplets.end());
    slots.makeCompressed();
    // Renumbered: order[new] = old local index.
    const std::vector<int> order =
        linalg::reverse_cuthill_mckee(b.size(), slots.outerIndexPtr(), slots.innerIndexPtr());
    std::vector<int> renumber(order.size());
    for (std::size_t k = 0; k < order.size(); ++k)
      renumber[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
    for (auto& t : triplets)
      t = Eigen::Triplet<double>(renumber[static_cast<std::size_t>(t.row())],
                                 renumber[static_cast<std::size_t>(t.col())], t.value());
    const std::vector<int> increasing = b.dofs;
    for (std::size_t k = 0; k < order.size(); ++k)
      b.dofs[k] = increasing[static_cast<std::size_t>(order[k])];
    slots.setZero();
    slots.setFromTriplets(triplets.begin(), triplets.end());
    slots.makeCompressed();
    for (Eigen::Index k = 0; k < slots.nonZeros(); ++k)
      b.slot.push_back(static_cast<std::size_t>(slots.valuePtr()[k]) - 1);
    b.A = slots.cast<Complex>();
    b.A.makeCompressed();
    b.row_sum.setZero(b.size());
    b.identity = count == 1;
    for (int i = 0; i < b.size(); ++i)
      b.identity = b.identity && b.dofs[static_cast<std::size_t>(i)] == i;
  }
  return blocks;
}

// from[slot[k]] for each k; empty when all are zero (Block::assemble skips the term).
std::vector<double> gather(const std::vector<double>& from, const std::vector<std::size_t>& slot) {
  std::vector<double> out(slot.size());
  bool any = false;
  for (std::size_t k = 0; k < slot.size(); ++k) {
    out[k] = from[slot[k]];
    any = any || out[k] != 0.0;
  }
  if (!any) out.clear();
  return out;
}

}  // namespace

// Modal damping i w B diag(c) B^T (B = M Phi, Phi^T M Phi = I) is kept out of the sparse factor.
// Plain Woodbury on the sparse part A = K - w^2 M + i w (C + W G) + i K_loss fails when A is
// singular or nearly so, which happens exactly at the undamped natural frequencies of a model
// damped only modally. So the factor is taken of the regularised A_s = A + i w s0 M, s0 > 0
// (every mode damped, A_s regular for w > 0), and
//   P = A_s + i w B diag(c - s0) B^T = D + i w s0 (M - B B^T)
// is inverted exactly by Woodbury:
//   P^{-1} F = Z - Y (I + S B^T Y)^{-1} S B^T Z,  Z = A_s^{-1} F, Y = A_s^{-1} B,
//   S = i w diag(c - s0)   (no inverse of S is needed, so c_r = s0 or c_r = 0 are harmless).
// P differs from D only on the M-orthogonal complement of the damping modes (M - B B^T), so
// iterative refinement x += P^{-1} (F - D x) removes the difference; its contraction on a
// complement mode j is w s0 / |w_j^2 - w^2 + i w s0| < 1 (one step when the basis spans all
// modes). Residuals use the exact D (sparse product plus the low-rank term).
//
// Blocks (issue #19): the pattern is the union of the non-zero entries of M, K(W), C(W) (with
// every entry a speed-dependent bearing can take), G and K_loss, so D(w; W) is block diagonal
// over its connected components at every w and W, and A^{-1} F is solved block by block, each
// with its own ordering and band (a straight shaft: lateral, axial, torsional). restrict_to()
// leaves out the blocks on which the load is zero: their response is exactly 0.
struct DynamicStiffness::Impl {
  fe::SparseMatrix pattern;  ///< union of the terms' non-zero entries (values unused)
  Coefficients global;       ///< the terms per entry of `pattern`
  std::vector<Block> blocks;
  std::vector<char> loaded;  ///< per block: restrict_to's load reaches it
  bool restricted = false;
  Eigen::MatrixXcd loads;  ///< restrict_to's load
  bool prepared = false;   ///< the banded blocks forward-substituted `loads` at the last factor
  Eigen::VectorXd row_mass, row_stiffness, row_damping, row_gyroscopic, row_loss;
  bool analysed = false;
  int n = 0;
  double omega = 0.0, speed = 0.0;  ///< of the last factorize
  fe::ComplexSparseMatrix M;        ///< complex copy of M for the residual
  Eigen::MatrixXcd B;
  Eigen::VectorXd c;
  double s0 = 0.0;
  Eigen::VectorXcd s_full;  ///< i w c
  Eigen::VectorXcd s;       ///< i w (c - s0)
  Complex shift{0.0};       ///< i w s0 (A_s = A + shift M)
  Eigen::MatrixXcd Y;
  Eigen::PartialPivLU<Eigen::MatrixXcd> capacitance;
  bool modal_path = false;
  double norm_inf = 0.0;  ///< bound of the infinity norm of the exact D (backward errors)

  void build_pattern(const fe::LinearSystem& system, const fe::SparseMatrix& K,
                     const fe::SparseMatrix& C) {
    std::vector<Eigen::Triplet<double>> triplets;
    for (const auto* X : {&system.M, &K, &C, &system.G, &system.K_loss}) add_pattern(*X, triplets);
    add_speed_bearing_pattern(system, triplets);
    for (int i = 0; i < n; ++i) triplets.emplace_back(i, i, 0.0);
    pattern.resize(n, n);
    pattern.setFromTriplets(triplets.begin(), triplets.end());
    pattern.makeCompressed();
    blocks = split_blocks(pattern);
    loaded.assign(blocks.size(), 1);
    map_term(system.M, pattern, global.mass);
    map_term(system.G, pattern, global.gyroscopic);
    map_term(system.K_loss, pattern, global.loss);
    for (Block& b : blocks) {
      b.terms.mass = gather(global.mass, b.slot);
      b.terms.gyroscopic = gather(global.gyroscopic, b.slot);
      b.terms.loss = gather(global.loss, b.slot);
    }
    map_speed_terms(K, C);
    analysed = false;
  }

  // K(W), C(W) into the pattern and the blocks.
  void map_speed_terms(const fe::SparseMatrix& K, const fe::SparseMatrix& C) {
    map_term(K, pattern, global.stiffness);
    map_term(C, pattern, global.damping);
    for (Block& b : blocks) {
      b.terms.stiffness = gather(global.stiffness, b.slot);
      b.terms.damping = gather(global.damping, b.slot);
      if (analysed && b.banded_path) b.set_banded_terms();
    }
  }

  // A^{-1} F block by block (X is resized only when its shape differs); 0 on blocks left out.
  // `reuse`: F is the load of restrict_to, forward-substituted during the factorisation.
  bool factor_solve(const Eigen::MatrixXcd& F, Eigen::MatrixXcd& X, bool reuse = false) const {
    X.resize(F.rows(), F.cols());
    for (const Block& b : blocks) {
      if (!b.active) {
        for (int g : b.dofs) X.row(g).setZero();
      } else if (b.banded_path) {
        for (Eigen::Index j = 0; j < F.cols(); ++j) {
          const int column = static_cast<int>(j);
          if (b.identity) {
            if (reuse)
              b.banded.solve_prepared(column, X.col(j).data(), b.work.data());
            else
              b.banded.solve(F.col(j).data(), X.col(j).data(), b.work.data());
            continue;
          }
          Complex* x = b.x.data();
          if (reuse) {
            b.banded.solve_prepared(column, x, b.work.data());
          } else {
            for (int i = 0; i < b.size(); ++i) x[i] = F(b.dofs[static_cast<std::size_t>(i)], j);
            b.banded.solve(x, x, b.work.data());
          }
          for (int i = 0; i < b.size(); ++i) X(b.dofs[static_cast<std::size_t>(i)], j) = x[i];
        }
      } else if (b.identity) {
        if (!b.lu->solve(b.A, F, X)) return false;
      } else {
        b.b.resize(b.size(), F.cols());
        for (int i = 0; i < b.size(); ++i) b.b.row(i) = F.row(b.dofs[static_cast<std::size_t>(i)]);
        if (!b.lu->solve(b.A, b.b, b.x)) return false;
        for (int i = 0; i < b.size(); ++i) X.row(b.dofs[static_cast<std::size_t>(i)]) = b.x.row(i);
      }
    }
    return true;
  }

  // P^{-1} F (A_s^{-1} F without the modal path).
  bool apply_inverse(const Eigen::MatrixXcd& F, Eigen::MatrixXcd& X, bool reuse = false) const {
    if (!factor_solve(F, X, reuse)) return false;
    if (modal_path) X -= Y * capacitance.solve(s.asDiagonal() * (B.transpose() * X));
    return true;
  }

  // D x with the exact operator (blocks left out by restrict_to assembled on the fly).
  Eigen::MatrixXcd apply(const Eigen::MatrixXcd& x) const {
    Eigen::MatrixXcd y(x.rows(), x.cols());
    for (const Block& b : blocks) {
      fe::ComplexSparseMatrix fresh;
      const fe::ComplexSparseMatrix* A = &b.A;
      if (!b.assembled) {
        fresh = b.A;
        Eigen::VectorXd sums(b.size());
        b.assemble(omega, speed, shift.imag(), fresh.valuePtr(), sums.data());
        A = &fresh;
      }
      if (b.identity) {
        y = *A * x;
        continue;
      }
      Eigen::MatrixXcd xb(b.size(), x.cols());
      for (int i = 0; i < b.size(); ++i) xb.row(i) = x.row(b.dofs[static_cast<std::size_t>(i)]);
      const Eigen::MatrixXcd yb = *A * xb;
      for (int i = 0; i < b.size(); ++i) y.row(b.dofs[static_cast<std::size_t>(i)]) = yb.row(i);
    }
    if (s_full.size() > 0) {
      if (shift != Complex(0.0)) y -= shift * (M * x);
      y += B * (s_full.asDiagonal() * (B.transpose() * x));
    }
    return y;
  }

  // The first (lowest) equation of a factorised block whose row of D cancels to round-off
  // relative to its terms, with that ratio; -1 when none.
  std::pair<int, double> cancelled_row(double w, double W) {
    const double w2 = w * w, wg = w * std::abs(W);
    std::pair<int, double> first{-1, 0.0};
    norm_inf = 0.0;
    for (const Block& b : blocks) {
      if (!b.active) continue;
      for (int i = 0; i < b.size(); ++i) {
        const auto g = static_cast<Eigen::Index>(b.dofs[static_cast<std::size_t>(i)]);
        const double row = b.row_sums()[i];
        norm_inf = std::max(norm_inf, row);
        const double scale = row_stiffness[g] + w2 * row_mass[g] + w * row_damping[g] +
                             wg * row_gyroscopic[g] + row_loss[g] + std::abs(shift) * row_mass[g];
        if (scale > 0.0 && row < kSingularPivotRatio * scale &&
            (first.first < 0 || g < first.first))
          first = {static_cast<int>(g), row / scale};
      }
    }
    return first;
  }
};

DynamicStiffness::DynamicStiffness(const fe::LinearSystem& system, double speed,
                                   std::string analysis, FactorPath path)
    : system_(system),
      analysis_(std::move(analysis)),
      requested_(path),
      impl_(std::make_unique<Impl>()) {
  n_ = static_cast<int>(system.M.rows());
  if (n_ == 0)
    throw NumericalError(analysis_, "the model has no free degrees of freedom (all constrained)");
  check_square(system.M, n_, "M");
  check_square(system.K, n_, "K");
  check_square(system.C, n_, "C");
  check_square(system.G, n_, "G");
  check_square(system.K_loss, n_, "K_loss");
  Impl& m = *impl_;
  m.n = n_;
  m.row_mass = abs_row_sums(system.M, n_);
  m.row_gyroscopic = abs_row_sums(system.G, n_);
  m.row_loss = abs_row_sums(system.K_loss, n_);
  if (system.has_modal_damping()) {
    if (system.modal_basis.rows() != n_ ||
        system.modal_basis.cols() != system.modal_coefficients.size())
      throw std::logic_error("LinearSystem: modal_basis and modal_coefficients do not match");
    m.B = system.modal_basis.cast<Complex>();
    m.c = system.modal_coefficients;
    m.M = system.M.cast<Complex>();
    // The smallest positive modal coefficient: enough to make A_s regular, and small, so the
    // refinement contracts fast on modes outside the basis.
    for (Eigen::Index r = 0; r < m.c.size(); ++r)
      if (m.c[r] > 0.0 && (m.s0 == 0.0 || m.c[r] < m.s0)) m.s0 = m.c[r];
  }
  set_speed(speed);
}

DynamicStiffness::~DynamicStiffness() = default;

void DynamicStiffness::set_speed(double speed) {
  if (!std::isfinite(speed)) throw std::invalid_argument("DynamicStiffness: speed is not finite");
  speed_ = speed;
  omega_ = std::numeric_limits<double>::quiet_NaN();
  Impl& m = *impl_;
  // Without speed-dependent bearings K(W) = K and C(W) = C: nothing to rebuild (W enters only
  // through the factor of G at factorize).
  const bool first = m.pattern.rows() != n_;
  if (system_.speed_bearings.empty() && !first) return;
  const fe::SparseMatrix K = system_.K_at(speed);
  const fe::SparseMatrix C = system_.C_at(speed);
  check_square(K, n_, "K_at");
  check_square(C, n_, "C_at");
  m.row_stiffness = abs_row_sums(K, n_);
  m.row_damping = abs_row_sums(C, n_);
  // The pattern holds every entry the bearings can take, so later speeds change values only:
  // the blocks and the symbolic analysis stay.
  if (first)
    m.build_pattern(system_, K, C);
  else
    m.map_speed_terms(K, C);
}

void DynamicStiffness::restrict_to(const Eigen::MatrixXcd& loads) {
  if (loads.rows() != n_)
    throw std::invalid_argument(fmt::format(
        "DynamicStiffness::restrict_to: the load has {} rows, expected {}", loads.rows(), n_));
  Impl& m = *impl_;
  for (std::size_t k = 0; k < m.blocks.size(); ++k) {
    bool reached = false;
    for (int g : m.blocks[k].dofs)
      reached = reached || (loads.row(g).array() != Complex(0.0)).any();
    m.loaded[k] = reached ? 1 : 0;
    // The banded factorisation forward-substitutes this load as it goes (BandedLU::factorize
    // with right-hand sides), so that solve() with it has only the back substitution left.
    Block& b = m.blocks[k];
    b.load.resize(b.size(), loads.cols());
    if (reached)
      for (int i = 0; i < b.size(); ++i)
        b.load.row(i) = loads.row(b.dofs[static_cast<std::size_t>(i)]);
  }
  m.loads = loads;
  m.restricted = true;
  m.prepared = false;  // until the next factorize forward-substitutes the new load
}

void DynamicStiffness::unrestrict() {
  impl_->restricted = false;
  impl_->prepared = false;
}

std::vector<DynamicStiffness::BlockInfo> DynamicStiffness::blocks() const {
  std::vector<BlockInfo> out;
  for (const Block& b : impl_->blocks) {
    BlockInfo info;
    info.size = b.size();
    info.factorised = impl_->analysed && b.active;
    if (impl_->analysed) {
      info.path = b.banded_path ? FactorPath::Banded : FactorPath::Sparse;
      if (b.banded_path) {
        info.lower_bandwidth = b.banded.lower_bandwidth();
        info.upper_bandwidth = b.banded.upper_bandwidth();
      }
    }
    out.push_back(info);
  }
  return out;
}

void DynamicStiffness::factorize(double omega) {
  if (!(omega >= 0.0) || !std::isfinite(omega))
    throw std::invalid_argument(fmt::format("DynamicStiffness: frequency {} rad/s", omega));
  Impl& m = *impl_;
  const bool modal = system_.has_modal_damping();
  m.modal_path = modal && omega > 0.0 && m.s0 > 0.0;
  const Complex iw(0.0, omega);
  m.shift = m.modal_path ? iw * m.s0 : Complex(0.0);
  m.omega = omega;
  m.speed = speed_;
  omega_ = omega;
  // Blocks left out by restrict_to are not factorised and their response is 0 exactly. That is
  // D's solution there whenever the block is regular. A block that is singular and unloaded
  // (an axially free rotor at w = 0) has a consistent, undetermined response there; 0 is
  // returned, and the block's singularity is not reported, since nothing excites its free
  // motion. The modal damping term (w > 0) couples every block: nothing is left out then.
  const bool restricted = m.restricted && !(modal && omega > 0.0);
  m.prepared = restricted;
  for (std::size_t k = 0; k < m.blocks.size(); ++k) {
    Block& b = m.blocks[k];
    b.active = !restricted || m.loaded[k] != 0;
    // The first factorisation assembles every block: the symbolic analysis sees real values.
    // The banded factor assembles its block itself; the values are kept for the residuals of
    // the modal path only.
    b.assembled = !m.analysed || (b.active && (!b.banded_path || m.modal_path));
    if (b.assembled) b.assemble(omega, speed_, m.shift.imag(), b.A.valuePtr(), b.row_sum.data());
  }

  auto singular = [&](const std::string& measure) {
    std::string head = fmt::format(
        "D(w) = K - w^2 M + i w (C + W G) + i K_loss{} is singular at f = {:.6g} Hz "
        "(w = {:.6g} rad/s, reference speed W = {:.6g} rpm; {})",
        modal ? " + i w C_modal" : "", omega * kHzPerRadS, omega, speed_ * kRpmPerRadS, measure);
    std::string cause;
    if (omega == 0.0)
      cause =
          "model has rigid-body motion: add bearings or constraints (a rotor free in "
          "torsion or axially needs a spring or constraint there), or start the frequency "
          "range above 0";
    else
      cause =
          "this frequency is at (or, relative to the stiffness, very near) a natural "
          "frequency of an undamped model, or near 0 Hz with rigid-body motion: add damping "
          "(bearing, Rayleigh, structural or modal), bearings or constraints, or shift the "
          "frequencies";
    return NumericalError(analysis_, head + ": " + cause);
  };

  if (!m.analysed) analyze();
  const bool regular = factor_blocks();
  // A row whose terms cancel to round-off is undetermined, whatever the pivots say (the LU
  // scales rows, so a matrix made entirely of round-off can show a pivot ratio of 1).
  const auto [row, ratio] = m.cancelled_row(omega, speed_);
  if (row >= 0) throw singular(fmt::format("row {} cancels to {:.2g} of its terms", row, ratio));
  // rcond_ is NaN when every block is left out (nothing factorised, nothing to judge).
  if (!regular || !(rcond_ >= kSingularPivotRatio || std::isnan(rcond_)))
    throw singular(fmt::format("LU pivot ratio {:.2g}", rcond_));

  if (modal) {
    m.s_full = iw * m.c.cast<Complex>();
    // |D| <= |A_s| + |i w s0| |M| + |B| |S| |B|^T, row by row.
    const Eigen::MatrixXd B_abs = system_.modal_basis.cwiseAbs();
    const Eigen::VectorXd modal_rows =
        B_abs *
        (omega * m.c.cwiseAbs()).cwiseProduct(B_abs.transpose() * Eigen::VectorXd::Ones(n_));
    m.norm_inf += std::abs(m.shift) * m.row_mass.maxCoeff() + modal_rows.maxCoeff();
  }
  if (m.modal_path) {
    m.s = iw * (m.c.array() - m.s0).matrix().cast<Complex>();
    if (!m.factor_solve(m.B, m.Y)) throw singular("UMFPACK solve failed");
    const Eigen::Index r = m.B.cols();
    const Eigen::MatrixXcd cap =
        Eigen::MatrixXcd::Identity(r, r) + m.s.asDiagonal() * (m.B.transpose() * m.Y);
    m.capacitance.compute(cap);
    // The capacitance matrix is singular exactly when P is (A_s is regular).
    if (!(m.capacitance.rcond() >= kSingularPivotRatio))
      throw singular(fmt::format("Woodbury capacitance rcond {:.2g}", m.capacitance.rcond()));
  }
}

// Numerical LU of every active block; rcond_ = min |u_ii| / max |u_ii| over all of them (the
// ratio of the block-diagonal factor, each block row-scaled as the whole would be). False when a
// pivot is exactly zero.
bool DynamicStiffness::factor_blocks() {
  Impl& m = *impl_;
  double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  bool regular = true, any = false;
  for (Block& b : m.blocks) {
    if (!b.active) continue;
    any = true;
    if (b.banded_path) {
      // D = K - w^2 M + i w C + i w W G + i K_loss, with the modal shift i w s0 M.
      const double w = m.omega;
      const std::array<Complex, 5> weights{Complex(1.0), Complex(-w * w, m.shift.imag()),
                                           Complex(0.0, w), Complex(0.0, w * m.speed),
                                           Complex(0.0, 1.0)};
      const Status status = m.prepared ? b.banded.factorize_terms(weights.data(), b.load.data(),
                                                                  static_cast<int>(b.load.cols()))
                                       : b.banded.factorize_terms(weights.data());
      regular = status == Status::Ok && regular;
      smallest = std::min(smallest, b.banded.smallest_pivot());
      largest = std::max(largest, b.banded.largest_pivot());
      continue;
    }
    const int status = b.lu->factorize(b.A);
    if (status != UMFPACK_OK && status != UMFPACK_WARNING_singular_matrix)
      throw NumericalError(analysis_, fmt::format("UMFPACK numeric factorisation failed (status "
                                                  "{}) at f = {:.6g} Hz; out of memory?",
                                                  status, m.omega * kHzPerRadS));
    regular = status == UMFPACK_OK && regular;
    smallest = std::min(smallest, b.lu->smallest_pivot());
    largest = std::max(largest, b.lu->largest_pivot());
  }
  if (!any)
    rcond_ = std::numeric_limits<double>::quiet_NaN();
  else
    rcond_ = regular && largest > 0.0 ? smallest / largest : 0.0;
  return regular;
}

void DynamicStiffness::analyze() {
  Impl& m = *impl_;
  bool all_banded = true;
  for (Block& b : m.blocks) {
    if (requested_ != FactorPath::Banded) {
      b.lu = std::make_unique<UmfpackLu>();
      const int status = b.lu->analyze(b.A);
      if (status != UMFPACK_OK)
        throw NumericalError(analysis_, fmt::format("UMFPACK could not analyse the pattern of "
                                                    "D(w) (status {})",
                                                    status));
    }
    if (requested_ != FactorPath::Sparse)
      b.banded.analyze(b.size(), b.A.outerIndexPtr(), b.A.innerIndexPtr(),
                       linalg::BandedLU::Ordering::Given);
    // Per block: the band when it is narrow (a shaft line), UMFPACK for a branched one.
    b.banded_path =
        requested_ == FactorPath::Banded ||
        (requested_ == FactorPath::Automatic &&
         b.banded.storage_entries() <= kBandedFillRatio * b.lu->factor_entries_estimate());
    if (b.banded_path) {
      b.set_banded_terms();
      b.lu.reset();
      b.work.resize(b.size());
      b.x.resize(b.size(), 1);
    }
    all_banded = all_banded && b.banded_path;
  }
  chosen_ = all_banded ? FactorPath::Banded : FactorPath::Sparse;
  m.analysed = true;
}

Eigen::MatrixXcd DynamicStiffness::solve(const Eigen::MatrixXcd& F) const {
  Eigen::MatrixXcd X;
  solve(F, X);
  return X;
}

void DynamicStiffness::solve(const Eigen::MatrixXcd& F, Eigen::MatrixXcd& X) const {
  if (std::isnan(omega_)) throw std::logic_error("DynamicStiffness::solve before factorize");
  if (F.rows() != n_) throw std::invalid_argument("DynamicStiffness::solve: wrong load size");
  const Impl& m = *impl_;
  // The load of restrict_to was forward-substituted during the factorisation: reuse it when F
  // is that load exactly (bit-identical to the full solve); it is zero on the skipped blocks.
  const bool prepared =
      m.prepared && F.rows() == m.loads.rows() && F.cols() == m.loads.cols() && F == m.loads;
  for (const Block& b : m.blocks)
    if (!b.active && !prepared)
      for (int g : b.dofs)
        if ((F.row(g).array() != Complex(0.0)).any())
          throw std::invalid_argument(fmt::format(
              "DynamicStiffness::solve: load on equation {}, outside the blocks restrict_to "
              "kept",
              g));
  const double f_hz = omega_ * kHzPerRadS;
  if (!m.apply_inverse(F, X, prepared))
    throw NumericalError(analysis_, fmt::format("UMFPACK solve failed at f = {:.6g} Hz", f_hz));
  if (m.modal_path) {
    // Iterative refinement until the normwise backward error
    //   eta = |F - D X|_inf / (|D|_inf |X|_inf + |F|_inf)
    // is at round-off level, which makes X as accurate as a direct solve of D could, or until
    // it stops falling (round-off reached; accepted while eta <= 1e-10). One residual and no
    // correction when the damping modes span the whole space (P = D).
    constexpr int kMaxRefinements = 100;
    constexpr double kConverged = 1e-14, kAcceptable = 1e-10;
    double eta = std::numeric_limits<double>::infinity();
    double previous = eta;
    Eigen::MatrixXcd dX;
    for (int k = 0; k <= kMaxRefinements; ++k) {
      const Eigen::MatrixXcd R = F - m.apply(X);
      const double scale = m.norm_inf * X.cwiseAbs().maxCoeff() + F.cwiseAbs().maxCoeff();
      eta = scale > 0.0 ? R.cwiseAbs().maxCoeff() / scale : 0.0;
      if (eta > previous) {  // the last correction was round-off: undo it
        X -= dX;
        eta = previous;
        break;
      }
      if (!(eta > kConverged) || eta > 0.5 * previous || k == kMaxRefinements) break;
      previous = eta;
      if (!m.apply_inverse(R, dX))
        throw NumericalError(analysis_, fmt::format("UMFPACK solve failed at f = {:.6g} Hz", f_hz));
      X += dX;
    }
    if (!(eta <= kAcceptable))
      throw NumericalError(
          analysis_,
          fmt::format("modal damping: the correction for modes outside the {} damping modes did "
                      "not converge at f = {:.6g} Hz (backward error {:.2g}); an undamped mode "
                      "outside the modal damping basis is near this frequency: use more modal "
                      "damping modes or add Rayleigh or structural damping",
                      m.B.cols(), f_hz, eta));
  }
  if (!X.allFinite())
    throw NumericalError(analysis_, fmt::format("the response at f = {:.6g} Hz is not finite "
                                                "(overflow near an undamped resonance?)",
                                                f_hz));
}

Eigen::MatrixXcd DynamicStiffness::apply(const Eigen::MatrixXcd& x) const {
  if (std::isnan(omega_)) throw std::logic_error("DynamicStiffness::apply before factorize");
  return impl_->apply(x);
}

// ---------------------------------------------------------------------------------------------

unsigned sweep_threads(int requested, std::size_t points, FactorPath path, std::string& note) {
  unsigned threads = requested > 0 ? static_cast<unsigned>(requested)
                                   : std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(points, 1)));
  note.clear();
  // The BLAS-safety rule of analyses/sweep.cpp: UMFPACK calls the system BLAS from every thread.
  const linalg::BlasLibrary& blas = linalg::loaded_blas();
  if (threads > 1 && path != FactorPath::Banded && !linalg::safe_for_concurrent_calls(blas)) {
    note = fmt::format(
        "ran on 1 thread instead of {}: the sparse LU calls the system BLAS ({}), a sequential "
        "OpenBLAS, which is not safe to call from several threads at once",
        threads, blas.description);
    threads = 1;
  }
  return threads;
}

void for_each_point(std::size_t begin, std::size_t end, unsigned threads,
                    const std::function<void(std::size_t, unsigned)>& work,
                    const std::function<void(std::size_t)>& done) {
  std::atomic<std::size_t> next{begin};
  std::size_t finished = 0;
  std::size_t failed_at = end;
  std::exception_ptr failure;
  std::mutex mutex;
  auto worker = [&](unsigned t) {
    for (;;) {
      const std::size_t i = next++;
      if (i >= end) return;
      try {
        work(i, t);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (i < failed_at) {
          failed_at = i;
          failure = std::current_exception();
        }
        next = end;  // stop handing out points; those already taken finish
        return;
      }
      const std::lock_guard<std::mutex> lock(mutex);
      done(++finished);
    }
  };
  {
    std::vector<std::jthread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker, t);
    worker(0);
  }
  if (failure) std::rethrow_exception(failure);
}

// ---------------------------------------------------------------------------------------------

Eigen::MatrixXcd FrfResult::response() const {
  const int power = static_cast<int>(quantity);  // Receptance 0, Mobility 1, Accelerance 2
  Eigen::MatrixXcd out = displacement;
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    Complex factor(1.0);
    for (int p = 0; p < power; ++p) factor *= Complex(0.0, frequencies[i]);
    out.row(i) *= factor;
  }
  return out;
}

std::string FrfResult::amplitude_unit(int s) const {
  std::string unit = sensors.at(static_cast<std::size_t>(s)).rotational ? "rad" : "m";
  if (quantity == ResponseQuantity::Mobility) unit += "/s";
  if (quantity == ResponseQuantity::Accelerance) unit += "/s^2";
  if (!forced) unit += input_rotational ? "/(N m)" : "/N";
  return unit;
}

namespace {

static_assert(static_cast<int>(ResponseQuantity::Receptance) == 0 &&
              static_cast<int>(ResponseQuantity::Mobility) == 1 &&
              static_cast<int>(ResponseQuantity::Accelerance) == 2);

bool is_rotation(model::Component c) {
  return c == model::Component::Rx || c == model::Component::Ry || c == model::Component::Rz;
}

// "m/s^2/(N m)" -> "m_per_s2_per_Nm": the unit as a column-name suffix.
std::string unit_slug(const std::string& unit) {
  std::string out;
  for (char ch : unit) {
    if (ch == '/')
      out += "_per_";
    else if (ch != '(' && ch != ')' && ch != ' ' && ch != '^')
      out += ch;
  }
  return out;
}

void validate_grid(const HarmonicSettings& s, const Context& context) {
  auto fail = [&](const std::string& field, const std::string& expected, double found) {
    throw context.error(field, expected, fmt::format("{}", found));
  };
  if (!std::isfinite(s.f_min) || s.f_min < 0.0)
    fail("frequency_start_hz", "a finite value >= 0", s.f_min * kHzPerRadS);
  if (!std::isfinite(s.f_max) || s.f_max <= s.f_min)
    fail("frequency_stop_hz",
         fmt::format("a finite value > frequency_start_hz = {}", s.f_min * kHzPerRadS),
         s.f_max * kHzPerRadS);
  if (s.n_points < 2) fail("frequency_count", "an integer >= 2", s.n_points);
  if (s.spacing == Spacing::Log && s.f_min <= 0.0)
    fail("frequency_start_hz", "a value > 0 for spacing = \"log\"", s.f_min * kHzPerRadS);
  if (!std::isfinite(s.speed)) fail("speed_rpm", "a finite value", s.speed * kRpmPerRadS);
}

std::vector<double> initial_grid(const HarmonicSettings& s) {
  std::vector<double> f(static_cast<std::size_t>(s.n_points));
  const double last = s.n_points - 1;
  for (int k = 0; k < s.n_points; ++k) {
    const double t = k / last;
    f[static_cast<std::size_t>(k)] =
        s.spacing == Spacing::Log
            ? std::exp(std::log(s.f_min) + t * (std::log(s.f_max) - std::log(s.f_min)))
            : s.f_min + t * (s.f_max - s.f_min);
  }
  f.front() = s.f_min;
  f.back() = s.f_max;
  return f;
}

double to_db(double a) { return 20.0 * std::log10(std::max(a, 1e-300)); }

// Examines every peak of every sensor; appends the frequencies that would resolve the
// unresolved ones to `wanted` (when not null).
std::vector<FrfPeak> analyse_peaks(const std::vector<double>& f,
                                   const std::vector<std::vector<double>>& amplitude,
                                   const AdaptiveGridOptions& o, std::vector<double>* wanted) {
  std::vector<FrfPeak> peaks;
  const std::size_t n = f.size();
  auto want = [&](double x) {
    if (wanted != nullptr) wanted->push_back(x);
  };
  auto midpoint = [&](std::size_t k) { want(0.5 * (f[k] + f[k + 1])); };
  std::vector<double> db(n);
  for (std::size_t s = 0; s < amplitude.size(); ++s) {
    const auto& a = amplitude[s];
    for (std::size_t i = 0; i < n; ++i) db[i] = to_db(a[i]);
    for (const auto& p : signal::find_peaks(db, o.min_prominence_db)) {
      const auto hp = signal::half_power(f, a, p.index);
      FrfPeak peak;
      peak.sensor = static_cast<int>(s);
      peak.frequency = hp.frequency;
      peak.amplitude = hp.amplitude;
      peak.f1 = hp.f1;
      peak.f2 = hp.f2;
      peak.q_factor = hp.q_factor;
      peak.points_in_band = hp.points_in_band;
      const std::size_t i = p.index;
      // The true maximum of a peak lies between the neighbours of the sampled maximum, so
      // their distance bounds the location error; the parabolic vertex is then much closer.
      auto bracket = [&](double bw) { return std::max(f[i] - f[i - 1], f[i + 1] - f[i]) / bw; };
      // Samples at the vertex and tol/2 band widths either side of it: if the vertex is right,
      // the next pass sees the peak bracketed to tol; if not, the new samples move the maximum
      // and the parabola through them is much closer.
      auto locate = [&](double bw) {
        want(hp.frequency);
        want(hp.frequency - 0.5 * o.peak_tolerance * bw);
        want(hp.frequency + 0.5 * o.peak_tolerance * bw);
      };
      if (hp.has_bandwidth()) {
        const double bw = hp.bandwidth;
        peak.location_error = bracket(bw);
        bool ok = true;
        if (hp.points_in_band < o.min_points_in_band) {
          for (std::size_t k = hp.lower_bracket; k <= hp.upper_bracket; ++k) midpoint(k);
          ok = false;
        } else {
          if (peak.location_error > o.peak_tolerance) {
            locate(bw);
            ok = false;
          }
          for (std::size_t k : {hp.lower_bracket, hp.upper_bracket})
            if (f[k + 1] - f[k] > o.crossing_tolerance * bw) {
              midpoint(k);
              ok = false;
            }
        }
        peak.resolved = ok;
      } else if (i > 0 && i + 1 < n) {
        // The band is cut by the end of the range or runs into a higher peak: resolve the top
        // with the half-band that is there; no Q is reported.
        const double half = hp.has_lower()   ? hp.frequency - hp.f1
                            : hp.has_upper() ? hp.f2 - hp.frequency
                                             : std::numeric_limits<double>::quiet_NaN();
        if (std::isfinite(half) && half > 0.0) {
          const double bw = 2.0 * half;
          peak.location_error = bracket(bw);
          if (f[i] - f[i - 1] > bw / o.min_points_in_band) midpoint(i - 1);
          if (f[i + 1] - f[i] > bw / o.min_points_in_band) midpoint(i);
          if (peak.location_error > o.peak_tolerance) locate(bw);
        }
      }
      peaks.push_back(peak);
    }
  }
  return peaks;
}

// Intervals whose end amplitudes differ by more than the jump ratio, bisected down to a floor
// set by the initial spacing there.
void jump_points(const std::vector<double>& f, const std::vector<std::vector<double>>& amplitude,
                 const std::vector<double>& initial, const AdaptiveGridOptions& o,
                 std::vector<double>& wanted) {
  const double floor_factor = std::ldexp(1.0, -o.max_jump_levels);
  for (std::size_t k = 0; k + 1 < f.size(); ++k) {
    const double mid = 0.5 * (f[k] + f[k + 1]);
    auto it = std::upper_bound(initial.begin(), initial.end(), mid);
    const std::size_t j = std::clamp<std::size_t>(static_cast<std::size_t>(it - initial.begin()), 1,
                                                  initial.size() - 1);
    const double floor = (initial[j] - initial[j - 1]) * floor_factor;
    if (f[k + 1] - f[k] <= floor * 1.000001) continue;
    for (const auto& a : amplitude) {
      const double lo = std::min(a[k], a[k + 1]), hi = std::max(a[k], a[k + 1]);
      if (hi > o.jump_ratio * lo) {
        wanted.push_back(mid);
        break;
      }
    }
  }
}

// NotConverged (with what stopped the grid and the first unresolved resonance) when a peak
// with a half-power band is left unresolved; a limit reached with every peak resolved is only
// recorded in the grid summary.
void set_grid_status(FrfResult& result) {
  const GridSummary& grid = result.grid;
  int unresolved = 0;
  const FrfPeak* first = nullptr;
  for (const auto& p : result.peaks)
    if (std::isfinite(p.q_factor) && !p.resolved) {
      ++unresolved;
      if (first == nullptr) first = &p;
    }
  if (!grid.adaptive || grid.converged || first == nullptr) {
    result.status = Status::Ok;
    result.message.clear();
    return;
  }
  result.status = Status::NotConverged;
  result.message = fmt::format(
      "adaptive frequency grid stopped at {} with {} points; {} resonance peak(s) not resolved, "
      "first: sensor {} at {:.6g} Hz: a resonance with (almost) no damping has no finite band "
      "(add damping, e.g. more modal damping modes, Rayleigh or structural), or raise the limit "
      "or narrow the frequency range",
      grid.limit_hit, grid.final_points, unresolved,
      result.sensors[static_cast<std::size_t>(first->sensor)].name, first->frequency * kHzPerRadS);
}

}  // namespace

void diagnose_unresolved_peaks(FrfResult& result, int modes_in_band) {
  if (result.status != Status::NotConverged || result.grid.converged) return;
  std::vector<int> per_sensor(result.sensors.size(), 0);
  for (const auto& p : result.peaks)
    if (std::isfinite(p.q_factor) && !p.resolved) ++per_sensor[static_cast<std::size_t>(p.sensor)];
  const auto worst = std::max_element(per_sensor.begin(), per_sensor.end());
  if (worst == per_sensor.end() || *worst <= 2 * modes_in_band + 2) return;
  const auto s = static_cast<std::size_t>(worst - per_sensor.begin());
  result.message = fmt::format(
      "adaptive frequency grid stopped at {} with {} points; sensor {} has {} unresolved peaks "
      "but the system has only {} mode(s) in the frequency range: the response is not smooth, "
      "a numerical fault (e.g. an inaccurate or inconsistent solve of D(w) X = F), not a "
      "lightly damped resonance; adding damping will not help: check the model's "
      "conditioning (stiffness and mass values far apart) and report it with the model",
      result.grid.limit_hit, result.grid.final_points, result.sensors[s].name, *worst,
      modes_in_band);
}

namespace {

// The frequencies the next pass of the adaptive grid adds: those that would resolve the
// unresolved peaks and bisect the jumps, inside the range and not within 1e-12 f_max of a
// sample or of each other.
std::vector<double> new_frequencies(const std::vector<double>& f,
                                    const std::vector<std::vector<double>>& amplitude,
                                    const std::vector<double>& initial,
                                    const std::map<double, Eigen::VectorXcd>& samples,
                                    const HarmonicSettings& settings,
                                    const AdaptiveGridOptions& options) {
  const double same = 1e-12 * settings.f_max;
  std::vector<double> wanted;
  analyse_peaks(f, amplitude, options, &wanted);
  jump_points(f, amplitude, initial, options, wanted);
  std::sort(wanted.begin(), wanted.end());
  std::vector<double> fresh;
  for (double w : wanted) {
    if (!(w > settings.f_min && w < settings.f_max)) continue;
    if (!fresh.empty() && w - fresh.back() <= same) continue;
    auto it = samples.lower_bound(w);
    if (it != samples.end() && it->first - w <= same) continue;
    if (it != samples.begin() && w - std::prev(it)->first <= same) continue;
    fresh.push_back(w);
  }
  return fresh;
}

// The fewest samples in a band and the largest location error over the peaks with a band.
void summarize_peaks(const std::vector<FrfPeak>& peaks, bool adaptive, GridSummary& grid) {
  bool any_band = false;
  for (const auto& p : peaks) {
    if (!std::isfinite(p.q_factor)) continue;
    grid.min_points_in_band =
        any_band ? std::min(grid.min_points_in_band, p.points_in_band) : p.points_in_band;
    grid.max_location_error = std::max(grid.max_location_error, p.location_error);
    any_band = true;
    // A peak left unresolved without a limit hit: its band is narrower than the grid can
    // separate (samples closer than 1e-12 f_max are merged).
    if (adaptive && grid.converged && !p.resolved) {
      grid.converged = false;
      grid.limit_hit = "the frequency resolution (1e-12 x frequency_stop)";
    }
  }
}

}  // namespace

FrfResult frequency_response(const fe::LinearSystem& system, const Eigen::VectorXcd& load,
                             const std::vector<int>& outputs, const HarmonicSettings& settings,
                             const Context& context, const AdaptiveGridOptions& options) {
  validate_grid(settings, context);
  const std::string& analysis_name = context.name();
  Progress& progress = context.progress();
  const int n = static_cast<int>(system.M.rows());
  if (load.size() != n)
    throw std::invalid_argument(
        fmt::format("frequency_response: load has {} entries, system {}", load.size(), n));
  if (outputs.empty()) throw std::invalid_argument("frequency_response: no outputs");
  for (int eq : outputs)
    if (eq < 0 || eq >= n)
      throw std::invalid_argument(fmt::format("frequency_response: output equation {}", eq));
  if (options.min_points_in_band < 3 || !(options.peak_tolerance > 0.0) ||
      !(options.crossing_tolerance > 0.0) || !(options.jump_ratio > 1.0) ||
      options.max_points < settings.n_points || options.max_passes < 0)
    throw std::invalid_argument("frequency_response: invalid AdaptiveGridOptions");

  FrfResult result;
  result.quantity = settings.quantity;
  result.speed = settings.speed;
  for (int eq : outputs) result.sensors.push_back({fmt::format("eq{}", eq), eq, false});
  const std::size_t m = outputs.size();
  const int power = static_cast<int>(settings.quantity);

  // One DynamicStiffness per thread; the first frequency on this thread fixes the factor path
  // (and so whether threads may run). Each frequency is independent of the others, so the
  // samples are bit-identical for any thread count.
  const Eigen::MatrixXcd F = load;
  std::vector<std::unique_ptr<DynamicStiffness>> solvers;
  solvers.push_back(std::make_unique<DynamicStiffness>(system, settings.speed, analysis_name));
  std::vector<Eigen::MatrixXcd> work(1);
  unsigned threads = 0;  // decided after the first frequency
  std::map<double, Eigen::VectorXcd> samples;
  auto evaluate_all = [&](const std::vector<double>& ws,
                          const std::function<void(std::size_t)>& done) {
    std::vector<Eigen::VectorXcd> out(ws.size(), Eigen::VectorXcd(static_cast<Eigen::Index>(m)));
    auto point = [&](std::size_t k, unsigned t) {
      solvers[t]->factorize(ws[k]);
      solvers[t]->solve(F, work[t]);
      for (std::size_t s = 0; s < m; ++s)
        out[k][static_cast<Eigen::Index>(s)] = work[t](outputs[s], 0);
    };
    std::size_t begin = 0;
    if (threads == 0 && !ws.empty()) {
      point(0, 0);
      done(1);
      begin = 1;
      std::string note;
      threads = sweep_threads(settings.threads, std::numeric_limits<std::size_t>::max(),
                              solvers.front()->factor_path(), note);
      result.thread_note = note;
      for (unsigned t = 1; t < threads; ++t)
        solvers.push_back(
            std::make_unique<DynamicStiffness>(system, settings.speed, analysis_name));
      work.resize(threads);
    }
    for_each_point(begin, ws.size(), std::max(threads, 1u), point,
                   [&](std::size_t count) { done(begin + count); });
    for (std::size_t k = 0; k < ws.size(); ++k) samples[ws[k]] = std::move(out[k]);
  };

  const std::vector<double> initial = initial_grid(settings);
  progress.start(fmt::format("{}: {} frequencies", analysis_name, initial.size()), initial.size());
  evaluate_all(initial, [&](std::size_t count) { progress.update(count); });
  progress.finish();

  std::vector<double> f;
  std::vector<std::vector<double>> amplitude(m);
  auto to_arrays = [&]() {
    f.clear();
    for (auto& a : amplitude) a.clear();
    for (const auto& [w, x] : samples) {
      f.push_back(w);
      const double scale = std::pow(w, power);
      for (std::size_t s = 0; s < m; ++s)
        amplitude[s].push_back(std::abs(x[static_cast<Eigen::Index>(s)]) * scale);
    }
  };
  to_arrays();

  GridSummary& grid = result.grid;
  grid.initial_points = static_cast<int>(initial.size());
  grid.required_points_in_band = options.min_points_in_band;
  grid.required_location_error = options.peak_tolerance;
  grid.adaptive = settings.adaptive;
  if (settings.adaptive) {
    progress.start(fmt::format("{}: refining the frequency grid", analysis_name), 0);
    for (int pass = 0;; ++pass) {
      const std::vector<double> fresh =
          new_frequencies(f, amplitude, initial, samples, settings, options);
      if (fresh.empty()) break;
      if (pass >= options.max_passes) {
        grid.converged = false;
        grid.limit_hit = fmt::format("max_passes = {}", options.max_passes);
        break;
      }
      if (samples.size() + fresh.size() > static_cast<std::size_t>(options.max_points)) {
        grid.converged = false;
        grid.limit_hit = fmt::format("max_points = {}", options.max_points);
        break;
      }
      evaluate_all(fresh, [](std::size_t) {});
      grid.passes = pass + 1;
      to_arrays();
      progress.update(samples.size());
    }
    progress.finish();
  }

  result.peaks = analyse_peaks(f, amplitude, options, nullptr);
  std::stable_sort(result.peaks.begin(), result.peaks.end(),
                   [](const FrfPeak& a, const FrfPeak& b) { return a.sensor < b.sensor; });
  grid.final_points = static_cast<int>(f.size());
  summarize_peaks(result.peaks, settings.adaptive, grid);

  result.frequencies =
      Eigen::Map<const Eigen::VectorXd>(f.data(), static_cast<Eigen::Index>(f.size()));
  result.displacement.resize(static_cast<Eigen::Index>(f.size()), static_cast<Eigen::Index>(m));
  Eigen::Index row = 0;
  for (const auto& [w, x] : samples) result.displacement.row(row++) = x.transpose();

  set_grid_status(result);
  return result;
}

namespace {

// The equation of DOF `c` of node `node`; `fail(expected, found, hint)` makes the error.
template <class Fail>
int equation_of(const fe::DofMap& dofs, const std::string& node, model::Component c,
                const Fail& fail) {
  const int index = dofs.find_node(node);
  if (index < 0) throw fail("the name of a node", "'" + node + "'", "");
  const int eq = dofs.dof(index, c);
  if (eq < 0)
    throw fail("an unconstrained DOF",
               fmt::format("{}.{} (constrained)", node,
                           model::kComponentNames[static_cast<std::size_t>(c)]),
               "a constrained DOF neither moves nor takes load");
  return eq;
}

// The load of the unit input or of the named forces; sets the input fields of `header`.
Eigen::VectorXcd harmonic_load(const model::Model& model, const fe::LinearSystem& system,
                               const HarmonicSettings& settings, const Context& context,
                               FrfResult& header) {
  const fe::DofMap& dofs = system.dofs;
  Eigen::VectorXcd load = Eigen::VectorXcd::Zero(system.M.rows());
  if (!settings.input_node.empty()) {
    equation_of(dofs, settings.input_node, settings.input_dof,
                [&](std::string expected, std::string found, std::string hint) {
                  return context.error("input_node", std::move(expected), std::move(found),
                                       std::move(hint));
                });
    load =
        system.unit_load(dofs.find_node(settings.input_node), settings.input_dof).cast<Complex>();
    header.input = settings.input_node + "." +
                   model::kComponentNames[static_cast<std::size_t>(settings.input_dof)];
    header.input_rotational = is_rotation(settings.input_dof);
    return load;
  }
  for (const auto& force_name : settings.forces) {
    auto it = std::find_if(model.forces.begin(), model.forces.end(),
                           [&](const model::HarmonicForce& h) { return h.name == force_name; });
    if (it == model.forces.end())
      throw context.error("forces", "the name of a harmonic force", "'" + force_name + "'");
    // A force's node is checked where the force is defined.
    equation_of(
        dofs, it->node, it->dof, [&](std::string expected, std::string found, std::string hint) {
          return InputError(it->where, fmt::format("forces[{}].node", it - model.forces.begin()),
                            std::move(expected), std::move(found), std::move(hint));
        });
    load += std::polar(it->amplitude, it->phase) *
            system.unit_load(dofs.find_node(it->node), it->dof).cast<Complex>();
    header.input += (header.input.empty() ? "" : ", ") + force_name;
  }
  header.forced = true;
  return load;
}

}  // namespace

FrfResult run_harmonic(const model::Model& model, const HarmonicSettings& settings,
                       const Context& context, const AdaptiveGridOptions& options) {
  validate_grid(settings, context);
  const fe::LinearSystem& system = context.system();
  const bool has_input = !settings.input_node.empty();
  const bool has_forces = !settings.forces.empty();
  if (has_input == has_forces)
    throw InputError(context.where(), context.key_path(),
                     "either input_node (FRF) or forces (forced response)",
                     has_input ? "both" : "neither");

  FrfResult header;
  const Eigen::VectorXcd load = harmonic_load(model, system, settings, context, header);

  const std::vector<const model::Sensor*> sensors =
      select_sensors(model, settings.sensors, context);
  if (sensors.empty())
    throw context.error("sensors", "at least one sensor", "none", "add [[sensors]] to the model");
  std::vector<int> outputs;
  for (const auto* s : sensors)
    // A sensor's node is checked where the sensor is defined.
    outputs.push_back(equation_of(
        system.dofs, s->node, s->dof,
        [&](std::string expected, std::string found, std::string hint) {
          return InputError(s->where, fmt::format("sensors[{}].node", s - model.sensors.data()),
                            std::move(expected), std::move(found), std::move(hint));
        }));

  FrfResult result = frequency_response(system, load, outputs, settings, context, options);
  result.forced = header.forced;
  result.input = header.input;
  result.input_rotational = header.input_rotational;
  for (std::size_t k = 0; k < sensors.size(); ++k) {
    result.sensors[k].name = sensors[k]->name;
    result.sensors[k].rotational = is_rotation(sensors[k]->dof);
  }
  set_grid_status(result);  // again, now with the sensor names
  result.stability = scan_stability(system, {settings.speed}, settings.f_max);
  if (result.status == Status::NotConverged) {
    int modes_in_band = 0;
    for (const auto& l : result.stability.solves.front().eigenvalues)
      if (std::abs(l) >= 0.9 * settings.f_min && std::abs(l) <= 1.1 * settings.f_max)
        ++modes_in_band;
    diagnose_unresolved_peaks(result, modes_in_band);
  }
  if (!result.stability.all_stable()) {
    const std::string unstable = unstable_message(result.stability);
    result.status = worse(result.status, Status::Unstable);
    result.message = result.message.empty() ? unstable : result.message + "; also " + unstable;
  }
  return result;
}

namespace {

const char* quantity_name(ResponseQuantity q) {
  return q == ResponseQuantity::Receptance ? "receptance"
         : q == ResponseQuantity::Mobility ? "mobility"
                                           : "accelerance";
}

// What the curves are: "receptance for a unit force at n.ux", "forced response (velocity) to f1".
std::string response_description(const FrfResult& result) {
  return result.forced
             ? fmt::format("forced response ({}) to {}",
                           result.quantity == ResponseQuantity::Receptance ? "displacement"
                           : result.quantity == ResponseQuantity::Mobility ? "velocity"
                                                                           : "acceleration",
                           result.input)
             : fmt::format("{} for a unit {} at {}", quantity_name(result.quantity),
                           result.input_rotational ? "moment" : "force", result.input);
}

// Table "frf" and the amplitude and phase plots, one column pair and trace per sensor.
void add_response(const FrfResult& result, const std::string& what, Table& frf, Plot& amp_plot,
                  Plot& phase_plot) {
  const Eigen::MatrixXcd response = result.response();
  std::vector<double> f_hz(static_cast<std::size_t>(result.frequencies.size()));
  for (std::size_t i = 0; i < f_hz.size(); ++i)
    f_hz[i] = result.frequencies[static_cast<Eigen::Index>(i)] * kHzPerRadS;
  frf.name = "frf";
  frf.title = fmt::format("Frequency response: {} at {:.6g} rpm", what, result.speed * kRpmPerRadS);
  frf.add("frequency_hz", "Hz", f_hz);

  amp_plot.name = "amplitude";
  amp_plot.title = fmt::format("Amplitude: {}", what);
  amp_plot.x_label = "frequency [Hz]";
  amp_plot.y_log = true;
  phase_plot.name = "phase";
  phase_plot.title = fmt::format("Phase: {}", what);
  phase_plot.x_label = "frequency [Hz]";
  phase_plot.y_label = "phase [deg]";

  std::vector<std::string> units;
  for (std::size_t s = 0; s < result.sensors.size(); ++s) {
    const std::string unit = result.amplitude_unit(static_cast<int>(s));
    if (std::find(units.begin(), units.end(), unit) == units.end()) units.push_back(unit);
    std::vector<double> amp(f_hz.size()), phase(f_hz.size());
    for (std::size_t i = 0; i < f_hz.size(); ++i) {
      const Complex z = response(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(s));
      amp[i] = std::abs(z);
      phase[i] = std::arg(z) * 180.0 / kPi;
    }
    const std::string& sensor = result.sensors[s].name;
    frf.add(sensor + "_amplitude_" + unit_slug(unit), unit, amp);
    frf.add(sensor + "_phase_deg", "deg", phase);
    Trace a;
    a.name = sensor;
    a.x = f_hz;
    a.y = amp;
    amp_plot.traces.push_back(std::move(a));
    Trace p;
    p.name = sensor;
    p.x = f_hz;
    p.y = std::move(phase);
    phase_plot.traces.push_back(std::move(p));
  }
  std::string unit_list;
  for (const auto& u : units) unit_list += (unit_list.empty() ? "" : ", ") + u;
  amp_plot.y_label = fmt::format("amplitude [{}]", unit_list);
}

// Table "peaks" (core/peak_table.hpp); markers of the peaks on the amplitude plot.
Table peaks_table(const FrfResult& result, Plot& amp_plot) {
  std::vector<PeakRow> rows;
  Trace markers;
  markers.name = "peaks";
  markers.mode = Trace::Mode::Markers;
  const std::string curve =
      result.forced ? std::string(result.quantity == ResponseQuantity::Receptance ? "displacement"
                                  : result.quantity == ResponseQuantity::Mobility ? "velocity"
                                                                                  : "acceleration")
                    : std::string(quantity_name(result.quantity));
  for (const auto& p : result.peaks) {
    const auto s = static_cast<std::size_t>(p.sensor);
    PeakRow row;
    row.sensor = result.sensors[s].name;
    row.curve = curve;
    row.location = p.frequency * kHzPerRadS;
    row.amplitude = p.amplitude;
    row.amplitude_unit = result.amplitude_unit(p.sensor);
    row.half_power_low = p.f1 * kHzPerRadS;
    row.half_power_high = p.f2 * kHzPerRadS;
    row.q_factor = p.q_factor;
    row.points_in_band = p.points_in_band;
    row.resolved = p.resolved;
    rows.push_back(std::move(row));
    markers.x.push_back(p.frequency * kHzPerRadS);
    markers.y.push_back(p.amplitude);
    markers.hover.push_back(fmt::format("{}: {:.6g} Hz, Q = {:.4g}", result.sensors[s].name,
                                        p.frequency * kHzPerRadS, p.q_factor));
  }
  if (!markers.x.empty()) amp_plot.traces.push_back(std::move(markers));
  return peak_table("peaks", "Resonance peaks (half-power bandwidth, Q = f_r / (f2 - f1))",
                    frequency_axis(), rows);
}

std::vector<std::string> harmonic_notes(const FrfResult& result, const fe::LinearSystem& system) {
  std::vector<std::string> notes;
  const GridSummary& g = result.grid;
  notes.push_back(fmt::format(
      "Direct solution of D(w) = K - w^2 M + i w (C + W G) + i K_loss{} at W = {:.6g} rpm with a "
      "sparse complex LU (UMFPACK) per frequency; phase is arg of the response (x = Re(X "
      "e^(iwt))).",
      system.has_modal_damping()
          ? fmt::format(" + i w C_modal ({} modes, applied by the Woodbury identity)",
                        system.modal_coefficients.size())
          : "",
      result.speed * kRpmPerRadS));
  if (g.adaptive) {
    std::string peaks_note =
        g.min_points_in_band > 0
            ? fmt::format(
                  "every resonance with a half-power band in range has >= {} samples in it "
                  "(fewest {}) and its maximum is bracketed by samples at most {:.2g} % of its "
                  "bandwidth from the sampled peak (refined by a parabola through them)",
                  g.required_points_in_band, g.min_points_in_band, 100.0 * g.max_location_error)
            : std::string("no resonance with a complete half-power band in range");
    notes.push_back(
        fmt::format("Adaptive frequency grid: {} initial points refined in {} "
                    "passes to {} points{}; {}.",
                    g.initial_points, g.passes, g.final_points,
                    g.converged ? "" : " (stopped at " + g.limit_hit + ")", peaks_note));
  } else {
    notes.push_back(fmt::format(
        "Fixed frequency grid of {} points (adaptive = false): a resonance narrower than the "
        "grid spacing may be missed or clipped; Q values need >= 5 samples per half-power band "
        "(fewest here: {}).",
        g.final_points, g.min_points_in_band));
  }
  notes.push_back(
      "Q = f_r / (f2 - f1) from the -3 dB crossings interpolated linearly between samples; "
      "damping_ratio = 1/(2Q) holds for an isolated, lightly damped mode. Peaks whose band "
      "runs out of the range or into a higher peak, or that the grid did not resolve, have no Q "
      "(NaN); their half-power points are still listed.");
  if (!result.thread_note.empty()) notes.push_back(result.thread_note);
  return notes;
}

// A dashed vertical line at the natural frequency of every growing mode inside the range.
void mark_unstable_modes(const FrfResult& result, Plot& amp_plot) {
  if (result.stability.solves.empty() || result.frequencies.size() == 0) return;
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const auto& t : amp_plot.traces)
    for (double y : t.y)
      if (y > 0.0 && std::isfinite(y)) {
        lo = std::min(lo, y);
        hi = std::max(hi, y);
      }
  if (!(hi > 0.0)) return;
  for (const auto& m : result.stability.solves.front().unstable) {
    const double f = m.frequency;
    if (f < result.frequencies[0] || f > result.frequencies[result.frequencies.size() - 1])
      continue;
    Trace line;
    line.name = fmt::format("UNSTABLE {}", describe(m));
    line.x = {f * kHzPerRadS, f * kHzPerRadS};
    line.y = {lo, hi};
    line.dash = "dash";
    amp_plot.traces.push_back(std::move(line));
  }
  if (!result.stability.all_stable()) amp_plot.title += " - UNSTABLE (growing modes dashed)";
}

}  // namespace

AnalysisOutput harmonic_output(const model::Model& /*model*/, const HarmonicSettings& /*settings*/,
                               const FrfResult& result, const Context& context) {
  AnalysisOutput out;
  out.name = context.name();
  out.type = "harmonic";
  out.status = result.status;
  out.message = result.message;
  Table frf;
  Plot amp_plot, phase_plot;
  add_response(result, response_description(result), frf, amp_plot, phase_plot);
  Table peaks = peaks_table(result, amp_plot);
  out.tables.push_back(std::move(frf));
  out.tables.push_back(std::move(peaks));
  out.plots.push_back(std::move(amp_plot));
  out.plots.push_back(std::move(phase_plot));
  out.notes = harmonic_notes(result, context.system());
  if (!result.stability.solves.empty()) {
    out.notes.push_back(stability_note(result.stability));
    mark_unstable_modes(result, out.plots.front());
  }
  return out;
}

FrfResult run_harmonic(const model::Model& model, const HarmonicSettings& settings,
                       const Context& context) {
  // The sample budget grows with the requested grid: frequency_count may be anything the schema
  // allows (up to 1e6), with as many samples again for the adaptive refinement.
  AdaptiveGridOptions options;
  options.max_points = std::max(options.max_points, 2 * settings.n_points);
  return run_harmonic(model, settings, context, options);
}

}  // namespace geardyn::analyses
