#pragma once
// Forced responses to gear-mesh excitation, wired to the model file (issue [mesh-excitation]
// sections 6 and 7; DESIGN 4.3-4.5): (model, settings) -> AnalysisOutput with tables, plots and
// notes. Bad input throws InputError (call check_forced_analyses before running, so it shows
// before any result); a numerical failure throws NumericalError naming the analysis.
//
//   cyclic_forced_response  one sector of a cyclic solid (a gear, one tooth per sector when a
//       gear pair loads it) in the frame turning with it. Per nodal diameter h the modes are
//       solved once (cyclic::solve_cyclic_modes, optionally on a Craig-Bampton sector whose
//       masters are the interfaces, the excitation and the sensor nodes); every engine order k
//       with k = +-h (mod N) is then a modal sum per speed (forced::run_cyclic_forced_response):
//       u_0(W) = sum_r psi_r (psi_r^H f_0) / (w_r^2 - (k W)^2 + 2 i zeta w_r k W).
//       The tooth-force harmonics F_k come from a [[gear_pairs]] entry exactly as mesh_harmonics
//       computes them (gearan::tooth_force_over_revolution: dynamic mesh force at one speed,
//       tooth-load window, order spectrum, 3D split), or are given (force_amplitude).
//       Load directions at an excitation node x of sector 0 (unit vectors e_r = radial outwards,
//       e_theta = z x e_r): tangential -e_theta (the load presses the flank facing +theta, where
//       meshgen::gear_sector puts its "excitation" node), radial -e_r (positive radial force
//       pushes the tooth towards its axis, gear/tooth_forces.hpp), axial +z when the pitch-cone
//       apex is on the -z side (positive axial force points away from the apex). The load is
//       shared equally by the nodes of the excitation set.
//       Optional measured curve over speed (gear::read_measured_response_csv, displacement):
//       peak speed, amplitude and Q compared, and the force scaling that matches the peak.
//   gear_forced_response  a rotor with a [[gear_meshes]] entry, excited along the line of action
//       at mesh orders p = 1 .. n with amplitudes F_p (forced::run_mesh_forced_response, modal
//       basis of n_modes modes at zero speed plus the static residual vector). F_p is the
//       blocked mesh force of a [[gear_pairs]] entry (gearan::blocked_mesh_force_harmonics:
//       F_s k(t) / k_mean, harmonic p, = k_mean e_p to first order) or given (force_amplitude).
#include <string>

#include "geardyn/component/solid_component.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::forcedan {

AnalysisOutput run_cyclic_forced_response(const model::Model& model,
                                          const component::SolidComponent& solid,
                                          const model::CyclicForcedResponseSettings& settings,
                                          const std::string& name,
                                          Progress& progress = null_progress());

AnalysisOutput run_gear_forced_response(const model::Model& model, const fe::LinearSystem& system,
                                        const model::GearForcedResponseSettings& settings,
                                        const std::string& name,
                                        Progress& progress = null_progress());

/// What the parser cannot check: the node sets and node ids the cyclic forced responses name
/// exist in the built meshes (and carry DOFs), their solids are meshes (not reduced files), the
/// gear pairs build, and the measured files read and hold a displacement over speed. Throws
/// InputError with the analysis' key path.
void check_forced_analyses(const model::Model& model, const component::SolidComponents& solids);

}  // namespace geardyn::forcedan
