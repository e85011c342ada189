#pragma once
// Campbell diagram (docs/theory.md §3): complex modes of the damped gyroscopic system over a list
// of reference speeds, tracked from speed to speed by the shapes (MAC with an optimal one-to-one
// assignment, so crossing modes keep their identity), engine-order lines and critical speeds
// where a tracked mode meets a line, f_mode(Omega) = order Omega / 2pi.
#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Speeds per chunk (see run_campbell): about a sixteenth of the speeds (room for up to 8 threads
/// to share the work), at least kCampbellMinChunkSpeeds, and at most what keeps one chunk's mode
/// shapes within kCampbellChunkBytes (but never below the minimum). A function of the number of
/// speeds, DOFs and candidate modes only, never of the thread count. Each chunk repeats the
/// enrichment of the projection basis its speeds need, so fewer, longer chunks cost less.
inline constexpr std::size_t kCampbellMinChunkSpeeds = 16;
inline constexpr double kCampbellChunkBytes = 64.0 * 1024 * 1024;
std::size_t campbell_chunk_speeds(std::size_t n_speeds, std::size_t n_dofs,
                                  std::size_t n_candidates);

struct CampbellSettings : model::SettingsOf<CampbellSettings> {
  std::vector<double> speeds;  ///< reference speeds [rad/s]
  int n_modes = 8;
  std::vector<double> engine_orders = {1.0};  ///< orders of the reference shaft
  bool shaft_orders = true;                   ///< add order 1 of every shaft (x its speed ratio)
  bool mesh_orders = true;                    ///< add teeth x shaft order of every mesh with teeth
  double mac_threshold = 0.7;                 ///< below this a tracking step is flagged ambiguous
  /// Refine critical speeds and instability onsets by eigen-solves between the grid speeds
  /// (false: linear interpolation on the grid). Not a model key yet (adding one needs the
  /// regenerated model reference); set by library callers.
  bool refine_crossings = true;
  EigenMethod method = EigenMethod::Auto;
  /// Start each speed from the previous one's solver state within its chunk of speeds (the
  /// projection basis, enriched so far; the Arnoldi start vector; see run_campbell). false:
  /// every speed is solved from scratch (the cold start that tests compare against; slower).
  /// Not a model key; set by library callers.
  bool warm_start = true;
  /// Worker threads over the chunks of speeds (<= 0: all cores). The results are bit-identical
  /// for any count (see run_campbell); 1 when the solves call a system BLAS that is not safe
  /// from several threads (CampbellResult::thread_note says so).
  int threads = 1;
};

/// One tracked mode at one speed (shapes are not kept: n_speeds x n_modes x n would be large).
struct TrackPoint {
  double speed = eig::kNaN;  ///< reference speed [rad/s]
  std::complex<double> eigenvalue{eig::kNaN, eig::kNaN};
  double frequency_hz = eig::kNaN;  ///< |lambda| / 2pi (NaN: no mode assigned)
  double damped_frequency_hz = eig::kNaN;
  double damping_ratio = eig::kNaN;
  Whirl whirl = Whirl::None;
  ModeKind kind = ModeKind::Coupled;
  double residual = eig::kNaN;
  /// MAC with the track's shape at the previous speed (1 at the first speed). When the track's
  /// previous eigenvalue was repeated (e.g. the two whirl directions of an isotropic rotor at
  /// rest), the MAC with the subspace of all modes computed there with that eigenvalue.
  double mac = eig::kNaN;
  bool ambiguous = false;  ///< mac < mac_threshold, or no mode assigned
};

/// f = order x Omega / 2pi; `order` per revolution of the reference shaft.
struct EngineOrderLine {
  std::string label;
  double order = 0;
};

struct CriticalSpeed {
  int mode = 0;  ///< 1-based track
  double order = 0;
  std::string line;          ///< label of the engine-order line
  double speed = eig::kNaN;  ///< reference speed [rad/s]
  double frequency_hz = eig::kNaN;
  double damping_ratio = eig::kNaN;
  Whirl whirl = Whirl::None;
  ModeKind kind = ModeKind::Coupled;  ///< of the mode at the critical speed
  bool ambiguous = false;             ///< the track was ambiguous at either neighbouring speed
  /// Located by root-finding on the eigenvalue curve (false: linear interpolation between the
  /// grid speeds, when no unambiguous root could be followed between them).
  bool refined = false;
};

/// A speed at which a tracked mode's damping ratio crosses zero downwards (it becomes unstable).
struct InstabilityOnset {
  int mode = 0;              ///< 1-based track
  double speed = eig::kNaN;  ///< [rad/s]
  double frequency_hz = eig::kNaN;
  Whirl whirl = Whirl::None;
  ModeKind kind = ModeKind::Coupled;
  bool refined = false;         ///< root of zeta(Omega) = 0 found between grid speeds
  bool at_first_speed = false;  ///< unstable already at the first speed: onset at or below it
  double min_damping_ratio = eig::kNaN;  ///< lowest damping ratio of the track over the grid
  double speed_of_min = eig::kNaN;       ///< [rad/s] where that lowest value is
};

