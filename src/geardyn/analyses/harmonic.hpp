#pragma once
// Linear frequency response (docs/theory.md §5) by direct solution of the dynamic stiffness
//   D(w) = K(W) - w^2 M + i w (C(W) + W G) + i K_loss + i w B diag(c) B^T
// at reference speed W, for a unit force (FRF: receptance H, mobility i w H, accelerance
// -w^2 H) or for the model's named harmonic forces (forced response). The last term is the
// low-rank modal damping of fe::LinearSystem; it is applied with the Sherman-Morrison-Woodbury
// identity on the sparse factor of the rest, never as a dense n x n matrix.
// The frequency grid is refined around every resonance until its half-power band holds enough
// samples and its peak is located to a fraction of that band (see AdaptiveGridOptions).
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/stability_check.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

enum class Spacing { Linear, Log };
enum class ResponseQuantity { Receptance, Mobility, Accelerance };

struct HarmonicSettings : model::SettingsOf<HarmonicSettings> {
  double speed = 0.0;
  double f_min = model::kNaN, f_max = model::kNaN;  ///< [rad/s]
  int n_points = 200;
  Spacing spacing = Spacing::Linear;
  bool adaptive = true;    ///< refine around peaks
  std::string input_node;  ///< unit-force input (FRF) ...
  model::Component input_dof = model::Component::Ux;
  std::vector<std::string> forces;   ///< ... or these named harmonic forces (forced response)
  std::vector<std::string> sensors;  ///< empty: all sensors
  ResponseQuantity quantity = ResponseQuantity::Receptance;
  /// Worker threads over frequencies (library setting; <= 0: all cores). Results are
  /// bit-identical for any count (tests/analyses/harmonic_threads_test.cpp).
  int threads = 1;
};

/// How DynamicStiffness factorises the sparse part of D(w).
enum class FactorPath {
  Automatic,  ///< Banded when its band holds at most kBandedFillRatio x the entries UMFPACK's
              ///< analysis estimates for L + U (shaft lines), UMFPACK otherwise; a property of
              ///< the pattern, so every frequency and every thread takes the same path
  Banded,     ///< RCM ordering + banded LU, threshold partial pivoting (linalg/banded_lu.hpp)
  Sparse      ///< UMFPACK with its fill-reducing ordering, symbolic analysis kept
};

/// Factorises D(w) for one reference speed and solves D(w) X = F for any number of right-hand
/// sides. The sparsity pattern (union of the non-zero entries of M, K(W), C(W) with every entry
/// a speed-dependent bearing can take, G, K_loss) is analysed once and split into its connected
/// components ("blocks": on a straight shaft line the lateral, axial and torsional motions; a
/// gear mesh or a cross-coupled bearing joins them), over which D is block diagonal at every
/// frequency and speed; each block has its own ordering and factor. Each frequency costs one
/// numerical LU per block (banded or UMFPACK, see FactorPath, chosen per block; the banded path
/// allocates nothing per frequency). restrict_to() skips the blocks a load does not reach. With
/// modal damping the sparse factor is of A + i w s0 M (s0: smallest modal coefficient, so the
/// factor stays regular at undamped natural frequencies), the low-rank remainder i w B diag(c - s0)
/// B^T is applied by the Woodbury identity (r extra solves and an r x r dense LU, r = number of
/// damping modes), and iterative refinement against the exact D removes the i w s0 (M - B B^T)
/// difference (see the .cpp). Singularity is judged by UMFPACK's pivot ratio and by rows that
/// cancel to round-off. Keeps a reference to `system`. Not thread-safe (solve() uses the object's
/// workspace): give each thread its own; results do not depend on which object or thread computed
/// them.
class DynamicStiffness {
 public:
  /// `analysis` names the analysis in error messages.
  DynamicStiffness(const fe::LinearSystem& system, double speed, std::string analysis,
                   FactorPath path = FactorPath::Automatic);
  ~DynamicStiffness();
  DynamicStiffness(const DynamicStiffness&) = delete;
  DynamicStiffness& operator=(const DynamicStiffness&) = delete;

  /// Changes the reference speed W (K(W), C(W), W G); the symbolic analysis is reused when the
  /// pattern does not change.
  void set_speed(double speed);
  double speed() const { return speed_; }

  /// From the next factorize on, factorises only the blocks on which some column of `loads`
  /// (n x m) has a non-zero entry; solve() then returns exactly 0 on the other blocks and
  /// requires its F to be zero there (std::invalid_argument otherwise). Exact for any load
  /// with that pattern: an unloaded regular block has response 0. An unloaded singular block
  /// (free axial motion at w = 0) is not reported (0 is returned: nothing excites it). With
  /// modal damping at w > 0 every block is factorised (the modal term couples them). The
  /// banded factorisation also forward-substitutes `loads` as it goes, so a solve() with
  /// exactly these loads only back-substitutes (bit-identical to the full solve).
  void restrict_to(const Eigen::MatrixXcd& loads);
  /// Factorises every block again from the next factorize on (the default).
  void unrestrict();

