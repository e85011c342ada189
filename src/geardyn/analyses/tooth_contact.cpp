#include "geardyn/analyses/tooth_contact.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>

#include "geardyn/analyses/gear_helpers.hpp"
#include "geardyn/analyses/tooth_contact_correlation.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/gear/fe_compliance.hpp"
#include "geardyn/gear/tooth_forces.hpp"
#include "geardyn/gear/topography_csv.hpp"

namespace geardyn::analyses {

namespace {

constexpr double kDeg = 180.0 / units::kPi;

gear::ReliefShape shape(model::ReliefShapeKind k) {
  return k == model::ReliefShapeKind::Parabolic ? gear::ReliefShape::Parabolic
                                                : gear::ReliefShape::Linear;
}

// A relief start given by diameter or roll angle xi (r = r_b sqrt(1 + xi^2)) as a radius.
double start_radius(double diameter, double roll_angle, double base_radius) {
  if (!std::isnan(diameter)) return 0.5 * diameter;
  if (!std::isnan(roll_angle)) return base_radius * std::sqrt(1.0 + roll_angle * roll_angle);
  return std::numeric_limits<double>::quiet_NaN();
}

gear::FlankModification flank(const model::FlankModificationSpec& f, double base_radius,
                              const model::GearPair& p, const char* key) {
  gear::FlankModification m;
  m.tip_relief_m = f.tip_relief;
  m.tip_relief_start_radius_m =
      start_radius(f.tip_relief_start_diameter, f.tip_relief_start_roll_angle, base_radius);
  m.tip_relief_shape = shape(f.tip_relief_shape);
  m.root_relief_m = f.root_relief;
  m.root_relief_start_radius_m =
      start_radius(f.root_relief_start_diameter, f.root_relief_start_roll_angle, base_radius);
  m.root_relief_shape = shape(f.root_relief_shape);
  if (f.tip_relief > 0.0 && std::isnan(m.tip_relief_start_radius_m))
    throw InputError(f.where.line > 0 ? f.where : p.where, fmt::format("{}.tip_relief", key),
                     "tip_relief_start_diameter or tip_relief_start_roll_angle_deg with a tip "
                     "relief",
                     "neither");
  if (f.root_relief > 0.0 && std::isnan(m.root_relief_start_radius_m))
    throw InputError(f.where.line > 0 ? f.where : p.where, fmt::format("{}.root_relief", key),
                     "root_relief_start_diameter or root_relief_start_roll_angle_deg with a "
                     "root relief",
                     "neither");
  m.profile_crowning_m = f.profile_crowning;
  m.lead_crowning_m = f.lead_crowning;
  m.lead_slope_m = f.lead_slope;
  m.end_relief_m = f.end_relief;
  m.end_relief_length_m = f.end_relief_length;
  m.end_relief_shape = shape(f.end_relief_shape);
  m.pitch_deviation_m = f.pitch_deviations;
  m.where = f.where;
  return m;
}

// The flank's topography_file, read into the modification's TopographyMap (errors at the file's
// line and column, or at the key when the file is missing).
void add_topography(const model::Model& model, const model::FlankModificationSpec& f,
                    const model::GearPair& p, const std::string& key, gear::FlankModification& m) {
  if (f.topography_file.empty()) return;
  const std::filesystem::path path = resolve_model_path(model, f.topography_file);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(f.where.line > 0 ? f.where : p.where, key + ".topography_file",
                     "a readable topography CSV file (relative to the model file)",
                     fmt::format("\"{}\" ({} does not exist)", f.topography_file, path.string()));
  m.topography = gear::read_topography_csv(path);
}

gear::ElasticConstants elastic(const model::Model& m, const std::string& material) {
  gear::ElasticConstants e;
  if (material.empty()) return e;  // steel, E = 206 GPa, nu = 0.3
  const model::Material* mat = m.find_material(material);
  if (mat == nullptr) throw std::logic_error("gear-pair material not resolved: " + material);
  e.youngs_modulus_pa = mat->youngs_modulus;
  e.poisson_ratio = mat->youngs_modulus / (2.0 * mat->shear_modulus) - 1.0;
  return e;
}

// Bevel / hypoid pairs (docs/theory.md §15.9): the ease-off and the mounting errors into the
// options; returns the geometry the compliance is built on (the virtual cylindrical pair with
// the mounting errors' centre distance change; the pair itself for a cylindrical pair).
gear::GearPairGeometry bevel_contact(const model::GearPair& p, const gear::GearPairGeometry& g,
                                     const std::string& path, gear::ToothContactOptions& o) {
  const model::EaseOffSpec& e = p.ease_off;
  o.ease_off = {e.profile_crowning, e.length_crowning, e.bias, e.profile_slope, e.length_slope};
  const model::ContactModelSpec& c = p.contact;
  o.mounting = {c.mounting_h, c.mounting_v, c.mounting_j, c.shaft_angle_error, true};
  const bool given = !o.ease_off.zero() || !o.mounting.zero();
  if (!gear::is_bevel(g.spec.type)) {
    if (given)
      throw InputError(e.where.line > 0 && !o.ease_off.zero() ? e.where : p.where,
                       path + (o.ease_off.zero() ? ".contact.mounting_h" : ".ease_off"),
                       "no ease-off or mounting errors H, V, J, shaft angle error (bevel and "
                       "hypoid pairs only)",
                       fmt::format("a {} pair with them", gear::to_string(g.spec.type)),
                       "use [gear_pairs.flank1/2] and contact.misalignment for cylindrical pairs");
    return g;
  }
  // The loaded pinion flank from hand and rotation, as the tooth forces take it.
  const auto hand = p.hand == model::Hand::Left ? gear::SpiralHand::Left : gear::SpiralHand::Right;
  const auto rot = p.rotation == model::GearRotation::Clockwise ? gear::Rotation::Clockwise
                                                                : gear::Rotation::CounterClockwise;
  o.mounting.pinion_concave_loaded =
      g.spec.type == gear::GearType::StraightBevel ||
      gear::loaded_flank(hand, rot, gear::MemberRole::Driving) == gear::Flank::Concave;
  gear::GearPairGeometry keyed = g;
  keyed.spec.key_path = path;
  return gear::virtual_cylindrical_pair(
      keyed, gear::mounting_effect(keyed, o.mounting).centre_distance_change_m);
}

}  // namespace

std::shared_ptr<ToothContactModel> build_tooth_contact_model(const model::Model& model,
                                                             std::size_t index) {
  return build_tooth_contact_model(model, build_pair_model(model, index));
}

gear::SteCurve contact_ste(const model::Model& model, const PairModel& pm) {
  const auto tc = build_tooth_contact_model(model, pm);
  const model::GearPair& p = *pm.pair;
  const gear::ToothContactResult r = tc->contact->solve(p.torque);
  if (r.status != Status::Ok)
    throw InputError(p.where, pm.key_path + ".ste_source",
                     "a tooth contact analysis that converges at the pair's torque",
                     fmt::format("at T1 = {:.6g} N m: {}", p.torque, r.message),
                     "check the flank modifications and the misalignment, or use \"iso\"");
  const auto n = static_cast<std::size_t>(tc->options.positions);  // the first mesh cycle
  std::vector<double> e(r.te_m.begin(), r.te_m.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<double> eg(r.unloaded_te_m.begin(),
                         r.unloaded_te_m.begin() + static_cast<std::ptrdiff_t>(n));
  return gear::SteCurve::from_samples(std::move(e), gear::SteInterpolation::Linear, std::move(eg),
                                      p.torque)
      .shifted(p.ste_shift, static_cast<std::size_t>(std::max(0, p.ste_samples)));
}

namespace {

// The compliance route of [gear_pairs.contact] compliance (docs/theory.md §15.3, §15.8).
std::unique_ptr<gear::ContactCompliance> make_compliance(const gear::ToothCompliance& teeth,
                                                         const gear::ToothComplianceOptions& co,
                                                         const model::ContactModelSpec& c,
                                                         double coupling_length_m) {
  if (c.compliance == model::ContactComplianceKind::Analytic)
    return std::make_unique<gear::SliceCompliance>(teeth, coupling_length_m);
  gear::FeComplianceOptions fo;
  fo.mesh_size = c.fe_mesh_size;
  fo.profile_points = c.fe_profile_points;
  fo.face_points = c.fe_face_points;
  fo.segment_teeth = c.fe_teeth;
  fo.teeth = co;
  return std::make_unique<gear::FeCompliance>(teeth, fo);
}

// How the slices of a tooth pair are coupled, for the notes.
std::string coupling_text(const ToothContactModel& m) {
  const model::ContactModelSpec& c = m.pair.pair->contact;
  if (c.compliance == model::ContactComplianceKind::Fe)
    return "slices coupled through the FE influence coefficients";
  if (m.coupling_length_m == 0.0)
    return "slices uncoupled (coupling_length = 0): a point-like contact spreads no load to its "
           "neighbours, which over-estimates the load peaks at modification edges";
  return fmt::format(
      "slices coupled by a shear layer of decay length {:.6g} m ({:.3g} m_n{})",
      m.coupling_length_m, m.coupling_length_m / m.pair.geometry.normal_module_m,
      std::isnan(c.coupling_length) ? ", the FE-calibrated default of docs/theory.md §15.8" : "");
}

// The note saying which compliance route ran, its mesh and its cost.
std::string compliance_note(const ToothContactModel& m) {
  const model::ContactModelSpec& c = m.pair.pair->contact;
  const auto* fe = dynamic_cast<const gear::FeCompliance*>(m.compliance.get());
  if (fe == nullptr)
    return fmt::format(
        "'{}': analytic compliance route (potential-energy tooth, Sainsot foundation, {}).",
        m.pair.pair->name, m.coupling_length_m > 0.0 ? "shear-layer coupling" : "uncoupled slices");
  const gear::ToothInfluence& p = fe->pinion();
  const gear::ToothInfluence& w = fe->wheel();
  return fmt::format(
      "'{}': FE compliance route (docs/theory.md §15.8): tet10 meshes of {}, element size "
      "{:.3g} m_n at the loaded tooth; pinion {} nodes / {} "
      "DOFs, wheel {} nodes / {} DOFs; grid {} profile x {} face points per gear; mesh + "
      "factorisation {:.3g} s, load cases {:.3g} s (both gears); Hertzian approach analytic; "
      "coupling_length not used.",
      m.pair.pair->name,
      c.fe_teeth == 0 ? std::string("the whole gears fixed at the bore")
                      : fmt::format("segments of {} teeth fixed at bore and cut faces", c.fe_teeth),
      c.fe_mesh_size, p.nodes, p.dofs, w.nodes, w.dofs, p.path.size(), p.face.size(),
      p.mesh_seconds + w.mesh_seconds, p.solve_seconds + w.solve_seconds);
}

}  // namespace

std::shared_ptr<ToothContactModel> build_tooth_contact_model(const model::Model& model,
                                                             const PairModel& pm) {
  auto tc = std::make_shared<ToothContactModel>();
  tc->pair = pm;
  const model::GearPair& p = *tc->pair.pair;
  const gear::GearPairGeometry& g = tc->pair.geometry;
  const std::string path = tc->pair.key_path;
  tc->pinion = flank(p.flank1, g.pinion.base_radius_m, p, (path + ".flank1").c_str());
  tc->wheel = flank(p.flank2, g.wheel.base_radius_m, p, (path + ".flank2").c_str());
  add_topography(model, p.flank1, p, path + ".flank1", tc->pinion);
  add_topography(model, p.flank2, p, path + ".flank2", tc->wheel);
  const model::ContactModelSpec& c = p.contact;
  tc->misalignment = contact_misalignment(model, tc->pair);
  tc->misalignment_m = tc->misalignment.at(p.torque);
  tc->options.positions = c.positions;
  tc->options.slices = c.slices;
  tc->options.misalignment_in_plane_m = tc->misalignment_m;
  tc->options.hunting_period = c.hunting_period;
  gear::ToothComplianceOptions co;
  co.pinion = elastic(model, p.material1);
  co.wheel = elastic(model, p.material2);
  tc->teeth = std::make_unique<gear::ToothCompliance>(bevel_contact(p, g, path, tc->options), co);
  tc->coupling_length_m = std::isnan(c.coupling_length)
                              ? kCouplingLengthPerModule * g.normal_module_m
                              : c.coupling_length;
  tc->compliance = make_compliance(*tc->teeth, co, c, tc->coupling_length_m);
  // The gear library reports keys as modifications1.<key>; the model calls them flank1.<key>.
  gear::GearPairGeometry keyed = g;
  keyed.spec.key_path = path;
  tc->contact = std::make_unique<gear::ToothContact>(keyed, tc->pinion, tc->wheel, *tc->compliance,
                                                     tc->options);
  return tc;
}

ToothContactRunResult run_tooth_contact(const model::Model& model,
                                        const ToothContactSettings& settings,
                                        const Context& context) {
  ToothContactRunResult r;
  r.model = build_tooth_contact_model(model, pair_index(model, settings.pair));
  std::vector<double> torques = settings.torques;
  if (torques.empty()) torques.push_back(r.model->pair.pair->torque);
  Progress& progress = context.progress();
  progress.start("torques", torques.size());
  for (std::size_t i = 0; i < torques.size(); ++i) {
    r.torques.push_back(solve_contact(*r.model, torques[i]));
    r.harmonics_m.push_back(gear::mesh_order_amplitudes(
        r.torques.back().te_m, r.model->contact->cycles(), settings.orders));
    r.stiffness_harmonics_n_per_m.push_back(gear::mesh_order_amplitudes(
        r.torques.back().stiffness_tangent_n_per_m, r.model->contact->cycles(), settings.orders));
    progress.update(i + 1);
  }
  progress.finish();
  r.te_correlation = correlate_measured_te(model, settings, r, context);
  double want = settings.distribution_torque;
  if (std::isnan(want)) {
    const double own = r.model->pair.pair->torque;
    want = std::find(torques.begin(), torques.end(), own) != torques.end()
               ? own
               : *std::max_element(torques.begin(), torques.end());
  }
  r.distribution_index =
      static_cast<std::size_t>(std::min_element(torques.begin(), torques.end(),
                                                [&](double a, double b) {
                                                  return std::abs(a - want) < std::abs(b - want);
                                                }) -
                               torques.begin());
  return r;
}

namespace {

double peak_peak(const std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *hi - *lo;
}

double mean(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

Table te_table(const ToothContactRunResult& r) {
  const double rb1 = r.model->contact->force_radius();
  const double pitch_deg = 360.0 / r.model->pair.pair->teeth1;
  Table t;
  t.name = "transmission_error";
  t.title =
      "Loaded transmission error, mesh stiffness and load sharing over the mesh cycle, per "
      "torque (u = 0: a tooth pair enters contact)";
  std::vector<double> torque, u, angle, te, te_rad, ute, ks, kt, pts, wmax, pmax;
  const auto pairs = r.torques.front().pair_load_share.cols();
  std::vector<std::vector<double>> share(static_cast<std::size_t>(pairs));
  for (const auto& res : r.torques)
    for (std::size_t p = 0; p < res.te_m.size(); ++p) {
      torque.push_back(res.torque_nm);
      u.push_back(res.mesh_fraction[p]);
      angle.push_back(res.mesh_fraction[p] * pitch_deg);
      te.push_back(res.te_m[p]);
      te_rad.push_back(res.te_m[p] / rb1);
      ute.push_back(res.unloaded_te_m[p]);
      ks.push_back(res.stiffness_secant_n_per_m[p]);
      kt.push_back(res.stiffness_tangent_n_per_m[p]);
      pts.push_back(res.points_in_contact[p]);
      wmax.push_back(res.max_line_load_n_per_m[p]);
      pmax.push_back(res.max_pressure_pa[p]);
      for (Eigen::Index j = 0; j < pairs; ++j)
        share[static_cast<std::size_t>(j)].push_back(
            res.pair_load_share(static_cast<Eigen::Index>(p), j));
    }
  t.add("torque_nm", "N m", torque);
  t.add("mesh_fraction", "", u);
  t.add("pinion_angle_deg", "deg", angle);
  t.add("te_m", "m", te);
  t.add("te_rad", "rad", te_rad);
  t.add("unloaded_te_m", "m", ute);
  t.add("stiffness_secant_n_per_m", "N/m", ks);
  t.add("stiffness_tangent_n_per_m", "N/m", kt);
  t.add("slices_in_contact", "", pts);
  t.add("max_line_load_n_per_m", "N/m", wmax);
  t.add("max_pressure_pa", "Pa", pmax);
  for (std::size_t j = 0; j < share.size(); ++j)
    t.add(fmt::format("load_share_pair{}", j), "", share[j]);
  return t;
}

Table summary_table(const ToothContactRunResult& r) {
  const double rb1 = r.model->contact->force_radius();
  Table t;
  t.name = "summary";
  t.title =
      "Per torque: TE peak-to-peak and mean, mesh stiffness, face-load factor, peak "
      "contact pressure, mesh misalignment used (of which from the rotor's deflection)";
  std::vector<double> torque, ppm, ppr, mte, ks, kt, khb, pmax, wmax, fma, fdefl;
  for (const auto& res : r.torques) {
    torque.push_back(res.torque_nm);
    fma.push_back(r.model->misalignment.at(res.torque_nm));
    fdefl.push_back(r.model->misalignment.deflection_at(res.torque_nm));
    ppm.push_back(peak_peak(res.te_m));
    ppr.push_back(peak_peak(res.te_m) / rb1);
    mte.push_back(mean(res.te_m));
    ks.push_back(mean(res.stiffness_secant_n_per_m));
    kt.push_back(mean(res.stiffness_tangent_n_per_m));
    khb.push_back(res.face_load_factor);
    pmax.push_back(*std::max_element(res.max_pressure_pa.begin(), res.max_pressure_pa.end()));
    wmax.push_back(
        *std::max_element(res.max_line_load_n_per_m.begin(), res.max_line_load_n_per_m.end()));
  }
  t.add("torque_nm", "N m", torque);
  t.add("te_peak_peak_m", "m", ppm);
  t.add("te_peak_peak_rad", "rad", ppr);
  t.add("te_mean_m", "m", mte);
  t.add("stiffness_secant_mean_n_per_m", "N/m", ks);
  t.add("stiffness_tangent_mean_n_per_m", "N/m", kt);
  t.add("face_load_factor", "", khb);
  t.add("max_pressure_pa", "Pa", pmax);
  t.add("max_line_load_n_per_m", "N/m", wmax);
  t.add("misalignment_m", "m", fma);
  t.add("misalignment_deflection_m", "m", fdefl);
  return t;
}

Table harmonics_table(const ToothContactRunResult& r) {
  const double rb1 = r.model->contact->force_radius();
  Table t;
  t.name = "te_harmonics";
  t.title =
      "TE harmonics at the mesh orders: 0-peak amplitude and peak-peak (2 x 0-peak) of each "
      "harmonic, and the 0-peak harmonics of the tangent mesh stiffness";
  std::vector<double> torque, order, amp, pp, amp_rad, stiffness;
  for (std::size_t i = 0; i < r.torques.size(); ++i)
    for (std::size_t k = 0; k < r.harmonics_m[i].size(); ++k) {
      torque.push_back(r.torques[i].torque_nm);
      order.push_back(static_cast<double>(k + 1));
      amp.push_back(r.harmonics_m[i][k]);
      pp.push_back(2.0 * r.harmonics_m[i][k]);
      amp_rad.push_back(r.harmonics_m[i][k] / rb1);
      stiffness.push_back(r.stiffness_harmonics_n_per_m[i][k]);
    }
  t.add("torque_nm", "N m", torque);
  t.add("mesh_order", "", order);
  t.add("amplitude_0_peak_m", "m", amp);
  t.add("amplitude_peak_peak_m", "m", pp);
  t.add("amplitude_0_peak_rad", "rad", amp_rad);
  t.add("stiffness_0_peak_n_per_m", "N/m", stiffness);
  return t;
}

Table distribution_table(const ToothContactRunResult& r) {
  const auto& res = r.torques[r.distribution_index];
  Table t;
  t.name = "load_distribution";
  t.title = fmt::format(
      "Load distribution over the flank at T1 = {:.6g} N m: every candidate "
      "slice of every mesh position (line load 0: open)",
      res.torque_nm);
  std::vector<double> pos, u, pair, s, y, roll, r1, r2, gap, w, p;
  for (const auto& c : res.distribution) {
    pos.push_back(c.position);
    u.push_back(res.mesh_fraction[static_cast<std::size_t>(c.position)]);
    pair.push_back(c.pair);
    s.push_back(c.path_m);
    y.push_back(c.face_m);
    roll.push_back(c.roll_angle1_rad * kDeg);
    r1.push_back(c.radius1_m);
    r2.push_back(c.radius2_m);
    gap.push_back(c.gap_m);
    w.push_back(c.line_load_n_per_m);
    p.push_back(c.pressure_pa);
  }
  t.add("position", "", pos);
  t.add("mesh_fraction", "", u);
  t.add("pair", "", pair);
  t.add("path_m", "m", s);
  t.add("face_m", "m", y);
  t.add("roll_angle1_deg", "deg", roll);
  t.add("radius1_m", "m", r1);
  t.add("radius2_m", "m", r2);
  t.add("gap_m", "m", gap);
  t.add("line_load_n_per_m", "N/m", w);
  t.add("pressure_pa", "Pa", p);
  return t;
}

Table face_load_table(const ToothContactRunResult& r) {
  Table t;
  t.name = "face_load";
  t.title =
      "Face-load distribution: line load summed over the tooth pairs at each face "
      "position, mean over the mesh cycle(s), per torque";
  const auto& g = r.model->pair.geometry;
  std::vector<double> torque, y, w;
  for (const auto& res : r.torques) {
    const std::size_t n = res.face_load_n_per_m.size();
    for (std::size_t k = 0; k < n; ++k) {
      torque.push_back(res.torque_nm);
      y.push_back((static_cast<double>(k) + 0.5) * g.face_width_m / static_cast<double>(n));
      w.push_back(res.face_load_n_per_m[k]);
    }
  }
  t.add("torque_nm", "N m", torque);
  t.add("face_m", "m", y);
  t.add("line_load_n_per_m", "N/m", w);
  return t;
}

Plot plot(std::string name, std::string title, std::string x, std::string y) {
  Plot p;
  p.name = std::move(name);
  p.title = std::move(title);
  p.x_label = std::move(x);
  p.y_label = std::move(y);
  return p;
}

// A quantity of the load distribution over the flank of gear 1 as a heat map: face position
// (slice centres) x roll angle of gear 1, on a uniform grid of the path of contact. Each slice's
// candidate points (every mesh position and tooth pair) lie on the path s; where several fall on
// one s (the cycles of a hunting period: different teeth) the largest is kept, so the map is the
// envelope a tooth flank sees while it rolls through the mesh; between the points of a slice it
// is linear in s, and blank beyond them.
Trace flank_map(const ToothContactRunResult& r, const gear::ToothContactResult& res,
                double (*value)(const gear::ContactPoint&), std::string z_label) {
  const gear::ToothContact& contact = *r.model->contact;
  const auto& g = contact.geometry();
  const int slices = contact.options().slices;
  const double path = g.path_of_contact_m;
  // One grid row per sampled step of the path, p_bt / positions (at most 201 rows).
  const double step = g.transverse_base_pitch_m / contact.options().positions;
  const auto rows = static_cast<std::size_t>(
      std::clamp(std::lround(path / step) + 1, static_cast<long>(2), static_cast<long>(201)));
  std::vector<std::vector<std::pair<double, double>>> per_slice(static_cast<std::size_t>(slices));
  for (const auto& c : res.distribution) {
    const auto k = static_cast<std::size_t>(
        std::clamp(static_cast<int>(c.face_m / g.face_width_m * slices), 0, slices - 1));
    per_slice[k].emplace_back(c.path_m, value(c));
  }
  Trace t;
  t.name = fmt::format("{:.6g} N m", res.torque_nm);
  t.z_label = std::move(z_label);
  for (int k = 0; k < slices; ++k) t.x.push_back((k + 0.5) * g.face_width_m / slices * 1e3);
  for (std::size_t i = 0; i < rows; ++i) {
    const double s = path * static_cast<double>(i) / static_cast<double>(rows - 1);
    t.y.push_back(contact.pinion_roll_length(s) / contact.base_radius1() * kDeg);
  }
  t.z.assign(rows, std::vector<double>(static_cast<std::size_t>(slices),
                                       std::numeric_limits<double>::quiet_NaN()));
  const double merge = 1e-9 * path;
  for (std::size_t k = 0; k < per_slice.size(); ++k) {
    auto& pts = per_slice[k];
    std::sort(pts.begin(), pts.end());
    std::vector<std::pair<double, double>> merged;
    for (const auto& pt : pts)
      if (!merged.empty() && pt.first - merged.back().first < merge)
        merged.back().second = std::max(merged.back().second, pt.second);
      else
        merged.push_back(pt);
    if (merged.empty()) continue;
    for (std::size_t i = 0; i < rows; ++i) {
      const double s = path * static_cast<double>(i) / static_cast<double>(rows - 1);
      if (s < merged.front().first - merge || s > merged.back().first + merge) continue;
      auto hi = std::lower_bound(merged.begin(), merged.end(), std::pair{s, -1e300});
      if (hi == merged.end()) hi = std::prev(hi);
      const auto lo = hi == merged.begin() ? hi : std::prev(hi);
      const double f = hi->first > lo->first ? (s - lo->first) / (hi->first - lo->first) : 0.0;
      t.z[i][k] = lo->second + std::clamp(f, 0.0, 1.0) * (hi->second - lo->second);
    }
  }
  return t;
}

void add_flank_maps(AnalysisOutput& out, const ToothContactRunResult& r) {
  const auto& res = r.torques[r.distribution_index];
  const int cycles = r.model->contact->cycles();
  const std::string envelope =
      cycles > 1 ? fmt::format(", largest over the {} cycles of the hunting period", cycles) : "";
  Plot load = plot("line_load_map",
                   fmt::format("Line load over the flank of gear 1 (contact pattern) at T1 = "
                               "{:.6g} N m{}",
                               res.torque_nm, envelope),
                   "face position [mm]", "roll angle of gear 1 [deg]");
  load.traces.push_back(flank_map(
      r, res, [](const gear::ContactPoint& c) { return c.line_load_n_per_m * 1e-3; },
      "line load [N/mm]"));
  Plot pressure = plot("pressure_map",
                       fmt::format("Peak contact pressure over the flank of gear 1 at T1 = "
                                   "{:.6g} N m{}",
                                   res.torque_nm, envelope),
                       "face position [mm]", "roll angle of gear 1 [deg]");
  pressure.traces.push_back(flank_map(
      r, res, [](const gear::ContactPoint& c) { return c.pressure_pa * 1e-6; },
      "contact pressure [MPa]"));
  out.plots.push_back(std::move(load));
  out.plots.push_back(std::move(pressure));
}

void add_plots(AnalysisOutput& out, const ToothContactRunResult& r) {
  const double pitch_deg = 360.0 / r.model->pair.pair->teeth1;
  const double rb1 = r.model->contact->force_radius();
  Plot te = plot("transmission_error", "Loaded transmission error over the mesh cycle",
                 "rotation of gear 1 [deg]", "TE of gear 1 [urad]");
  Plot k = plot("mesh_stiffness", "Mesh stiffness (tangent) over the mesh cycle",
                "rotation of gear 1 [deg]", "mesh stiffness [N/m]");
  Plot face = plot("face_load", "Face-load distribution (mean over the cycle)",
                   "face position [mm]", "line load [N/mm]");
  for (const auto& res : r.torques) {
    const std::string name = fmt::format("{:.6g} N m", res.torque_nm);
    te.traces.push_back(
        line(name, scaled(res.mesh_fraction, pitch_deg), scaled(res.te_m, 1e6 / rb1)));
    k.traces.push_back(
        line(name, scaled(res.mesh_fraction, pitch_deg), res.stiffness_tangent_n_per_m));
    std::vector<double> y;
    const std::size_t n = res.face_load_n_per_m.size();
    for (std::size_t i = 0; i < n; ++i)
      y.push_back((static_cast<double>(i) + 0.5) * r.model->pair.geometry.face_width_m * 1e3 /
                  static_cast<double>(n));
    face.traces.push_back(line(name, y, scaled(res.face_load_n_per_m, 1e-3)));
  }
  te.traces.push_back(
      line("unloaded (geometric) TE", scaled(r.torques.front().mesh_fraction, pitch_deg),
           scaled(r.torques.front().unloaded_te_m, 1e6 / rb1), Trace::Mode::Lines, "dash"));
  out.plots.push_back(std::move(te));
  out.plots.push_back(std::move(k));
  out.plots.push_back(std::move(face));
  if (r.torques.size() > 1 || r.te_correlation) {
    Plot harris =
        plot("te_vs_torque", "TE peak-to-peak and mesh-order harmonics versus torque (Harris map)",
             "torque of gear 1 [N m]", "TE of gear 1 [urad]");
    std::vector<double> torque, pp;
    for (const auto& res : r.torques) {
      torque.push_back(res.torque_nm);
      pp.push_back(peak_peak(res.te_m) / rb1 * 1e6);
    }
    harris.traces.push_back(line("peak-to-peak", torque, pp, Trace::Mode::LinesMarkers));
    for (std::size_t k2 = 0; k2 < r.harmonics_m.front().size(); ++k2) {
      std::vector<double> a;
      for (const auto& h : r.harmonics_m) a.push_back(h[k2] / rb1 * 1e6);
      harris.traces.push_back(line(fmt::format("order {} (0-peak)", k2 + 1), torque, a,
                                   Trace::Mode::LinesMarkers, "dash"));
    }
    if (r.te_correlation) add_measured_te_traces(harris, *r.te_correlation);
    out.plots.push_back(std::move(harris));
  }
  add_flank_maps(out, r);
}

// Bevel / hypoid pairs: what the virtual pair and the mounting errors make of the pair, and the
// first-order pattern centre (docs/theory.md §15.9).
std::string bevel_note(const ToothContactModel& m) {
  const gear::ToothContact& tc = *m.contact;
  const gear::GearPairGeometry& v = tc.geometry();
  const gear::MountingEffect& me = tc.mounting();
  const gear::EaseOff& e = m.options.ease_off;
  const auto [xi, eta] = gear::ease_off_centre(e, 0.5 * me.profile_gradient * v.path_of_contact_m,
                                               0.5 * me.lead_slope_m);
  return fmt::format(
      "'{}': {} pair through its virtual cylindrical pair at mid face (ISO 10300-1; docs/theory.md "
      "§15.9, an approximation: no cone taper of the compliance, straight contact lines, hypoid "
      "offset via the virtual pair only): z_v = {:.4g} / {:.4g}, centre distance {:.6g} m, "
      "eps_alpha = {:.4g}, F_bt = T1 / {:.6g} m. Mounting errors H = {:.6g} m, V = {:.6g} m, "
      "J = {:.6g} m, Delta Sigma = {:.4g} deg (Gleason: H, J > 0 out of mesh; {} pinion flank "
      "loaded): approach d.n = {:.4g} m, lead slope {:.4g} m (heel minus toe), centre distance "
      "change {:.4g} m, profile gradient {:.4g}; first-order pattern centre (15.24) xi = {:.3g}, "
      "eta = {:.3g} (NaN: the ease-off has no bounded minimum).",
      m.pair.pair->name, gear::to_string(m.pair.geometry.spec.type), v.pinion.virtual_teeth,
      v.wheel.virtual_teeth, v.centre_distance_m, v.transverse_contact_ratio, tc.force_radius(),
      m.options.mounting.h_m, m.options.mounting.v_m, m.options.mounting.j_m,
      m.options.mounting.shaft_angle_rad / units::kRadPerDegree,
      m.options.mounting.pinion_concave_loaded ? "concave" : "convex", me.normal_approach_m,
      me.lead_slope_m, me.centre_distance_change_m, me.profile_gradient, xi + 0.0, eta + 0.0);
}

}  // namespace

AnalysisOutput tooth_contact_output(const model::Model& /*model*/,
                                    const ToothContactSettings& /*settings*/,
                                    const ToothContactRunResult& r, const Context& context) {
  AnalysisOutput out;
  for (const auto& res : r.torques)
    if (res.status != Status::Ok) {
      out.status = res.status;
      out.message = fmt::format("T1 = {:.6g} N m: {}", res.torque_nm, res.message);
      return out;
    }
  out.tables.push_back(summary_table(r));
  out.tables.push_back(te_table(r));
  out.tables.push_back(harmonics_table(r));
  if (r.te_correlation) out.tables.push_back(te_correlation_table(*r.te_correlation));
  out.tables.push_back(face_load_table(r));
  out.tables.push_back(distribution_table(r));
  add_plots(out, r);
  const auto& m = *r.model;
  const auto& g = m.pair.geometry;
  out.notes.push_back(fmt::format(
      "'{}': slice model, {} mesh positions per cycle x {} slices over b = {:.6g} m, {} mesh "
      "cycle{}; tooth compliance by the potential-energy method with fillet foundation and "
      "Hertzian approach per slice (docs/theory.md §15); {}.",
      m.pair.pair->name, m.options.positions, m.options.slices, g.face_width_m, m.contact->cycles(),
      m.contact->cycles() == 1 ? "" : "s (hunting period)", coupling_text(m)));
  out.notes.push_back(compliance_note(m));
  out.notes.push_back(misalignment_note(m));
  if (m.contact->bevel()) out.notes.push_back(bevel_note(m));
  if (r.te_correlation) out.notes.push_back(te_correlation_note(context.name(), *r.te_correlation));
  for (const auto& res : r.torques) {
    const double covered = [&] {
      int n = 0;
      for (double w : res.face_load_n_per_m) n += w > 0.0;
      return static_cast<double>(n) / static_cast<double>(res.face_load_n_per_m.size());
    }();
    if (covered < 1.0)
      out.notes.push_back(fmt::format(
          "T1 = {:.6g} N m: the contact covers {:.0f} % of the face width (the rest never "
          "touches over the cycle: crowning, misalignment or end relief larger than the "
          "deflection).",
          res.torque_nm, 100.0 * covered));
  }
  return out;
}

}  // namespace geardyn::analyses
