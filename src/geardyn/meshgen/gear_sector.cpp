#include "geardyn/meshgen/gear_sector.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "geardyn/core/units.hpp"
#include "geardyn/meshgen/gmsh_session.hpp"

namespace geardyn::meshgen {
namespace {

constexpr const char* kAnalysis = "gear_sector";

class Checker {
 public:
  explicit Checker(const GearSectorParams& p) : p_(p) {}

  [[noreturn]] void fail(const std::string& key, const std::string& expected, double found,
                         const std::string& hint = {}) const {
    throw InputError(p_.where, p_.key_path + "." + key, expected, fmt::format("{:.6g}", found),
                     hint);
  }
  void positive(const std::string& key, double value) const {
    if (!(value > 0) || !std::isfinite(value)) fail(key, "a positive finite number", value);
  }
  void material(const std::string& key, const solid::Material& m) const {
    positive(key + ".E", m.E);
    positive(key + ".rho", m.rho);
    if (!(m.nu > -1.0 && m.nu < 0.5)) fail(key + ".nu", "a Poisson's ratio in (-1, 0.5)", m.nu);
  }

 private:
  const GearSectorParams& p_;
};

struct Interval {
  double lo, hi;
  bool contains(const Interval& o, double tol) const {
    return o.lo >= lo - tol && o.hi <= hi + tol;
  }
  bool overlaps(const Interval& o, double tol) const { return o.lo < hi - tol && o.hi > lo + tol; }
};

Interval centred(double centre, double width) {
  return {centre - 0.5 * width, centre + 0.5 * width};
}

double sector_angle(const GearSectorParams& p) { return units::kTwoPi / p.num_sectors; }

}  // namespace

double ToothGeometry::area() const {
  const double beta_f = root_thickness / (2.0 * root_radius);
  const double beta_a = tip_thickness / (2.0 * tip_radius);
  return root_radius * tip_radius * std::sin(beta_f - beta_a) + tip_radius * tip_radius * beta_a -
         root_radius * root_radius * beta_f;
}

ToothGeometry resolve_tooth(const GearSectorParams& p) {
  const Checker check(p);
  const ToothParams& t = p.tooth;
  if (p.num_teeth < 1) check.fail("num_teeth", "a positive number of teeth", p.num_teeth);
  ToothGeometry g;
  if (t.profile == ToothProfile::Module) {
    check.positive("tooth.module", t.module);
    if (!(t.pressure_angle > 0 && t.pressure_angle < units::kPi / 4))
      check.fail("tooth.pressure_angle", "an angle in (0, pi/4) rad", t.pressure_angle);
    check.positive("tooth.addendum_coefficient", t.addendum_coefficient);
    check.positive("tooth.dedendum_coefficient", t.dedendum_coefficient);
    g.pitch_radius = 0.5 * t.module * p.num_teeth;
    g.tip_radius = g.pitch_radius + t.addendum_coefficient * t.module;
    g.root_radius = g.pitch_radius - t.dedendum_coefficient * t.module;
    // Basic rack: thickness pi m / 2 at the pitch line, flanks inclined by the pressure angle.
    const double s_p = 0.5 * units::kPi * t.module;
    g.tip_thickness = s_p - 2.0 * t.addendum_coefficient * t.module * std::tan(t.pressure_angle);
    g.root_thickness = s_p + 2.0 * t.dedendum_coefficient * t.module * std::tan(t.pressure_angle);
    if (!(g.root_radius > 0))
      check.fail("tooth.dedendum_coefficient", "a root radius m (z/2 - dedendum) > 0",
                 g.root_radius);
    if (!(g.tip_thickness > 0))
      check.fail("tooth.pressure_angle", "a tooth with positive tip thickness", g.tip_thickness,
                 "the straight-flank tooth comes to a point: lower the pressure angle or the "
                 "addendum coefficient");
  } else {
    g.root_radius = t.root_radius;
    g.tip_radius = t.tip_radius;
    g.pitch_radius = t.pitch_radius;
    g.root_thickness = t.root_thickness;
    g.tip_thickness = t.tip_thickness;
    check.positive("tooth.root_radius", g.root_radius);
    check.positive("tooth.root_thickness", g.root_thickness);
    check.positive("tooth.tip_thickness", g.tip_thickness);
    if (!(g.tip_radius > g.root_radius))
      check.fail("tooth.tip_radius", fmt::format("> root radius ({:.6g})", g.root_radius),
                 g.tip_radius);
    if (!(g.pitch_radius > g.root_radius && g.pitch_radius < g.tip_radius))
      check.fail(
          "tooth.pitch_radius",
          fmt::format("between root ({:.6g}) and tip ({:.6g}) radius", g.root_radius, g.tip_radius),
          g.pitch_radius);
  }
  // A tooth space must remain at the root (the sector faces cut through it); 2 % of the pitch
  // keeps the mesh there from degenerating into slivers.
  const double root_pitch = 2.0 * units::kPi * g.root_radius / p.num_teeth;
  if (!(g.root_thickness < 0.98 * root_pitch))
    check.fail(
        t.profile == ToothProfile::Module ? "tooth.module" : "tooth.root_thickness",
        fmt::format("a root tooth thickness below 98 % of the root pitch ({:.6g})", root_pitch),
        g.root_thickness, "the teeth overlap at the root: fewer or thinner teeth");
  const double beta_f = g.root_thickness / (2.0 * g.root_radius);
  const double beta_a = g.tip_thickness / (2.0 * g.tip_radius);
  if (!(beta_a < beta_f))
    check.fail(t.profile == ToothProfile::Module ? "tooth.pressure_angle" : "tooth.tip_thickness",
               "a tooth narrowing (in angle) from root to tip", g.tip_thickness);
  return g;
}

void validate(const GearSectorParams& p) {
  const Checker check(p);
  if (p.num_sectors < 2)
    check.fail("num_sectors", "at least 2 sectors (a full wheel is built from sectors)",
               p.num_sectors);
  if (p.num_teeth < 1) check.fail("num_teeth", "a positive number of teeth", p.num_teeth);
  if (p.num_teeth % p.num_sectors != 0)
    check.fail("num_teeth", fmt::format("a multiple of num_sectors ({})", p.num_sectors),
               p.num_teeth, "each sector must hold the same whole number of teeth");
  check.positive("bore_radius", p.bore_radius);
  if (!(p.bore_radius < p.hub_outer_radius))
    check.fail("bore_radius", fmt::format("< hub_outer_radius ({:.6g})", p.hub_outer_radius),
               p.bore_radius);
  if (!(p.hub_outer_radius < p.rim_inner_radius))
    check.fail("hub_outer_radius", fmt::format("< rim_inner_radius ({:.6g})", p.rim_inner_radius),
               p.hub_outer_radius);
  check.positive("hub_width", p.hub_width);
  check.positive("web_thickness", p.web_thickness);
  check.positive("face_width", p.face_width);
  const ToothGeometry tooth = resolve_tooth(p);
  if (!(p.rim_inner_radius < tooth.root_radius))
    check.fail("rim_inner_radius",
               fmt::format("< the tooth root radius ({:.6g})", tooth.root_radius),
               p.rim_inner_radius);

  const double tol = 1e-9 * tooth.tip_radius;
  const Interval hub = centred(p.hub_offset, p.hub_width);
  const Interval web = centred(p.web_offset, p.web_thickness);
  const Interval rim = centred(0.0, p.face_width);
  if (!hub.contains(web, tol) || !rim.contains(web, tol))
    check.fail("web_offset",
               fmt::format("a web [{:.6g}, {:.6g}] inside the hub [{:.6g}, {:.6g}] and the rim "
                           "[{:.6g}, {:.6g}] axially",
                           web.lo, web.hi, hub.lo, hub.hi, rim.lo, rim.hi),
               p.web_offset);

  if (p.groove) {
    const GrooveParams& g = *p.groove;
    check.positive("groove.width", g.width);
    check.positive("groove.depth", g.depth);
    const Interval groove = centred(g.axial_position, g.width);
    if (!rim.contains(groove, tol))
      check.fail("groove.axial_position",
                 fmt::format("a groove [{:.6g}, {:.6g}] inside the rim [{:.6g}, {:.6g}]", groove.lo,
                             groove.hi, rim.lo, rim.hi),
                 g.axial_position);
    if (groove.overlaps(web, tol))
      check.fail("groove.axial_position",
                 fmt::format("a groove [{:.6g}, {:.6g}] clear of the web [{:.6g}, {:.6g}]",
                             groove.lo, groove.hi, web.lo, web.hi),
                 g.axial_position, "the groove is cut in the rim's inner surface beside the web");
    if (!(p.rim_inner_radius + g.depth < tooth.root_radius))
      check.fail("groove.depth",
                 fmt::format("< the rim's radial thickness ({:.6g})",
                             tooth.root_radius - p.rim_inner_radius),
                 g.depth, "the groove would cut through the rim");
    const RingParams& r = g.ring;
    check.positive("groove.ring.width", r.width);
    check.positive("groove.ring.radial_thickness", r.radial_thickness);
    if (!(r.width <= g.width + tol))
      check.fail("groove.ring.width", fmt::format("<= groove width ({:.6g})", g.width), r.width);
    if (!groove.contains(centred(r.axial_position, r.width), tol))
      check.fail("groove.ring.axial_position", "a ring lying inside the groove axially",
                 r.axial_position);
    const double ring_inner = p.rim_inner_radius + g.depth - r.radial_thickness;
    if (!(ring_inner > p.hub_outer_radius))
      check.fail("groove.ring.radial_thickness",
                 fmt::format("a ring inner radius above the hub ({:.6g})", p.hub_outer_radius),
                 r.radial_thickness);
    check.material("ring_material", p.ring_material);
  }
  check.positive("mesh.global", p.mesh.global);
  if (!(p.mesh.tooth >= 0)) check.fail("mesh.tooth", "a size >= 0 (0: global)", p.mesh.tooth);
  if (!(p.mesh.groove >= 0)) check.fail("mesh.groove", "a size >= 0 (0: global)", p.mesh.groove);
  if (p.mesh.element_order != 1 && p.mesh.element_order != 2)
    check.fail("mesh.element_order", "1 (tet4) or 2 (tet10)", p.mesh.element_order);
  check.material("gear_material", p.gear_material);
}

SectorVolumes analytic_volumes(const GearSectorParams& p) {
  validate(p);
  const ToothGeometry t = resolve_tooth(p);
  const double half_angle = 0.5 * sector_angle(p);
  auto annulus = [&](double r0, double r1, double width) {
    return half_angle * (r1 * r1 - r0 * r0) * width;
  };
  SectorVolumes v;
  v.gear = annulus(p.bore_radius, p.hub_outer_radius, p.hub_width) +
           annulus(p.hub_outer_radius, p.rim_inner_radius, p.web_thickness) +
           annulus(p.rim_inner_radius, t.root_radius, p.face_width) +
           (p.num_teeth / p.num_sectors) * t.area() * p.face_width;
  if (p.groove) {
    const double rc = p.rim_inner_radius + p.groove->depth;
    v.gear -= annulus(p.rim_inner_radius, rc, p.groove->width);
    v.ring = annulus(rc - p.groove->ring.radial_thickness, rc, p.groove->ring.width);
  }
  return v;
}

namespace {

namespace occ = gmsh::model::occ;

/// Plane face of the rectangle [r0, r1] x [z0, z1] in the half-plane y = 0, x > 0.
int add_section_rectangle(double r0, double r1, double z0, double z1) {
  const int p0 = occ::addPoint(r0, 0, z0), p1 = occ::addPoint(r1, 0, z0);
  const int p2 = occ::addPoint(r1, 0, z1), p3 = occ::addPoint(r0, 0, z1);
  const int loop = occ::addCurveLoop(
      {occ::addLine(p0, p1), occ::addLine(p1, p2), occ::addLine(p2, p3), occ::addLine(p3, p0)});
  return occ::addPlaneSurface({loop});
}

std::vector<int> revolve_faces(const gmsh::vectorpair& faces, double angle) {
  gmsh::vectorpair out;
  occ::revolve(faces, 0, 0, 0, 0, 0, 1, angle, out);
  std::vector<int> volumes;
  for (const auto& [dim, tag] : out)
    if (dim == 3) volumes.push_back(tag);
  return volumes;
}

Eigen::Vector2d polar(double r, double theta) { return {r * std::cos(theta), r * std::sin(theta)}; }

/// Tooth j's volume: transverse section at z = -b/2 extruded by b.
int add_tooth(const ToothGeometry& t, double theta, double face_width) {
  const double beta_f = t.root_thickness / (2.0 * t.root_radius);
  const double beta_a = t.tip_thickness / (2.0 * t.tip_radius);
  const double z0 = -0.5 * face_width;
  auto point = [&](const Eigen::Vector2d& x) { return occ::addPoint(x.x(), x.y(), z0); };
  const int centre = occ::addPoint(0, 0, z0);
  const int f_minus = point(polar(t.root_radius, theta - beta_f));
  const int a_minus = point(polar(t.tip_radius, theta - beta_a));
  const int a_plus = point(polar(t.tip_radius, theta + beta_a));
  const int f_plus = point(polar(t.root_radius, theta + beta_f));
  const int loop =
      occ::addCurveLoop({occ::addLine(f_minus, a_minus), occ::addCircleArc(a_minus, centre, a_plus),
                         occ::addLine(a_plus, f_plus), occ::addCircleArc(f_plus, centre, f_minus)});
  const int face = occ::addPlaneSurface({loop});
  gmsh::vectorpair out;
  occ::extrude({{2, face}}, 0, 0, face_width, out);
  occ::remove({{0, centre}});
  for (const auto& [dim, tag] : out)
    if (dim == 3) return tag;
  throw NumericalError(kAnalysis, "extruding a tooth section gave no volume");
}

/// The point of the +theta flank of a tooth centred at `theta` at radius r_p, on z = 0.
Eigen::Vector3d flank_point(const ToothGeometry& t, double theta) {
  const Eigen::Vector2d a = polar(t.root_radius, theta + t.root_thickness / (2.0 * t.root_radius));
  const Eigen::Vector2d b = polar(t.tip_radius, theta + t.tip_thickness / (2.0 * t.tip_radius));
  // |a + s (b - a)| = r_p, s in (0, 1): the larger root of the quadratic in s.
  const Eigen::Vector2d d = b - a;
  const double qa = d.squaredNorm(), qb = 2.0 * a.dot(d),
               qc = a.squaredNorm() - t.pitch_radius * t.pitch_radius;
  const double s = (-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
  const Eigen::Vector2d x = a + s * d;
  return {x.x(), x.y(), 0.0};
}

std::vector<Eigen::Vector3d> vertices_of(int surface) {
  gmsh::vectorpair points;
  gmsh::model::getBoundary({{2, surface}}, points, false, false, true);
  std::vector<Eigen::Vector3d> out;
  for (const auto& [dim, tag] : points) {
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(0, tag, x0, y0, z0, x1, y1, z1);
    out.emplace_back(x0, y0, z0);
  }
  return out;
}

/// Pairs each right surface with the left surface whose vertices, rotated by `angle`, are the
/// right surface's vertices.
std::vector<int> match_left(const std::vector<int>& left, const std::vector<int>& right,
                            double angle, double tol) {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  std::vector<int> out;
  for (int r : right) {
    const std::vector<Eigen::Vector3d> rv = vertices_of(r);
    int match = -1;
    for (int l : left) {
      const std::vector<Eigen::Vector3d> lv = vertices_of(l);
      if (lv.size() != rv.size()) continue;
      const bool same = std::all_of(lv.begin(), lv.end(), [&](const Eigen::Vector3d& x) {
        return std::any_of(rv.begin(), rv.end(), [&](const Eigen::Vector3d& y) {
          return (rotation * x - y).norm() <= tol;
        });
      });
      if (same) {
        match = l;
        break;
      }
    }
    if (match < 0)
      throw NumericalError(kAnalysis, fmt::format("sector face {} has no counterpart on the "
                                                  "left face: the geometry is not periodic",
                                                  r));
    out.push_back(match);
  }
  return out;
}

std::vector<int> intersection(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> out;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

std::vector<int> points_of(const std::vector<int>& volumes) {
  gmsh::vectorpair dim_tags, points;
  for (int v : volumes) dim_tags.emplace_back(3, v);
  gmsh::model::getBoundary(dim_tags, points, false, false, true);
  std::set<int> out;
  for (const auto& [dim, tag] : points)
    if (dim == 0) out.insert(tag);
  return {out.begin(), out.end()};
}

// A curved tet whose det J drops below this fraction of its straight shape's somewhere is
// treated as tangled: it would stiffen or break the solution as much as an inverted one.
constexpr double kMinRelativeJacobian = 0.05;

constexpr std::array<std::array<int, 2>, 6> kTetEdges{
    {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}}};

/// Smallest det J of a tet sampled at its nodes and centroid, relative to det J of the straight
/// tet on its corners (1 for a straight tet, <= 0 for an inverted one). For tet10,
/// x(L) = sum N_i x_i with N_corner = L_i (2 L_i - 1), N_edge(a,b) = 4 L_a L_b (barycentric L,
/// edges in Gmsh order); det J is a cubic, so this samples it, catching the usual failure (a
/// flat tet turned inside out by mid-nodes moved onto a curved face).
double min_relative_tet_jacobian(const solid::Mesh& mesh, const solid::Element& e) {
  static const std::array<Eigen::Vector3d, 4> kGradL{
      Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
      Eigen::Vector3d(0, 0, 1)};
  static const std::vector<std::array<double, 4>> kSamples = [] {
    std::vector<std::array<double, 4>> out = {
        {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}, {0.25, 0.25, 0.25, 0.25}};
    for (const auto& [a, b] : kTetEdges) {
      std::array<double, 4> L{0, 0, 0, 0};
      L[static_cast<std::size_t>(a)] = L[static_cast<std::size_t>(b)] = 0.5;
      out.push_back(L);
    }
    return out;
  }();
  const bool quadratic = e.type == solid::ElementType::Tet10;
  auto x = [&](std::size_t i) -> const Eigen::Vector3d& {
    return mesh.coords[static_cast<std::size_t>(e.nodes[i])];
  };
  Eigen::Matrix3d straight;
  straight << x(1) - x(0), x(2) - x(0), x(3) - x(0);
  const double reference = straight.determinant();
  if (!(reference > 0)) return reference;
  double lowest = std::numeric_limits<double>::max();
  for (const std::array<double, 4>& L : kSamples) {
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();  // columns d x / d(xi, eta, zeta)
    for (std::size_t i = 0; i < 4; ++i)
      J += x(i) * ((quadratic ? 4.0 * L[i] - 1.0 : 1.0) * kGradL[i]).transpose();
    if (quadratic)
      for (std::size_t k = 0; k < kTetEdges.size(); ++k) {
        const auto a = static_cast<std::size_t>(kTetEdges[k][0]);
        const auto b = static_cast<std::size_t>(kTetEdges[k][1]);
        J += x(4 + k) * (4.0 * (L[a] * kGradL[b] + L[b] * kGradL[a])).transpose();
      }
    lowest = std::min(lowest, J.determinant());
  }
  return lowest / reference;
}

/// Copies of one node that must move together: (node, rotation about z in units of the sector
/// angle: 0 for a contact twin, +1 left -> right, -1 right -> left).
using NodeLinks = std::vector<std::vector<std::pair<int, int>>>;

NodeLinks node_links(const solid::Mesh& mesh) {
  NodeLinks links(static_cast<std::size_t>(mesh.num_nodes()));
  auto link = [&](const char* from, const char* to, int turns) {
    const auto f = mesh.node_sets.find(from), t = mesh.node_sets.find(to);
    if (f == mesh.node_sets.end() || t == mesh.node_sets.end()) return;
    for (std::size_t i = 0; i < f->second.size(); ++i) {
      links[static_cast<std::size_t>(f->second[i])].emplace_back(t->second[i], turns);
      links[static_cast<std::size_t>(t->second[i])].emplace_back(f->second[i], -turns);
    }
  };
  link("left", "right", 1);
  link("ring_left", "ring_right", 1);
  link("groove_contact", "ring_contact", 0);
  return links;
}

/// Untangles quadratic tets turned inside out (or nearly, min det J below kMinRelativeJacobian
/// of the straight tet's) by curving: the mid-edge nodes of such a tet10 go back to the midpoints
/// of their edges (so that edge is straight, as in the valid linear mesh), carrying their periodic
/// partners and contact twins along so that the left / right and contact pairs stay exact; repeated
/// until no tet is inverted (a mesh of straight tet10s is as valid as the linear mesh). Returns the
/// number of nodes moved; throws NumericalError if a linear tet is inverted.
int untangle_tets(solid::Mesh& mesh, double alpha) {
  const NodeLinks links = node_links(mesh);
  int moved = 0;
  for (;;) {
    std::vector<std::size_t> inverted;
    for (std::size_t e = 0; e < mesh.elements.size(); ++e)
      if (!(min_relative_tet_jacobian(mesh, mesh.elements[e]) > kMinRelativeJacobian))
        inverted.push_back(e);
    if (inverted.empty()) return moved;
    int moved_now = 0;
    for (std::size_t e : inverted) {
      const solid::Element& element = mesh.elements[e];
      if (element.type != solid::ElementType::Tet10) continue;
      for (std::size_t k = 0; k < kTetEdges.size(); ++k) {
        const int node = element.nodes[4 + k];
        const Eigen::Vector3d midpoint =
            0.5 * (mesh.coords[static_cast<std::size_t>(
                       element.nodes[static_cast<std::size_t>(kTetEdges[k][0])])] +
                   mesh.coords[static_cast<std::size_t>(
                       element.nodes[static_cast<std::size_t>(kTetEdges[k][1])])]);
        if (mesh.coords[static_cast<std::size_t>(node)] == midpoint) continue;
        // Move the node and every copy reachable through the links, each rotated accordingly.
        std::vector<std::pair<int, int>> stack{{node, 0}};
        std::set<int> seen{node};
        while (!stack.empty()) {
          const auto [n, turns] = stack.back();
          stack.pop_back();
          mesh.coords[static_cast<std::size_t>(n)] =
              Eigen::AngleAxisd(turns * alpha, Eigen::Vector3d::UnitZ()) * midpoint;
          ++moved_now;
          for (const auto& [other, step] : links[static_cast<std::size_t>(n)])
            if (seen.insert(other).second) stack.emplace_back(other, turns + step);
        }
      }
    }
    if (moved_now == 0) {
      const solid::Element& e = mesh.elements[inverted.front()];
      const Eigen::Vector3d& c = mesh.coords[static_cast<std::size_t>(e.nodes[0])];
      throw NumericalError(kAnalysis,
                           fmt::format("{} tets are inverted even with straight edges, e.g. "
                                       "element {} at ({:.6g}, {:.6g}, {:.6g}) m",
                                       inverted.size(), e.id, c.x(), c.y(), c.z()));
    }
    moved += moved_now;
  }
}

// The gear (and ring) volumes of the sector, and the radius of the groove's contact face.
struct SectorBodies {
  std::vector<int> gear, ring;
  double contact_radius = 0;
};

SectorBodies sector_bodies(const GearSectorParams& p, const ToothGeometry& tooth, double alpha) {
  const int teeth_per_sector = p.num_teeth / p.num_sectors;
  SectorBodies out;
  std::vector<int>& gear = out.gear;
  std::vector<int>& ring = out.ring;
  double& contact_radius = out.contact_radius;
  // Blank: hub, web and rim (minus groove) half-sections, revolved by the sector angle.
  const double b = p.face_width;
  const int hub_face =
      add_section_rectangle(p.bore_radius, p.hub_outer_radius, p.hub_offset - 0.5 * p.hub_width,
                            p.hub_offset + 0.5 * p.hub_width);
  const int web_face = add_section_rectangle(p.hub_outer_radius, p.rim_inner_radius,
                                             p.web_offset - 0.5 * p.web_thickness,
                                             p.web_offset + 0.5 * p.web_thickness);
  gmsh::vectorpair rim_faces = {
      {2, add_section_rectangle(p.rim_inner_radius, tooth.root_radius, -0.5 * b, 0.5 * b)}};
  if (p.groove) {
    const GrooveParams& g = *p.groove;
    contact_radius = p.rim_inner_radius + g.depth;
    const int notch =
        add_section_rectangle(p.rim_inner_radius, contact_radius, g.axial_position - 0.5 * g.width,
                              g.axial_position + 0.5 * g.width);
    gmsh::vectorpair cut;
    std::vector<gmsh::vectorpair> cut_map;
    occ::cut(rim_faces, {{2, notch}}, cut, cut_map);
    rim_faces = cut;
  }
  gmsh::vectorpair blank_faces = {{2, hub_face}, {2, web_face}};
  blank_faces.insert(blank_faces.end(), rim_faces.begin(), rim_faces.end());
  const std::vector<int> blank_volumes = revolve_faces(blank_faces, alpha);

  std::vector<int> tooth_volumes;
  for (int j = 0; j < teeth_per_sector; ++j)
    tooth_volumes.push_back(add_tooth(tooth, (j + 0.5) * 2.0 * units::kPi / p.num_teeth, b));

  // One gear solid: fusing (rather than fragmenting) the blank pieces and the teeth leaves no
  // internal faces; a flat tet with its four corners on such a curved internal face (e.g. the
  // web / rim cylinder) would turn inside out when its mid-nodes are curved.
  gmsh::vectorpair tools;
  for (std::size_t i = 1; i < blank_volumes.size(); ++i) tools.emplace_back(3, blank_volumes[i]);
  for (int v : tooth_volumes) tools.emplace_back(3, v);
  gmsh::vectorpair fused;
  std::vector<gmsh::vectorpair> fused_map;
  occ::fuse({{3, blank_volumes.front()}}, tools, fused, fused_map);
  for (const auto& [dim, tag] : fused)
    if (dim == 3) gear.push_back(tag);
  if (p.groove) {
    // Fragment gear and ring so that the contact face is one face shared by both (conforming
    // meshes); outDimTagsMap[i] holds the pieces of input i (gear volumes first, then ring).
    gmsh::vectorpair objects, ring_tools, fragments;
    for (int v : gear) objects.emplace_back(3, v);
    const std::vector<int> ring_volumes = revolve_faces(
        {{2, add_section_rectangle(contact_radius - p.groove->ring.radial_thickness, contact_radius,
                                   p.groove->ring.axial_position - 0.5 * p.groove->ring.width,
                                   p.groove->ring.axial_position + 0.5 * p.groove->ring.width)}},
        alpha);
    for (int v : ring_volumes) ring_tools.emplace_back(3, v);
    std::vector<gmsh::vectorpair> pieces;
    occ::fragment(objects, ring_tools, fragments, pieces);
    std::set<int> gear_pieces, ring_pieces;
    for (std::size_t i = 0; i < pieces.size(); ++i)
      for (const auto& [dim, tag] : pieces[i])
        if (dim == 3) (i < objects.size() ? gear_pieces : ring_pieces).insert(tag);
    gear.assign(gear_pieces.begin(), gear_pieces.end());
    ring.assign(ring_pieces.begin(), ring_pieces.end());
  }
  if (gear.empty() || (p.groove && ring.empty()) || !intersection(gear, ring).empty())
    throw NumericalError(kAnalysis,
                         "the boolean operations did not give separate gear and ring "
                         "bodies");
  return out;
}

// The excitation point (the pitch point of the first flank), embedded as a mesh node in the
// flank face it lies on. Returns its Gmsh point tag.
int embed_excitation_point(const GearSectorParams& p, const ToothGeometry& tooth,
                           const std::vector<int>& gear, double tol) {
  const Eigen::Vector3d pitch_point = flank_point(tooth, units::kPi / p.num_teeth);
  const int excitation_point = occ::addPoint(pitch_point.x(), pitch_point.y(), pitch_point.z());
  occ::synchronize();

  // The excitation point becomes a mesh node of the flank face it lies on.
  int flank = -1;
  for (int s : boundary_surfaces(gear)) {
    std::vector<double> closest, uv;
    gmsh::model::getClosestPoint(2, s, {pitch_point.x(), pitch_point.y(), pitch_point.z()}, closest,
                                 uv);
    if ((Eigen::Vector3d(closest[0], closest[1], closest[2]) - pitch_point).norm() <= tol &&
        gmsh::model::isInside(2, s, uv)) {
      flank = s;
      break;
    }
  }
  if (flank < 0) throw NumericalError(kAnalysis, "no tooth flank face holds the pitch point");
  gmsh::model::mesh::embed(0, {excitation_point}, 2, flank);
  return excitation_point;
}

// Sizes at the geometric points, graded in between by Gmsh's interpolation.
void set_point_sizes(const GearSectorParams& p, const ToothGeometry& tooth,
                     const SectorBodies& bodies, int excitation_point, double tol) {
  const std::vector<int>& gear = bodies.gear;
  const std::vector<int>& ring = bodies.ring;
  const double contact_radius = bodies.contact_radius;
  const double size_tooth = p.mesh.tooth > 0 ? p.mesh.tooth : p.mesh.global;
  const double size_groove = p.mesh.groove > 0 ? p.mesh.groove : p.mesh.global;
  gmsh::vectorpair all_points;
  gmsh::model::getEntities(all_points, 0);
  std::map<int, double> size;
  for (const auto& [dim, tag] : all_points) size[tag] = p.mesh.global;
  auto refine = [&](const std::vector<int>& points, double h) {
    for (int t : points) size[t] = std::min(size[t], h);
  };
  std::vector<int> tooth_points;  // points on or outside the root circle
  for (int t : points_of(gear)) {
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(0, t, x0, y0, z0, x1, y1, z1);
    if (std::hypot(x0, y0) >= tooth.root_radius - tol) tooth_points.push_back(t);
  }
  refine(tooth_points, size_tooth);
  refine({excitation_point}, size_tooth);
  if (p.groove) {
    refine(points_of(ring), size_groove);
    const Interval groove = centred(p.groove->axial_position, p.groove->width);
    std::vector<int> groove_points;
    for (const auto& [dim, tag] : all_points) {
      double x0, y0, z0, x1, y1, z1;
      gmsh::model::getBoundingBox(0, tag, x0, y0, z0, x1, y1, z1);
      const double r = std::hypot(x0, y0);
      if (r >= p.rim_inner_radius - tol && r <= contact_radius + tol && z0 >= groove.lo - tol &&
          z0 <= groove.hi + tol)
        groove_points.push_back(tag);
    }
    refine(groove_points, size_groove);
  }
  for (const auto& [tag, h] : size) gmsh::model::mesh::setSize({{0, tag}}, h);
}

// The node sets of the sector mesh: sector faces, bore, tooth tip, excitation point and (with a
// groove) the contact faces and the ring's sector faces.
void add_node_sets(solid::Mesh& mesh, const GmshMeshExtraction& extraction,
                   const GearSectorParams& p, const ToothGeometry& tooth,
                   const SectorBodies& bodies, const std::vector<int>& left,
                   const std::vector<int>& right, int excitation_point, double tol) {
  const std::vector<int>& gear = bodies.gear;
  const std::vector<int>& ring = bodies.ring;
  const double contact_radius = bodies.contact_radius;
  const std::vector<int> gear_surfaces = boundary_surfaces(gear);
  mesh.node_sets["left"] = extraction.body_nodes_on(0, 2, intersection(left, gear_surfaces));
  mesh.node_sets["right"] = extraction.body_nodes_on(0, 2, intersection(right, gear_surfaces));
  mesh.node_sets["bore"] =
      extraction.body_nodes_on(0, 2, surfaces_at_radius(gear_surfaces, p.bore_radius, tol));
  mesh.node_sets["tooth_tip"] =
      extraction.body_nodes_on(0, 2, surfaces_at_radius(gear_surfaces, tooth.tip_radius, tol));
  mesh.node_sets["excitation"] = extraction.body_nodes_on(0, 0, {excitation_point});
  if (mesh.node_sets["excitation"].size() != 1)
    throw NumericalError(kAnalysis, "the excitation point did not become a gear mesh node");
  if (p.groove) {
    const std::vector<int> ring_surfaces = boundary_surfaces(ring);
    const std::vector<int> contact =
        intersection(surfaces_at_radius(ring_surfaces, contact_radius, tol), gear_surfaces);
    if (contact.empty())
      throw NumericalError(kAnalysis, "the ring's outer face is not shared with the groove");
    mesh.node_sets["groove_contact"] = extraction.body_nodes_on(0, 2, contact);
    mesh.node_sets["ring_contact"] = extraction.body_nodes_on(1, 2, contact);
    mesh.node_sets["ring_left"] = extraction.body_nodes_on(1, 2, intersection(left, ring_surfaces));
    mesh.node_sets["ring_right"] =
        extraction.body_nodes_on(1, 2, intersection(right, ring_surfaces));
  }
}

solid::Mesh build(const GearSectorParams& p, Progress& progress) {
  const ToothGeometry tooth = resolve_tooth(p);
  const double alpha = sector_angle(p);
  const double scale = tooth.tip_radius;
  const double tol = 1e-7 * scale;

  GmshSession session("geardyn_gear_sector");
  progress.start("gear sector mesh", 4);

  const SectorBodies sector = sector_bodies(p, tooth, alpha);
  const int excitation_point = embed_excitation_point(p, tooth, sector.gear, tol);

  // Periodic sector faces: right = R(alpha) left.
  const std::vector<int> left = surfaces_on_half_plane(0.0, tol);
  const std::vector<int> right = surfaces_on_half_plane(alpha, tol);
  if (left.empty() || left.size() != right.size())
    throw NumericalError(kAnalysis, fmt::format("found {} faces at theta = 0 and {} at theta = "
                                                "2 pi / N; expected the same non-zero number",
                                                left.size(), right.size()));
  const std::vector<int> masters = match_left(left, right, alpha, tol);
  const double c = std::cos(alpha), s = std::sin(alpha);
  gmsh::model::mesh::setPeriodic(2, right, masters,
                                 {c, -s, 0, 0, s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});

  set_point_sizes(p, tooth, sector, excitation_point, tol);
  progress.update(1);

  gmsh::option::setNumber("Mesh.ElementOrder", p.mesh.element_order);
  gmsh::model::mesh::generate(3);
  progress.update(3);

  std::vector<GmshBody> bodies = {{"gear", 0, sector.gear}};
  if (p.groove) bodies.push_back({"ring", 1, sector.ring});
  GmshMeshExtraction extraction(kAnalysis, bodies, left, right, alpha, scale);
  solid::Mesh mesh = std::move(extraction.mesh());
  mesh.source = fmt::format("gear_sector(N={}, z={}, order {})", p.num_sectors, p.num_teeth,
                            p.mesh.element_order);
  mesh.materials.push_back(p.gear_material);
  if (p.groove) mesh.materials.push_back(p.ring_material);

  add_node_sets(mesh, extraction, p, tooth, sector, left, right, excitation_point, tol);
  if (const int moved = untangle_tets(mesh, alpha); moved > 0)
    mesh.source += fmt::format(", {} mid-edge nodes straightened to untangle curved tets", moved);
  progress.update(4);
  progress.finish();
  return mesh;
}

}  // namespace

solid::Mesh gear_sector(const GearSectorParams& params, Progress& progress) {
  validate(params);
  try {
    return build(params, progress);
  } catch (const std::string& gmsh_error) {
    throw NumericalError(kAnalysis,
                         fmt::format("Gmsh failed: {} (a smaller mesh size at the teeth / groove, "
                                     "or less extreme proportions, usually helps)",
                                     gmsh_error));
  }
}

}  // namespace geardyn::meshgen