  /// Factorises D(omega), omega [rad/s] >= 0. Throws NumericalError naming the frequency and
  /// the likely cause when D (or, with modal damping, its sparse part) is singular on the
  /// blocks it factorises.
  void factorize(double omega);
  /// X = D(omega)^{-1} F for the omega of the last factorize (F: n x m).
  Eigen::MatrixXcd solve(const Eigen::MatrixXcd& F) const;
  /// The same into `X` (resized only when its shape differs: no allocation in a sweep).
  void solve(const Eigen::MatrixXcd& F, Eigen::MatrixXcd& X) const;
  /// D(omega) x for the last factorised omega (for residual checks).
  Eigen::MatrixXcd apply(const Eigen::MatrixXcd& x) const;

  /// Reciprocal pivot ratio min|U_ii| / max|U_ii| of the last factor (row-scaled), over the
  /// blocks it factorised (NaN when restrict_to left out every block).
  double reciprocal_pivot_ratio() const { return rcond_; }
  int size() const { return n_; }
  /// The path taken (Banded when every block is banded, else Sparse: UMFPACK is called; fixed
  /// at the first factorize, Automatic before).
  FactorPath factor_path() const { return chosen_; }

  /// One block of D's pattern (a connected component).
  struct BlockInfo {
    int size = 0;                             ///< equations
    FactorPath path = FactorPath::Automatic;  ///< Banded or Sparse once analysed
    int lower_bandwidth = 0;                  ///< after RCM (banded path only)
    int upper_bandwidth = 0;                  ///< after RCM (banded path only)
    bool factorised = false;                  ///< at the last factorize
  };
  /// The blocks, numbered by their lowest equation.
  std::vector<BlockInfo> blocks() const;

 private:
  struct Impl;
  /// Symbolic analysis of each block; chooses its factor path.
  void analyze();
  /// Numerical LU of the blocks factorised at this frequency; sets rcond_. False when a pivot
  /// is exactly zero.
  bool factor_blocks();
  const fe::LinearSystem& system_;
  std::string analysis_;
  int n_ = 0;
  double speed_ = 0.0;
  double omega_ = std::numeric_limits<double>::quiet_NaN();
  double rcond_ = std::numeric_limits<double>::quiet_NaN();
  FactorPath requested_ = FactorPath::Automatic, chosen_ = FactorPath::Automatic;
  std::unique_ptr<Impl> impl_;
};

/// Worker threads for a sweep of DynamicStiffness solves: `requested` (<= 0: all hardware
/// threads), at most `points`; 1 when `path` is Sparse and the system BLAS is not safe to call
/// from several threads at once (UMFPACK calls it; the banded path does not), and `note` then
/// says so (otherwise it is left empty).
unsigned sweep_threads(int requested, std::size_t points, FactorPath path, std::string& note);

/// Calls `work(i, t)` for every i in [begin, end) on `threads` threads (t in [0, threads): the
/// calling thread is t = 0), handing out indices in increasing order, and `done(count)` (under a
/// lock) after each point. The results must depend on i only, never on t or on the order, which
/// makes them bit-identical for any number of threads. When points throw, the exception of the
/// smallest index is rethrown once all threads have stopped (the one a single thread meets
/// first), so errors do not depend on the thread count either.
void for_each_point(std::size_t begin, std::size_t end, unsigned threads,
                    const std::function<void(std::size_t, unsigned)>& work,
                    const std::function<void(std::size_t)>& done);

/// Controls of the adaptive frequency grid. A resonance counts as resolved when
///  (a) its half-power band [f1, f2] holds at least `min_points_in_band` samples,
///  (b) both neighbours of the sampled maximum lie within `peak_tolerance` x (f2 - f1) of it,
///      so the true peak is bracketed that tightly (the reported peak is the parabolic vertex
///      through the three samples, more accurate still), and
///  (c) each -3 dB crossing is bracketed by samples closer than `crossing_tolerance` x (f2 - f1).
/// Peaks are local maxima of the amplitude (of the requested quantity) of any sensor with a
/// prominence of at least `min_prominence_db`. Independently, an interval whose end amplitudes
/// differ by more than `jump_ratio` is bisected, down to 1/2^max_jump_levels of the initial
/// spacing there, so that a resonance hidden between two samples shows up as a maximum.
struct AdaptiveGridOptions {
  int min_points_in_band = 5;
  double peak_tolerance = 1e-3;
  double crossing_tolerance = 2e-2;
  double min_prominence_db = 1e-3;
  double jump_ratio = 2.0;
  int max_jump_levels = 6;
  int max_passes = 60;
  int max_points = 20000;  ///< total samples; reaching it with a peak unresolved: NotConverged
};

/// A response output: a model sensor (or, at matrix level, an equation "eq<k>").
struct ResponseSensor {
  std::string name;
  int equation = -1;        ///< in the DofMap numbering
  bool rotational = false;  ///< measures a rotation (rad) rather than a displacement (m)
};

