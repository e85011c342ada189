#include "geardyn/gear/fe_compliance.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"
#include "geardyn/meshgen/involute_segment.hpp"
#include "geardyn/solid/assembly.hpp"

namespace geardyn::gear {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

[[noreturn]] void fail(const GearPairGeometry& g, const std::string& key,
                       const std::string& expected, const std::string& found,
                       const std::string& hint = {}) {
  throw InputError(g.spec.where, g.spec.key_path + ".contact." + key, expected, found, hint);
}

void check(const GearPairGeometry& g, const FeComplianceOptions& o) {
  if (g.spec.type != GearType::Spur)
    fail(g, "compliance", "\"analytic\" for a non-spur pair (the FE route meshes spur teeth)",
         "\"fe\"", "use compliance = \"analytic\" for helical, bevel and hypoid pairs");
  if (g.spec.mesh != MeshType::External)
    fail(g, "compliance", "\"analytic\" for an internal pair (the FE route meshes external teeth)",
         "\"fe\"", "use compliance = \"analytic\" for internal gears");
  if (!(o.mesh_size >= 0.05 && o.mesh_size <= 1.0))
    fail(g, "fe_mesh_size", "an element size in [0.05, 1] modules", fmt::format("{}", o.mesh_size));
  if (!std::isnan(o.body_size) && !(o.body_size >= o.mesh_size && o.body_size <= 4.0))
    fail(g, "fe_body_size", "an element size in [fe_mesh_size, 4] modules",
         fmt::format("{}", o.body_size));
  if (o.profile_points < 3 || o.profile_points > 64)
    fail(g, "fe_profile_points", "3 ... 64", fmt::format("{}", o.profile_points));
  if (o.face_points != 0 && (o.face_points < 2 || o.face_points > 201))
    fail(g, "fe_face_points", "0 (automatic) or 2 ... 201", fmt::format("{}", o.face_points));
  if (o.segment_teeth != 0 &&
      (o.segment_teeth < 1 || o.segment_teeth % 2 == 0 || o.segment_teeth > 7))
    fail(g, "fe_teeth", "0 (the whole gear) or an odd number of teeth 1 ... 7",
         fmt::format("{}", o.segment_teeth));
}

/// The segment mesh parameters of one gear.
meshgen::InvoluteSegmentParams segment_params(const GearPairGeometry& g, bool wheel,
                                              const FeComplianceOptions& o) {
  const GearGeometry& gg = wheel ? g.wheel : g.pinion;
  const ElasticConstants& ec = wheel ? o.teeth.wheel : o.teeth.pinion;
  meshgen::InvoluteSegmentParams p;
  p.teeth = gg.teeth;
  const int largest_odd = std::max(1, (gg.teeth / 2) - (gg.teeth / 2 + 1) % 2);
  p.segment_teeth = o.segment_teeth == 0 ? gg.teeth : std::min(o.segment_teeth, largest_odd);
  p.module = g.normal_module_m;
  p.pressure_angle = g.normal_pressure_angle_rad;
  p.profile_shift = gg.profile_shift;
  p.tip_radius = gg.tip_radius_m;
  p.dedendum_coefficient = g.spec.dedendum_coefficient;
  p.root_fillet_coefficient = o.teeth.root_fillet_coefficient;
  const double bore = wheel ? o.teeth.bore_radius_wheel_m : o.teeth.bore_radius_pinion_m;
  // Sainsot's body: r_int = r_f / 2 by default, at most r_f / 7 deep (as the analytic route).
  const double rf = gg.root_radius_m;
  p.bore_radius = std::isnan(bore) ? 0.5 * rf : std::max(bore, rf / 7.0);
  p.face_width = g.face_width_m;
  p.tooth_size = o.mesh_size * p.module;
  p.body_size = (std::isnan(o.body_size) ? 3.0 : o.body_size) * p.module;
  p.material.name = wheel ? "wheel" : "pinion";
  p.material.E = ec.youngs_modulus_pa;
  p.material.nu = ec.poisson_ratio;
  p.material.rho = 7850.0;
  p.key_path = g.spec.key_path + (wheel ? ".wheel_segment" : ".pinion_segment");
  p.where = g.spec.where;
  return p;
}

/// The loaded flank of the loaded tooth (centred on +x) at radius r: point, unit load direction
/// (into the tooth, along the involute normal = the base-circle tangent) and the centre-line
/// point where that line crosses the x axis.
struct FlankPoint {
  Eigen::Vector2d point, load, centre;
};

FlankPoint flank_point(const std::vector<meshgen::ProfilePoint>& prof, int teeth, double rb,
                       double r) {
  const double psi = meshgen::half_tooth_angle(prof, teeth, r);
  const double alpha = std::acos(std::clamp(rb / r, -1.0, 1.0));
  const double phi_t = psi - alpha;  // angle of the base tangent point
  FlankPoint f;
  f.point = {r * std::cos(psi), r * std::sin(psi)};
  f.load = {std::sin(phi_t), -std::cos(phi_t)};
  const double d = f.point.y() / std::cos(phi_t);
  f.centre = f.point + d * f.load;
  return f;
}

/// Boundary faces (6-node triangles) of the tets near the loaded tooth.
struct Face {
  std::array<int, 6> nodes;  ///< corners a b c, mid-nodes ab bc ca
};

std::vector<Face> flank_faces(const solid::Mesh& mesh, double r_min, double angle_max) {
  static constexpr std::array<std::array<int, 6>, 4> kFaces = {
      {{0, 1, 2, 4, 5, 6}, {0, 1, 3, 4, 9, 7}, {1, 2, 3, 5, 8, 9}, {0, 2, 3, 6, 8, 7}}};
  std::map<std::array<int, 3>, std::pair<int, Face>> seen;
  for (const solid::Element& e : mesh.elements) {
    const Eigen::Vector3d& x = mesh.coords[static_cast<std::size_t>(e.nodes[0])];
    if (std::hypot(x.x(), x.y()) < r_min || std::abs(std::atan2(x.y(), x.x())) > angle_max)
      continue;
    for (const auto& lf : kFaces) {
      Face f;
      for (int i = 0; i < 6; ++i)
        f.nodes[static_cast<std::size_t>(i)] =
            e.nodes[static_cast<std::size_t>(lf[static_cast<std::size_t>(i)])];
      std::array<int, 3> key = {f.nodes[0], f.nodes[1], f.nodes[2]};
      std::sort(key.begin(), key.end());
      auto [it, inserted] = seen.try_emplace(key, 0, f);
      ++it->second.first;
    }
  }
  std::vector<Face> out;
  for (const auto& [key, v] : seen)
    if (v.first == 1) out.push_back(v.second);
  return out;
}

/// Consistent nodal forces of a point force `force` at x on the nearest boundary face, added to
/// `rhs` (reduced DOFs).
void add_point_force(const solid::Mesh& mesh, const solid::SolidSystem& sys,
                     const std::vector<Face>& faces, const Eigen::Vector3d& x,
                     const Eigen::Vector3d& force, Eigen::Ref<Eigen::VectorXd> rhs) {
  double best = std::numeric_limits<double>::infinity();
  const Face* face = nullptr;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
  for (const Face& f : faces) {
    const Eigen::Vector3d& a = mesh.coords[static_cast<std::size_t>(f.nodes[0])];
    const Eigen::Vector3d& b = mesh.coords[static_cast<std::size_t>(f.nodes[1])];
    const Eigen::Vector3d& c = mesh.coords[static_cast<std::size_t>(f.nodes[2])];
    const Eigen::Vector3d e1 = b - a, e2 = c - a, n = e1.cross(e2);
    const double nn = n.squaredNorm();
    if (!(nn > 0.0)) continue;
    const Eigen::Vector3d v = x - a;
    const double dist = std::abs(v.dot(n)) / std::sqrt(nn);
    const double l1 = v.cross(e2).dot(n) / nn;
    const double l2 = e1.cross(v).dot(n) / nn;
    const double l0 = 1.0 - l1 - l2;
    const double outside = std::max({0.0, -l0, -l1, -l2}) * std::sqrt(std::sqrt(nn));
    const double score = dist + outside;
    if (score < best) {
      best = score;
      face = &f;
      bary = {std::max(l0, 0.0), std::max(l1, 0.0), std::max(l2, 0.0)};
      bary /= bary.sum();
    }
  }
  if (face == nullptr) throw NumericalError("fe_compliance", "no flank face found for a load");
  const double l0 = bary(0), l1 = bary(1), l2 = bary(2);
  const std::array<double, 6> shape = {l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1),
                                       4 * l0 * l1,       4 * l1 * l2,       4 * l2 * l0};
  for (std::size_t a = 0; a < 6; ++a)
    for (int c = 0; c < 3; ++c) {
      const int dof = sys.node_dof(face->nodes[a], c);
      if (dof >= 0) rhs(dof) += shape[a] * force(c);
    }
}

