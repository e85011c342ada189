// GCC's -Wnull-dereference false positive inside Eigen's and <complex>'s inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "geardyn/core/error.hpp"
#include "geardyn/damper/damper_ring.hpp"
#include "geardyn/eig/hermitian_eigen.hpp"
#include "geardyn/hbm/stability.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::damper {

using cd = std::complex<double>;

namespace {

std::map<std::pair<long, int>, Eigen::Index> dof_index(const std::vector<solid::DofInfo>& dofs) {
  std::map<std::pair<long, int>, Eigen::Index> m;
  for (std::size_t i = 0; i < dofs.size(); ++i)
    m[{dofs[i].node_id, dofs[i].component}] = static_cast<Eigen::Index>(i);
  return m;
}

// Cylindrical unit vectors (e_r, e_theta, e_z) at x about the z axis.
std::array<Eigen::Vector3d, 3> cylindrical_frame(const Eigen::Vector3d& x) {
  Eigen::Vector3d er(x[0], x[1], 0.0);
  er.normalize();
  const Eigen::Vector3d ez = Eigen::Vector3d::UnitZ();
  return {er, ez.cross(er), ez};
}

// Rows of the contact coordinates of one pair in the local frame (see the header).
std::vector<Eigen::Vector3d> coordinate_directions(const ContactLaw& law,
                                                   const Eigen::Vector3d& x) {
  const auto [er, et, ez] = cylindrical_frame(x);
  if (law.tangential_directions == 2) return {er, et, ez};
  return {er, std::cos(law.inclination) * et + std::sin(law.inclination) * ez};
}

hbm::FrictionContact friction_contact(const ContactLaw& law, double preload) {
  hbm::FrictionContact c;
  c.tangential_directions = law.tangential_directions;
  c.normal_stiffness = law.normal_stiffness;
  c.tangential_stiffness = law.tangential_stiffness;
  c.friction_coefficient = law.friction_coefficient;
  c.normal_preload = preload;
  return c;
}

}  // namespace

ContactPairing pair_contact_nodes(const std::vector<solid::DofInfo>& dofs,
                                  const std::vector<long>& gear_nodes,
                                  const std::vector<long>& ring_nodes,
                                  const cyclic::SectorInterfaces& interfaces, double tolerance,
                                  const std::string& key) {
  if (gear_nodes.size() != ring_nodes.size() || gear_nodes.empty())
    throw InputError(
        {}, key, "as many ring contact nodes as gear contact nodes (at least one)",
        fmt::format("{} gear and {} ring nodes", gear_nodes.size(), ring_nodes.size()));
  std::map<long, Eigen::Vector3d> position;
  for (const auto& d : dofs) position[d.node_id] = d.x;
  auto where = [&](long id) {
    const auto it = position.find(id);
    if (it == position.end())
      throw InputError({}, key, "contact nodes that carry DOFs",
                       fmt::format("node {} has none", id));
    return it->second;
  };
  std::set<long> right;
  for (const auto& p : interfaces.pairs) right.insert(p.right_node_id);
  ContactPairing out;
  std::set<long> used;
  for (long g : gear_nodes) {
    const Eigen::Vector3d xg = where(g);
    double best = std::numeric_limits<double>::infinity();
    long partner = 0;
    for (long r : ring_nodes) {
      const double d = (where(r) - xg).norm();
      if (d < best) {
        best = d;
        partner = r;
      }
    }
    if (best > out.worst_gap) {
      out.worst_gap = best;
      out.worst_gear_node = g;
    }
    if (!(best <= tolerance))
      throw InputError(
          {}, key,
          fmt::format("each gear contact node coincident with a ring contact node "
                      "(tolerance {:.3g} m)",
                      tolerance),
          fmt::format("gear node {} is {:.3g} m from the nearest ring node {}", g, best, partner),
          "the contact pairs must be meshed as coincident node twins "
          "(meshgen::gear_sector does this)");
    if (!used.insert(partner).second)
      throw InputError({}, key, "one ring node per gear node",
                       fmt::format("ring node {} is nearest to two gear nodes", partner));
    if (right.count(g)) {
      ++out.dropped_on_right_interface;
      continue;
    }
    out.pairs.push_back({g, partner, xg});
  }
  return out;
}

