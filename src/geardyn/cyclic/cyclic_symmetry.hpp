#pragma once
// Cyclic symmetry of a structure made of N identical sectors about an axis through the origin
// (docs/theory.md §10).
//
// The sector's DOFs are listed as solid::DofInfo (node id, component 0..5 = ux uy uz rx ry rz in
// global Cartesian axes, or -1 for a generalised coordinate, and the node position). Its
// boundary nodes split into the left interface L and the right interface R, each right node
// lying at its left partner's position rotated by alpha = 2 pi / N about the axis (right-handed
// about `axis`). For nodal diameter h in 0..floor(N/2), with phi_h = 2 pi h / N,
//
//   u_R = e^{i phi_h} R(alpha) u_L          (R rotates every Cartesian triple: translations
//                                            and rotations alike)
//   [u_L; u_I; u_R] = T_h [u_L; u_I],       K_h = T_h^H K T_h,  M_h = T_h^H M T_h,
//
// K_h and M_h are Hermitian, real for h = 0 and h = N/2. A mode of K_h with 0 < h < N/2 is a
// double mode of the full wheel (it and its complex conjugate, the travelling waves with h and
// N - h); h = 0 and h = N/2 give single modes. (Thomas, "Dynamics of rotationally periodic
// structures", Int. J. Numer. Meth. Eng. 14 (1979) 81-102.)
//
// Full-wheel expansion (expand_to_sector): sector s = 0..N-1 occupies the sector's region
// rotated by s alpha; the node at position x in sector 0 sits at R(s alpha) x in sector s, and
// its displacement there is
//   u_s = e^{i s phi_h} R(s alpha) u_0     (generalised coordinates: u_s = e^{i s phi_h} u_0),
// so that the right interface of sector s equals the left interface of sector s + 1. The
// physical motion is the real part of u_s e^{i omega t}.
//
// Interface triples: when both partners carry DOFs of a triple (translations or rotations),
// both must carry the complete triple (so R can act); a triple present on only one side of a
// pair (e.g. rotations created by a point mass on the left node only) stays an independent DOF,
// because nothing else in the sector moves that DOF of the shared node.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <array>
#include <complex>
#include <string>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/eig/eigen_options.hpp"
#include "geardyn/eig/hermitian_eigen.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::cyclic {

/// How the left/right interfaces are found.
struct InterfaceOptions {
  /// Number of sectors N >= 2 of the full wheel; the sector angle is alpha = 2 pi / N.
  int n_sectors = 0;
  /// Axis of symmetry through the origin (normalised internally; must be non-zero).
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  /// Largest distance [m] between a right node and its rotated left partner, also the distance
  /// from an edge plane within which a node counts as on the plane. NaN: 1e-6 times the size of
  /// the sector (largest distance of a node from the origin).
  double tolerance = eig::kNaN;
  /// Explicit interface node ids (both given or both empty). Given: left[k] is paired with the
  /// right node nearest R(alpha) x_left[k], which must be within tolerance; use this for
  /// interfaces that are not planar. Empty: the nodes on the sector's two edge half-planes (the
  /// half-planes through the axis at the smallest and the largest node angle) are found from
  /// the geometry.
  std::vector<long> left_nodes;
  std::vector<long> right_nodes;
};

struct NodePair {
  long left_node_id = 0;
  long right_node_id = 0;
  double mismatch = 0;  ///< |x_right - R(alpha) x_left| [m]
};

struct SectorInterfaces {
  int n_sectors = 0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< unit vector
  double sector_angle = 0;                          ///< alpha = 2 pi / N [rad]
  double tolerance_used = 0;                        ///< [m]
  std::vector<NodePair> pairs;                      ///< sorted by left node id
  double worst_mismatch = 0;                        ///< largest NodePair::mismatch [m]
  long worst_left_node = 0;                         ///< left node id of that pair
};

/// Pairs every left-interface node with its right partner (spatial hashing, O(n)). Throws
/// InputError when: N < 2 or the axis is zero; a node lies on the axis (it would belong to all
/// sectors; not supported: mesh a small hole around the axis); the nodes span more than the
/// sector angle; a node on an edge plane has no partner within tolerance (the message names the
/// node ids and the worst mismatch found); two left nodes share a right partner.
SectorInterfaces find_interfaces(const std::vector<long>& node_ids,
                                 const std::vector<Eigen::Vector3d>& coords,
                                 const InterfaceOptions& options);
/// The same on the nodes named by a DOF list (DOFs with component -1 are ignored).
SectorInterfaces find_interfaces(const std::vector<solid::DofInfo>& dofs,
                                 const InterfaceOptions& options);

/// Rotation by `angle` [rad] about the unit vector `axis` (right-handed).
Eigen::Matrix3d rotation(const Eigen::Vector3d& axis, double angle);

