#pragma once
// Complex banded LU for the dynamic stiffness of shaft lines (issue #19).
//
// A shaft line couples each node only to its neighbours, so after a reverse Cuthill-McKee
// renumbering its matrices are banded with a half-bandwidth of about twice the DOFs per node,
// independent of the number of elements. Gaussian elimination with threshold partial pivoting
// inside the band then costs about n kl (kl + ku) complex multiply-adds at most (n kl ku when
// the diagonal pivots hold, as on a beam chain), linear in n; the storage is allocated once
// per pattern, so a sweep over frequencies allocates nothing.
//
//   P_r A S P_c = L U     S an optional column scaling (set_column_scale), P_c the symmetric
//                         RCM permutation, P_r the row interchanges, chosen on the rows
//                         weighted by R = diag(1 / sum_j |a_ij s_j|_1) (implicit equilibration)
//
// Elimination follows LAPACK's xGBTF2 (band columns with kl extra rows for the fill of the row
// interchanges): E. Anderson et al., LAPACK Users' Guide, 3rd ed., SIAM 1999, section 5.1.4;
// here in a window of kl + ku + 1 columns, with U and L written out row by row and column by
// column. Ordering: E. Cuthill and J. McKee, "Reducing the bandwidth of sparse symmetric
// matrices", Proc. 24th ACM National Conference, 1969, reversed as in A. George and J. W. H.
// Liu, Computer Solution of Large Sparse Positive Definite Systems, Prentice-Hall 1981,
// chapter 4 (start node: a pseudo-peripheral node of each component).
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

