#pragma once
// Radiated sound power of a vibrating surface (issue #17, item 3; docs/theory.md §17):
//   - the equivalent radiated power ERP = 1/2 rho c sigma sum_i A_i |v_n,i|^2, the power a surface
//     would radiate if every part of it radiated as a plane wave (radiation efficiency sigma = 1),
//     an upper-bound-like measure used to rank designs (e.g. Fritze, Marburg and Hardtke,
//     "Estimation of radiated sound power: a case study on common approximation methods", 2009);
//   - its fast form for a reduced model, ERP(q, w) = 1/2 rho c sigma w^2 q^H W q with the m x m
//     matrix W = R_n^T diag(A) R_n precomputed once (R_n the normal-projected recovery rows);
//   - the 0-order (pulsating sphere) radiator of Kinsler, Frey, Coppens and Sanders, "Fundamentals
//     of Acoustics", 4th ed. 2000, §7.5: P = 2 pi R^2 v^2 rho c (kR)^2 / (1 + (kR)^2), k = w/c;
//   - sound power and free-field pressure levels, re 1e-12 W and 20 uPa (ISO 1683):
//     L_W = 10 lg(P / 1e-12 W), L_p = L_W + 10 lg(Q / (4 pi r^2 / 1 m^2)) for a point source of
//     directivity factor Q at distance r in air (rho c ~ 400 Pa s/m, where the two references
//     match to 0.1 dB).
// Velocities are complex amplitudes (0-peak), so |v|^2 / 2 is the mean square.
#include <Eigen/Dense>
#include <filesystem>
#include <string>
#include <vector>

#include "geardyn/acoustics/surface.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/meshio/vtu_writer.hpp"

namespace geardyn::acoustics {

/// Air at 20 degC (the values of the e-axle study of issue #17).
struct Air {
  double density = 1.2041;                                       ///< [kg/m^3]
  double speed_of_sound = 343.4;                                 ///< [m/s]
  double impedance() const { return density * speed_of_sound; }  ///< rho c [Pa s/m]
};

/// ERP = 1/2 rho c sigma sum_i A_i |v_n,i|^2 [W], v_n the complex normal velocity amplitudes per
/// surface node (Surface::nodes order). Throws std::invalid_argument on a size mismatch.
double erp(const Surface& s, const Eigen::VectorXcd& normal_velocity, const Air& air,
           double radiation_efficiency = 1.0);

/// Per-face ERP [W]: 1/2 rho c sigma sum over the face's nodes of its share of the node's lumped
/// area (SurfaceFace::node_weight) times |v_n|^2, i.e. the face's area times a weighted nodal
/// average of |v_n|^2. Sums to erp() exactly (up to round-off).
Eigen::VectorXd face_erp(const Surface& s, const Eigen::VectorXcd& normal_velocity, const Air& air,
                         double radiation_efficiency = 1.0);

/// The normal velocity amplitudes i w n_i . u_i of displacement amplitudes `displacement`
/// (3 per surface node: ux, uy, uz in global axes, surface-node order) at circular frequency w.
Eigen::VectorXcd normal_velocity(const Surface& s, const Eigen::VectorXcd& displacement,
                                 double omega);

/// ERP of a reduced model. `recovery` has 3 rows per surface node (ux, uy, uz in global axes,
/// surface-node order) and m columns (the reduced coordinates q). Precomputes
/// W = R_n^T diag(A) R_n (m x m), R_n the normal-projected rows (n x m, kept for
/// normal_velocity), so that power(q, w) costs O(m^2). Building W costs n m^2 flops (a symmetric
/// rank-n update in blocks of rows).
class ErpOperator {
 public:
  ErpOperator(const Surface& s, const Eigen::MatrixXd& recovery);
  /// 1/2 rho c sigma w^2 q^H W q [W]. Throws std::invalid_argument when q.size() != m.
  double power(const Eigen::VectorXcd& q, double omega, const Air& air, double sigma = 1) const;
  /// i w R_n q: the complex normal velocity amplitude per surface node [m/s].
  Eigen::VectorXcd normal_velocity(const Eigen::VectorXcd& q, double omega) const;
  /// The amplitude v~ with S v~^2 = sum_i A_i |v_n,i|^2 (area-weighted rms of |v_n| over the
  /// surface, as an amplitude) [m/s].
  double mean_normal_velocity(const Eigen::VectorXcd& q, double omega) const;
  double area() const { return area_; }                     ///< S = sum of the lumped areas [m^2]
  int size() const { return static_cast<int>(W_.rows()); }  ///< m
  const Eigen::MatrixXd& matrix() const { return W_; }      ///< W [m^2 per q unit^2]

