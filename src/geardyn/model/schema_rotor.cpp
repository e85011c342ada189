// The model file's rotor sections: materials, shafts and their elements, nodes, disks, point
// masses, bearings, couplings, gear meshes, constraints, unbalances, forces, sensors, damping.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/model/schema_builder.hpp"
#include "geardyn/model/schema_sections.hpp"

namespace geardyn::model {
namespace {

using namespace keys;  // NOLINT: the declaration table reads as a table

void finish_material(Material& m, const TableContext& t) {
  if (t.has("poisson_ratio")) {
    const double nu = t.at("poisson_ratio").number;
    m.shear_modulus = m.youngs_modulus / (2.0 * (1.0 + nu));
  }
}

void finish_shaft(Shaft& s, const TableContext& t) {
  double norm = std::hypot(s.axis[0], s.axis[1], s.axis[2]);
  for (auto& a : s.axis) a /= norm;
  if (t.has("gear_ratio") && s.gear_ratio == 0.0)
    t.fail("gear_ratio", "a non-zero number (speed of this shaft / speed of driven_by)", "0");
  if (t.has("driven_by") && s.driven_by == s.name)
    t.fail("driven_by", "the name of another shaft",
           fmt::format("\"{}\", the shaft itself", s.driven_by));
}

void finish_element(ShaftElement& e, const TableContext& t) {
  if (e.inner_diameter >= e.outer_diameter)
    t.fail("inner_diameter",
           fmt::format("a number < outer_diameter = {} m", value_text(e.outer_diameter)),
           value_text(e.inner_diameter));
}

void finish_sensor(Sensor& s, const TableContext& t) {
  if (s.solid.empty()) return;
  if (static_cast<int>(s.dof) >= 3)
    t.fail("dof", "ux, uy or uz (a solid sensor measures the mean translation of its node set)",
           fmt::format("\"{}\"", kComponentNames[static_cast<std::size_t>(s.dof)]));
  // '/' is not allowed in solid names, so this cannot be the name of another node.
  s.node = s.solid + "/" + s.node_set;
}

void finish_node(Node& n, const TableContext&) {
  double norm = std::hypot(n.axis[0], n.axis[1], n.axis[2]);
  for (auto& a : n.axis) a /= norm;
}

void finish_gear_mesh(GearMesh& g, const TableContext&) {
  if (g.mesh_direction) {
    auto& d = *g.mesh_direction;
    const double norm = std::hypot(d[0], d[1], d[2]);
    for (auto& x : d) x /= norm;
  }
}

void finish_disk(Disk& d, const TableContext& t) {
  if (t.has("outer_diameter") && d.inner_diameter >= d.outer_diameter)
    t.fail("inner_diameter",
           fmt::format("a number < outer_diameter = {} m", value_text(d.outer_diameter)),
           value_text(d.inner_diameter));
}

struct BearingKey {
  const char* name;
  int row, col;
  bool damping;
  bool diagonal;
};

// Coefficients in the node frame, over (ux, uy, uz, rx, ry, rz): k.. stiffness, c.. damping,
// t = tilting (rx, ry), tzz = torsional (rz).
constexpr BearingKey kBearingKeys[] = {
    {"kxx", 0, 0, false, true},   {"kxy", 0, 1, false, false},  {"kyx", 1, 0, false, false},
    {"kyy", 1, 1, false, true},   {"kzz", 2, 2, false, true},   {"ktxx", 3, 3, false, true},
    {"ktxy", 3, 4, false, false}, {"ktyx", 4, 3, false, false}, {"ktyy", 4, 4, false, true},
    {"ktzz", 5, 5, false, true},  {"cxx", 0, 0, true, true},    {"cxy", 0, 1, true, false},
    {"cyx", 1, 0, true, false},   {"cyy", 1, 1, true, true},    {"czz", 2, 2, true, true},
    {"ctxx", 3, 3, true, true},   {"ctxy", 3, 4, true, false},  {"ctyx", 4, 3, true, false},
    {"ctyy", 4, 4, true, true},   {"ctzz", 5, 5, true, true},
};

/// Writes one coefficient into every tabulated matrix: a number sets all of them, an array of n
/// values makes the table n long (copying the constant entries already set) and sets entry i.
void set_bearing_entry(Bearing& b, const BearingKey& key, const FieldValue& v) {
  auto& table = key.damping ? b.damping : b.stiffness;
  if (table.empty()) table.push_back(Bearing::Matrix6{});
  const std::size_t index = static_cast<std::size_t>(key.row * 6 + key.col);
  if (!v.is_array) {
    for (auto& m : table) m[index] = v.number;
    return;
  }
  if (table.size() == 1 && v.numbers.size() > 1) table.resize(v.numbers.size(), table[0]);
  for (std::size_t i = 0; i < v.numbers.size() && i < table.size(); ++i)
    table[i][index] = v.numbers[i];
}

void set_bearing_matrix(Bearing& b, bool damping, const FieldValue& v) {
  auto& table = damping ? b.damping : b.stiffness;
  table.clear();
  for (std::size_t k = 0; k < v.count; ++k) {
    Bearing::Matrix6 m{};
    std::copy_n(v.numbers.begin() + static_cast<std::ptrdiff_t>(k * 36), 36, m.begin());
    table.push_back(m);
  }
}

void check_matrix_diagonal(const std::vector<double>& a, int n, std::size_t count,
                           const TableContext& t, const char* key, const char* what) {
  for (std::size_t k = 0; k < count; ++k) {
    for (int i = 0; i < n; ++i) {
      const double d = a[k * static_cast<std::size_t>(n * n) + static_cast<std::size_t>(i * n + i)];
      if (d < 0.0)
        t.fail(key, fmt::format("a {} matrix with diagonal entries >= 0", what),
               fmt::format("{} at row {}{}", value_text(d), i + 1,
                           count > 1 ? fmt::format(" of matrix {}", k + 1) : ""));
    }
  }
}

void finish_bearing(Bearing& b, const TableContext& t) {
  bool any = false;
  for (const auto& key : kBearingKeys) any = any || t.has(key.name);
  if (!any && !t.has("stiffness") && !t.has("damping"))
    t.fail("kxx",
           "at least one stiffness or damping coefficient (kxx, ..., cxx, ..., or the "
           "stiffness / damping matrix)",
           "none");
  for (const char* key : {"stiffness", "damping"}) {
    if (t.has(key)) {
      const auto& v = t.at(key);
      check_matrix_diagonal(v.numbers, 6, v.count, t, key, "6x6");
    }
  }
  for (auto* table : {&b.stiffness, &b.damping}) {
    if (table->empty()) table->push_back(Bearing::Matrix6{});
    if (!b.speeds.empty() && table->size() == 1) table->resize(b.speeds.size(), (*table)[0]);
  }
}

void finish_coupling(Coupling& c, const TableContext& t) {
  const int n = c.node2.empty() ? 6 : 12;
  bool any = false;
  for (const char* key : {"stiffness", "damping", "mass"}) {
    if (!t.has(key)) continue;
    any = true;
    const auto& v = t.at(key);
    if (v.rows != n)
      t.fail(key,
             fmt::format("a {0}x{0} matrix ({1})", n,
                         c.node2.empty() ? "6x6 for a coupling to ground, without node2"
                                         : "12x12 for a coupling between node1 and node2"),
             fmt::format("a {0}x{0} matrix", v.rows));
    check_matrix_diagonal(v.numbers, n, 1, t, key, fmt::format("{0}x{0}", n).c_str());
  }
  if (!any) t.fail("stiffness", "at least one of stiffness, damping, mass", "none");
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const double a = c.mass.empty() ? 0.0 : c.mass[static_cast<std::size_t>(i * n + j)];
      const double b = c.mass.empty() ? 0.0 : c.mass[static_cast<std::size_t>(j * n + i)];
      if (std::abs(a - b) > 1e-12 * std::max({std::abs(a), std::abs(b), 1e-300}))
        t.fail("mass", "a symmetric mass matrix",
               fmt::format("mass[{}][{}] = {} but mass[{}][{}] = {}", i, j, value_text(a), j, i,
                           value_text(b)));
    }
  }
}