cyclic::SectorInterfaces two_body_interfaces(const std::vector<solid::DofInfo>& dofs,
                                             const cyclic::InterfaceOptions& options,
                                             const std::vector<long>& gear_left,
                                             const std::vector<long>& gear_right,
                                             const std::vector<long>& ring_left,
                                             const std::vector<long>& ring_right) {
  std::set<long> with_dofs;  // physical DOFs only (a reduced sector's modal DOFs have -1)
  for (const auto& d : dofs)
    if (d.component >= 0) with_dofs.insert(d.node_id);
  auto kept = [&](const std::vector<long>& ids) {
    std::vector<long> out;
    for (long id : ids)
      if (with_dofs.count(id)) out.push_back(id);
    return out;
  };
  cyclic::InterfaceOptions o = options;
  o.left_nodes = kept(gear_left);
  o.right_nodes = kept(gear_right);
  cyclic::SectorInterfaces gear = cyclic::find_interfaces(dofs, o);
  o.left_nodes = kept(ring_left);
  o.right_nodes = kept(ring_right);
  const cyclic::SectorInterfaces ring = cyclic::find_interfaces(dofs, o);
  gear.pairs.insert(gear.pairs.end(), ring.pairs.begin(), ring.pairs.end());
  std::sort(gear.pairs.begin(), gear.pairs.end(),
            [](const auto& a, const auto& b) { return a.left_node_id < b.left_node_id; });
  if (ring.worst_mismatch > gear.worst_mismatch) {
    gear.worst_mismatch = ring.worst_mismatch;
    gear.worst_left_node = ring.worst_left_node;
  }
  return gear;
}

hbm::CondensedHarmonicBalance DamperRingModel::system(const ContactLaw& law) const {
  std::vector<hbm::LocalForce> forces;
  const int cp = coordinates_per_pair;
  const double c = preload_per_speed_squared;
  const double k = engine_order;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    std::vector<int> coords;
    for (int j = 0; j < cp; ++j) coords.push_back(static_cast<int>(p) * cp + j);
    // N0 = c W^2 = (c / k^2) omega^2. With k_n > 0 the element gives df/domega exactly (no extra
    // march); with a constant normal load (k_n = 0) the preload is differentiated numerically.
    if (law.normal_stiffness > 0.0) {
      forces.push_back(
          hbm::local_friction_contact(coords, friction_contact(law, 0.0), c / (k * k)));
      continue;
    }
    hbm::LocalForce f;
    f.coordinates = std::move(coords);
    f.evaluate = [law, c, k](const hbm::HarmonicBasis& b, const Eigen::VectorXd& w, double omega,
                             Eigen::VectorXd& force, Eigen::MatrixXd* J,
                             Eigen::VectorXd* df_domega) {
      const double speed = omega / k;
      const double N0 = c * speed * speed;
      const hbm::ContactResponse r =
          hbm::friction_contact_response(friction_contact(law, N0), b, w);
      force += r.coefficients;
      if (J) *J += r.jacobian;
      if (df_domega && c > 0.0) {
        // dN0/domega = 2 c omega / k^2; df/dN0 by central differences (the law is piecewise
        // smooth in N0; the step is far below any switching scale).
        const double h = 1e-6 * std::max(N0, 1e-12);
        const double lo = std::max(N0 - h, 0.0);
        const Eigen::VectorXd up =
            hbm::friction_contact_response(friction_contact(law, N0 + h), b, w).coefficients;
        const Eigen::VectorXd down =
            hbm::friction_contact_response(friction_contact(law, lo), b, w).coefficients;
        *df_domega += (up - down) / (N0 + h - lo) * (2.0 * c * omega / (k * k));
      }
    };
    forces.push_back(std::move(f));
  }
  return hbm::CondensedHarmonicBalance(coordinates(), basis, receptances, std::move(forces));
}

Eigen::VectorXcd DamperRingModel::free_response(double speed) const {
  const hbm::ModalReceptance& r = receptances.at(1);
  return r.sensor_response(engine_order * speed, Eigen::VectorXcd::Zero(coordinates()));
}

Eigen::VectorXcd DamperRingModel::stuck_response(double speed) const {
  return StuckRingResponse(*this)(speed);
}

