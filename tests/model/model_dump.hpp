#pragma once
// Text dump of every value of a Model (not the source locations), for comparing two models.
#include <fmt/format.h>

#include <string>
#include <variant>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/correlation.hpp"
#include "geardyn/analyses/cyclic_forced_response.hpp"
#include "geardyn/analyses/cyclic_modal.hpp"
#include "geardyn/analyses/damper_ring_response.hpp"
#include "geardyn/analyses/gear_forced_response.hpp"
#include "geardyn/analyses/gear_pair.hpp"
#include "geardyn/analyses/harmonic.hpp"
#include "geardyn/analyses/mesh_force.hpp"
#include "geardyn/analyses/mesh_harmonics.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/reduction.hpp"
#include "geardyn/analyses/solid_modal.hpp"
#include "geardyn/analyses/sweep.hpp"
#include "geardyn/analyses/transient.hpp"
#include "geardyn/analyses/unbalance.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::model::test {

using namespace ::geardyn::analyses;  // NOLINT: the settings types of every analysis

/// Calls f with the analysis's settings as their own type (most derived first).
template <class F>
void visit_settings(F&& f, const Analysis& a) {
  if (const auto* s = a.settings_as<analyses::DamperRingResponseSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::ModalSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::CampbellSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::HarmonicSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::UnbalanceSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::TransientSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::SweepSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::SolidModalSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::CyclicModalSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::ReductionSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::GearPairSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::MeshForceSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::MeshHarmonicsSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::CorrelationSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::CyclicForcedResponseSettings>()) return f(*s);
  if (const auto* s = a.settings_as<analyses::GearForcedResponseSettings>()) return f(*s);
}

inline std::string num(double x) { return fmt::format("{:.17g}", x); }

template <class Range>
std::string nums(const Range& r) {
  std::string out = "[";
  for (const auto& x : r) out += num(static_cast<double>(x)) + ",";
  return out + "]";
}

inline std::string strs(const std::vector<std::string>& r) {
  std::string out = "[";
  for (const auto& x : r) out += x + ",";
  return out + "]";
}

