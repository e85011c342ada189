#pragma once
// Solids joined to the rotor: a [[solids]] entry with [[solids.spiders]] becomes a body of the
// rotor system (fe/superelement.hpp), reduced by Craig-Bampton (docs/theory.md §9) onto physical
// points that the rotor system keeps:
//
//   spider k, rigid (RBE2):      a reference node r_k at the rotor node's position, with a Rigid
//                                element to the node set: u_set = u_r + theta_r x (x - x_r).
//                                Its 6 DOFs are masters.
//   spider k, averaging (RBE3):  a reference node r_k with an Averaging element: u_r = A_k x, the
//                                weighted least-squares rigid fit of the set's translations
//                                (solid/assembly.hpp). The set keeps its own flexibility.
//   sensor set s:                u_s = A_s x = sum_{i in set} u_i / n (translations, global).
//
// The constraint rows A (averaging spiders and sensors, stacked, r in all) stay constraints:
// couple_solid reduces (K, M) of the solid by Craig-Bampton with interface constraints
// (reduce::craig_bampton with InterfaceConstraints, docs/theory.md §9) with the masters
//   q = [u_r1 (6), ..., u_rk (6), u_s1 (3), ...; eta (coupling_modes fixed-interface modes)],
// fixed-interface meaning all spider and sensor points held, using sparse factorisations only.
// With all masters free the constraint modes contain the six rigid-body motions, so the body's
// inertia is exact for any number of modes; an averaging spider does not stiffen the set.
// spider_system builds the equivalent eliminated form: r pivot DOFs D of the solid (column-
// pivoted QR of A, rigid masters excluded) are eliminated, x_D = A_D^-1 (u - A_F x_F), so that
// z = [x_F; u] describes every motion, x = S z. Its S^T K S is the exact unreduced body, but
// every pivot depends on its whole node set, so it fills in set x set (90 % dense on the
// benchmark housing): it serves checks, not the reduction.
//
// Rotor side: spider points join the rotor node's 6 DOFs (rotated from global axes into the node
// frame), sensor points become new nodes "<solid>/<node_set>" (translations only, global axes),
// and eta become generalised coordinates of the DofMap named after the solid.
// Gyroscopic effect: when all spider nodes spin at one speed ratio r about one axis e3, the body
// adds the rigid-disk gyroscopic matrix r Ip (fe/rigid_disk.hpp) at its first spider point, with
// Ip = e3^T J e3 its polar inertia (J the inertia tensor about that point, from the reduced mass
// matrix and the rigid-body motions). The gyroscopic coupling of its elastic modes is neglected.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/fe/superelement.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/reduce/reduced_component.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::assembly {

/// A solid's matrices in the eliminated coordinates z = [x_F; u] (see the file comment): the
/// exact (unreduced) body for checks. Dense in set x set for averaging spiders on large sets.
struct SpiderSystem {
  Eigen::SparseMatrix<double> K, M;  ///< S^T K S, S^T M S (symmetric)
  std::vector<solid::DofInfo> dofs;  ///< of z (u entries: the reference / sensor node ids)
  /// Masters, indices into z, in the order of the body's points and their listed components.
  std::vector<int> masters;
  std::vector<fe::SuperelementPoint> points;  ///< spider points, then sensor points
  Eigen::SparseMatrix<double> transform;      ///< S: solid DOFs (SolidSystem) x = S z
  solid::SolidSystem system;                  ///< the solid assembled with its spiders
  /// The same without elimination: A x = u on the solid DOFs x (averaging spiders and sensors)
  /// and the masters as indices into [x; u] (what couple_solid reduces).
  reduce::InterfaceConstraints constraints;
  std::vector<int> constrained_masters;
  /// Mass matrix of the rigid body about the first spider point in global axes,
  /// [m I, -m S(c); m S(c), J] (c: centre of mass from the point).
  Eigen::Matrix<double, 6, 6> rigid_mass = Eigen::Matrix<double, 6, 6>::Zero();
};

/// A joined solid, reduced.
struct CoupledSolid {
  std::string name;
  fe::Superelement body;  ///< what fe::assemble adds to the rotor system
  /// Craig-Bampton with interface constraints: full coordinates z = [x; u] (solid DOFs, then
  /// the constrained spider and sensor coordinates), z = T q.
  reduce::ReducedComponent reduced;
  Eigen::SparseMatrix<double> transform;  ///< S = [I 0]: solid DOFs x = S z
  /// The solid assembled with its spiders, without K and M: its DOF map x and the recovery of
  /// every node's DOFs (those eliminated by rigid spiders too) from x.
  solid::SolidSystem solid_dofs;
  Eigen::Matrix<double, 6, 6> rigid_mass = Eigen::Matrix<double, 6, 6>::Zero();
  double polar_inertia = 0;  ///< Ip used for the gyroscopic matrix [kg m^2] (0: none added)
  std::string description;   ///< one line: points, modes, mass, highest kept mode
};

/// Builds the coupling coordinates of `solid` (an entry of model.solids with spiders) from its
/// built component (mesh and fixed sets). Throws InputError for a node set that is not in the
/// mesh (listing the sets), a spider or sensor whose point is already fixed by others (e.g. a
/// sensor on a rigidly joined set), a reduced component, and for what solid assembly refuses.
SpiderSystem spider_system(const model::Model& model, const model::Solid& solid,
                           const SolidComponent& built, Progress& progress = null_progress());

/// Reduces one joined solid (spider_system, then Craig-Bampton with solid.coupling_modes modes).
/// Throws InputError when the spider points leave the solid free to move (a mechanism), naming
/// the free motion; NumericalError when the fixed-interface eigen-solve fails.
CoupledSolid couple_solid(const model::Model& model, const model::Solid& solid,
                          const SolidComponent& built, Progress& progress = null_progress());

/// Every solid of the model with spiders, reduced, in model order; solids missing from `built`
/// (or all, when it is null) are built here.
std::vector<CoupledSolid> couple_solids(const model::Model& model, const SolidComponents* built,
                                        Progress& progress = null_progress());

/// The translations (ux, uy, uz in global axes; 3 rows per node) of the mesh nodes `nodes`
/// (indices into the solid's mesh) as a function of the body coordinates q of `solid`
/// (body.size() columns): the Craig-Bampton recovery z = T q (constraint and fixed-interface
/// modes) after the rigid spiders' recovery of the nodes they eliminate. Dense, 3 n x m. Throws
/// std::invalid_argument for a node index outside the mesh or a node without translations.
Eigen::MatrixXd node_translations(const CoupledSolid& solid, const std::vector<int>& nodes);

/// True when some solid of the model has spiders (is part of the rotor system).
bool has_joined_solids(const model::Model& model);

}  // namespace geardyn::assembly