StuckRingResponse::StuckRingResponse(const DamperRingModel& model)
    : receptance_(&model.receptances.at(1)), engine_order_(model.engine_order) {
  const hbm::ModalReceptance& r = *receptance_;
  const Eigen::Index n = model.coordinates();
  kc_.resize(n);
  for (Eigen::Index i = 0; i < n; ++i)
    kc_[i] = i % model.coordinates_per_pair == 0 ? model.contact.normal_stiffness
                                                 : model.contact.tangential_stiffness;
  Eigen::MatrixXcd B = Eigen::MatrixXcd::Identity(n, n);
  if (r.residual.size() > 0) B += r.residual * kc_.asDiagonal();
  b_lu_.compute(B);
  w_ = r.right.adjoint() * kc_.asDiagonal();
  p_ = b_lu_.solve(r.left);
  q_ = w_ * p_;
}

Eigen::VectorXcd StuckRingResponse::operator()(double speed) const {
  const hbm::ModalReceptance& r = *receptance_;
  const double w = engine_order_ * speed;
  const Eigen::VectorXcd f = r.modal_factors(w);
  const Eigen::VectorXcd y = b_lu_.solve(r.linear_response(w));
  Eigen::MatrixXcd small = q_ * f.asDiagonal();
  small += Eigen::MatrixXcd::Identity(small.rows(), small.cols());
  const Eigen::VectorXcd x =
      y - p_ * f.cwiseProduct(small.partialPivLu().solve(Eigen::VectorXcd(w_ * y)));
  return r.sensor_response(w, kc_.cast<cd>().cwiseProduct(x));
}