/// One resonance peak of one sensor's amplitude curve.
struct FrfPeak {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  int sensor = 0;
  double frequency = kNaN;      ///< refined peak frequency [rad/s]
  double amplitude = kNaN;      ///< refined peak amplitude, in the sensor's amplitude unit
  double f1 = kNaN, f2 = kNaN;  ///< half-power crossings [rad/s] (NaN: not in range)
  double q_factor = kNaN;       ///< f_r / (f2 - f1)
  int points_in_band = 0;
  /// Larger distance from the sampled maximum to a neighbour, / (f2 - f1): the true peak lies
  /// within this many bandwidths of the sampled maximum.
  double location_error = kNaN;
  bool resolved = false;  ///< all three criteria of AdaptiveGridOptions hold
  double damping_ratio() const { return 0.5 / q_factor; }
};

/// What the grid refinement achieved.
struct GridSummary {
  int required_points_in_band = 5;  ///< AdaptiveGridOptions used
  double required_location_error = 1e-3;
  int initial_points = 0;
  int final_points = 0;
  int passes = 0;
  bool adaptive = false;
  bool converged = true;          ///< every peak resolved within the limits
  int min_points_in_band = 0;     ///< smallest over peaks with a bandwidth (0: none)
  double max_location_error = 0;  ///< largest over peaks with a bandwidth
  std::string limit_hit;          ///< which limit stopped the refinement, empty if none
};

struct FrfResult {
  Status status = Status::Ok;
  std::string message;  ///< why status is not Ok, and what usually helps
  bool forced = false;  ///< true: response to the model's harmonic forces; false: unit force
  ResponseQuantity quantity = ResponseQuantity::Receptance;
  double speed = 0.0;             ///< reference speed [rad/s]
  std::string input;              ///< "node.dof" of the unit force, or the force names
  bool input_rotational = false;  ///< unit moment (N m) rather than force (N)
  std::vector<ResponseSensor> sensors;
  Eigen::VectorXd frequencies;  ///< [rad/s], increasing
  /// Displacement response per unit input (or to the forces), frequencies x sensors.
  Eigen::MatrixXcd displacement;
  std::vector<FrfPeak> peaks;  ///< by sensor, then frequency
  GridSummary grid;
  /// Stability at the speed (run_harmonic only; frequency_response leaves it empty): an
  /// unstable mode makes the status Unstable.
  StabilityScan stability;
  std::string thread_note;  ///< why fewer threads ran than asked for (empty when none)

  /// The requested quantity: displacement x (i w)^p with p = 0, 1, 2.
  Eigen::MatrixXcd response() const;
  /// Unit of the requested quantity's amplitude for sensor `s`, e.g. "m/N", "rad/s/(N m)", "m/s".
  std::string amplitude_unit(int s) const;
};

/// Matrix-level response: `load` (length n) applied, responses at the equations `outputs`,
/// grid, speed and quantity from `settings` (input/forces/sensors fields are not used). Throws
/// InputError (located by the context) for a bad grid, NumericalError (naming the context's
/// analysis) for a singular D(w). Progress goes to the context's. Sensor names are "eq<k>".
FrfResult frequency_response(const fe::LinearSystem& system, const Eigen::VectorXcd& load,
                             const std::vector<int>& outputs, const HarmonicSettings& settings,
                             const Context& context, const AdaptiveGridOptions& options = {});

/// The harmonic analysis of docs/theory.md §5 on the context's linear system: resolves input node /
/// forces and sensors by name (InputError when unknown or constrained), runs
/// frequency_response and checks the stability at the speed (analyses/stability_check.hpp,
/// modes up to twice frequency_stop): Status::Unstable when a mode grows.
FrfResult run_harmonic(const model::Model& model, const HarmonicSettings& settings,
                       const Context& context, const AdaptiveGridOptions& options);
/// The same with the default grid options (the driver the registry runs).
FrfResult run_harmonic(const model::Model& model, const HarmonicSettings& settings,
                       const Context& context);

/// When the adaptive grid left peaks unresolved (NotConverged), tells a lightly damped resonance
/// from a response that is not smooth: when one sensor has more than 2 x modes_in_band + 2
/// unresolved peaks (a mode gives one peak per sensor), the response has maxima no mode
/// explains, a numerical fault, and the message says so instead of advising damping.
/// `modes_in_band`: modes whose natural frequency lies in the analysis's range (within 10 %).
void diagnose_unresolved_peaks(FrfResult& result, int modes_in_band);

/// Tables "frf" (frequency_hz, per sensor <sensor>_amplitude_<unit>, <sensor>_phase_deg) and
/// "peaks" (the resonance-peak table of core/peak_table.hpp, curve = the response quantity),
/// amplitude (log) and phase plots (growing modes in range marked by a dashed vertical line),
/// notes on the grid refinement and the stability check.
AnalysisOutput harmonic_output(const model::Model& model, const HarmonicSettings& settings,
                               const FrfResult& result, const Context& context);

}  // namespace geardyn::analyses
