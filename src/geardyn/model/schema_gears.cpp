// The model file's [[gear_pairs]] section: the gear pairs of the mesh-excitation chain.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/model/schema_builder.hpp"
#include "geardyn/model/schema_sections.hpp"

namespace geardyn::model {
namespace {

using namespace keys;  // NOLINT: the declaration table reads as a table

constexpr Unit kTorque{"N m", 1.0};
const std::vector<std::string> kCylindrical = {"spur", "helical"};
const std::vector<std::string> kSpiral = {"spiral_bevel", "hypoid"};

void finish_gear_pair(GearPair& g, const TableContext& t) {
  // One width for both gears, or one per gear; the contact (and ISO 6336-1 stiffness, overlap
  // ratio) uses the common width, the smaller of the two (ISO 6336-1:2019, b: "the smaller of
  // the face widths of pinion and wheel").
  if (t.has("face_width")) {
    g.face_width1 = g.face_width2 = g.face_width;
  } else {
    if (t.has("face_width1") != t.has("face_width2"))
      t.fail(t.has("face_width1") ? "face_width1" : "face_width2",
             "face_width1 and face_width2 together (or one face_width for both gears)",
             fmt::format("only {}", t.has("face_width1") ? "face_width1" : "face_width2"));
    g.face_width = std::min(g.face_width1, g.face_width2);
  }
  const bool bevel = g.type == GearType::StraightBevel || g.type == GearType::SpiralBevel ||
                     g.type == GearType::Hypoid;
  // ste_source chooses between the two STEs computed here; a file (ste_file, ltca_file) is
  // the STE itself, so an explicit ste_source with a file is a contradiction.
  for (const char* file : {"ste_file", "ltca_file"})
    if (t.has("ste_source") && t.has(file))
      t.fail("ste_source", fmt::format("no ste_source with an {} (the file is the STE)", file),
             fmt::format("ste_source and an {}", file));
  if (g.internal && bevel)
    t.fail("internal", "false for bevel and hypoid gears (internal gears are spur or helical)",
           "true");
  if (g.internal && g.teeth2 <= g.teeth1)
    t.fail("teeth2",
           fmt::format("more teeth than gear 1 (teeth1 = {}) for an internal gear pair", g.teeth1),
           std::to_string(g.teeth2));
  if (t.has("rim_thickness") != t.has("web_thickness"))
    t.fail(t.has("rim_thickness") ? "web_thickness" : "rim_thickness",
           "rim_thickness and web_thickness together (a gear blank with a web), or neither",
           "only one of them");
  // An LTCA table (ltca_file) is an STE source like ste_file: the two exclude each other and
  // ste_source = "tooth_contact"; it takes ste_interpolation and ste_extrapolation.
  if (t.has("ltca_file") && t.has("ste_file"))
    t.fail("ltca_file", "either an ltca_file or an ste_file (each gives the STE)", "both");
  if (t.has("ltca_file") && t.has("ste_speed_rpm"))
    t.fail("ste_speed_rpm", "no ste_speed_rpm with an ltca_file (its abscissa is the angle)",
           "ste_speed_rpm");
  if (!t.has("ste_file") && !t.has("ltca_file") &&
      (t.has("ste_interpolation") || t.has("ste_extrapolation") || t.has("ste_speed_rpm")))
    t.fail(t.has("ste_interpolation")   ? "ste_interpolation"
           : t.has("ste_extrapolation") ? "ste_extrapolation"
                                        : "ste_speed_rpm",
           "an ste_file (or ltca_file) to apply to (the synthetic STE from ISO 6336 is sampled "
           "uniformly)",
           "no ste_file");
}

std::vector<Field> gear_pair_fields_1() {
  return {
      name_key("Unique gear-pair name.").required().to(&GearPair::name),
      choice("type", kGearTypes, "Gear type; selects the keys below.")
          .def("\"spur\"")
          .to_enum(&GearPair::type, {GearType::Spur, GearType::Helical, GearType::StraightBevel,
                                     GearType::SpiralBevel, GearType::Hypoid}),
      boolean("internal", "Gear 2 is an internal gear (ring gear).")
          .def("false")
          .only_in(kCylindrical)
          .to(&GearPair::internal),
      integer("teeth1", "Number of teeth z1 of gear 1 (pinion).")
          .required()
          .ge(3)
          .le(100000)
          .to(&GearPair::teeth1),
      integer("teeth2", "Number of teeth z2 of gear 2 (internal gear: its tooth count).")
          .required()
          .ge(3)
          .le(100000)
          .to(&GearPair::teeth2),
      number("module", kMetre,
             "Normal module m_n (spur, helical); outer transverse module m_e at the heel "
             "(bevel; hypoid: the wheel's).")
          .required()
          .gt(0)
          .to(&GearPair::module),
      number("pressure_angle_deg", kDegree, "Normal pressure angle of the basic rack.")
          .def("20.0")
          .gt(0)
          .lt(45)
          .to(&GearPair::pressure_angle),
      number("helix_angle_deg", kDegree,
             "Helix angle (helical), mean spiral angle (spiral bevel), the wheel's mean "
             "spiral angle (hypoid).")
          .required()
          .gt(0)
          .lt(90)
          .only_in(kHelical)
          .to(&GearPair::helix_angle),
      number("pinion_spiral_angle_deg", kDegree,
             "Hypoid: the pinion's mean spiral angle (> the wheel's helix_angle_deg).")
          .required()
          .gt(0)
          .lt(90)
          .only_in({"hypoid"})
          .to(&GearPair::pinion_spiral_angle),
      choice("hand", {"right", "left"}, "Hand of gear 1's helix or spiral.")
          .def("\"right\"")
          .only_in(kHelical)
          .to_enum(&GearPair::hand, {Hand::Right, Hand::Left}),
      choice("rotation", {"cw", "ccw"},
             "Direction of rotation of gear 1, seen from its back (cone base) towards "
             "the apex; with `hand` it sets which flank is loaded and the sign of the "
             "axial force.")
          .def("\"cw\"")
          .only_in(kSpiral)
          .to_enum(&GearPair::rotation, {GearRotation::Clockwise, GearRotation::CounterClockwise}),
      number("face_width", kMetre,
             "Face width b of both gears (or give face_width1 and face_width2).")
          .gt(0)
          .to(&GearPair::face_width),
      number("face_width1", kMetre,
             "Face width b1 of gear 1 when the widths differ (with face_width2); the contact "
             "width is the smaller one (ISO 6336-1).")
          .gt(0)
          .to(&GearPair::face_width1),
      number("face_width2", kMetre, "Face width b2 of gear 2 (with face_width1).")
          .gt(0)
          .to(&GearPair::face_width2),
      number("profile_shift1", kNoUnit, "Profile shift coefficient x1 of gear 1.")
          .def("0.0")
          .ge(-2.0)
          .le(2.0)
          .to(&GearPair::profile_shift1),
      number("profile_shift2", kNoUnit,
             "Profile shift coefficient x2 of gear 2 (ISO 21771 sign for internal "
             "gears; bevel gears need x2 = -x1).")
          .def("0.0")
          .ge(-2.0)
          .le(2.0)
          .to(&GearPair::profile_shift2),
      number("addendum_coefficient", kNoUnit, "Addendum of the basic rack h_aP / m_n.")
          .def("1.0")
          .gt(0)
          .le(2.0)
          .to(&GearPair::addendum_coefficient),
      number("dedendum_coefficient", kNoUnit, "Dedendum of the basic rack h_fP / m_n.")
          .def("1.25")
          .gt(0)
          .le(2.5)
          .to(&GearPair::dedendum_coefficient),
      number("centre_distance", kMetre,
             "Working centre distance (must leave backlash >= 0 for the profile shifts).")
          .gt(0)
          .note("the zero-backlash value for x1 + x2")
          .only_in(kCylindrical)
          .to(&GearPair::centre_distance),
      number("shaft_angle_deg", kDegree, "Shaft angle Sigma.")
          .def("90.0")
          .gt(0)
          .lt(180)
          .only_in(kBevel)
          .to(&GearPair::shaft_angle),
      number("outer_cone_distance", kMetre,
             "Outer cone distance R_e (checked against m_e z1 / (2 sin delta1)).")
          .gt(0)
          .note("from module, teeth and shaft angle")
          .only_in(kBevel)
          .to(&GearPair::outer_cone_distance),
  };
}

std::vector<Field> gear_pair_fields_2() {
  return {
      number("torque", kTorque, "Torque on gear 1 (drive side).")
          .required()
          .gt(0)
          .to(&GearPair::torque),
      number("inertia1", kInertia,
             "Polar moment of inertia of gear 1 (with what turns rigidly with it); "
             "may be inf.")
          .gt(0)
          .allow_infinity()
          .note("needed by mesh_force / mesh_harmonics with model = \"dynamic\"")
          .to(&GearPair::inertia1),
      number("inertia2", kInertia, "Polar moment of inertia of gear 2; may be inf.")
          .gt(0)
          .allow_infinity()
          .note("needed by mesh_force / mesh_harmonics with model = \"dynamic\"")
          .to(&GearPair::inertia2),
      reference("material1", Ref::Material,
                "Material of gear 1 (its Young's modulus enters the ISO 6336 stiffness).")
          .note("steel, E = 206 GPa")
          .to(&GearPair::material1),
      reference("material2", Ref::Material, "Material of gear 2.")
          .note("steel, E = 206 GPa")
          .to(&GearPair::material2),
      number("stiffness_correction", kNoUnit,
             "ISO 6336-1 correction factor C_M (measured / theoretical stiffness) of the ISO "
             "stiffness (the gear_pair table; the STE with ste_source = \"iso\").")
          .def("0.8")
          .gt(0)
          .le(2.0)
          .to(&GearPair::stiffness_correction),
      number("application_factor", kNoUnit,
             "ISO 6336-1 application factor K_A in the light-load correction.")
          .def("1.0")
          .ge(1.0)
          .le(10.0)
          .to(&GearPair::application_factor),
      boolean("load_correction",
              "Apply ISO 6336-1's stiffness reduction for line loads F_t K_A / b below "
              "100 N/mm.")
          .def("true")
          .to(&GearPair::load_correction),
      number("rim_thickness", kMetre,
             "Rim thickness s_R of a gear blank with a web (ISO 6336-1 C_R; give "
             "web_thickness too).")
          .gt(0)
          .note("solid disc, C_R = 1")
          .to(&GearPair::rim_thickness),
      number("web_thickness", kMetre, "Web thickness b_s of a gear blank with a web.")
          .gt(0)
          .note("solid disc, C_R = 1")
          .to(&GearPair::web_thickness),
      text("ste_file",
           "Static transmission error over one mesh cycle, CSV relative to the model "
           "file (format in docs/input-files.md: an angle_deg or angle_rad column of gear 1's "
           "rotation, or a time_s or time_ms column (with ste_speed_rpm), over one mesh "
           "cycle, ste_<unit> or ste_<unit>@<torque>Nm columns; "
           "angular STE is scaled by gear 1's base radius); the first row is the tooth "
           "entering contact.")
          .note("synthetic STE e = F_s / k from the ISO 6336 mesh stiffness")
          .to(&GearPair::ste_file),
      text("ltca_file",
           "LTCA table exported by another tool (KISSsoft, MASTA, Romax, Gleason / Klingelnberg), "
           "CSV relative to the model file (format in docs/input-files.md): loaded TE and "
           "optionally the mesh stiffness over gear 1's angle in one mesh cycle x torque x the "
           "mounting errors H, V, J, one row per sample on a regular grid; interpolated at the "
           "pair's torque and [gear_pairs.contact] mounting_h, mounting_v, mounting_j, it gives "
           "the STE like an ste_file (ste_extrapolation allows values outside the table).")
          .note("no LTCA table")
          .to(&GearPair::ltca_file),
      choice("ste_source", {"tooth_contact", "iso"},
             "Where the STE comes from without an ste_file or ltca_file: \"tooth_contact\", the "
             "loaded tooth contact analysis of the pair at its torque (its first mesh cycle: the "
             "loaded TE and the secant mesh stiffness, with the flank modifications and "
             "misalignment of [gear_pairs.flank1/2] and [gear_pairs.contact]; bevel and hypoid "
             "pairs through their virtual cylindrical pair); \"iso\", synthetic e = F_s / k from "
             "the ISO 6336-1 mesh stiffness curve (stiffness_correction, load_correction, "
             "rim_thickness, web_thickness), no modifications.")
          .def("\"tooth_contact\"")
          .to_enum(&GearPair::ste_source, {SteSourceKind::ToothContact, SteSourceKind::Iso}),
      choice("ste_interpolation", {"linear", "hold"},
             "How the STE file is read between its rows: periodic linear, or each row "
             "held to the next (contact steps).")
          .def("\"linear\"")
          .to_enum(&GearPair::ste_interpolation,
                   {SteInterpolationKind::Linear, SteInterpolationKind::Hold}),
      boolean("ste_extrapolation",
              "Allow a torque outside the file's torques (linear extrapolation).")
          .def("false")
          .to(&GearPair::ste_extrapolation),
      number("ste_shift", kNoUnit,
             "Moves the start of the STE cycle (the tooth entering contact) by this "
             "fraction of a mesh cycle.")
          .def("0.0")
          .ge(0)
          .lt(1)
          .to(&GearPair::ste_shift),
      number("ste_speed_rpm", kRpm,
             "Speed of gear 1 while an STE file with a time abscissa (time_s, time_ms) "
             "was recorded: one mesh period is 60 / (speed teeth1) s.")
          .gt(0)
          .note("required with a time abscissa")
          .to(&GearPair::ste_speed),
      integer("ste_samples", "Samples of the STE per mesh cycle.")
          .ge(16)
          .le(100000)
          .note("512 for the synthetic STE; the file's rows per cycle")
          .to(&GearPair::ste_samples),
      number("mesh_damping_ratio", kNoUnit,
             "Damping ratio zeta of the mesh: c = 2 zeta sqrt(k_mean m_e).")
          .def("0.08")
          .ge(0)
          .le(1.0)
          .to(&GearPair::mesh_damping_ratio),
      number("backlash", kMetre,
             "Backlash along the line of action: back-side contact when the DTE falls "
             "below -backlash.")
          .gt(0)
          .note("no back-side contact")
          .to(&GearPair::backlash),
  };
}

const std::vector<std::string> kShapes = {"linear", "parabolic"};

F relief_shape(const char* name, const char* what, ReliefShapeKind FlankModificationSpec::*member) {
  return choice(name, kShapes,
                fmt::format("Shape of the {}: linear or parabolic growth from its start.", what))
      .def("\"linear\"")
      .to_enum(member, {ReliefShapeKind::Linear, ReliefShapeKind::Parabolic});
}

Section flank_section(const char* name, const char* gear, FlankModificationSpec GearPair::*member) {
  const std::string title = fmt::format("[gear_pairs.{}]", name);
  return S(name, SectionKind::Table, title,
           fmt::format(
               "Flank modifications of gear {} (its loaded flanks), used by the loaded tooth "
               "contact analysis (type = \"tooth_contact\"; docs/theory.md §15): material "
               "removed normal to the flank, in metres (micrometres are 1e-6). Profile "
               "modifications run over the active profile (the part of the flank that meshes), "
               "lead modifications over the face width b, from the face end where the contact "
               "lines enter (y = 0) to y = b.",
               gear))
      .in_table(member)
      .located(&FlankModificationSpec::where)
      .fields({
          number("tip_relief", kMetre, "Tip relief C_a at the tip circle.")
              .def("0.0")
              .ge(0)
              .to(&FlankModificationSpec::tip_relief),
          number("tip_relief_start_diameter", kMetre,
                 "Diameter where the tip relief starts (on the active profile).")
              .gt(0)
              .note("give it or tip_relief_start_roll_angle_deg with tip_relief")
              .to(&FlankModificationSpec::tip_relief_start_diameter),
          number("tip_relief_start_roll_angle_deg", kDegree,
                 "Roll angle (rho / r_b) where the tip relief starts.")
              .gt(0)
              .note("see tip_relief_start_diameter")
              .to(&FlankModificationSpec::tip_relief_start_roll_angle),
          relief_shape("tip_relief_shape", "tip relief", &FlankModificationSpec::tip_relief_shape),
          number("root_relief", kMetre,
                 "Root relief C_f at the start of the active profile (the lowest point that "
                 "meshes).")
              .def("0.0")
              .ge(0)
              .to(&FlankModificationSpec::root_relief),
          number("root_relief_start_diameter", kMetre,
                 "Diameter where the root relief starts (on the active profile).")
              .gt(0)
              .note("give it or root_relief_start_roll_angle_deg with root_relief")
              .to(&FlankModificationSpec::root_relief_start_diameter),
          number("root_relief_start_roll_angle_deg", kDegree,
                 "Roll angle (rho / r_b) where the root relief starts.")
              .gt(0)
              .note("see root_relief_start_diameter")
              .to(&FlankModificationSpec::root_relief_start_roll_angle),
          relief_shape("root_relief_shape", "root relief",
                       &FlankModificationSpec::root_relief_shape),
          number("profile_crowning", kMetre,
                 "Profile crowning C_alpha: parabolic over the active profile, 0 in its middle.")
              .def("0.0")
              .ge(0)
              .to(&FlankModificationSpec::profile_crowning),
          number("lead_crowning", kMetre,
                 "Lead crowning C_beta: parabolic over the face width, 0 at mid face.")
              .def("0.0")
              .ge(0)
              .to(&FlankModificationSpec::lead_crowning),
          number("lead_slope", kMetre,
                 "Helix slope modification f_Hbeta: removal growing linearly across the face "
                 "(-f/2 at y = 0, +f/2 at y = b; positive unloads the y = b end).")
              .def("0.0")
              .to(&FlankModificationSpec::lead_slope),
          number("end_relief", kMetre, "End relief C_I at both face ends.")
              .def("0.0")
              .ge(0)
              .to(&FlankModificationSpec::end_relief),
          number("end_relief_length", kMetre,
                 "Length of the end relief from each face end (<= b / 2).")
              .def("0.0")
              .ge(0)
              .to(&FlankModificationSpec::end_relief_length),
          relief_shape("end_relief_shape", "end relief", &FlankModificationSpec::end_relief_shape),
          numbers("pitch_deviations", kMetre,
                  "Position deviation of each tooth along the line of action, one value per "
                  "tooth from the tooth in contact at the start (positive: the flank stands "
                  "ahead and contacts early); the contact analysis then runs over the hunting "
                  "period.")
              .def("[]")
              .to(&FlankModificationSpec::pitch_deviations),
          text("topography_file",
               "Topological modification: material removed over roll angle x face position, "
               "CSV relative to the model file (format in docs/input-files.md: roll_angle_deg, "
               "face_mm, removed_um columns on a regular grid); bilinear between its points, "
               "constant beyond its edges, added to the modifications above.")
              .note("no topography")
              .to(&FlankModificationSpec::topography_file),
      })
      .choices(
          {{{{"tip_relief_start_diameter"}, {"tip_relief_start_roll_angle_deg"}}, false, {}},
           {{{"root_relief_start_diameter"}, {"root_relief_start_roll_angle_deg"}}, false, {}}});
}

Section contact_section() {
  return S("contact", SectionKind::Table, "[gear_pairs.contact]",
           "The slice model of the loaded tooth contact analysis (type = \"tooth_contact\"; "
           "docs/theory.md §15): mesh positions, slices, coupling of the slices and the mesh "
           "misalignment.")
      .in_table(&GearPair::contact)
      .located(&ContactModelSpec::where)
      .fields({
          integer("positions", "Mesh positions per mesh cycle.")
              .def("64")
              .ge(4)
              .le(4096)
              .to(&ContactModelSpec::positions),
          integer("slices", "Slices over the face width.")
              .def("40")
              .ge(1)
              .le(1000)
              .to(&ContactModelSpec::slices),
          number("coupling_length", kMetre,
                 "Decay length of the elastic coupling between neighbouring slices of a tooth "
                 "(a Pasternak layer: a point load's deflection decays as exp(-|dy| / length)); "
                 "0: uncoupled slices (Winkler). The analytic route only (the FE route couples "
                 "the slices itself).")
              .note("2.5 m_n, the decay length of the FE route's face influence line (docs/"
                    "theory.md §15.8)")
              .ge(0)
              .to(&ContactModelSpec::coupling_length),
          number("misalignment", kMetre,
                 "Mesh misalignment f_ma in the plane of action: the gap difference along the "
                 "line of action between the face ends (y = b minus y = 0).")
              .def("0.0")
              .to(&ContactModelSpec::misalignment),
          number("axis_inclination_deviation", kMetre,
                 "ISO 1328 / ISO 6336-1 f_Sigma_delta over the face width (in the plane of the "
                 "axes); adds f_Sigma_delta sin(alpha_wt) to the misalignment in the plane of "
                 "action.")
              .def("0.0")
              .to(&ContactModelSpec::axis_inclination_deviation),
          number("axis_deviation", kMetre,
                 "ISO 1328 / ISO 6336-1 f_Sigma_beta over the face width (normal to the plane "
                 "of the axes); adds f_Sigma_beta cos(alpha_wt) to the misalignment in the "
                 "plane of action.")
              .def("0.0")
              .to(&ContactModelSpec::axis_deviation),
          number("mounting_h", kMetre,
                 "Bevel / hypoid mounting error H: the pinion moved along its axis, positive away "
                 "from the crossing point of the axes (Gleason convention; docs/theory.md "
                 "§15.9).")
              .def("0.0")
              .to(&ContactModelSpec::mounting_h),
          number("mounting_v", kMetre,
                 "Bevel / hypoid mounting error V: the pinion moved along the common "
                 "perpendicular of the axes (the offset), positive in the direction in which its "
                 "loaded flank pushes the wheel.")
              .def("0.0")
              .to(&ContactModelSpec::mounting_v),
          number("mounting_j", kMetre,
                 "Bevel / hypoid mounting error J: the wheel moved along its axis, positive away "
                 "from the crossing point of the axes.")
              .def("0.0")
              .to(&ContactModelSpec::mounting_j),
          number("shaft_angle_error_deg", kDegree,
                 "Bevel / hypoid shaft angle error Delta Sigma (positive: a larger shaft angle).")
              .def("0.0")
              .to(&ContactModelSpec::shaft_angle_error),
          boolean("hunting_period",
                  "With pitch deviations, compute the hunting period lcm(z1, z2) mesh cycles "
                  "(false: the first mesh cycle only).")
              .def("true")
              .to(&ContactModelSpec::hunting_period),
          text("deflection_mesh",
               "Name of the [[gear_meshes]] entry of the rotor model that is this pair: the "
               "static deflection of the rotor (shafts, bearings) under the pair's tooth forces "
               "at the analysed torque, without that mesh's spring and with torsion held, tilts "
               "the two gear nodes; their relative tilt in the plane of action times the face "
               "width adds to the misalignment (docs/theory.md §15.7).")
              .note("the misalignment is the given one")
              .to(&ContactModelSpec::deflection_mesh),
          choice("compliance", {"analytic", "fe"},
                 "Compliance of the tooth pairs (docs/theory.md §15.8): \"analytic\", slices "
                 "with the potential-energy tooth, Sainsot's foundation and the shear-layer "
                 "coupling_length; \"fe\", influence coefficients from a tet10 mesh of each "
                 "whole gear (every tooth, fixed at the bore) plus the analytic Hertz term; "
                 "spur external pairs; the slices couple through the FE (coupling_length is not "
                 "used).")
              .def("\"analytic\"")
              .to_enum(&ContactModelSpec::compliance,
                       {ContactComplianceKind::Analytic, ContactComplianceKind::Fe}),
          number("fe_mesh_size", kNoUnit,
                 "compliance = \"fe\": element size at the loaded tooth, in modules (3 "
                 "modules in the rest of the body); 0.35 leaves about 2.6 % discretisation "
                 "error in the compliance, 0.25 about 1.3 % at three times the cost "
                 "(docs/theory.md §15.8).")
              .def("0.35")
              .ge(0.05)
              .le(1.0)
              .to(&ContactModelSpec::fe_mesh_size),
          integer("fe_profile_points",
                  "compliance = \"fe\": load / receiver points over the active profile (the "
                  "influence is interpolated linearly between them).")
              .def("9")
              .ge(3)
              .le(64)
              .to(&ContactModelSpec::fe_profile_points),
          integer("fe_face_points",
                  "compliance = \"fe\": load / receiver points over the face width, hat loads "
                  "between them; 0: one per half module, at least 5.")
              .def("0")
              .ge(0)
              .le(201)
              .to(&ContactModelSpec::fe_face_points),
          integer("fe_teeth",
                  "compliance = \"fe\": 0, mesh the whole gear (the body of Sainsot's "
                  "foundation formula, a full disc fixed at its bore); an odd 1 ... 7, only a "
                  "segment of that many teeth (the loaded tooth in the middle; capped at the "
                  "largest odd number <= z / 2) fixed at its bore and its two radial cut faces: "
                  "cheaper, but a stiffer body (7 teeth: 4 ... 13 % less tooth compliance than "
                  "the whole gear; docs/theory.md §15.8).")
              .def("0")
              .ge(0)
              .le(7)
              .to(&ContactModelSpec::fe_teeth),
      });
}

Section ease_off_section() {
  return S("ease_off", SectionKind::Table, "[gear_pairs.ease_off]",
           "Ease-off of a bevel or hypoid pair for the loaded tooth contact analysis "
           "(docs/theory.md §15.9): the relative flank modification of the pair, material "
           "removed in metres along the virtual pair's line of action, E = C_a xi^2 + C_b eta^2 "
           "+ B xi eta + F_a xi + F_b eta over the pinion's normalised roll angle xi (-1 at the "
           "start of its active profile, +1 at its tip) and the normalised face position eta "
           "(-1 at the toe, +1 at the heel).")
      .in_table(&GearPair::ease_off)
      .located(&EaseOffSpec::where)
      .fields({
          number("profile_crowning", kMetre, "Profile crowning C_a (at xi = +-1).")
              .def("0.0")
              .ge(0)
              .to(&EaseOffSpec::profile_crowning),
          number("length_crowning", kMetre, "Length crowning C_b (at eta = +-1).")
              .def("0.0")
              .ge(0)
              .to(&EaseOffSpec::length_crowning),
          number("bias", kMetre,
                 "Bias B (the twist term B xi eta): positive removes material at the pinion's "
                 "tip at the heel and root at the toe, so the pattern runs from tip-toe to "
                 "root-heel.")
              .def("0.0")
              .to(&EaseOffSpec::bias),
          number("profile_slope", kMetre,
                 "Flank (pressure) angle modification F_a at xi = 1 (positive unloads the tip).")
              .def("0.0")
              .to(&EaseOffSpec::profile_slope),
          number("length_slope", kMetre,
                 "Spiral angle modification F_b at eta = 1 (positive unloads the heel).")
              .def("0.0")
              .to(&EaseOffSpec::length_slope),
      });
}

}  // namespace

Section gear_pairs_section() {
  return S("gear_pairs", SectionKind::ArrayOfTables, "[[gear_pairs]]",
           "Gear pairs of the mesh-excitation chain (docs/theory.md §11-13): geometry and contact "
           "ratio "
           "(ISO 21771; bevel and hypoid gears as virtual cylindrical gears at mid face), tooth "
           "forces, ISO 6336-1 mesh stiffness, the static transmission error (STE) from a file or "
           "synthetic from the stiffness, the dynamic mesh force and the engine-order harmonics "
           "(analyses gear_pair, mesh_force, mesh_harmonics). Gear 1 is the pinion; `torque` acts "
           "on it. The geometry is checked (interference, contact ratio >= 1, backlash) before any "
           "analysis runs.")
      .in_array(&Model::gear_pairs)
      .located(&GearPair::where)
      .fields(join_fields({gear_pair_fields_1(), gear_pair_fields_2()}))
      .sections({flank_section("flank1", "1", &GearPair::flank1),
                 flank_section("flank2", "2", &GearPair::flank2), contact_section(),
                 ease_off_section()})
      .choices({{{{"face_width"}, {"face_width1", "face_width2"}}, true, {}}})
      .variants("type",
                {
                    variant<GearPair>("spur", "Spur gears (external or internal)."),
                    variant<GearPair>("helical", "Helical gears (external or internal)."),
                    variant<GearPair>("straight_bevel",
                                      "Straight bevel gears (virtual spur gears at mid "
                                      "face)."),
                    variant<GearPair>("spiral_bevel", "Spiral bevel gears."),
                    variant<GearPair>("hypoid",
                                      "Hypoid gears (approximation: the offset is neglected "
                                      "in the cone geometry; pinion enlargement from the "
                                      "spiral angles)."),
                })
      .finish<GearPair>(finish_gear_pair);
}

}  // namespace geardyn::model