namespace {

// The checks of the problem that need no modes.
void check_problem(const DamperRingProblem& p) {
  if (p.pairs.empty())
    throw InputError({}, "damper_ring.contact", "at least one contact pair", "none");
  if (p.contact.tangential_directions != 1 && p.contact.tangential_directions != 2)
    throw InputError({}, "damper_ring.contact", "2d or 3d",
                     std::to_string(p.contact.tangential_directions + 1) + "d");
  hbm::validate(friction_contact(p.contact, 0.0));
  if (!(p.ring_mass >= 0.0 && p.ring_radius > 0.0))
    throw InputError({}, "damper_ring.ring", "a ring of non-negative mass and positive radius",
                     fmt::format("mass {} kg, radius {} m", p.ring_mass, p.ring_radius));
  if (p.ring_mass == 0.0 && p.contact.friction_coefficient == 0.0)
    throw InputError({}, "damper_ring.contact",
                     "friction or a centrifugal preload (zero friction together with zero "
                     "preload transmits no friction force: the ring cannot damp)",
                     "friction coefficient 0 and ring mass 0",
                     "give the ring its density and the contact its friction coefficient");
  if (p.loads.empty() || static_cast<int>(p.loads.size()) > p.harmonics)
    throw InputError({}, "damper_ring.loads",
                     fmt::format("loads for 1 .. {} harmonics", p.harmonics),
                     std::to_string(p.loads.size()));
  if (const auto problems = p.damping.validate(); !problems.empty())
    throw InputError({}, "damper_ring.damping", "a valid modal damping", problems.front());
  if (p.harmonics < 1)
    throw InputError({}, "damper_ring.harmonics", "at least 1", std::to_string(p.harmonics));
}

// Contact coordinates (G) and sensors (Gs) from sector DOFs, and the sector-0 load of each loaded
// harmonic.
struct SectorProjections {
  Eigen::SparseMatrix<cd> G, Gs;
  std::vector<Eigen::VectorXcd> f0;
};

SectorProjections sector_projections(const DamperRingModel& m, const DamperRingProblem& p,
                                     const cyclic::CyclicSector& sector) {
  SectorProjections out;
  const auto index = dof_index(sector.dofs());
  const Eigen::Index n_dof = sector.num_dofs();
  auto dof = [&](long node, int comp, const std::string& what) {
    const auto it = index.find({node, comp});
    if (it == index.end())
      throw InputError({}, what, "a node with translational DOFs in the sector",
                       fmt::format("node {} component {}", node, comp));
    return it->second;
  };
  // G: contact coordinates from sector DOFs; Gs: sensors.
  const int n_c = m.coordinates();
  std::vector<Eigen::Triplet<double>> tg;
  for (std::size_t q = 0; q < p.pairs.size(); ++q) {
    const auto dirs = coordinate_directions(p.contact, p.pairs[q].position);
    for (std::size_t j = 0; j < dirs.size(); ++j) {
      const int row = static_cast<int>(q) * m.coordinates_per_pair + static_cast<int>(j);
      for (int c = 0; c < 3; ++c) {
        if (dirs[j][c] == 0.0) continue;
        tg.emplace_back(row, dof(p.pairs[q].ring_node, c, "damper_ring.contact"), dirs[j][c]);
        tg.emplace_back(row, dof(p.pairs[q].gear_node, c, "damper_ring.contact"), -dirs[j][c]);
      }
    }
  }
  Eigen::SparseMatrix<cd>& G = out.G;
  G.resize(n_c, n_dof);
  {
    std::vector<Eigen::Triplet<cd>> t;
    for (const auto& e : tg) t.emplace_back(e.row(), e.col(), cd(e.value(), 0.0));
    G.setFromTriplets(t.begin(), t.end());
  }
  const Eigen::Index n_s = static_cast<Eigen::Index>(p.sensors.size());
  Eigen::SparseMatrix<cd>& Gs = out.Gs;
  Gs.resize(n_s, n_dof);
  {
    std::vector<Eigen::Triplet<cd>> t;
    for (Eigen::Index i = 0; i < n_s; ++i)
      t.emplace_back(i,
                     dof(p.sensors[static_cast<std::size_t>(i)].node_id,
                         p.sensors[static_cast<std::size_t>(i)].component, "damper_ring.sensors"),
                     cd(1.0, 0.0));
    Gs.setFromTriplets(t.begin(), t.end());
  }
  // Sector-0 load of each loaded harmonic (engine order n k).
  std::vector<Eigen::VectorXcd>& f0 = out.f0;
  f0.assign(p.loads.size(), Eigen::VectorXcd::Zero(n_dof));
  for (std::size_t n = 0; n < p.loads.size(); ++n)
    for (const auto& l : p.loads[n])
      for (int c = 0; c < 3; ++c) f0[n][dof(l.node_id, c, "damper_ring.excitation")] += l.force[c];
  return out;
}

// The receptances of the harmonics on nodal diameter nd: the retained modes plus the residual
// flexibility of the others, and their excitation.
void add_diameter_receptances(DamperRingModel& m, const DamperRingProblem& p,
                              const cyclic::CyclicSector& sector,
                              const cyclic::NodalDiameterModes& nd, const SectorProjections& proj) {
  const int H = p.harmonics;
  const Eigen::SparseMatrix<cd>& G = proj.G;
  const Eigen::SparseMatrix<cd>& Gs = proj.Gs;
  const std::vector<Eigen::VectorXcd>& f0 = proj.f0;
  const int h = nd.nodal_diameter;
  const Eigen::SparseMatrix<cd> T = sector.transformation(h);
  const Eigen::SparseMatrix<cd> Kh = sector.reduce(p.K, h), Mh = sector.reduce(p.M, h);
  const double sigma = eig::automatic_shift(Kh, Mh);
  linalg::SparseLU<cd> lu;
  const Eigen::SparseMatrix<cd> shifted = Kh - cd(sigma, 0.0) * Mh;
  // K - sigma M with sigma below the spectrum: well conditioned, no iterative refinement
  // (the residual flexibility solves one right-hand side per contact coordinate).
  if (lu.compute(shifted, false) != Status::Ok)
    throw NumericalError(
        "damper_ring",
        fmt::format("nodal diameter {}: the shifted stiffness is singular ({})", h, lu.message()));
  const Eigen::SparseMatrix<cd> A = G * T, As = Gs * T;
  const Eigen::MatrixXcd Y = lu.solve(Eigen::MatrixXcd(Eigen::MatrixXcd(A.adjoint())));
  const Eigen::MatrixXcd static_cc = A * Y, static_sc = As * Y;
  const Eigen::MatrixXcd& psi = nd.sector_shapes;
  const Eigen::VectorXd lambda = nd.eigen.eigenvalues;
  const Eigen::Index n_m = lambda.size();
  Eigen::VectorXd w(n_m), zeta(n_m), inv_shifted(n_m);
  for (Eigen::Index r = 0; r < n_m; ++r) {
    w[r] = std::sqrt(std::max(lambda[r], 0.0));
    zeta[r] = p.damping.ratio(r);
    inv_shifted[r] = 1.0 / (lambda[r] - sigma);
  }
  const Eigen::MatrixXcd U = G * psi, S = Gs * psi;
  const Eigen::MatrixXcd R_cc = static_cc - U * inv_shifted.asDiagonal() * U.adjoint();
  const Eigen::MatrixXcd R_sc = static_sc - S * inv_shifted.asDiagonal() * U.adjoint();
  for (int n = 1; n <= H; ++n) {
    if (m.harmonic_diameter[n] != h) continue;
    const bool conj = m.harmonic_conjugate[n];
    hbm::ModalReceptance& rec = m.receptances[static_cast<std::size_t>(n)];
    rec.natural_frequency = w;
    rec.damping_ratio = zeta;
    rec.left = conj ? Eigen::MatrixXcd(U.conjugate()) : U;
    rec.right = rec.left;
    rec.residual = conj ? Eigen::MatrixXcd(R_cc.conjugate()) : R_cc;
    rec.sensor_left = conj ? Eigen::MatrixXcd(S.conjugate()) : S;
    rec.sensor_residual = conj ? Eigen::MatrixXcd(R_sc.conjugate()) : R_sc;
    if (n <= static_cast<int>(f0.size())) {
      // The excitation: for the conjugate pattern everything is the conjugate of the
      // nodal-diameter-h response to conj(f0) (H_{-h} = conj H_h).
      const Eigen::VectorXcd& fn = f0[static_cast<std::size_t>(n - 1)];
      const Eigen::VectorXcd f = conj ? Eigen::VectorXcd(fn.conjugate()) : fn;
      const Eigen::VectorXcd yb = lu.solve(Eigen::VectorXcd(T.adjoint() * f));
      const Eigen::VectorXcd pm = psi.adjoint() * f;
      const Eigen::VectorXcd r_cf = A * yb - U * (inv_shifted.cast<cd>().cwiseProduct(pm));
      const Eigen::VectorXcd r_sf = As * yb - S * (inv_shifted.cast<cd>().cwiseProduct(pm));
      rec.modal_excitation = conj ? Eigen::VectorXcd(pm.conjugate()) : pm;
      rec.residual_excitation = conj ? Eigen::VectorXcd(r_cf.conjugate()) : r_cf;
      rec.sensor_residual_excitation = conj ? Eigen::VectorXcd(r_sf.conjugate()) : r_sf;
    }
  }
}

void add_notes(DamperRingModel& m, const DamperRingProblem& p,
               const response::OrderRelation& relation) {
  const int H = p.harmonics;
  m.notes.push_back(fmt::format(
      "Damper ring: {} contact pairs per sector ({} coordinates each), engine order {} on nodal "
      "diameter {} ({} wave); harmonics 1..{} on nodal diameters {}; {} time samples per period; "
      "{} modes per nodal diameter plus the residual flexibility of the others; the mean held at "
      "the preloaded equilibrium.",
      p.pairs.size(), m.coordinates_per_pair, p.engine_order, p.nodal_diameter,
      response::to_string(relation.wave), H,
      [&] {
        std::string s;
        for (int n = 1; n <= H; ++n)
          s += fmt::format("{}{}{}", n > 1 ? ", " : "", m.harmonic_diameter[n],
                           m.harmonic_conjugate[n] ? "*" : "");
        return s;
      }(),
      m.basis.time_samples(), p.n_modes));
  m.notes.push_back(fmt::format(
      "Centrifugal preload per contact N0 = m_ring W^2 r_G / (N n_pairs) = {:.6g} W^2 N "
      "(m_ring {:.6g} kg, r_G {:.6g} m).",
      m.preload_per_speed_squared, p.ring_mass, p.ring_radius));
}

}  // namespace