void finish_band(DampingBand& b, const TableContext& t) {
  if (b.f_max <= b.f_min)
    t.fail("f_max_hz",
           fmt::format("a frequency > f_min_hz = {} Hz",
                       value_text(t.at("f_min_hz").number / units::kTwoPi)),
           fmt::format("{} Hz", value_text(t.at("f_max_hz").number / units::kTwoPi)));
}

std::vector<Field> bearing_coefficient_fields() {
  std::vector<Field> out;
  for (const auto& key : kBearingKeys) {
    const bool tilt = key.row >= 3;
    Unit unit = key.damping ? (tilt ? kTiltDamping : kDampingCoefficient)
                            : (tilt ? kTiltStiffness : kStiffness);
    const char* axis_names[] = {"x", "y", "z", "rx", "ry", "rz"};
    std::string help = fmt::format("{} {} coefficient: {} at {} from motion in {}{}.",
                                   key.diagonal ? "Direct" : "Cross-coupled",
                                   key.damping ? "damping" : "stiffness", tilt ? "moment" : "force",
                                   axis_names[key.row], axis_names[key.col],
                                   key.row == 5 ? " (torsional)"
                                   : tilt       ? " (tilting)"
                                                : "");
    F f(key.name, FieldType::NumberOrArray, help);
    f.unit(unit)
        .def("0.0")
        .tabulated_by("speed_rpm")
        .to_fn<Bearing>([key](Bearing& b, const FieldValue& v) { set_bearing_entry(b, key, v); });
    if (key.diagonal) f.ge(0.0);
    out.push_back(f);
  }
  return out;
}
}  // namespace

