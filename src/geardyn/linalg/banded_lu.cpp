#include "geardyn/linalg/banded_lu.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>

// The kernels are compiled twice, for x86-64 with AVX2 and for the baseline, and the loader
// picks one by the processor (GCC's target_clones; elsewhere one version).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define GEARDYN_KERNEL_CLONES [[gnu::target_clones("avx2", "default")]]
#else
#define GEARDYN_KERNEL_CLONES
#endif

namespace geardyn::linalg {
namespace {

using Complex = std::complex<double>;

// Threshold partial pivoting (I. S. Duff, A. M. Erisman and J. K. Reid, Direct Methods for
// Sparse Matrices, Oxford 1986, section 5.4): the diagonal is kept as the pivot when its
// (scaled) modulus is at least this fraction of the largest in its column, which bounds the
// growth of each step by 1 + 1 / 0.1; 0.1 is also UMFPACK's default pivot tolerance. The
// Schur complements of a beam chain put the next node's rotation above the diagonal's by a
// factor of about 2, so that plain partial pivoting interchanges half of the rows and fills
// the band to kl + ku.
constexpr double kPivotThreshold = 0.1;

// The vector kernels run over whole groups of kLanes rows; the stored factors, the dense terms
// and the window columns are padded with zeros to such groups.
constexpr int kLanes = 4;

inline std::size_t whole_lanes(int k) {
  return static_cast<std::size_t>((k + kLanes - 1) / kLanes * kLanes);
}

// |z| without std::abs's overflow-safe hypot, which dominated the profile of a sweep; matrix
// entries of a structural model are far from 1e154, where the square would overflow.
[[gnu::always_inline]] inline double magnitude(Complex z) {
  return std::sqrt(z.real() * z.real() + z.imag() * z.imag());
}

// 1 / z by the conjugate (no libgcc __divdc3 call); z != 0.
[[gnu::always_inline]] inline Complex reciprocal(Complex z) {
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

// Four doubles (GCC/Clang vector extension): one AVX register in the AVX2 clones of the
// kernels, two SSE2 registers otherwise, two NEON registers on ARM. GCC 12 vectorises the
// kernels' short loops only in part by itself. Without FMA the clones round alike, so the
// results do not depend on the processor.
using Quad = double __attribute__((vector_size(32)));
// The helpers taking and returning a Quad are always inlined (file-local): their calling
// convention, which GCC warns differs with and without AVX, is never used.
#pragma GCC diagnostic ignored "-Wpsabi"

[[gnu::always_inline]] inline Quad load(const double* p) {
  Quad v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

[[gnu::always_inline]] inline void store(double* p, Quad v) { std::memcpy(p, &v, sizeof v); }

[[gnu::always_inline]] inline Quad splat(double a) { return Quad{a, a, a, a}; }

// Lanes of a column's entries r + i i: their moduli |r| + |i| into the row sums of A (`sum`)
// and, times the column's scale s, of A S (`scaled`).
[[gnu::always_inline]] inline void add_moduli(Quad r, Quad i, Quad s, double* sum, double* scaled) {
  const Quad m = (r < 0.0 ? -r : r) + (i < 0.0 ? -i : i);
  store(sum, load(sum) + m);
  store(scaled, load(scaled) + s * m);
}

// x -= l u on `count` rows (wide bands and the last kl steps), real and imaginary parts apart.
[[gnu::always_inline]] inline void update_rows(double* xr, double* xi, const double* lr,
                                               const double* li, double ur, double ui, int count) {
  for (int i = 0; i < count; ++i) {
    xr[i] -= lr[i] * ur - li[i] * ui;
    xi[i] -= lr[i] * ui + li[i] * ur;
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
  // Step j touches columns j .. j + kv, so kv + 1 columns are live at once: the window holds
  // the next power of two of them (a mask finds a column's slot).
  int window = 1;
  while (window < kv_ + 1) window *= 2;
  window_mask_ = window - 1;
  upper_stride_ = whole_lanes(kv_);
  lower_stride_ = whole_lanes(kl_);
  dense_width_ = whole_lanes(kv_ + 1);
  // A window column: the band (ld rows), and zero padding for the vector kernels, which reach
  // row kl + dense_width_ - 1 (the dense terms) and kv + lower_stride_ (the update).
  stride_ =
      whole_lanes(static_cast<int>(std::max({ld_, kl_ + dense_width_, kv_ + lower_stride_ + 1})));
  const auto un = static_cast<std::size_t>(n);
  std::vector<int> new_index(un);
  for (std::size_t k = 0; k < un; ++k)
    new_index[static_cast<std::size_t>(perm_[k])] = static_cast<int>(k);
  // Entries grouped by renumbered column (counting sort), so that the elimination assembles
  // each column just before it first touches it, while it is in cache.
  column_start_.assign(un + 1, 0);
  for (int j = 0; j < n; ++j)
    column_start_[static_cast<std::size_t>(new_index[static_cast<std::size_t>(j)]) + 1] +=
        outer[j + 1] - outer[j];
  std::partial_sum(column_start_.begin(), column_start_.end(), column_start_.begin());
  entries_.resize(static_cast<std::size_t>(outer[n]));
  std::vector<int> next(column_start_.begin(), column_start_.end() - 1);
  for (int j = 0; j < n; ++j) {
    const int c = new_index[static_cast<std::size_t>(j)];
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int r = new_index[static_cast<std::size_t>(inner[k])];
      entries_[static_cast<std::size_t>(next[static_cast<std::size_t>(c)]++)] = {k, kv_ + r - c};
    }
  }
  terms_.clear();
  terms_set_ = false;
  // The row sums take whole lanes of rows below the last (zeros).
  row_sum_.assign(un + dense_width_, 0.0);
  scaled_sum_.assign(un + dense_width_, 0.0);
  column_scale_.assign(un, 1.0);
  row_weight_.assign(un, 1.0);
  pivot_.assign(un, 0);
  inverse_pivot_.assign(un, Complex(0.0));
  window_re_.assign(static_cast<std::size_t>(window) * stride_, 0.0);
  window_im_.assign(static_cast<std::size_t>(window) * stride_, 0.0);
  upper_.assign(2 * un * upper_stride_, 0.0);
  upper_start_.assign(un + 1, 0);
  lower_re_.assign(un * lower_stride_, 0.0);
  lower_im_.assign(un * lower_stride_, 0.0);
  pivot_ratio_ = 0.0;
}

void BandedLU::set_terms(const std::vector<const double*>& terms) {
  if (n_ == 0) throw std::logic_error("BandedLU::set_terms before analyze");
  const auto un = static_cast<std::size_t>(n_);
  const auto width = static_cast<std::size_t>(kv_) + 1;  // rows c - ku .. c + kl
  terms_.resize(terms.size());
  std::vector<std::size_t> dense;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    Term& term = terms_[t];
    std::size_t count = 0;
    if (terms[t] != nullptr)
      for (const Entry& e : entries_) count += terms[t][e.source] != 0.0 ? 1 : 0;
    term.start.clear();
    term.offset.clear();
    term.value.clear();
    // Dense when it fills a quarter of the band: a vector operation per column is then cheaper
    // than decoding a list.
    term.kind = count == 0                ? Term::Kind::Empty
                : 4 * count >= un * width ? Term::Kind::Dense
                                          : Term::Kind::Sparse;
    if (term.kind == Term::Kind::Dense) dense.push_back(t);
  }
  dense_count_ = static_cast<int>(dense.size());
  const std::size_t block = dense.size() * dense_width_;
  dense_value_.assign(un * block, 0.0);
  dense_weight_re_.assign(dense.size(), 0.0);
  dense_weight_im_.assign(dense.size(), 0.0);
  sparse_column_.assign(un, 0);
  for (std::size_t c = 0; c < un; ++c)
    for (int e = column_start_[c]; e < column_start_[c + 1]; ++e) {
      const Entry& entry = entries_[static_cast<std::size_t>(e)];
      const auto row = static_cast<std::size_t>(entry.offset - kl_);
      for (std::size_t d = 0; d < dense.size(); ++d)
        dense_value_[c * block + d * dense_width_ + row] = terms[dense[d]][entry.source];
    }
  for (std::size_t t = 0; t < terms.size(); ++t) {
    Term& term = terms_[t];
    if (term.kind != Term::Kind::Sparse) continue;
    term.start.assign(un + 1, 0);
    for (std::size_t c = 0; c < un; ++c) {
      for (int e = column_start_[c]; e < column_start_[c + 1]; ++e) {
        const Entry& entry = entries_[static_cast<std::size_t>(e)];
        const double v = terms[t][entry.source];
        if (v == 0.0) continue;
        term.offset.push_back(entry.offset);
        term.value.push_back(v);
        sparse_column_[c] = 1;
      }
      term.start[c + 1] = static_cast<int>(term.offset.size());
    }
  }
  terms_set_ = true;
}

void BandedLU::set_column_scale(const double* scale) {
  if (n_ == 0) throw std::logic_error("BandedLU::set_column_scale before analyze");
  for (std::size_t k = 0; k < perm_.size(); ++k) {
    const double s = scale != nullptr ? scale[perm_[k]] : 1.0;
    if (!(s > 0.0) || !std::isfinite(s))
      throw std::invalid_argument("BandedLU::set_column_scale: a scale is not positive and finite");
    column_scale_[k] = s;
  }
}

double BandedLU::factor_operations() const { return static_cast<double>(n_) * kl_ * (kl_ + ku_); }

double BandedLU::storage_entries() const {
  return static_cast<double>(n_) * static_cast<double>(ld_);
}

// Step j of the elimination (LAPACK xGBTF2): scaled threshold pivot search in column j, row
// interchange over the columns it reaches, multipliers, rank-1 update of the band; row j of U
// and column j of L are final then and leave the window. `last_column`: the last column touched
// by a pivot row so far. KM > 0: the rows below the diagonal are KM (= kl, a compile-time
// count: the multipliers are whole lanes, zero beyond KM, which leaves the entries there
// unchanged); KM = 0: `km` of them (the last kl steps, and bands wider than the unrolled ones).
template <int KM>
[[gnu::always_inline]] inline void BandedLU::eliminate_column(int j, int km_runtime,
                                                              int& last_column) {
  const int km = KM > 0 ? KM : km_runtime;
  double* re = window_re_.data();
  double* im = window_im_.data();
  const std::size_t diagonal = slot(j, j);
  const double* weight = row_weight_.data() + j;
  int p = 0;
  double best = -1.0;
  for (int i = 0; i <= km; ++i) {
    const double a = (std::abs(re[diagonal + static_cast<std::size_t>(i)]) +
                      std::abs(im[diagonal + static_cast<std::size_t>(i)])) *
                     weight[i];
    if (a > best) {
      best = a;
      p = i;
    }
  }
  // Threshold pivoting: the diagonal stays the pivot while it is within kPivotThreshold of the
  // largest candidate, so that the band does not fill from interchanges.
  if (p != 0 &&
      (std::abs(re[diagonal]) + std::abs(im[diagonal])) * weight[0] >= kPivotThreshold * best)
    p = 0;
  pivot_[static_cast<std::size_t>(j)] = j + p;
  const auto uj = static_cast<std::size_t>(j);
  double* lower_re = lower_re_.data() + uj * lower_stride_;
  double* lower_im = lower_im_.data() + uj * lower_stride_;
  // Row j of U, packed: its entries right of the diagonal up to the last column a pivot row
  // reached (w of them, zero-padded to whole lanes), real parts then imaginary parts.
  const auto row_of_u = [&](int w) {
    const std::size_t lanes = whole_lanes(w);
    const std::size_t start = upper_start_[uj];
    upper_start_[uj + 1] = start + 2 * lanes;
    double* row = upper_.data() + start;
    std::fill(row + w, row + lanes, 0.0);
    std::fill(row + lanes + w, row + 2 * lanes, 0.0);
    upper_width_ = std::max(upper_width_, w);
    return std::pair<double*, double*>{row, row + lanes};
  };
  if (best == 0.0) {
    // Singular: the factor is unusable; keep the stored factor defined.
    inverse_pivot_[uj] = Complex(0.0);
    smallest_pivot_ = 0.0;
    std::fill(lower_re, lower_re + km, 0.0);
    std::fill(lower_im, lower_im + km, 0.0);
    const int last_in_band = std::min(j + kv_, n_ - 1);
    const auto [upper_re, upper_im] = row_of_u(last_in_band - j);
    for (int c = j + 1; c <= last_in_band; ++c) {
      upper_re[c - j - 1] = re[slot(j, c)];
      upper_im[c - j - 1] = im[slot(j, c)];
    }
    return;
  }
  last_column = std::max(last_column, std::min(j + ku_ + p, n_ - 1));
  const auto [upper_re, upper_im] = row_of_u(last_column - j);
  if (p != 0) {
    for (int c = j; c <= last_column; ++c) {
      const std::size_t s = slot(j, c);
      std::swap(re[s], re[s + static_cast<std::size_t>(p)]);
      std::swap(im[s], im[s + static_cast<std::size_t>(p)]);
    }
    std::swap(row_weight_[uj], row_weight_[uj + static_cast<std::size_t>(p)]);
  }
  // u_jj is final here: later steps interchange and update rows below j only.
  const Complex pivot(re[diagonal], im[diagonal]);
  const double d = magnitude(pivot) * row_weight_[uj];
  smallest_pivot_ = std::min(smallest_pivot_, d);
  largest_pivot_ = std::max(largest_pivot_, d);
  const Complex inverse = reciprocal(pivot);
  inverse_pivot_[uj] = inverse;
  const double vr = inverse.real(), vi = inverse.imag();
  if constexpr (KM > 0) {
    // Multipliers l_i = a(j + i, j) / u_jj, i = 1 .. KM, in registers; zero beyond KM.
    constexpr int kQuads = (KM + kLanes - 1) / kLanes;
    Quad lr[kQuads], li[kQuads];
    const Quad qr = splat(vr), qi = splat(vi);
    for (int q = 0; q < kQuads; ++q) {
      const Quad a = load(re + diagonal + 1 + kLanes * q), b = load(im + diagonal + 1 + kLanes * q);
      lr[q] = a * qr - b * qi;
      li[q] = a * qi + b * qr;
    }
    for (int i = KM; i < kQuads * kLanes; ++i) {
      lr[kQuads - 1][i % kLanes] = 0.0;
      li[kQuads - 1][i % kLanes] = 0.0;
    }
    for (int q = 0; q < kQuads; ++q) {
      store(lower_re + kLanes * q, lr[q]);
      store(lower_im + kLanes * q, li[q]);
    }
    for (int c = j + 1; c <= last_column; ++c) {
      const std::size_t s = slot(j, c);
      double* xr = re + s;  // xr[0] = Re a(j, c), then the rows below
      double* xi = im + s;
      const double ur = xr[0], ui = xi[0];
      upper_re[c - j - 1] = ur;
      upper_im[c - j - 1] = ui;
      if (ur == 0.0 && ui == 0.0) continue;
      const Quad pr = splat(ur), pi = splat(ui);
      for (int q = 0; q < kQuads; ++q) {
        double* yr = xr + 1 + kLanes * q;
        double* yi = xi + 1 + kLanes * q;
        store(yr, load(yr) - (lr[q] * pr - li[q] * pi));
        store(yi, load(yi) - (lr[q] * pi + li[q] * pr));
      }
    }
  } else {
    for (int i = 0; i < km; ++i) {
      const double ar = re[diagonal + 1 + static_cast<std::size_t>(i)];
      const double ai = im[diagonal + 1 + static_cast<std::size_t>(i)];
      lower_re[i] = ar * vr - ai * vi;
      lower_im[i] = ar * vi + ai * vr;
    }
    for (int c = j + 1; c <= last_column; ++c) {
      const std::size_t s = slot(j, c);
      const double ur = re[s], ui = im[s];
      upper_re[c - j - 1] = ur;
      upper_im[c - j - 1] = ui;
      if (ur == 0.0 && ui == 0.0) continue;
      update_rows(re + s + 1, im + s + 1, lower_re, lower_im, ur, ui, km);
    }
  }
}

// The dense terms of column c into its (zeroed) window slot: sum_d w_d v_d, each lane summed
// over the terms in their order. `fused`: the column has no sparse entries and its rows start
// at c - ku >= 0, so its row sums and column scaling are taken in the same pass (returns true:
// the column is complete). D > 0: the count of dense terms, their weights held in registers.
template <int D>
[[gnu::always_inline]] inline bool BandedLU::assemble_dense(int c, bool fused) {
  const std::size_t count =
      D > 0 ? static_cast<std::size_t>(D) : static_cast<std::size_t>(dense_count_);
  const auto uc = static_cast<std::size_t>(c);
  const std::size_t base = static_cast<std::size_t>(c & window_mask_) * stride_;
  double* band_re = window_re_.data() + base + kl_;
  double* band_im = window_im_.data() + base + kl_;
  const double* v = dense_value_.data() + uc * count * dense_width_;
  constexpr std::size_t kHeld = D > 0 ? static_cast<std::size_t>(D) : 1;
  Quad wr[kHeld], wi[kHeld];
  if constexpr (D > 0)
    for (std::size_t d = 0; d < kHeld; ++d) {
      wr[d] = splat(dense_weight_re_[d]);
      wi[d] = splat(dense_weight_im_[d]);
    }
  const auto lanes = [&](std::size_t k, Quad& r, Quad& i) {
    r = splat(0.0);
    i = splat(0.0);
    for (std::size_t d = 0; d < count; ++d) {
      const Quad x = load(v + d * dense_width_ + k);
      if constexpr (D > 0) {
        r += wr[d] * x;
        i += wi[d] * x;
      } else {
        r += splat(dense_weight_re_[d]) * x;
        i += splat(dense_weight_im_[d]) * x;
      }
    }
  };
  if (!fused) {
    for (std::size_t k = 0; k < dense_width_; k += kLanes) {
      Quad r, i;
      lanes(k, r, i);
      store(band_re + k, r);
      store(band_im + k, i);
    }
    return false;
  }
  // Whole lanes from row c - ku (the rows past the last are padding and take zeros).
  double* sum = row_sum_.data() + (c - ku_);
  double* scaled = scaled_sum_.data() + (c - ku_);
  const Quad qs = splat(column_scale_[uc]);
  for (std::size_t k = 0; k < dense_width_; k += kLanes) {
    Quad r, i;
    lanes(k, r, i);
    add_moduli(r, i, qs, sum + k, scaled + k);
    store(band_re + k, r * qs);
    store(band_im + k, i * qs);
  }
  return true;
}

// Column c of the matrix into its window slot, its row sums |.|_1 (of A and of A S) and its
// column scaling. Each entry is the sum of its dense terms in their order, then of its sparse
// terms; a column without sparse entries (most) is assembled, summed and scaled in one pass.
[[gnu::always_inline]] inline void BandedLU::assemble_column(int c) {
  const std::size_t base = static_cast<std::size_t>(c & window_mask_) * stride_;
  double* re = window_re_.data() + base;
  double* im = window_im_.data() + base;
  const Quad zero = splat(0.0);
  for (std::size_t k = 0; k < stride_; k += kLanes) {
    store(re + k, zero);
    store(im + k, zero);
  }
  const auto uc = static_cast<std::size_t>(c);
  // Rows c - ku .. c + kl (band positions kl .. kl + kv), then zeros to whole lanes.
  double* band_re = re + kl_;
  double* band_im = im + kl_;
  const double s = column_scale_[uc];
  const Quad qs = splat(s);
  if (weights_ != nullptr) {
    const bool fused = sparse_column_[uc] == 0 && c >= ku_;
    // Up to six dense terms with their weights in registers; more through the generic count.
    switch (dense_count_) {
      case 0:
        break;
      case 1:
        if (assemble_dense<1>(c, fused)) return;
        break;
      case 2:
        if (assemble_dense<2>(c, fused)) return;
        break;
      case 3:
        if (assemble_dense<3>(c, fused)) return;
        break;
      case 4:
        if (assemble_dense<4>(c, fused)) return;
        break;
      case 5:
        if (assemble_dense<5>(c, fused)) return;
        break;
      case 6:
        if (assemble_dense<6>(c, fused)) return;
        break;
      default:
        if (assemble_dense<0>(c, fused)) return;
        break;
    }
    for (std::size_t t = 0; t < terms_.size(); ++t) {
      const Term& term = terms_[t];
      if (term.kind != Term::Kind::Sparse) continue;
      const double ar = weights_[t].real(), ai = weights_[t].imag();
      for (int e = term.start[uc]; e < term.start[uc + 1]; ++e) {
        const auto offset = static_cast<std::size_t>(term.offset[static_cast<std::size_t>(e)]);
        const double x = term.value[static_cast<std::size_t>(e)];
        re[offset] += ar * x;
        im[offset] += ai * x;
      }
    }
  } else {
    for (int e = column_start_[uc]; e < column_start_[uc + 1]; ++e) {
      const Entry& entry = entries_[static_cast<std::size_t>(e)];
      const auto offset = static_cast<std::size_t>(entry.offset);
      re[offset] += values_[entry.source].real();
      im[offset] += values_[entry.source].imag();
    }
  }
  if (c >= ku_) {
    double* sum = row_sum_.data() + (c - ku_);
    double* scaled = scaled_sum_.data() + (c - ku_);
    for (std::size_t k = 0; k < dense_width_; k += kLanes)
      add_moduli(load(band_re + k), load(band_im + k), qs, sum + k, scaled + k);
  } else {
    for (int r = 0; r <= std::min(n_ - 1, c + kl_); ++r) {
      const auto k = static_cast<std::size_t>(kv_ + r - c);
      const double m = std::abs(re[k]) + std::abs(im[k]);
      row_sum_[static_cast<std::size_t>(r)] += m;
      scaled_sum_[static_cast<std::size_t>(r)] += s * m;
    }
  }
  if (s != 1.0)
    for (std::size_t k = 0; k < dense_width_; k += kLanes) {
      store(band_re + k, load(band_re + k) * qs);
      store(band_im + k, load(band_im + k) * qs);
    }
}

// Step j: the columns it touches (j .. j + kl + ku at most) are assembled just before; row
// j + kl is complete then (its last column is j + kl + ku), and its pivot weight is set. Then
// the elimination (KM as eliminate_column), and the forward substitution of the prepared loads
// while column j of L is in cache (the same operations in the same order as solve()).
template <int KM>
[[gnu::always_inline]] inline void BandedLU::step(int j, int km, Progress& at) {
  for (const int need = std::min(n_ - 1, j + kv_); at.assembled <= need; ++at.assembled)
    assemble_column(at.assembled);
  for (const int need = std::min(n_ - 1, j + kl_); at.weighted <= need; ++at.weighted) {
    const double sum = scaled_sum_[static_cast<std::size_t>(at.weighted)];
    row_weight_[static_cast<std::size_t>(at.weighted)] = sum > 0.0 ? 1.0 / sum : 1.0;
  }
  eliminate_column<KM>(j, km, at.last_column);
  const auto un = static_cast<std::size_t>(n_);
  for (std::size_t c = 0; c < static_cast<std::size_t>(prepared_columns_); ++c)
    forward_step(j, prepared_.data() + 2 * c * un, prepared_.data() + (2 * c + 1) * un);
}

// All steps: those with kl rows below the diagonal by the unrolled kernel when KL = kl_.
// Compiled also for AVX2, chosen at run time (GCC function multi-versioning); everything it
// calls per step is inlined into each version.
template <int KL>
GEARDYN_KERNEL_CLONES void BandedLU::eliminate_all() {
  Progress at;
  const int interior = KL > 0 ? std::max(0, n_ - KL) : 0;
  for (int j = 0; j < interior; ++j) step<KL>(j, KL, at);
  for (int j = interior; j < n_; ++j) step<0>(j, std::min(kl_, n_ - 1 - j), at);
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

Status BandedLU::factorize(const Complex* values) { return factorize(values, nullptr, 0); }

Status BandedLU::factorize(const Complex* values, const Complex* rhs, int columns) {
  if (n_ == 0) throw std::logic_error("BandedLU::factorize before analyze");
  values_ = values;
  weights_ = nullptr;
  const Status status = run(rhs, columns);
  values_ = nullptr;
  return status;
}

Status BandedLU::factorize_terms(const Complex* weights, const Complex* rhs, int columns) {
  if (n_ == 0 || !terms_set_)
    throw std::logic_error("BandedLU::factorize_terms before analyze and set_terms");
  weights_ = weights;
  values_ = nullptr;
  std::size_t d = 0;
  for (std::size_t t = 0; t < terms_.size(); ++t)
    if (terms_[t].kind == Term::Kind::Dense) {
      dense_weight_re_[d] = weights[t].real();
      dense_weight_im_[d++] = weights[t].imag();
    }
  const Status status = run(rhs, columns);
  weights_ = nullptr;
  return status;
}

// The elimination of the matrix given by values_ or weights_. `rhs` (columns of size()
// entries, original numbering) are forward-substituted into prepared_ during the elimination.
Status BandedLU::run(const Complex* rhs, int columns) {
  prepared_columns_ = columns;
  const auto un = static_cast<std::size_t>(n_);
  if (prepared_.size() < 2 * un * static_cast<std::size_t>(columns))
    prepared_.resize(2 * un * static_cast<std::size_t>(columns));
  for (std::size_t c = 0; c < static_cast<std::size_t>(columns); ++c)
    for (std::size_t k = 0; k < un; ++k) {
      const Complex b = rhs[c * un + static_cast<std::size_t>(perm_[k])];
      prepared_[2 * c * un + k] = b.real();
      prepared_[(2 * c + 1) * un + k] = b.imag();
    }
  std::fill(row_sum_.begin(), row_sum_.end(), 0.0);
  std::fill(scaled_sum_.begin(), scaled_sum_.end(), 0.0);
  smallest_pivot_ = std::numeric_limits<double>::infinity();
  largest_pivot_ = 0.0;
  upper_width_ = 0;
  eliminate();
  pivot_ratio_ = largest_pivot_ > 0.0 ? smallest_pivot_ / largest_pivot_ : 0.0;
  return smallest_pivot_ > 0.0 ? Status::Ok : Status::Singular;
}

// One step of L y = P c: the interchange and the multipliers of elimination step j (y's real
// and imaginary parts apart).
[[gnu::always_inline]] inline void BandedLU::forward_step(int j, double* yr, double* yi) const {
  const int p = pivot_[static_cast<std::size_t>(j)];
  if (p != j) {
    std::swap(yr[j], yr[p]);
    std::swap(yi[j], yi[p]);
  }
  const double tr = yr[j], ti = yi[j];
  if (tr == 0.0 && ti == 0.0) return;
  const std::size_t base = static_cast<std::size_t>(j) * lower_stride_;
  const double* lr = lower_re_.data() + base;
  const double* li = lower_im_.data() + base;
  double* xr = yr + j + 1;
  double* xi = yi + j + 1;
  const auto rows = static_cast<int>(lower_stride_);
  if (j + rows < n_) {
    // Whole lanes (the padding multipliers are zero).
    const Quad vr = splat(tr), vi = splat(ti);
    for (int k = 0; k < rows; k += kLanes) {
      const Quad a = load(lr + k), b = load(li + k);
      store(xr + k, load(xr + k) - (a * vr - b * vi));
      store(xi + k, load(xi + k) - (a * vi + b * vr));
    }
    return;
  }
  update_rows(xr, xi, lr, li, tr, ti, std::min(kl_, n_ - 1 - j));
}

// U z = y row by row from the last (U's rows packed one after the other, each as long as its
// last non-zero entry; z's real and imaginary parts apart), then x = S P_c z.
GEARDYN_KERNEL_CLONES void BandedLU::back_substitute(double* zr, double* zi, Complex* x) const {
  for (int j = n_ - 1; j >= 0; --j) {
    const std::size_t start = upper_start_[static_cast<std::size_t>(j)];
    const auto width =
        static_cast<int>((upper_start_[static_cast<std::size_t>(j) + 1] - start) / 2);
    const double* ur = upper_.data() + start;
    const double* ui = ur + width;
    const double* rr = zr + j + 1;
    const double* ri = zi + j + 1;
    double sr = zr[j], si = zi[j];
    if (j + width < n_) {
      // Whole lanes (the padding entries of U are zero).
      Quad ar = splat(0.0), ai = splat(0.0);
      for (int k = 0; k < width; k += kLanes) {
        const Quad a = load(ur + k), b = load(ui + k);
        const Quad c = load(rr + k), d = load(ri + k);
        ar += a * c - b * d;
        ai += a * d + b * c;
      }
      sr -= (ar[0] + ar[1]) + (ar[2] + ar[3]);
      si -= (ai[0] + ai[1]) + (ai[2] + ai[3]);
    } else {
      for (int k = 0; k < std::min(width, n_ - 1 - j); ++k) {
        sr -= ur[k] * rr[k] - ui[k] * ri[k];
        si -= ur[k] * ri[k] + ui[k] * rr[k];
      }
    }
    const Complex v = inverse_pivot_[static_cast<std::size_t>(j)];
    zr[j] = sr * v.real() - si * v.imag();
    zi[j] = sr * v.imag() + si * v.real();
  }
  for (int k = 0; k < n_; ++k) {
    const double s = column_scale_[static_cast<std::size_t>(k)];
    x[perm_[static_cast<std::size_t>(k)]] = Complex(s * zr[k], s * zi[k]);
  }
}

// `work` (n complex entries) holds the real parts of y in its first n doubles, the imaginary
// parts in the next n.
GEARDYN_KERNEL_CLONES void BandedLU::solve(const Complex* b, Complex* x, Complex* work) const {
  double* yr = reinterpret_cast<double*>(work);
  double* yi = yr + n_;
  for (int k = 0; k < n_; ++k) {
    const Complex v = b[perm_[static_cast<std::size_t>(k)]];
    yr[k] = v.real();
    yi[k] = v.imag();
  }
  // L y = P c: interchanges and multipliers in the order they were made.
  for (int j = 0; j < n_; ++j) forward_step(j, yr, yi);
  back_substitute(yr, yi, x);
}

void BandedLU::solve_prepared(int column, Complex* x, Complex* work) const {
  if (column < 0 || column >= prepared_columns_)
    throw std::logic_error("BandedLU::solve_prepared: no such prepared right-hand side");
  const auto un = static_cast<std::size_t>(n_);
  const double* y = prepared_.data() + 2 * static_cast<std::size_t>(column) * un;
  double* z = reinterpret_cast<double*>(work);
  std::copy(y, y + 2 * un, z);
  back_substitute(z, z + n_, x);
}

}  // namespace geardyn::linalg