/// Interpolation weights of a point inside the tet10 mesh: (reduced DOF, weight) per component.
struct Probe {
  std::array<int, 10> nodes{};
  std::array<double, 10> shape{};
};

Probe locate(const solid::Mesh& mesh, const Eigen::Vector3d& x, double reach) {
  static constexpr std::array<std::array<int, 2>, 6> kEdges = {
      {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}}};
  double best = -std::numeric_limits<double>::infinity();
  Probe probe;
  for (const solid::Element& e : mesh.elements) {
    const auto& c = mesh.coords;
    const Eigen::Vector3d& x0 = c[static_cast<std::size_t>(e.nodes[0])];
    if ((x0 - x).norm() > reach) continue;  // farther than any element's size
    Eigen::Matrix3d j;
    for (int k = 0; k < 3; ++k)
      j.col(k) = c[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(k + 1)])] - x0;
    const Eigen::Vector3d l = j.partialPivLu().solve(x - x0);
    const std::array<double, 4> lam = {1.0 - l.sum(), l(0), l(1), l(2)};
    const double worst = *std::min_element(lam.begin(), lam.end());
    if (worst > best) {
      best = worst;
      for (std::size_t a = 0; a < 10; ++a) probe.nodes[a] = e.nodes[a];
      for (std::size_t a = 0; a < 4; ++a) probe.shape[a] = lam[a] * (2.0 * lam[a] - 1.0);
      for (std::size_t k = 0; k < 6; ++k)
        probe.shape[4 + k] = 4.0 * lam[static_cast<std::size_t>(kEdges[k][0])] *
                             lam[static_cast<std::size_t>(kEdges[k][1])];
    }
    if (best >= 0.0) break;
  }
  if (best < -1e-6)
    throw NumericalError("fe_compliance", "a centre-line probe is outside the mesh");
  return probe;
}

