#pragma once
// The model as plain data, in SI units (m, kg, s, N, rad, rad/s). Filled by the parser
// (parse.hpp) from a TOML file; physics lives in fe/ and the analyses, not here.
// Every object keeps the SourceLocation of its table so later checks can point at the file.
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/model/drivetrain_spec.hpp"
#include "geardyn/model/nonlinear_element_spec.hpp"

namespace geardyn::model {

using Vec3 = std::array<double, 3>;
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Node DOF components, expressed in the node's own frame (e1, e2, e3 = spin axis).
/// For a shaft along global z the node frame is the global frame.
enum class Component { Ux = 0, Uy = 1, Uz = 2, Rx = 3, Ry = 4, Rz = 5 };
inline constexpr std::array<const char*, 6> kComponentNames = {"ux", "uy", "uz", "rx", "ry", "rz"};

struct Material {
  std::string name;
  double youngs_modulus = kNaN;  ///< E [Pa]
  double shear_modulus = kNaN;   ///< G [Pa] (given, or E / (2 (1 + poisson_ratio)))
  double density = kNaN;         ///< rho [kg/m^3]
  SourceLocation where;
};

/// One shaft section; `divisions` equal beam elements are made from it.
struct ShaftElement {
  double length = kNaN;          ///< [m]
  double outer_diameter = kNaN;  ///< [m]
  double inner_diameter = 0.0;   ///< [m], 0 for a solid section
  std::string material;          ///< empty: the shaft's material
  double loss_factor = 0.0;      ///< structural damping eta of this element (K (1 + i eta))
  int divisions = 1;
  SourceLocation where;
};

enum class BeamTheory { Timoshenko, EulerBernoulli };

/// The node DOFs a shaft (or the whole model) keeps; the others are absent (no equation) at
/// every node of that shaft, so the disks, bearings, couplings and gear meshes there act only
/// on the DOFs kept. Lateral: ux, uy, rx, ry; axial: uz; torsional: rz (node frame, e3 = axis).
enum class DofSet {
  All,
  Lateral,
  Axial,
  Torsional,
  LateralAxial,
  LateralTorsional,
  AxialTorsional
};
/// The key values of DofSet, in its order ("all", "lateral", ..., "axial+torsional").
inline constexpr std::array<const char*, 7> kDofSetNames = {
    "all",           "lateral",           "axial",          "torsional",
    "lateral+axial", "lateral+torsional", "axial+torsional"};
/// The components (ux, uy, uz, rx, ry, rz) a DOF set keeps.
std::array<bool, 6> dof_set_components(DofSet set);

/// A straight shaft along `axis` from `origin`. Nodes are named "<shaft>.<k>", k = 0..n_elements
/// counted after `divisions` are expanded. Spin speed = speed_ratio x reference speed; a shaft
/// driven through a gear pair gives `driven_by` and `gear_ratio` (spin = gear_ratio x spin of
/// driven_by; negative for opposite sense), resolved by the parser into `speed_ratio`.
struct Shaft {
  std::string name;
  std::string material;
  Vec3 origin{0.0, 0.0, 0.0};
  Vec3 axis{0.0, 0.0, 1.0};  ///< unit vector (normalised by the parser)
  double speed_ratio = 1.0;
  std::string driven_by;
  double gear_ratio = kNaN;
  double shear_coefficient =
      kNaN;  ///< NaN: Cowper's (1966) value for the (hollow) circle per element
  BeamTheory theory = BeamTheory::Timoshenko;
  bool rotary_inertia = true;
  bool gyroscopic = true;
  std::optional<DofSet> dofs;  ///< empty: the model's `dofs`
  std::vector<ShaftElement> elements;
  SourceLocation where;
};

/// A node that is not on a shaft (a gear disk on a flexible web, a housing point).
/// It spins with `spin_of` (a shaft name, empty: not spinning) about `axis`.
struct Node {
  std::string name;
  Vec3 position{0.0, 0.0, 0.0};
  Vec3 axis{0.0, 0.0, 1.0};
  std::string spin_of;
  double speed_ratio = 0.0;  ///< resolved from spin_of by the parser
  SourceLocation where;
};

/// Rigid disk at a node: mass and inertias given, or from geometry (resolved by the parser).
struct Disk {
  std::string name;
  std::string node;
  double mass = kNaN;               ///< [kg]
  double polar_inertia = kNaN;      ///< Ip about the spin axis [kg m^2]
  double diametral_inertia = kNaN;  ///< Id about a diameter [kg m^2]
  /// Geometry input (a steel blank etc.): when outer_diameter is not NaN, the parser computed
  /// mass and inertias from it with the material's density. Kept for drawing and reports.
  double outer_diameter = kNaN;  ///< [m]
  double inner_diameter = 0.0;   ///< [m]
  double thickness = kNaN;       ///< [m]
  std::string material;
  SourceLocation where;
};

struct PointMass {
  std::string name;
  std::string node;
  double mass = kNaN;
  SourceLocation where;
};

/// Bearing / bushing between `node` and ground (node2 empty) or between two nodes.
/// 6x6 stiffness and damping in `node`'s frame, row-major over (ux, uy, uz, rx, ry, rz),
/// acting on the relative motion u_node - u_node2. When `speeds` is not empty, stiffness[i]
/// and damping[i] are given at speeds[i] (reference speed, rad/s, increasing) and interpolated
/// linearly, held constant outside the table.
struct Bearing {
  using Matrix6 = std::array<double, 36>;
  std::string name;
  std::string node;
  std::string node2;
  std::vector<double> speeds;
  std::vector<Matrix6> stiffness;  ///< size 1 when not tabulated
  std::vector<Matrix6> damping;
  SourceLocation where;
};

/// General linear element between two nodes (or node and ground): full 12x12 (6x6 to ground)
/// stiffness, damping and mass in global coordinates, row-major over (node1 dofs, node2 dofs).
struct Coupling {
  std::string name;
  std::string node1;
  std::string node2;                             ///< empty: ground, matrices are 6x6
  std::vector<double> stiffness, damping, mass;  ///< empty: zero
  SourceLocation where;
};

enum class GearType { Spur, Helical, StraightBevel, SpiralBevel, Hypoid };
enum class Hand { Right, Left };
enum class Flank { Drive, Coast };

/// Linear gear-mesh coupling: a spring-damper along the line of action between the gear
/// nodes, coupling lateral, axial, torsional and tilting DOFs of both gears.
/// gear1 drives. Angles in rad.
struct GearMesh {
  std::string name;
  std::string gear1, gear2;
  GearType type = GearType::Spur;
  int teeth1 = 0, teeth2 = 0;                       ///< for gear-mesh orders (0: unknown)
  double base_radius1 = kNaN, base_radius2 = kNaN;  ///< [m]
  double pressure_angle = kNaN;    ///< transverse (spur), normal (helical, bevel) [rad]
  double helix_angle = 0.0;        ///< helix / mean spiral angle [rad]
  double pitch_cone_angle1 = 0.0;  ///< bevel only [rad]
  double pitch_cone_angle2 = 0.0;
  Hand hand = Hand::Right;  ///< hand of gear1's helix / spiral
  Flank flank = Flank::Drive;
  double stiffness = kNaN;             ///< mesh stiffness along the line of action [N/m]
  double damping = 0.0;                ///< [N s/m]
  std::optional<Vec3> mesh_direction;  ///< from gear1's centre towards the pitch point; default
                                       ///< from the node positions
  /// The tooth contact of the drivetrain transient (absent: a contact with the constant
  /// `stiffness`, no back flank, the linear law).
  std::optional<MeshContactSpec> contact;
  SourceLocation where;
};

struct Constraint {
  std::string node;
  std::vector<Component> dofs;  ///< in the node's frame
  SourceLocation where;
};

struct Unbalance {
  std::string name;
  std::string node;
  double mass_eccentricity = kNaN;  ///< m e [kg m]
  double phase = 0.0;               ///< [rad]
  SourceLocation where;
};

/// A force or moment at a node along a component of the node frame, amplitude and phase.
struct HarmonicForce {
  std::string name;
  std::string node;
  Component dof = Component::Ux;
  double amplitude = kNaN;  ///< [N] or [N m]
  double phase = 0.0;       ///< [rad]
  SourceLocation where;
};

struct Sensor {
  std::string name;
  std::string node;               ///< a solid sensor: "<solid>/<node_set>" (set by the parser)
  Component dof = Component::Ux;  ///< in the node's frame (a solid sensor: global ux, uy, uz)
  std::string solid;              ///< non-empty: the mean motion of a node set of this solid
  std::string node_set;           ///< with `solid`
  SourceLocation where;
};

/// Frequency band with a modal damping ratio (applies to modes whose undamped frequency lies in
/// [f_min, f_max)).
struct DampingBand {
  double f_min = 0.0;  ///< [rad/s] inside (keys say _hz)
  double f_max = 0.0;
  double ratio = 0.0;
};

struct Damping {
  double rayleigh_alpha = 0.0;       ///< C += alpha M [1/s]
  double rayleigh_beta = 0.0;        ///< C += beta K [s]
  double loss_factor = 0.0;          ///< global structural eta (frequency domain only)
  double modal_ratio = 0.0;          ///< ratio for every mode not in modal_ratios / bands
  std::vector<double> modal_ratios;  ///< per mode, in order of undamped frequency
  std::vector<DampingBand> bands;
  int modal_modes = 0;  ///< modes used to build modal damping (0: none used)
  bool any_modal() const { return modal_ratio > 0.0 || !modal_ratios.empty() || !bands.empty(); }
};

// ---------------------------------------------------------------------------------------------
// Solid components (3D finite elements): a mesh file, a generated sector or plate, a reduced
// component saved by an earlier run, or stiffness and mass matrices exported by another FE code
// (Matrix Market) with their DOF map. A cyclic component is one sector of `sectors`.

enum class SolidSource { MeshFile, AnnularPlate, GearSector, Reduced, Matrices };

/// Annular plate about the z axis (the whole plate, or one sector when Solid::sectors > 1).
struct AnnularPlateSpec {
  double inner_radius = kNaN;        ///< [m]
  double outer_radius = kNaN;        ///< [m]
  double thickness = kNaN;           ///< [m]
  int radial_elements = 8;           ///< elements across the radius
  int circumferential_elements = 0;  ///< over the mesh's angle (0: about square elements)
  int layers = 2;                    ///< elements through the thickness
  int order = 2;                     ///< 1: linear, 2: quadratic elements
};

/// Gear-blank sector about the z axis with an optional damper-ring groove and ring.
struct GearSectorSpec {
  int teeth = 0;
  double module = kNaN;               ///< [m]
  double pressure_angle = kNaN;       ///< [rad]
  double face_width = kNaN;           ///< [m]
  double bore_radius = kNaN;          ///< [m]
  double hub_radius = kNaN;           ///< [m]
  double hub_width = kNaN;            ///< [m]
  double hub_offset = 0.0;            ///< axial centre of the hub from mid-face [m]
  double web_thickness = kNaN;        ///< [m]
  double web_offset = 0.0;            ///< axial centre of the web from mid-face [m]
  double rim_inner_radius = kNaN;     ///< [m]
  bool groove = false;                ///< damper-ring groove and ring
  double groove_position = 0.0;       ///< axial position of the groove centre from mid-face [m]
  double groove_width = kNaN;         ///< [m]
  double groove_depth = kNaN;         ///< [m]
  double ring_width = kNaN;           ///< axial width of the ring [m] (NaN: groove_width)
  double ring_thickness = kNaN;       ///< radial thickness of the ring [m]
  double element_size = kNaN;         ///< global target size [m]
  double tooth_element_size = kNaN;   ///< at the teeth (and the groove) [m]
  double groove_element_size = kNaN;  ///< at the groove and ring (NaN: tooth_element_size) [m]
  int order = 2;
};

/// Joins a node set of a solid to a rotor node (RBE2 / RBE3-like, solid/mesh.hpp RigidElement):
/// rigid: the set moves with the node as a rigid body; averaging: the node moves with the
/// weighted least-squares rigid fit of the set's translations, without stiffening the set.
enum class SpiderKind { Rigid, Averaging };
struct Spider {
  std::string node_set;  ///< node set of the solid's mesh
  std::string node;      ///< rotor node: "<shaft>.<k>" or a [[nodes]] name
  SpiderKind kind = SpiderKind::Rigid;
  SourceLocation where;
};

struct Solid {
  std::string name;
  SolidSource source = SolidSource::MeshFile;
  std::string mesh;            ///< mesh file (Gmsh .msh, Nastran .bdf/.dat/.nas/.blk), as written
  std::string reduced;         ///< reduced component (.h5), as written
  std::string stiffness_file;  ///< Matrix Market K (type matrices), as written
  std::string mass_file;       ///< Matrix Market M (type matrices), as written
  std::string dof_map_file;    ///< DOF map CSV of K and M (type matrices), as written
  std::string material;        ///< gear / plate / Gmsh-mesh material
  std::string ring_material;   ///< damper ring (generated gear sectors)
  int sectors = 1;             ///< the body is `sectors` copies of this mesh about z (1: whole)
  double interface_tolerance = 1e-6;          ///< sector interface matching [m]
  std::vector<std::string> fixed_sets;        ///< node sets whose translations are fixed
  bool unsupported_cards_are_errors = false;  ///< Nastran: unsupported card -> error
  AnnularPlateSpec annular_plate;
  GearSectorSpec gear_sector;
  std::vector<Spider> spiders;  ///< joints to rotor nodes (non-empty: part of the rotor system)
  int coupling_modes = 20;      ///< fixed-interface modes kept when joined to the rotor
  /// Viscous ratio zeta of every fixed-interface mode when joined to the rotor (docs/theory.md
  /// §9, eq. 9.4): C_eta = diag(2 zeta omega_k); the constraint modes stay undamped. 0: none.
  double modal_damping_ratio = 0.0;
  SourceLocation where;
};

// ---------------------------------------------------------------------------------------------
// Gear pairs of the mesh-excitation chain (docs/theory.md §11-13): geometry, tooth forces, mesh
// stiffness / STE, dynamic mesh force and engine-order harmonics (gearan/ analyses). Gear 1 is
// the pinion (the driving member under `torque`), gear 2 the wheel (or the internal gear).

/// Direction of rotation of gear 1 seen from its back (cone base side), towards the apex.
enum class GearRotation { Clockwise, CounterClockwise };
enum class SteInterpolationKind { Linear, Hold };
enum class SteSourceKind { Iso, ToothContact };

enum class ReliefShapeKind { Linear, Parabolic };

/// Flank modifications of one gear of a pair ([gear_pairs.flank1] / [gear_pairs.flank2]),
/// material removed normal to the flank [m]; the loaded tooth contact analysis (docs/theory.md
/// §15) uses them.
struct FlankModificationSpec {
  double tip_relief = 0.0;                    ///< C_a at the tip
  double tip_relief_start_diameter = kNaN;    ///< [m]
  double tip_relief_start_roll_angle = kNaN;  ///< [rad] (alternative to the diameter)
  ReliefShapeKind tip_relief_shape = ReliefShapeKind::Linear;
  double root_relief = 0.0;  ///< C_f at the start of the active profile
  double root_relief_start_diameter = kNaN;
  double root_relief_start_roll_angle = kNaN;
  ReliefShapeKind root_relief_shape = ReliefShapeKind::Linear;
  double profile_crowning = 0.0;  ///< C_alpha
  double lead_crowning = 0.0;     ///< C_beta
  double lead_slope = 0.0;        ///< f_Hbeta
  double end_relief = 0.0, end_relief_length = 0.0;
  ReliefShapeKind end_relief_shape = ReliefShapeKind::Linear;
  std::vector<double> pitch_deviations;  ///< per tooth [m] (empty: none)
  /// Topological modification map, CSV over roll angle x face position (relative to the model
  /// file; empty: none).
  std::string topography_file;
  SourceLocation where;
};

/// Ease-off of a bevel / hypoid pair ([gear_pairs.ease_off], docs/theory.md §15.9): the relative
/// flank modification over the pinion's normalised roll angle xi and face position eta [m].
struct EaseOffSpec {
  double profile_crowning = 0.0;  ///< C_a at xi = +-1
  double length_crowning = 0.0;   ///< C_b at eta = +-1
  double bias = 0.0;              ///< B, the xi eta (twist) term
  double profile_slope = 0.0;     ///< F_a, the flank-angle modification at xi = 1
  double length_slope = 0.0;      ///< F_b, the spiral-angle modification at eta = 1
  SourceLocation where;
};

/// The slice model of the loaded tooth contact analysis ([gear_pairs.contact]).
enum class ContactComplianceKind { Analytic, Fe };

struct ContactModelSpec {
  int positions = 64;  ///< mesh positions per mesh cycle
  int slices = 40;     ///< slices over the face width
  /// Decay length of the coupling between neighbouring slices of a tooth [m] (0: uncoupled;
  /// NaN: 2.5 m_n, analyses::kCouplingLengthPerModule).
  double coupling_length = kNaN;
  double misalignment = 0.0;                ///< f_ma in the plane of action over b [m]
  double axis_inclination_deviation = 0.0;  ///< f_Sigma_delta over b [m]
  double axis_deviation = 0.0;              ///< f_Sigma_beta over b [m]
  double mounting_h = 0.0;                  ///< bevel / hypoid mounting error H: pinion axial [m]
  double mounting_v = 0.0;                  ///< bevel / hypoid mounting error V: offset [m]
  double mounting_j = 0.0;                  ///< bevel / hypoid mounting error J: wheel axial [m]
  double shaft_angle_error = 0.0;           ///< bevel / hypoid mounting error Delta Sigma [rad]
  bool hunting_period = true;               ///< with pitch deviations: lcm(z1, z2) cycles
  /// [[gear_meshes]] name of the rotor's mesh of this pair (empty: none): its static
  /// deflection under the pair's tooth forces adds to the misalignment (docs/theory.md §15.7).
  std::string deflection_mesh;
  /// Compliance route (docs/theory.md §15.8): analytic slices or FE influence coefficients.
  ContactComplianceKind compliance = ContactComplianceKind::Analytic;
  double fe_mesh_size = 0.35;  ///< element size at the loaded tooth / m_n
  int fe_profile_points = 9;   ///< FE grid: roll positions over the active profile
  int fe_face_points = 0;      ///< FE grid: face positions (0: one per m_n / 2, >= 5)
  int fe_teeth = 0;            ///< 0: the whole gear; odd 1 ... 7: a segment
  SourceLocation where;
};

struct GearPair {
  std::string name;
  GearType type = GearType::Spur;
  bool internal = false;              ///< gear 2 is an internal gear (spur, helical)
  int teeth1 = 0, teeth2 = 0;         ///< z1, z2
  double module = kNaN;               ///< normal module; bevel: outer transverse module [m]
  double pressure_angle = kNaN;       ///< normal pressure angle of the rack [rad]
  double helix_angle = 0.0;           ///< helix / mean spiral (hypoid: wheel's) angle [rad]
  double pinion_spiral_angle = kNaN;  ///< hypoid: the pinion's mean spiral angle [rad]
  Hand hand = Hand::Right;            ///< hand of gear 1's helix / spiral
  GearRotation rotation = GearRotation::Clockwise;
  /// Face width of the contact [m]: the smaller of face_width1 and face_width2 (ISO 6336-1: b
  /// in the mesh stiffness and the overlap ratio is the common width of the pair).
  double face_width = kNaN;
  double face_width1 = kNaN, face_width2 = kNaN;  ///< of gear 1 and gear 2 [m]
  double profile_shift1 = 0.0, profile_shift2 = 0.0;
  double addendum_coefficient = 1.0, dedendum_coefficient = 1.25;
  double centre_distance = kNaN;            ///< working centre distance [m] (NaN: zero backlash)
  double shaft_angle = kNaN;                ///< bevel / hypoid Sigma [rad]
  double outer_cone_distance = kNaN;        ///< bevel / hypoid R_e [m] (NaN: from the module)
  double torque = kNaN;                     ///< on gear 1 [N m]
  double inertia1 = kNaN, inertia2 = kNaN;  ///< polar inertias [kg m^2] (may be infinite)
  std::string material1, material2;         ///< empty: steel, E = 206 GPa
  double stiffness_correction = 0.8;        ///< ISO 6336-1 C_M
  double application_factor = 1.0;          ///< ISO 6336-1 K_A
  bool load_correction = true;              ///< ISO 6336-1 stiffness correction for light loads
  double rim_thickness = kNaN, web_thickness = kNaN;  ///< gear blank with a web [m]
  std::string ste_file;  ///< STE CSV as written (relative to the model file)
  /// LTCA table of another tool (TE, stiffness over angle x torque x H/V/J), as written.
  std::string ltca_file;
  /// Without ste_file / ltca_file: the loaded tooth contact analysis (default) or the
  /// synthetic ISO 6336 STE.
  SteSourceKind ste_source = SteSourceKind::ToothContact;
  SteInterpolationKind ste_interpolation = SteInterpolationKind::Linear;
  double ste_shift = 0.0;          ///< fraction of a mesh cycle
  bool ste_extrapolation = false;  ///< torque outside the file's torques allowed
  int ste_samples = 0;             ///< samples per mesh cycle (0: 512 / the file's rows)
  /// Speed of gear 1 while an STE file with a time abscissa was recorded [rad/s] (NaN: none);
  /// one mesh period is 2 pi / (speed teeth1).
  double ste_speed = kNaN;
  double mesh_damping_ratio = 0.08;  ///< zeta of the dynamic mesh model
  double backlash = kNaN;            ///< [m] (NaN: no back-side contact)
  FlankModificationSpec flank1, flank2;
  EaseOffSpec ease_off;  ///< bevel / hypoid only
  ContactModelSpec contact;
  SourceLocation where;
};

// ---------------------------------------------------------------------------------------------
// Analyses

/// The settings of one analysis. Each analysis type declares its own struct, derived from this
/// through SettingsOf, next to its driver (src/geardyn/analyses/<type>.hpp); the model file's
/// keys of that type fill it. The model only holds them.
struct AnalysisSettings {
  virtual ~AnalysisSettings() = default;
  virtual std::unique_ptr<AnalysisSettings> clone() const = 0;
};

/// `struct MySettings : SettingsOf<MySettings> {...}` gives MySettings its clone(); a settings
/// struct that extends another gives that one as Base.
template <class Derived, class Base = AnalysisSettings>
struct SettingsOf : Base {
  std::unique_ptr<AnalysisSettings> clone() const override {
    return std::make_unique<Derived>(static_cast<const Derived&>(*this));
  }
};

/// Owns an analysis's settings with value semantics (a copied Analysis copies its settings).
class AnalysisSettingsValue {
 public:
  AnalysisSettingsValue() = default;
  AnalysisSettingsValue(std::unique_ptr<AnalysisSettings> s) : p_(std::move(s)) {}  // NOLINT
  AnalysisSettingsValue(const AnalysisSettingsValue& o) : p_(o.p_ ? o.p_->clone() : nullptr) {}
  AnalysisSettingsValue(AnalysisSettingsValue&&) noexcept = default;
  AnalysisSettingsValue& operator=(const AnalysisSettingsValue& o) {
    if (this != &o) p_ = o.p_ ? o.p_->clone() : nullptr;
    return *this;
  }
  AnalysisSettingsValue& operator=(AnalysisSettingsValue&&) noexcept = default;
  AnalysisSettings* get() const { return p_.get(); }

