#include "geardyn/analyses/gear_pair.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <vector>

#include "geardyn/analyses/gear_helpers.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/gear/geometry.hpp"
#include "geardyn/gear/tooth_forces.hpp"

namespace geardyn::analyses {

namespace {

using units::kTwoPi;
/// Degrees per radian, as the tables have always multiplied by it (bit for bit).
constexpr double kDeg = 180.0 / units::kPi;

/// The STE the dynamic model uses, with the mesh stiffness it implies, over one mesh cycle.
Table ste_table(const PairModel& pm, const std::string& table_name) {
  const gear::SteCurve& ste = *pm.ste;
  const std::size_t n = ste.size();
  const double pitch = kTwoPi / pm.pair->teeth1;
  Table t;
  t.name = table_name;
  t.title = fmt::format(
      "Static transmission error and mesh stiffness of '{}' over one mesh cycle "
      "({}; sample 0: a tooth pair enters contact)",
      pm.pair->name, pm.ste_source_label());
  std::vector<double> u(n), angle(n), e(n), eg(n), k(n);
  for (std::size_t j = 0; j < n; ++j) {
    u[j] = static_cast<double>(j) / static_cast<double>(n);
    angle[j] = u[j] * pitch * kDeg;
    e[j] = ste.ste_m()[j];
    eg[j] = ste.geometric_te_m()[j];
    k[j] = pm.static_force_n / (e[j] - eg[j]);
  }
  t.add("mesh_fraction", "", u);
  t.add("pinion_angle_deg", "deg", angle);
  t.add("ste_m", "m", e);
  t.add("ste_rad", "rad", scaled(e, 1.0 / pm.base_radius1_m));
  t.add("geometric_te_m", "m", eg);
  t.add("stiffness_n_per_m", "N/m", k);
  return t;
}

Table iso_table(const std::vector<PairModel>& pairs) {
  Table t;
  t.name = "iso_stiffness";
  t.title = "ISO 6336-1:2019 Method B tooth stiffness (per unit face width in N/(mm um))";
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols(16);
  for (const PairModel& pm : pairs) {
    const gear::IsoStiffness& s = pm.stiffness.iso;
    names.push_back(pm.pair->name);
    const double v[] = {s.normal_virtual_teeth_pinion,
                        s.normal_virtual_teeth_wheel,
                        s.flexibility_q_prime,
                        s.theoretical_single_stiffness,
                        s.correction_factor,
                        s.blank_factor,
                        s.basic_rack_factor,
                        s.helix_factor,
                        s.material_factor,
                        s.load_factor,
                        s.single_stiffness,
                        s.mesh_stiffness_alpha,
                        s.mesh_stiffness_beta,
                        s.single_stiffness_n_per_m,
                        s.mesh_stiffness_n_per_m,
                        pm.stiffness.mean_stiffness_n_per_m};
    for (std::size_t c = 0; c < cols.size(); ++c) cols[c].push_back(v[c]);
  }
  t.add_text("pair", names);
  const char* col_names[] = {"normal_virtual_teeth1",
                             "normal_virtual_teeth2",
                             "flexibility_q_prime_mm_um_per_n",
                             "theoretical_single_stiffness_n_per_mm_um",
                             "correction_factor_cm",
                             "blank_factor_cr",
                             "basic_rack_factor_cb",
                             "helix_factor",
                             "material_factor",
                             "load_factor",
                             "single_stiffness_n_per_mm_um",
                             "mesh_stiffness_alpha_n_per_mm_um",
                             "mesh_stiffness_beta_n_per_mm_um",
                             "single_stiffness_n_per_m",
                             "mesh_stiffness_n_per_m",
                             "curve_mean_stiffness_n_per_m"};
  const char* units[] = {"", "", "mm um/N",   "N/(mm um)", "",          "",    "",    "",
                         "", "", "N/(mm um)", "N/(mm um)", "N/(mm um)", "N/m", "N/m", "N/m"};
  for (std::size_t c = 0; c < cols.size(); ++c) t.add(col_names[c], units[c], cols[c]);
  return t;
}

/// The mesh-stiffness table, its plots and the notes of one pair.
void add_pair_output(AnalysisOutput& out, const PairModel& pm, bool several) {
  const std::string suffix = several ? "_" + pm.pair->name : "";
  Table ste = ste_table(pm, "mesh_stiffness" + suffix);
  const std::vector<double>& angle = ste.column("pinion_angle_deg").numbers;

  Plot k;
  k.name = "mesh_stiffness" + suffix;
  k.title = fmt::format("Mesh stiffness of '{}' over one mesh cycle", pm.pair->name);
  k.x_label = "rotation of gear 1 [deg]";
  k.y_label = "mesh stiffness [N/m]";
  k.traces.push_back(line(pm.ste_from_file      ? "from the STE file"
                          : pm.ste_from_ltca    ? "from the LTCA table"
                          : pm.ste_from_contact ? "loaded tooth contact"
                                                : "ISO 6336 (synthetic STE)",
                          angle, ste.column("stiffness_n_per_m").numbers));
  if (pm.ste_from_file || pm.ste_from_ltca || pm.ste_from_contact) {
    // The ISO-based curve for comparison (unshifted: its sample 0 is the contact entry).
    std::vector<double> iso_angle = scaled(pm.stiffness.pinion_angle_rad, kDeg);
    k.traces.push_back(line("ISO 6336-1 (geometry)", iso_angle, pm.stiffness.stiffness_n_per_m,
                            Trace::Mode::Lines, "dash"));
  }
  Plot e;
  e.name = "ste" + suffix;
  e.title = fmt::format("Static transmission error of '{}' at T1 = {:.6g} N m", pm.pair->name,
                        pm.pair->torque);
  e.x_label = "rotation of gear 1 [deg]";
  e.y_label = "STE along the line of action [um]";
  e.traces.push_back(line("STE", angle, scaled(ste.column("ste_m").numbers, 1e6)));
  out.tables.push_back(std::move(ste));
  out.plots.push_back(std::move(k));
  out.plots.push_back(std::move(e));

  const gear::GearPairGeometry& g = pm.geometry;
  const double k_mean = mean_mesh_stiffness(pm);
  out.notes.push_back(fmt::format(
      "'{}': contact ratio eps_alpha = {:.4f}, eps_beta = {:.4f}, eps_gamma = {:.4f}; mesh "
      "frequency = {} x speed of gear 1; F_s = T1 / r_b1 = {:.6g} N (r_b1 = {:.6g} m).",
      pm.pair->name, g.transverse_contact_ratio, g.overlap_ratio, g.total_contact_ratio,
      pm.pair->teeth1, pm.static_force_n, pm.base_radius1_m));
  out.notes.push_back(fmt::format(
      "'{}': mean mesh stiffness {:.6g} N/m from the {} (ISO 6336-1 c_gamma_alpha b = {:.6g} "
      "N/m); the time-varying ISO curve is a single-pair law with load sharing, not a "
      "loaded tooth-contact analysis.",
      pm.pair->name, k_mean,
      pm.ste_from_file      ? fmt::format("STE file {}", pm.pair->ste_file)
      : pm.ste_from_ltca    ? fmt::format("LTCA table {}", pm.pair->ltca_file)
      : pm.ste_from_contact ? std::string("loaded tooth contact analysis")
                            : std::string("synthetic STE"),
      pm.stiffness.iso.mesh_stiffness_n_per_m));
  if (gear::is_bevel(g.spec.type))
    out.notes.push_back(fmt::format(
        "'{}': bevel / hypoid geometry as the virtual cylindrical pair at mid face (ISO "
        "10300-1, Tredgold); the ISO 6336 stiffness is applied to that virtual pair, outside "
        "ISO 6336's scope.",
        pm.pair->name));
  if (!std::isnan(pm.pair->inertia1) && !std::isnan(pm.pair->inertia2)) {
    const double fn = mesh_natural_frequency_hz(pm);
    out.notes.push_back(fmt::format(
        "'{}': mesh natural frequency sqrt(k_mean / m_e) / 2 pi = {:.6g} Hz (m_e = {:.6g} kg), "
        "met by the mesh frequency at gear 1 speed {}.",
        pm.pair->name, fn, pm.equivalent_mass_kg(), rpm_text(60.0 * fn / pm.pair->teeth1)));
  }
}

}  // namespace

double mean_mesh_stiffness(const PairModel& pm) {
  return pm.static_force_n * pm.ste->mean_inverse_elastic_per_m();
}

double mesh_natural_frequency_hz(const PairModel& pm) {
  if (std::isnan(pm.pair->inertia1) || std::isnan(pm.pair->inertia2))
    return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(pm.static_force_n * pm.ste->mean_inverse_elastic_per_m() /
                   pm.equivalent_mass_kg()) /
         kTwoPi;
}

GearPairResult run_gear_pair(const model::Model& model, const GearPairSettings& settings,
                             const Context& context) {
  GearPairResult r;
  Progress& progress = context.progress();
  if (settings.pair.empty()) {
    progress.start("gear pairs", model.gear_pairs.size());
    for (std::size_t i = 0; i < model.gear_pairs.size(); ++i) {
      r.pairs.push_back(build_pair_model(model, i));
      progress.update(i + 1);
    }
  } else {
    progress.start("gear pairs", 1);
    r.pairs.push_back(build_pair_model(model, pair_index(model, settings.pair)));
    progress.update(1);
  }
  progress.finish();
  return r;
}

AnalysisOutput gear_pair_output(const model::Model& /*model*/, const GearPairSettings& /*settings*/,
                                const GearPairResult& result, const Context& /*context*/) {
  const std::vector<PairModel>& pairs = result.pairs;
  AnalysisOutput out;
  std::vector<gear::GearPairGeometry> geometries, force_pairs;
  std::vector<gear::MeshLoadCase> loads;
  for (const PairModel& pm : pairs) {
    geometries.push_back(pm.geometry);
    force_pairs.push_back(pm.geometry);
    force_pairs.push_back(pm.geometry);
    loads.push_back(pm.drive);
    loads.push_back(pm.coast);
  }
  out.tables.push_back(gear::geometry_table(geometries));
  // Each member's own face width (b1, b2); the contact uses the smaller (contact_face_width_m).
  std::vector<double> face_widths;
  for (const PairModel& pm : pairs) {
    face_widths.push_back(pm.pair->face_width1);
    face_widths.push_back(pm.pair->face_width2);
  }
  out.tables.back().add("face_width_m", "m", std::move(face_widths));
  out.tables.push_back(gear::tooth_force_table(force_pairs, loads));
  out.tables.push_back(iso_table(pairs));
  for (const PairModel& pm : pairs) add_pair_output(out, pm, pairs.size() != 1);
  return out;
}

}  // namespace geardyn::analyses
