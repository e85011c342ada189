// The model file's [[solids]] section: meshes, generated sectors and plates, reduced components
// and imported matrices, with their spiders.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/model/schema_builder.hpp"
#include "geardyn/model/schema_sections.hpp"

namespace geardyn::model {
namespace {

using namespace keys;  // NOLINT: the declaration table reads as a table

const std::vector<std::string> kPlate = {"annular_plate"};
const std::vector<std::string> kGear = {"gear_sector"};
/// Setter into a member of a nested spec of a Solid (annular_plate / gear_sector keys).
template <class Spec, class V>
std::function<void(Solid&, const FieldValue&)> solid_spec(Spec Solid::*spec, V Spec::*member) {
  return [spec, member](Solid& s, const FieldValue& v) { assign(s.*spec.*member, v); };
}
template <class V>
auto plate(V AnnularPlateSpec::*member) {
  return solid_spec(&Solid::annular_plate, member);
}
template <class V>
auto gear(V GearSectorSpec::*member) {
  return solid_spec(&Solid::gear_sector, member);
}

void finish_solid(Solid& s, const TableContext& t) {
  const bool needs_material = s.source == SolidSource::AnnularPlate ||
                              s.source == SolidSource::GearSector ||
                              (s.source == SolidSource::MeshFile && s.mesh.ends_with(".msh"));
  if (needs_material && s.material.empty())
    t.fail("material", "a material name (Gmsh and generated meshes carry no material)", "nothing");
  if (s.spiders.empty() && s.modal_damping_ratio > 0.0)
    t.fail("modal_damping_ratio",
           "0 for a solid not joined to the rotor by [[solids.spiders]] (it damps the modes of "
           "the joined component)",
           value_text(s.modal_damping_ratio));
  if (!s.spiders.empty() && s.sectors > 1)
    t.fail("sectors", "1 for a solid joined to the rotor by [[solids.spiders]] (the whole body)",
           std::to_string(s.sectors));
  if (s.source == SolidSource::AnnularPlate) {
    const auto& p = s.annular_plate;
    if (p.outer_radius <= p.inner_radius)
      t.fail("outer_radius",
             fmt::format("a radius > inner_radius = {} m", value_text(p.inner_radius)),
             fmt::format("{} m", value_text(p.outer_radius)));
  }
  if (s.source == SolidSource::GearSector) {
    const auto& g = s.gear_sector;
    if (g.teeth % s.sectors != 0)
      t.fail("sectors", fmt::format("a divisor of teeth = {} (whole teeth per sector)", g.teeth),
             std::to_string(s.sectors));
    if (g.groove) {
      if (s.ring_material.empty())
        t.fail("ring_material", "a material name for the damper ring (groove = true)", "nothing");
      for (const char* key : {"groove_width", "groove_depth", "ring_thickness"})
        if (!t.has(key)) t.fail(key, "a value (groove = true)", "nothing");
    }
    const double root = g.module * (g.teeth / 2.0 - 1.25);
    const double radii[] = {g.bore_radius, g.hub_radius, g.rim_inner_radius, root};
    const char* keys[] = {"bore_radius", "hub_radius", "rim_inner_radius"};
    for (int k = 0; k < 3; ++k)
      if (radii[k] >= radii[k + 1])
        t.fail(keys[k],
               fmt::format("a radius < {} = {} m", k + 1 < 3 ? keys[k + 1] : "root radius",
                           value_text(radii[k + 1])),
               fmt::format("{} m", value_text(radii[k])));
  }
}

Section spiders_section() {
  return S("spiders", SectionKind::ArrayOfTables, "[[solids.spiders]]",
           "Joints of the solid to rotor nodes through node sets of its mesh (RBE2 / RBE3-like). "
           "Each adds a reference point at the rotor node's position, whose 6 DOFs (global axes, "
           "rotated into the node frame) become the rotor node's.")
      .in_array(&Solid::spiders)
      .located(&Spider::where)
      .only_in({"mesh", "annular_plate", "gear_sector"})
      .fields({
          text("node_set", "Node set of the solid's mesh that is joined.")
              .required()
              .to(&Spider::node_set),
          reference("node", Ref::Node, "Rotor node joined: \"<shaft>.<k>\" or a [[nodes]] name.")
              .required()
              .to(&Spider::node),
          choice("kind", {"rigid", "averaging"},
                 "rigid (RBE2): the set moves with the node as a rigid body; averaging (RBE3): "
                 "the node follows the least-squares rigid fit of the set's translations, "
                 "which keep their own flexibility.")
              .def("\"rigid\"")
              .to_enum(&Spider::kind, {SpiderKind::Rigid, SpiderKind::Averaging}),
      });
}

std::vector<Field> solid_fields_1() {
  return {
      name_key("Unique solid name.").required().to(&Solid::name),
      choice("type", {"mesh", "annular_plate", "gear_sector", "reduced", "matrices"},
             "Where the solid comes from; selects the keys below.")
          .required()
          .to_enum(&Solid::source,
                   {SolidSource::MeshFile, SolidSource::AnnularPlate, SolidSource::GearSector,
                    SolidSource::Reduced, SolidSource::Matrices}),
      text("file",
           "Mesh file (Gmsh .msh v4, or Nastran bulk data .bdf/.dat/.nas/.blk), "
           "relative to the model file.")
          .required()
          .only_in({"mesh"})
          .to(&Solid::mesh),
      text("reduced_file",
           "Reduced component (.h5) written by a `reduction` analysis, relative to the "
           "model file.")
          .required()
          .only_in({"reduced"})
          .to(&Solid::reduced),
      text("stiffness_file",
           "Stiffness matrix K in Matrix Market format (coordinate or array, real, "
           "general or symmetric), relative to the model file.")
          .required()
          .only_in({"matrices"})
          .to(&Solid::stiffness_file),
      text("mass_file", "Mass matrix M in Matrix Market format, the same size as K.")
          .required()
          .only_in({"matrices"})
          .to(&Solid::mass_file),
      text("dof_map_file",
           "DOF map CSV of K and M, one row per matrix row: node_id, component (1-6, "
           "ux..rz, or q for a generalised coordinate), x, y, z [m] "
           "(docs/reduced-component-format.md).")
          .required()
          .only_in({"matrices"})
          .to(&Solid::dof_map_file),
      reference("material", Ref::Material,
                "Material of the solid (Nastran decks carry their own MAT1).")
          .note("required except for Nastran meshes and reduced components")
          .only_in({"mesh", "annular_plate", "gear_sector"})
          .to(&Solid::material),
      integer("sectors", "Number of identical sectors of the body (1: the whole body).")
          .def("1")
          .ge(1)
          .le(10000)
          .to(&Solid::sectors),
      number("interface_tolerance", kMetre,
             "Largest distance between a right-interface node and the rotated "
             "left-interface node it is paired with.")
          .def("1e-6")
          .gt(0)
          .to(&Solid::interface_tolerance),
      F("fixed_sets", FieldType::StringArray, "Node sets whose translations are fixed.")
          .def("[]")
          .only_in({"mesh", "annular_plate", "gear_sector"})
          .to(&Solid::fixed_sets),
      integer("coupling_modes",
              "Fixed-interface modes (spider and sensor points held) kept when the solid "
              "is joined to the rotor by [[solids.spiders]]; 0: Guyan (static) coupling.")
          .def("20")
          .ge(0)
          .le(10000)
          .only_in({"mesh", "annular_plate", "gear_sector"})
          .to(&Solid::coupling_modes),
      number("modal_damping_ratio", kNoUnit,
             "Viscous damping ratio zeta of every fixed-interface mode of the solid joined to "
             "the rotor, independent of [damping]: C_eta = diag(2 zeta omega_k) in its modal "
             "coordinates (docs/theory.md §9, eq. 9.4); the spider and sensor points' constraint "
             "modes "
             "stay undamped. Reaches every analysis of the rotor system (modal, frf, transient, "
             "drivetrain_transient).")
          .def("0.0")
          .ge(0)
          .lt(1)
          .only_in({"mesh", "annular_plate", "gear_sector"})
          .to(&Solid::modal_damping_ratio),
      choice("unsupported_cards", {"warn", "error"},
             "Nastran cards geardyn does not read: listed as warnings, or an error.")
          .def("\"warn\"")
          .only_in({"mesh"})
          .to_fn<Solid>([](Solid& s, const FieldValue& v) {
            s.unsupported_cards_are_errors = v.choice == 1;
          }),
      // annular plate
      number("inner_radius", kMetre,
             "Inner radius b; 0 makes a solid disc (meshed with a centre square, so no element "
             "is degenerate; whole plates only, sectors = 1).")
          .required()
          .ge(0)
          .only_in(kPlate)
          .to_fn<Solid>(plate(&AnnularPlateSpec::inner_radius)),
  };
}

std::vector<Field> solid_fields_2() {
  return {
      number("outer_radius", kMetre, "Outer radius a (> inner_radius).")
          .required()
          .gt(0)
          .only_in(kPlate)
          .to_fn<Solid>(plate(&AnnularPlateSpec::outer_radius)),
      number("thickness", kMetre, "Plate thickness h.")
          .required()
          .gt(0)
          .only_in(kPlate)
          .to_fn<Solid>(plate(&AnnularPlateSpec::thickness)),
      integer("radial_elements",
              "Elements across the radius (a solid disc: across the ring outside its centre "
              "square, r = a/2 .. a).")
          .def("8")
          .ge(1)
          .le(1000)
          .only_in(kPlate)
          .to_fn<Solid>(plate(&AnnularPlateSpec::radial_elements)),
      integer("circumferential_elements",
              "Elements around the circumference of the mesh (the sector, or the whole "
              "plate; a solid disc: rounded up to a multiple of 4).")
          .ge(0)
          .le(100000)
          .note("about square elements at the outer radius (a solid disc: 2 pi radial_elements)")
          .only_in(kPlate)
          .to_fn<Solid>(plate(&AnnularPlateSpec::circumferential_elements)),
      integer("layers", "Elements through the thickness.")
          .def("2")
          .ge(1)
          .le(100)
          .only_in(kPlate)
          .to_fn<Solid>(plate(&AnnularPlateSpec::layers)),
      integer("order", "Element order: 1 linear, 2 quadratic.")
          .def("2")
          .ge(1)
          .le(2)
          .only_in({"annular_plate", "gear_sector"})
          .to_fn<Solid>([](Solid& s, const FieldValue& v) {
            s.annular_plate.order = static_cast<int>(v.integer);
            s.gear_sector.order = static_cast<int>(v.integer);
          }),
      // gear sector
      integer("teeth", "Number of teeth of the whole gear.")
          .required()
          .ge(3)
          .le(10000)
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::teeth)),
      number("module", kMetre, "Transverse module m (pitch radius m z / 2).")
          .required()
          .gt(0)
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::module)),
      number("pressure_angle_deg", kDegree, "Pressure angle of the simplified tooth.")
          .def("20.0")
          .gt(0)
          .lt(45)
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::pressure_angle)),
      number("face_width", kMetre, "Face width of the rim and teeth.")
          .required()
          .gt(0)
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::face_width)),
      number("bore_radius", kMetre, "Bore radius.")
          .required()
          .gt(0)
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::bore_radius)),
      number("hub_radius", kMetre, "Outer radius of the hub.")
          .required()
          .gt(0)
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::hub_radius)),
      number("hub_width", kMetre, "Axial width of the hub.")
          .required()
          .gt(0)
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::hub_width)),
      number("hub_offset", kMetre, "Axial position of the hub centre from mid-face.")
          .def("0.0")
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::hub_offset)),
  };
}

