// GCC's -Wnull-dereference false positive inside Eigen's and <complex>'s inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>
#include <time.h>

#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/condensed.hpp"

namespace geardyn::hbm {

using cd = std::complex<double>;

double CondensedStatistics::now() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Clusters of elements that share coordinates, and the real form of each harmonic's modal sum,
// fixed at construction. Unknowns of harmonic n: rows a (d s + cos n) and, for n >= 1, rows b
// (d s + sin n); real form of a complex n_c x n_c map M on [F_a; F_b] (F = F_a - i F_b):
// [[M_r, M_i], [-M_i, M_r]] (condensed.hpp), which composes like the complex maps.
struct CondensedHarmonicBalance::Structure {
  struct Cluster {
    std::vector<int> coordinates;  // global coordinate of each local one
    Eigen::MatrixXd residual;      // R_b on the cluster's unknowns (empty: none)
  };
  struct Modal {
    int offset = 0;  // first capacitance column
    int modes = 0;
    // n >= 1: columns [re (m), im (m)], U = [[U_r, U_i], [-U_i, U_r]] on rows [a; b], D the
    // complex factors in real form. n = 0: the real part U_r D V_r^T + U_i D V_i^T of the sum:
    // U = [U_r, U_i] (U_r alone for real shapes), D real, repeated on both halves.
    bool paired = false;
    Eigen::MatrixXd U, V;
    int columns() const { return static_cast<int>(U.cols()); }
  };
  std::vector<Cluster> clusters;
  std::vector<int> force_cluster;             // per force
  std::vector<std::vector<int>> force_local;  // per force: local index of each coordinate
  std::vector<Modal> modal;                   // per harmonic
  int capacity = 0;
  bool residual_couples_clusters = false;
  // Every harmonic with the same real modes and real residual flexibility (a real structure,
  // H_n(w) = H(n w)): J is applied on all 2H + 1 coefficient columns at once (U, V, R_res real).
  bool shared = false;
  Eigen::MatrixXd shared_left, shared_right, shared_residual;
};

namespace {

// True when every harmonic has the same real left and right modes and the same real residual
// flexibility, with at least one mode.
bool shares_real_modes(const std::vector<ModalReceptance>& harmonics) {
  const ModalReceptance& first = harmonics.front();
  if (first.modes() == 0) return false;
  for (const ModalReceptance& r : harmonics) {
    if (!r.left.imag().isZero(0.0) || !r.right.imag().isZero(0.0) || !r.residual.imag().isZero(0.0))
      return false;
    if (r.left.rows() != first.left.rows() || r.left.cols() != first.left.cols() ||
        r.left != first.left || r.right.rows() != first.right.rows() ||
        r.right.cols() != first.right.cols() || r.right != first.right ||
        r.residual.size() != first.residual.size() ||
        (r.residual.size() > 0 && r.residual != first.residual))
      return false;
  }
  return true;
}

}  // namespace

Eigen::VectorXcd ModalReceptance::modal_factors(double w, Eigen::VectorXcd* d) const {
  const Eigen::Index m = modes();
  Eigen::VectorXcd f(m);
  if (d) d->resize(m);
  for (Eigen::Index r = 0; r < m; ++r) {
    const double wr = natural_frequency[r], z = damping_ratio[r];
    const cd den(wr * wr - w * w, 2.0 * z * wr * w);
    f[r] = 1.0 / den;
    // d(1/den)/dw = -(d den/dw) / den^2, d den/dw = -2 w + 2 i zeta w_r.
    if (d) (*d)[r] = -cd(-2.0 * w, 2.0 * z * wr) * f[r] * f[r];
  }
  return f;
}

Eigen::MatrixXcd ModalReceptance::receptance(double w, Eigen::MatrixXcd* dH) const {
  Eigen::VectorXcd df;
  const Eigen::VectorXcd f = modal_factors(w, dH ? &df : nullptr);
  Eigen::MatrixXcd H = left * f.asDiagonal() * right.adjoint();
  if (residual.size()) H += residual;
  if (dH) *dH = left * df.asDiagonal() * right.adjoint();
  return H;
}

Eigen::VectorXcd ModalReceptance::linear_response(double w, Eigen::VectorXcd* dx) const {
  Eigen::VectorXcd x = Eigen::VectorXcd::Zero(coordinates());
  if (dx) dx->setZero(coordinates());
  if (modal_excitation.size()) {
    Eigen::VectorXcd df;
    const Eigen::VectorXcd f = modal_factors(w, dx ? &df : nullptr);
    x += left * f.cwiseProduct(modal_excitation);
    if (dx) *dx += left * df.cwiseProduct(modal_excitation);
  }
  if (residual_excitation.size()) x += residual_excitation;
  return x;
}

Eigen::VectorXcd ModalReceptance::sensor_response(double w, const Eigen::VectorXcd& f) const {
  const Eigen::VectorXcd factors = modal_factors(w);
  Eigen::VectorXcd modal = -(right.adjoint() * f);
  if (modal_excitation.size()) modal += modal_excitation;
  Eigen::VectorXcd z = sensor_left * factors.cwiseProduct(modal);
  if (sensor_residual.size()) z -= sensor_residual * f;
  if (sensor_residual_excitation.size()) z += sensor_residual_excitation;
  return z;
}

void ModalReceptance::validate(Eigen::Index n_c, const char* what) const {
  const Eigen::Index m = modes();
  auto fail = [&](const std::string& expected, const std::string& found) {
    throw InputError({}, what, expected, found);
  };
  if (damping_ratio.size() != m)
    fail(fmt::format("{} damping ratios", m), fmt::format("{}", damping_ratio.size()));
  if (left.rows() != n_c || left.cols() != m || right.rows() != n_c || right.cols() != m)
    fail(fmt::format("left and right shapes of {} coordinates x {} modes", n_c, m),
         fmt::format("{}x{} and {}x{}", left.rows(), left.cols(), right.rows(), right.cols()));
  if (residual.size() && (residual.rows() != n_c || residual.cols() != n_c))
    fail(fmt::format("a residual of {0}x{0}", n_c),
         fmt::format("{}x{}", residual.rows(), residual.cols()));
  if (modal_excitation.size() && modal_excitation.size() != m)
    fail(fmt::format("{} modal excitations", m), fmt::format("{}", modal_excitation.size()));
  if (residual_excitation.size() && residual_excitation.size() != n_c)
    fail(fmt::format("{} residual excitations", n_c),
         fmt::format("{}", residual_excitation.size()));
  if (sensor_left.size() && sensor_left.cols() != m)
    fail(fmt::format("sensor shapes of {} modes", m), fmt::format("{}", sensor_left.cols()));
  if (sensor_residual.size() &&
      (sensor_residual.rows() != sensors() || sensor_residual.cols() != n_c))
    fail(fmt::format("a sensor residual of {}x{}", sensors(), n_c),
         fmt::format("{}x{}", sensor_residual.rows(), sensor_residual.cols()));
  for (Eigen::Index r = 0; r < m; ++r)
    if (!(natural_frequency[r] >= 0.0 && std::isfinite(natural_frequency[r]) &&
          damping_ratio[r] >= 0.0 && std::isfinite(damping_ratio[r])))
      fail(
          "finite natural frequencies and damping ratios >= 0",
          fmt::format("mode {}: {} rad/s, zeta {}", r + 1, natural_frequency[r], damping_ratio[r]));
}

namespace {

std::vector<FrequencyDependentForce> frequency_independent(std::vector<NonlinearForce> forces) {
  std::vector<FrequencyDependentForce> out;
  for (auto& f : forces)
    out.push_back([f = std::move(f)](const HarmonicBasis& b, const Eigen::VectorXd& X, double,
                                     Eigen::VectorXd& F, Eigen::MatrixXd* J, Eigen::VectorXd*) {
      if (J) {
        f(b, X, F, *J);
      } else {
        Eigen::MatrixXd unused = Eigen::MatrixXd::Zero(X.size(), X.size());
        f(b, X, F, unused);
      }
    });
  return out;
}

// A harmonic whose receptance has neither modes, nor residual, nor excitation: H = 0 and
// x_lin = 0 there, the rows read R = X (the mean held at zero).
bool inactive(const ModalReceptance& r) {
  return r.modes() == 0 && r.residual.size() == 0 && r.residual_excitation.size() == 0;
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

// Row of coordinate d in the real form of harmonic n: a rows first, then b rows.
inline int a_row(int d) { return d; }
inline int b_row(int d, int n_c) { return n_c + d; }

}  // namespace

LocalForce local_friction_contact(std::vector<int> coordinates, FrictionContact contact,
                                  double preload_per_omega_squared) {
  validate(contact);
  const std::size_t count = static_cast<std::size_t>(1 + contact.tangential_directions);
  if (coordinates.size() != count)
    throw InputError({}, "coordinates",
                     fmt::format("{} coordinates (normal, then {} tangential)", count, count - 1),
                     fmt::format("{} indices", coordinates.size()));
  const double c = preload_per_omega_squared;
  if (!(c >= 0.0 && std::isfinite(c)))
    throw InputError({}, "preload_per_omega_squared", "a finite coefficient >= 0 [N s^2]",
                     fmt::format("{}", c));
  if (c > 0.0 && !(contact.normal_stiffness > 0.0))
    throw InputError({}, "normal_stiffness", "k_n > 0 N/m for a preload that follows the frequency",
                     fmt::format("{}", contact.normal_stiffness));
  LocalForce f;
  f.coordinates = std::move(coordinates);
  f.evaluate = [contact, c](const HarmonicBasis& b, const Eigen::VectorXd& w, double omega,
                            Eigen::VectorXd& force, Eigen::MatrixXd* J,
                            Eigen::VectorXd* df_domega) {
    FrictionContact law = contact;
    law.normal_preload += c * omega * omega;
    const ContactResponse r = friction_contact_response(law, b, w);
    force += r.coefficients;
    if (J) *J += r.jacobian;
    if (df_domega && c > 0.0) {
      // df/dN_0 = J e / k_n - e (e: the a_0 of v, the first unknown), dN_0/domega = 2 c omega.
      Eigen::VectorXd df = r.jacobian.col(0) / law.normal_stiffness;
      df[0] -= 1.0;
      *df_domega += (2.0 * c * omega) * df;
    }
  };
  return f;
}

CondensedHarmonicBalance::CondensedHarmonicBalance(int coordinates, HarmonicBasis basis,
                                                   std::vector<ModalReceptance> harmonics,
                                                   std::vector<NonlinearForce> forces)
    : CondensedHarmonicBalance(coordinates, std::move(basis), std::move(harmonics),
                               frequency_independent(std::move(forces))) {}

CondensedHarmonicBalance::CondensedHarmonicBalance(int coordinates, HarmonicBasis basis,
                                                   std::vector<ModalReceptance> harmonics,
                                                   std::vector<FrequencyDependentForce> forces)
    : n_c_(coordinates),
      basis_(std::move(basis)),
      harmonics_(std::move(harmonics)),
      forces_(std::move(forces)) {
  if (n_c_ < 1) throw InputError({}, "coordinates", "at least 1", std::to_string(n_c_));
  if (static_cast<int>(harmonics_.size()) != basis_.harmonics() + 1)
    throw InputError(
        {}, "harmonics",
        fmt::format("{} receptances (harmonics 0..{})", basis_.harmonics() + 1, basis_.harmonics()),
        std::to_string(harmonics_.size()));
  for (std::size_t n = 0; n < harmonics_.size(); ++n) {
    const auto& h = harmonics_[n];
    // An empty harmonic-0 entry (no modes, no residual) fixes the mean; give it its size.
    if (h.left.size() == 0 && h.modes() == 0 && h.left.rows() != n_c_) {
      harmonics_[n].left.resize(n_c_, 0);
      harmonics_[n].right.resize(n_c_, 0);
    }
    harmonics_[n].validate(n_c_, n == 0 ? "harmonic 0 receptance" : "harmonic receptance");
  }
}

CondensedHarmonicBalance::CondensedHarmonicBalance(int coordinates, HarmonicBasis basis,
                                                   std::vector<ModalReceptance> harmonics,
                                                   std::vector<LocalForce> forces)
    : CondensedHarmonicBalance(coordinates, std::move(basis), std::move(harmonics),
                               std::vector<FrequencyDependentForce>{}) {
  const int s = basis_.size();
  auto st = std::make_shared<Structure>();
  // Clusters: union of the coordinate sets of elements that share a coordinate.
  std::vector<int> parent(static_cast<std::size_t>(n_c_));
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t i = 0; i < forces.size(); ++i) {
    const auto& c = forces[i].coordinates;
    const std::string key = fmt::format("forces[{}]", i);
    if (!forces[i].evaluate) throw InputError({}, key + ".evaluate", "a function", "none");
    if (c.empty()) throw InputError({}, key + ".coordinates", "at least one coordinate", "none");
    for (std::size_t j = 0; j < c.size(); ++j) {
      if (c[j] < 0 || c[j] >= n_c_)
        throw InputError({}, fmt::format("{}.coordinates[{}]", key, j),
                         fmt::format("a coordinate in 0..{}", n_c_ - 1), std::to_string(c[j]));
      for (std::size_t k = 0; k < j; ++k)
        if (c[k] == c[j])
          throw InputError({}, fmt::format("{}.coordinates[{}]", key, j),
                           "a coordinate distinct from the element's others",
                           fmt::format("{} (also coordinates[{}])", c[j], k));
      parent[static_cast<std::size_t>(find_root(parent, c[j]))] = find_root(parent, c[0]);
    }
  }
  std::vector<int> cluster_of_root(static_cast<std::size_t>(n_c_), -1);
  std::vector<int> local_of(static_cast<std::size_t>(n_c_), -1);
  for (const auto& f : forces) {
    const int root = find_root(parent, f.coordinates[0]);
    int& k = cluster_of_root[static_cast<std::size_t>(root)];
    if (k < 0) {
      k = static_cast<int>(st->clusters.size());
      st->clusters.emplace_back();
    }
    auto& cluster = st->clusters[static_cast<std::size_t>(k)];
    std::vector<int> local;
    for (int d : f.coordinates) {
      int& l = local_of[static_cast<std::size_t>(d)];
      if (l < 0) {
        l = static_cast<int>(cluster.coordinates.size());
        cluster.coordinates.push_back(d);
      }
      local.push_back(l);
    }
    st->force_cluster.push_back(k);
    st->force_local.push_back(std::move(local));
  }
  std::vector<int> cluster_of(static_cast<std::size_t>(n_c_), -1);
  for (std::size_t k = 0; k < st->clusters.size(); ++k)
    for (int d : st->clusters[k].coordinates)
      cluster_of[static_cast<std::size_t>(d)] = static_cast<int>(k);