DamperRingModel build_damper_ring_model(const DamperRingProblem& p, Progress& progress) {
  if (!p.sector) throw InputError({}, "damper_ring.sector", "the cyclic sector", "none");
  const cyclic::CyclicSector& sector = *p.sector;
  const int N = sector.n_sectors();
  const response::OrderRelation relation =
      response::relate_order(N, p.nodal_diameter, p.engine_order);
  check_problem(p);

  DamperRingModel m;
  m.n_sectors = N;
  m.nodal_diameter = p.nodal_diameter;
  m.engine_order = p.engine_order;
  m.contact = p.contact;
  m.pairs = p.pairs;
  m.coordinates_per_pair = 1 + p.contact.tangential_directions;
  m.preload_per_speed_squared =
      p.ring_mass * p.ring_radius / (N * static_cast<double>(p.pairs.size()));
  const int H = p.harmonics;
  m.basis =
      hbm::HarmonicBasis(H, p.time_samples > 0 ? p.time_samples : hbm::default_time_samples(H));
  for (const auto& s : p.sensors) m.sensor_names.push_back(s.name);

  // Nodal diameter of each harmonic: pattern of engine order n k.
  m.harmonic_diameter.assign(H + 1, 0);
  m.harmonic_conjugate.assign(H + 1, false);
  std::set<int> diameters;
  for (int n = 1; n <= H; ++n) {
    const int pattern = static_cast<int>((static_cast<long>(n) * p.engine_order) % N);
    m.harmonic_diameter[n] = std::min(pattern, N - pattern);
    m.harmonic_conjugate[n] = 2 * pattern > N;
    diameters.insert(m.harmonic_diameter[n]);
  }

  const int n_c = m.coordinates();
  const Eigen::Index n_s = static_cast<Eigen::Index>(p.sensors.size());
  const SectorProjections proj = sector_projections(m, p, sector);

  // Modes of every nodal diameter used.
  cyclic::CyclicModesOptions mo;
  mo.nodal_diameters.assign(diameters.begin(), diameters.end());
  mo.eigen.n_modes = p.n_modes;
  progress.start("damper ring: cyclic modes", 0);
  const cyclic::CyclicModesResult modes = cyclic::solve_cyclic_modes(p.K, p.M, sector, mo);
  progress.finish();
  if (modes.status != Status::Ok)
    throw NumericalError("damper_ring", "cyclic modes: " + modes.message);

  m.receptances.assign(H + 1, hbm::ModalReceptance{});
  progress.start("damper ring: residual flexibility and excitation", 0);
  for (const auto& nd : modes.diameters) {
    add_diameter_receptances(m, p, sector, nd, proj);
  }
  progress.finish();
  // Harmonic 0 stays empty: the mean held at the preloaded equilibrium.
  m.receptances[0].left.resize(n_c, 0);
  m.receptances[0].right.resize(n_c, 0);
  m.receptances[0].sensor_left.resize(n_s, 0);

  add_notes(m, p, relation);
  return m;
}

