#pragma once
// Static transmission error (STE) over one mesh cycle: the input of the dynamic mesh model
// (docs/theory.md §11.4, §13). The STE e(t) is the deflection along the line of action, as a
// length, when the gears turn slowly under a constant torque; it sets the time-varying mesh
// stiffness
//   k(t) = F_s / (e(t) - e_g(t)),   F_s = T / r_b,
// where e_g is the optional unloaded (geometric) transmission error of the flanks (profile
// modifications, pitch errors): the part of e that is not elastic. Without it e_g = 0.
// An angular STE (radians) becomes a length by multiplying with the base radius r_b of the gear
// it refers to (the base radius of the equivalent spur gear for bevel gears).
// Reference: A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears Equipped
// with Damper Rings", MSc thesis, Politecnico di Torino, 2018 (the damper-ring thesis),
// sec. 3.1-3.2 (the STE of one mesh cycle, tangential component, scaled by the base radius,
// repeated periodically).
//
// Conventions kept by every SteCurve:
//   * n uniform samples over one mesh period, sample j at the cycle fraction j / n;
//   * sample 0 is the tooth entering contact (the tooth-load window starts there, docs/theory.md
//   §12.1);
//   * the curve is periodic: between sample n-1 and the next cycle's sample 0 it wraps around.
//
// CSV format read by parse_ste_csv / read_ste_csv (comma separated, UTF-8, '#' comment lines and
// blank lines ignored; the first other line is the header; the units are in the names):
//
//   abscissa (first column, exactly one of)
//     angle_rad, angle_deg     rotation angle of the gear with `teeth` teeth; one mesh period is
//                              2 pi / teeth (360 / teeth degrees)
//     time_s, time_ms          time; one mesh period is SteReadOptions::mesh_period_s
//   the abscissa must increase strictly; it need not start at zero (the first row is the tooth
//   entering contact). The rows span either one period exactly (closed: the last row is the
//   first one of the next cycle, and its value is used as the end of the last interval) or one
//   period minus one spacing (open: the last interval wraps to the first row). Anything else,
//   beyond SteReadOptions::period_tolerance, is an error.
//
//   loaded STE, one of two layouts
//     wide:  one column per torque, `ste_<unit>@<torque><Nm|kNm>`, e.g. ste_um@200Nm,
//            ste_um@450.5Nm; or a single `ste_<unit>` column (torque unknown).
//     long:  a `torque_nm` (or `torque_knm`) column plus one `ste_<unit>` column; the rows of
//            one torque form one contiguous block, each block one mesh cycle.
//   optional `geometric_te_<unit>`: unloaded TE e_g at the same rows (one column; in the long
//   layout it may differ between torque blocks).
//   units: rad, mrad, urad, deg, arcsec (angular: need SteReadOptions::base_radius_m) or
//          m, mm, um, nm (length).
//
// Example:
//   # STE of the pinion, 23 teeth, measured with Transmission3D
//   angle_deg, ste_urad@100Nm, ste_urad@200Nm
//   0.0, 21.0, 40.2
//   ...
#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/core/error.hpp"

namespace geardyn::gear {

/// How an SteCurve is evaluated between its samples.
enum class SteInterpolation {
  Linear,  ///< periodic piecewise-linear interpolation (measured or smooth curves)
  Hold     ///< sample j holds over [j, j+1) / n of the cycle (single/double contact steps)
};

/// One STE curve over one mesh cycle (see the conventions above). Immutable; every sample is a
/// finite length in metres and the elastic part e - e_g is strictly positive.
class SteCurve {
 public:
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  /// A curve from uniform samples over one mesh period, sample 0 = tooth entering contact,
  /// e.g. the synthetic STE of mesh_stiffness. `geometric_te_m` is empty (no unloaded TE) or has
  /// the size of `ste_m`. Throws InputError (key path `ste[j]`) for fewer than 2 samples, a
  /// non-finite sample, or e_j - e_g,j <= 0 (a mesh stiffness F_s / (e - e_g) that is negative
  /// or infinite).
  static SteCurve from_samples(std::vector<double> ste_m,
                               SteInterpolation interpolation = SteInterpolation::Linear,
                               std::vector<double> geometric_te_m = {}, double torque_nm = kNaN);

  std::size_t size() const { return ste_m_.size(); }
  const std::vector<double>& ste_m() const { return ste_m_; }
  /// Unloaded TE per sample; zeros when none was given.
  const std::vector<double>& geometric_te_m() const { return geometric_m_; }
  bool has_geometric_te() const { return has_geometric_; }
  SteInterpolation interpolation() const { return interpolation_; }
  /// Torque the curve was computed or measured at [N m]; NaN when unknown.
  double torque_nm() const { return torque_nm_; }

