#pragma once
// The model as plain data, in SI units (m, kg, s, N, rad, rad/s). Filled by the parser
// (parse.hpp) from a TOML file; physics lives in fe/ and the analyses, not here.
// Every object keeps the SourceLocation of its table so later checks can point at the file.
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "geardyn/core/error.hpp"

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
  SourceLocation where;
};

// ---------------------------------------------------------------------------------------------
// Gear pairs of the mesh-excitation chain (DESIGN 4.4-4.5): geometry, tooth forces, mesh
// stiffness / STE, dynamic mesh force and engine-order harmonics (gearan/ analyses). Gear 1 is
// the pinion (the driving member under `torque`), gear 2 the wheel (or the internal gear).

/// Direction of rotation of gear 1 seen from its back (cone base side), towards the apex.
enum class GearRotation { Clockwise, CounterClockwise };
enum class SteInterpolationKind { Linear, Hold };

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
  double face_width = kNaN;  ///< [m]
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
  SteInterpolationKind ste_interpolation = SteInterpolationKind::Linear;
  double ste_shift = 0.0;          ///< fraction of a mesh cycle
  bool ste_extrapolation = false;  ///< torque outside the file's torques allowed
  int ste_samples = 0;             ///< samples per mesh cycle (0: 512 / the file's rows)
  /// Speed of gear 1 while an STE file with a time abscissa was recorded [rad/s] (NaN: none);
  /// one mesh period is 2 pi / (speed teeth1).
  double ste_speed = kNaN;
  double mesh_damping_ratio = 0.08;  ///< zeta of the dynamic mesh model
  double backlash = kNaN;            ///< [m] (NaN: no back-side contact)
  SourceLocation where;
};

// ---------------------------------------------------------------------------------------------
// Analyses

enum class EigenMethod { Auto, Dense, Sparse };
enum class Spacing { Linear, Log };
enum class ResponseQuantity { Receptance, Mobility, Accelerance };
enum class Integrator { Newmark, GeneralizedAlpha };

struct ModalSettings {
  double speed = 0.0;  ///< reference speed [rad/s]
  int n_modes = 10;
  bool complex_modes = true;  ///< also the damped gyroscopic (complex) modes
  EigenMethod method = EigenMethod::Auto;
  double shift = 0.0;  ///< shift for shift-invert [rad/s]; modes nearest to it
};

struct CampbellSettings {
  std::vector<double> speeds;  ///< reference speeds [rad/s]
  int n_modes = 8;
  std::vector<double> engine_orders = {1.0};  ///< orders of the reference shaft
  bool shaft_orders = true;                   ///< add order 1 of every shaft (x its speed ratio)
  bool mesh_orders = true;                    ///< add teeth x shaft order of every mesh with teeth
  double mac_threshold = 0.7;                 ///< below this a tracking step is flagged ambiguous
  EigenMethod method = EigenMethod::Auto;
};

struct HarmonicSettings {
  double speed = 0.0;
  double f_min = kNaN, f_max = kNaN;  ///< [rad/s]
  int n_points = 200;
  Spacing spacing = Spacing::Linear;
  bool adaptive = true;    ///< refine around peaks
  std::string input_node;  ///< unit-force input (FRF) ...
  Component input_dof = Component::Ux;
  std::vector<std::string> forces;   ///< ... or these named harmonic forces (forced response)
  std::vector<std::string> sensors;  ///< empty: all sensors
  ResponseQuantity quantity = ResponseQuantity::Receptance;
};

struct UnbalanceSettings {
  std::vector<double> speeds;           ///< [rad/s]
  std::vector<std::string> unbalances;  ///< empty: all
  std::vector<std::string> sensors;     ///< empty: all
};

struct TransientSettings {
  double speed = 0.0;       ///< constant speed, or start of a run-up [rad/s]
  double speed_end = kNaN;  ///< run-up end speed (NaN: constant speed)
  double duration = kNaN;   ///< [s]
  double time_step = kNaN;  ///< [s]
  Integrator integrator = Integrator::GeneralizedAlpha;
  double rho_infinity = 0.9;            ///< spectral radius at infinity (generalised-alpha)
  double steady_fraction = 0.5;         ///< last fraction of the record used for spectra and orbits
  std::vector<std::string> unbalances;  ///< empty: all
  std::vector<std::string> sensors;     ///< empty: all
  int output_every = 1;                 ///< store every n-th step
};