keys::F dof_set_key(const std::string& help) {
  return choice("dofs", std::vector<std::string>(kDofSetNames.begin(), kDofSetNames.end()),
                help +
                    " lateral: ux, uy, rx, ry; axial: uz; torsional: rz (node frame, z = the "
                    "axis); \"lateral+torsional\" etc. combine them. The other DOFs are absent "
                    "at every node concerned, as if constrained: disks, point masses, bearings, "
                    "couplings, gear meshes, forces and unbalances there act on the DOFs kept "
                    "only (a bearing's lateral stiffness on a torsion-only shaft is dropped), "
                    "and no [[constraints]] table is needed for them.");
}

Section materials_section() {
  return S("materials", SectionKind::ArrayOfTables, "[[materials]]",
           "Isotropic linear-elastic materials, referred to by name from shafts, shaft elements "
           "and disks.")
      .in_array(&Model::materials)
      .located(&Material::where)
      .fields({
          name_key("Unique material name.").required().to(&Material::name),
          number("youngs_modulus", kPascal, "Young's modulus E.")
              .required()
              .gt(0)
              .to(&Material::youngs_modulus),
          number("shear_modulus", kPascal, "Shear modulus G.")
              .required()
              .gt(0)
              .to(&Material::shear_modulus),
          number("poisson_ratio", kNoUnit, "Poisson's ratio nu; gives G = E / (2 (1 + nu)).")
              .required()
              .gt(-1.0)
              .le(0.5)
              .read_by_finish<Material>(),
          number("density", kDensity,
                 "Mass density rho; 0 for a massless shaft (the disks and point masses then "
                 "carry the mass, e.g. a Jeffcott rotor). A disk or solid made of a material "
                 "needs a density > 0.")
              .required()
              .ge(0)
              .to(&Material::density),
      })
      .choices({{{{"shear_modulus"}, {"poisson_ratio"}}, true, {}}})
      .finish<Material>(finish_material);
}

Section elements_section() {
  return S("elements", SectionKind::ArrayOfTables, "[[shafts.elements]]",
           "Sections of the shaft from its origin along its axis, in order. Each is cut into "
           "`divisions` equal beam elements; the stations between them are the shaft's nodes.")
      .in_array(&Shaft::elements)
      .located(&ShaftElement::where)
      .required()
      .min_count(1)
      .fields({
          number("length", kMetre, "Length of the section.")
              .required()
              .gt(0)
              .to(&ShaftElement::length),
          number("outer_diameter", kMetre, "Outer diameter.")
              .required()
              .gt(0)
              .to(&ShaftElement::outer_diameter),
          number("inner_diameter", kMetre,
                 "Bore diameter (0: solid); must be < "
                 "outer_diameter.")
              .def("0.0")
              .ge(0)
              .to(&ShaftElement::inner_diameter),
          reference("material", Ref::Material, "Material of this section.")
              .note("the shaft's material")
              .to(&ShaftElement::material),
          number("loss_factor", kNoUnit,
                 "Structural (hysteretic) loss factor eta of this section: stiffness "
                 "K (1 + i eta) in frequency-domain analyses.")
              .def("0.0")
              .ge(0)
              .to(&ShaftElement::loss_factor),
          integer("divisions", "Number of equal beam elements made from this section.")
              .def("1")
              .ge(1)
              .le(1000)
              .to(&ShaftElement::divisions),
      })
      .finish<ShaftElement>(finish_element);
}

