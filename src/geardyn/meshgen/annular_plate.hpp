#pragma once
// Structured mesh of an annular plate (or a sector of it): inner radius b, outer radius a,
// thickness h, mid-plane z = 0, axis z, the sector theta in [0, sector_angle].
//
// The mesh is mapped (transfinite) in the plane -- n_r elements radially, n_theta
// circumferentially -- and extruded through the thickness in n_t layers, so every element is a
// hexahedron (or a wedge, two per quadrilateral), with quadratic serendipity elements (hex20 /
// wedge15, mid-nodes on the circular arcs) for order 2. Thin plates need the quadratic elements
// and at least two layers for accurate bending (locking-free enough for h/a ~ 1/30); see the
// validation tests of the solid elements.
//
// Solid disc (b = 0, the whole plate only): an "O-grid" in the plane -- a centre square with its
// corners on the x and y axes at r = a / 2, n_theta / 4 x n_theta / 4 elements, and four ring
// patches from its sides to the rim, n_r elements radially -- so no element is degenerate and the
// centre is meshed once. n_theta is rounded up to a multiple of 4. A sector of a disc is refused
// (its apex lies on the axis, which cyclic symmetry does not support).
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::meshgen {

enum class PlateElementShape {
  Hex,    ///< hex8 / hex20
  Wedge,  ///< wedge6 / wedge15 (each in-plane quadrilateral split into two triangles)
};

struct AnnularPlateParams {
  double inner_radius = 0;              ///< b [m], >= 0 (0: a solid disc, full plate only)
  double outer_radius = 0;              ///< a [m], > b
  double thickness = 0;                 ///< h [m]
  double sector_angle = units::kTwoPi;  ///< (0, 2 pi]; 2 pi: the full plate
  int element_order = 2;                ///< 1 or 2
  PlateElementShape shape = PlateElementShape::Hex;
  double mesh_size = 0;     ///< target in-plane element size [m]; sets n_r and n_theta when those
                            ///< are 0: n_r = ceil((a - b) / size), n_theta = ceil(angle a / size)
                            ///< (disc: b replaced by a / 2, the centre square's corner radius)
  int elements_radial = 0;  ///< n_r (0: from mesh_size)
  int elements_circumferential = 0;    ///< n_theta over the whole sector angle (0: from mesh_size)
  int elements_through_thickness = 2;  ///< n_t >= 1
  solid::Material material;
  std::string key_path = "annular_plate";  ///< prefix of key paths in error messages
  SourceLocation where{};
};

/// Checks every parameter; throws InputError naming the first bad key.
void validate(const AnnularPlateParams& params);

/// Meshes the plate. Element set "plate", material [0]. Node sets (sorted): "inner" (r = b; none
/// for a disc),
/// "outer" (r = a), "bottom" (z = -h/2), "top" (z = +h/2) and, for a sector (angle < 2 pi),
/// "left" (theta = 0) and "right" (theta = angle), right[i] = left[i] rotated by the angle.
solid::Mesh annular_plate(const AnnularPlateParams& params, Progress& progress = null_progress());

}  // namespace geardyn::meshgen
