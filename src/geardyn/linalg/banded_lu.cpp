#include "geardyn/linalg/banded_lu.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>

namespace geardyn::linalg {
namespace {

using Complex = std::complex<double>;

// |z| without std::abs's overflow-safe hypot, which dominated the profile of a sweep; matrix
// entries of a structural model are far from 1e154, where the square would overflow.
double magnitude(Complex z) { return std::sqrt(z.real() * z.real() + z.imag() * z.imag()); }

// 1 / z by the conjugate (no libgcc __divdc3 call); z != 0.
Complex reciprocal(Complex z) {
  const double d = z.real() * z.real() + z.imag() * z.imag();
  return {z.real() / d, -z.imag() / d};
}

// Symmetrised adjacency (no self loops) of a compressed-column pattern, in CSR form.
struct Graph {
  std::vector<int> start, adjacent;
  int degree(int v) const { return start[static_cast<std::size_t>(v) + 1] - start[v]; }
};

Graph symmetric_graph(int n, const int* outer, const int* inner) {
  const auto un = static_cast<std::size_t>(n);
  std::vector<std::vector<int>> lists(un);
  for (int j = 0; j < n; ++j)
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int i = inner[k];
      if (i == j) continue;
      lists[static_cast<std::size_t>(i)].push_back(j);
      lists[static_cast<std::size_t>(j)].push_back(i);
    }
  Graph g;
  g.start.assign(un + 1, 0);
  for (std::size_t v = 0; v < un; ++v) {
    std::sort(lists[v].begin(), lists[v].end());
    lists[v].erase(std::unique(lists[v].begin(), lists[v].end()), lists[v].end());
    g.start[v + 1] = g.start[v] + static_cast<int>(lists[v].size());
    g.adjacent.insert(g.adjacent.end(), lists[v].begin(), lists[v].end());
  }
  return g;
}

// Breadth-first search from `root` over unnumbered vertices (mark[v] != done); appends the
// visited vertices to `order` level by level, neighbours by increasing degree (Cuthill-McKee).
// Returns the number of levels; `last_level_begin` receives where the last level starts.
int cuthill_mckee_levels(const Graph& g, int root, int done, std::vector<int>& mark,
                         std::vector<int>& order, std::size_t& last_level_begin) {
  const std::size_t begin = order.size();
  order.push_back(root);
  mark[static_cast<std::size_t>(root)] = done;
  std::size_t level_begin = begin, level_end = order.size();
  int levels = 0;
  std::vector<int> fresh;
  while (level_begin < level_end) {
    ++levels;
    last_level_begin = level_begin;
    for (std::size_t k = level_begin; k < level_end; ++k) {
      const int v = order[k];
      fresh.clear();
      for (int a = g.start[static_cast<std::size_t>(v)];
           a < g.start[static_cast<std::size_t>(v) + 1]; ++a) {
        const int w = g.adjacent[static_cast<std::size_t>(a)];
        if (mark[static_cast<std::size_t>(w)] == done) continue;
        mark[static_cast<std::size_t>(w)] = done;
        fresh.push_back(w);
      }
      std::stable_sort(fresh.begin(), fresh.end(),
                       [&](int x, int y) { return g.degree(x) < g.degree(y); });
      order.insert(order.end(), fresh.begin(), fresh.end());
    }
    level_begin = level_end;
    level_end = order.size();
  }
  return levels;
}

// y[0..count) -= a[0..count) * s in plain real arithmetic (std::complex's operator* checks for
// NaN results and calls libgcc on them, which keeps the loop from vectorising).
void multiply_subtract(const Complex* a, Complex s, Complex* y, int count) {
  const auto* ar = reinterpret_cast<const double*>(a);
  auto* yr = reinterpret_cast<double*>(y);
  const double sr = s.real(), si = s.imag();
  for (int i = 0; i < count; ++i) {
    yr[2 * i] -= ar[2 * i] * sr - ar[2 * i + 1] * si;
    yr[2 * i + 1] -= ar[2 * i] * si + ar[2 * i + 1] * sr;
  }
}

}  // namespace