  /// Loaded STE at the cycle fraction `u` (any real; taken modulo 1) [m].
  double ste_at(double u) const { return evaluate(ste_m_, u); }
  /// Unloaded TE at the cycle fraction `u` [m].
  double geometric_at(double u) const { return evaluate(geometric_m_, u); }
  /// Mean of e - e_g over the cycle [m].
  double mean_elastic_m() const;
  /// Mean over the cycle of 1 / (e - e_g) [1/m], exact for the interpolation
  /// (for Linear: the integral of 1/(a + b u) on each interval); k_mean = F_s * this.
  double mean_inverse_elastic_per_m() const;

  /// The same curve with sample 0 moved to the cycle fraction `shift` of this one:
  /// result(u) = this(u + shift). Resamples to `samples` points (0: keep size()).
  SteCurve shifted(double shift, std::size_t samples = 0) const;
  /// This curve at `samples` uniform points (periodic interpolation).
  SteCurve resampled(std::size_t samples) const { return shifted(0.0, samples); }

 private:
  SteCurve() = default;
  double evaluate(const std::vector<double>& v, double u) const;

  std::vector<double> ste_m_, geometric_m_;
  bool has_geometric_ = false;
  SteInterpolation interpolation_ = SteInterpolation::Linear;
  double torque_nm_ = kNaN;
};

/// STE curves at several torques, sorted by increasing torque, all with the same sample count.
struct SteTable {
  std::vector<SteCurve> curves;
  std::string source;  ///< file name, for messages

  /// The curve at `torque_nm`: linear interpolation, sample by sample, between the two curves
  /// whose torques bracket it (the exact curve when it matches one). Outside [first, last]
  /// torque: InputError unless `allow_extrapolation` (then linear from the two end curves; the
  /// result is still checked for positive stiffness). A table of one curve without torque (NaN)
  /// returns it for any torque; a single curve at a known torque is, with extrapolation, scaled
  /// in its elastic part, e_g + (T / T_0) (e - e_g) (a linear mesh). Throws InputError for a
  /// non-finite or negative torque.
  SteCurve at_torque(double torque_nm, bool allow_extrapolation = false) const;
};

/// How to read an STE file.
struct SteReadOptions {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  int teeth = 0;                   ///< teeth of the gear the angles refer to (angle abscissa)
  double mesh_period_s = kNaN;     ///< one mesh period (time abscissa) [s]
  double base_radius_m = kNaN;     ///< base radius converting angular STE to length [m]
  double period_tolerance = 0.01;  ///< relative tolerance on the span of one mesh period
  double shift = 0.0;              ///< fraction of the cycle in [0, 1): sample 0 of the result is
                                   ///< the data at this fraction (moves the contact entry)
  std::size_t samples = 0;         ///< uniform samples per cycle; 0: the number of rows per cycle
  SteInterpolation interpolation = SteInterpolation::Linear;  ///< of the resulting curves
  /// Throws InputError (key path `ste_options.<field>`) listing the first problem.
  void validate() const;
};

/// Parses an STE CSV document (format above) and returns its curves resampled to a uniform grid
/// with sample 0 at the first row shifted by `options.shift`. Errors: InputError with file,
/// line, column and the column name, e.g. non-numeric or non-finite values, a decreasing
/// abscissa, a span that is not one mesh period, fewer than 3 rows per cycle, e - e_g <= 0,
/// unknown or repeated column names, torque columns with different units kinds or a repeated
/// torque, a torque block split in two.
SteTable parse_ste_csv(std::string_view text, const std::string& file_name,
                       const SteReadOptions& options);

/// Reads `path` and calls parse_ste_csv. Throws InputError when the file cannot be read.
SteTable read_ste_csv(const std::filesystem::path& path, const SteReadOptions& options);

/// A numeric CSV document: header names and rows of doubles, with the position of every cell
/// (shared by the STE and the measured-response readers).
struct NumericCsv {
  std::string file;
  std::vector<std::string> names;  ///< header fields, trimmed
  std::vector<int> name_columns;   ///< 1-based character column of each header field
  int header_line = 0;
  std::vector<std::vector<double>> rows;
  std::vector<int> row_lines;                  ///< 1-based line of each row
  std::vector<std::vector<int>> cell_columns;  ///< 1-based character column of each cell

  SourceLocation at(std::size_t row, std::size_t column) const;
  SourceLocation at_header(std::size_t column) const;
  std::size_t find(std::string_view name) const;  ///< index of a column, or npos
};

/// Splits `text` into a NumericCsv: '#' comments and blank lines skipped, CR/LF endings and a
/// UTF-8 byte-order mark accepted, fields trimmed. Throws InputError for an empty document, an
/// empty or repeated header name, a row with the wrong number of fields, or a cell that is not
/// a finite number (the whole cell must parse). Fewer than `min_rows` rows is an error.
NumericCsv parse_numeric_csv(std::string_view text, const std::string& file_name,
                             std::size_t min_rows);

}  // namespace geardyn::gear
