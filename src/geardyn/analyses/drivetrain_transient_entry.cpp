// The `type = "drivetrain_transient"` analysis in the registry: its model-file keys and their
// rules, its checks, how it runs and what it offers to sweeps.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/analyses/common_checks.hpp"
#include "geardyn/analyses/drivetrain_transient.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/rotor_scalars.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {
namespace {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;
using model::FieldValue;

void check(const Analysis& a, const std::string& path, const model::ModelCheck& check) {
  const auto& t = a.settings_of<DrivetrainTransientSettings>();
  const auto& m = check.model();
  check.check_named(path + ".sensors", t.sensors, model::names_of(m.virtual_sensors),
                    "virtual sensor", "virtual_sensors");
  if (const auto p = frf_settings_problem(m, t))
    check.fail(path + "." + p->key, p->expected, p->found, p->hint);
  if (!t.order_channels.empty() && t.order_reference.empty())
    check.fail(path + ".order_reference", "the angle channel of the order analysis's shaft", "none",
               "e.g. order_reference = \"<mesh>_pinion_angle_rad\"");
  if (!t.order_channels.empty() && t.order_options.orders.empty())
    check.fail(path + ".orders", "the orders to cut (with order_channels)", "none");
  for (double o : t.order_options.orders)
    if (!(o > 0.0)) check.fail(path + ".orders", "positive orders", fmt::format("{:g}", o));
  if (m.drivers.empty())
    check.fail(path + ".type", "a model with at least one [[drivers]] entry", "no [[drivers]]",
               "add a speed driver or a motor on the input shaft's node");
}

std::vector<model::Field> keys() {
  return {
      number("duration", kSecond, "Simulated time from t = 0.")
          .required()
          .gt(0)
          .to_settings(&DrivetrainTransientSettings::duration),
      number("sample_rate_hz", kHertz,
             "Output samples per second, independent of the integrator's steps (interpolated "
             "within a step); spectra reach sample_rate_hz / 2.")
          .required()
          .gt(0)
          .to_settings(&DrivetrainTransientSettings::sample_angular_rate),
      choice("integrator", {"generalized_alpha", "ida"},
             "Adaptive integrator: geardyn's generalised-alpha with local error control and "
             "contact event location, or SUNDIALS IDA (variable-order BDF).")
          .def("\"generalized_alpha\"")
          .to_settings_enum(&DrivetrainTransientSettings::integrator,
                            {DrivetrainIntegrator::GeneralizedAlpha, DrivetrainIntegrator::Ida}),
      number("relative_tolerance", kNoUnit, "Local error tolerance, relative to the state.")
          .def("1e-4")
          .gt(0)
          .lt(1)
          .to_settings(&DrivetrainTransientSettings::relative_tolerance),
      number("absolute_tolerance", kMetre, "Local error tolerance, absolute (m or rad).")
          .def("1e-9")
          .gt(0)
          .to_settings(&DrivetrainTransientSettings::absolute_tolerance),
      number("max_step", kSecond, "Largest time step.")
          .gt(0)
          .note("1 / sample_rate_hz")
          .to_settings(&DrivetrainTransientSettings::max_step),
      number("rho_infinity", kNoUnit,
             "Spectral radius at infinite frequency of generalised-alpha (1: no numerical "
             "damping).")
          .def("0.8")
          .ge(0)
          .le(1)
          .to_settings(&DrivetrainTransientSettings::rho_infinity),
      boolean("static_start",
              "Start from the static equilibrium under the loads and preloads at t = 0 (drivers "
              "and motors held); false: from the undeformed state.")
          .def("true")
          .to_settings(&DrivetrainTransientSettings::static_start),
      integer("modes", "Modes of the linearisation at the operating point tabulated (0: none).")
          .def("20")
          .ge(0)
          .le(1000)
          .to_settings(&DrivetrainTransientSettings::modes),
      names("sensors", model::Ref::None, "[[virtual_sensors]] recorded.")
          .note("all virtual sensors")
          .to_settings(&DrivetrainTransientSettings::sensors),
      number("spectrum_start", kSecond,
             "Spectra and orbits (two sensors on one node along different directions) are taken "
             "over [spectrum_start, duration].")
          .def("0.0")
          .ge(0)
          .to_settings(&DrivetrainTransientSettings::spectrum_start),
      text("frf_excitation",
           "FRF by modal superposition at the operating point (left and right eigenvectors of "
           "the linearisation, docs/theory.md §16.14): the load, the name of a "
           "[[virtual_sensors]] entry (a unit force at its node along its DOF or direction, a "
           "unit moment for a rotation DOF or `rotation = true`) or of a [[gear_meshes]] entry "
           "(a unit pair of opposite forces along its line of action, the dynamic mesh force). "
           "Table frf: every recorded sensor's response per unit load, magnitude and phase.")
          .note("no FRF")
          .to_settings(&DrivetrainTransientSettings::frf_excitation),
      numbers("frf_band_hz", kHertz, "FRF band [f_min, f_max], 0 <= f_min < f_max.")
          .note("0 to 1.25 x the highest mode of the sum")
          .to_settings(&DrivetrainTransientSettings::frf_band),
      integer("frf_points", "FRF frequencies, evenly spaced over frf_band_hz.")
          .def("400")
          .ge(2)
          .le(100000)
          .to_settings(&DrivetrainTransientSettings::frf_points),
      integer("frf_modes",
              "Modes in the FRF's sum: the lowest of the linearisation, at most `modes` (0: all "
              "`modes`). The modes above are truncated: the notes give the error this leaves at "
              "0 Hz (residual flexibility) and against a direct solve in the band.")
          .def("0")
          .ge(0)
          .le(1000)
          .to_settings(&DrivetrainTransientSettings::frf_modes),
      boolean("frf_static_correction",
              "Add the truncated modes' static part K_t^-1 f - (the sum at 0 Hz) to the FRF at "
              "every frequency (static correction, mode-acceleration method): exact at 0 Hz; "
              "false: the plain modal sum. Needs K_t regular (no free spin).")
          .def("true")
          .to_settings(&DrivetrainTransientSettings::frf_static_correction),
      choice("frf_quantity", {"displacement", "velocity", "acceleration"},
             "Response per unit load in the FRF: receptance (m/N), mobility (i w x: m/s/N) or "
             "accelerance (-w^2 x: m/s^2/N); rad instead of m for rotation sensors, per N m for "
             "a moment.")
          .def("\"displacement\"")
          .to_settings_enum(
              &DrivetrainTransientSettings::frf_quantity,
              {FrfQuantity::Displacement, FrfQuantity::Velocity, FrfQuantity::Acceleration}),
      F("order_channels", model::FieldType::StringArray,
        "Channels of the record (columns of time_history) to order-analyse as order_analysis "
        "does: order cuts, order map, waterfall with order lines, levels, 1/3-octave bands, PSD "
        "(empty: none).")
          .unique()
          .to_settings(&DrivetrainTransientSettings::order_channels),
      text(
          "order_reference",
          "The angle channel [rad] of the order analysis's shaft, e.g. \"<mesh>_pinion_angle_rad\" "
          "(needed with order_channels).")
          .to_settings(&DrivetrainTransientSettings::order_reference),
      numbers("orders", kNoUnit, "Orders of the order analysis (of order_reference's shaft).")
          .to_settings_fn<DrivetrainTransientSettings>(
              [](DrivetrainTransientSettings& s, const FieldValue& v) {
                s.order_options.orders = v.numbers;
              }),
      integer("order_revolutions_per_block",
              "Revolutions per order block of the order analysis (order resolution 1 / this).")
          .def("1")
          .ge(1)
          .le(100000)
          .to_settings_fn<DrivetrainTransientSettings>(
              [](DrivetrainTransientSettings& s, const FieldValue& v) {
                s.order_options.revolutions_per_block = static_cast<int>(v.integer);
              }),
      integer("order_block_length", "Samples per waterfall block of the order analysis.")
          .def("256")
          .ge(16)
          .le(16777216)
          .to_settings_fn<DrivetrainTransientSettings>(
              [](DrivetrainTransientSettings& s, const FieldValue& v) {
                s.order_options.block_length = static_cast<int>(v.integer);
              }),
      number("order_db_reference", kNoUnit,
             "Reference of the order analysis's dB levels, in the unit of its channels (1e-6 for "
             "m/s^2, ISO 1683).")
          .def("1e-6")
          .gt(0)
          .to_settings_fn<DrivetrainTransientSettings>(
              [](DrivetrainTransientSettings& s, const FieldValue& v) {
                s.order_options.db_reference = v.number;
              }),
  };
}

}  // namespace