std::vector<int> reverse_cuthill_mckee(int n, const int* outer, const int* inner) {
  const Graph g = symmetric_graph(n, outer, inner);
  const auto un = static_cast<std::size_t>(n);
  std::vector<int> order;
  order.reserve(un);
  std::vector<int> numbered(un, 0), scratch(un, 0);
  std::vector<int> by_degree(un);
  std::iota(by_degree.begin(), by_degree.end(), 0);
  std::stable_sort(by_degree.begin(), by_degree.end(),
                   [&](int x, int y) { return g.degree(x) < g.degree(y); });
  int search = 0;  // distinct mark per trial search, so `scratch` is never cleared
  for (int seed : by_degree) {
    if (numbered[static_cast<std::size_t>(seed)] != 0) continue;
    // Pseudo-peripheral start (George and Liu's algorithm): move to a vertex of least degree in
    // the last level while the number of levels grows.
    int root = seed, levels = 0;
    for (;;) {
      // The search stays inside this component, none of which is numbered yet.
      std::vector<int> trial;
      std::size_t last = 0;
      const int depth = cuthill_mckee_levels(g, root, ++search, scratch, trial, last);
      if (depth <= levels) break;
      levels = depth;
      root = *std::min_element(trial.begin() + static_cast<std::ptrdiff_t>(last), trial.end(),
                               [&](int x, int y) { return g.degree(x) < g.degree(y); });
    }
    std::size_t last = 0;
    cuthill_mckee_levels(g, root, 1, numbered, order, last);
  }
  std::reverse(order.begin(), order.end());
  return order;
}

std::pair<int, int> bandwidths(int n, const int* outer, const int* inner,
                               const std::vector<int>& perm) {
  std::vector<int> new_index(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    new_index[static_cast<std::size_t>(perm[static_cast<std::size_t>(k)])] = k;
  int kl = 0, ku = 0;
  for (int j = 0; j < n; ++j)
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int d =
          new_index[static_cast<std::size_t>(inner[k])] - new_index[static_cast<std::size_t>(j)];
      kl = std::max(kl, d);
      ku = std::max(ku, -d);
    }
  return {kl, ku};
}

void BandedLU::analyze(int n, const int* outer, const int* inner, Ordering ordering) {
  if (n <= 0) throw std::invalid_argument("BandedLU::analyze: empty matrix");
  n_ = n;
  if (ordering == Ordering::Given) {
    perm_.resize(static_cast<std::size_t>(n));
    std::iota(perm_.begin(), perm_.end(), 0);
  } else {
    perm_ = reverse_cuthill_mckee(n, outer, inner);
  }
  std::tie(kl_, ku_) = bandwidths(n, outer, inner, perm_);
  kv_ = kl_ + ku_;
  ld_ = static_cast<std::size_t>(2 * kl_ + ku_ + 1);
  const auto un = static_cast<std::size_t>(n);
  std::vector<int> new_index(un);
  for (std::size_t k = 0; k < un; ++k)
    new_index[static_cast<std::size_t>(perm_[k])] = static_cast<int>(k);
  const auto nnz = static_cast<std::size_t>(outer[n]);
  new_row_.resize(nnz);
  // Entries grouped by renumbered column (counting sort), so that the elimination assembles
  // each column just before it first touches it, while it is in cache.
  column_start_.assign(un + 1, 0);
  for (int j = 0; j < n; ++j)
    column_start_[static_cast<std::size_t>(new_index[static_cast<std::size_t>(j)]) + 1] +=
        outer[j + 1] - outer[j];
  std::partial_sum(column_start_.begin(), column_start_.end(), column_start_.begin());
  entries_.resize(nnz);
  std::vector<int> next(column_start_.begin(), column_start_.end() - 1);
  for (int j = 0; j < n; ++j) {
    const int c = new_index[static_cast<std::size_t>(j)];
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int r = new_index[static_cast<std::size_t>(inner[k])];
      new_row_[static_cast<std::size_t>(k)] = r;
      entries_[static_cast<std::size_t>(next[static_cast<std::size_t>(c)]++)] = {k, r, kv_ + r - c};
    }
  }
  row_scale_.assign(un, 0.0);
  pivot_.assign(un, 0);
  inverse_pivot_.assign(un, Complex(0.0));
  band_.assign(un * ld_, Complex(0.0));
  pivot_ratio_ = 0.0;
}

double BandedLU::factor_operations() const { return static_cast<double>(n_) * kl_ * (kl_ + ku_); }

double BandedLU::storage_entries() const {
  return static_cast<double>(n_) * static_cast<double>(ld_);
}

