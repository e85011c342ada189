#pragma once
// Parts the forced responses of a cyclic sector share (cyclic_forced_response and
// damper_ring_response): the excitation and sensor points of the sector, the tooth-load frame, the
// tooth-force harmonics of a gear pair and the loads they put on the excitation nodes, and the
// amplitude-over-speed plots.
#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/cyclic_forced_response.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/reduce/craig_bampton.hpp"
#include "geardyn/response/cyclic_forced_response.hpp"

namespace geardyn::analyses {

/// The names of the node sets of a mesh, quoted, for messages.
std::string set_list(const solid::Mesh& mesh);

/// The excitation and sensor points of the sector.
struct SectorPoints {
  std::vector<int> excitation;  ///< node indices of the excitation set
  std::vector<response::CyclicSensor> sensors;
  std::vector<int> sensor_nodes;  ///< node index of each sensor point
};
/// Reads them from the mesh of `c` (sets and ids of `s`); InputError located by `context` for a
/// missing set or node, fixed excitation or sensor components, or a solid without a mesh.
SectorPoints sector_points(const Context& context, const assembly::SolidComponent& c,
                           const CyclicForcedResponseSettings& s);

/// The sector matrices a forced response solves: the assembled mesh, or its Craig-Bampton
/// reduction (s.reduction) with `masters` (node ids) and the nodes of s.master_sets with DOFs as
/// physical masters and s.cb_modes fixed-interface modes. The masters keep their node ids, so
/// loads and sensors at them are found in `dofs` as in the mesh.
struct SolvedSector {
  std::vector<solid::DofInfo> dofs;
  Eigen::SparseMatrix<double> K, M;
  std::optional<reduce::ReducedComponent> cb;  ///< set when reduced
  std::string note;                            ///< what the reduction kept (empty: none)
};
/// `masters_are` names the masters for the note, e.g. "interfaces, excitation and sensor nodes".
/// `mass`: the sector's mass matrix if not c.mass() (e.g. with a body's mass scaled).
SolvedSector solved_sector(const assembly::SolidComponent& c, const CyclicForcedResponseSettings& s,
                           std::vector<long> masters, const std::string& masters_are,
                           const Context& context,
                           const Eigen::SparseMatrix<double>* mass = nullptr);

/// Unit vectors of the tooth load at node x (forced_analyses.hpp: tangential -e_theta, radial
/// -e_r, axial +z with the pitch-cone apex below).
struct LoadFrame {
  Eigen::Vector3d tangential, radial, axial;
};
LoadFrame load_frame(const Eigen::Vector3d& x, bool apex_below);

/// One excited (h, k) with its harmonic in tooth-force components.
using OrderForce = CyclicOrderForce;

/// Fills the tangential, radial and axial harmonics of every order from the gear pair s.pair,
/// exactly as mesh_harmonics computes them; returns the note that says how. InputError at
/// `orders_key` (the key naming the orders) when an order is too high for the samples of one
/// revolution.
std::string tooth_force_harmonics(const model::Model& model, const Context& context,
                                  const CyclicForcedResponseSettings& s,
                                  std::vector<OrderForce>& orders, const std::string& orders_key);

/// The loads of one order on the excitation nodes of sector 0 (shared equally), times `scale`:
/// the pair's components in the load frame, or force_amplitude along force_direction or the
/// tangential direction.
std::vector<response::ToothLoad> order_loads(const assembly::SolidComponent& c,
                                             const SectorPoints& points,
                                             const CyclicForcedResponseSettings& s,
                                             const OrderForce& f, double scale);

/// An amplitude-over-speed plot (log amplitude) and one curve of it (zeros floored for the log
/// axis).
Plot amplitude_plot(std::string plot_name, std::string title);
Trace curve(std::string trace_name, const std::vector<double>& x, std::vector<double> y,
            std::string dash = {});

}  // namespace geardyn::analyses
