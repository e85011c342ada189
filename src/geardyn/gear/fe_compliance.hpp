#pragma once
// The finite-element compliance route of the loaded tooth contact analysis (docs/theory.md
// §15.8): influence coefficients of the flank from a solid mesh of each gear, combined with the
// analytic Hertzian approach -- the hybrid approach of commercial LTCA codes (S.M. Vijayakar, "A
// combined surface integral and finite element solution for a three-dimensional contact
// problem", Int. J. Numer. Methods Eng. 31, 1991: FE far field, analytic near field).
//
// Per gear: the whole gear, every involute tooth on the full rim (meshgen/involute_segment.hpp,
// tet10, fine at the loaded tooth, coarse elsewhere), fixed at its bore: the body of Sainsot's
// foundation formula, a full disc from r_int to r_f (the bore here is the same r_int,
// ToothComplianceOptions::bore_radius_*, default r_f / 2). A segment of `segment_teeth` teeth
// fixed at its two radial cut faces too (the option of a cheaper mesh) is stiffer: 7 teeth give
// 4 ... 13 % less tooth compliance; with free cut faces it is softer (theory §15.8, the
// bracket of fe_compliance_slow_test.cpp). The stiffness is factored once (CHOLMOD, linalg/
// sparse_factorization.hpp); the load cases are line loads along the contact line on the loaded
// flank of the tooth on +x, at `profile_points` roll positions spanning the gear's active profile
// (path s = 0 ... g_alpha), each with a hat distribution over the face centred at one of
// `face_points` face positions (unit peak [N/m]); the receivers are the same grid.
//
// Near field. A load on the surface of an FE mesh has a mesh-dependent (singular) local
// displacement under it. As in Weber's decomposition that the analytic route uses (C. Weber,
// K. Banaschek 1955, tooth_compliance.hpp), the FE displacement is read at the tooth centre
// line, at the point where the load's line of action through the contact point crosses it, and
// projected on the load direction: the FE gives the tooth and body deflection of that point
// (bending, shear, compression, foundation, and the coupling along the face), the analytic Hertz
// term (approach between the flank and the centre line at the depth d = h_c / cos(alpha_1))
// gives the rest. The local field at depth d of a load smoothed over the face grid spacing is
// resolved by an element size of ~m / 4 (the mesh-convergence test checks it).
//
// Pair compliance: A(i, k) = pinion + wheel influence at the candidate points, interpolated on
// the grids: linear in the path position of receiver and load, linear in the receiver's face
// position, and the load's slice [y_k - dy/2, y_k + dy/2] projected on the face hats (its
// integral of each hat over the hat's integral, which preserves the force and reproduces a
// uniform load exactly). The slices of one pair are coupled through the FE: no coupling_length.
// Neighbouring teeth: pair j's load on pair k's teeth is neglected (the contact solver's A is
// block diagonal over pairs); the neighbouring teeth stiffen the body as they do.
//
// Spur gears, external pair only (the segment is a spur segment; helical and internal gears use
// the analytic route): InputError otherwise.
#include <Eigen/Core>
#include <vector>

#include "geardyn/gear/slice_compliance.hpp"
#include "geardyn/gear/tooth_compliance.hpp"
#include "geardyn/gear/tooth_contact.hpp"

namespace geardyn::gear {

struct FeComplianceOptions {
  /// Element size at the loaded tooth / m_n, in [0.05, 1].
  double mesh_size = 0.35;
  /// Element size in the rest of the body / m_n, in [mesh_size, 4] (NaN: 3). The far body
  /// barely matters: 1 m_n instead of 3 changes the compliance by < 0.3 % (theory §15.8).
  double body_size = std::numeric_limits<double>::quiet_NaN();
  int profile_points = 9;  ///< roll positions over the active profile (>= 3)
  int face_points = 0;     ///< face positions (>= 2; 0: one per m_n / 2, at least 5)
  /// 0: the whole gear (every tooth, fixed at the bore: the body of Sainsot's formula); an odd
  /// 1 ... 7: a segment of that many teeth (capped at the largest odd number <= z / 2).
  int segment_teeth = 0;
  /// A segment's two radial cut faces fixed (true: a stiffer body than the whole gear, a lower
  /// bound of its compliance) or free (a softer one, an upper bound). Unused for the whole gear.
  bool fix_cut_faces = true;
  /// Materials, bores (r_int) and rack fillet, as for the analytic route.
  ToothComplianceOptions teeth;
};

/// The influence grid of one gear's tooth.
struct ToothInfluence {
  std::vector<double> path;  ///< s of the profile grid [m], increasing, 0 ... g_alpha
  std::vector<double> face;  ///< y of the face grid [m], 0 ... b
  /// U(receiver, load), index p * face.size() + f: deflection along the load direction at the
  /// centre-line point of receiver (p, f) per line load of unit peak [N/m] with the hat
  /// distribution of face point f at profile point p [m^2/N].
  Eigen::MatrixXd influence;
  int nodes = 0, elements = 0, dofs = 0;
  double mesh_seconds = 0.0, solve_seconds = 0.0;
  /// Deflection at receiver (s_i, y_i) per line load w = 1 N/m on [y_a, y_b] at path s_k.
  double at(double s_i, double y_i, double s_k, double y_a, double y_b) const;
};

/// The FE influence grid of the pinion (`wheel` false) or the wheel of a spur pair.
/// InputError (key path geometry.spec.key_path + ".contact.compliance") for a helical, bevel or
/// internal pair; for options out of range (".contact.fe_*").
ToothInfluence fe_tooth_influence(const ToothCompliance& teeth, bool wheel,
                                  const FeComplianceOptions& options);

class FeCompliance final : public HertzianContactCompliance {
 public:
  /// Builds both gears' grids (the expensive part: two meshes, two factorisations). `teeth`
  /// must outlive this object; its Hertz terms are used.
  FeCompliance(const ToothCompliance& teeth, const FeComplianceOptions& options);

  Eigen::MatrixXd body_influence(const std::vector<double>& s, const std::vector<double>& y,
                                 double dy) const override;

  const ToothInfluence& pinion() const { return pinion_; }
  const ToothInfluence& wheel() const { return wheel_; }

 private:
  ToothInfluence pinion_, wheel_;
};

}  // namespace geardyn::gear