double probe_value(const solid::SolidSystem& sys, const Probe& p, const Eigen::Vector3d& dir,
                   const Eigen::Ref<const Eigen::VectorXd>& u) {
  double v = 0.0;
  for (std::size_t a = 0; a < 10; ++a)
    for (int c = 0; c < 3; ++c) {
      const int dof = sys.node_dof(p.nodes[a], c);
      if (dof >= 0) v += p.shape[a] * dir(c) * u(dof);
    }
  return v;
}

/// Integral of the hat of node f of the grid over [a, b].
double hat_integral(const std::vector<double>& grid, std::size_t f, double a, double b) {
  const double lo = f > 0 ? grid[f - 1] : grid[f];
  const double hi = f + 1 < grid.size() ? grid[f + 1] : grid[f];
  const double c = grid[f];
  auto part = [&](double x0, double x1, bool rising) {  // integral of the linear piece
    const double s = std::max(a, x0), e = std::min(b, x1);
    if (!(e > s) || !(x1 > x0)) return 0.0;
    auto val = [&](double x) { return rising ? (x - x0) / (x1 - x0) : (x1 - x) / (x1 - x0); };
    return 0.5 * (val(s) + val(e)) * (e - s);
  };
  return part(lo, c, true) + part(c, hi, false);
}

