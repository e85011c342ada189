// GCC 12 -Wnull-dereference false positives in Eigen's complex kernels (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "geardyn/analyses/damper_ring_response.hpp"
#include "geardyn/analyses/sector_excitation.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/damper/damper_ring.hpp"
#include "geardyn/hbm/harmonic_basis.hpp"
#include "geardyn/response/speed_peaks.hpp"

namespace geardyn::analyses {

namespace {

constexpr double kRpm = 60.0 / units::kTwoPi;  // rpm per rad/s
constexpr double kDeg = 180.0 / units::kPi;
/// Above this share of the contact force beyond the balanced harmonics the balance is flagged.
/// Stick-slip forces carry large higher harmonics (a Coulomb square wave: 44 %) which the
/// structure filters away from resonance, so the share is a warning only when the force is
/// dominated by them; the response's own convergence is checked by raising harmonics (the
/// damper-ring example: H = 1 to 3 moves the peak by 0.1 % with a 31 % force share).
constexpr double kTruncationWarning = 0.5;

/// Everything the model file and the mesh determine before any solve.
struct DamperSetup {
  SectorPoints points;
  std::vector<solid::DofInfo> dofs;
  cyclic::SectorInterfaces interfaces;
  /// Node ids of the sector faces: gear left, gear right, ring left, ring right.
  std::vector<long> faces[4];
  damper::ContactPairing pairing;
  std::vector<long> ring_ids;
  damper::BodyMass ring;
  damper::ContactLaw law;
  std::vector<std::string> notes;
};

std::vector<long> ids_of(const solid::Mesh& mesh, const std::vector<int>& nodes) {
  std::vector<long> out;
  out.reserve(nodes.size());
  for (int n : nodes) out.push_back(mesh.node_ids[static_cast<std::size_t>(n)]);
  return out;
}

/// The contact law per pair: k_n given or from the contact stiffness per area, k_t given or by
/// Mindlin's ratio of the two materials (notes into d.notes).
damper::ContactLaw contact_law(const Context& context, const assembly::SolidComponent& c,
                               const DamperRingResponseSettings& s, DamperSetup& d,
                               const solid::Material& gear_material,
                               const solid::Material& ring_material) {
  const solid::Mesh& mesh = c.mesh;
  const int n_pairs = static_cast<int>(d.pairing.pairs.size());
  damper::ContactLaw law;
  law.tangential_directions = s.contact_directions;
  law.inclination = s.ring_inclination;
  law.friction_coefficient = s.friction_coefficient;
  if (!std::isnan(s.normal_stiffness)) {
    law.normal_stiffness = s.normal_stiffness;
  } else {
    double r_c = 0.0, z_lo = 1e300, z_hi = -1e300;
    for (const auto& p : d.pairing.pairs) r_c += std::hypot(p.position.x(), p.position.y());
    r_c /= n_pairs;
    for (int n : mesh.node_sets.at(s.ring_contact_set)) {
      z_lo = std::min(z_lo, mesh.coords[static_cast<std::size_t>(n)].z());
      z_hi = std::max(z_hi, mesh.coords[static_cast<std::size_t>(n)].z());
    }
    const double area = units::kTwoPi * r_c * (z_hi - z_lo) / c.sectors;
    if (!(area > 0.0))
      throw context.error("contact_stiffness",
                          "a contact face with an axial width (its area sets k_n per pair)",
                          fmt::format("a face of width {} m", z_hi - z_lo),
                          "give normal_stiffness per pair instead");
    law.normal_stiffness = s.contact_stiffness * area / n_pairs;
    d.notes.push_back(fmt::format(
        "Normal contact stiffness from contact_stiffness {:.4g} N/m^3 x the contact face of a "
        "sector, 2 pi r_c w / N = {:.4g} m^2 (r_c {:.5g} m, w {:.4g} m), shared by {} pairs: "
        "k_n = {:.4g} N/m per pair.",
        s.contact_stiffness, area, r_c, z_hi - z_lo, n_pairs, law.normal_stiffness));
  }
  if (!std::isnan(s.tangential_stiffness)) {
    law.tangential_stiffness = s.tangential_stiffness;
  } else {
    const double ratio =
        damper::mindlin_ratio(gear_material.E, gear_material.nu, ring_material.E, ring_material.nu);
    law.tangential_stiffness = ratio * law.normal_stiffness;
    d.notes.push_back(fmt::format(
        "Tangential contact stiffness by Mindlin's ratio of the gear ({}) and ring ({}) "
        "materials: k_t = {:.4f} k_n = {:.4g} N/m per pair.",
        gear_material.name, ring_material.name, ratio, law.tangential_stiffness));
  }
  if (!(law.tangential_stiffness > 0.0))
    throw context.error(
        "tangential_stiffness",
        "a positive tangential stiffness (k_t > 0: the elastic stick of the contact)",
        fmt::format("{} N/m", law.tangential_stiffness),
        "give tangential_stiffness, or a positive normal stiffness");
  return law;
}

DamperSetup damper_setup(const Context& context, const assembly::SolidComponent& c,
                         const DamperRingResponseSettings& s) {
  DamperSetup d;
  d.points = sector_points(context, c, s);  // also: the solid has a mesh
  const solid::Mesh& mesh = c.mesh;
  auto node_set = [&](const std::string& set, const std::string& key) -> const std::vector<int>& {
    const auto it = mesh.node_sets.find(set);
    if (it == mesh.node_sets.end() || it->second.empty())
      throw context.error(
          key, fmt::format("a non-empty node set of solid '{}' ({})", c.name, set_list(mesh)),
          fmt::format("\"{}\"", set),
          key == "solid" ? "generate the solid as a gear_sector with groove = true, "
                           "or give its mesh the sets left, right, ring_left and "
                           "ring_right (the sector faces of gear and ring)"
                         : std::string());
    return it->second;
  };
  const std::vector<long> gear_contact =
      ids_of(mesh, node_set(s.gear_contact_set, "gear_contact_set"));
  const std::vector<long> ring_contact =
      ids_of(mesh, node_set(s.ring_contact_set, "ring_contact_set"));
  d.dofs = c.dofs();
  cyclic::InterfaceOptions io;
  io.n_sectors = c.sectors;
  io.tolerance = c.interface_tolerance;
  try {
    const char* face_sets[4] = {"left", "right", "ring_left", "ring_right"};
    for (int f = 0; f < 4; ++f) d.faces[f] = ids_of(mesh, node_set(face_sets[f], "solid"));
    d.interfaces =
        damper::two_body_interfaces(d.dofs, io, d.faces[0], d.faces[1], d.faces[2], d.faces[3]);
    d.pairing = damper::pair_contact_nodes(d.dofs, gear_contact, ring_contact, d.interfaces,
                                           c.interface_tolerance, "ring_contact_set");
  } catch (const InputError& e) {
    if (e.where().line > 0) throw;
    throw context.error(e.key_path() == "ring_contact_set" ? "ring_contact_set" : "solid",
                        e.expected(), e.found(), e.hint());
  }
  const int n_pairs = static_cast<int>(d.pairing.pairs.size());
  for (std::size_t i = 0; i < s.hysteresis_pairs.size(); ++i)
    if (s.hysteresis_pairs[i] >= n_pairs)
      throw context.error(fmt::format("hysteresis_pairs[{}]", i),
                          fmt::format("a contact pair index 0 .. {}", n_pairs - 1),
                          std::to_string(s.hysteresis_pairs[i]));

  // The ring: its nodes, mass and centre-of-mass radius; the materials in contact.
  const auto es = mesh.element_sets.find(s.ring_element_set);
  if (es == mesh.element_sets.end() || es->second.empty())
    throw context.error("ring_element_set",
                        fmt::format("a non-empty element set of solid '{}'", c.name),
                        fmt::format("\"{}\"", s.ring_element_set));
  std::set<int> ring_nodes;
  std::set<int> ring_elements(es->second.begin(), es->second.end());
  for (int e : es->second)
    for (int n : mesh.elements[static_cast<std::size_t>(e)].nodes) ring_nodes.insert(n);
  d.ring_ids = ids_of(mesh, std::vector<int>(ring_nodes.begin(), ring_nodes.end()));
  try {
    d.ring = damper::body_mass(c.mass(), d.dofs, d.ring_ids, c.sectors, "ring_element_set");
  } catch (const InputError& e) {
    throw context.error("ring_element_set", e.expected(), e.found());
  }
  const solid::Material& ring_material =
      mesh.materials[static_cast<std::size_t>(mesh.elements[*ring_elements.begin()].material)];
  const solid::Material* gear_material = nullptr;
  for (std::size_t e = 0; e < mesh.elements.size() && gear_material == nullptr; ++e)
    if (!ring_elements.count(static_cast<int>(e)))
      gear_material = &mesh.materials[static_cast<std::size_t>(mesh.elements[e].material)];
  if (gear_material == nullptr)
    throw context.error("ring_element_set", "a ring that is part of the mesh, not all of it",
                        "every element");

  if (s.friction_coefficient == 0.0 && d.ring.mass == 0.0)
    throw context.error("friction_coefficient",
                        "friction or a centrifugal preload (zero friction together with zero "
                        "preload transmits no friction force: the ring cannot damp)",
                        "friction_coefficient = 0 and a massless ring",
                        "give the ring its density and the contact its friction coefficient");

  d.law = contact_law(context, c, s, d, *gear_material, ring_material);
  return d;
}

/// The loads of harmonic n = 1..L (engine order n k) at the excitation nodes.
std::vector<std::vector<response::ToothLoad>> harmonic_loads(
    const model::Model& model, const Context& context, const assembly::SolidComponent& c,
    const DamperRingResponseSettings& s, const SectorPoints& points,
    std::vector<OrderForce>& orders, std::string& note) {
  const int N = c.sectors;
  const int loaded = s.pair.empty() ? static_cast<int>(s.force_amplitude.size()) : s.harmonics;
  for (int n = 1; n <= loaded; ++n) {
    OrderForce f;
    f.engine_order = n * s.engine_order;
    const int r = f.engine_order % N;
    f.nodal_diameter = std::min(r, N - r);
    f.amplitude =
        s.pair.empty() ? s.force_amplitude[static_cast<std::size_t>(n - 1)] : response::kNaN;
    orders.push_back(f);
  }
  note =
      !s.pair.empty()
          ? tooth_force_harmonics(model, context, s, orders, "engine_order")
          : fmt::format("Harmonic forces given (force_amplitude) on harmonics 1 .. {}, {}.", loaded,
                        s.force_direction ? "along force_direction" : "tangential (-e_theta)");
  std::vector<std::vector<response::ToothLoad>> loads;
  for (const auto& f : orders) loads.push_back(order_loads(c, points, s, f, 1.0));
  return loads;
}

/// The largest resonance peak of one curve (speeds increasing): its speed, amplitude and Q; a
/// curve that is not monotonic in speed (a turning point) gets its largest sample, Q NaN.
response::SpeedPeak main_peak(const std::vector<double>& speeds, const std::vector<double>& a) {
  response::SpeedPeak best;
  bool increasing = speeds.size() >= 3;
  for (std::size_t i = 1; i < speeds.size(); ++i)
    increasing = increasing && speeds[i] > speeds[i - 1];
  if (increasing) {
    response::PeakOptions o;
    o.min_prominence_db = 0.5;
    const auto peaks = response::find_speed_peaks(
        Eigen::Map<const Eigen::VectorXd>(speeds.data(), static_cast<Eigen::Index>(speeds.size())),
        Eigen::Map<const Eigen::VectorXd>(a.data(), static_cast<Eigen::Index>(a.size())), 0, 0, o);
    for (const auto& p : peaks)
      if (std::isnan(best.amplitude) || p.amplitude > best.amplitude) best = p;
    if (!std::isnan(best.amplitude)) return best;
  }
  const auto it = std::max_element(a.begin(), a.end());
  if (it != a.end()) {
    best.speed = speeds[static_cast<std::size_t>(it - a.begin())];
    best.amplitude = *it;
  }
  return best;
}

/// The main peak of a linear reference curve, resolved: `response(speed)` (sensor `sensor`)
/// sampled again on 2001 speeds around the largest sample of the given grid (2 % of its speed or
/// three grid steps each side, within the range), so that a lightly damped peak and its half-power
/// band are met however coarse the tabulated grid is.
template <class Response>
response::SpeedPeak refined_linear_peak(const std::vector<double>& speeds,
                                        const std::vector<double>& amplitude, Response response,
                                        Eigen::Index sensor) {
  const auto i = static_cast<std::size_t>(std::max_element(amplitude.begin(), amplitude.end()) -
                                          amplitude.begin());
  const double half = std::max(
      0.02 * speeds[i], speeds[std::min(i + 3, speeds.size() - 1)] - speeds[i >= 3 ? i - 3 : 0]);
  const double lo = std::max(speeds.front(), speeds[i] - half);
  const double hi = std::min(speeds.back(), speeds[i] + half);
  std::vector<double> fine(2001), a(2001);
  for (std::size_t j = 0; j < fine.size(); ++j) {
    fine[j] = lo + (hi - lo) * static_cast<double>(j) / 2000.0;
    a[j] = std::abs(response(fine[j])[sensor]);
  }
  return main_peak(fine, a);
}

std::vector<double> column(const Eigen::MatrixXd& m, Eigen::Index c) {
  return std::vector<double>(m.col(c).data(), m.col(c).data() + m.rows());
}

DamperPerformancePoint performance_point(const damper::DamperRingModel& m,
                                         const damper::DamperRingOptions& options, double value,
                                         Progress& progress) {
  damper::DamperRingOptions o = options;
  o.hysteresis_pairs.clear();
  const damper::DamperRingResult r = damper::run_damper_ring(m, o, progress);
  DamperPerformancePoint p;
  p.value = value;
  p.status = r.status;
  p.message = r.message;
  std::vector<double> speeds, amplitude;
  for (const auto& d : r.damped) {
    speeds.push_back(d.speed);
    amplitude.push_back(d.amplitude.size() ? d.amplitude[0] : 0.0);
  }
  p.peak = main_peak(speeds, amplitude);
  if (r.peak_point >= 0) {
    const auto& d = r.damped[static_cast<std::size_t>(r.peak_point)];
    p.energy = d.energy_per_cycle;
    p.slip = d.slip;
  }
  return p;
}

// --- set-up and solve

/// Node ids of the physical masters of a Craig-Bampton sector: the sector faces, the contact
/// pairs, the excitation and the sensor nodes (all the condensed model addresses by node).
std::vector<long> sector_masters(const assembly::SolidComponent& c, const DamperSetup& setup) {
  std::vector<long> masters;
  for (const auto& face : setup.faces) masters.insert(masters.end(), face.begin(), face.end());
  for (const auto& pr : setup.pairing.pairs) {
    masters.push_back(pr.gear_node);
    masters.push_back(pr.ring_node);
  }
  for (int n : setup.points.excitation)
    masters.push_back(c.mesh.node_ids[static_cast<std::size_t>(n)]);
  for (int n : setup.points.sensor_nodes)
    masters.push_back(c.mesh.node_ids[static_cast<std::size_t>(n)]);
  return masters;
}

/// K, M and the cyclic sector of a problem from the mesh's mass matrix `mass` (reduced again
/// when the sector is reduced: the fixed-interface modes depend on the mass); returns the
/// reduction's note.
std::string set_sector(damper::DamperRingProblem& q, const Eigen::SparseMatrix<double>& mass,
                       const assembly::SolidComponent& c, const DamperRingResponseSettings& s,
                       const DamperSetup& setup, const Context& context) {
  SolvedSector solved = solved_sector(
      c, s, sector_masters(c, setup),
      "sector faces of gear and ring, contact pairs, excitation and sensor nodes", context, &mass);
  q.K = std::move(solved.K);
  q.M = std::move(solved.M);
  if (solved.cb) {
    cyclic::InterfaceOptions io;
    io.n_sectors = c.sectors;
    io.tolerance = c.interface_tolerance;
    q.sector = cyclic::CyclicSector(
        solved.dofs, damper::two_body_interfaces(solved.dofs, io, setup.faces[0], setup.faces[1],
                                                 setup.faces[2], setup.faces[3]));
  } else {
    q.sector = cyclic::CyclicSector(setup.dofs, setup.interfaces);
  }
  return solved.note;
}

/// The harmonic-balance problem: loads, sector, contacts, ring, damping.
damper::DamperRingProblem damper_problem(const model::Model& model,
                                         const assembly::SolidComponent& c,
                                         const DamperRingResponseSettings& s,
                                         const DamperSetup& setup, DamperRingResponseResult& g,
                                         const Context& context) {
  const int N = c.sectors;
  const int k = s.engine_order;
  damper::DamperRingProblem p;
  p.loads = harmonic_loads(model, context, c, s, setup.points, g.orders, g.force_note);
  g.reduction_note = set_sector(p, c.mass(), c, s, setup, context);
  p.pairs = setup.pairing.pairs;
  p.contact = setup.law;
  p.ring_mass = setup.ring.mass;
  p.ring_radius = setup.ring.radius;
  p.nodal_diameter = std::min(k % N, N - k % N);
  p.engine_order = k;
  p.sensors = setup.points.sensors;
  if (!std::isnan(s.q_factor))
    p.damping.q_factor = s.q_factor;
  else
    p.damping.damping_ratio = s.damping_ratio;
  p.n_modes = s.n_modes;
  p.harmonics = s.harmonics;
  p.time_samples = s.time_samples;
  return p;
}

damper::DamperRingOptions continuation_options(const DamperRingResponseSettings& s, int n_pairs) {
  damper::DamperRingOptions o;
  o.speed_min = s.speeds.front();
  o.speed_max = s.speeds.back();
  o.linear_points = static_cast<int>(s.speeds.size());
  o.max_step = s.max_step;
  o.hysteresis_pairs = s.hysteresis_pairs;
  if (o.hysteresis_pairs.empty()) {
    o.hysteresis_pairs = {0};
    if (n_pairs > 2) o.hysteresis_pairs.push_back(n_pairs / 2);
    if (n_pairs > 1) o.hysteresis_pairs.push_back(n_pairs - 1);
  }
  return o;
}

const char* sweep_name(DamperSweep sweep) {
  return sweep == DamperSweep::RingMass              ? "ring_mass_factor"
         : sweep == DamperSweep::FrictionCoefficient ? "friction_coefficient"
                                                     : "contact_stiffness_factor";
}

/// The damper performance curve: the damped peak with the ring mass, the friction coefficient
/// or the contact stiffnesses changed.
std::vector<DamperPerformancePoint> performance_curve(
    const assembly::SolidComponent& c, const DamperRingResponseSettings& s,
    const DamperSetup& setup, const damper::DamperRingProblem& p, const damper::DamperRingModel& m,
    const damper::DamperRingOptions& o, const Context& context) {
  Progress& progress = context.progress();
  const char* what = sweep_name(s.sweep);
  std::vector<DamperPerformancePoint> points;
  // The ring's DOFs in the mesh, for scaling its mass (gear and ring share no node).
  std::vector<char> in_ring;
  if (s.sweep == DamperSweep::RingMass) {
    std::set<long> ids(setup.ring_ids.begin(), setup.ring_ids.end());
    for (const auto& d : setup.dofs) in_ring.push_back(ids.count(d.node_id) ? 1 : 0);
  }
  for (std::size_t i = 0; i < s.sweep_values.size(); ++i) {
    const double v = s.sweep_values[i];
    progress.start(fmt::format("{}: performance curve, {} = {:.4g} ({} of {})", context.name(),
                               what, v, i + 1, s.sweep_values.size()),
                   0);
    if (s.sweep == DamperSweep::RingMass) {
      damper::DamperRingProblem q = p;
      q.ring_mass = v * p.ring_mass;
      Eigen::SparseMatrix<double> mass = c.mass();
      for (int col = 0; col < mass.outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(mass, col); it; ++it)
          if (in_ring[static_cast<std::size_t>(it.row())] && in_ring[static_cast<std::size_t>(col)])
            it.valueRef() *= v;
      (void)set_sector(q, mass, c, s, setup, context);
      points.push_back(performance_point(damper::build_damper_ring_model(q), o, v, progress));
    } else {
      damper::DamperRingModel q = m;
      if (s.sweep == DamperSweep::FrictionCoefficient) {
        q.contact.friction_coefficient = v;
      } else {
        q.contact.normal_stiffness *= v;
        q.contact.tangential_stiffness *= v;
      }
      points.push_back(performance_point(q, o, v, progress));
    }
    progress.finish();
  }
  return points;
}

std::vector<double> damped_column(const damper::DamperRingResult& r, Eigen::Index sensor,
                                  bool peak) {
  std::vector<double> v;
  for (const auto& d : r.damped) v.push_back(peak ? d.peak[sensor] : d.amplitude[sensor]);
  return v;
}

/// The main peaks of the damped curve and of the linear references (see the result).
void find_peaks(DamperRingResponseResult& g, const damper::DamperRingModel& m) {
  const damper::DamperRingResult& r = g.response;
  std::vector<double> damped_speed;
  for (const auto& d : r.damped) damped_speed.push_back(d.speed);
  const std::vector<double> linear_speed(r.linear_speeds.data(),
                                         r.linear_speeds.data() + r.linear_speeds.size());
  const auto n_s = static_cast<Eigen::Index>(m.sensor_names.size());
  for (Eigen::Index j = 0; j < n_s; ++j) {
    g.damped_peaks.push_back(main_peak(damped_speed, damped_column(r, j, false)));
    g.free_peaks.push_back(refined_linear_peak(
        linear_speed, column(r.free_amplitude, j), [&](double w) { return m.free_response(w); },
        j));
  }
  const damper::StuckRingResponse stuck(m);
  g.stuck_peak = refined_linear_peak(
      linear_speed, column(r.stuck_amplitude, 0), [&](double w) { return stuck(w); }, 0);
}

// --- post-processing

void add_resonance(AnalysisOutput& out, const DamperRingResponseSettings& s,
                   const DamperRingResponseResult& g) {
  Table t;
  t.name = "resonance";
  t.title = fmt::format(
      "Resonance of sensor {} (harmonic 1 of EO {}): the damped response against the gear "
      "without ring (free) and with the ring stuck",
      g.sensor_names.front(), s.engine_order);
  const response::SpeedPeak& dp = g.damped_peaks.front();
  const response::SpeedPeak& fp = g.free_peaks.front();
  const response::SpeedPeak& sp = g.stuck_peak;
  std::vector<double> rpm, amp, q, vs_free, vs_stuck, shift_free, shift_stuck;
  for (const auto* x : {&dp, &fp, &sp}) {
    rpm.push_back(x->speed * kRpm);
    amp.push_back(x->amplitude);
    q.push_back(x->resolved ? x->q_factor : response::kNaN);
    vs_free.push_back(x->amplitude / fp.amplitude);
    vs_stuck.push_back(x->amplitude / sp.amplitude);
    shift_free.push_back(100.0 * (x->speed / fp.speed - 1.0));
    shift_stuck.push_back(100.0 * (x->speed / sp.speed - 1.0));
  }
  t.add_text("curve", {"damped", "free (no ring)", "stuck ring"});
  t.add("peak_speed_rpm", "rpm", rpm);
  t.add("peak_amplitude_m", "m", amp);
  t.add("q_factor", "", q);
  t.add("amplitude_vs_free", "", vs_free);
  t.add("amplitude_vs_stuck", "", vs_stuck);
  t.add("speed_shift_vs_free_pct", "%", shift_free);
  t.add("speed_shift_vs_stuck_pct", "%", shift_stuck);
  out.tables.push_back(std::move(t));
  if (!dp.resolved)
    out.notes.push_back(
        "The damped peak's half-power band holds fewer than 3 continuation points, so its Q "
        "is not given: lower max_step or narrow the speed range around the resonance.");
  out.notes.push_back(fmt::format(
      "Damped peak {:.4g} m at {:.6g} rpm (Q {:.4g}): {:.3g} x the stuck ring's peak ({:.4g} m "
      "at "
      "{:.6g} rpm, Q {:.4g}) and {:.3g} x the gear's without ring ({:.4g} m at {:.6g} rpm, Q "
      "{:.4g}); resonance shift {:+.2f} % from the stuck ring.",
      dp.amplitude, dp.speed * kRpm, dp.resolved ? dp.q_factor : response::kNaN,
      dp.amplitude / sp.amplitude, sp.amplitude, sp.speed * kRpm, sp.q_factor,
      dp.amplitude / fp.amplitude, fp.amplitude, fp.speed * kRpm, fp.q_factor,
      100.0 * (dp.speed / sp.speed - 1.0)));
}

void add_damped_response(AnalysisOutput& out, const DamperRingResponseSettings& s,
                         const DamperRingResponseResult& g, const std::vector<double>& damped_rpm) {
  const damper::DamperRingResult& r = g.response;
  Table t;
  t.name = "damped_response";
  t.title = fmt::format(
      "Friction-damped response per continuation point (harmonic 1 and the largest |x(t)| of "
      "all {} harmonics), energy dissipated by the whole ring per cycle, contact states",
      s.harmonics);
  t.add("speed_rpm", "rpm", damped_rpm);
  for (std::size_t j = 0; j < g.sensor_names.size(); ++j) {
    const auto col = static_cast<Eigen::Index>(j);
    t.add(g.sensor_names[j] + "_amplitude_m", "m", damped_column(r, col, false));
    t.add(g.sensor_names[j] + "_peak_m", "m", damped_column(r, col, true));
  }
  std::vector<double> energy, stick, slip, lift, iterations, closed, fold;
  for (const auto& d : r.damped) {
    energy.push_back(d.energy_per_cycle);
    stick.push_back(d.stick);
    slip.push_back(d.slip);
    lift.push_back(d.lift_off);
    iterations.push_back(d.iterations);
    closed.push_back(d.loops_closed ? 1.0 : 0.0);
    fold.push_back(d.fold_unstable ? 1.0 : 0.0);
  }
  t.add("energy_per_cycle_j", "J", energy);
  t.add("stick_fraction", "", stick);
  t.add("slip_fraction", "", slip);
  t.add("lift_off_fraction", "", lift);
  t.add("newton_iterations", "", iterations);
  t.add("loops_closed", "", closed);
  t.add("unstable_fold", "", fold);
  out.tables.push_back(std::move(t));

  Plot e;
  e.name = "energy";
  e.title = "Energy dissipated by the ring per cycle";
  e.x_label = "speed [rpm]";
  e.y_label = "energy per cycle [J]";
  e.traces.push_back(curve("energy per cycle", damped_rpm, energy));
  out.plots.push_back(std::move(e));
  Plot st;
  st.name = "contact_states";
  st.title = "Stick, slip and lift-off over the contact (fractions of pairs x time)";
  st.x_label = "speed [rpm]";
  st.y_label = "fraction";
  st.traces.push_back(curve("stick", damped_rpm, stick));
  st.traces.push_back(curve("slip", damped_rpm, slip));
  st.traces.push_back(curve("lift-off", damped_rpm, lift));
  out.plots.push_back(std::move(st));
}

void add_linear_response(AnalysisOutput& out, const DamperRingResponseSettings& s,
                         const DamperRingResponseResult& g, const std::vector<double>& damped_rpm,
                         int h) {
  const damper::DamperRingResult& r = g.response;
  const auto n_s = static_cast<Eigen::Index>(g.sensor_names.size());
  std::vector<double> linear_rpm;
  for (Eigen::Index i = 0; i < r.linear_speeds.size(); ++i)
    linear_rpm.push_back(r.linear_speeds[i] * kRpm);
  Table t;
  t.name = "linear_response";
  t.title = "Linear references: the gear without ring (free) and with the ring stuck";
  t.add("speed_rpm", "rpm", linear_rpm);
  for (Eigen::Index j = 0; j < n_s; ++j) {
    t.add(g.sensor_names[static_cast<std::size_t>(j)] + "_free_m", "m",
          column(r.free_amplitude, j));
    t.add(g.sensor_names[static_cast<std::size_t>(j)] + "_stuck_m", "m",
          column(r.stuck_amplitude, j));
  }
  out.tables.push_back(std::move(t));
  Plot pl = amplitude_plot(
      "response", fmt::format("Response to EO {} (ND {}): friction-damped, without ring and "
                              "with the ring stuck",
                              s.engine_order, h));
  pl.y_label = "amplitude [m]";
  for (Eigen::Index j = 0; j < n_s; ++j) {
    const std::string& sn = g.sensor_names[static_cast<std::size_t>(j)];
    pl.traces.push_back(curve(sn + " damped", damped_rpm, damped_column(r, j, false)));
    pl.traces.push_back(curve(sn + " free", linear_rpm, column(r.free_amplitude, j), "dot"));
    pl.traces.push_back(curve(sn + " stuck", linear_rpm, column(r.stuck_amplitude, j), "dash"));
  }
  std::vector<double> unstable_rpm, unstable_amplitude;
  for (const auto& d : r.damped)
    if (d.fold_unstable && n_s > 0) {
      unstable_rpm.push_back(d.speed * kRpm);
      unstable_amplitude.push_back(d.amplitude[0]);
    }
  if (!unstable_rpm.empty()) {
    Trace u = curve(g.sensor_names.front() + " unstable (between folds)", unstable_rpm,
                    unstable_amplitude);
    u.mode = Trace::Mode::Markers;
    pl.traces.push_back(std::move(u));
  }
  out.plots.push_back(std::move(pl));
  std::vector<std::string> turns;
  for (double w : r.turning_points) turns.push_back(fmt::format("{:.6g}", w * kRpm));
  out.notes.push_back(
      (r.turning_points.empty()
           ? std::string("Stability: the damped curve has no turning point in speed, so no "
                         "fold-type instability (jump)")
           : fmt::format("Stability: the damped curve turns at {} rpm; the {} points after an "
                         "odd number of turns are unstable (a real Floquet multiplier > 1, the "
                         "jump phenomenon), marked on the response plot and in "
                         "damped_response.unstable_fold",
                         fmt::join(turns, ", "), unstable_rpm.size())) +
      ". Period doubling and quasi-periodic losses of stability are not assessed: Hill's "
      "method with the stick-slip Jacobian gives spurious flutter exponents here "
      "(hbm/condensed_stability.hpp).");
}

Table contact_pairs_table(const DamperRingResponseResult& g, double peak_rpm) {
  const damper::DamperRingResult& r = g.response;
  Table t;
  t.name = "contact_pairs";
  t.title = fmt::format(
      "Contact pairs at the damped peak ({:.6g} rpm): position, stick / slip / lift-off "
      "fractions of the period, energy dissipated per cycle",
      peak_rpm);
  std::vector<double> idx, gear_node, ring_node, radius, theta, z, stick, slip, lift, energy;
  for (int q = 0; q < static_cast<int>(g.pairs.size()); ++q) {
    const auto& pr = g.pairs[static_cast<std::size_t>(q)];
    idx.push_back(q);
    gear_node.push_back(static_cast<double>(pr.gear_node));
    ring_node.push_back(static_cast<double>(pr.ring_node));
    radius.push_back(std::hypot(pr.position.x(), pr.position.y()));
    theta.push_back(std::atan2(pr.position.y(), pr.position.x()) * kDeg);
    z.push_back(pr.position.z());
    stick.push_back(r.pair_states(q, 0));
    slip.push_back(r.pair_states(q, 1));
    lift.push_back(r.pair_states(q, 2));
    energy.push_back(r.pair_energy[q]);
  }
  t.add("pair", "", idx);
  t.add("gear_node", "", gear_node);
  t.add("ring_node", "", ring_node);
  t.add("radius_m", "m", radius);
  t.add("theta_deg", "deg", theta);
  t.add("z_m", "m", z);
  t.add("stick_fraction", "", stick);
  t.add("slip_fraction", "", slip);
  t.add("lift_off_fraction", "", lift);
  t.add("energy_per_cycle_j", "J", energy);
  return t;
}

void add_hysteresis(AnalysisOutput& out, const damper::DamperRingResult& r, double peak_rpm) {
  Table loops;
  loops.name = "hysteresis_loops";
  loops.title = fmt::format(
      "Hysteresis loops at the damped peak ({:.6g} rpm): relative slip u and tangential force "
      "T over one period, with the normal load N",
      peak_rpm);
  std::vector<double> pair, sample, u, force, normal;
  Plot pl;
  pl.name = "hysteresis";
  pl.title = loops.title;
  pl.x_label = "slip u [m]";
  pl.y_label = "tangential force T [N]";
  for (const auto& l : r.loops) {
    std::vector<double> lu(l.slip.data(), l.slip.data() + l.slip.size());
    std::vector<double> lf(l.force.data(), l.force.data() + l.force.size());
    for (Eigen::Index i = 0; i < l.slip.size(); ++i) {
      pair.push_back(l.pair);
      sample.push_back(static_cast<double>(i));
      u.push_back(l.slip[i]);
      force.push_back(l.force[i]);
      normal.push_back(l.normal[i]);
    }
    // Close the loop on the plot.
    lu.push_back(lu.front());
    lf.push_back(lf.front());
    Trace tr;
    tr.name = fmt::format("pair {}", l.pair);
    tr.x = std::move(lu);
    tr.y = std::move(lf);
    pl.traces.push_back(std::move(tr));
  }
  loops.add("pair", "", pair);
  loops.add("sample", "", sample);
  loops.add("slip_m", "m", u);
  loops.add("tangential_force_n", "N", force);
  loops.add("normal_force_n", "N", normal);
  out.tables.push_back(std::move(loops));
  out.plots.push_back(std::move(pl));
}

void add_performance(AnalysisOutput& out, const DamperRingResponseSettings& s,
                     const DamperRingResponseResult& g) {
  const std::vector<DamperPerformancePoint>& points = g.performance;
  const char* what = sweep_name(s.sweep);
  std::size_t best = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].peak.amplitude < points[best].peak.amplitude) best = i;
  Table t;
  t.name = "performance";
  t.title = fmt::format(
      "Damper performance: resonance of sensor {} against {} (optimum: the lowest peak)",
      g.sensor_names.front(), what);
  std::vector<double> value, mass, rpm, amp, q, energy, slip, optimum;
  std::vector<std::string> status;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const DamperPerformancePoint& pp = points[i];
    value.push_back(pp.value);
    mass.push_back(g.ring.mass * (s.sweep == DamperSweep::RingMass ? pp.value : 1.0));
    rpm.push_back(pp.peak.speed * kRpm);
    amp.push_back(pp.peak.amplitude);
    q.push_back(pp.peak.resolved ? pp.peak.q_factor : response::kNaN);
    energy.push_back(pp.energy);
    slip.push_back(pp.slip);
    optimum.push_back(i == best ? 1.0 : 0.0);
    status.push_back(pp.status == Status::Ok ? "ok" : "failed: " + pp.message);
  }
  t.add(what, "", value);
  t.add("ring_mass_kg", "kg", mass);
  t.add("peak_speed_rpm", "rpm", rpm);
  t.add("peak_amplitude_m", "m", amp);
  t.add("q_factor", "", q);
  t.add("energy_at_peak_j", "J", energy);
  t.add("slip_at_peak", "", slip);
  t.add("optimum", "", optimum);
  t.add_text("status", status);
  out.tables.push_back(std::move(t));
  Plot pl;
  pl.name = "performance";
  pl.title = fmt::format("Damper performance curve: peak amplitude against {}", what);
  pl.x_label = what;
  pl.y_label = "peak amplitude [m]";
  // Factors span decades; a friction coefficient may start at 0.
  const bool x_log = s.sweep != DamperSweep::FrictionCoefficient;
  pl.x_log = x_log;
  Trace tr = curve("damped peak", value, amp);
  tr.mode = Trace::Mode::LinesMarkers;
  pl.traces.push_back(std::move(tr));
  Trace opt = curve("optimum", {value[best]}, {amp[best]});
  opt.mode = Trace::Mode::Markers;
  pl.traces.push_back(std::move(opt));
  out.plots.push_back(std::move(pl));
  Plot ps;
  ps.name = "performance_speed";
  ps.title = fmt::format("Resonance speed and Q against {}", what);
  ps.x_label = what;
  ps.x_log = x_log;
  ps.y_label = "resonance speed [rpm] / Q";
  Trace trs = curve("resonance speed [rpm]", value, rpm);
  trs.mode = Trace::Mode::LinesMarkers;
  ps.traces.push_back(std::move(trs));
  Trace trq = curve("Q", value, q);
  trq.mode = Trace::Mode::LinesMarkers;
  ps.traces.push_back(std::move(trq));
  out.plots.push_back(std::move(ps));
  out.notes.push_back(fmt::format(
      "Performance curve: the lowest peak, {:.4g} m at {:.6g} rpm, is at {} = {:.4g}{}.", amp[best],
      rpm[best], what, value[best],
      best == 0 || best + 1 == points.size()
          ? " -- at the end of the values given, so the optimum may lie beyond them"
          : ""));
  for (const auto& pp : points)
    if (pp.status != Status::Ok)
      out.notes.push_back(fmt::format("Performance point {} = {:.4g} did not complete: {}", what,
                                      pp.value, pp.message));
}

