#pragma once
// Damper ring in a gear-web groove: the friction-damped forced response of a cyclic gear to one
// engine order of its tooth force, by harmonic balance condensed to the contact coordinates
// (docs/theory.md §8; the damper-ring thesis: A. Durastante, "Simulation of the Dynamic Response of
// Aeronautical Gears Equipped with Damper Rings", MSc thesis, Politecnico di Torino, 2018, ch. 4
// and sec. 5.3).
//
// Model. One sector of the gear and one sector of the split ring (one mesh, two bodies, no
// elements between them: meshgen::gear_sector with a groove) joined only by node-to-node friction
// contacts at the coincident node pairs of the groove's contact face. Pairs on the right sector
// interface are the left pairs of the next sector and are dropped (each contact counted once).
// Cyclic symmetry: the excitation of engine order k has the pattern of nodal diameter h
// (k = +-h mod N, forced/cyclic_forced_response.hpp); harmonic n of the periodic response at
// w = k W carries the pattern of engine order n k, i.e. nodal diameter m = n k mod N (used
// directly for m <= N/2, as the conjugate pattern of N - m otherwise).
//
// Contact coordinates per pair, from the relative displacement d = x_ring - x_gear in the
// cylindrical frame of the pair's position (e_r outwards, e_theta = e_z x e_r, e_z the axis):
//   v = e_r . d (the ring pressed outwards onto the groove bottom: approach > 0),
//   2D contact:  u = cos(psi) e_theta . d + sin(psi) e_z . d  (psi the inclination of the ring's
//                slip direction from the circumferential one, thesis sec. 4.2),
//   3D contact:  u_1 = e_theta . d, u_2 = e_z . d.
// Law: hbm/friction_contact.hpp (normal load N = max(N_0 + k_n v, 0), Coulomb slip with elastic
// stick k_t, lift-off), with the centrifugal preload of the split ring shared by the contacts,
//   N_0(W) = m_ring W^2 r_G / (N n_pairs),
// m_ring the whole ring's mass, r_G the radius of its centre of mass (thesis sec. 4.3.1), and W
// the speed: the preload follows the speed along the curve (W = w / k).
//
// Linear structure: per harmonic the modal receptance of the sector at its nodal diameter
// (n_modes modes, modal damping zeta) plus the residual flexibility of the modes left out,
// computed once per nodal diameter from (K_m - sigma M_m)^{-1} at the small negative shift sigma
// of the eigen-solver (so a free ring's rigid-body modes are admitted); the mean (harmonic 0) is
// held at the preloaded equilibrium (hbm/condensed.hpp). Limits: mu -> infinity is the linear
// structure with the ring stuck by the contact springs; mu = 0 (or N_0 = 0 with k_n = 0) leaves
// the gear alone (its linear response: the ring is not excited).
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/hbm/condensed.hpp"
#include "geardyn/hbm/friction_contact.hpp"
#include "geardyn/response/cyclic_forced_response.hpp"