/// Scalar results a sweep tabulates per point.
struct SweepOutput {
  enum class Quantity { NaturalFrequency, CriticalSpeed, PeakAmplitude, PeakLocation, AmplitudeAt };
  Quantity quantity = Quantity::NaturalFrequency;
  int mode = 1;        ///< NaturalFrequency / CriticalSpeed: 1-based index
  std::string sensor;  ///< PeakAmplitude / PeakLocation / AmplitudeAt
  double at = kNaN;    ///< AmplitudeAt: speed or frequency [rad/s]
  std::string label;   ///< column name stem
};

struct SweepSettings {
  std::string parameter;  ///< key path, e.g. "bearings[0].kxx" or "gear_meshes[0].stiffness"
  std::vector<std::string> linked_parameters;  ///< further key paths set to the same value
  std::vector<double> values;                  ///< in the units of the key
  std::string analysis;                        ///< name of the analysis run per point
  std::vector<SweepOutput> outputs;
  bool log_x = false;  ///< plot with a log axis
  int threads = 0;     ///< 0: all cores
};

/// Modes of a solid component (the mesh as given, or the whole wheel of a cyclic one).
struct SolidModalSettings {
  std::string solid;
  int n_modes = 10;
  double f_max = kNaN;      ///< band mode: every mode up to this [rad/s] (n_modes ignored)
  bool full_wheel = false;  ///< cyclic solid: replicate the sector to 360 deg first
  int shapes = 10;          ///< mode shapes written to VTU / Gmsh files (0: none)
};

enum class ReductionMethod { None, Guyan, CraigBampton };

/// Modes per nodal diameter of a cyclic solid, optionally after Craig-Bampton reduction of the
/// sector and interface-mode reduction, and the rotating-frame Campbell diagram.
struct CyclicModalSettings {
  std::string solid;
  std::vector<int> nodal_diameters;  ///< empty: 0 .. sectors / 2
  int n_modes = 6;                   ///< per nodal diameter
  ReductionMethod reduction = ReductionMethod::None;
  int cb_modes = 40;                     ///< fixed-interface modes kept
  std::vector<std::string> master_sets;  ///< node sets kept physical besides the interfaces
  int interface_modes = 0;               ///< Tran interface modes per ND (0: interfaces kept)
  bool compare_full = false;             ///< also solve the replicated 360 deg mesh
  int shapes = 2;                        ///< expanded full-wheel shapes written per ND
  std::vector<double> speeds;            ///< Campbell speeds [rad/s] (empty: no Campbell)
  int max_engine_order = 0;              ///< 0: 2 x sectors
};

/// Craig-Bampton (or Guyan) reduction of a solid: reduced vs full frequencies, a convergence
/// table, and the reduced component file.
struct ReductionSettings {
  std::string solid;
  ReductionMethod method = ReductionMethod::CraigBampton;
  std::vector<std::string> master_sets;
  int n_modes = 20;              ///< fixed-interface modes kept
  double f_max = kNaN;           ///< ... or all up to this [rad/s]
  int compare_modes = 10;        ///< full-model modes compared
  std::vector<int> convergence;  ///< mode counts of the convergence table (empty: automatic)
  bool save = true;              ///< write <analysis>.h5
};

enum class MeshForceModel { Dynamic, InfiniteInertia };
enum class SweepDirectionKind { Up, Down, Both };

/// Geometry, tooth forces, ISO 6336 stiffness and the mesh stiffness / STE over one mesh cycle.
struct GearPairSettings {
  std::string pair;  ///< empty: every [[gear_pairs]] entry
};

/// The dynamic mesh force over a speed range of gear 1 (DESIGN 4.5).
struct MeshForceSettings {
  std::string pair;            ///< empty: the model's only gear pair
  std::vector<double> speeds;  ///< speeds of gear 1 [rad/s], increasing
  SweepDirectionKind direction = SweepDirectionKind::Both;
  MeshForceModel model = MeshForceModel::Dynamic;
  bool contact_loss = true;           ///< false: linear mesh law for every x
  std::vector<double> detail_speeds;  ///< time histories at these speeds of gear 1 [rad/s]
};

/// Engine-order harmonics of the tooth force of one gear at one speed (DESIGN 4.4).
struct MeshHarmonicsSettings {
  std::string pair;
  double speed = 0.0;  ///< speed of gear 1 [rad/s]
  int gear = 1;        ///< 1 or 2: the gear whose teeth are loaded
  MeshForceModel model = MeshForceModel::Dynamic;
  bool contact_loss = true;
  double window_shift = 0.0;         ///< tooth-load window shift [pitches of that gear]
  double contact_ratio = kNaN;       ///< window contact ratio (NaN: the total contact ratio)
  std::vector<int> nodal_diameters;  ///< empty: 0 .. N / 2
  int orders_per_diameter = 2;       ///< orders k = +-h (mod N) per nodal diameter
  int max_order = 0;                 ///< order spectrum up to this (0: 2 N)
};

