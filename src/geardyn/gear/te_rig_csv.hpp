#pragma once
// A test rig's transmission error at the mesh orders (a measured TE order analysis over torque)
// read from a CSV file, and its point-by-point comparison with the TE harmonics of a loaded tooth
// contact analysis (docs/theory.md §15.3 for the computed harmonics, docs/input-files.md §3a for
// the format).
//
// Format (comma separated, '#' comment lines and blank lines ignored, the first other line is
// the header; names case-insensitive; one row per measured point, any order):
//   torque_nm                            torque on gear 1 (the pinion) [N m], > 0
//   mesh_order                           the mesh order k = 1, 2, ... (an integer)
//   amplitude_<convention>_<unit>        the TE amplitude of that harmonic, > 0:
//     <convention>  0_peak | peak_peak   (peak-peak = 2 x 0-peak for a sine)
//     <unit>        m | mm | um | nm     along the line of action
//                   rad | mrad | urad    the pinion's angular TE (= TE along the line of action /
//                                        the radius the analysis converts with, r_b1)
// Each (torque, mesh order) once.
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/core/error.hpp"

namespace geardyn::gear {

enum class TeConvention { ZeroPeak, PeakPeak };

/// One measured point: the amplitude in SI (m along the line of action, or rad of the pinion) in
/// the file's convention.
struct TeRigPoint {
  double torque_nm = 0.0;
  int mesh_order = 0;
  double amplitude = 0.0;
  int line = 0;  ///< 1-based line in the file
};

struct TeRigFile {
  std::string source;
  std::string amplitude_column;  ///< as written in the header
  TeConvention convention = TeConvention::ZeroPeak;
  bool angular = false;  ///< amplitude in rad of the pinion (else m along the line of action)
  std::vector<TeRigPoint> points;

  /// Point i as a 0-peak amplitude along the line of action [m]: peak-peak halved, an angle
  /// times `radius_m` (the radius the analysis converts TE angles with, r_b1).
  double zero_peak_m(std::size_t i, double radius_m) const;
};

/// Parses the format above. InputError (file, line, column, column name, expected, found) for an
/// unknown, repeated or missing column, a cell that is not a finite number, a torque <= 0, a mesh
/// order that is not an integer >= 1, an amplitude <= 0, or a (torque, order) given twice.
TeRigFile parse_te_rig_csv(std::string_view text, const std::string& file_name);
/// Reads `path` and parses it; InputError when it cannot be read.
TeRigFile read_te_rig_csv(const std::filesystem::path& path);

/// Why a measured point was or was not compared.
enum class TeMatch {
  Computed,      ///< at a computed torque
  Interpolated,  ///< between two computed torques (linear in torque)
  OutsideTorques,
  AboveOrders
};
const char* to_string(TeMatch m);

struct TeComparisonRow {
  double torque_nm = 0.0;
  int mesh_order = 0;
  int line = 0;
  double measured_m = 0.0;     ///< 0-peak along the line of action
  double computed_m = 0.0;     ///< 0-peak along the line of action; NaN when not compared
  double ratio = 0.0;          ///< measured / computed; NaN when not compared
  double difference_db = 0.0;  ///< 20 log10(measured / computed); NaN when not compared
  TeMatch match = TeMatch::Computed;
  bool compared() const { return match == TeMatch::Computed || match == TeMatch::Interpolated; }
};

/// The comparison of a rig file with computed TE harmonics, and its summary over the compared
/// points.
struct TeComparison {
  TeRigFile rig;
  double radius_m = 0.0;              ///< the radius the angles were converted with
  std::vector<TeComparisonRow> rows;  ///< in the order of the file
  std::size_t compared = 0;
  double mean_ratio = 0.0;  ///< arithmetic mean of measured / computed
  double max_abs_db = 0.0;  ///< largest |20 log10(measured / computed)|
  std::size_t max_db_row = 0;
  /// Least-squares line measured = gain x computed + offset (NaN with fewer than two distinct
  /// computed values): a gain error and an additive floor are told apart.
  double fit_gain = 0.0, fit_offset_m = 0.0;
};

/// Compares `rig` with the computed 0-peak harmonics `harmonics_m[i][k - 1]` (mesh order k) at
/// the strictly increasing `torques_nm[i]`. A measured torque between two computed ones takes
/// the computed amplitude interpolated linearly in torque; a torque outside the computed range
/// (relative tolerance 1e-9) or an order above the computed ones is kept as not compared.
TeComparison compare_te(const TeRigFile& rig, std::span<const double> torques_nm,
                        const std::vector<std::vector<double>>& harmonics_m, double radius_m);

/// y(x) interpolated linearly over the strictly increasing x at xq; NaN outside [x.front(),
/// x.back()] beyond a relative tolerance `rel_tol` of the range (or of |x| for a single point).
double interpolate_in_range(std::span<const double> x, std::span<const double> y, double xq,
                            double rel_tol = 1e-9);

}  // namespace geardyn::gear