Table harmonic_forces_table(const DamperRingResponseSettings& s,
                            const std::vector<OrderForce>& orders) {
  Table t;
  t.name = "harmonic_forces";
  t.title = "Tooth-force harmonics on the balanced harmonics (engine order n k on harmonic n)";
  std::vector<double> harmonic, eo, nd, ft, fr, fa;
  for (std::size_t n = 0; n < orders.size(); ++n) {
    harmonic.push_back(static_cast<double>(n + 1));
    eo.push_back(orders[n].engine_order);
    nd.push_back(orders[n].nodal_diameter);
    ft.push_back(s.pair.empty() ? orders[n].amplitude : std::abs(orders[n].tangential));
    fr.push_back(s.pair.empty() ? 0.0 : std::abs(orders[n].radial));
    fa.push_back(s.pair.empty() ? 0.0 : std::abs(orders[n].axial));
  }
  t.add("harmonic", "", harmonic);
  t.add("engine_order", "", eo);
  t.add("nodal_diameter", "", nd);
  t.add(s.pair.empty() ? "amplitude_n" : "tangential_n", "N", ft);
  t.add("radial_n", "N", fr);
  t.add("axial_n", "N", fa);
  return t;
}

/// The model (ring, contacts, harmonics) and how far to trust it.
void add_model_notes(AnalysisOutput& out, const DamperRingResponseSettings& s,
                     const DamperRingResponseResult& g) {
  const damper::DamperRingResult& r = g.response;
  out.notes.push_back(g.force_note);
  for (const auto& note : g.setup_notes) out.notes.push_back(note);
  for (const auto& note : g.model_notes) out.notes.push_back(note);
  out.notes.push_back(fmt::format(
      "Ring: mass {:.5g} kg (whole ring, from the mass matrix of element set \"{}\"), centre-of-"
      "mass radius r_G {:.5g} m; {} contact pairs per sector ({} on the right sector face "
      "dropped as the next sector's left ones); contact {} with k_n {:.4g} N/m, k_t {:.4g} N/m, "
      "mu {:.4g} per pair; preload N0 {:.4g} N per pair at {:.6g} rpm.",
      g.ring.mass, s.ring_element_set, g.ring.radius, g.pairs.size(), g.dropped_pairs,
      s.contact_directions == 1 ? "2d" : "3d", g.contact.normal_stiffness,
      g.contact.tangential_stiffness, g.contact.friction_coefficient, g.preload_at_max,
      s.speeds.back() * kRpm));
  const int default_samples = hbm::default_time_samples(s.harmonics);
  if (s.time_samples > 0 && s.time_samples < default_samples)
    out.notes.push_back(fmt::format(
        "Warning: time_samples = {} is below the {} the friction law needs for {} harmonics "
        "(its stick-slip kinks alias onto the balanced harmonics): the forces and Jacobians "
        "lose accuracy; leave time_samples out or raise it.",
        s.time_samples, default_samples, s.harmonics));
  if (r.truncation_pair >= 0) {
    if (r.force_truncation > kTruncationWarning)
      out.notes.push_back(fmt::format(
          "Warning: at the damped peak {:.1f} % of the contact force of pair {} lies beyond the "
          "{} balanced harmonic{} (checked by marching the same motion with {} harmonics): the "
          "balance neglects it; raise harmonics to resolve it.",
          100.0 * r.force_truncation, r.truncation_pair, s.harmonics, s.harmonics > 1 ? "s" : "",
          3 * s.harmonics + 2));
    else
      out.notes.push_back(fmt::format(
          "Harmonic truncation: at the damped peak at most {:.2f} % of a pair's contact force lies "
          "beyond the {} balanced harmonic{} (warning above {:.0f} %); the structure responds to "
          "those higher harmonics off resonance unless a mode lies near n k W: to check the "
          "response, run again with more harmonics.",
          100.0 * r.force_truncation, s.harmonics, s.harmonics > 1 ? "s" : "",
          100.0 * kTruncationWarning));
  }
  int open_loops = 0;
  for (const auto& d : r.damped) open_loops += d.loops_closed ? 0 : 1;
  if (open_loops > 0)
    out.notes.push_back(fmt::format(
        "Warning: at {} of {} points the hysteresis loop of some contact did not close within "
        "the periods marched (table damped_response, loops_closed = 0): the forces there are "
        "those of the last period marched.",
        open_loops, r.damped.size()));
  out.notes.push_back(
      "How far to trust it: the contact law is node-to-node Coulomb friction with elastic stick "
      "and a variable normal load (lift-off); the linear structure is a modal sum with residual "
      "flexibility per nodal diameter, checked against a direct solve (0.1 %) and the mu -> "
      "infinity and mu = 0 limits (1e-7) in the tests; the contact stiffness and the friction "
      "coefficient are the uncertain inputs -- sweep them (performance_parameter).");
}

}  // namespace

