// The `type = "order_analysis"` analysis in the registry: its model-file keys and their rules, its
// checks and how it runs.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "geardyn/analyses/order_analysis.hpp"
#include "geardyn/analyses/registry.hpp"
#include "geardyn/model/schema_builder.hpp"

namespace geardyn::analyses {
namespace {

using namespace model::keys;  // NOLINT: the declaration table reads as a table
using model::Analysis;
using model::FieldValue;
using S = OrderAnalysisSettings;

std::vector<model::Field> keys() {
  return {
      text("record_file",
           "The record: a CSV file with a header row (e.g. geardyn's time_history.csv or a "
           "measurement; uniformly sampled) or geardyn's time_history.h5, relative to the model "
           "file.")
          .required()
          .to_settings(&S::record_file),
      text("time_column", "Column of the time [s].").def("\"time_s\"").to_settings(&S::time_column),
      F("channels", model::FieldType::StringArray,
        "Columns to analyse (default: every numeric column but time and the reference).")
          .unique()
          .to_settings(&S::channels),
      text("angle_column",
           "Reference: column of the shaft angle [rad], increasing (e.g. geardyn's rotation "
           "record). Give this or tacho_column.")
          .to_settings(&S::angle_column),
      text("tacho_column",
           "Reference: column of a tacho signal with pulses_per_revolution pulses per revolution "
           "of the reference shaft. Give this or angle_column.")
          .to_settings(&S::tacho_column),
      integer("pulses_per_revolution", "Tacho pulses per revolution of the reference shaft.")
          .def("1")
          .ge(1)
          .le(100000)
          .to_settings(&S::pulses_per_revolution),
      number("tacho_threshold", kNoUnit,
             "Level the tacho rises through at each pulse, in the unit of the tacho column "
             "(default: midway between its minimum and maximum).")
          .to_settings(&S::tacho_threshold),
      number("shaft_ratio", kNoUnit,
             "Speed of the analysed shaft over the reference shaft's (orders are of the analysed "
             "shaft).")
          .def("1.0")
          .gt(0)
          .to_settings(&S::shaft_ratio),
      numbers("orders", kNoUnit, "Orders to cut (cycles per revolution of the analysed shaft).")
          .required()
          .min_items(1)
          .to_settings_fn<S>([](S& s, const FieldValue& v) { s.options.orders = v.numbers; }),
      integer("revolutions_per_block",
              "Revolutions per order-analysis block: the order resolution is its inverse.")
          .def("8")
          .ge(1)
          .le(100000)
          .to_settings_fn<S>([](S& s, const FieldValue& v) {
            s.options.revolutions_per_block = static_cast<int>(v.integer);
          }),
      integer("samples_per_revolution",
              "Angle-domain samples per revolution (0: the smallest power of 2 >= 16 and >= 4 "
              "times the highest order).")
          .def("0")
          .ge(0)
          .le(65536)
          .to_settings_fn<S>([](S& s, const FieldValue& v) {
            s.options.samples_per_revolution = static_cast<int>(v.integer);
          }),
      integer("block_length", "Samples per waterfall block (and Welch PSD segment).")
          .def("4096")
          .ge(16)
          .le(16777216)
          .to_settings_fn<S>([](S& s, const FieldValue& v) {
            s.options.block_length = static_cast<int>(v.integer);
          }),
      number("overlap", kNoUnit, "Overlap of consecutive blocks, as a fraction of a block.")
          .def("0.5")
          .ge(0)
          .lt(0.95)
          .to_settings_fn<S>([](S& s, const FieldValue& v) { s.options.overlap = v.number; }),
      choice("window", {"hann", "flattop", "rectangular"},
             "Window of the waterfall and order spectra (flattop: amplitudes within 0.1 % "
             "between bins).")
          .def("\"hann\"")
          .to_settings_fn<S>([](S& s, const FieldValue& v) {
            constexpr signal::Window kWindows[] = {signal::Window::Hann, signal::Window::FlatTop,
                                                   signal::Window::Rectangular};
            s.options.window = kWindows[v.choice];
          }),
      numbers("speed_range_rpm", kRpm,
              "[min, max] speed of the analysed shaft to analyse (default: the whole record); "
              "must lie inside the speeds the record covers.")
          .increasing()
          .to_settings(&S::speed_range),
      number("db_reference", kNoUnit,
             "Reference of the dB levels, in the unit of the channels (1e-6 for acceleration in "
             "m/s^2, ISO 1683; 2e-5 for sound pressure in Pa).")
          .def("1e-6")
          .gt(0)
          .to_settings_fn<S>([](S& s, const FieldValue& v) { s.options.db_reference = v.number; }),
      boolean("a_weighting", "Also A-weighted 1/3-octave levels (IEC 61672-1).")
          .def("true")
          .to_settings_fn<S>([](S& s, const FieldValue& v) { s.options.a_weighting = v.boolean; }),
  };
}

void check_keys(const S& s, const Context& c) {
  if (s.angle_column.empty() == s.tacho_column.empty())
    throw c.error(s.angle_column.empty() ? "tacho_column" : "angle_column",
                  "exactly one reference: angle_column or tacho_column",
                  s.angle_column.empty() ? "neither" : "both");
  if (!s.speed_range.empty() && s.speed_range.size() != 2)
    throw c.error("speed_range_rpm", "two speeds [min, max]",
                  fmt::format("{} values", s.speed_range.size()));
  for (double o : s.options.orders)
    if (!(o > 0.0)) throw c.error("orders", "positive orders", fmt::format("{:g}", o));
}

}  // namespace

AnalysisType order_analysis_analysis() {
  AnalysisType type;
  type.name = "order_analysis";
  type.declare = [] {
    auto d = declaration<S>("order_analysis",
                            "Order analysis of a run-up record file (CSV or time_history.h5): "
                            "order cuts, order map, waterfall with order lines, overall level vs "
                            "speed, 1/3-octave bands and PSD.");
    d.fields = keys();
    return d;
  };
  type.check_inputs = [](const model::Model& m, const Analysis& a, const InputContext& c) {
    check_keys(a.settings_of<S>(), c);
    check_order_analysis_inputs(m, a.settings_of<S>(), c);
  };
  type.run = runner(run_order_analysis, order_analysis_output);
  type.scalars = {{"overall_rms",
                   "",
                   "RMS of channel `channel` over the analysed range (mean removed), in the "
                   "channel's unit.",
                   {"channel"}}};
  type.scalar = [](const Outcome& o, const ScalarRequest& q, std::string& unit) -> double {
    const auto& r = result_of<OrderAnalysisResult>(o);
    for (const ChannelOrders& c : r.channels)
      if (c.name == q.sensor || q.sensor.empty()) {
        unit = "";
        return std::sqrt(c.variance);
      }
    throw std::runtime_error(fmt::format("the analysis has no channel '{}'", q.sensor));
  };
  return type;
}

}  // namespace geardyn::analyses
