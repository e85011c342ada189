#pragma once
// Isoparametric linear-elastic isotropic solid elements: stiffness and consistent mass.
//
//   K_e = ∫ B^T D B dV,   M_e = ∫ rho N^T N dV        (Zienkiewicz & Taylor, The Finite Element
//   Method, vol. 1, 6th ed., ch. 6 and 8; Bathe, Finite Element Procedures, 1996, §5.3)
//
// DOF order is node-major: (u_x, u_y, u_z) of node 0, then node 1, ... (3 n DOFs), nodes in Gmsh
// order (see mesh.hpp). D is the isotropic elasticity matrix in Voigt order
// (xx, yy, zz, xy, yz, zx) with engineering shear strains.
//
// Quadrature (exact for the mass of an undistorted, i.e. affine or parallelepiped, element):
//   Tet4     K: 1 point           M: degree-2 rule (4 points)
//   Tet10    K: degree-2 (4 pts)  M: degree-5 rule (14 points, positive weights) [N^T N: degree 4]
//   Hex8     K, M: 2x2x2 Gauss
//   Hex20    K, M: 3x3x3 Gauss (full integration, no hourglass modes)
//   Wedge6   K, M: 6-point rule = degree-2 triangle (3 pts) x 2-point Gauss
//   Wedge15  K, M: 21-point rule = degree-5 triangle (7 pts) x 3-point Gauss
//
// The stiffness rules are exact for straight-edged elements (tet10: affine; hex20: trilinear
// geometry), which therefore pass the patch test exactly; elements with curved edges are
// integrated with the usual rules of commercial codes (e.g. 4 points for tet10).
//
// Degenerate or inverted elements: the Jacobian determinant is checked at every quadrature
// point and at every node; an element whose smallest value is <= kMinJacobianRatio times its
// mean (volume / reference volume) is rejected with InputError.
#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::solid {

/// Smallest accepted ratio  min det J / mean det J  (1 for an affine element; a value this small
/// means a collapsed or nearly flat element whose stiffness would be meaningless).
inline constexpr double kMinJacobianRatio = 1e-6;

struct ElementMatrices {
  Eigen::MatrixXd K;  ///< 3n x 3n stiffness [N/m], node-major DOFs
  Eigen::MatrixXd M;  ///< 3n x 3n consistent mass [kg]
  double volume = 0;  ///< [m^3]
};

/// Stiffness and consistent mass of one element with node coordinates `x` (num_element_nodes(type)
/// of them, Gmsh order). Throws InputError naming `element_id` and `where` (key path
/// "elements[id <element_id>]") for a degenerate/inverted element, a wrong node count, or an
/// invalid material (E <= 0, nu outside (-1, 0.5), rho < 0; key path "materials[<name>]").
ElementMatrices element_matrices(ElementType type, const std::vector<Eigen::Vector3d>& x,
                                 const Material& material, long element_id = 0,
                                 const SourceLocation& where = {});

/// Same for element `index` of `mesh` (its coordinates, its material, its id and location).
ElementMatrices element_matrices(const Mesh& mesh, int index);

/// Shape-function mass matrix  m_ab = ∫ N_a N_b dV  (n x n, no density); the consistent mass
/// is rho * m ⊗ I_3. Same quadrature and checks as element_matrices.
Eigen::MatrixXd element_shape_mass(ElementType type, const std::vector<Eigen::Vector3d>& x,
                                   long element_id = 0, const SourceLocation& where = {});

/// Quality of the element geometry.
struct ElementQuality {
  double min_det_j = 0;  ///< smallest det J over quadrature points and nodes
  double max_det_j = 0;  ///< largest det J over the same points
  double volume = 0;     ///< ∫ dV [m^3] (stiffness rule)
  double min_ratio = 0;  ///< min_det_j / (volume / reference volume); <= 0: inverted
};

/// Jacobian quality of an element; never throws for bad geometry (throws InputError only for a
/// wrong node count).
ElementQuality element_quality(ElementType type, const std::vector<Eigen::Vector3d>& x);

/// min det J / mean det J (see ElementQuality::min_ratio): 1 for affine elements, <= 0 inverted.
double element_min_jacobian(ElementType type, const std::vector<Eigen::Vector3d>& x);

/// Shape functions N (n) and their derivatives dN/dxi (n x 3) at reference point `xi`.
/// Reference domains: tet {xi,eta,zeta >= 0, sum <= 1} (node 0 at the origin); hex [-1,1]^3;
/// wedge triangle {xi,eta >= 0, xi + eta <= 1} x zeta in [-1,1] (bottom face zeta = -1).
void shape_functions(ElementType type, const Eigen::Vector3d& xi, Eigen::VectorXd& N,
                     Eigen::MatrixXd& dN);

/// Reference coordinates of the element's nodes (n x 3), in Gmsh order.
Eigen::MatrixXd reference_nodes(ElementType type);

/// The corner pairs of the mid-edge nodes of a quadratic element, in node order (mid-edge node
/// k + number of corners lies on edge k); empty for linear elements. See mesh.hpp.
std::vector<std::array<int, 2>> element_edges(ElementType type);

/// Number of corner nodes (4, 8 or 6).
int num_corner_nodes(ElementType type);

/// Isotropic elasticity matrix (6x6, Voigt xx,yy,zz,xy,yz,zx, engineering shear) [Pa].
Eigen::Matrix<double, 6, 6> elasticity_matrix(double E, double nu);

/// Checks E > 0, -1 < nu < 0.5, rho >= 0 (all finite); throws InputError (key path
/// "materials[<name or id>]") otherwise.
void check_material(const Material& material);

}  // namespace geardyn::solid