/// A measured response curve: resonance peaks, Q by the half-power method, optional reference.
struct CorrelationSettings {
  std::string measured_file;  ///< as written (relative to the model file)
  double min_prominence_db = 6.0;
  int max_peaks = 8;
  double reference_peak = kNaN;       ///< reference peak position [rad/s] (speed or frequency)
  bool reference_is_speed = true;     ///< reference_peak is a speed (rpm key) or frequency (hz key)
  double reference_amplitude = kNaN;  ///< in the measured file's SI amplitude unit
  double reference_q = kNaN;
};

/// Forced response of a cyclic solid to the engine-order harmonics of its tooth force, over the
/// speed of that solid, by modal summation per (nodal diameter, engine order) (DESIGN 4.3-4.4;
/// forced/cyclic_forced_response.hpp). The harmonics come from a [[gear_pairs]] entry (computed
/// as mesh_harmonics does) or are given as force_amplitude.
struct CyclicForcedResponseSettings {
  std::string solid;
  std::string pair;  ///< [[gear_pairs]] entry (empty: force_amplitude)
  int gear = 1;      ///< 1 or 2: the member of the pair the solid is
  MeshForceModel model = MeshForceModel::Dynamic;
  bool contact_loss = true;
  double window_shift = 0.0;            ///< [pitches]
  double contact_ratio = kNaN;          ///< window contact ratio (NaN: total contact ratio)
  double harmonics_speed = kNaN;        ///< gear-1 speed of the dynamic mesh force [rad/s]
  std::vector<double> force_amplitude;  ///< [N]: one for every order, or one per engine order
  std::optional<Vec3> force_direction;  ///< of an explicit force (empty: tangential)
  bool apex_below = true;               ///< the pitch-cone apex lies on the -z side
  std::vector<int> nodal_diameters;     ///< empty: 0 .. sectors / 2
  std::vector<int> engine_orders;       ///< empty: orders_per_diameter orders per diameter
  int orders_per_diameter = 2;
  std::string excitation_set = "excitation";
  std::vector<std::string> sensor_sets;
  std::vector<int> sensor_nodes;  ///< node ids of the mesh
  std::vector<Component> sensor_components = {Component::Ux, Component::Uy, Component::Uz};
  double damping_ratio = kNaN;  ///< zeta of every mode ...
  double q_factor = kNaN;       ///< ... or Q = 1 / (2 zeta)
  std::vector<double> speeds;   ///< speeds of the solid [rad/s]
  int n_modes = 10;             ///< modes per nodal diameter
  ReductionMethod reduction = ReductionMethod::None;
  int cb_modes = 40;
  std::vector<std::string> master_sets;
  bool superpose = true;
  std::string measured_file;      ///< measured response over speed (empty: none)
  std::string measured_sensor;    ///< sensor compared (empty: the first)
  int measured_engine_order = 0;  ///< curve compared: this order (0: the superposed sum)
  bool scale_to_measured = false;
  double min_prominence_db = 6.0;
};

/// Friction-damped forced response of a cyclic gear with a damper ring in a groove, by harmonic
/// balance condensed to the ring's contacts (damper/damper_ring.hpp, DESIGN 4.6-4.7). It is a
/// cyclic forced response (the excitation, sensor, damping and speed keys are the same, for one
/// engine order) plus the ring: its contacts, the harmonics balanced and an optional
/// performance sweep.
enum class DamperSweep { None, RingMass, FrictionCoefficient, ContactStiffness };
struct DamperRingResponseSettings : CyclicForcedResponseSettings {
  int engine_order = 0;  ///< k; the nodal diameter is h = +-k mod N
  std::string gear_contact_set = "groove_contact";
  std::string ring_contact_set = "ring_contact";
  std::string ring_element_set = "ring";
  int contact_directions = 1;          ///< 1: 2D contact (normal, one slip direction); 2: 3D
  double ring_inclination = 0.0;       ///< psi [rad] of the 2D slip direction
  double normal_stiffness = kNaN;      ///< k_n per contact pair [N/m] ...
  double contact_stiffness = kNaN;     ///< ... or per contact area [N/m^3]
  double tangential_stiffness = kNaN;  ///< k_t per pair [N/m] (NaN: Mindlin ratio of k_n)
  double friction_coefficient = kNaN;  ///< mu
  int harmonics = 1;                   ///< H balanced
  int time_samples = 0;                ///< per period (0: from H)
  std::vector<int> hysteresis_pairs;   ///< contact pairs whose loops are reported (empty: 3)
  double max_step = 0.02;              ///< continuation step / (speed range, amplitude)
  DamperSweep sweep = DamperSweep::None;
  std::vector<double> sweep_values;  ///< ring-mass or stiffness factors, or mu
};

