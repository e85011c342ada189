#pragma once
// Stability check of the steady-state analyses (unbalance, harmonic): a steady state computed
// from D(w) X = F exists for any system whose D(w) is regular, stable or not, but an unstable
// machine never reaches it. Before such a result is called ok, the least-damped complex modes of
//   M q'' + (C(W) + W G + C_modal) q' + K(W) q = 0
// at the analysis's speed W are computed with the quadratic eigen-solver (eig/quadratic_eigen)
// and every mode with Re(lambda) > 0 is reported.
//
// Which modes (the rule): the modes of smallest |lambda| (the solver's automatic target), as
// many as needed so that the highest natural frequency computed is at least
// kBandMargin x the highest frequency the analysis excites (unbalance: largest order x speed;
// harmonic: frequency_stop), and at least kMinModes; the count grows until that holds, every
// mode of the system is computed, or kMaxModes is reached (the cost of one Arnoldi solve grows
// with the modes asked for; a band that needs more is rare for rotors and the note then says
// up to which frequency the check holds). Modes above the highest one computed are not checked.
//
// Verdict: a mode is unstable when its growth rate Re(lambda) exceeds
// kGrowthTolerance x (the highest natural frequency checked). The eigenvalues carry a backward
// error of about 1e-14 (relative to the matrix norms, i.e. to the highest frequency), and a
// double root (rigid-body roots of free torsion) moves by about its square root, 1e-7 of it:
// 1e-6 is above both, and a mode growing that slowly needs 1e6 radians of the highest frequency
// to grow by e (less than any physical damping can be trusted to).
#include <complex>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/fe/linear_system.hpp"

namespace geardyn::analyses {

struct StabilityMode {
  int mode = 0;                     ///< rank by natural frequency among the modes checked (1..)
  std::complex<double> eigenvalue;  ///< lambda [rad/s], Im >= 0
  double frequency = 0.0;           ///< natural frequency |lambda| [rad/s]
  double damping_ratio = 0.0;       ///< -Re(lambda) / |lambda|
};

/// The verdict at one speed.
struct StabilityAtSpeed {
  double speed = 0.0;  ///< [rad/s]
  bool stable = true;  ///< no checked mode grows
  int modes_checked = 0;
  double covered = 0.0;        ///< highest natural frequency checked [rad/s]
  bool band_covered = true;    ///< covered >= the band asked for (false: every mode was computed
                               ///< and the system has none higher, also fine; see message)
  StabilityMode least_damped;  ///< smallest damping ratio among the modes checked
  std::vector<StabilityMode> unstable;            ///< growing modes, by frequency
  std::vector<std::complex<double>> eigenvalues;  ///< every mode checked, Im >= 0, by |lambda|
  Status solver_status = Status::Ok;              ///< of the eigen-solve
  std::string solver_message;
};

constexpr double kBandMargin = 2.0;
constexpr int kMinModes = 24;  // one solve covers twice the top excitation of most rotors
constexpr int kMaxModes = 150;
constexpr double kGrowthTolerance = 1e-6;

/// The verdict at `speed` [rad/s], checking the modes up to kBandMargin x `band_top` [rad/s].
/// `n_modes_hint` (in/out): the mode count to start with; on return the count that sufficed.
StabilityAtSpeed check_stability(const fe::LinearSystem& system, double speed, double band_top,
                                 int* n_modes_hint = nullptr);

/// The verdicts over a list of speeds (any order). Up to kMaxSampledSpeeds speeds every one is
/// checked; beyond that an evenly spread subset of the sorted list (ends included) is, and
/// between two sampled speeds whose verdicts differ the first speed of the list with the other
/// verdict is found by bisection on the list, then the onset itself by bisection on the speed
/// to kOnsetTolerance (relative). The other speeds take the verdict of the sampled speeds around
/// them (a stability window narrower than the sample spacing can be missed: the note says so).
struct StabilityScan {
  double band_top = 0.0;                 ///< highest excitation frequency [rad/s]
  std::vector<bool> stable;              ///< per speed of the list, in its order
  std::vector<bool> checked;             ///< per speed: its own eigen-solve (false: inferred)
  std::vector<StabilityAtSpeed> solves;  ///< every solve, sorted by speed
  /// Onsets: speeds [rad/s] where the verdict changes, refined; with the verdict above them.
  struct Change {
    double speed = 0.0;
    bool stable_above = false;
  };
  std::vector<Change> changes;
  int n_solves = 0;
  bool subsampled = false;

  bool all_stable() const;
  /// The least-damped solve among the unstable ones (nullptr: none).
  const StabilityAtSpeed* worst() const;
};

constexpr int kMaxSampledSpeeds = 41;
constexpr double kOnsetTolerance = 1e-4;

/// `band_top`: highest excitation frequency of the analysis [rad/s] (the same at every speed).
StabilityScan scan_stability(const fe::LinearSystem& system, const std::vector<double>& speeds,
                             double band_top);

/// "mode 4 (95.75 Hz, damping ratio -0.052)".
std::string describe(const StabilityMode& m);

/// The message of Status::Unstable for a scan: the unstable speed range(s) in rpm and the
/// least-damped unstable mode with its speed. Empty when every speed is stable.
std::string unstable_message(const StabilityScan& scan);

/// The note on the check: the rule, modes checked, band, solves, least damping ratio, and the
/// unstable range(s).
std::string stability_note(const StabilityScan& scan);

}  // namespace geardyn::analyses