std::vector<Field> solid_fields_3() {
  return {
      number("web_offset", kMetre, "Axial position of the web centre from mid-face.")
          .def("0.0")
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::web_offset)),
      number("web_thickness", kMetre, "Axial thickness of the web.")
          .required()
          .gt(0)
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::web_thickness)),
      number("rim_inner_radius", kMetre, "Inner radius of the rim.")
          .required()
          .gt(0)
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::rim_inner_radius)),
      boolean("groove", "Damper-ring groove under the rim, with its split ring.")
          .def("false")
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::groove)),
      number("groove_position", kMetre, "Axial position of the groove centre from mid-face.")
          .def("0.0")
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::groove_position)),
      number("groove_width", kMetre, "Axial width of the groove (and the ring).")
          .gt(0)
          .note("required when groove = true")
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::groove_width)),
      number("groove_depth", kMetre, "Radial depth of the groove into the rim.")
          .gt(0)
          .note("required when groove = true")
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::groove_depth)),
      number("ring_width", kMetre, "Axial width of the ring (<= groove_width).")
          .gt(0)
          .note("groove_width")
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::ring_width)),
      number("ring_thickness", kMetre, "Radial thickness of the ring.")
          .gt(0)
          .note("required when groove = true")
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::ring_thickness)),
      reference("ring_material", Ref::Material, "Material of the damper ring.")
          .note("required when groove = true")
          .only_in(kGear)
          .to(&Solid::ring_material),
      number("element_size", kMetre, "Target element size.")
          .required()
          .gt(0)
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::element_size)),
      number("tooth_element_size", kMetre, "Target element size at the teeth and groove.")
          .gt(0)
          .note("element_size")
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::tooth_element_size)),
      number("groove_element_size", kMetre,
             "Target element size at the groove and the ring (sets how many contact "
             "pairs the ring has).")
          .gt(0)
          .note("tooth_element_size")
          .only_in(kGear)
          .to_fn<Solid>(gear(&GearSectorSpec::groove_element_size)),
  };
}

}  // namespace

