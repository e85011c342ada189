#pragma once
// A solid finite-element mesh as plain data: what the readers (Gmsh, Nastran) and the parametric
// generator produce, and what solid assembly consumes. Units SI (m, kg, N, Pa).
//
// Node ordering inside an element follows Gmsh's convention for every type (readers of other
// formats permute to it):
//   Tet4    0..3 corners
//   Tet10   corners 0..3, then mid-edge nodes on edges (0,1) (1,2) (2,0) (0,3) (2,3) (1,3)
//   Hex8    0..3 one face (counter-clockwise seen from the opposite face), 4..7 above 0..3
//   Hex20   corners 0..7, then mid-edge nodes on edges (0,1) (0,3) (0,4) (1,2) (1,5) (2,3) (2,6)
//           (3,7) (4,5) (4,7) (5,6) (6,7)
//   Wedge6  0..2 bottom triangle, 3..5 top triangle (i + 3 above i)
//   Wedge15 corners 0..5, then mid-edge nodes on edges (0,1) (0,2) (0,3) (1,2) (1,4) (2,5) (3,4)
//           (3,5) (4,5)
// (Gmsh reference manual, section "Node ordering".)
#include <Eigen/Dense>
#include <array>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/core/error.hpp"

namespace geardyn::solid {

enum class ElementType { Tet4, Tet10, Hex8, Hex20, Wedge6, Wedge15 };

constexpr int num_element_nodes(ElementType t) {
  switch (t) {
    case ElementType::Tet4:
      return 4;
    case ElementType::Tet10:
      return 10;
    case ElementType::Hex8:
      return 8;
    case ElementType::Hex20:
      return 20;
    case ElementType::Wedge6:
      return 6;
    case ElementType::Wedge15:
      return 15;
  }
  return 0;
}

constexpr std::string_view to_string(ElementType t) {
  switch (t) {
    case ElementType::Tet4:
      return "tet4";
    case ElementType::Tet10:
      return "tet10";
    case ElementType::Hex8:
      return "hex8";
    case ElementType::Hex20:
      return "hex20";
    case ElementType::Wedge6:
      return "wedge6";
    case ElementType::Wedge15:
      return "wedge15";
  }
  return "?";
}

/// Linear elastic isotropic material.
struct Material {
  std::string name;
  long id = 0;             ///< external id (Nastran MAT1 MID), 0 if none
  double E = 0;            ///< Young's modulus [Pa]
  double nu = 0;           ///< Poisson's ratio [-]
  double rho = 0;          ///< density [kg/m^3]
  SourceLocation where{};  ///< where it was defined (for error messages)
};

struct Element {
  ElementType type = ElementType::Tet4;
  long id = 0;             ///< external element id (Nastran EID / Gmsh tag)
  int material = 0;        ///< index into Mesh::materials
  std::vector<int> nodes;  ///< node indices (into Mesh::coords), Gmsh ordering
  SourceLocation where{};  ///< source line, for error messages naming the element
};

/// Concentrated mass on a node (Nastran CONM2): mass, offset and inertia about the centre of
/// gravity in global axes. A non-zero inertia gives the node rotational DOFs.
struct PointMass {
  long id = 0;
  int node = 0;
  double mass = 0;                                    ///< [kg]
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();   ///< CG offset from the node [m]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the CG [kg m^2]
  SourceLocation where{};
};

/// Spring between two node DOFs (Nastran CELAS1/CELAS2). node2 = -1: grounded.
/// Components 0..5 = ux, uy, uz, rx, ry, rz (global axes).
///
/// Each end acts along a unit vector n_e of its node's translation triple (component_e 0..2) or
/// rotation triple (component_e 3..5): the spring's stretch is d = n_1 . u_1 - n_2 . u_2 (u_e the
/// triple of node e), its energy k d^2 / 2, its stiffness k [n1 n1^T, -n1 n2^T; -n2 n1^T,
/// n2 n2^T] on the two 3x3 blocks. direction_e zero (the default): n_e is the component's own
/// global axis, the scalar spring of a Nastran CELAS on that one DOF. A non-zero direction_e
/// (replicate() sets it on the rotated copies of a sector's springs) must have unit length.
struct Spring {
  long id = 0;
  int node1 = -1, component1 = 0;
  int node2 = -1, component2 = 0;
  double stiffness = 0;                                  ///< [N/m] or [N m/rad]
  Eigen::Vector3d direction1 = Eigen::Vector3d::Zero();  ///< n_1 (zero: along component1)
  Eigen::Vector3d direction2 = Eigen::Vector3d::Zero();  ///< n_2 (zero: along component2)
  SourceLocation where{};
};

/// The unit vector an end of a spring acts along within its triple: `direction` when non-zero,
/// else the axis of `component` (0..5: ux..rz -> e_x, e_y, e_z, e_x, e_y, e_z).
inline Eigen::Vector3d spring_axis(int component, const Eigen::Vector3d& direction) {
  if (!direction.isZero(0.0)) return direction;
  return Eigen::Vector3d::Unit(component % 3);
}

/// Rigid (RBE2-like) or averaging (RBE3-like) connection.
///   Rigid:     the dependent nodes' listed components follow the rigid-body motion of the
///              independent node (6 DOFs).
///   Averaging: the reference node's listed components are the weighted least-squares average
///              of the motion of the independent nodes (which keep their own stiffness).
struct RigidElement {
  enum class Kind { Rigid, Averaging };
  Kind kind = Kind::Rigid;
  long id = 0;
  int reference = 0;            ///< RBE2 independent node / RBE3 reference (dependent) node
  std::vector<int> nodes;       ///< RBE2 dependent nodes / RBE3 independent nodes
  std::vector<double> weights;  ///< RBE3 weights, one per node (empty: all 1)
  std::array<bool, 6> components{true, true, true, true, true, true};
  SourceLocation where{};
};

/// Fixed DOFs of a node (Nastran SPC1 / fixed node sets). Components 0..5 as in Spring.
struct Constraint {
  int node = 0;
  std::array<bool, 6> components{true, true, true, false, false, false};
  SourceLocation where{};
};

struct Mesh {
  std::string source;                   ///< file it was read from / generator description
  std::vector<long> node_ids;           ///< external node ids, one per node
  std::vector<Eigen::Vector3d> coords;  ///< global coordinates [m]
  std::vector<Element> elements;
  std::vector<Material> materials;
  std::map<std::string, std::vector<int>> node_sets;     ///< name -> node indices (sorted)
  std::map<std::string, std::vector<int>> element_sets;  ///< name -> element indices (sorted)
  std::vector<PointMass> point_masses;
  std::vector<Spring> springs;
  std::vector<RigidElement> rigid_elements;
  std::vector<Constraint> constraints;

  int num_nodes() const { return static_cast<int>(coords.size()); }
  int num_elements() const { return static_cast<int>(elements.size()); }
};

/// One degree of freedom of a component that is described by matrices rather than a mesh
/// (Matrix Market import, reduced components): the node it belongs to, its component and the
/// node's coordinates. component: 0..5 = ux, uy, uz, rx, ry, rz (global axes); -1 = a
/// generalised (modal) coordinate, for which node_id is the mode number.
struct DofInfo {
  long node_id = 0;
  int component = 0;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
};

}  // namespace geardyn::solid
