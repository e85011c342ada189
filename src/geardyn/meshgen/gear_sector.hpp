#pragma once
// Parametric mesh of one cyclic sector of a gear blank with simplified teeth and an optional
// damper-ring groove with its split ring (the models of damper-ring gear studies: one sector of a
// gear and one sector of the ring, meshed separately, coupled by friction contacts at node pairs
// of the groove's radial contact face; cyclic symmetry joins the sectors).
//
// Geometry (axis z, SI units). The blank is axisymmetric; its (r, z) half-section is
//
//     r ^
//  tip  |            +=========+          teeth (transverse trapezoids, root -> tip radius)
//  root |      +-----+---------+-----+
//       |      |   rim           +--+|    groove notch in the rim bore, ring (R) inside it,
//       |      |                 |RR||    the ring's outer face on the groove bottom
//  rim  |      +------+   +------+--+-+
//  bore |             |web|
//       |         +---+   +---+
//  hub  |         |    hub    |
//  bore |         +-----------+
//       +---------------------------------> z
//
// i.e. three rectangles in (r, z): hub [bore, hub_outer] x hub_offset +- hub_width/2; web
// [hub_outer, rim_inner] x web_offset +- web_thickness/2; rim [rim_inner, root] x +- face_width/2
// (the rim is centred on z = 0). The groove is a rectangular notch in the rim's inner surface:
// [rim_inner, rim_inner + depth] x groove.axial_position +- groove.width/2; it must not overlap
// the web. The ring is the rectangle [r_c - ring.radial_thickness, r_c] x ring.axial_position
// +- ring.width/2 inside the groove, with r_c = rim_inner + depth: its outer cylindrical face
// lies on the groove bottom, which is the radial contact face (centrifugal load presses the
// split ring outwards against it).
//
// Teeth: z teeth on the full wheel, z / num_sectors per sector, centred at theta_j = (j + 1/2)
// 2 pi / z (so the sector faces cut through tooth spaces). A tooth's transverse section is
// bounded by the root circle, the tip circle and two straight flanks joining the points at
// half-angle beta_f = s_f / (2 r_f) on the root circle and beta_a = s_a / (2 r_a) on the tip
// circle (s = arc tooth thickness); it is extruded over the face width. Its area is
//   A = r_f r_a sin(beta_f - beta_a) + r_a^2 beta_a - r_f^2 beta_f.
// From a module m and pressure angle alpha (ToothProfile::Module): r_p = m z / 2, r_a = r_p +
// addendum m, r_f = r_p - dedendum m, and the basic-rack thickness s(y) = pi m / 2 - 2 y tan alpha
// at height y above the pitch circle gives s_a and s_f (a trapezoid, not an involute).
//
// Mesh: quadratic (tet10, mid-nodes on the curved geometry) or linear tets, through the Gmsh
// API with the OpenCASCADE kernel (blank and teeth fused into one solid, then fragmented with
// the ring); faces at theta = 0 and theta = 2 pi / num_sectors meshed periodically; the groove
// contact face meshed once and its nodes duplicated for the ring, so gear and ring are separate
// bodies with coincident contact node pairs. Sizes are set at the geometric points (global,
// tooth: every point at r >= root radius, groove: points of the groove and ring) and graded
// in between by Gmsh. A tet10 that curving turns inside out (or whose det J falls below 5 % of
// its straight shape's) gets straight edges (mid-nodes at the edge midpoints, periodic partners
// and contact twins moved alike); Mesh::source then says how many nodes moved. Deterministic:
// the same parameters give the same mesh (see meshgen/gmsh_session.hpp).
#include <optional>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::meshgen {

enum class ToothProfile {
  Module,    ///< from module, pressure angle and addendum / dedendum coefficients
  Explicit,  ///< root / tip radius and arc thicknesses given directly
};

struct ToothParams {
  ToothProfile profile = ToothProfile::Module;
  // ToothProfile::Module
  double module = 0;                                ///< [m]
  double pressure_angle = 20.0 * units::kPi / 180;  ///< [rad]
  double addendum_coefficient = 1.0;                ///< tip radius = r_p + this * module
  double dedendum_coefficient = 1.25;               ///< root radius = r_p - this * module
  // ToothProfile::Explicit
  double root_radius = 0;     ///< r_f [m] (= the rim's outer radius)
  double tip_radius = 0;      ///< r_a [m]
  double pitch_radius = 0;    ///< r_p [m], where the excitation node is placed
  double root_thickness = 0;  ///< s_f, arc length at r_f [m]
  double tip_thickness = 0;   ///< s_a, arc length at r_a [m]
};