AnalysisType drivetrain_transient_analysis() {
  AnalysisType type;
  type.name = "drivetrain_transient";
  type.declare = [] {
    auto d = declaration<DrivetrainTransientSettings>(
        "drivetrain_transient",
        "Nonlinear drivetrain in the time domain: drivers and loads on the shafts' spins, tooth "
        "contact with backlash, rolling bearings, bushings, preloaded bolts and contacts; static "
        "equilibrium, linearisation (modal table) and an adaptive run with virtual sensors.");
    d.fields = keys();
    d.check = check;
    return d;
  };
  type.run = runner(run_drivetrain_transient, drivetrain_transient_output);
  type.scalars = {{"channel_peak", "", "Largest |x(t)| of `channel` over the record.", {"channel"}},
                  {"channel_rms", "", "RMS of `channel` over the record.", {"channel"}}};
  type.scalar = [](const Outcome& o, const ScalarRequest& q, std::string& unit) {
    const auto& r = result_of<DrivetrainTransientResult>(o);
    const auto it = std::find_if(r.channels.begin(), r.channels.end(),
                                 [&](const DrivetrainChannel& c) { return c.name == q.sensor; });
    if (it == r.channels.end())
      throw std::runtime_error("drivetrain_transient has no channel '" + q.sensor +
                               "' (the columns of its time_history table)");
    if (r.time.empty()) throw std::runtime_error("drivetrain_transient recorded no samples");
    const Eigen::VectorXd x = r.values.col(it - r.channels.begin());
    unit = it->unit;
    if (q.quantity == "channel_peak") return x.cwiseAbs().maxCoeff();
    if (q.quantity == "channel_rms")
      return std::sqrt(x.squaredNorm() / static_cast<double>(x.size()));
    unknown_scalar("drivetrain_transient", q.quantity);
  };
  return type;
}

}  // namespace geardyn::analyses
