#include "geardyn/meshgen/annular_plate.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <algorithm>
#include <cmath>

#include "geardyn/core/units.hpp"
#include "geardyn/meshgen/gmsh_session.hpp"

namespace geardyn::meshgen {
namespace {

constexpr const char* kAnalysis = "annular_plate";

/// A solid disc's centre square has its corners at this fraction of the outer radius.
constexpr double kDiscCentreFraction = 0.5;

bool is_full(const AnnularPlateParams& p) { return p.sector_angle >= units::kTwoPi * (1 - 1e-12); }

/// Patches of at most 90 degrees: the built-in kernel's circle arcs must stay below 180.
int num_patches(const AnnularPlateParams& p) {
  return std::max(1, static_cast<int>(std::ceil(p.sector_angle / (0.5 * units::kPi) - 1e-9)));
}

struct Divisions {
  int radial = 0, circumferential = 0;
};

bool is_disc(const AnnularPlateParams& p) { return p.inner_radius == 0.0; }

Divisions divisions(const AnnularPlateParams& p) {
  Divisions d;
  const double a = p.outer_radius, b = is_disc(p) ? kDiscCentreFraction * a : p.inner_radius;
  d.radial = p.elements_radial > 0 ? p.elements_radial
                                   : static_cast<int>(std::ceil((a - b) / p.mesh_size - 1e-9));
  d.circumferential =
      p.elements_circumferential > 0
          ? p.elements_circumferential
          : std::max(num_patches(p),
                     static_cast<int>(std::ceil(p.sector_angle * a / p.mesh_size - 1e-9)));
  // A disc's centre square has n_theta / 4 elements on each side: n_theta a multiple of 4.
  if (is_disc(p)) d.circumferential = 4 * ((d.circumferential + 3) / 4);
  return d;
}

}  // namespace

void validate(const AnnularPlateParams& p) {
  auto fail = [&](const std::string& key, const std::string& expected, double found) {
    throw InputError(p.where, p.key_path + "." + key, expected, fmt::format("{:.6g}", found));
  };
  auto positive = [&](const std::string& key, double value) {
    if (!(value > 0) || !std::isfinite(value)) fail(key, "a positive finite number", value);
  };
  if (!(p.inner_radius >= 0) || !std::isfinite(p.inner_radius))
    fail("inner_radius", "a finite radius >= 0 (0: a solid disc)", p.inner_radius);
  if (p.inner_radius == 0.0 && !is_full(p))
    throw InputError(
        p.where, p.key_path + ".inner_radius",
        "inner_radius > 0 for a sector of a plate (sectors > 1)",
        fmt::format("0 with a sector angle of {:.6g} deg", p.sector_angle / units::kTwoPi * 360.0),
        "a solid disc's centre lies on the axis, in every sector, which cyclic "
        "symmetry does not support: set sectors = 1 for a disc, or give the "
        "sector a small hole (inner_radius > 0)");
  if (!(p.outer_radius > p.inner_radius) || !std::isfinite(p.outer_radius))
    fail("outer_radius", fmt::format("> inner_radius ({:.6g})", p.inner_radius), p.outer_radius);
  positive("thickness", p.thickness);
  if (!(p.sector_angle > 0 && p.sector_angle <= units::kTwoPi * (1 + 1e-12)))
    fail("sector_angle", "an angle in (0, 2 pi] rad", p.sector_angle);
  if (p.element_order != 1 && p.element_order != 2)
    fail("element_order", "1 or 2", p.element_order);
  if (p.elements_radial < 0) fail("elements_radial", ">= 0 (0: from mesh_size)", p.elements_radial);
  if (p.elements_circumferential < 0)
    fail("elements_circumferential", ">= 0 (0: from mesh_size)", p.elements_circumferential);
  if ((p.elements_radial == 0 || p.elements_circumferential == 0))
    positive("mesh_size", p.mesh_size);
  if (p.elements_circumferential > 0 && p.elements_circumferential < num_patches(p))
    fail("elements_circumferential",
         fmt::format(">= {} (one element per 90 degrees at least)", num_patches(p)),
         p.elements_circumferential);
  if (p.elements_through_thickness < 1)
    fail("elements_through_thickness", ">= 1", p.elements_through_thickness);
  positive("material.E", p.material.E);
  positive("material.rho", p.material.rho);
  if (!(p.material.nu > -1.0 && p.material.nu < 0.5))
    fail("material.nu", "a Poisson's ratio in (-1, 0.5)", p.material.nu);
}

namespace {

namespace geo = gmsh::model::geo;

std::vector<int> surfaces_at_height(double z, double tol) {
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  std::vector<int> out;
  for (const auto& [dim, tag] : surfaces) {
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(2, tag, x0, y0, z0, x1, y1, z1);
    if (std::abs(z0 - z) <= tol && std::abs(z1 - z) <= tol) out.push_back(tag);
  }
  return out;
}

// In-plane patches of an annulus b..a: one ring patch per <= 90 degrees, each n_r x n_arc.
gmsh::vectorpair annulus_patches(const AnnularPlateParams& p, const Divisions& n, int centre,
                                 double z0) {
  const bool full = is_full(p);
  const double angle = full ? units::kTwoPi : p.sector_angle;
  const int patches = full ? 4 : num_patches(p);
  const double a = p.outer_radius, b = p.inner_radius;
  std::vector<int> inner, outer;  // points at theta_k, k = 0..patches (last = first if full)
  for (int k = 0; k <= patches; ++k) {
    if (full && k == patches) {
      inner.push_back(inner.front());
      outer.push_back(outer.front());
      break;
    }
    const double theta = angle * k / patches;
    inner.push_back(geo::addPoint(b * std::cos(theta), b * std::sin(theta), z0));
    outer.push_back(geo::addPoint(a * std::cos(theta), a * std::sin(theta), z0));
  }
  std::vector<int> radial;
  for (int k = 0; k <= patches; ++k) {
    if (full && k == patches) {
      radial.push_back(radial.front());
      break;
    }
    radial.push_back(geo::addLine(inner[k], outer[k]));
  }
  gmsh::vectorpair base;
  for (int k = 0; k < patches; ++k) {
    const int inner_arc = geo::addCircleArc(inner[k], centre, inner[k + 1]);
    const int outer_arc = geo::addCircleArc(outer[k], centre, outer[k + 1]);
    const int loop = geo::addCurveLoop({radial[k], outer_arc, -radial[k + 1], -inner_arc});
    const int surface = geo::addPlaneSurface({loop});
    // Circumferential elements spread over the patches as evenly as possible.
    const int n_arc = n.circumferential / patches + (k < n.circumferential % patches ? 1 : 0);
    geo::mesh::setTransfiniteCurve(inner_arc, n_arc + 1);
    geo::mesh::setTransfiniteCurve(outer_arc, n_arc + 1);
    base.emplace_back(2, surface);
  }
  for (int k = 0; k < (full ? patches : patches + 1); ++k)
    geo::mesh::setTransfiniteCurve(radial[k], n.radial + 1);
  return base;
}

// In-plane patches of a solid disc (an "O-grid"): a centre square with its corners on the axes
// at r = c = kDiscCentreFraction a, n_q x n_q elements (n_q = n_theta / 4), and four ring
// patches between its sides and the quarter arcs of the rim, n_r x n_q each. Every element is a
// proper quadrilateral (or two triangles); the centre is meshed once, so no node is duplicated
// and none is collapsed.
gmsh::vectorpair disc_patches(const AnnularPlateParams& p, const Divisions& n, int centre,
                              double z0) {
  const double a = p.outer_radius, c = kDiscCentreFraction * a;
  const int n_q = n.circumferential / 4;
  std::vector<int> corner, outer;
  for (int k = 0; k < 4; ++k) {
    const double theta = 0.5 * units::kPi * k;
    corner.push_back(geo::addPoint(c * std::cos(theta), c * std::sin(theta), z0));
    outer.push_back(geo::addPoint(a * std::cos(theta), a * std::sin(theta), z0));
  }
  std::vector<int> side, spoke, arc;
  for (int k = 0; k < 4; ++k) {
    side.push_back(geo::addLine(corner[k], corner[(k + 1) % 4]));
    spoke.push_back(geo::addLine(corner[k], outer[k]));
    arc.push_back(geo::addCircleArc(outer[k], centre, outer[(k + 1) % 4]));
  }
  gmsh::vectorpair base;
  base.emplace_back(2, geo::addPlaneSurface({geo::addCurveLoop(side)}));
  for (int k = 0; k < 4; ++k) {
    const int loop = geo::addCurveLoop({spoke[k], arc[k], -spoke[(k + 1) % 4], -side[k]});
    base.emplace_back(2, geo::addPlaneSurface({loop}));
    geo::mesh::setTransfiniteCurve(side[k], n_q + 1);
    geo::mesh::setTransfiniteCurve(arc[k], n_q + 1);
    geo::mesh::setTransfiniteCurve(spoke[k], n.radial + 1);
  }
  return base;
}

solid::Mesh build(const AnnularPlateParams& p, Progress& progress) {
  const bool full = is_full(p);
  const double angle = full ? units::kTwoPi : p.sector_angle;
  const Divisions n = divisions(p);
  const double a = p.outer_radius, b = p.inner_radius, h = p.thickness;
  const double z0 = -0.5 * h;
  const double tol = 1e-7 * a;

  GmshSession session("geardyn_annular_plate");
  progress.start("annular plate mesh", 3);

  const int centre = geo::addPoint(0, 0, z0);
  const gmsh::vectorpair base =
      is_disc(p) ? disc_patches(p, n, centre, z0) : annulus_patches(p, n, centre, z0);
  for (const auto& [dim, tag] : base) {
    geo::mesh::setTransfiniteSurface(tag);
    if (p.shape == PlateElementShape::Hex) geo::mesh::setRecombine(2, tag);
  }
  gmsh::vectorpair extruded;
  geo::extrude(base, 0, 0, h, extruded, {p.elements_through_thickness}, {}, true);
  geo::remove({{0, centre}});
  geo::synchronize();
  std::vector<int> volumes;
  for (const auto& [dim, tag] : extruded)
    if (dim == 3) volumes.push_back(tag);
  progress.update(1);

  gmsh::model::mesh::generate(3);
  if (p.element_order == 2) gmsh::model::mesh::setOrder(2);
  progress.update(2);

  const std::vector<int> left = full ? std::vector<int>{} : surfaces_on_half_plane(0.0, tol);
  const std::vector<int> right = full ? std::vector<int>{} : surfaces_on_half_plane(angle, tol);
  GmshMeshExtraction extraction(kAnalysis, {{"plate", 0, volumes}}, left, right, angle, a);
  solid::Mesh mesh = std::move(extraction.mesh());
  mesh.source = fmt::format(
      "annular_plate(b={:.6g}, a={:.6g}, h={:.6g}, angle={:.6g}, {}x{}x{}, "
      "order {})",
      b, a, h, angle, n.radial, n.circumferential, p.elements_through_thickness, p.element_order);
  mesh.materials.push_back(p.material);
  const std::vector<int> surfaces = boundary_surfaces(volumes);
  if (!is_disc(p))
    mesh.node_sets["inner"] = extraction.body_nodes_on(0, 2, surfaces_at_radius(surfaces, b, tol));
  mesh.node_sets["outer"] = extraction.body_nodes_on(0, 2, surfaces_at_radius(surfaces, a, tol));
  mesh.node_sets["bottom"] = extraction.body_nodes_on(0, 2, surfaces_at_height(-0.5 * h, tol));
  mesh.node_sets["top"] = extraction.body_nodes_on(0, 2, surfaces_at_height(0.5 * h, tol));
  if (!full) {
    mesh.node_sets["left"] = extraction.body_nodes_on(0, 2, left);
    mesh.node_sets["right"] = extraction.body_nodes_on(0, 2, right);
  }
  progress.update(3);
  progress.finish();
  return mesh;
}

}  // namespace

solid::Mesh annular_plate(const AnnularPlateParams& params, Progress& progress) {
  validate(params);
  try {
    return build(params, progress);
  } catch (const std::string& gmsh_error) {
    throw NumericalError(kAnalysis, fmt::format("Gmsh failed: {}", gmsh_error));
  }
}

}  // namespace geardyn::meshgen