/// Index and weight of linear interpolation on an increasing grid (clamped to its ends).
std::pair<std::size_t, double> bracket(const std::vector<double>& grid, double v) {
  if (grid.size() < 2 || v <= grid.front()) return {0, 0.0};
  if (v >= grid.back()) return {grid.size() - 2, 1.0};
  const auto i =
      static_cast<std::size_t>(std::upper_bound(grid.begin(), grid.end(), v) - grid.begin()) - 1;
  return {i, (v - grid[i]) / (grid[i + 1] - grid[i])};
}

}  // namespace

double ToothInfluence::at(double s_i, double y_i, double s_k, double y_a, double y_b) const {
  const std::size_t nf = face.size();
  const auto [pi, fi] = bracket(path, s_i);
  const auto [yi, gi] = bracket(face, y_i);
  const auto [pk, fk] = bracket(path, s_k);
  double total = 0.0;
  for (std::size_t f = 0; f < nf; ++f) {
    const double w = hat_integral(face, f, y_a, y_b);
    if (w == 0.0) continue;
    const double mass = hat_integral(face, f, face.front(), face.back());
    const double load_weight = w / mass;
    for (int dp = 0; dp < 2; ++dp) {
      const double wp = dp == 0 ? 1.0 - fk : fk;
      if (wp == 0.0) continue;
      const std::size_t col = (pk + static_cast<std::size_t>(dp)) * nf + f;
      double recv = 0.0;
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
          const double wr = (a == 0 ? 1.0 - fi : fi) * (b == 0 ? 1.0 - gi : gi);
          if (wr == 0.0) continue;
          recv += wr * influence(static_cast<Eigen::Index>((pi + static_cast<std::size_t>(a)) * nf +
                                                           yi + static_cast<std::size_t>(b)),
                                 static_cast<Eigen::Index>(col));
        }
      total += load_weight * wp * recv;
    }
  }
  return total;
}