 private:
  std::unique_ptr<AnalysisSettings> p_;
};

struct Analysis {
  std::string name;
  std::string type;     ///< the analysis type's name in the registry ("modal", "campbell", ...)
  bool enabled = true;  ///< false: only run through a sweep
  /// Model changes for this analysis only ("key.path=value", like --set), e.g. a variant
  /// without the gear mesh: ["gear_meshes[0].stiffness=0"].
  std::vector<std::string> overrides;
  AnalysisSettingsValue settings;
  SourceLocation where;

  /// The settings as S when they are an S or derived from it (a damper-ring response is a
  /// cyclic forced response), else null.
  template <class S>
  const S* settings_as() const {
    return dynamic_cast<const S*>(settings.get());
  }
  template <class S>
  S* settings_as() {
    return dynamic_cast<S*>(settings.get());
  }
  /// The settings as S; std::logic_error when they are not (a caller's bug, not bad input).
  template <class S>
  const S& settings_of() const {
    const S* s = settings_as<S>();
    if (s == nullptr)
      throw std::logic_error("analysis '" + name + "' has settings of another type");
    return *s;
  }
  template <class S>
  S& settings_of() {
    S* s = settings_as<S>();
    if (s == nullptr)
      throw std::logic_error("analysis '" + name + "' has settings of another type");
    return *s;
  }
};

struct Model {
  int version = 1;
  std::string title;
  DofSet dofs = DofSet::All;  ///< DOFs of every node (a shaft's `dofs` overrides it)
  std::string source_file;
  std::vector<Material> materials;
  std::vector<Shaft> shafts;
  std::vector<Node> nodes;
  std::vector<Disk> disks;
  std::vector<PointMass> point_masses;
  std::vector<Bearing> bearings;
  std::vector<Coupling> couplings;
  std::vector<GearMesh> gear_meshes;
  std::vector<Constraint> constraints;
  std::vector<Unbalance> unbalances;
  std::vector<HarmonicForce> forces;
  std::vector<Sensor> sensors;
  Damping damping;
  std::vector<Solid> solids;
  std::vector<GearPair> gear_pairs;
  // The nonlinear drivetrain (drivetrain_spec.hpp; used by drivetrain_transient only).
  std::vector<ContactSpec> contacts;
  std::vector<BoltSpec> bolts;
  std::vector<BushingSpec> bushings;
  std::vector<RollingBearingSpec> rolling_bearings;
  std::vector<DriverSpec> drivers;
  std::vector<LoadTorqueSpec> loads;
  std::vector<ClutchSpec> clutches;
  std::vector<VirtualSensorSpec> virtual_sensors;
  // Nonlinear elements of harmonic balance (nonlinear_element_spec.hpp; nonlinear_response only).
  std::vector<NonlinearElementSpec> nonlinear_elements;
  std::vector<Analysis> analyses;

  const Material* find_material(const std::string& name) const;
  const Analysis* find_analysis(const std::string& name) const;
  const Solid* find_solid(const std::string& name) const;
  const GearPair* find_gear_pair(const std::string& name) const;
};

}  // namespace geardyn::model