// Step j of the elimination (LAPACK xGBTF2): pivot search in column j, row interchange over
// the columns it reaches, multipliers, rank-1 update of the band. `last_column`: the last
// column touched by a pivot row so far. KM > 0: the rows below the diagonal are KM (= kl, a
// compile-time count, so the short loops unroll); KM = 0: `km` of them (the last kl steps).
template <int KM>
void BandedLU::eliminate_column(int j, int km_runtime, int& last_column) {
  const int km = KM > 0 ? KM : km_runtime;
  Complex* column = &at(j, j);
  int p = 0;
  double best = -1.0;
  for (int i = 0; i <= km; ++i) {
    const double a = std::abs(column[i].real()) + std::abs(column[i].imag());
    if (a > best) {
      best = a;
      p = i;
    }
  }
  pivot_[static_cast<std::size_t>(j)] = j + p;
  if (best == 0.0) {
    inverse_pivot_[static_cast<std::size_t>(j)] = Complex(0.0);
    smallest_pivot_ = 0.0;
    return;
  }
  last_column = std::max(last_column, std::min(j + ku_ + p, n_ - 1));
  if (p != 0)
    for (int c = j; c <= last_column; ++c) std::swap(at(j, c), at(j + p, c));
  // u_jj is final here: later steps interchange and update rows below j only.
  const double d = magnitude(column[0]);
  smallest_pivot_ = std::min(smallest_pivot_, d);
  largest_pivot_ = std::max(largest_pivot_, d);
  const Complex inverse = reciprocal(column[0]);
  inverse_pivot_[static_cast<std::size_t>(j)] = inverse;
  double* l = reinterpret_cast<double*>(column);
  const double vr = inverse.real(), vi = inverse.imag();
  for (int i = 1; i <= km; ++i) {
    const double lr = l[2 * i], li = l[2 * i + 1];
    l[2 * i] = lr * vr - li * vi;
    l[2 * i + 1] = lr * vi + li * vr;
  }
  for (int c = j + 1; c <= last_column; ++c) {
    double* u = reinterpret_cast<double*>(&at(j, c));  // u[0..1] = a(j, c), then rows below
    const double ur = u[0], ui = u[1];
    if (ur == 0.0 && ui == 0.0) continue;
    for (int i = 1; i <= km; ++i) {
      const double lr = l[2 * i], li = l[2 * i + 1];
      u[2 * i] -= lr * ur - li * ui;
      u[2 * i + 1] -= lr * ui + li * ur;
    }
  }
}

// All steps: those with kl rows below the diagonal by the unrolled kernel when KL = kl_.
// Column c of the row-scaled matrix into the band storage (its other entries zero).
void BandedLU::assemble_column(int c) {
  Complex* column = band_.data() + static_cast<std::size_t>(c) * ld_;
  std::fill(column, column + ld_, Complex(0.0));
  for (int e = column_start_[static_cast<std::size_t>(c)];
       e < column_start_[static_cast<std::size_t>(c) + 1]; ++e) {
    const Entry& entry = entries_[static_cast<std::size_t>(e)];
    column[entry.offset] += row_scale_[static_cast<std::size_t>(entry.row)] * values_[entry.source];
  }
}

// All steps: those with kl rows below the diagonal by the unrolled kernel when KL = kl_. Step j
// touches columns j .. j + kl + ku at most, which are assembled just before.
template <int KL>
void BandedLU::eliminate_all() {
  int last_column = 0, assembled = 0;
  const auto un = static_cast<std::size_t>(n_);
  const auto step = [&](int j, auto kernel) {
    for (const int need = std::min(n_ - 1, j + kv_); assembled <= need; ++assembled)
      assemble_column(assembled);
    kernel(j);
    // Column j of L is final: the forward substitution of the prepared loads takes it now,
    // while it is in cache (the same operations in the same order as solve()).
    for (std::size_t c = 0; c < static_cast<std::size_t>(prepared_columns_); ++c)
      forward_step(j, prepared_.data() + c * un);
  };
  const int interior = KL > 0 ? std::max(0, n_ - KL) : 0;
  for (int j = 0; j < interior; ++j)
    step(j, [&](int i) { eliminate_column<KL>(i, KL, last_column); });
  for (int j = interior; j < n_; ++j)
    step(j, [&](int i) { eliminate_column<0>(i, std::min(kl_, n_ - 1 - i), last_column); });
}

void BandedLU::eliminate() {
  // Unrolled kernels for the narrow bands of shaft lines (kl up to 16); generic beyond.
  switch (kl_) {
    case 1:
      return eliminate_all<1>();
    case 2:
      return eliminate_all<2>();
    case 3:
      return eliminate_all<3>();
    case 4:
      return eliminate_all<4>();
    case 5:
      return eliminate_all<5>();
    case 6:
      return eliminate_all<6>();
    case 7:
      return eliminate_all<7>();
    case 8:
      return eliminate_all<8>();
    case 9:
      return eliminate_all<9>();
    case 10:
      return eliminate_all<10>();
    case 11:
      return eliminate_all<11>();
    case 12:
      return eliminate_all<12>();
    case 13:
      return eliminate_all<13>();
    case 14:
      return eliminate_all<14>();
    case 15:
      return eliminate_all<15>();
    case 16:
      return eliminate_all<16>();
    default:
      return eliminate_all<0>();
  }
}

