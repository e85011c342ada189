#pragma once
// Dynamic mesh force of a gear pair reduced to one degree of freedom along the line of action
// (docs/theory.md §13; Parker-type model as in A. Durastante, "Simulation of the Dynamic Response
// of Aeronautical Gears Equipped with Damper Rings", MSc thesis, Politecnico di Torino, 2018,
// sec. 3.2):
//
//   m_e x'' + f_c + f_k(x, t) = F_s + F_a cos(2 pi r f_m t + phi),
//   f_k = k(t) (x - e_g(t))          when x - e_g > 0          (drive-side contact)
//       = 0                          when -b < x - e_g <= 0    (contact loss, free flight)
//       = k(t) (x - e_g(t) + b)      when x - e_g <= -b        (back-side contact, backlash b)
//
//   m_e = J1 J2 / (J1 r_b2^2 + J2 r_b1^2),  F_s = T / r_b,  k(t) = F_s / (e(t) - e_g(t)),
//   c = 2 zeta sqrt(k_mean m_e),  F_d(t) = f_k + f_c,
//   f_c = c x' (damping on the DTE, default) or, damping on the elastic deflection,
//   f_c = c (x' - e_g') in contact (drive or back side) and 0 in contact loss (MeshDamping);
//   F_a, r, phi an optional external harmonic force at a whole mesh order r.
//
// x is the dynamic transmission error (DTE, a length), e the loaded STE and e_g the unloaded
// (geometric) TE of the SteCurve (e_g = 0 when none). Without backlash (b = infinity) the
// back-side branch never acts; with `contact_loss = false` the drive-side law holds for all x
// (the linear time-periodic model).
//
// Method. k(t) and e_g(t) are taken constant on each of N uniform intervals of the mesh period
// (the STE's Hold steps, or for Linear STE the exact mean of F_s / (e - e_g) and the mean e_g over
// each sub-interval: second-order accurate in 1/N). On an interval the equation is linear in each
// contact region, so the state is propagated exactly with the 2x2 transition matrix
// exp(A t) in closed form; a change of contact region inside an interval is located by a
// bracketed root search on the exact solution (N is large enough that an interval is shorter than
// a sixteenth of the shortest natural period, so a region is left at most once per extremum and
// no crossing is missed). The contact force is continuous across the region boundaries, so the
// transition matrices chain without saltation terms and their product over a cycle is the exact
// monodromy matrix M of the Poincaré map s_{n+1} = P(s_n), s = (x, x') at the cycle start.
// With damping on the elastic deflection, e_g is linear in time on each interval (the Linear
// STE's own e_g' enters exactly through the particular solution x_p = e_g(t) + F_s / k), and the
// damper force jumps at a contact change: its saltation matrix enters the monodromy. The
// harmonic force enters through its closed-form particular solution.
//
// Steady state: the map is iterated (time marching) until the scaled change
//   r = sqrt( (dx / x_s)^2 + (dv / (omega x_s))^2 ),  x_s = F_s / k_mean, omega = sqrt(k_mean/m_e)
// between consecutive cycles is below `tolerance` (period 1), or between cycles n and n - p
// (period p <= max_period: subharmonic response). Optionally (default) Newton's method on
// P(s) - s = 0 with the monodromy as Jacobian accelerates this; its fixed point is accepted only
// if it is asymptotically stable (all Floquet multipliers |mu| < 1 - 1e-9), so an unstable
// periodic solution (parametric instability, the unstable middle branch of a softening jump) is
// never reported as a steady state. Growth beyond `divergence_factor` times the largest static
// deflection stops with Status::Diverged; no steady state within max_cycles gives
// Status::NotConverged (quasi-periodic or chaotic response, or no damping).
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/gear/ste.hpp"

