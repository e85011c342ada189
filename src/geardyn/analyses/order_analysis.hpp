#pragma once
// order_analysis: order analysis of a run-up (or any) time record read from a file
// (docs/theory.md §14; issue #17): a CSV with a header row (geardyn's time_history.csv or a
// measurement) or geardyn's time_history.h5.
//
//   record -> time, channels, reference (an angle column [rad] or a tacho column with its
//   pulses per revolution) x shaft ratio -> the analysed shaft's angle
//     -> per channel: computed order tracking (signal/order_tracking: resampling to the angle,
//        order cuts and order map over blocks of whole revolutions), waterfall (signal/
//        waterfall: short-time spectra vs mean speed, with order lines), overall RMS level per
//        waterfall block, Welch PSD and 1/3-octave band levels (linear and A-weighted) of the
//        analysed range.
// analyse_orders() is the record-independent core, shared with drivetrain_transient's own
// order analysis. Bad input throws InputError (check_order_analysis_inputs runs before any
// analysis: missing file or column, non-increasing time with the file's line, a tacho with fewer
// than 2 pulses, an angle that does not increase, a speed range the record does not cover).
#include <Eigen/Dense>
#include <filesystem>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/signal/order_tracking.hpp"
#include "geardyn/signal/waterfall.hpp"

namespace geardyn::analyses {

/// What to compute, independent of where the record comes from.
struct OrderAnalysisOptions {
  std::vector<double> orders;      ///< orders to cut (of the analysed shaft)
  int revolutions_per_block = 8;   ///< order resolution 1 / revolutions_per_block
  int samples_per_revolution = 0;  ///< angle-domain sampling (0: automatic)
  int block_length = 4096;         ///< waterfall block [samples]
  double overlap = 0.5;            ///< of the waterfall and order blocks
  signal::Window window = signal::Window::Hann;
  double speed_min_rpm = 0.0;  ///< analysed range; both 0: the whole record
  double speed_max_rpm = 0.0;
  double db_reference = 1e-6;  ///< reference of the levels, in the unit of the channels
  bool a_weighting = true;     ///< also A-weighted 1/3-octave levels
};

/// One channel's results.
struct ChannelOrders {
  std::string name;  ///< the column name (carries the unit suffix)
  signal::OrderCuts cuts;
  signal::OrderSpectra map;
  signal::Waterfall waterfall;
  Eigen::VectorXd block_rms;  ///< RMS of each waterfall block (mean removed)
  Eigen::VectorXd psd_frequency_hz, psd;
  double variance = 0.0;         ///< of the analysed range
  Eigen::VectorXd band_power;    ///< per 1/3-octave band (linear)
  Eigen::VectorXd band_power_a;  ///< A-weighted
};

struct OrderAnalysisResult {
  std::vector<ChannelOrders> channels;
  std::vector<double> band_nominal_hz, band_mid_hz;
  int samples_per_revolution = 0;
  double sample_rate_hz = 0.0;
  double start_s = 0.0, end_s = 0.0;                    ///< analysed time range
  double covered_min_rpm = 0.0, covered_max_rpm = 0.0;  ///< speeds the record covers
  double max_rate_rpm_per_s = 0.0;                      ///< largest |dn/dt| in the analysed range
  std::string reference;  ///< how the angle was obtained, for the notes
};

/// The record-independent core: time (uniform), channels (samples x channels, named) and the
/// analysed shaft's angle [rad] at each sample (increasing); samples outside [first_valid,
/// last_valid] (e.g. before the first tacho pulse) are not analysed. Throws InputError through
/// `context` at `key_prefix` keys for a speed range the record does not cover.
OrderAnalysisResult analyse_orders(const Eigen::VectorXd& time_s, const Eigen::MatrixXd& values,
                                   const std::vector<std::string>& names,
                                   const Eigen::VectorXd& angle_rad, Eigen::Index first_valid,
                                   Eigen::Index last_valid, const OrderAnalysisOptions& options,
                                   const Context& context);

/// The analysed samples [start, end] within [first_valid, last_valid]: those whose speed is in
/// the options' range (all when it is empty), and the speeds the valid samples cover. InputError
/// at speed_range_rpm for a range the record does not cover (naming the range it covers).
struct AnalysedSpan {
  Eigen::Index start = 0, end = 0;
  double covered_min_rpm = 0.0, covered_max_rpm = 0.0;
};
AnalysedSpan analysed_span(const Eigen::VectorXd& time_s, const Eigen::VectorXd& angle_rad,
                           Eigen::Index first_valid, Eigen::Index last_valid,
                           const OrderAnalysisOptions& options, const Context& context);

/// Tables, plots and notes of an order analysis; table and plot names start with `prefix`.
void add_order_analysis_output(AnalysisOutput& out, const OrderAnalysisResult& r,
                               const OrderAnalysisOptions& options, const std::string& prefix);

struct OrderAnalysisSettings : model::SettingsOf<OrderAnalysisSettings> {
  std::string record_file;
  std::string time_column = "time_s";
  std::vector<std::string> channels;  ///< empty: every column but time and the reference
  std::string angle_column;
  std::string tacho_column;
  int pulses_per_revolution = 1;
  double tacho_threshold = model::kNaN;  ///< NaN: midway between the tacho's min and max
  double shaft_ratio = 1.0;              ///< analysed shaft speed / reference shaft speed
  std::vector<double> speed_range;       ///< [rad/s] (key speed_range_rpm); empty: all
  OrderAnalysisOptions options;
};

/// The settings' options with the speed range in rpm.
OrderAnalysisOptions options_of(const OrderAnalysisSettings& settings);

OrderAnalysisResult run_order_analysis(const model::Model& model,
                                       const OrderAnalysisSettings& settings,
                                       const Context& context);

AnalysisOutput order_analysis_output(const model::Model& model,
                                     const OrderAnalysisSettings& settings,
                                     const OrderAnalysisResult& result, const Context& context);

/// A record read from its file: every column (text cells NaN) and each sample's file line.
struct OrderRecord {
  std::filesystem::path path;
  std::vector<std::string> names;
  Eigen::MatrixXd values;  ///< samples x columns
  std::vector<int> line;   ///< file line of each sample (0: not a text file)
};

/// The time axis and the analysed shaft's angle.
struct OrderReference {
  Eigen::VectorXd time, angle;
  Eigen::Index first = 0, last = 0;  ///< analysable samples (between the tacho's pulses)
  Eigen::Index reference_column = -1;
  std::string description;
};

/// Reads record_file (InputError: missing, unreadable, ragged rows at their line).
OrderRecord read_order_record(const model::Model& model, const OrderAnalysisSettings& settings,
                              const Context& context);
/// Time and angle (InputError: missing column, non-increasing or non-uniform time at its line,
/// an angle that does not increase at its line, a tacho with fewer than 2 pulses).
OrderReference order_reference(const OrderRecord& record, const OrderAnalysisSettings& settings,
                               const Context& context);
/// The analysed columns (InputError: missing column, a non-numeric value at its line).
std::vector<Eigen::Index> order_channels(const OrderRecord& record,
                                         const OrderAnalysisSettings& settings,
                                         const OrderReference& reference, const Context& context);

/// Reads the record and checks it: InputError located at the record file's line where it
/// applies, or at the analysis's keys.
void check_order_analysis_inputs(const model::Model& model, const OrderAnalysisSettings& settings,
                                 const Context& context);

}  // namespace geardyn::analyses
