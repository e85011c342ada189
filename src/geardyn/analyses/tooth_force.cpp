#include "geardyn/analyses/tooth_force.hpp"

#include <fmt/format.h>

#include <cmath>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::analyses {

namespace {

constexpr double kTwoPi = units::kTwoPi;

std::string rpm_text(double omega) { return fmt::format("{:.6g} rpm", omega * 60.0 / kTwoPi); }

}  // namespace

std::vector<gear::HarmonicComponents> ToothForceRevolution::components(
    const std::vector<int>& orders) const {
  std::vector<gear::HarmonicComponents> out;
  for (const gear::EngineOrderHarmonic& e : gear::engine_order_harmonics(tooth, orders)) {
    gear::HarmonicComponents c;
    const int r = e.order % teeth;
    c.nodal_diameter = std::min(r, teeth - r);
    c.order = e.order;
    c.tangential = std::polar(e.amplitude, e.phase_rad);
    c.radial = directions.radial_per_tangential * c.tangential;
    c.axial = directions.axial_per_tangential * c.tangential;
    out.push_back(c);
  }
  return out;
}

ToothForceRevolution tooth_force_over_revolution(const PairModel& pm, const ToothForceOptions& o,
                                                 const std::string& analysis) {
  ToothForceRevolution r;
  const int z1 = pm.pair->teeth1;
  r.teeth = o.gear == 1 ? pm.pair->teeth1 : pm.pair->teeth2;
  const gear::DynamicMesh mesh(*pm.ste, pm.mesh_options(o.model, o.contact_loss));
  r.mesh_frequency_hz = z1 * o.speed / kTwoPi;
  r.mesh = mesh.solve(r.mesh_frequency_hz);
  const gear::MeshResponse& d = r.mesh;
  if (d.status != Status::Ok)
    throw NumericalError(
        analysis,
        fmt::format("no periodic steady state of the mesh at gear 1 speed {} (f_m = {:.6g} "
                    "Hz): {}; {}. What usually helps: more mesh damping, or model = "
                    "\"infinite_inertia\" far below the mesh resonance.",
                    rpm_text(o.speed), r.mesh_frequency_hz, to_string(d.status), d.message));
  const int period = d.period_cycles;
  if (r.teeth % period != 0)
    throw NumericalError(
        analysis,
        fmt::format("the steady state at {} repeats every {} mesh cycles, which does not "
                    "divide the {} teeth of gear {}: the tooth force is not periodic over "
                    "one revolution, so its engine orders are not defined. Choose another "
                    "speed or more mesh damping.",
                    rpm_text(o.speed), period, r.teeth, o.gear));

  // One revolution of the chosen gear is `teeth` mesh cycles; sample 0 is a tooth entering
  // contact (the STE cycle start), which is also where the tooth-load window starts.
  const std::size_t per_record = d.force_n.size();
  const std::size_t per_cycle = per_record / static_cast<std::size_t>(period);
  const std::size_t n = per_cycle * static_cast<std::size_t>(r.teeth);
  r.member = o.gear == 1 ? pm.drive_forces.pinion : pm.drive_forces.wheel;
  r.flank = o.gear == 1 ? pm.drive_forces.pinion_flank : pm.drive_forces.wheel_flank;
  // The tangential tooth force follows the mesh force: F_t(phi) = F_d(phi) F_t,static / F_s.
  const double tangential_per_mesh = r.member.tangential_n / pm.static_force_n;
  r.mesh_force.resize(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i)
    r.mesh_force[static_cast<Eigen::Index>(i)] = d.force_n[i % per_record];
  r.tangential = r.mesh_force * tangential_per_mesh;

  r.contact_ratio = std::isnan(o.contact_ratio) ? pm.geometry.total_contact_ratio : o.contact_ratio;
  r.shift_rad = o.window_shift * kTwoPi / r.teeth;
  r.tooth = gear::filtered_tooth_force(r.tangential, r.teeth, r.contact_ratio, r.shift_rad);
  r.window =
      gear::tooth_load_window_samples(static_cast<int>(n), r.teeth, r.contact_ratio, r.shift_rad);
  r.directions = gear::ForceDirections{o.gear == 1 ? pm.drive_forces.pinion_radial_per_tangential
                                                   : pm.drive_forces.wheel_radial_per_tangential,
                                       o.gear == 1 ? pm.drive_forces.pinion_axial_per_tangential
                                                   : pm.drive_forces.wheel_axial_per_tangential};
  return r;
}

std::vector<std::complex<double>> blocked_mesh_force_harmonics(const PairModel& pm, int max_order) {
  // The algebraic model has no dynamics: any mesh frequency gives the same F_s k(t) / k_mean.
  const gear::DynamicMesh mesh(*pm.ste, pm.mesh_options(MeshForceModel::InfiniteInertia, false));
  const gear::MeshResponse d = mesh.solve(1.0);
  const std::size_t per_cycle = d.force_n.size() / static_cast<std::size_t>(d.period_cycles);
  Eigen::VectorXd force(static_cast<Eigen::Index>(per_cycle));
  for (std::size_t i = 0; i < per_cycle; ++i) force[static_cast<Eigen::Index>(i)] = d.force_n[i];
  std::vector<int> orders;
  for (int p = 1; p <= max_order; ++p) orders.push_back(p);
  std::vector<std::complex<double>> out;
  for (const gear::EngineOrderHarmonic& e : gear::engine_order_harmonics(force, orders))
    out.push_back(std::polar(e.amplitude, e.phase_rad));
  return out;
}

}  // namespace geardyn::analyses