Status BandedLU::factorize(const Complex* values) {
  if (n_ == 0) throw std::logic_error("BandedLU::factorize before analyze");
  std::fill(row_scale_.begin(), row_scale_.end(), 0.0);
  for (std::size_t k = 0; k < new_row_.size(); ++k)
    row_scale_[static_cast<std::size_t>(new_row_[k])] += magnitude(values[k]);
  return factorize_summed(values, nullptr, 0);
}

Status BandedLU::factorize(const Complex* values, const double* row_sums) {
  return factorize(values, row_sums, nullptr, 0);
}

Status BandedLU::factorize(const Complex* values, const double* row_sums, const Complex* rhs,
                           int columns) {
  if (n_ == 0) throw std::logic_error("BandedLU::factorize before analyze");
  for (std::size_t k = 0; k < row_scale_.size(); ++k)
    row_scale_[k] = row_sums[static_cast<std::size_t>(perm_[k])];
  return factorize_summed(values, rhs, columns);
}

// row_scale_ holds the absolute row sums (new numbering) on entry. `rhs` (columns of size()
// entries, analysed numbering) are forward-substituted into prepared_ during the elimination.
Status BandedLU::factorize_summed(const Complex* values, const Complex* rhs, int columns) {
  for (double& s : row_scale_) s = s > 0.0 ? 1.0 / s : 1.0;
  values_ = values;
  prepared_columns_ = columns;
  const auto un = static_cast<std::size_t>(n_);
  if (prepared_.size() < un * static_cast<std::size_t>(columns))
    prepared_.resize(un * static_cast<std::size_t>(columns));
  for (std::size_t c = 0; c < static_cast<std::size_t>(columns); ++c)
    for (std::size_t k = 0; k < un; ++k)
      prepared_[c * un + k] = row_scale_[k] * rhs[c * un + static_cast<std::size_t>(perm_[k])];

  smallest_pivot_ = std::numeric_limits<double>::infinity();
  largest_pivot_ = 0.0;
  eliminate();
  values_ = nullptr;
  pivot_ratio_ = largest_pivot_ > 0.0 ? smallest_pivot_ / largest_pivot_ : 0.0;
  return smallest_pivot_ > 0.0 ? Status::Ok : Status::Singular;
}

// One step of L y = P_r c: the interchange and the multipliers of elimination step j.
void BandedLU::forward_step(int j, Complex* y) const {
  const int p = pivot_[static_cast<std::size_t>(j)];
  if (p != j) std::swap(y[j], y[p]);
  const Complex t = y[j];
  if (t == Complex(0.0)) return;
  const Complex* column =
      band_.data() + static_cast<std::size_t>(kv_) + static_cast<std::size_t>(j) * ld_;  // a(j, j)
  multiply_subtract(column + 1, t, y + j + 1, std::min(kl_, n_ - 1 - j));
}

// U z = y (upper bandwidth kl + ku after the interchanges), then x = P_c z.
void BandedLU::back_substitute(Complex* work, Complex* x) const {
  for (int j = n_ - 1; j >= 0; --j) {
    if (work[j] == Complex(0.0)) continue;
    work[j] *= inverse_pivot_[static_cast<std::size_t>(j)];
    const Complex z = work[j];
    const int top = std::max(0, j - kv_);
    const Complex* column = band_.data() + static_cast<std::size_t>(kv_ + top - j) +
                            static_cast<std::size_t>(j) * ld_;  // a(top, j)
    multiply_subtract(column, z, work + top, j - top);
  }
  for (int k = 0; k < n_; ++k) x[perm_[static_cast<std::size_t>(k)]] = work[k];
}

void BandedLU::solve(const Complex* b, Complex* x, Complex* work) const {
  for (int k = 0; k < n_; ++k) {
    const auto old = static_cast<std::size_t>(perm_[static_cast<std::size_t>(k)]);
    work[k] = row_scale_[static_cast<std::size_t>(k)] * b[old];
  }
  // L y = P_r c: interchanges and multipliers in the order they were made.
  for (int j = 0; j < n_; ++j) forward_step(j, work);
  back_substitute(work, x);
}

void BandedLU::solve_prepared(int column, Complex* x, Complex* work) const {
  if (column < 0 || column >= prepared_columns_)
    throw std::logic_error("BandedLU::solve_prepared: no such prepared right-hand side");
  const Complex* y =
      prepared_.data() + static_cast<std::size_t>(column) * static_cast<std::size_t>(n_);
  std::copy(y, y + n_, work);
  back_substitute(work, x);
}

}  // namespace geardyn::linalg