std::size_t DamperRingResponseResult::sensor_index(const std::string& name) const {
  if (sensor_names.empty()) throw std::runtime_error("the analysis has no sensor");
  if (name.empty()) return 0;
  for (std::size_t i = 0; i < sensor_names.size(); ++i)
    if (sensor_names[i] == name) return i;
  throw std::runtime_error(fmt::format("the analysis has no sensor '{}'", name));
}

void check_damper_ring_response(const assembly::SolidComponent& c,
                                const DamperRingResponseSettings& s, const Context& context) {
  (void)damper_setup(context, c, s);
}

DamperRingResponseResult run_damper_ring_response(const model::Model& model,
                                                  const DamperRingResponseSettings& s,
                                                  const Context& context) {
  const assembly::SolidComponent& c = context.solid(model, s.solid);
  Progress& progress = context.progress();
  const DamperSetup setup = damper_setup(context, c, s);
  DamperRingResponseResult g;
  const damper::DamperRingProblem p = damper_problem(model, c, s, setup, g, context);
  const damper::DamperRingModel m = damper::build_damper_ring_model(p, progress);
  const damper::DamperRingOptions o =
      continuation_options(s, static_cast<int>(setup.pairing.pairs.size()));
  g.response = damper::run_damper_ring(m, o, progress);
  g.sensor_names = m.sensor_names;
  g.pairs = m.pairs;
  g.model_notes = m.notes;
  g.setup_notes = setup.notes;
  g.ring = setup.ring;
  g.contact = setup.law;
  g.dropped_pairs = setup.pairing.dropped_on_right_interface;
  g.preload_at_max = m.preload(o.speed_max);
  find_peaks(g, m);
  if (s.sweep != DamperSweep::None)
    g.performance = performance_curve(c, s, setup, p, m, o, context);
  return g;
}