inline std::string dump(const Model& m) {
  std::string o = fmt::format("version={} title={}\n", m.version, m.title);
  for (const auto& x : m.materials)
    o += fmt::format("material {} E={} G={} rho={}\n", x.name, num(x.youngs_modulus),
                     num(x.shear_modulus), num(x.density));
  for (const auto& s : m.shafts) {
    o += fmt::format(
        "shaft {} mat={} origin={} axis={} ratio={} driven_by={} gear_ratio={} "
        "kappa={} theory={} rotary={} gyro={}\n",
        s.name, s.material, nums(s.origin), nums(s.axis), num(s.speed_ratio), s.driven_by,
        num(s.gear_ratio), num(s.shear_coefficient), static_cast<int>(s.theory), s.rotary_inertia,
        s.gyroscopic);
    for (const auto& e : s.elements)
      o += fmt::format("  element L={} do={} di={} mat={} eta={} div={}\n", num(e.length),
                       num(e.outer_diameter), num(e.inner_diameter), e.material, num(e.loss_factor),
                       e.divisions);
  }
  for (const auto& n : m.nodes)
    o += fmt::format("node {} pos={} axis={} spin_of={} ratio={}\n", n.name, nums(n.position),
                     nums(n.axis), n.spin_of, num(n.speed_ratio));
  for (const auto& d : m.disks)
    o += fmt::format("disk {} node={} m={} Ip={} Id={} do={} di={} h={} mat={}\n", d.name, d.node,
                     num(d.mass), num(d.polar_inertia), num(d.diametral_inertia),
                     num(d.outer_diameter), num(d.inner_diameter), num(d.thickness), d.material);
  for (const auto& p : m.point_masses)
    o += fmt::format("point_mass {} node={} m={}\n", p.name, p.node, num(p.mass));
  for (const auto& b : m.bearings) {
    o += fmt::format("bearing {} node={} node2={} speeds={}\n", b.name, b.node, b.node2,
                     nums(b.speeds));
    for (const auto& k : b.stiffness) o += "  K " + nums(k) + "\n";
    for (const auto& c : b.damping) o += "  C " + nums(c) + "\n";
  }
  for (const auto& c : m.couplings)
    o += fmt::format("coupling {} {} {} K={} C={} M={}\n", c.name, c.node1, c.node2,
                     nums(c.stiffness), nums(c.damping), nums(c.mass));
  for (const auto& g : m.gear_meshes)
    o += fmt::format(
        "mesh {} {} {} type={} z={}/{} rb={}/{} alpha={} beta={} delta={}/{} hand={} "
        "flank={} k={} c={} dir={}\n",
        g.name, g.gear1, g.gear2, static_cast<int>(g.type), g.teeth1, g.teeth2, num(g.base_radius1),
        num(g.base_radius2), num(g.pressure_angle), num(g.helix_angle), num(g.pitch_cone_angle1),
        num(g.pitch_cone_angle2), static_cast<int>(g.hand), static_cast<int>(g.flank),
        num(g.stiffness), num(g.damping), g.mesh_direction ? nums(*g.mesh_direction) : "-");
  for (const auto& c : m.constraints) {
    o += fmt::format("constraint {}", c.node);
    for (auto d : c.dofs) o += fmt::format(" {}", static_cast<int>(d));
    o += "\n";
  }
  for (const auto& u : m.unbalances)
    o += fmt::format("unbalance {} {} me={} phase={}\n", u.name, u.node, num(u.mass_eccentricity),
                     num(u.phase));
  for (const auto& f : m.forces)
    o += fmt::format("force {} {} dof={} F={} phase={}\n", f.name, f.node, static_cast<int>(f.dof),
                     num(f.amplitude), num(f.phase));
  for (const auto& s : m.sensors)
    o += fmt::format("sensor {} {} dof={}\n", s.name, s.node, static_cast<int>(s.dof));
  const auto& d = m.damping;
  o += fmt::format("damping a={} b={} eta={} zeta={} ratios={} modes={}\n", num(d.rayleigh_alpha),
                   num(d.rayleigh_beta), num(d.loss_factor), num(d.modal_ratio),
                   nums(d.modal_ratios), d.modal_modes);
  for (const auto& b : d.bands)
    o += fmt::format("  band {} {} {}\n", num(b.f_min), num(b.f_max), num(b.ratio));
  for (const auto& a : m.analyses) {
    o += fmt::format("analysis {} type={} enabled={}: ", a.name, a.type, a.enabled);
    visit_settings(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<S, ModalSettings>)
            o += fmt::format("speed={} n={} complex={} method={} shift={}", num(s.speed), s.n_modes,
                             s.complex_modes, static_cast<int>(s.method), num(s.shift));
          if constexpr (std::is_same_v<S, CampbellSettings>)
            o += fmt::format("speeds={} n={} eo={} so={} mo={} mac={} method={}", nums(s.speeds),
                             s.n_modes, nums(s.engine_orders), s.shaft_orders, s.mesh_orders,
                             num(s.mac_threshold), static_cast<int>(s.method));
          if constexpr (std::is_same_v<S, HarmonicSettings>)
            o += fmt::format(
                "speed={} f={}..{} n={} spacing={} adaptive={} in={}:{} forces={} "
                "sensors={} q={}",
                num(s.speed), num(s.f_min), num(s.f_max), s.n_points, static_cast<int>(s.spacing),
                s.adaptive, s.input_node, static_cast<int>(s.input_dof), strs(s.forces),
                strs(s.sensors), static_cast<int>(s.quantity));
          if constexpr (std::is_same_v<S, UnbalanceSettings>)
            o += fmt::format("speeds={} unb={} sensors={}", nums(s.speeds), strs(s.unbalances),
                             strs(s.sensors));
          if constexpr (std::is_same_v<S, TransientSettings>)
            o += fmt::format(
                "speed={}..{} T={} dt={} int={} rho={} steady={} unb={} sensors={} "
                "every={}",
                num(s.speed), num(s.speed_end), num(s.duration), num(s.time_step),
                static_cast<int>(s.integrator), num(s.rho_infinity), num(s.steady_fraction),
                strs(s.unbalances), strs(s.sensors), s.output_every);
          if constexpr (std::is_same_v<S, SweepSettings>) {
            o += fmt::format("param={} values={} analysis={} log={} threads={}", s.parameter,
                             nums(s.values), s.analysis, s.log_x, s.threads);
            for (const auto& out : s.outputs)
              o += fmt::format(" | q={} mode={} sensor={} at={} label={}", out.quantity, out.mode,
                               out.sensor, num(out.at), out.label);
          }
        },
        a);
    o += "\n";
  }
  return o;
}

}  // namespace geardyn::model::test