Section shafts_section() {
  return S("shafts", SectionKind::ArrayOfTables, "[[shafts]]",
           "Straight shafts of beam elements. Node k of shaft `s` is named \"s.k\" (k = 0 at the "
           "origin, counted after `divisions` are expanded). Each shaft spins at speed_ratio times "
           "the reference speed of the analysis.")
      .in_array(&Model::shafts)
      .located(&Shaft::where)
      .fields({
          name_key("Unique shaft name; its nodes are `\"<name>.<k>\"`.")
              .required()
              .to(&Shaft::name),
          reference("material", Ref::Material, "Material of the shaft's elements.")
              .required()
              .to(&Shaft::material),
          vector3("origin", kMetre, "Position of node 0.")
              .def("[0.0, 0.0, 0.0]")
              .to(&Shaft::origin),
          vector3("axis", kNoUnit, "Direction of the shaft (normalised); the spin axis.")
              .def("[0.0, 0.0, 1.0]")
              .nonzero()
              .to(&Shaft::axis),
          number("speed_ratio", kNoUnit,
                 "Spin speed / reference speed (negative: opposite sense about `axis`).")
              .def("1.0")
              .to(&Shaft::speed_ratio),
          reference("driven_by", Ref::Shaft,
                    "Shaft this one is driven from through a gear pair; its speed_ratio is "
                    "gear_ratio x the speed_ratio of that shaft.")
              .required()
              .to(&Shaft::driven_by),
          number("gear_ratio", kNoUnit,
                 "Speed of this shaft / speed of `driven_by` (non-zero; negative for the "
                 "opposite sense).")
              .required()
              .to(&Shaft::gear_ratio),
          number("shear_coefficient", kNoUnit, "Timoshenko shear coefficient kappa.")
              .gt(0)
              .le(1.0)
              .note("Cowper's (1966) value for each element's (hollow) circle")
              .to(&Shaft::shear_coefficient),
          choice("theory", {"timoshenko", "euler_bernoulli"},
                 "Beam theory: Timoshenko (shear deformation) or Euler-Bernoulli.")
              .def("\"timoshenko\"")
              .to_enum(&Shaft::theory, {BeamTheory::Timoshenko, BeamTheory::EulerBernoulli}),
          boolean("rotary_inertia", "Include the rotary inertia of the cross-sections.")
              .def("true")
              .to(&Shaft::rotary_inertia),
          boolean("gyroscopic", "Include gyroscopic moments of the spinning shaft.")
              .def("true")
              .to(&Shaft::gyroscopic),
          dof_set_key("The DOFs of this shaft's nodes (overrides the model's `dofs`).")
              .note("the model's `dofs`")
              .to_fn<Shaft>(
                  [](Shaft& s, const FieldValue& v) { s.dofs = static_cast<DofSet>(v.choice); }),
      })
      .choices({{{{"speed_ratio"}, {"driven_by", "gear_ratio"}}, false, {}}})
      .sections({elements_section()})
      .finish<Shaft>(finish_shaft);
}

Section nodes_section() {
  return S("nodes", SectionKind::ArrayOfTables, "[[nodes]]",
           "Nodes that are not on a shaft (a gear on a flexible web, a housing point).")
      .in_array(&Model::nodes)
      .located(&Node::where)
      .fields({
          name_key("Unique node name (must differ from every shaft station name).")
              .required()
              .to(&Node::name),
          vector3("position", kMetre, "Position of the node.").required().to(&Node::position),
          vector3("axis", kNoUnit, "Spin axis of the node frame (normalised).")
              .def("[0.0, 0.0, 1.0]")
              .nonzero()
              .to(&Node::axis),
          reference("spin_of", Ref::Shaft, "Shaft whose speed this node spins with.")
              .note("not spinning")
              .to(&Node::spin_of),
      })
      .finish<Node>(finish_node);
}