 private:
  Eigen::MatrixXd Rn_;  // n x m
  Eigen::MatrixXd W_;   // m x m, symmetric
  double area_ = 0;
};

/// 0-order spherical radiator (pulsating sphere of radius R): P = 2 pi R^2 v^2 rho c
/// (w/wK)^2 / (1 + (w/wK)^2), wK = c/R, v the normal velocity amplitude [m/s] (Kinsler et al.
/// 2000, §7.5). Throws std::invalid_argument for R <= 0.
double spherical_radiator_power(double velocity_amplitude, double radius, double omega,
                                const Air& air);
/// The radius of the sphere with the surface's area, sqrt(S / (4 pi)) [m].
double equivalent_sphere_radius(double area);

double sound_power_level_db(double power_w);  ///< 10 lg(P / 1e-12 W); -inf for P = 0
/// Free-field SPL at distance r for directivity factor Q (1: free space, 2: on a reflecting
/// plane): L_p = L_W + 10 lg(Q / (4 pi r^2)), r in m. Throws std::invalid_argument for r <= 0 or
/// Q <= 0.
double sound_pressure_level_db(double power_w, double distance_m, double directivity = 1.0);

/// Radiation efficiency sigma(f): a constant, or a table (f_hz, sigma) interpolated linearly in
/// lg f, held constant outside the table.
class RadiationEfficiency {
 public:
  explicit RadiationEfficiency(double sigma = 1.0);
  /// Throws std::invalid_argument unless the frequencies are > 0 and strictly increasing, the
  /// sizes match and are >= 1, and every sigma >= 0.
  RadiationEfficiency(std::vector<double> frequency_hz, std::vector<double> sigma);
  double at(double frequency_hz) const;
  bool is_constant() const { return frequency_hz_.size() <= 1; }

 private:
  std::vector<double> frequency_hz_, sigma_;
};

/// The per-face ERP density (W/m^2) binned onto a grid in the plane of the surface's two largest
/// (axis-aligned) extents: each cell holds sum(face ERP) / sum(face area) over the faces whose
/// centroid falls into it (both sides of a closed housing fall into the same cells), NaN where
/// none does. `cells` along the largest extent; the other axis gets cells in proportion.
struct ErpDensityMap {
  Trace trace;  ///< heat map: x, y the cell centres [m], z[i][k] at (x[k], y[i]) [W/m^2]
  std::string x_label, y_label;  ///< e.g. "x [m]", "z [m]"
  int x_axis = 0, y_axis = 1;    ///< the global axes (0, 1, 2) of the map's x and y
};
ErpDensityMap erp_density_map(const Surface& s, const Eigen::VectorXd& face_erp_w, int cells = 40);

/// The surface as a VTU for ParaView: the faces as (quadratic) triangle / quad cells on the
/// surface nodes, with `cell_fields` (one value set per face, SurfaceFace order) and
/// `point_fields` (per surface node, Surface::nodes order), plus node_id and element_id.
void write_surface_vtu(const std::filesystem::path& path, const solid::Mesh& mesh, const Surface& s,
                       const std::vector<meshio::Field>& cell_fields,
                       const std::vector<meshio::Field>& point_fields);

/// The standard ERP fields of one state: cells "erp_w" and "erp_density_w_per_m2", point
/// "normal_velocity_m_per_s" (|v_n|). Pass them to write_surface_vtu.
struct ErpFields {
  std::vector<meshio::Field> cells, points;
};
ErpFields erp_fields(const Surface& s, const Eigen::VectorXcd& normal_velocity, const Air& air,
                     double radiation_efficiency = 1.0);

}  // namespace geardyn::acoustics
