#pragma once
// damper_ring_response: the friction-damped forced response of a cyclic gear with a damper ring
// in a groove of its rim, wired to the model file (issue [friction-hbm] sections 3, 4 and 7;
// DESIGN 4.6-4.7; the damper-ring thesis, /work/shared/references/000, ch. 4 and sec. 5.3).
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
// the optimum marked). Bad input throws InputError with the analysis' key path; a continuation
// that stops early returns the points reached with status Failed and its message.
#include <string>

#include "geardyn/component/solid_component.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::forcedan {

AnalysisOutput run_damper_ring_response(const model::Model& model,
                                        const component::SolidComponent& solid,
                                        const model::DamperRingResponseSettings& settings,
                                        const std::string& name,
                                        Progress& progress = null_progress());

/// What the parser cannot check for one damper_ring_response: the node and element sets exist,
/// the contact nodes pair up, the ring has a mass, hysteresis_pairs name existing pairs. Throws
/// InputError with the analysis' key path.
void check_damper_ring_response(const model::Model& model, const component::SolidComponent& solid,
                                const model::DamperRingResponseSettings& settings,
                                const std::string& name);

}  // namespace geardyn::forcedan