namespace geardyn::gear {

/// Equivalent mass along the line of action, m_e = J1 J2 / (J1 r_b2^2 + J2 r_b1^2) [kg], from the
/// polar inertias [kg m^2] and base radii [m] of the two gears. Either inertia may be infinite
/// (m_e = J_other / r_b,other^2). Throws InputError for non-positive or non-finite values.
double equivalent_mass(double inertia1_kgm2, double inertia2_kgm2, double base_radius1_m,
                       double base_radius2_m);

/// Mesh frequency f_m = z n / 60 [Hz] of a gear with `teeth` teeth at `speed_rpm`.
double mesh_frequency_hz(double speed_rpm, int teeth);

/// What the mesh damper c acts on (docs/theory.md §13).
enum class MeshDamping {
  /// c x': on the dynamic transmission error, in and out of contact (a damper between the gear
  /// bodies, e.g. bearings and lubricant; the default).
  Dte,
  /// c (x' - e_g') on the elastic deflection of the teeth, as in A. Kahraman, R. Singh,
  /// "Non-linear dynamics of a spur gear pair", J. Sound Vib. 1990 and H.N. Özgüven,
  /// D.R. Houser, "Mathematical models used in gear dynamics - a review", J. Sound Vib. 1988,
  /// but acting in contact only (a tooth damper: no damping in free flight, where those models
  /// keep it); e_g is followed piecewise linearly and exactly.
  ElasticDeflection
};

enum class MeshModel {
  Dynamic,         ///< the equation above, integrated to its periodic steady state
  InfiniteInertia  ///< algebraic: x = F_s / k_mean, F_d(t) = F_s k(t) / k_mean (no dynamics)
};

/// When the periodic steady state is reached.
struct SteadyStateOptions {
  double tolerance = 1e-9;  ///< on the scaled Poincaré change r (see above), relative
  int max_cycles = 20000;   ///< mesh cycles before Status::NotConverged
  int max_period = 8;       ///< longest subharmonic period (in mesh cycles) detected
  bool newton = true;       ///< Newton acceleration on the Poincaré map (stable fixed points only)
  double divergence_factor = 1e3;  ///< |x| > this * max(e) => Status::Diverged
};

struct DynamicMeshOptions {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double equivalent_mass_kg = kNaN;  ///< m_e (see equivalent_mass); needed for Dynamic
  double static_force_n = kNaN;      ///< F_s = T / r_b > 0 [N]
  double damping_ratio = 0.08;       ///< zeta >= 0; c = 2 zeta sqrt(k_mean m_e)
  MeshModel model = MeshModel::Dynamic;
  bool contact_loss = true;            ///< false: linear law k (x - e_g) for every x
  double backlash_m = kInf;            ///< b > 0 [m]; infinity: no back-side contact
  int min_points_per_period = 128;     ///< at least this many intervals per mesh period
  int points_per_natural_period = 16;  ///< intervals per shortest natural period (>= 8)
  MeshDamping damping_on = MeshDamping::Dte;
  /// External harmonic force on the mesh coordinate, added to F_s:
  /// F(t) = F_s + F_a cos(2 pi r f_m t + phi), r = force_order (an integer, so that F(t) has the
  /// mesh period and the periodic steady state exists), t = 0 at the cycle start.
  double force_amplitude_n = 0.0;  ///< F_a >= 0 [N]
  int force_order = 1;             ///< r in [1, 1000]
  double force_phase_rad = 0.0;    ///< phi [rad]
  SteadyStateOptions steady_state;
  /// Throws InputError (key path `dynamic_mesh.<field>`) for the first invalid field.
  void validate() const;
};

/// State on the Poincaré section (start of a mesh cycle, where the tooth enters contact).
struct MeshState {
  double x_m = 0.0;
  double v_m_s = 0.0;
};

/// The periodic steady state at one mesh frequency.
struct MeshResponse {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  Status status = Status::Failed;
  /// Empty for a period-1 steady state; names a subharmonic (Ok) or says what failed and what
  /// usually helps.
  std::string message;
  double mesh_frequency_hz = kNaN;
  int transient_cycles = 0;   ///< mesh cycles integrated before the steady state (incl. Newton)
  int newton_iterations = 0;  ///< of which Newton iterations
  int period_cycles = 0;      ///< period of the steady state in mesh cycles (1; > 1 subharmonic)
  int points_per_period = 0;  ///< intervals per mesh period used
  double poincare_change = kNaN;     ///< last scaled change r
  double floquet_multiplier = kNaN;  ///< largest |mu| of the monodromy over period_cycles
  MeshState start_state;             ///< on the periodic orbit at the cycle start

  /// period_cycles * points_per_period samples at t_i = i T_m / points_per_period (the start of
  /// each interval; force and contact force use that interval's k: right limits).
  std::vector<double> time_s, dte_m, velocity_m_s, force_n, contact_force_n;

  // Over the steady state (exact extrema on the piecewise solution; means by 4-point Gauss
  // quadrature on every piece):
  double dte_mean_m = kNaN;
  double dte_rms_m = kNaN;  ///< RMS of the fluctuation, sqrt(mean((x - mean x)^2))
  double dte_max_m = kNaN;
  double dte_min_m = kNaN;
  double force_mean_n = kNaN;  ///< of F_d (equals F_s at a periodic steady state)
  double force_max_n = kNaN;
  double force_min_n = kNaN;
  double dynamic_factor = kNaN;         ///< force_max / F_s
  double contact_loss_fraction = kNaN;  ///< fraction of time with x - e_g <= 0
  double back_contact_fraction = kNaN;  ///< fraction of time in back-side contact
};

/// The mesh model for one STE curve and load; solve() is const and may run concurrently.
class DynamicMesh {
 public:
  /// Validates the options (InputError) and precomputes k_mean and c.
  DynamicMesh(SteCurve ste, DynamicMeshOptions options);