/// The cyclic-symmetry map of one sector's DOF list: builds T_h, reduces matrices, expands
/// shapes. Keeps copies of the DOF list and interfaces, no reference to the caller's data.
class CyclicSector {
 public:
  /// Throws InputError when an interface node id is missing from `dofs`, or when partners
  /// carry incomplete Cartesian triples (see the file comment).
  CyclicSector(std::vector<solid::DofInfo> dofs, SectorInterfaces interfaces);

  int n_sectors() const { return interfaces_.n_sectors; }
  int max_nodal_diameter() const { return interfaces_.n_sectors / 2; }
  double sector_angle() const { return interfaces_.sector_angle; }
  const SectorInterfaces& interfaces() const { return interfaces_; }
  const std::vector<solid::DofInfo>& dofs() const { return dofs_; }
  Eigen::Index num_dofs() const { return static_cast<Eigen::Index>(dofs_.size()); }
  /// DOFs kept by T_h: all but the dependent right-interface DOFs.
  Eigen::Index num_reduced_dofs() const { return num_reduced_; }
  /// Sector DOF index of each reduced DOF.
  const std::vector<Eigen::Index>& reduced_dofs() const { return reduced_to_dof_; }

  /// e^{i phi_h}, exactly 1 for h = 0 and -1 for h = N/2.
  std::complex<double> phase(int nodal_diameter) const;
  /// T_h (num_dofs x num_reduced_dofs). Throws InputError for h outside 0..floor(N/2).
  Eigen::SparseMatrix<std::complex<double>> transformation(int nodal_diameter) const;
  /// T_h^H A T_h for a real symmetric sector matrix A (num_dofs square), exactly Hermitian.
  Eigen::SparseMatrix<std::complex<double>> reduce(const Eigen::SparseMatrix<double>& A,
                                                   int nodal_diameter) const;
  /// Sector shape T_h x from reduced coordinates x.
  Eigen::VectorXcd expand(const Eigen::VectorXcd& reduced, int nodal_diameter) const;
  /// Displacement of sector s (0..N-1) from the sector-0 shape u0 (num_dofs): DOF j of the
  /// result belongs to the node at R(s alpha) x_j, in global Cartesian components.
  Eigen::VectorXcd expand_to_sector(const Eigen::VectorXcd& u0, int nodal_diameter,
                                    int sector) const;

 private:
  struct Dependency {  // right DOF = e^{i phi} sum_k weight_k * (left DOF)_k
    Eigen::Index dof = 0;
    std::vector<std::pair<Eigen::Index, double>> terms;
  };
  void check_nodal_diameter(int nodal_diameter) const;

  std::vector<solid::DofInfo> dofs_;
  SectorInterfaces interfaces_;
  Eigen::Matrix3d R_alpha_;
  std::vector<Eigen::Index> dof_to_reduced_;  // -1 for dependent DOFs
  std::vector<Eigen::Index> reduced_to_dof_;
  std::vector<Dependency> dependencies_;
  std::vector<std::array<Eigen::Index, 3>> triples_;  // Cartesian triples, rotated by expand
  Eigen::Index num_reduced_ = 0;
};

struct CyclicModesOptions {
  /// Nodal diameters to solve; empty: all of 0..floor(N/2).
  std::vector<int> nodal_diameters;
  /// Modes per nodal diameter (n_modes or a band in rad^2/s^2) and solver knobs.
  eig::HermitianEigenOptions eigen;
  std::vector<std::string> validate(int n_sectors) const;
};

struct NodalDiameterModes {
  int nodal_diameter = 0;
  /// Full-wheel multiplicity of each mode: 1 for h = 0 and h = N/2, else 2.
  int multiplicity = 1;
  eig::HermitianEigenResult eigen;  ///< on the reduced DOFs (eigenvectors phi, phi^H M_h phi = 1)
  Eigen::VectorXd frequency_hz;     ///< sqrt(max(lambda, 0)) / (2 pi)
  Eigen::MatrixXcd sector_shapes;   ///< T_h phi on all sector DOFs, one column per mode
};

struct CyclicModesResult {
  Status status = Status::Failed;  ///< worst over the nodal diameters
  std::string message;             ///< each non-ok nodal diameter, with its solver message
  int n_sectors = 0;
  std::vector<NodalDiameterModes> diameters;
  double seconds = 0;

  /// Table "cyclic_modes": nodal_diameter, mode (1-based per nodal diameter), frequency_hz,
  /// multiplicity (in the full wheel), residual (backward error).
  Table table() const;
  std::string brief_report() const;
};

/// Natural modes of the cyclic structure whose sector has stiffness K and mass M (real,
/// symmetric, rows in the order of sector.dofs()), per nodal diameter. Throws InputError for
/// mismatched sizes or invalid options; numerical trouble per nodal diameter is reported in the
/// status and message (the other nodal diameters are still solved).
CyclicModesResult solve_cyclic_modes(const Eigen::SparseMatrix<double>& K,
                                     const Eigen::SparseMatrix<double>& M,
                                     const CyclicSector& sector,
                                     const CyclicModesOptions& options = {},
                                     Progress& progress = null_progress());

}  // namespace geardyn::cyclic