namespace geardyn::damper {

struct ContactPair {
  long gear_node = 0;
  long ring_node = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< of the gear node [m]
};

struct ContactPairing {
  std::vector<ContactPair> pairs;  ///< independent pairs (right-interface ones dropped)
  int dropped_on_right_interface = 0;
  double worst_gap = 0.0;  ///< largest distance between the nodes of a pair [m]
  long worst_gear_node = 0;
};

/// Pairs each gear contact node with the ring contact node at the same position (within
/// `tolerance` [m]); pairs whose gear node is a right-interface node of `interfaces` are dropped.
/// Throws InputError (key `key`) when the sets differ in size, a node has no DOFs, or a gear node
/// has no ring node within tolerance (the worst pair and its gap are named).
ContactPairing pair_contact_nodes(const std::vector<solid::DofInfo>& dofs,
                                  const std::vector<long>& gear_nodes,
                                  const std::vector<long>& ring_nodes,
                                  const cyclic::SectorInterfaces& interfaces, double tolerance,
                                  const std::string& key);

/// The sector interfaces of two bodies meshed together (gear and ring): each body's left nodes
/// paired with its own right nodes (the contact twins on the sector edges coincide, so one
/// nearest-node search over both bodies could pair a gear node with a ring node), merged. Nodes
/// without DOFs (e.g. the clamped bore) are skipped. Throws InputError as cyclic::find_interfaces.
cyclic::SectorInterfaces two_body_interfaces(const std::vector<solid::DofInfo>& dofs,
                                             const cyclic::InterfaceOptions& options,
                                             const std::vector<long>& gear_left,
                                             const std::vector<long>& gear_right,
                                             const std::vector<long>& ring_left,
                                             const std::vector<long>& ring_right);

struct ContactLaw {
  int tangential_directions = 1;      ///< 1: 2D contact (v, u); 2: 3D contact (v, u_theta, u_z)
  double inclination = 0.0;           ///< psi [rad] of the 2D contact's slip direction
  double normal_stiffness = 0.0;      ///< k_n per contact pair [N/m]
  double tangential_stiffness = 0.0;  ///< k_t per contact pair [N/m]
  double friction_coefficient = 0.0;  ///< mu
};

struct DamperRingProblem {
  Eigen::SparseMatrix<double> K, M;  ///< sector of gear and ring, rows in sector.dofs() order
  std::optional<cyclic::CyclicSector> sector;  ///< required
  std::vector<ContactPair> pairs;
  ContactLaw contact;
  double ring_mass = 0.0;    ///< whole ring [kg] (0: no centrifugal preload)
  double ring_radius = 0.0;  ///< r_G, radius of the ring's centre of mass [m]
  int nodal_diameter = 0;
  int engine_order = 1;
  /// The loads of engine order n k on harmonic n = 1, 2, ... at the excitation nodes of sector 0:
  /// loads[n - 1] (F_k, F_2k, ...). Fewer entries than harmonics: the higher harmonics are
  /// unloaded (they still carry the response the contacts generate).
  std::vector<std::vector<response::ToothLoad>> loads;
  std::vector<response::CyclicSensor> sensors;
  response::ModalDamping damping;
  int n_modes = 20;      ///< per nodal diameter
  int harmonics = 1;     ///< H
  int time_samples = 0;  ///< per period (0: hbm::default_time_samples(H))
};

/// The condensed model, built once: receptances per harmonic and the contact elements.
struct DamperRingModel {
  int n_sectors = 0;
  int nodal_diameter = 0;
  int engine_order = 1;
  ContactLaw contact;
  std::vector<ContactPair> pairs;
  int coordinates_per_pair = 2;
  double preload_per_speed_squared = 0.0;  ///< N_0 / W^2 = m_ring r_G / (N n_pairs) [kg m]
  hbm::HarmonicBasis basis{1, 64};
  std::vector<hbm::ModalReceptance> receptances;  ///< harmonic 0..H
  std::vector<int> harmonic_diameter;             ///< nodal diameter of each harmonic
  std::vector<bool> harmonic_conjugate;           ///< the conjugate pattern (N - m)
  std::vector<std::string> sensor_names;
  std::vector<std::string> notes;

  int coordinates() const { return coordinates_per_pair * static_cast<int>(pairs.size()); }
  /// N_0 at speed W [rad/s].
  double preload(double speed) const { return preload_per_speed_squared * speed * speed; }
  /// The harmonic-balance problem with the contacts' law (preload following the speed).
  hbm::CondensedHarmonicBalance system(const ContactLaw& law) const;
  /// Harmonic-1 sensor amplitudes of the linear structure at speed W: ring free (no contact
  /// forces) or stuck (the contacts as linear springs k_n, k_t; for many speeds use
  /// StuckRingResponse, which factors once).
  Eigen::VectorXcd free_response(double speed) const;
  Eigen::VectorXcd stuck_response(double speed) const;
};

/// The linear response with the ring stuck (the contacts as springs k_n, k_t), for many speeds:
/// (I + H(w) K_c) x = x_lin(w) with H = U F(w) V^H + R solved by Woodbury around the part that
/// does not depend on w, B = I + R K_c (factored once): x = y - P F (I + Q F)^-1 W y with
/// y = B^-1 x_lin, W = V^H K_c, P = B^-1 U, Q = W P. Per speed one solve with the LU of B and a
/// modes-sized system, instead of forming and factoring the coordinates-sized H.
class StuckRingResponse {
 public:
  explicit StuckRingResponse(const DamperRingModel& model);
  /// Harmonic-1 sensor amplitudes at speed W [rad/s].
  Eigen::VectorXcd operator()(double speed) const;