namespace {

// The linear references (free and stuck ring) and the amplitude scale of the continuation.
double linear_references(const DamperRingModel& m, const DamperRingOptions& o, Progress& progress,
                         DamperRingResult& out) {
  const double k = m.engine_order;
  const Eigen::Index n_s = static_cast<Eigen::Index>(m.sensor_names.size());
  // Linear references.
  progress.start("damper ring: linear references", 0);
  const int nl = std::max(o.linear_points, 2);
  out.linear_speeds = Eigen::VectorXd::LinSpaced(nl, o.speed_min, o.speed_max);
  out.free_amplitude.resize(nl, n_s);
  out.stuck_amplitude.resize(nl, n_s);
  double x_scale = 0.0;
  const hbm::ModalReceptance& r1 = m.receptances.at(1);
  const StuckRingResponse stuck(m);
  for (int i = 0; i < nl; ++i) {
    out.free_amplitude.row(i) = m.free_response(out.linear_speeds[i]).cwiseAbs().transpose();
    out.stuck_amplitude.row(i) = stuck(out.linear_speeds[i]).cwiseAbs().transpose();
  }
  // The amplitude scale of the continuation: the largest linear response on a grid fine enough
  // to meet a lightly damped resonance of the range (independent of linear_points).
  const int n_scale = std::max(nl, 1000);
  for (int i = 0; i < n_scale; ++i) {
    const double speed = o.speed_min + (o.speed_max - o.speed_min) * i / (n_scale - 1.0);
    x_scale = std::max(x_scale, r1.linear_response(k * speed).norm());
  }
  progress.finish();
  return x_scale;
}

// One point of the damped branch: sensor harmonics and peaks, contact states and energy.
DampedPoint damped_point(const DamperRingModel& m, const hbm::CondensedHarmonicBalance& hb,
                         const hbm::ContinuationPoint& pt) {
  const double k = m.engine_order;
  const Eigen::Index n_s = static_cast<Eigen::Index>(m.sensor_names.size());
  const hbm::HarmonicBasis& b = m.basis;
  const int cp = m.coordinates_per_pair, s = b.size();
  const int H = b.harmonics();
  DampedPoint d;
  d.speed = pt.omega / k;
  d.iterations = pt.iterations;
  d.amplitude.resize(n_s);
  d.peak.setZero(n_s);
  d.harmonics.resize(H, n_s);
  Eigen::MatrixXd signal = Eigen::MatrixXd::Zero(b.time_samples(), n_s);
  for (int n = 1; n <= H; ++n) {
    const Eigen::VectorXcd z = hb.sensor_response(pt.X, pt.omega, n);
    if (n == 1) d.amplitude = z.cwiseAbs();
    d.harmonics.row(n - 1) = z.cwiseAbs().transpose();
    for (Eigen::Index i = 0; i < n_s; ++i) {
      Eigen::VectorXd c = Eigen::VectorXd::Zero(s);
      c[hbm::HarmonicBasis::cos_index(n)] = z[i].real();
      c[hbm::HarmonicBasis::sin_index(n)] = -z[i].imag();
      signal.col(i) += b.to_time(c);
    }
  }
  d.peak = signal.cwiseAbs().colwise().maxCoeff().transpose();
  const double N0 = m.preload(d.speed);
  double stick = 0, slip = 0, lift = 0, energy = 0;
  for (std::size_t q = 0; q < m.pairs.size(); ++q) {
    const Eigen::VectorXd w = pt.X.segment(static_cast<Eigen::Index>(q) * cp * s, cp * s);
    const hbm::ContactResponse r =
        hbm::friction_contact_response(friction_contact(m.contact, N0), b, w);
    stick += r.stick_fraction;
    slip += r.slip_fraction;
    lift += r.lift_off_fraction;
    energy += r.energy_per_cycle;
    d.loops_closed = d.loops_closed && r.loop_closed;
  }
  const double np = static_cast<double>(m.pairs.size());
  d.stick = stick / np;
  d.slip = slip / np;
  d.lift_off = lift / np;
  d.energy_per_cycle = energy * m.n_sectors;
  return d;
}

// Fold-type instability: the branch after an odd number of turning points in speed.
void mark_fold_instability(DamperRingResult& out) {
  std::vector<double> speeds;
  for (const auto& d : out.damped) speeds.push_back(d.speed);
  const std::vector<char> unstable = hbm::fold_unstable(speeds);
  for (std::size_t i = 0; i < out.damped.size(); ++i) {
    out.damped[i].fold_unstable = unstable[i] != 0;
    if (i > 0 && unstable[i] != unstable[i - 1])  // the curve turned at point i - 1
      out.turning_points.push_back(speeds[i - 1]);
  }
}

// At the peak point: the contact state and energy of each pair, the harmonic truncation of the
// contact forces and the hysteresis loops asked for.
void peak_point_details(const DamperRingModel& m, const DamperRingOptions& o,
                        const hbm::ContinuationPoint& pt, DamperRingResult& out) {
  const double k = m.engine_order;
  const hbm::HarmonicBasis& b = m.basis;
  const int cp = m.coordinates_per_pair, s = b.size();
  const int H = b.harmonics();
  const double N0 = m.preload(pt.omega / k);
  const Eigen::Index np = static_cast<Eigen::Index>(m.pairs.size());
  out.pair_states.resize(np, 3);
  out.pair_energy.resize(np);
  // The truncation check: the same motion with 3H + 2 harmonics (their coefficients zero).
  const int Hc = 3 * H + 2;
  const hbm::HarmonicBasis bc(Hc, std::max(b.time_samples(), hbm::default_time_samples(Hc)));
  const int sc = bc.size();
  for (Eigen::Index q = 0; q < np; ++q) {
    const Eigen::VectorXd w = pt.X.segment(q * cp * s, cp * s);
    const hbm::ContactResponse r =
        hbm::friction_contact_response(friction_contact(m.contact, N0), b, w);
    Eigen::VectorXd wc = Eigen::VectorXd::Zero(cp * sc);
    for (int j = 0; j < cp; ++j) wc.segment(j * sc, s) = w.segment(j * s, s);
    const hbm::ContactResponse rc =
        hbm::friction_contact_response(friction_contact(m.contact, N0), bc, wc);
    double kept = 0.0, beyond = 0.0;
    for (int j = 0; j < cp; ++j) {
      kept += rc.coefficients.segment(j * sc + 1, s - 1).squaredNorm();
      beyond += rc.coefficients.segment(j * sc + s, sc - s).squaredNorm();
    }
    const double share = kept + beyond > 0.0 ? std::sqrt(beyond / (kept + beyond)) : 0.0;
    if (share > out.force_truncation) {
      out.force_truncation = share;
      out.truncation_pair = static_cast<int>(q);
    }
    out.pair_states.row(q) << r.stick_fraction, r.slip_fraction, r.lift_off_fraction;
    out.pair_energy[q] = r.energy_per_cycle;
    if (std::find(o.hysteresis_pairs.begin(), o.hysteresis_pairs.end(), q) !=
        o.hysteresis_pairs.end()) {
      HysteresisLoop loop;
      loop.pair = static_cast<int>(q);
      loop.slip = b.to_time(w.segment(s, s));
      loop.force = r.force.col(1);
      loop.normal = r.force.col(0);
      out.loops.push_back(std::move(loop));
    }
  }
}

}  // namespace