  // Real form of the modal sums.
  for (int n = 0; n <= basis_.harmonics(); ++n) {
    const ModalReceptance& r = harmonics_[static_cast<std::size_t>(n)];
    Structure::Modal m;
    m.offset = st->capacity;
    m.modes = static_cast<int>(r.modes());
    const Eigen::MatrixXd Ur = r.left.real(), Ui = r.left.imag();
    const Eigen::MatrixXd Vr = r.right.real(), Vi = r.right.imag();
    const int q = m.modes;
    if (n > 0) {
      m.paired = true;
      m.U.resize(2 * n_c_, 2 * q);
      m.U << Ur, Ui, -Ui, Ur;
      m.V.resize(2 * n_c_, 2 * q);
      m.V << Vr, Vi, -Vi, Vr;
    } else if (Ui.isZero(0.0) && Vi.isZero(0.0)) {
      m.U = Ur;
      m.V = Vr;
    } else {
      m.U.resize(n_c_, 2 * q);
      m.U << Ur, Ui;
      m.V.resize(n_c_, 2 * q);
      m.V << Vr, Vi;
    }
    st->capacity += m.columns();
    st->modal.push_back(std::move(m));
    // The residual flexibility inside each cluster (R_b), and whether any couples clusters.
    if (r.residual.size() == 0) continue;
    for (int col = 0; col < n_c_; ++col) {
      const int k = cluster_of[static_cast<std::size_t>(col)];
      if (k < 0) continue;
      for (int row = 0; row < n_c_; ++row)
        if (cluster_of[static_cast<std::size_t>(row)] != k && r.residual(row, col) != 0.0)
          st->residual_couples_clusters = true;
    }
    for (auto& cluster : st->clusters) {
      const int nk = static_cast<int>(cluster.coordinates.size());
      if (cluster.residual.size() == 0) cluster.residual.setZero(nk * s, nk * s);
      for (int i = 0; i < nk; ++i)
        for (int j = 0; j < nk; ++j) {
          const cd v = r.residual(cluster.coordinates[static_cast<std::size_t>(i)],
                                  cluster.coordinates[static_cast<std::size_t>(j)]);
          if (n == 0) {
            cluster.residual(i * s, j * s) = v.real();
            continue;
          }
          const int ca = HarmonicBasis::cos_index(n), sb = HarmonicBasis::sin_index(n);
          cluster.residual(i * s + ca, j * s + ca) = v.real();
          cluster.residual(i * s + ca, j * s + sb) = v.imag();
          cluster.residual(i * s + sb, j * s + ca) = -v.imag();
          cluster.residual(i * s + sb, j * s + sb) = v.real();
        }
    }
  }
  st->shared = shares_real_modes(harmonics_);
  if (st->shared) {
    st->shared_left = harmonics_.front().left.real();
    st->shared_right = harmonics_.front().right.real();
    if (harmonics_.front().residual.size() > 0)
      st->shared_residual = harmonics_.front().residual.real();
  }
  local_forces_ = std::move(forces);
  structure_ = std::move(st);
}

Eigen::VectorXcd CondensedHarmonicBalance::complex_harmonic(const Eigen::VectorXd& v, int n) const {
  const int s = basis_.size();
  Eigen::VectorXcd z(n_c_);
  for (int d = 0; d < n_c_; ++d)
    z[d] = n == 0 ? cd(v[d * s], 0.0)
                  : cd(v[d * s + HarmonicBasis::cos_index(n)],
                       -v[d * s + HarmonicBasis::sin_index(n)]);
  return z;
}

Eigen::VectorXd CondensedHarmonicBalance::nonlinear_forces(const Eigen::VectorXd& X,
                                                           double omega) const {
  Eigen::VectorXd F = Eigen::VectorXd::Zero(size());
  if (structure_) {
    evaluate_local(X, omega, F, nullptr, nullptr);
    return F;
  }
  for (const auto& f : forces_) f(basis_, X, omega, F, nullptr, nullptr);
  return F;
}

void CondensedHarmonicBalance::evaluate_local(const Eigen::VectorXd& X, double omega,
                                              Eigen::VectorXd& F, std::vector<Eigen::MatrixXd>* J,
                                              Eigen::VectorXd* dF) const {
  const double started = statistics_ ? CondensedStatistics::now() : 0.0;
  const int s = basis_.size();
  const Structure& st = *structure_;
  if (J) {
    J->resize(st.clusters.size());
    for (std::size_t k = 0; k < st.clusters.size(); ++k) {
      const auto unknowns = static_cast<Eigen::Index>(st.clusters[k].coordinates.size()) * s;
      (*J)[k].setZero(unknowns, unknowns);
    }
  }
  Eigen::VectorXd w, f, df;
  Eigen::MatrixXd Jf;
  for (std::size_t i = 0; i < local_forces_.size(); ++i) {
    const auto& coordinates = local_forces_[i].coordinates;
    const int q = static_cast<int>(coordinates.size());
    w.resize(q * s);
    for (int j = 0; j < q; ++j)
      w.segment(j * s, s) = X.segment(coordinates[static_cast<std::size_t>(j)] * s, s);
    f.setZero(q * s);
    if (J) Jf.setZero(q * s, q * s);
    if (dF) df.setZero(q * s);
    local_forces_[i].evaluate(basis_, w, omega, f, J ? &Jf : nullptr, dF ? &df : nullptr);
    if (f.size() != q * s || (J && (Jf.rows() != q * s || Jf.cols() != q * s)) ||
        (dF && df.size() != q * s))
      throw InputError(
          {}, fmt::format("forces[{}].evaluate", i),
          fmt::format("f and df/domega of {0} and J of {0}x{0} values, as given", q * s),
          fmt::format("{}, {} and {}x{}", f.size(), dF ? df.size() : 0, J ? Jf.rows() : 0,
                      J ? Jf.cols() : 0));
    for (int j = 0; j < q; ++j) {
      const int row = coordinates[static_cast<std::size_t>(j)] * s;
      F.segment(row, s) += f.segment(j * s, s);
      if (dF) dF->segment(row, s) += df.segment(j * s, s);
    }
    if (J) {
      Eigen::MatrixXd& G = (*J)[static_cast<std::size_t>(st.force_cluster[i])];
      const auto& local = st.force_local[i];
      for (int a = 0; a < q; ++a)
        for (int b = 0; b < q; ++b)
          G.block(local[static_cast<std::size_t>(a)] * s, local[static_cast<std::size_t>(b)] * s, s,
                  s) += Jf.block(a * s, b * s, s, s);
    }
  }
  if (statistics_) statistics_->element_seconds += CondensedStatistics::now() - started;
}

Eigen::VectorXd CondensedHarmonicBalance::receptance_residual(const Eigen::VectorXd& X,
                                                              double omega,
                                                              const Eigen::VectorXd& F,
                                                              const Eigen::VectorXd* dF,
                                                              Eigen::VectorXd* dR_domega) const {
  const double started = statistics_ ? CondensedStatistics::now() : 0.0;
  const int s = basis_.size();
  Eigen::VectorXd R = X;
  if (dR_domega) dR_domega->setZero(size());
  for (int n = 0; n <= basis_.harmonics(); ++n) {
    const ModalReceptance& rec = harmonics_[static_cast<std::size_t>(n)];
    if (inactive(rec)) continue;
    // H f - x_lin = U diag(1/d) (V^H f - p) + R_res f - r_res, without forming H.
    Eigen::VectorXcd dfactor;
    const Eigen::VectorXcd factor = rec.modal_factors(n * omega, dR_domega ? &dfactor : nullptr);
    const Eigen::VectorXcd f = complex_harmonic(F, n);
    Eigen::VectorXcd modal = rec.right.adjoint() * f;
    if (rec.modal_excitation.size()) modal -= rec.modal_excitation;
    Eigen::VectorXcd r = rec.left * factor.cwiseProduct(modal);
    if (rec.residual.size()) r.noalias() += rec.residual * f;
    if (rec.residual_excitation.size()) r -= rec.residual_excitation;
    Eigen::VectorXcd dr;
    if (dR_domega) {
      // d/d omega = n d/dw on the factors, plus H dF/d omega.
      dr = double(n) * (rec.left * dfactor.cwiseProduct(modal));
      if (dF) {
        const Eigen::VectorXcd df = complex_harmonic(*dF, n);
        dr.noalias() += rec.left * factor.cwiseProduct(rec.right.adjoint() * df);
        if (rec.residual.size()) dr.noalias() += rec.residual * df;
      }
    }
    const int ca = HarmonicBasis::cos_index(n), sb = HarmonicBasis::sin_index(n);
    for (int d = 0; d < n_c_; ++d) {
      R[d * s + ca] += r[d].real();
      if (n > 0) R[d * s + sb] -= r[d].imag();
      if (dR_domega) {
        (*dR_domega)[d * s + ca] += dr[d].real();
        if (n > 0) (*dR_domega)[d * s + sb] -= dr[d].imag();
      }
    }
  }
  if (statistics_) statistics_->receptance_seconds += CondensedStatistics::now() - started;
  return R;
}

CondensedJacobian CondensedHarmonicBalance::linearize(const Eigen::VectorXd& X,
                                                      double omega) const {
  if (!structure_)
    throw std::logic_error("CondensedHarmonicBalance::linearize needs the LocalForce form");
  if (X.size() != size())
    throw InputError({}, "X", fmt::format("{} coefficients", size()), std::to_string(X.size()));
  CondensedJacobian J(*this);
  J.omega_ = omega;
  Eigen::VectorXd F = Eigen::VectorXd::Zero(size()), dF = Eigen::VectorXd::Zero(size());
  evaluate_local(X, omega, F, &J.blocks_, &dF);
  J.R_ = receptance_residual(X, omega, F, &dF, &J.dR_domega_);
  const double started = statistics_ ? CondensedStatistics::now() : 0.0;
  for (int n = 0; n <= basis_.harmonics(); ++n)
    J.factors_.push_back(harmonics_[static_cast<std::size_t>(n)].modal_factors(n * omega));
  if (statistics_) {
    statistics_->receptance_seconds += CondensedStatistics::now() - started;
    ++statistics_->residual_evaluations;
    ++statistics_->linearizations;
  }
  return J;
}

Eigen::VectorXd CondensedHarmonicBalance::linear_response(double omega) const {
  const int s = basis_.size();
  Eigen::VectorXd X = Eigen::VectorXd::Zero(size());
  for (int n = 0; n <= basis_.harmonics(); ++n) {
    const Eigen::VectorXcd x = harmonics_[n].linear_response(n * omega);
    for (int d = 0; d < n_c_; ++d) {
      if (n == 0) {
        X[d * s] = x[d].real();
      } else {
        X[d * s + HarmonicBasis::cos_index(n)] = x[d].real();
        X[d * s + HarmonicBasis::sin_index(n)] = -x[d].imag();
      }
    }
  }
  return X;
}

Eigen::MatrixXd CondensedHarmonicBalance::nonlinear_jacobian(const Eigen::VectorXd& X,
                                                             double omega) const {
  const int s = basis_.size(), N = size();
  if (X.size() != N)
    throw InputError({}, "X", fmt::format("{} coefficients", N), std::to_string(X.size()));
  Eigen::MatrixXd Jn = Eigen::MatrixXd::Zero(N, N);
  Eigen::VectorXd F = Eigen::VectorXd::Zero(N);
  if (!structure_) {
    for (const auto& f : forces_) f(basis_, X, omega, F, &Jn, nullptr);
    return Jn;
  }
  std::vector<Eigen::MatrixXd> blocks;
  evaluate_local(X, omega, F, &blocks, nullptr);
  for (std::size_t k = 0; k < structure_->clusters.size(); ++k) {
    const auto& co = structure_->clusters[k].coordinates;
    for (std::size_t a = 0; a < co.size(); ++a)
      for (std::size_t b = 0; b < co.size(); ++b)
        Jn.block(co[a] * s, co[b] * s, s, s) = blocks[k].block(
            static_cast<Eigen::Index>(a) * s, static_cast<Eigen::Index>(b) * s, s, s);
  }
  return Jn;
}

Eigen::VectorXd CondensedHarmonicBalance::residual(const Eigen::VectorXd& X, double omega,
                                                   Eigen::MatrixXd* J,
                                                   Eigen::VectorXd* dR_domega) const {
  const int s = basis_.size(), N = size();
  if (X.size() != N)
    throw InputError({}, "X", fmt::format("{} coefficients", N), std::to_string(X.size()));
  if (structure_) {
    if (J || dR_domega) {
      const CondensedJacobian lin = linearize(X, omega);
      if (J) *J = lin.dense();
      if (dR_domega) *dR_domega = lin.omega_derivative();
      return lin.residual();
    }
    Eigen::VectorXd F = Eigen::VectorXd::Zero(N);
    evaluate_local(X, omega, F, nullptr, nullptr);
    if (statistics_) ++statistics_->residual_evaluations;
    return receptance_residual(X, omega, F, nullptr, nullptr);
  }
  double started = statistics_ ? CondensedStatistics::now() : 0.0;
  Eigen::VectorXd F = Eigen::VectorXd::Zero(N);
  Eigen::MatrixXd Jn;
  Eigen::VectorXd dF;
  if (J) Jn.setZero(N, N);
  if (dR_domega) dF.setZero(N);
  for (const auto& f : forces_)
    f(basis_, X, omega, F, J ? &Jn : nullptr, dR_domega ? &dF : nullptr);
  if (statistics_) {
    const double now = CondensedStatistics::now();
    statistics_->element_seconds += now - started;
    started = now;
    ++statistics_->residual_evaluations;
    if (J) ++statistics_->linearizations;
  }

  Eigen::VectorXd R = X;
  if (J) J->setIdentity(N, N);
  if (dR_domega) dR_domega->setZero(N);
  for (int n = 0; n <= basis_.harmonics(); ++n) {
    const ModalReceptance& rec = harmonics_[n];
    if (rec.modes() == 0 && rec.residual.size() == 0 && rec.residual_excitation.size() == 0)
      continue;  // the mean held at zero: R = X on these rows
    const double w = n * omega;
    Eigen::MatrixXcd dH;
    Eigen::VectorXcd dx;
    const Eigen::MatrixXcd H = rec.receptance(w, dR_domega ? &dH : nullptr);
    const Eigen::VectorXcd x_lin = rec.linear_response(w, dR_domega ? &dx : nullptr);
    const Eigen::VectorXcd f = complex_harmonic(F, n);
    const Eigen::VectorXcd r = H * f - x_lin;
    Eigen::VectorXcd dr;
    // d/d omega = n d/dw on H and x_lin, plus H dF/d omega.
    if (dR_domega) dr = double(n) * (dH * f - dx) + H * complex_harmonic(dF, n);
    std::vector<int> rows_a(n_c_), rows_b;
    for (int d = 0; d < n_c_; ++d) rows_a[d] = d * s + HarmonicBasis::cos_index(n);
    if (n > 0) {
      rows_b.resize(n_c_);
      for (int d = 0; d < n_c_; ++d) rows_b[d] = d * s + HarmonicBasis::sin_index(n);
    }
    for (int d = 0; d < n_c_; ++d) {
      R[rows_a[d]] += r[d].real();
      if (n > 0) R[rows_b[d]] -= r[d].imag();
      if (dR_domega) {
        (*dR_domega)[rows_a[d]] += dr[d].real();
        if (n > 0) (*dR_domega)[rows_b[d]] -= dr[d].imag();
      }
    }
    if (J) {
      // Rows a: H_r J_a + H_i J_b; rows b: -H_i J_a + H_r J_b (J_a, J_b: the rows of dF/dX).
      Eigen::MatrixXd Ja(n_c_, N), Jb;
      for (int d = 0; d < n_c_; ++d) Ja.row(d) = Jn.row(rows_a[d]);
      const Eigen::MatrixXd Hr = H.real(), Hi = H.imag();
      Eigen::MatrixXd A = Hr * Ja, B;
      if (n > 0) {
        Jb.resize(n_c_, N);
        for (int d = 0; d < n_c_; ++d) Jb.row(d) = Jn.row(rows_b[d]);
        A.noalias() += Hi * Jb;
        B = Hr * Jb;
        B.noalias() -= Hi * Ja;
      }
      for (int d = 0; d < n_c_; ++d) {
        J->row(rows_a[d]) += A.row(d);
        if (n > 0) J->row(rows_b[d]) += B.row(d);
      }
    }
  }
  if (statistics_) statistics_->receptance_seconds += CondensedStatistics::now() - started;
  return R;
}

double CondensedHarmonicBalance::residual_scale(const Eigen::VectorXd& X, double omega) const {
  const double s = X.norm() + linear_response(omega).norm();
  return s > 0.0 ? s : 1e-30;
}

Eigen::VectorXcd CondensedHarmonicBalance::sensor_response(const Eigen::VectorXd& X, double omega,
                                                           int n) const {
  const Eigen::VectorXcd f = complex_harmonic(nonlinear_forces(X, omega), n);
  return harmonics_.at(static_cast<std::size_t>(n)).sensor_response(n * omega, f);
}

namespace {

// out += H q for a structure whose harmonics share real modes (Structure::shared), s = 2H + 1
// coefficients per coordinate, `factors` the modal factors of each harmonic.
void apply_shared(const CondensedHarmonicBalance::Structure& st,
                  const std::vector<Eigen::VectorXcd>& factors, int s, int n_c,
                  const Eigen::VectorXd& q, Eigen::VectorXd& out) {
  // Q(c, d) = q[d s + c]: the coefficient columns side by side. Modal coefficients of each
  // column G = Q V; harmonic n's complex f = a - i b has V^T f = G_a - i G_b, scaled by the
  // factors d_n, and U (d_n V^T f) returns on rows a (real part) and b (minus the imaginary).
  const Eigen::Map<const Eigen::MatrixXd> Q(q.data(), s, n_c);
  Eigen::MatrixXd G = Q * st.shared_right;
  G.row(0).array() *= factors[0].real().transpose().array();
  for (int n = 1; 2 * n < s; ++n) {
    const int ca = HarmonicBasis::cos_index(n), sb = HarmonicBasis::sin_index(n);
    const Eigen::VectorXcd& d = factors[static_cast<std::size_t>(n)];
    const Eigen::RowVectorXd re = G.row(ca), im = -G.row(sb);
    G.row(ca) = d.real().transpose().cwiseProduct(re) - d.imag().transpose().cwiseProduct(im);
    G.row(sb) = -(d.real().transpose().cwiseProduct(im) + d.imag().transpose().cwiseProduct(re));
  }
  Eigen::Map<Eigen::MatrixXd> O(out.data(), s, n_c);
  O.noalias() += G * st.shared_left.transpose();
  if (st.shared_residual.size() > 0) O.noalias() += Q * st.shared_residual.transpose();
}

}  // namespace

Eigen::VectorXd CondensedJacobian::apply(const Eigen::VectorXd& v) const {
  const CondensedHarmonicBalance& sys = *system_;
  const auto& st = *sys.structure_;
  const int s = sys.basis_.size(), n_c = sys.n_c_;
  // q = J_nl v, cluster by cluster.
  Eigen::VectorXd q = Eigen::VectorXd::Zero(v.size()), local, product;
  for (std::size_t k = 0; k < st.clusters.size(); ++k) {
    const auto& coordinates = st.clusters[k].coordinates;
    const int nk = static_cast<int>(coordinates.size());
    local.resize(nk * s);
    for (int i = 0; i < nk; ++i)
      local.segment(i * s, s) = v.segment(coordinates[static_cast<std::size_t>(i)] * s, s);
    product.noalias() = blocks_[k] * local;
    for (int i = 0; i < nk; ++i)
      q.segment(coordinates[static_cast<std::size_t>(i)] * s, s) += product.segment(i * s, s);
  }
  // v + H q, harmonic by harmonic, H applied as its modal sum plus residual.
  Eigen::VectorXd out = v;
  if (st.shared) {
    apply_shared(st, factors_, s, n_c, q, out);
    return out;
  }
  for (int n = 0; n <= sys.basis_.harmonics(); ++n) {
    const ModalReceptance& rec = sys.harmonics_[static_cast<std::size_t>(n)];
    if (rec.modes() == 0 && rec.residual.size() == 0) continue;
    const Eigen::VectorXcd f = sys.complex_harmonic(q, n);
    Eigen::VectorXcd r =
        rec.left * factors_[static_cast<std::size_t>(n)].cwiseProduct(rec.right.adjoint() * f);
    if (rec.residual.size()) r.noalias() += rec.residual * f;
    const int ca = HarmonicBasis::cos_index(n), sb = HarmonicBasis::sin_index(n);
    for (int d = 0; d < n_c; ++d) {
      out[d * s + ca] += r[d].real();
      if (n > 0) out[d * s + sb] -= r[d].imag();
    }
  }
  return out;
}

Eigen::MatrixXd CondensedJacobian::dense() const {
  const CondensedHarmonicBalance& sys = *system_;
  const auto& st = *sys.structure_;
  const int s = sys.basis_.size(), n_c = sys.n_c_, N = sys.size();
  Eigen::MatrixXd J = Eigen::MatrixXd::Identity(N, N);
  for (int n = 0; n <= sys.basis_.harmonics(); ++n) {
    const ModalReceptance& rec = sys.harmonics_[static_cast<std::size_t>(n)];
    if (rec.modes() == 0 && rec.residual.size() == 0) continue;
    Eigen::MatrixXcd H =
        rec.left * factors_[static_cast<std::size_t>(n)].asDiagonal() * rec.right.adjoint();
    if (rec.residual.size()) H += rec.residual;
    const int ca = HarmonicBasis::cos_index(n), sb = HarmonicBasis::sin_index(n);
    // Rows a: H_r G_a + H_i G_b, rows b: -H_i G_a + H_r G_b, where G_a, G_b are the rows of
    // harmonic n of the cluster's block and H_r, H_i the receptance's columns of its coordinates
    // (J_nl vanishes outside the clusters).
    for (std::size_t k = 0; k < st.clusters.size(); ++k) {
      const auto& coordinates = st.clusters[k].coordinates;
      const int nk = static_cast<int>(coordinates.size());
      const Eigen::MatrixXd& G = blocks_[k];
      Eigen::MatrixXd Hr(n_c, nk), Hi(n_c, nk), Ga(nk, nk * s), Gb(nk, nk * s);
      for (int i = 0; i < nk; ++i) {
        const int d = coordinates[static_cast<std::size_t>(i)];
        Hr.col(i) = H.col(d).real();
        Hi.col(i) = H.col(d).imag();
        Ga.row(i) = G.row(i * s + ca);
        if (n > 0) Gb.row(i) = G.row(i * s + sb);
      }
      Eigen::MatrixXd A = Hr * Ga, B;
      if (n > 0) {
        A.noalias() += Hi * Gb;
        B = Hr * Gb;
        B.noalias() -= Hi * Ga;
      }
      for (int i = 0; i < nk; ++i)
        for (int c = 0; c < s; ++c) {
          const int col = coordinates[static_cast<std::size_t>(i)] * s + c, j = i * s + c;
          for (int d = 0; d < n_c; ++d) {
            J(d * s + ca, col) += A(d, j);
            if (n > 0) J(d * s + sb, col) += B(d, j);
          }
        }
    }
  }
  return J;
}

CondensedPreconditioner::CondensedPreconditioner(const CondensedHarmonicBalance& system,
                                                 const CondensedJacobian& J)
    : system_(&system), factors_(J.factors_) {
  if (!system.structure_)
    throw std::logic_error("CondensedPreconditioner needs the LocalForce form");
  const auto& st = *system.structure_;
  const int s = system.basis_.size(), n_c = system.n_c_, N = system.size();
  exact_ = !st.residual_couples_clusters;
  // Operation counts of a build and of one application of J and M^{-1} (rebuild_cost).
  double build = 0.0, apply = 0.0;
  {
    const double k = st.capacity;
    for (int n = 0; n <= system.basis_.harmonics(); ++n) {
      const ModalReceptance& rec = system.harmonics_[static_cast<std::size_t>(n)];
      const double rows = n == 0 ? n_c : 2.0 * n_c,
                   columns = st.modal[static_cast<std::size_t>(n)].columns();
      build += 2.0 * columns * rows * k;
      apply += 8.0 * n_c * static_cast<double>(rec.modes()) * 2.0 + 4.0 * rows * columns;
      if (rec.residual.size()) apply += 8.0 * n_c * n_c;
    }
    build += 2.0 / 3.0 * k * k * k;
    apply += 2.0 * k * k;
    for (const auto& c : st.clusters) {
      const double coordinates = static_cast<double>(c.coordinates.size()), q = coordinates * s;
      build += (c.residual.size() ? 4.0 * q * q * q : 0.0) + 4.0 * q * coordinates * k;
      apply += (c.residual.size() ? 8.0 : 4.0) * q * q;
    }
  }
  rebuild_cost_ = build / std::max(apply, 1.0);
  // B = J_nl (I + R_b J_nl)^{-1}, cluster by cluster.
  B_.resize(st.clusters.size());
  for (std::size_t k = 0; k < st.clusters.size(); ++k) {
    const Eigen::MatrixXd& G = J.blocks_[k];
    const Eigen::MatrixXd& Rb = st.clusters[k].residual;
    if (Rb.size() == 0) {
      B_[k] = G;
      continue;
    }
    Eigen::MatrixXd A = Rb * G;
    A.diagonal().array() += 1.0;
    B_[k] = G * A.partialPivLu().inverse();
    if (!B_[k].allFinite()) status_ = Status::Singular;
  }
  const int k_total = st.capacity;
  if (k_total == 0) return;
  // S = V^T B U, with Z = B U formed cluster by cluster in the rows of the real form of each
  // harmonic (coefficient-major: row c n_c + d for coefficient c of coordinate d, so harmonic
  // n >= 1 is the contiguous rows (2n - 1) n_c .. (2n + 1) n_c, a then b).
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(N, k_total);
  const int H = system.basis_.harmonics();
  for (std::size_t k = 0; k < st.clusters.size(); ++k) {
    const auto& coordinates = st.clusters[k].coordinates;
    const int nk = static_cast<int>(coordinates.size());
    for (int n = 0; n <= H; ++n) {
      const auto& m = st.modal[static_cast<std::size_t>(n)];
      if (m.columns() == 0) continue;
      const int per = n == 0 ? 1 : 2;
      Eigen::MatrixXd Bc(nk * s, per * nk), Ur(per * nk, m.columns());
      for (int i = 0; i < nk; ++i) {
        const int d = coordinates[static_cast<std::size_t>(i)];
        Bc.col(per * i) = B_[k].col(i * s + HarmonicBasis::cos_index(n));
        Ur.row(per * i) = m.U.row(a_row(d));
        if (n > 0) {
          Bc.col(per * i + 1) = B_[k].col(i * s + HarmonicBasis::sin_index(n));
          Ur.row(per * i + 1) = m.U.row(b_row(d, n_c));
        }
      }
      const Eigen::MatrixXd block = Bc * Ur;
      for (int i = 0; i < nk; ++i)
        for (int c = 0; c < s; ++c)
          Z.block(c * n_c + coordinates[static_cast<std::size_t>(i)], m.offset, 1, m.columns()) =
              block.row(i * s + c);
    }
  }
  capacitance_.setIdentity(k_total, k_total);
  for (int n = 0; n <= H; ++n) {
    const auto& m = st.modal[static_cast<std::size_t>(n)];
    if (m.columns() == 0) continue;
    const int first = n == 0 ? 0 : (2 * n - 1) * n_c;
    Eigen::MatrixXd S = m.V.transpose() * Z.middleRows(first, m.V.rows());
    // Rows times D: per mode the complex factor in real form (paired), or the real factor.
    const Eigen::VectorXcd& f = factors_[static_cast<std::size_t>(n)];
    const int q = m.modes;
    if (m.paired) {
      for (int r = 0; r < q; ++r) {
        const Eigen::RowVectorXd re = S.row(r), im = S.row(q + r);
        S.row(r) = f[r].real() * re + f[r].imag() * im;
        S.row(q + r) = -f[r].imag() * re + f[r].real() * im;
      }
    } else {
      for (int r = 0; r < m.columns(); ++r) S.row(r) *= f[r % q].real();
    }
    capacitance_.middleRows(m.offset, m.columns()) += S;
  }
  lu_.compute(capacitance_);
  if (!lu_.matrixLU().allFinite()) status_ = Status::Singular;
}

Eigen::VectorXd CondensedPreconditioner::solve(const Eigen::VectorXd& r) const {
  const CondensedHarmonicBalance& sys = *system_;
  const auto& st = *sys.structure_;
  const int s = sys.basis_.size(), n_c = sys.n_c_;
  // Cluster-local products: out += sign R_b B x on each cluster; q = B x when asked.
  Eigen::VectorXd local, product;
  auto cluster_pass = [&](const Eigen::VectorXd& x, Eigen::VectorXd* q, Eigen::VectorXd& out,
                          double sign) {
    for (std::size_t k = 0; k < st.clusters.size(); ++k) {
      const auto& coordinates = st.clusters[k].coordinates;
      const int nk = static_cast<int>(coordinates.size());
      local.resize(nk * s);
      for (int i = 0; i < nk; ++i)
        local.segment(i * s, s) = x.segment(coordinates[static_cast<std::size_t>(i)] * s, s);
      product.noalias() = B_[k] * local;
      if (q)
        for (int i = 0; i < nk; ++i)
          q->segment(coordinates[static_cast<std::size_t>(i)] * s, s) = product.segment(i * s, s);
      const Eigen::MatrixXd& Rb = st.clusters[k].residual;
      if (Rb.size() == 0) continue;
      local.noalias() = Rb * product;
      for (int i = 0; i < nk; ++i)
        out.segment(coordinates[static_cast<std::size_t>(i)] * s, s) +=
            sign * local.segment(i * s, s);
    }
  };
  // u = (I - R_b B) r, q = B r.
  Eigen::VectorXd q = Eigen::VectorXd::Zero(r.size());
  Eigen::VectorXd out = r;
  cluster_pass(r, &q, out, -1.0);
  const int k_total = static_cast<int>(capacitance_.rows());
  if (k_total == 0) return out;
  // c = (I + D V^T B U)^{-1} D V^T q.
  Eigen::VectorXd g(k_total), rows;
  const int H = sys.basis_.harmonics();
  for (int n = 0; n <= H; ++n) {
    const auto& m = st.modal[static_cast<std::size_t>(n)];
    if (m.columns() == 0) continue;
    const int per = n == 0 ? 1 : 2;
    rows.resize(per * n_c);
    for (int d = 0; d < n_c; ++d) {
      rows[a_row(d)] = q[d * s + HarmonicBasis::cos_index(n)];
      if (n > 0) rows[b_row(d, n_c)] = q[d * s + HarmonicBasis::sin_index(n)];
    }
    auto gn = g.segment(m.offset, m.columns());
    gn.noalias() = m.V.transpose() * rows;
    const Eigen::VectorXcd& f = factors_[static_cast<std::size_t>(n)];
    const int qm = m.modes;
    if (m.paired) {
      for (int i = 0; i < qm; ++i) {
        const double re = gn[i], im = gn[qm + i];
        gn[i] = f[i].real() * re + f[i].imag() * im;
        gn[qm + i] = -f[i].imag() * re + f[i].real() * im;
      }
    } else {
      for (int i = 0; i < m.columns(); ++i) gn[i] *= f[i % qm].real();
    }
  }
  const Eigen::VectorXd c = lu_.solve(g);
  // out = u - (I - R_b B) U c.
  Eigen::VectorXd w = Eigen::VectorXd::Zero(r.size());
  for (int n = 0; n <= H; ++n) {
    const auto& m = st.modal[static_cast<std::size_t>(n)];
    if (m.columns() == 0) continue;
    rows.noalias() = m.U * c.segment(m.offset, m.columns());
    for (int d = 0; d < n_c; ++d) {
      w[d * s + HarmonicBasis::cos_index(n)] = rows[a_row(d)];
      if (n > 0) w[d * s + HarmonicBasis::sin_index(n)] = rows[b_row(d, n_c)];
    }
  }
  out -= w;
  cluster_pass(w, nullptr, out, 1.0);
  return out;
}

}  // namespace geardyn::hbm