/// True when a track point's damping ratio is below -kUnstableDampingRatio.
bool is_unstable(const TrackPoint& point);

struct CampbellResult {
  Status status = Status::Failed;
  std::string message;
  std::vector<double> speeds;                   ///< [rad/s], ascending
  std::vector<std::vector<TrackPoint>> tracks;  ///< tracks[t][i]: track t at speeds[i]
  std::vector<EngineOrderLine> lines;
  std::vector<CriticalSpeed> critical_speeds;  ///< ordered by speed
  std::vector<InstabilityOnset> onsets;        ///< ordered by speed
  int refinement_solves = 0;                   ///< eigen-solves between grid speeds
  std::string fewer_modes_note;                ///< set when n_modes exceeds the modes the model has
  int ambiguous_points = 0;
  int candidates_per_speed = 0;  ///< elastic modes computed per speed (tracks + spares)
  int rigid_body_roots = 0;      ///< roots at 0 Hz (rigid-body motion) left out of the tracking
  double max_residual = 0;
  std::string method;  ///< solver method(s) used: "projected", "dense", "sparse"
  /// Largest size of the projection basis over the sweep and the refinements (0: no
  /// projection; see ModeSolver in campbell.cpp and eig/projected_quadratic.hpp).
  int projection_basis = 0;
  /// Solves the projection could not certify, redone by the reference solver (method lists it).
  int projection_fallbacks = 0;
  std::string first_fallback;  ///< where and why the first of them happened
  /// Operations of the solves (linear solves with a factor) at the speeds and in the
  /// refinements, plus those of the seed solves counted once (see run_campbell).
  int total_operations = 0;
  int threads_used = 1;
  std::string thread_note;  ///< why fewer threads ran than asked for (empty when none)
  double run_time_s = 0;
};

/// Engine-order lines: the settings' orders of the reference shaft; order |speed_ratio| of every
/// shaft if shaft_orders; teeth x |speed ratio| of every gear mesh with teeth if mesh_orders
/// (gear1's teeth and node; gear2's if gear1 has none). Orders equal to an earlier one within
/// 1e-9 are merged into its label.
std::vector<EngineOrderLine> engine_order_lines(const model::Model& model,
                                                const fe::LinearSystem& system,
                                                const CampbellSettings& settings);

/// Optimal assignment maximising the total score (Hungarian method: H. W. Kuhn, "The Hungarian
/// method for the assignment problem", 1955; J. Munkres, "Algorithms for the assignment and
/// transportation problems", 1957):
/// rows (tracks) to distinct columns (candidates); rows <= columns. Returns the column of each
/// row. Ties go to the lower column index, so the result is deterministic.
std::vector<int> best_assignment(const Eigen::MatrixXd& score);

/// Runs the sweep on the context's linear system. Throws InputError (located by the context)
/// for invalid settings (no speeds, speeds not strictly increasing or negative, n_modes < 1,
/// threshold outside [0, 1], non-positive orders).
///
/// Two phases, so that the results are bit-identical for any number of threads:
///  (a) the eigen-solves (and the description of every mode: rigid-body test, families,
///      whirl) of each speed, in chunks of campbell_chunk_speeds() consecutive speeds whose
///      bounds do not depend on the thread count. Each worker thread owns its solver, seeded
///      the same way on every thread (a solve at the first speed; the projection basis so built
///      is kept) and returned to that seed at the start of every chunk (the kept basis; the
///      Arnoldi start vector dropped), so a speed's result depends on its chunk only, never on
///      the thread that ran it. One thread runs the same chunks.
///  (b) the tracking (MAC scores against the previous speed, optimal assignment), sequential
///      and cheap, over the solved speeds in order, after each batch of chunks (one per thread,
///      so that at most threads x kCampbellChunkBytes of mode shapes are held).
/// The refinements of critical speeds and onsets then run in order on one solver returned to
/// its seed. Errors from a worker are rethrown (the one of the lowest chunk).
CampbellResult run_campbell(const model::Model& model, const CampbellSettings& settings,
                            const Context& context);

/// Tables "campbell", "critical_speeds", "engine_orders"; plots "campbell" (frequency vs speed
/// with dashed engine-order lines and critical-speed markers) and "campbell_damping".
AnalysisOutput campbell_output(const model::Model& model, const CampbellSettings& settings,
                               const CampbellResult& result, const Context& context);

/// The lowest speed [rad/s] at which a tracked mode becomes unstable: the lowest of
/// result.onsets (root-refined where the damping ratio crosses zero between grid speeds; the
/// first speed when a mode is unstable there), NaN when every tracked mode stays stable.
double instability_onset_speed(const CampbellResult& result);

}  // namespace geardyn::analyses