DamperRingResult run_damper_ring(const DamperRingModel& m, const DamperRingOptions& o,
                                 Progress& progress) {
  if (!(o.speed_min > 0.0 && o.speed_max > o.speed_min))
    throw InputError({}, "damper_ring.speeds", "0 < speed_min < speed_max",
                     fmt::format("{} .. {} rad/s", o.speed_min, o.speed_max));
  DamperRingResult out;
  const double k = m.engine_order;
  const Eigen::Index n_s = static_cast<Eigen::Index>(m.sensor_names.size());

  const double x_scale = linear_references(m, o, progress, out);

  const hbm::CondensedHarmonicBalance hb = m.system(m.contact);
  hbm::ContinuationOptions co;
  co.omega_start = k * o.speed_min;
  co.omega_end = k * o.speed_max;
  co.omega_scale = co.omega_end - co.omega_start;
  co.x_scale = x_scale > 0.0 ? 0.1 * x_scale : 1.0;
  co.step = o.max_step / 4;
  co.max_step = o.max_step;
  co.min_step = 1e-6 * o.max_step;
  co.tolerance = o.tolerance;
  progress.start("damper ring: continuation over speed", 0);
  const hbm::ContinuationResult cr =
      hbm::continue_in_frequency(hb, Eigen::VectorXd::Zero(hb.size()), co);
  progress.finish();
  out.status = cr.status;
  out.message = cr.message;

  double best = -1.0;
  for (const auto& pt : cr.points) {
    DampedPoint d = damped_point(m, hb, pt);
    if (n_s > 0 && d.amplitude[0] > best) {
      best = d.amplitude[0];
      out.peak_point = static_cast<int>(out.damped.size());
    }
    out.damped.push_back(std::move(d));
  }

  mark_fold_instability(out);

  if (out.peak_point >= 0)
    peak_point_details(m, o, cr.points[static_cast<std::size_t>(out.peak_point)], out);
  return out;
}