Section disks_section() {
  return S("disks", SectionKind::ArrayOfTables, "[[disks]]",
           "Rigid disks (gears, impellers) at a node: give mass and inertias, or the geometry of a "
           "uniform annular disk, from which m = rho pi (ro^2 - ri^2) h, Ip = m (ro^2 + ri^2) / 2, "
           "Id = m (3 (ro^2 + ri^2) + h^2) / 12.")
      .in_array(&Model::disks)
      .located(&Disk::where)
      .fields({
          name_key("Name of the disk.").default_from_path().to(&Disk::name),
          reference("node", Ref::Node, "Node carrying the disk.").required().to(&Disk::node),
          number("mass", kKilogram, "Mass m.").required().gt(0).to(&Disk::mass),
          number("polar_inertia", kInertia, "Polar moment of inertia Ip about the spin axis.")
              .required()
              .ge(0)
              .to(&Disk::polar_inertia),
          number("diametral_inertia", kInertia, "Moment of inertia Id about a diameter.")
              .required()
              .ge(0)
              .to(&Disk::diametral_inertia),
          number("outer_diameter", kMetre, "Outer diameter 2 ro.")
              .required()
              .gt(0)
              .to(&Disk::outer_diameter),
          number("inner_diameter", kMetre, "Bore diameter 2 ri (< outer_diameter).")
              .def("0.0")
              .ge(0)
              .to(&Disk::inner_diameter),
          number("thickness", kMetre, "Axial thickness h.").required().gt(0).to(&Disk::thickness),
          reference("material", Ref::Material, "Material (its density is used).")
              .required()
              .to(&Disk::material),
      })
      .choices({{{{"mass", "polar_inertia", "diametral_inertia"},
                  {"outer_diameter", "inner_diameter", "thickness", "material"}},
                 true,
                 {}}})
      .finish<Disk>(finish_disk);
}

Section point_masses_section() {
  return S("point_masses", SectionKind::ArrayOfTables, "[[point_masses]]",
           "Point masses (translational inertia only) at a node.")
      .in_array(&Model::point_masses)
      .located(&PointMass::where)
      .fields({
          name_key("Name of the mass.").default_from_path().to(&PointMass::name),
          reference("node", Ref::Node, "Node carrying the mass.").required().to(&PointMass::node),
          number("mass", kKilogram, "Mass.").required().gt(0).to(&PointMass::mass),
      });
}

Section bearings_section() {
  std::vector<Field> bearing_fields = {
      name_key("Name of the bearing.").default_from_path().to(&Bearing::name),
      reference("node", Ref::Node, "Node of the bearing (its frame is the bearing's frame).")
          .required()
          .to(&Bearing::node),
      reference("node2", Ref::Node,
                "Second node: the bearing acts on the relative motion node - node2.")
          .note("ground")
          .to(&Bearing::node2),
      numbers("speed_rpm", kRpm,
              "Reference speeds of a tabulated bearing: coefficients given as arrays have one "
              "value per speed, interpolated linearly and held constant outside.")
          .ge(0)
          .increasing()
          .min_items(1)
          .note("constant coefficients")
          .to(&Bearing::speeds),
  };
  for (auto& f : bearing_coefficient_fields()) bearing_fields.push_back(std::move(f));
  {
    F stiffness = matrix("stiffness", {6},
                         "Full 6x6 stiffness matrix over (ux, uy, uz, rx, ry, "
                         "rz) in the node frame, instead of the k.. keys.");
    stiffness.tabulated_by("speed_rpm")
        .unit_note("N/m, N/rad, N, N m/rad by block")
        .to_fn<Bearing>([](Bearing& b, const FieldValue& v) { set_bearing_matrix(b, false, v); });
    F damping = matrix("damping", {6}, "Full 6x6 damping matrix, instead of the c.. keys.");
    damping.tabulated_by("speed_rpm")
        .unit_note("N s/m, N s/rad, N s, N m s/rad by block")
        .to_fn<Bearing>([](Bearing& b, const FieldValue& v) { set_bearing_matrix(b, true, v); });
    bearing_fields.push_back(stiffness);
    bearing_fields.push_back(damping);
  }
  std::vector<std::string> stiffness_keys, damping_keys;
  for (const auto& key : kBearingKeys)
    (key.damping ? damping_keys : stiffness_keys).push_back(key.name);

  return S("bearings", SectionKind::ArrayOfTables, "[[bearings]]",
           "Bearings and bushings: linear stiffness and damping between a node and ground, or "
           "between two nodes, in the node's frame. Each coefficient is a number, or an array "
           "with one value per `speed_rpm` entry.")
      .in_array(&Model::bearings)
      .located(&Bearing::where)
      .fields(bearing_fields)
      .choices(
          {{{stiffness_keys, {"stiffness"}}, false, {}}, {{damping_keys, {"damping"}}, false, {}}})
      .finish<Bearing>(finish_bearing);
}