AnalysisOutput damper_ring_response_output(const model::Model& model,
                                           const DamperRingResponseSettings& s,
                                           const DamperRingResponseResult& g,
                                           const Context& context) {
  const assembly::SolidComponent& c = context.solid(model, s.solid);
  const damper::DamperRingResult& r = g.response;
  const int N = c.sectors;
  const int k = s.engine_order;
  AnalysisOutput out;
  out.notes.push_back(c.description);
  for (const auto& w : c.warnings) out.notes.push_back(w);
  if (!g.reduction_note.empty()) out.notes.push_back(g.reduction_note);
  std::vector<double> damped_rpm;
  for (const auto& d : r.damped) damped_rpm.push_back(d.speed * kRpm);
  add_resonance(out, s, g);
  add_damped_response(out, s, g, damped_rpm);
  add_linear_response(out, s, g, damped_rpm, std::min(k % N, N - k % N));
  if (r.peak_point >= 0) {
    const double peak_rpm = r.damped[static_cast<std::size_t>(r.peak_point)].speed * kRpm;
    out.tables.push_back(contact_pairs_table(g, peak_rpm));
    add_hysteresis(out, r, peak_rpm);
  }
  if (s.sweep != DamperSweep::None) add_performance(out, s, g);
  out.tables.push_back(harmonic_forces_table(s, g.orders));
  add_model_notes(out, s, g);
  out.status = r.status;
  if (r.status != Status::Ok)
    out.message = fmt::format(
        "{} (the continuation stopped at {:.6g} rpm; the points reached are reported; a smaller "
        "max_step or more harmonics usually helps)",
        r.message, r.damped.empty() ? s.speeds.front() * kRpm : r.damped.back().speed * kRpm);
  return out;
}

}  // namespace geardyn::analyses
