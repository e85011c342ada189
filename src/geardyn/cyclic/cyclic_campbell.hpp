#pragma once
// Campbell diagram of a cyclic structure in the rotating frame (docs/theory.md §12.3;
// damper-ring thesis, sections 1.3.3 and 5.1, Figure 5-3).
//
// In the frame that rotates with the wheel, a mode of nodal diameter h keeps its frequency f_h
// (a horizontal line, or a curve f_h(Omega) when stiffening/softening with speed is modelled),
// while the k-th harmonic of a stationary excitation with N periods per revolution (mesh
// force, N teeth) sweeps the wheel as a travelling pattern at frequency k Omega / (2 pi). The
// pattern of order k has nodal diameter k mod N folded into 0..N/2, so the mode with h nodal
// diameters is excited by the engine orders
//   k = m N + h  and  k = m N - h,   m = 0, 1, 2, ...,   k >= 1,
// the lowest two being k = h (forward) and k = N - h (backward). Resonance where the
// engine-order line meets the mode:  f_h(Omega) = k Omega / (2 pi),  i.e. for a constant f_h,
//   speed_rpm = 60 f_h / k.
#include <string>
#include <vector>

#include "geardyn/core/table.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"

namespace geardyn::cyclic {

/// Engine orders 1..max_order that excite nodal diameter h of an N-sector structure, ascending:
/// k with k = h or k = -h (mod N). h = 0 gives N, 2N, ...; h = N/2 gives N/2, 3N/2, ...
/// Throws InputError for N < 2, h outside 0..N/2 or max_order < 1.
std::vector<int> engine_orders(int nodal_diameter, int n_sectors, int max_order);

/// The frequency of one mode of one nodal diameter, constant or against speed.
struct ModeFrequencyLine {
  int nodal_diameter = 0;
  int mode = 1;  ///< 1-based within its nodal diameter
  /// One value (constant with speed) or one per entry of CyclicCampbellOptions::speeds_rpm [Hz].
  std::vector<double> frequency_hz;
};

struct CyclicCampbellOptions {
  int n_sectors = 0;
  /// Highest engine order considered; 0: 2 N.
  int max_engine_order = 0;
  /// Speeds [rpm] at which speed-dependent frequencies are given (ascending). Needed only when
  /// some line has more than one value.
  std::vector<double> speeds_rpm;
};

/// The constant frequency lines of a cyclic modal solution, one per (nodal diameter, mode).
std::vector<ModeFrequencyLine> frequency_lines(const CyclicModesResult& modes);

/// Resonances of every mode line with every engine order that excites its nodal diameter.
/// Table "cyclic_campbell": nodal_diameter, mode, engine_order, branch ("h+mN" when
/// k = h (mod N), "mN-h" otherwise; "h+mN" when both), frequency_hz (at the resonance),
/// resonance_speed_rpm. Speed-dependent lines: every crossing of f_h(speed) with k speed / 60
/// inside the speed range, by linear interpolation between the given speeds. Rows sorted by
/// resonance speed. Throws InputError for invalid options, lines with bad nodal diameters or
/// a frequency count that is neither 1 nor speeds_rpm.size().
Table cyclic_campbell(const std::vector<ModeFrequencyLine>& lines,
                      const CyclicCampbellOptions& options);

}  // namespace geardyn::cyclic