Section couplings_section() {
  return S("couplings", SectionKind::ArrayOfTables, "[[couplings]]",
           "General linear elements: full stiffness, damping and mass matrices in global "
           "coordinates, 12x12 over (node1 DOFs, node2 DOFs), or 6x6 to ground without node2. "
           "DOF order per node: ux, uy, uz, rx, ry, rz.")
      .in_array(&Model::couplings)
      .located(&Coupling::where)
      .fields({
          name_key("Name of the coupling.").default_from_path().to(&Coupling::name),
          reference("node1", Ref::Node, "First node.").required().to(&Coupling::node1),
          reference("node2", Ref::Node, "Second node.")
              .note("ground (6x6 matrices)")
              .to(&Coupling::node2),
          matrix("stiffness", {6, 12}, "Stiffness matrix (diagonal >= 0).")
              .unit_note("N/m, N/rad, N, N m/rad by block")
              .note("zero")
              .to(&Coupling::stiffness),
          matrix("damping", {6, 12}, "Damping matrix (diagonal >= 0).")
              .unit_note("N s/m, N s/rad, N s, N m s/rad by block")
              .note("zero")
              .to(&Coupling::damping),
          matrix("mass", {6, 12}, "Mass matrix (symmetric, diagonal >= 0).")
              .unit_note("kg, kg m, kg m^2 by block")
              .note("zero")
              .to(&Coupling::mass),
      })
      .finish<Coupling>(finish_coupling);
}