Section solids_section() {
  return S("solids", SectionKind::ArrayOfTables, "[[solids]]",
           "Solid (3D finite-element) components: a mesh file, a generated annular plate or "
           "gear-blank sector, a reduced component saved by an earlier run, or stiffness and mass "
           "matrices exported by another FE code (Matrix Market) with their DOF map. With "
           "sectors > 1 "
           "the mesh is one sector of a cyclic body about the z axis. Mesh coordinates are in the "
           "global frame of the rotor model (generated plates and gears lie about the global z "
           "axis, mid-plane z = 0). A solid with [[solids.spiders]] is part of the rotor system: "
           "it is Craig-Bampton reduced onto its spider points (6 DOFs each, joined to the rotor "
           "node's 6 DOFs) and its sensor points, plus `coupling_modes` fixed-interface modes, "
           "which become generalised coordinates of the system. Its gyroscopic effect is that of "
           "its rigid-body polar inertia about the spin axis of its spider nodes, when they all "
           "spin at one speed; the gyroscopic coupling of its elastic modes is not included.")
      .in_array(&Model::solids)
      .located(&Solid::where)
      .fields(join_fields({solid_fields_1(), solid_fields_2(), solid_fields_3()}))
      .variants("type",
                {variant<Solid>("mesh", "A mesh file: Gmsh .msh (v4) or Nastran bulk data."),
                 variant<Solid>("annular_plate",
                                "A generated annular plate (or one sector of it) about z."),
                 variant<Solid>("gear_sector",
                                "A generated gear-blank sector with simplified teeth and an "
                                "optional damper-ring groove and ring."),
                 variant<Solid>("reduced", "A reduced component file (.h5)."),
                 variant<Solid>("matrices",
                                "Stiffness and mass matrices exported by another FE code "
                                "(e.g. an ANSYS or Nastran superelement) with a DOF map.")})
      .sections({spiders_section()})
      .finish<Solid>(finish_solid);
}

}  // namespace geardyn::model