ToothInfluence fe_tooth_influence(const ToothCompliance& teeth, bool wheel,
                                  const FeComplianceOptions& o) {
  const GearPairGeometry& g = teeth.geometry();
  check(g, o);
  const auto t0 = Clock::now();
  const meshgen::InvoluteSegmentParams params = segment_params(g, wheel, o);
  const std::vector<meshgen::ProfilePoint> prof = meshgen::tooth_space_profile(params);
  solid::Mesh mesh = meshgen::involute_segment(params);
  std::vector<int> fixed = mesh.node_sets.at("bore");
  if (o.fix_cut_faces) {
    const std::vector<int>& cut = mesh.node_sets.at("cut");  // empty for the whole gear
    fixed.insert(fixed.end(), cut.begin(), cut.end());
  }
  for (int n : fixed) mesh.constraints.push_back({n, {true, true, true, false, false, false}, {}});
  solid::AssemblyOptions ao;
  ao.mass = false;
  const solid::SolidSystem sys = solid::assemble(mesh, ao);
  linalg::SymmetricFactorization chol;
  if (chol.compute(sys.K) != Status::Ok)
    throw NumericalError("fe_compliance", "the segment stiffness is singular: " + chol.message());

  ToothInfluence out;
  out.nodes = mesh.num_nodes();
  out.elements = mesh.num_elements();
  out.dofs = sys.num_dofs();
  out.mesh_seconds = seconds_since(t0);
  const auto t1 = Clock::now();
  const int np = o.profile_points;
  const double b = g.face_width_m;
  const int nf = o.face_points > 0
                     ? o.face_points
                     : std::max(5, static_cast<int>(std::ceil(b / (0.5 * g.normal_module_m))) + 1);
  for (int p = 0; p < np; ++p) out.path.push_back(g.path_of_contact_m * p / (np - 1));
  for (int f = 0; f < nf; ++f) out.face.push_back(b * f / (nf - 1));

  const double rb = (wheel ? g.wheel : g.pinion).base_radius_m;
  const int z = (wheel ? g.wheel : g.pinion).teeth;
  const double pitch = 2.0 * units::kPi / z;
  const std::vector<Face> faces =
      flank_faces(mesh, (wheel ? g.wheel : g.pinion).root_radius_m - g.normal_module_m, pitch);
  std::vector<FlankPoint> fps;
  for (double s : out.path) {
    const double r = wheel ? teeth.wheel_radius(s) : teeth.pinion_radius(s);
    fps.push_back(flank_point(prof, z, rb, r));
  }
  std::vector<Probe> probes;
  for (int p = 0; p < np; ++p)
    for (int f = 0; f < nf; ++f) {
      const FlankPoint& fp = fps[static_cast<std::size_t>(p)];
      probes.push_back(locate(mesh,
                              {fp.centre.x(), fp.centre.y(), out.face[static_cast<std::size_t>(f)]},
                              3.0 * params.body_size));
    }
  const int n = np * nf;
  out.influence.resize(n, n);
  // Hat line loads sampled by point forces: 16 Gauss-free midpoints per grid interval.
  constexpr int kSub = 16;
  constexpr int kBlock = 48;
  for (int c0 = 0; c0 < n; c0 += kBlock) {
    const int nc = std::min(kBlock, n - c0);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(sys.num_dofs(), nc);
    for (int c = 0; c < nc; ++c) {
      const int p = (c0 + c) / nf, f = (c0 + c) % nf;
      const FlankPoint& fp = fps[static_cast<std::size_t>(p)];
      const Eigen::Vector3d dir(fp.load.x(), fp.load.y(), 0.0);
      for (int side = -1; side <= 1; side += 2) {
        const int nb = f + side;
        if (nb < 0 || nb >= nf) continue;
        const double yc = out.face[static_cast<std::size_t>(f)];
        const double len = std::abs(out.face[static_cast<std::size_t>(nb)] - yc);
        for (int k = 0; k < kSub; ++k) {
          const double t = (k + 0.5) / kSub;  // distance from the peak / len
          const double y = yc + side * t * len;
          add_point_force(mesh, sys, faces, {fp.point.x(), fp.point.y(), y},
                          dir * ((1.0 - t) * len / kSub), rhs.col(c));
        }
      }
    }
    const Eigen::MatrixXd u = chol.solve(rhs);
    for (int c = 0; c < nc; ++c)
      for (int i = 0; i < n; ++i) {
        const FlankPoint& fr = fps[static_cast<std::size_t>(i / nf)];
        out.influence(i, c0 + c) = probe_value(sys, probes[static_cast<std::size_t>(i)],
                                               {fr.load.x(), fr.load.y(), 0.0}, u.col(c));
      }
  }
  out.solve_seconds = seconds_since(t1);
  return out;
}

FeCompliance::FeCompliance(const ToothCompliance& teeth, const FeComplianceOptions& options)
    : HertzianContactCompliance(teeth),
      pinion_(fe_tooth_influence(teeth, false, options)),
      wheel_(fe_tooth_influence(teeth, true, options)) {}

Eigen::MatrixXd FeCompliance::body_influence(const std::vector<double>& s,
                                             const std::vector<double>& y, double dy) const {
  const auto m = static_cast<Eigen::Index>(s.size());
  Eigen::MatrixXd a(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index k = 0; k < m; ++k) {
      const auto ui = static_cast<std::size_t>(i), uk = static_cast<std::size_t>(k);
      const double ya = y[uk] - 0.5 * dy, yb = y[uk] + 0.5 * dy;
      a(i, k) = pinion_.at(s[ui], y[ui], s[uk], ya, yb) + wheel_.at(s[ui], y[ui], s[uk], ya, yb);
    }
  return a;
}

}  // namespace geardyn::gear