Section gear_meshes_section() {
  return S("gear_meshes", SectionKind::ArrayOfTables, "[[gear_meshes]]",
           "Linear gear-mesh couplings: a spring-damper along the line of action between the "
           "nodes of two gears (gear1 drives). Bevel and hypoid pairs are treated as the "
           "equivalent spur pair at mid face.")
      .in_array(&Model::gear_meshes)
      .located(&GearMesh::where)
      .fields({
          name_key("Name of the mesh.").default_from_path().to(&GearMesh::name),
          reference("gear1", Ref::Node, "Node of the driving gear.")
              .required()
              .to(&GearMesh::gear1),
          reference("gear2", Ref::Node, "Node of the driven gear.").required().to(&GearMesh::gear2),
          choice("type", kGearTypes, "Gear type; selects the keys below.")
              .def("\"spur\"")
              .to_enum(&GearMesh::type, {GearType::Spur, GearType::Helical, GearType::StraightBevel,
                                         GearType::SpiralBevel, GearType::Hypoid}),
          integer("teeth1", "Number of teeth of gear1 (for mesh orders).")
              .ge(1)
              .le(100000)
              .note("unknown (no mesh orders)")
              .to(&GearMesh::teeth1),
          integer("teeth2", "Number of teeth of gear2.")
              .ge(1)
              .le(100000)
              .note("unknown (no mesh orders)")
              .to(&GearMesh::teeth2),
          number("base_radius1", kMetre,
                 "Base radius of gear1 (equivalent spur gear for "
                 "bevels).")
              .required()
              .gt(0)
              .to(&GearMesh::base_radius1),
          number("base_radius2", kMetre, "Base radius of gear2.")
              .required()
              .gt(0)
              .to(&GearMesh::base_radius2),
          number("pressure_angle_deg", kDegree,
                 "Pressure angle: transverse for spur, normal for helical and bevel gears.")
              .def("20.0")
              .gt(0)
              .lt(60)
              .to(&GearMesh::pressure_angle),
          number("helix_angle_deg", kDegree, "Helix angle, or mean spiral angle of bevels.")
              .required()
              .gt(0)
              .lt(90)
              .only_in(kHelical)
              .to(&GearMesh::helix_angle),
          number("pitch_cone_angle1_deg", kDegree, "Pitch cone angle of gear1.")
              .required()
              .gt(0)
              .lt(90)
              .only_in(kBevel)
              .to(&GearMesh::pitch_cone_angle1),
          number("pitch_cone_angle2_deg", kDegree, "Pitch cone angle of gear2.")
              .required()
              .gt(0)
              .lt(90)
              .only_in(kBevel)
              .to(&GearMesh::pitch_cone_angle2),
          choice("hand", {"right", "left"}, "Hand of gear1's helix or spiral.")
              .def("\"right\"")
              .only_in(kHelical)
              .to_enum(&GearMesh::hand, {Hand::Right, Hand::Left}),
          choice("flank", {"drive", "coast"}, "Loaded flank.")
              .def("\"drive\"")
              .to_enum(&GearMesh::flank, {Flank::Drive, Flank::Coast}),
          number("stiffness", kStiffness,
                 "Mesh stiffness along the line of action (0: gears not coupled, e.g. a "
                 "variant without the mesh).")
              .required()
              .ge(0)
              .to(&GearMesh::stiffness),
          number("damping", kDampingCoefficient, "Mesh damping along the line of action.")
              .def("0.0")
              .ge(0)
              .to(&GearMesh::damping),
          vector3("mesh_direction", kNoUnit,
                  "Direction from gear1's centre towards the pitch point.")
              .nonzero()
              .note("from gear1's node towards gear2's node")
              .to(&GearMesh::mesh_direction),
      })
      .variants(
          "type",
          {
              variant<GearMesh>("spur", "Spur gears: no helix, no cone angles."),
              variant<GearMesh>("helical", "Parallel-axis helical gears."),
              variant<GearMesh>("straight_bevel", "Straight bevel gears."),
              variant<GearMesh>("spiral_bevel", "Spiral bevel gears."),
              variant<GearMesh>("hypoid", "Hypoid gears (equivalent spiral bevel at mid face)."),
          })
      .sections({mesh_contact_section()})
      .finish<GearMesh>(finish_gear_mesh);
}

Section constraints_section() {
  return S("constraints", SectionKind::ArrayOfTables, "[[constraints]]",
           "Fixed DOFs (in the node's frame), removed from the equations.")
      .in_array(&Model::constraints)
      .located(&Constraint::where)
      .fields({
          reference("node", Ref::Node, "Constrained node.").required().to(&Constraint::node),
          F("dofs", FieldType::DofList, "Fixed DOFs.")
              .required()
              .choices(kComponentChoices)
              .to(&Constraint::dofs),
      });
}

Section unbalances_section() {
  return S("unbalances", SectionKind::ArrayOfTables, "[[unbalances]]",
           "Rotating unbalances: force m e (r Omega)^2 turning with the node's spin.")
      .in_array(&Model::unbalances)
      .located(&Unbalance::where)
      .fields({
          name_key("Name of the unbalance.").default_from_path().to(&Unbalance::name),
          reference("node", Ref::Node, "Node of the unbalance (spinning).")
              .required()
              .to(&Unbalance::node),
          number("mass_eccentricity", kMassEccentricity, "Unbalance m e.")
              .required()
              .gt(0)
              .to(&Unbalance::mass_eccentricity),
          number("phase_deg", kDegree, "Angular position at t = 0, from the node's e1 axis.")
              .def("0.0")
              .to(&Unbalance::phase),
      });
}

