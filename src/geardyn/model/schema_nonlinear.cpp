// The model file's [[nonlinear_elements]] section (nonlinear_element_spec.hpp, docs/theory.md
// §19): the nonlinear force elements of harmonic balance, between two nodes of any model. The
// checks against the rest of the model (nodes, gear meshes) are in parse.cpp
// (Resolver::check_nonlinear_elements).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/model/schema_builder.hpp"
#include "geardyn/model/schema_sections.hpp"

namespace geardyn::model {
namespace {

using namespace keys;  // NOLINT: the declaration table reads as a table

constexpr Unit kCubicStiffness{"N/m^3", 1.0};
constexpr Unit kViscosity{"Pa s", 1.0};

// The element types whose coordinate is one direction between node1 and node2.
const std::vector<std::string> kAlongDirection = {
    "jenkins",    "coulomb", "polynomial",       "cubic",
    "unilateral", "contact", "friction_contact", "squeeze_film"};
const std::vector<std::string> kScalar = {"jenkins", "coulomb",    "polynomial",
                                          "cubic",   "unilateral", "contact"};

const char* kRotationNote = "m; rad for motion = \"rotation\"";

double norm(const DrivetrainVec3& v) { return std::hypot(v[0], v[1], v[2]); }

void normalise(DrivetrainVec3& v) {
  const double n = norm(v);
  for (auto& x : v) x /= n;
}

double dot(const DrivetrainVec3& a, const DrivetrainVec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void finish_element(NonlinearElementSpec& e, const TableContext& t) {
  normalise(e.direction);
  if (e.kind == NonlinearElementKind::FrictionContact) {
    if (e.normal_preload == 0.0 && e.normal_stiffness == 0.0)
      t.fail("normal_preload",
             "a normal preload > 0 N, or a normal_stiffness > 0 that loads the contact as it "
             "closes",
             "0 N and no normal stiffness (the contact would never carry a friction force)");
    normalise(e.tangent);
    if (std::abs(dot(e.tangent, e.direction)) > 1e-6)
      t.fail("tangent", "a direction normal to `direction` (the contact normal)",
             fmt::format("one at {:.4g} deg to it",
                         std::acos(std::clamp(dot(e.tangent, e.direction), -1.0, 1.0)) /
                             units::kRadPerDegree));
    if (t.has("tangent2")) {
      normalise(e.tangent2);
      if (std::abs(dot(e.tangent2, e.direction)) > 1e-6 ||
          std::abs(dot(e.tangent2, e.tangent)) > 1e-6)
        t.fail("tangent2", "a direction normal to both `direction` and `tangent`",
               "one that is not");
    }
  }
  if (e.kind == NonlinearElementKind::Polynomial) {
    if (e.powers.size() != e.coefficients.size())
      t.fail("coefficients", fmt::format("{} values, one per power", e.powers.size()),
             fmt::format("{}", e.coefficients.size()));
    for (double p : e.powers)
      if (p < 1.0 || p != std::floor(p) || p > 15.0)
        t.fail("powers", "integer powers from 1 to 15", fmt::format("{}", value_text(p)));
  }
}

std::vector<Field> element_fields() {
  return {
      name_key("Unique element name (result columns).").required().to(&NonlinearElementSpec::name),
      choice("type",
             {"jenkins", "coulomb", "friction_contact", "polynomial", "cubic", "unilateral",
              "contact", "gear_mesh", "squeeze_film"},
             "Kind of element; selects the keys below.")
          .required()
          .to_enum(&NonlinearElementSpec::kind,
                   {NonlinearElementKind::Jenkins, NonlinearElementKind::Coulomb,
                    NonlinearElementKind::FrictionContact, NonlinearElementKind::Polynomial,
                    NonlinearElementKind::Cubic, NonlinearElementKind::Unilateral,
                    NonlinearElementKind::Contact, NonlinearElementKind::GearMesh,
                    NonlinearElementKind::SqueezeFilm}),
      reference("node1", Ref::Node, "End i of the element.")
          .note("ground")
          .only_in(kAlongDirection)
          .to(&NonlinearElementSpec::node1),
      reference("node2", Ref::Node, "End j of the element: u = (motion of node2 - node1).")
          .required()
          .only_in(kAlongDirection)
          .to(&NonlinearElementSpec::node2),
      vector3("direction", kNoUnit,
              "Direction of u in global axes (normalised): the element's line; the contact "
              "normal of a friction contact (u_n > 0 presses the surfaces together); the "
              "damper's axis for a squeeze film.")
          .def("[1.0, 0.0, 0.0]")
          .nonzero()
          .only_in(kAlongDirection)
          .to(&NonlinearElementSpec::direction),
      choice("motion", {"translation", "rotation"},
             "What u measures: the relative translation, or the relative rotation vector "
             "projected on `direction` (a torsional element).")
          .def("\"translation\"")
          .only_in(kScalar)
          .to_enum(&NonlinearElementSpec::rotation, {false, true}),
      // jenkins, unilateral
      number("stiffness", kNoUnit,
             "Spring stiffness k (jenkins: in series with the slider; unilateral: acting once "
             "closed).")
          .unit_note("N/m; N m/rad for motion = \"rotation\"")
          .required()
          .gt(0)
          .only_in({"jenkins", "unilateral"})
          .to(&NonlinearElementSpec::stiffness),
      number("stiffness", kCubicStiffness, "k3 of f = k3 u^3 (negative: softening).")
          .required()
          .only_in({"cubic"})
          .to(&NonlinearElementSpec::stiffness),
      number("slip_force", kNoUnit, "Slip force F = mu N of the slider.")
          .unit_note("N; N m for motion = \"rotation\"")
          .required()
          .ge(0)
          .only_in({"jenkins", "coulomb"})
          .to(&NonlinearElementSpec::slip_force),
      number("regularisation_velocity", kNoUnit,
             "v_eps of f = F tanh(u' / v_eps): the smaller, the closer to a sign function and "
             "the more harmonics and samples the balance needs.")
          .unit_note("m/s; rad/s for motion = \"rotation\"")
          .def("1e-4")
          .gt(0)
          .only_in({"coulomb"})
          .to(&NonlinearElementSpec::regularisation_velocity),
      // polynomial
      numbers("powers", kNoUnit, "Integer powers p >= 1 of f = sum c_p u^p.")
          .required()
          .min_items(1)
          .only_in({"polynomial"})
          .to(&NonlinearElementSpec::powers),
      numbers("coefficients", kNoUnit, "Coefficients c_p, one per power.")
          .unit_note("N/m^p")
          .required()
          .min_items(1)
          .only_in({"polynomial"})
          .to(&NonlinearElementSpec::coefficients),
      // unilateral, contact
      number("gap", kNoUnit,
             "The element closes when u > gap (negative: closed and preloaded at u = 0).")
          .unit_note(kRotationNote)
          .def("0.0")
          .only_in({"unilateral", "contact"})
          .to(&NonlinearElementSpec::gap),
      number("damping", kNoUnit, "Viscous damping c u' while closed.")
          .unit_note("N s/m; N m s/rad for motion = \"rotation\"")
          .def("0.0")
          .ge(0)
          .only_in({"unilateral"})
          .to(&NonlinearElementSpec::damping),
      // friction_contact
      vector3("tangent", kNoUnit,
              "First tangential direction of the contact plane (global, normalised, normal to "
              "`direction`).")
          .required()
          .nonzero()
          .only_in({"friction_contact"})
          .to(&NonlinearElementSpec::tangent),
      vector3("tangent2", kNoUnit,
              "Second tangential direction: a 3D contact with slip in the plane (normal to "
              "`direction` and `tangent`).")
          .note("a 2D contact (one tangential direction)")
          .nonzero()
          .only_in({"friction_contact"})
          .to(&NonlinearElementSpec::tangent2),
      number("normal_stiffness", kStiffness,
             "Normal contact stiffness k_n: N = max(N_0 + k_n u_n, 0) (0: constant normal "
             "load N_0).")
          .def("0.0")
          .ge(0)
          .only_in({"friction_contact"})
          .to(&NonlinearElementSpec::normal_stiffness),
      number("tangential_stiffness", kStiffness, "Tangential contact stiffness k_t.")
          .required()
          .gt(0)
          .only_in({"friction_contact"})
          .to(&NonlinearElementSpec::tangential_stiffness),
      number("friction_coefficient", kNoUnit, "Coulomb friction coefficient mu.")
          .required()
          .ge(0)
          .only_in({"friction_contact"})
          .to(&NonlinearElementSpec::friction_coefficient),
      number("normal_preload", kNewton,
             "Normal force N_0 at u = 0 (the static preload, balanced by the load that makes "
             "it).")
          .def("0.0")
          .ge(0)
          .only_in({"friction_contact"})
          .to(&NonlinearElementSpec::normal_preload),
      // gear_mesh
      text("gear_mesh",
           "The [[gear_meshes]] entry whose tooth contact this is: its line of "
           "action, mean stiffness and damping, and with `contact.gear_pair` its "
           "gear pair's stiffness and unloaded TE over the mesh cycle.")
          .required()
          .only_in({"gear_mesh"})
          .to(&NonlinearElementSpec::gear_mesh),
      number("backlash", kMetre,
             "Total backlash along the line of action: the back flank closes when the approach "
             "falls below -backlash (relative to the unloaded TE).")
          .note("no back-flank contact")
          .ge(0)
          .only_in({"gear_mesh"})
          .to(&NonlinearElementSpec::backlash),
      // squeeze_film
      number("radius", kMetre, "Journal radius R of the damper land.")
          .required()
          .gt(0)
          .only_in({"squeeze_film"})
          .to(&NonlinearElementSpec::radius),
      number("length", kMetre, "Land length L (short-bearing theory: L / (2R) < 0.5).")
          .required()
          .gt(0)
          .only_in({"squeeze_film"})
          .to(&NonlinearElementSpec::length),
      number("clearance", kMetre, "Radial clearance c.")
          .required()
          .gt(0)
          .only_in({"squeeze_film"})
          .to(&NonlinearElementSpec::clearance),
      number("viscosity", kViscosity, "Dynamic viscosity mu of the oil.")
          .required()
          .gt(0)
          .only_in({"squeeze_film"})
          .to(&NonlinearElementSpec::viscosity),
      choice("film", {"pi", "full"},
             "Film model: \"pi\" (cavitated, half-Sommerfeld) or \"full\" (uncavitated 2 pi "
             "film).")
          .def("\"pi\"")
          .only_in({"squeeze_film"})
          .to_enum(&NonlinearElementSpec::cavitated, {true, false}),
  };
}

}  // namespace

Section nonlinear_elements_section() {
  return S("nonlinear_elements", SectionKind::ArrayOfTables, "[[nonlinear_elements]]",
           "Harmonic balance (`nonlinear_response`): nonlinear force elements between two nodes "
           "of any model (or a node and ground), on u = (motion of node2 - motion of node1) . "
           "direction. Ignored by the linear analyses and by drivetrain_transient.")
      .in_array(&Model::nonlinear_elements)
      .located(&NonlinearElementSpec::where)
      .fields(element_fields())
      .variants(
          "type",
          {
              variant<NonlinearElementSpec>(
                  "jenkins",
                  "A spring k in series with a Coulomb slider of slip force F: "
                  "stick-slip friction with hysteresis (a damper, a joint)."),
              variant<NonlinearElementSpec>("coulomb",
                                            "Regularised Coulomb friction f = F tanh(u' / "
                                            "v_eps), for comparison with the Jenkins element."),
              variant<NonlinearElementSpec>(
                  "friction_contact",
                  "A 2D or 3D friction contact with a variable normal load and lift-off: "
                  "N = max(N_0 + k_n u_n, 0), tangential stick-slip with k_t and mu N (Yang, Chu "
                  "& Menq 1998)."),
              variant<NonlinearElementSpec>("polynomial", "A polynomial spring f = sum c_p u^p."),
              variant<NonlinearElementSpec>("cubic", "A cubic spring f = k3 u^3 (Duffing)."),
              variant<NonlinearElementSpec>(
                  "unilateral", "A spring that acts only when closed: f = k max(u - gap, 0)."),
              variant<NonlinearElementSpec>(
                  "contact",
                  "A one-sided contact with a contact law (penalty, Hertz, IMPACT, "
                  "linear) beyond `gap`."),
              variant<NonlinearElementSpec>(
                  "gear_mesh",
                  "The tooth contact of a [[gear_meshes]] entry along its line of action: "
                  "time-varying stiffness and unloaded TE over the mesh cycle, contact loss and "
                  "back-flank contact through the backlash. The balance's fundamental is then "
                  "the mesh frequency."),
              variant<NonlinearElementSpec>(
                  "squeeze_film",
                  "A squeeze-film damper (short-bearing theory) acting on the journal motion of "
                  "node2 relative to node1 in the plane normal to `direction`."),
          })
      .sections({nonlinear_contact_law_section()})
      .finish<NonlinearElementSpec>(finish_element);
}

}  // namespace geardyn::model
