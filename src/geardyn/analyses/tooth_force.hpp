#pragma once
// The load on one tooth of a gear of a [[gear_pairs]] entry over one revolution, and the mesh
// force of the pair over one mesh cycle: the step shared by mesh_harmonics and the forced
// responses (docs/theory.md §11.2, §12).
//
// Tooth force: the dynamic (or infinite-inertia) mesh force at gear 1's speed, solved to its
// periodic steady state, tiled over one revolution of the chosen gear (N = its teeth mesh
// cycles), scaled to the tangential force of that gear, F_t(phi) = F_d(phi) F_t,static / F_s,
// and multiplied by the tooth-load window (gear/load_window.hpp). Sample 0 is the tooth
// entering contact (the STE cycle start); harmonics of the result are the engine-order
// harmonics F_k (one-sided amplitude, cosine phase) and 3D components follow from the member's
// radial / tangential and axial / tangential ratios.
//
// Mesh force harmonics: order p of the mesh frequency of the infinite-inertia mesh force
// F_d(t) = F_s k(t) / k_mean over one mesh cycle. This is the blocked force of the transmission
// error, k_mean e_p to first order in the stiffness variation (e = F_s / k): the excitation of a
// linear rotor model that carries the mean mesh stiffness itself
// (response/rotor_mesh_response.hpp).
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/gear/dynamic_mesh.hpp"
#include "geardyn/gear/load_window.hpp"
#include "geardyn/gear/tooth_forces.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

struct ToothForceOptions {
  int gear = 1;        ///< 1 or 2: the gear whose tooth is loaded
  double speed = 0.0;  ///< speed of gear 1 [rad/s], > 0
  MeshForceModel model = MeshForceModel::Dynamic;
  bool contact_loss = true;
  double window_shift = 0.0;           ///< [tooth pitches of that gear]
  double contact_ratio = model::kNaN;  ///< window contact ratio (NaN: the total contact ratio)
};

struct ToothForceRevolution {
  int teeth = 0;                   ///< N of the chosen gear
  double mesh_frequency_hz = 0.0;  ///< z1 W1 / 2 pi
  gear::MeshResponse mesh;         ///< the steady state of the mesh model
  Eigen::VectorXd mesh_force;      ///< F_d over one revolution of the gear [N]
  Eigen::VectorXd tangential;      ///< its tangential share on that gear [N]
  Eigen::VectorXd window;          ///< tooth-load window samples
  Eigen::VectorXd tooth;           ///< filtered tangential tooth force [N]
  double contact_ratio = 0.0;      ///< window contact ratio used
  double shift_rad = 0.0;          ///< window shift [rad]
  gear::ToothForces member;        ///< static forces on that gear
  gear::Flank flank = gear::Flank::Concave;
  gear::ForceDirections directions;  ///< radial and axial per tangential of that gear

  /// Engine-order harmonics in 3D components (tooth_forces.hpp signs) for orders `orders`,
  /// each tagged with nodal diameter h = min(k mod N, N - k mod N).
  std::vector<gear::HarmonicComponents> components(const std::vector<int>& orders) const;
};

/// Throws NumericalError (naming `analysis`) when the mesh model has no periodic steady state or
/// its period does not divide N; InputError for a bad window.
ToothForceRevolution tooth_force_over_revolution(const PairModel& pm, const ToothForceOptions& o,
                                                 const std::string& analysis);

/// Complex amplitudes F_p [N] (one-sided, cosine phase at the cycle start) of the
/// infinite-inertia mesh force at mesh orders 1 .. max_order (see the file comment). Throws
/// InputError when max_order exceeds half the samples per mesh cycle.
std::vector<std::complex<double>> blocked_mesh_force_harmonics(const PairModel& pm, int max_order);

}  // namespace geardyn::analyses