/// Forced response of a rotor model to the mesh-order harmonics of one of its [[gear_meshes]]
/// over speed (forced/rotor_mesh_response.hpp, modal method).
struct GearForcedResponseSettings {
  std::string gear_mesh;                ///< [[gear_meshes]] name (empty: the only one)
  std::string pair;                     ///< [[gear_pairs]] entry (empty: force_amplitude)
  std::vector<double> force_amplitude;  ///< [N]: one for every order, or one per order
  int max_mesh_order = 3;               ///< orders 1 .. this
  std::vector<std::string> sensors;     ///< empty: all
  std::vector<double> speeds;           ///< reference speeds [rad/s]
  int n_modes = 10;
  bool residual_vectors = true;
  std::string measured_file;    ///< measured response over speed (empty: none)
  std::string measured_sensor;  ///< sensor compared (empty: the first)
  int measured_mesh_order = 0;  ///< curve compared: this mesh order (0: the sum of the orders)
  bool scale_to_measured = false;
  double min_prominence_db = 6.0;
};

enum class AnalysisType {
  Modal,
  Campbell,
  Harmonic,
  Unbalance,
  Transient,
  Sweep,
  SolidModal,
  CyclicModal,
  Reduction,
  GearPair,
  MeshForce,
  MeshHarmonics,
  Correlation,
  CyclicForcedResponse,
  GearForcedResponse,
  DamperRingResponse
};

/// The model-file name (`type = "..."`) of each AnalysisType, in enum order.
inline constexpr std::array<const char*, 16> kAnalysisTypeNames = {"modal",
                                                                   "campbell",
                                                                   "harmonic",
                                                                   "unbalance",
                                                                   "transient",
                                                                   "sweep",
                                                                   "solid_modal",
                                                                   "cyclic_modal",
                                                                   "reduction",
                                                                   "gear_pair",
                                                                   "mesh_force",
                                                                   "mesh_harmonics",
                                                                   "correlation",
                                                                   "cyclic_forced_response",
                                                                   "gear_forced_response",
                                                                   "damper_ring_response"};
static_assert(kAnalysisTypeNames.size() ==
                  static_cast<std::size_t>(AnalysisType::DamperRingResponse) + 1,
              "one name per AnalysisType");

struct Analysis {
  std::string name;
  AnalysisType type = AnalysisType::Modal;
  bool enabled = true;  ///< false: only run through a sweep
  /// Model changes for this analysis only ("key.path=value", like --set), e.g. a variant
  /// without the gear mesh: ["gear_meshes[0].stiffness=0"].
  std::vector<std::string> overrides;
  std::variant<ModalSettings, CampbellSettings, HarmonicSettings, UnbalanceSettings,
               TransientSettings, SweepSettings, SolidModalSettings, CyclicModalSettings,
               ReductionSettings, GearPairSettings, MeshForceSettings, MeshHarmonicsSettings,
               CorrelationSettings, CyclicForcedResponseSettings, GearForcedResponseSettings,
               DamperRingResponseSettings>
      settings;
  SourceLocation where;
};

/// The analysis' settings as S when they are an S or derived from it (a damper-ring response is a
/// cyclic forced response), else null.
template <class S>
const S* settings_as(const Analysis& a) {
  return std::visit(
      [](const auto& s) -> const S* {
        if constexpr (std::is_base_of_v<S, std::decay_t<decltype(s)>>)
          return &s;
        else
          return nullptr;
      },
      a.settings);
}
template <class S>
S* settings_as(Analysis& a) {
  return const_cast<S*>(settings_as<S>(static_cast<const Analysis&>(a)));
}

struct Model {
  int version = 1;
  std::string title;
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
  std::vector<Analysis> analyses;

  const Material* find_material(const std::string& name) const;
  const Analysis* find_analysis(const std::string& name) const;
  const Solid* find_solid(const std::string& name) const;
  const GearPair* find_gear_pair(const std::string& name) const;
};

}  // namespace geardyn::model