Section forces_section() {
  return S("forces", SectionKind::ArrayOfTables, "[[forces]]",
           "Harmonic forces and moments at a node, along a DOF of the node frame.")
      .in_array(&Model::forces)
      .located(&HarmonicForce::where)
      .fields({
          name_key("Name of the force.").default_from_path().to(&HarmonicForce::name),
          reference("node", Ref::Node, "Node loaded.").required().to(&HarmonicForce::node),
          choice("dof", kComponentChoices, "Direction (rx, ry, rz: a moment).")
              .required()
              .to(&HarmonicForce::dof),
          number("amplitude", kNewton, "Amplitude.")
              .unit_note("N, or N m for rx, ry, rz")
              .required()
              .ge(0)
              .to(&HarmonicForce::amplitude),
          number("phase_deg", kDegree, "Phase.").def("0.0").to(&HarmonicForce::phase),
      });
}

Section sensors_section() {
  return S("sensors", SectionKind::ArrayOfTables, "[[sensors]]",
           "Response outputs: a DOF of a node, in the node's frame; or the mean translation of a "
           "node set of a solid joined to the rotor ([[solids.spiders]]), in global axes. A solid "
           "sensor's node set becomes a physical (master) point of the solid's reduction, node "
           "\"<solid>/<node_set>\" of the system.")
      .in_array(&Model::sensors)
      .located(&Sensor::where)
      .fields({
          name_key("Unique sensor name (used in result columns).").required().to(&Sensor::name),
          reference("node", Ref::Node, "Node measured.").required().to(&Sensor::node),
          reference("solid", Ref::Solid,
                    "Solid measured (joined to the rotor by [[solids.spiders]]).")
              .required()
              .to(&Sensor::solid),
          text("node_set",
               "Node set of the solid's mesh whose mean translation (sum u_i / n) is measured.")
              .required()
              .to(&Sensor::node_set),
          choice("dof", kComponentChoices,
                 "DOF measured (a solid sensor: ux, uy or uz in global axes).")
              .required()
              .to(&Sensor::dof),
      })
      .choices({{{{"node"}, {"solid", "node_set"}}, true, {}}})
      .finish<Sensor>(finish_sensor);
}

Section bands_section() {
  return S("bands", SectionKind::ArrayOfTables, "[[damping.bands]]",
           "Modal damping ratio for the modes whose undamped frequency lies in [f_min_hz, "
           "f_max_hz); bands must not overlap.")
      .in_array(&Damping::bands)
      .fields({
          number("f_min_hz", kHertz, "Lower band edge.").required().ge(0).to(&DampingBand::f_min),
          number("f_max_hz", kHertz, "Upper band edge (may be inf).")
              .required()
              .gt(0)
              .allow_infinity()
              .to(&DampingBand::f_max),
          number("ratio", kNoUnit, "Modal damping ratio zeta in the band.")
              .required()
              .ge(0)
              .to(&DampingBand::ratio),
      })
      .finish<DampingBand>(finish_band);
}

Section damping_section() {
  return S("damping", SectionKind::Table, "[damping]",
           "Global damping: Rayleigh C = alpha M + beta K, structural loss factor, and modal "
           "damping ratios (per mode, per band, or one for all modes).")
      .in_table(&Model::damping)
      .fields({
          number("rayleigh_alpha", kPerSecond, "Mass-proportional coefficient alpha.")
              .def("0.0")
              .ge(0)
              .to(&Damping::rayleigh_alpha),
          number("rayleigh_beta", kSecond, "Stiffness-proportional coefficient beta.")
              .def("0.0")
              .ge(0)
              .to(&Damping::rayleigh_beta),
          number("loss_factor", kNoUnit,
                 "Structural loss factor eta of the whole model, K (1 + i eta) in the "
                 "frequency domain.")
              .def("0.0")
              .ge(0)
              .to(&Damping::loss_factor),
          number("modal_ratio", kNoUnit,
                 "Damping ratio of every mode not covered by modal_ratios or bands.")
              .def("0.0")
              .ge(0)
              .to(&Damping::modal_ratio),
          numbers("modal_ratios", kNoUnit,
                  "Damping ratios of the first modes, in order of undamped frequency.")
              .ge(0)
              .note("modal_ratio and bands apply")
              .to(&Damping::modal_ratios),
      })
      .sections({bands_section()});
}

}  // namespace geardyn::model