 private:
  const hbm::ModalReceptance* receptance_ = nullptr;
  double engine_order_ = 1.0;
  Eigen::VectorXd kc_;
  Eigen::PartialPivLU<Eigen::MatrixXcd> b_lu_;
  Eigen::MatrixXcd p_, q_, w_;
};

/// Throws InputError for inconsistent input (no pairs, h / k mismatch, bad damping, law values,
/// zero friction together with zero preload: contacts that transmit no friction force);
/// NumericalError when the modes of a nodal diameter cannot be computed.
DamperRingModel build_damper_ring_model(const DamperRingProblem& problem,
                                        Progress& progress = null_progress());

struct DamperRingOptions {
  double speed_min = 0.0;  ///< [rad/s]
  double speed_max = 0.0;
  int linear_points = 400;  ///< speeds of the linear (free / stuck) curves
  double max_step = 0.02;   ///< continuation step, relative to the speed range and amplitude
  double tolerance = 1e-9;
  std::vector<int> hysteresis_pairs;  ///< pair indices whose loops are kept at the peak
};

struct DampedPoint {
  double speed = 0.0;             ///< W [rad/s]
  Eigen::VectorXd amplitude;      ///< harmonic-1 amplitude per sensor [m]
  Eigen::MatrixXd harmonics;      ///< |z_n|, harmonic n = 1..H (rows) per sensor [m]
  Eigen::VectorXd peak;           ///< largest |x(t)| over the period per sensor [m]
  double energy_per_cycle = 0.0;  ///< dissipated by the whole ring per cycle of w [J]
  double stick = 0.0, slip = 0.0, lift_off = 0.0;  ///< fractions over pairs and samples
  int iterations = 0;
  bool loops_closed = true;
  /// Unstable by the fold count along the curve (hbm::fold_unstable: after an odd number of
  /// turning points in speed, the jump phenomenon's middle branch).
  bool fold_unstable = false;
};

struct HysteresisLoop {
  int pair = 0;
  Eigen::VectorXd slip;    ///< u over the period [m] (first tangential coordinate)
  Eigen::VectorXd force;   ///< T [N]
  Eigen::VectorXd normal;  ///< N [N]
};

struct DamperRingResult {
  Status status = Status::Ok;
  std::string message;
  std::vector<DampedPoint> damped;
  Eigen::VectorXd linear_speeds;
  Eigen::MatrixXd free_amplitude, stuck_amplitude;  ///< linear_speeds x sensors
  int peak_point = -1;                ///< index in `damped` of the largest sensor-0 amplitude
  std::vector<HysteresisLoop> loops;  ///< at the peak
  /// Per pair at the peak: stick, slip, lift-off fractions and energy per cycle.
  Eigen::MatrixXd pair_states;
  Eigen::VectorXd pair_energy;
  /// At the peak: the largest share over the pairs of the contact force beyond the balanced
  /// harmonics, ||F_{n > H}|| / ||F_{n >= 1}||, from the same motion marched with 3H + 2
  /// harmonics (the balance neglects it; above a few per cent raise the harmonics).
  double force_truncation = 0.0;
  int truncation_pair = -1;
  /// Speeds [rad/s] of the turning points of the damped curve (folds).
  std::vector<double> turning_points;
};

/// Traces the damped response over [speed_min, speed_max] by continuation and evaluates the
/// linear references. A continuation that stops early is returned with its status and message
/// (the points reached are kept).
DamperRingResult run_damper_ring(const DamperRingModel& model, const DamperRingOptions& options,
                                 Progress& progress = null_progress());

/// Mass and centre-of-mass radius of one body of a cyclic sector, from the mass matrix: the
/// x-translation row sums of the consistent mass, m_n = sum_j M(n_x, j_x) = integral rho N_n dV,
/// give mass = N sum m_n (the whole ring, N sectors) and r_G = sum m_n r_n / sum m_n (r_n the
/// node's distance from the z axis; exact for r interpolated by the shape functions, O(h^2 / r^2)
/// otherwise; a massless body gets its mean node radius). InputError (key `key`) when a node has
/// no x-translation DOF, there are no nodes, or the mass is negative.
struct BodyMass {
  double mass = 0.0;    ///< whole body (all sectors) [kg]
  double radius = 0.0;  ///< r_G [m]
};
BodyMass body_mass(const Eigen::SparseMatrix<double>& M, const std::vector<solid::DofInfo>& dofs,
                   const std::vector<long>& nodes, int n_sectors, const std::string& key);

/// Tangential / normal stiffness of an elastic contact of two bodies (Mindlin 1949; Johnson,
/// Contact Mechanics, 1985, sec. 7.2): k_t / k_n = 4 G* / E* with 1 / E* = (1 - nu_1^2) / E_1 +
/// (1 - nu_2^2) / E_2 and 1 / G* = (2 - nu_1) / G_1 + (2 - nu_2) / G_2, G = E / (2 (1 + nu));
/// 2 (1 - nu) / (2 - nu) for equal materials.
double mindlin_ratio(double E1, double nu1, double E2, double nu2);

}  // namespace geardyn::damper