/// LU with threshold partial pivoting of a complex square matrix stored in a fixed
/// compressed-column pattern, in band form after an RCM renumbering. analyze() once per
/// pattern, factorize() per set of values (no allocation), solve() with a caller's workspace
/// (const and thread-safe: several threads may solve with one factor).
///
/// Pivoting is scaled: the candidates of column j are weighed by r_i (|Re a_ij| + |Im a_ij|),
/// r_i = 1 / sum_k (|Re a_ik| + |Im a_ik|) (of A S when set_column_scale was called), the row
/// equilibration of LAPACK's xGBEQU with its CABS1 modulus applied implicitly (the factor is
/// of A S itself), as in G. E. Forsythe and C. B. Moler, Computer Solution of Linear Algebraic
/// Systems, 1967, ch. 11. The diagonal stays the pivot while its weight is at least 0.1 of the
/// largest (threshold pivoting, I. S. Duff, A. M. Erisman and J. K. Reid, Direct Methods for
/// Sparse Matrices, 1986, section 5.4), so that interchanges do not fill the band.
///
/// The matrix may also be given as a combination A = sum_t w_t A_t of real terms with the
/// analysed pattern (a dynamic stiffness K - w^2 M + i w C + ...): set_terms() once, then
/// factorize_terms(w) assembles each column straight into the elimination, so the complex
/// values are never stored. Terms that fill much of the band are kept as dense band columns
/// (assembled by vector operations), the others as lists of their non-zero entries.
///
/// Memory and work (issue #19): the elimination runs in a window of the next kl + ku + 1
/// columns, real and imaginary parts apart, which stays in the first-level cache; each finished
/// row of U (up to its last non-zero) and column of L (kl multipliers) is written once to its
/// own array, and the back substitution reads U's rows contiguously. The kernels are compiled
/// for AVX2 too and chosen at load time (the same results: no fused multiply-adds).
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
  /// is then unusable). pivot_ratio() is min / max of r_i |u_ii| over the pivots (the ratio of
  /// the row-equilibrated factor).
  Status factorize(const Complex* values);
  /// The same, and also the forward substitution L y = P b of `columns` right-hand sides b
  /// (`rhs`: columns x size() entries, column by column, original numbering) during the
  /// elimination, while each column of L is in cache; solve_prepared() finishes them. Storage
  /// for them is allocated when `columns` first grows, not per factorisation.
  Status factorize(const Complex* values, const Complex* rhs, int columns);

  /// The real terms A_t of A = sum_t w_t A_t: terms[t] holds A_t's values in the order of the
  /// analysed pattern (nullptr: A_t = 0). Call again when a term changes; the number of terms
  /// may change too (at most 255).
  void set_terms(const std::vector<const double*>& terms);
  /// Factors sum_t weights[t] A_t (weights: one per term of set_terms), with `columns`
  /// right-hand sides prepared as factorize(values, rhs, columns) does. Each entry is summed
  /// over the dense terms in their order, then over the sparse ones.
  Status factorize_terms(const Complex* weights, const Complex* rhs = nullptr, int columns = 0);

  /// Column scaling S (one positive entry per unknown, in the numbering of the analysed
  /// pattern; nullptr: none): the factor is then of A S and x = S (A S)^{-1} b. A symmetric
  /// scaling such as S = diag(|a_ii|)^(-1/2) balances unknowns of different units (the
  /// displacements and rotations of a beam, whose stiffness terms differ by the element length
  /// squared), so that the scaled pivot search keeps to the diagonal and the band does not
  /// fill. Kept until the next analyze().
  void set_column_scale(const double* scale);

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
  /// Entries stored by a factorisation (U, L and the pivots: n (2 kl + ku + 1)).
  double storage_entries() const;
  /// Row sums sum_k (|Re a_ik| + |Im a_ik|) of the last factorised matrix, row i in the
  /// analysed numbering (within sqrt 2 of the sums of moduli).
  const double* row_sums() const { return row_sum_.data(); }
  /// Entries right of the diagonal in the widest row of the last U: ku when no row was
  /// interchanged, up to kl + ku (the fill of the interchanges).
  int fill_width() const { return upper_width_; }
  double pivot_ratio() const { return pivot_ratio_; }
  /// min r_i |u_ii| and max r_i |u_ii| of the last factor, to combine the pivot ratios of
  /// several independent blocks.
  double smallest_pivot() const { return smallest_pivot_; }
  double largest_pivot() const { return largest_pivot_; }

 private:
  /// Offset of a(row, col) in its window column (real and imaginary parts apart).
  std::size_t slot(int row, int col) const {
    return static_cast<std::size_t>(col & window_mask_) * stride_ +
           static_cast<std::size_t>(kv_ + row - col);
  }
  Status run(const Complex* rhs, int columns);
  void forward_step(int j, double* yr, double* yi) const;
  void back_substitute(double* zr, double* zi, Complex* x) const;
  void eliminate();
  void assemble_column(int c);
  template <int D>
  bool assemble_dense(int c, bool fused);
  /// Where the elimination stands: the last column a pivot row reached, the columns assembled
  /// and the rows weighted so far.
  struct Progress {
    int last_column = 0, assembled = 0, weighted = 0;
  };
  template <int KM>
  void step(int j, int km, Progress& at);
  template <int KL>
  void eliminate_all();
  template <int KM>
  void eliminate_column(int j, int km_runtime, int& last_column);

  int n_ = 0, kl_ = 0, ku_ = 0, kv_ = 0;
  std::size_t ld_ = 1;      ///< band rows of a column (2 kl + ku + 1)
  std::size_t stride_ = 1;  ///< a window column: ld_ rows and padding for whole vector lanes
  int window_mask_ = 0;
  std::vector<int> perm_;  ///< perm_[new] = old
  /// A pattern entry: its index in the values and its place in its column of the window.
  struct Entry {
    int source, offset;
  };
  std::vector<int> column_start_;  ///< entries_ of renumbered column c: [start c, c+1)
  std::vector<Entry> entries_;     ///< by renumbered column
  /// One term of set_terms: empty, dense (in dense_value_) or sparse (its non-zero entries by
  /// renumbered column: [start c, start c+1) of offset, the place in the window column, and
  /// value).
  struct Term {
    enum class Kind { Empty, Dense, Sparse } kind = Kind::Empty;
    std::vector<int> start, offset;
    std::vector<double> value;
  };
  std::vector<Term> terms_;
  /// The dense terms, column by column: dense term d of column c holds rows c - ku .. c + kl
  /// (zero-padded to dense_width_) at [(c dense_count_ + d) dense_width_, ..).
  std::vector<double> dense_value_;
  int dense_count_ = 0;
  std::vector<double> dense_weight_re_, dense_weight_im_;  ///< their weights (factorize_terms)
  std::vector<char> sparse_column_;  ///< column c has an entry of a sparse term
  bool terms_set_ = false;
  const Complex* values_ = nullptr;   ///< the values being factorised (factorize)
  const Complex* weights_ = nullptr;  ///< the terms' weights (factorize_terms)
  /// Forward-substituted right-hand sides: column c's real parts at [2 c n, 2 c n + n), its
  /// imaginary parts next.
  std::vector<double> prepared_;
  int prepared_columns_ = 0;
  std::vector<double> row_sum_;         ///< sum_k |a_ik|_1 (new numbering; zero padding)
  std::vector<double> scaled_sum_;      ///< the same of A S (the column-scaled matrix)
  std::vector<double> column_scale_;    ///< S (new numbering)
  std::vector<double> row_weight_;      ///< r of the row now in each position (pivot search)
  std::vector<int> pivot_;              ///< row interchanged with row j at step j
  std::vector<Complex> inverse_pivot_;  ///< 1 / u_jj
  /// window_mask_ + 1 columns of stride_ entries, real and imaginary parts apart (the update
  /// of a column is then a plain vector operation).
  std::vector<double> window_re_, window_im_;
  /// The rows of U right of the diagonal, packed: row j, u(j, j + 1 .. j + w_j) with w_j its
  /// last non-zero (ku without interchanges), zero-padded to whole groups of four, real parts
  /// then imaginary parts, at [upper_start_[j], upper_start_[j + 1]).
  std::vector<double> upper_;
  std::vector<std::size_t> upper_start_;
  /// Column j of L below the diagonal, l(j + 1 .. j + kl, j), at [j lower_stride_, ..), the
  /// same way.
  std::vector<double> lower_re_, lower_im_;
  std::size_t upper_stride_ = 0, lower_stride_ = 0;  ///< the most a row of U / column of L takes
  int upper_width_ = 0;          ///< the most entries right of the diagonal in a row of U
  std::size_t dense_width_ = 0;  ///< entries per column of a dense term (kv + 1, padded)
  double pivot_ratio_ = 0.0, smallest_pivot_ = 0.0, largest_pivot_ = 0.0;
};

}  // namespace geardyn::linalg
