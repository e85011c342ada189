#pragma once
// An LTCA table exported by another tool (KISSsoft, MASTA, Romax, Gleason or Klingelnberg LTCA):
// the loaded transmission error and, optionally, the mesh stiffness over the pinion angle of one
// mesh cycle x the pinion torque x the mounting errors H, V, J of a bevel or hypoid pair (any of
// them may be absent: then 0). LtcaTable::at interpolates it at one torque and mounting state,
// multilinearly over torque and H, V, J and periodically (piecewise linear) over the angle, and
// gives the STE curve of the dynamic mesh model (gear/ste.hpp) — the table then drives the
// dynamics exactly like an STE file.
//
// CSV format (comma separated, '#' comment lines and blank lines ignored, the first other line
// is the header; units in the column names, case-insensitive; long format, one row per sample):
//   angle_deg | angle_rad      rotation of the pinion (gear 1) within one mesh cycle,
//                              2 pi / z1; as the STE reader: closed (the last angle is the first
//                              plus one cycle) or open (one cycle minus one spacing)
//   torque_nm | torque_knm     pinion torque
//   h_<u>, v_<u>, j_<u>        optional mounting errors, u = m, mm, um (absent: 0)
//   te_<u>                     loaded TE; u = m, mm, um, nm (along the line of action) or
//                              rad, mrad, urad, deg, arcsec (angular: times the base radius r_b1)
//   stiffness_n_per_m | stiffness_n_m | stiffness_n_per_um
//                              optional secant mesh stiffness k = F / (e - e_g) along the line of
//                              action
// The rows must form a regular grid: every combination of the distinct torques, H, V and J
// values appears once at each of the distinct angles (in any order).
//
// The STE of the dynamic model needs e and the geometric (unloaded) TE e_g, with the mesh
// stiffness k = F_s / (e - e_g) (gear/ste.hpp). With a stiffness column, e_g = e - F_s / k at the
// interpolated point (F_s = T / r_b1), so the dynamic model's stiffness is the table's. Without
// it the whole TE is taken as elastic (e_g = 0, k = F_s / e), as for an STE file without a
// geometric_te column: right for unmodified flanks, a stiffness too low where the TE holds a
// geometric part (modifications, ease-off).
#include <array>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/gear/ste.hpp"

namespace geardyn::gear {

/// How an LTCA table is read.
struct LtcaReadOptions {
  int teeth = 0;  ///< pinion teeth z1: one mesh cycle is 2 pi / z1 (> 0)
  double base_radius_m = std::numeric_limits<double>::quiet_NaN();  ///< r_b1, angular TE
  double period_tolerance = 0.01;  ///< relative, on the angles' span of one mesh cycle
};

/// One state at which the table is evaluated.
struct LtcaPoint {
  double torque_nm = 0.0;
  double h_m = 0.0, v_m = 0.0, j_m = 0.0;  ///< mounting errors
};

/// The table as a regular grid.
class LtcaTable {
 public:
  /// Axis names, in the order of `axes()`: torque, H, V, J.
  static constexpr std::array<const char*, 4> kAxisNames = {"torque", "h", "v", "j"};

  /// Parses a CSV document (format above). InputError with file, line, column, the column name,
  /// what was expected and what was found, for: an unknown, repeated or missing column, a value
  /// that is not a finite number, a negative torque, a TE <= 0 without a stiffness column, a
  /// stiffness <= 0, a grid with a missing or repeated combination, fewer than 3 angles, angles
  /// that do not span one mesh cycle.
  static LtcaTable parse(std::string_view text, const std::string& file_name,
                         const LtcaReadOptions& options);
  /// Reads `path` and parses it; InputError when it cannot be read.
  static LtcaTable read(const std::filesystem::path& path, const LtcaReadOptions& options);

  /// Grid values of torque [N m], H, V, J [m] (increasing; one value for an absent column).
  const std::array<std::vector<double>, 4>& axes() const { return axes_; }
  /// Mesh-cycle fractions of the angles, increasing from 0, closed by 1 (the first angle again).
  const std::vector<double>& cycle_fraction() const { return u_; }
  bool has_stiffness() const { return has_stiffness_; }
  const std::string& source() const { return source_; }

  /// TE [m] and stiffness [N/m] (NaN without stiffness) at grid node (torque, h, v, j indices)
  /// and angle index a (a < cycle_fraction().size() - 1).
  double te_node(const std::array<std::size_t, 4>& node, std::size_t a) const;
  double stiffness_node(const std::array<std::size_t, 4>& node, std::size_t a) const;

  /// TE [m] and stiffness [N/m] at `point` and the cycle fraction `u` (any real, periodic):
  /// multilinear over the axes with more than one value, periodic linear over the angle. An
  /// axis with one value is held at it. Outside an axis's range (or off its only value):
  /// InputError (key `torque`, `h`, `v`, `j`) unless `extrapolate`, then linear from the two end
  /// nodes (held for a one-value axis; a single torque scales the TE with T / T_0, keeping the
  /// stiffness: a linear mesh).
  double te_at(const LtcaPoint& point, double u, bool extrapolate = false) const;
  double stiffness_at(const LtcaPoint& point, double u, bool extrapolate = false) const;

  /// The STE of the dynamic model at `point`: `samples` uniform samples over one cycle (0: the
  /// table's angles), sample 0 at the cycle fraction `shift`; e_g = e - F_s / k with
  /// F_s = T / r_b1 when the table has a stiffness, else none. InputError as te_at, and for a
  /// non-positive torque or base radius.
  SteCurve ste(const LtcaPoint& point, double base_radius_m, bool extrapolate = false,
               double shift = 0.0, std::size_t samples = 0,
               SteInterpolation interpolation = SteInterpolation::Linear) const;

 private:
  struct Weights {
    std::array<std::size_t, 4> lo{}, hi{};
    std::array<double, 4> w{};  ///< weight of hi
    double torque_scale = 1.0;  ///< single-torque extrapolation
  };
  Weights weights(const LtcaPoint& point, bool extrapolate) const;
  double blend(const std::vector<double>& values, const Weights& w, double u) const;
  std::size_t index(const std::array<std::size_t, 4>& node, std::size_t a) const;

  std::string source_;
  std::array<std::vector<double>, 4> axes_;
  std::vector<double> u_;                 ///< knots, closed
  std::size_t angles_ = 0;                ///< distinct angles (knots without the closing one)
  std::vector<double> te_m_, stiffness_;  ///< per node and knot (closed: angles_ + 1 knots)
  bool has_stiffness_ = false;
};

}  // namespace geardyn::gear
