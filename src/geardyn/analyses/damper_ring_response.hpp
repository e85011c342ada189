#pragma once
// damper_ring_response: the friction-damped forced response of a cyclic gear with a damper ring
// in a groove of its rim, wired to the model file (issue [friction-hbm] sections 3, 4 and 7;
// docs/theory.md §8; A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears
// Equipped with Damper Rings", MSc thesis, Politecnico di Torino, 2018, ch. 4 and sec. 5.3).
// run_damper_ring_response solves (model, settings, context) -> DamperRingResponseResult;
// damper_ring_response_output writes its tables, plots and notes.
//
// The solid is one sector of the gear and of the split ring, meshed together as two bodies
// (a generated gear_sector with groove = true, or a mesh file with the same sets): the contact
// faces' node sets (groove_contact, ring_contact) give the node-to-node contact pairs, the sector
// faces (left, right, ring_left, ring_right) the cyclic interfaces of each body, and the ring's
// element set its mass m_ring and centre-of-mass radius r_G (damper::body_mass), hence the
// centrifugal preload per contact N_0 = m_ring W^2 r_G / (N n_pairs).
//
// Contact stiffness: k_n per pair given, or per contact area (N/m^3) times the sector's contact
// face area 2 pi r_c w / N shared equally by the pairs (r_c the contact radius, w the face's axial
// width); k_t given or from k_n by Mindlin's ratio of the two materials (damper::mindlin_ratio).
//
// The excitation is one engine order k of the tooth force, taken from a [[gear_pairs]] entry as
// cyclic_forced_response does (harmonic n of the balance carries order n k, each loaded with its
// own tooth-force harmonic), or force_amplitude F_k (a list: F_k, F_2k, ... on harmonics 1, 2,
// ...). The response is traced over the speed range by continuation
// (damper::run_damper_ring) with the linear responses of the gear without ring (free) and with
// the ring stuck (contacts as springs k_n, k_t) over the same speeds.
//
// Outputs: resonance table (peak speed, amplitude and half-power Q of the damped, free and stuck
// curves, the amplitude reduction and the resonance shift); the damped response per continuation
// point with energy dissipated per cycle and stick / slip / lift-off fractions; the contact
// states per pair and the hysteresis loops at the damped peak; optionally the damper performance
// curve (resonance speed, peak, Q against ring mass, friction coefficient or contact stiffness,
// the optimum marked). Bad input throws InputError located by the context; a continuation that
// stops early returns the points reached with status Failed and its message.
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/cyclic_forced_response.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/damper/damper_ring.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/response/speed_peaks.hpp"

namespace geardyn::analyses {

/// Friction-damped forced response of a cyclic gear with a damper ring in a groove, by harmonic
/// balance condensed to the ring's contacts (damper/damper_ring.hpp, docs/theory.md §8). It is a
/// cyclic forced response (the excitation, sensor, damping and speed keys are the same, for one
/// engine order) plus the ring: its contacts, the harmonics balanced and an optional
/// performance sweep.
enum class DamperSweep { None, RingMass, FrictionCoefficient, ContactStiffness };
struct DamperRingResponseSettings
    : model::SettingsOf<DamperRingResponseSettings, CyclicForcedResponseSettings> {
  int engine_order = 0;  ///< k; the nodal diameter is h = +-k mod N
  std::string gear_contact_set = "groove_contact";
  std::string ring_contact_set = "ring_contact";
  std::string ring_element_set = "ring";
  int contact_directions = 1;                 ///< 1: 2D contact (normal, one slip direction); 2: 3D
  double ring_inclination = 0.0;              ///< psi [rad] of the 2D slip direction
  double normal_stiffness = model::kNaN;      ///< k_n per contact pair [N/m] ...
  double contact_stiffness = model::kNaN;     ///< ... or per contact area [N/m^3]
  double tangential_stiffness = model::kNaN;  ///< k_t per pair [N/m] (NaN: Mindlin ratio of k_n)
  double friction_coefficient = model::kNaN;  ///< mu
  int harmonics = 1;                          ///< H balanced
  int time_samples = 0;                       ///< per period (0: from H)
  std::vector<int> hysteresis_pairs;          ///< contact pairs whose loops are reported (empty: 3)
  double max_step = 0.02;                     ///< continuation step / (speed range, amplitude)
  DamperSweep sweep = DamperSweep::None;
  std::vector<double> sweep_values;  ///< ring-mass or stiffness factors, or mu
};

/// One point of the damper performance curve: the damped peak with one parameter changed.
struct DamperPerformancePoint {
  double value = 0.0;  ///< the ring-mass or stiffness factor, or mu
  response::SpeedPeak peak;
  double energy = 0.0, slip = 0.0;  ///< at the damped peak
  Status status = Status::Ok;
  std::string message;
};

/// What run_damper_ring_response solves.
struct DamperRingResponseResult {
  damper::DamperRingResult response;  ///< damped curve, linear references, contacts at the peak
  std::vector<std::string> sensor_names;
  std::vector<damper::ContactPair> pairs;  ///< the independent contact pairs
  std::vector<std::string> model_notes;    ///< of the condensed model
  std::vector<std::string> setup_notes;    ///< how the contact stiffnesses were found
  damper::BodyMass ring;                   ///< mass of the whole ring, r_G
  damper::ContactLaw contact;              ///< per pair
  int dropped_pairs = 0;                   ///< on the right sector face
  double preload_at_max = 0.0;             ///< N0 per pair at the highest speed [N]
  std::vector<CyclicOrderForce> orders;    ///< the harmonics loaded (engine order n k)
  std::string force_note;                  ///< where they come from
  std::string reduction_note;              ///< what the Craig-Bampton reduction kept (or empty)
  /// Per sensor: the main peak of the damped curve (harmonic 1) and of the gear without ring
  /// (resolved on a fine speed grid); the stuck ring's for sensor 0.
  std::vector<response::SpeedPeak> damped_peaks, free_peaks;
  response::SpeedPeak stuck_peak;
  std::vector<DamperPerformancePoint> performance;  ///< empty: no performance sweep

  /// Index of the sensor called `name` (empty: the first); std::runtime_error if none.
  std::size_t sensor_index(const std::string& name) const;
};

/// Solves the friction-damped response of the solid s.solid (from context.solid()).
DamperRingResponseResult run_damper_ring_response(const model::Model& model,
                                                  const DamperRingResponseSettings& settings,
                                                  const Context& context);

/// Its tables (resonance, damped_response, linear_response, contact_pairs, hysteresis_loops,
/// performance, harmonic_forces), plots and notes.
AnalysisOutput damper_ring_response_output(const model::Model& model,
                                           const DamperRingResponseSettings& settings,
                                           const DamperRingResponseResult& result,
                                           const Context& context);

/// What the parser cannot check for one damper_ring_response: the node and element sets exist,
/// the contact nodes pair up, the ring has a mass, hysteresis_pairs name existing pairs. Throws
/// InputError located by `context`.
void check_damper_ring_response(const assembly::SolidComponent& solid,
                                const DamperRingResponseSettings& settings, const Context& context);

}  // namespace geardyn::analyses
