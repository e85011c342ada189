#pragma once
// Complex banded LU for the dynamic stiffness of shaft lines (issue #19).
//
// A shaft line couples each node only to its neighbours, so after a reverse Cuthill-McKee
// renumbering its matrices are banded with a half-bandwidth of about twice the DOFs per node,
// independent of the number of elements. Gaussian elimination with partial pivoting inside the
// band then costs about n kl (kl + ku) complex multiply-adds and n (2 kl + ku + 1) stored
// entries, linear in n; the storage is allocated once per pattern, so a sweep over frequencies
// allocates nothing.
//
//   P_r (R A) P_c = L U     R = diag(1 / sum_j |a_ij|) (row scaling, as UMFPACK's default),
//                           P_c the symmetric RCM permutation, P_r the row interchanges
//
// Storage and elimination follow LAPACK's xGBTF2 / xGBTRS layout (band stored by columns with
// kl extra rows for the fill of the row interchanges): E. Anderson et al., LAPACK Users' Guide,
// 3rd ed., SIAM 1999, section 5.1.4. Ordering: E. Cuthill and J. McKee, "Reducing the bandwidth
// of sparse symmetric matrices", Proc. 24th ACM National Conference, 1969, reversed as in
// A. George and J. W. H. Liu, Computer Solution of Large Sparse Positive Definite Systems,
// Prentice-Hall 1981, chapter 4 (start node: a pseudo-peripheral node of each component).
#include <complex>
#include <utility>
#include <vector>

#include "geardyn/core/status.hpp"

namespace geardyn::linalg {

/// Reverse Cuthill-McKee ordering of the symmetrised pattern of an n x n matrix in compressed
/// column form (outer: n + 1 column starts, inner: row indices). Returns perm with
/// perm[new] = old; components are numbered one after the other.
std::vector<int> reverse_cuthill_mckee(int n, const int* outer, const int* inner);

/// Half-bandwidths (lower, upper) of the pattern renumbered by `perm` (perm[new] = old).
std::pair<int, int> bandwidths(int n, const int* outer, const int* inner,
                               const std::vector<int>& perm);

/// LU with partial pivoting of a complex square matrix stored in a fixed compressed-column
/// pattern, in band form after an RCM renumbering. analyze() once per pattern, factorize() per
/// set of values (no allocation), solve() with a caller's workspace (const and thread-safe:
/// several threads may solve with one factor).
class BandedLU {
 public:
  using Complex = std::complex<double>;

  /// How analyze() numbers the unknowns.
  enum class Ordering {
    ReverseCuthillMcKee,  ///< its own RCM ordering
    Given                 ///< as given (the caller has ordered the pattern, e.g. by RCM)
  };

  /// Orders the pattern (n x n, compressed columns with sorted rows) and sizes the storage.
  void analyze(int n, const int* outer, const int* inner,
               Ordering ordering = Ordering::ReverseCuthillMcKee);

  /// Factors the matrix whose values are `values`, in the order of the analysed pattern.
  /// Returns Status::Ok, or Status::Singular when a pivot column is exactly zero (the factor
  /// is then unusable). pivot_ratio() is min |u_ii| / max |u_ii| of the row-scaled matrix.
  Status factorize(const Complex* values);
  /// The same with the absolute row sums sum_j |a_ij| given by the caller (row i in the
  /// analysed numbering, size() entries), who has them from assembling the values: the row
  /// scaling then costs no second pass over the entries. Results are bit-identical to
  /// factorize(values) when row_sums holds exactly those sums.
  Status factorize(const Complex* values, const double* row_sums);

  /// The same, and also the forward substitution L y = P_r R P_c^T b of `columns` right-hand
  /// sides b (`rhs`: columns x size() entries, column by column, analysed numbering) during the
  /// elimination, while each column of L is in cache; solve_prepared() finishes them. Storage
  /// for them is allocated when `columns` first grows, not per factorisation.
  Status factorize(const Complex* values, const double* row_sums, const Complex* rhs, int columns);

  /// x = A^{-1} b (b, x of length size(); they may be the same array). `work`: size() entries.
  void solve(const Complex* b, Complex* x, Complex* work) const;
  /// x = A^{-1} b for the right-hand side `column` given to the last factorize (bit-identical
  /// to solve() with that b; only the back substitution is left). `work`: size() entries.
  void solve_prepared(int column, Complex* x, Complex* work) const;

  int size() const { return n_; }
  int lower_bandwidth() const { return kl_; }
  int upper_bandwidth() const { return ku_; }
  /// Complex multiply-adds of one factorisation (bound from the bandwidths: n kl (kl + ku)).
  double factor_operations() const;
  /// Entries of the band storage (n (2 kl + ku + 1)).
  double storage_entries() const;
  double pivot_ratio() const { return pivot_ratio_; }
  /// min |u_ii| and max |u_ii| of the last factor (row-scaled matrix), to combine the pivot
  /// ratios of several independent blocks.
  double smallest_pivot() const { return smallest_pivot_; }
  double largest_pivot() const { return largest_pivot_; }

 private:
  Complex& at(int row, int col) {
    return band_[static_cast<std::size_t>(kv_ + row - col) + static_cast<std::size_t>(col) * ld_];
  }
  Status factorize_summed(const Complex* values, const Complex* rhs, int columns);
  void forward_step(int j, Complex* y) const;
  void back_substitute(Complex* work, Complex* x) const;
  void eliminate();
  void assemble_column(int c);
  template <int KL>
  void eliminate_all();
  template <int KM>
  void eliminate_column(int j, int km_runtime, int& last_column);

  int n_ = 0, kl_ = 0, ku_ = 0, kv_ = 0;
  std::size_t ld_ = 1;
  std::vector<int> perm_;  ///< perm_[new] = old
  /// A pattern entry: its index in the values, its renumbered row, its place in its column.
  struct Entry {
    int source, row, offset;
  };
  std::vector<int> new_row_;         ///< row of each pattern entry, renumbered
  std::vector<int> column_start_;    ///< entries_ of renumbered column c: [start c, c+1)
  std::vector<Entry> entries_;       ///< by renumbered column
  const Complex* values_ = nullptr;  ///< the values being factorised
  std::vector<Complex> prepared_;    ///< forward-substituted right-hand sides
  int prepared_columns_ = 0;
  std::vector<double> row_scale_;       ///< in the new numbering
  std::vector<int> pivot_;              ///< row interchanged with row j at step j
  std::vector<Complex> inverse_pivot_;  ///< 1 / u_jj
  std::vector<Complex> band_;
  double pivot_ratio_ = 0.0, smallest_pivot_ = 0.0, largest_pivot_ = 0.0;
};

}  // namespace geardyn::linalg