  const SteCurve& ste() const { return ste_; }
  const DynamicMeshOptions& options() const { return options_; }
  double mean_stiffness_n_m() const { return k_mean_; }  ///< time mean of k(t)
  double max_stiffness_n_m() const { return k_max_; }
  double damping_n_s_m() const { return damping_; }  ///< c
  double natural_frequency_hz() const;               ///< sqrt(k_mean / m_e) / 2 pi
  double static_deflection_m() const { return options_.static_force_n / k_mean_; }
  double max_ste_m() const { return e_max_; }  ///< largest |e| over the cycle

  /// Steady state at `mesh_frequency_hz` (> 0), starting from `initial` (e.g. the start_state of
  /// a neighbouring frequency) or, when null, from the static equilibrium x = e(0), x' = 0.
  /// Numerical outcomes are in the status; throws InputError for a bad frequency.
  MeshResponse solve(double mesh_frequency_hz, const MeshState* initial = nullptr) const;

  /// Static equilibrium at the cycle start: x = e(0) (within the first interval), x' = 0.
  MeshState static_state() const;

  /// One mesh cycle of the Poincaré map from `start` at `mesh_frequency_hz`: the end state and
  /// the exact monodromy (Jacobian d end / d start, row-major [dx/dx, dx/dv, dv/dx, dv/dv],
  /// saltation at contact changes included). For tests and diagnostics; throws InputError for a
  /// bad frequency and NumericalError when the cycle cannot be integrated.
  MeshState poincare_map(double mesh_frequency_hz, const MeshState& start,
                         std::array<double, 4>* monodromy = nullptr) const;

 private:
  SteCurve ste_;
  DynamicMeshOptions options_;
  double k_mean_ = 0.0, k_max_ = 0.0, damping_ = 0.0, e_max_ = 0.0;
};

enum class SweepDirection { Up, Down, Both };

struct MeshSweepOptions {
  std::vector<double> mesh_frequencies_hz;  ///< strictly increasing, > 0
  int teeth = 0;  ///< teeth of the gear whose speed is tabulated (speed_rpm = 60 f_m / z); 0: NaN
  SweepDirection direction = SweepDirection::Both;
  bool keep_responses = false;  ///< keep every MeshResponse (time histories) in the result
};

/// One row of a sweep table.
struct MeshSweepPoint {
  double mesh_frequency_hz = MeshResponse::kNaN, speed_rpm = MeshResponse::kNaN;
  double dte_mean_m = MeshResponse::kNaN, dte_rms_m = MeshResponse::kNaN;
  double dte_max_m = MeshResponse::kNaN, force_max_n = MeshResponse::kNaN;
  double dte_min_m = MeshResponse::kNaN, force_min_n = MeshResponse::kNaN;
  double dynamic_factor = MeshResponse::kNaN, contact_loss_fraction = MeshResponse::kNaN;
  double floquet_multiplier = MeshResponse::kNaN;  ///< largest |mu| (< 1: a stable orbit)
  int period_cycles = 0, cycles = 0;
  Status status = Status::Failed;
  std::string message;  ///< why there is no steady state (empty when ok)
};

struct MeshSweepResult {
  /// Sweep up (increasing frequency) and sweep down (in the order computed: decreasing
  /// frequency); each point starts from the previous point's steady state (the first from the
  /// static equilibrium), so the jump and hysteresis of contact loss show up as a difference.
  std::vector<MeshSweepPoint> up, down;
  std::vector<MeshResponse> up_responses, down_responses;  ///< when keep_responses
  Status status = Status::Ok;                              ///< the worst point status
  std::string message;  ///< summary of the points that are not ok

  /// Table `name` with columns mesh_frequency_hz, speed_rpm, dte_mean_m, dte_rms_m, dte_min_m,
  /// dte_max_m, force_min_n, force_max_n, dynamic_factor, contact_loss (fraction of time),
  /// floquet_multiplier, period_cycles, cycles, status, message.
  static Table table(const std::vector<MeshSweepPoint>& points, std::string name,
                     std::string title);
};

/// Sweeps the mesh frequencies up and/or down with continuation of the steady state.
/// Reports progress per frequency. Throws InputError for bad options.
MeshSweepResult sweep_mesh_frequency(const DynamicMesh& mesh, const MeshSweepOptions& options,
                                     Progress& progress = null_progress());

}  // namespace geardyn::gear