BodyMass body_mass(const Eigen::SparseMatrix<double>& M, const std::vector<solid::DofInfo>& dofs,
                   const std::vector<long>& nodes, int n_sectors, const std::string& key) {
  const auto index = dof_index(dofs);
  std::vector<int> rows;
  std::vector<double> radius;
  for (long id : nodes) {
    const auto it = index.find({id, 0});
    if (it == index.end())
      throw InputError({}, key, "nodes with a free x translation (the body's mass is summed there)",
                       fmt::format("node {} without it", id));
    rows.push_back(it->second);
    const Eigen::Vector3d& x = dofs[static_cast<std::size_t>(it->second)].x;
    radius.push_back(std::hypot(x.x(), x.y()));
  }
  std::vector<char> in_body(static_cast<std::size_t>(M.rows()), 0);
  for (int r : rows) in_body[static_cast<std::size_t>(r)] = 1;
  // m_n = sum over the body's x DOFs j of M(n_x, j_x) (M symmetric: column sums).
  double mass = 0.0, moment = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    double m_n = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, rows[i]); it; ++it)
      if (in_body[static_cast<std::size_t>(it.row())]) m_n += it.value();
    mass += m_n;
    moment += m_n * radius[i];
  }
  if (!(mass >= 0.0) || rows.empty())
    throw InputError({}, key, "a body of non-negative mass with nodes",
                     fmt::format("{} kg per sector, {} nodes", mass, rows.size()));
  if (mass == 0.0) {  // a massless body: its mean node radius
    double r = 0.0;
    for (double x : radius) r += x;
    return {0.0, r / static_cast<double>(radius.size())};
  }
  return {mass * n_sectors, moment / mass};
}

double mindlin_ratio(double E1, double nu1, double E2, double nu2) {
  const double G1 = E1 / (2.0 * (1.0 + nu1)), G2 = E2 / (2.0 * (1.0 + nu2));
  const double E_star = 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
  const double G_star = 1.0 / ((2.0 - nu1) / G1 + (2.0 - nu2) / G2);
  return 4.0 * G_star / E_star;
}

}  // namespace geardyn::damper