/// The resolved tooth dimensions (both profiles end up here).
struct ToothGeometry {
  double root_radius = 0, tip_radius = 0, pitch_radius = 0;
  double root_thickness = 0, tip_thickness = 0;
  /// Transverse area of one tooth outside the root circle [m^2] (formula in the file comment).
  double area() const;
};

struct RingParams {
  double width = 0;             ///< axial width [m], <= groove width
  double axial_position = 0;    ///< axial centre [m]; the ring must lie inside the groove
  double radial_thickness = 0;  ///< [m]; inner radius = groove bottom radius - this
};

struct GrooveParams {
  double axial_position = 0;  ///< axial centre of the groove [m]
  double width = 0;           ///< axial width [m]
  double depth = 0;           ///< radial depth into the rim, measured from rim_inner_radius [m]
  RingParams ring;
};

struct SectorMeshSize {
  double global = 0;      ///< target element size away from teeth and groove [m]
  double tooth = 0;       ///< size in the teeth [m] (0: global)
  double groove = 0;      ///< size on the groove and ring [m] (0: global)
  int element_order = 2;  ///< 1: tet4, 2: tet10 (curved)
};

struct GearSectorParams {
  int num_sectors = 0;  ///< N >= 2; sector angle 2 pi / N
  int num_teeth = 0;    ///< z, a multiple of N
  double bore_radius = 0;
  double hub_outer_radius = 0;
  double hub_width = 0;
  double hub_offset = 0;  ///< axial centre of the hub [m]
  double web_thickness = 0;
  double web_offset = 0;  ///< axial centre of the web [m]
  double rim_inner_radius = 0;
  double face_width = 0;  ///< rim and teeth width, centred on z = 0 [m]
  ToothParams tooth;
  std::optional<GrooveParams> groove;  ///< none: a plain gear sector, no ring body
  SectorMeshSize mesh;
  solid::Material gear_material;
  solid::Material ring_material;
  std::string key_path = "gear_sector";  ///< prefix of key paths in error messages
  SourceLocation where{};                ///< where the parameters were defined
};

/// Tooth dimensions from the parameters (validated: InputError naming the key).
ToothGeometry resolve_tooth(const GearSectorParams& params);

/// Checks every parameter; throws InputError naming the first bad key (e.g.
/// "gear_sector.num_teeth" when z is not a multiple of N, "gear_sector.groove.depth" when the
/// groove leaves the rim, "gear_sector.bore_radius" when bore >= hub).
void validate(const GearSectorParams& params);

/// Analytic volumes of the idealised geometry [m^3]: gear sector (blank - groove + teeth) and
/// ring sector.
struct SectorVolumes {
  double gear = 0, ring = 0;
};
SectorVolumes analytic_volumes(const GearSectorParams& params);

/// Meshes one sector. The result has
///   materials      [0] gear_material, [1] ring_material (only with a groove)
///   element sets   "gear", "ring" (only with a groove)
///   node sets      "left", "right": gear nodes on theta = 0 and theta = 2 pi / N; right[i] is
///                  left[i] rotated by 2 pi / N about z (exactly, to round-off);
///                  "bore": gear nodes on r = bore_radius;
///                  "tooth_tip": gear nodes on the tip faces of the sector's teeth;
///                  "excitation": one node, exactly at the pitch radius on mid-face (z = 0) of
///                  the flank facing +theta of the first tooth (theta_0 = pi / z) -- a mesh node
///                  is forced there;
///   with a groove  "groove_contact" (gear) and "ring_contact" (ring): nodes of the contact
///                  face, same length, i-th coincides with i-th (distinct nodes);
///                  "ring_left", "ring_right": the ring's sector faces, paired like left/right.
/// All node sets are sorted. Throws InputError for bad parameters, NumericalError if Gmsh fails
/// or the result is not periodic.
solid::Mesh gear_sector(const GearSectorParams& params, Progress& progress = null_progress());

}  // namespace geardyn::meshgen
