#include "geardyn/analyses/order_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geardyn/core/units.hpp"
#include "geardyn/signal/octave.hpp"
#include "geardyn/signal/psd.hpp"
#include "geardyn/signal/weighting.hpp"

namespace geardyn::analyses {
namespace {

// Speed [rpm] at each sample from the angle, by central differences (one-sided at the ends).
Eigen::VectorXd sample_speed_rpm(const Eigen::VectorXd& t, const Eigen::VectorXd& angle) {
  const Eigen::Index n = t.size();
  Eigen::VectorXd s(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index a = std::max<Eigen::Index>(0, j - 1);
    const Eigen::Index b = std::min<Eigen::Index>(n - 1, j + 1);
    s[j] = 60.0 * (angle[b] - angle[a]) / (units::kTwoPi * (t[b] - t[a]));
  }
  return s;
}

int automatic_samples_per_revolution(const std::vector<double>& orders) {
  const double top = orders.empty() ? 1.0 : *std::max_element(orders.begin(), orders.end());
  int spr = 16;
  while (spr < 4.0 * top) spr *= 2;
  return spr;
}

void analyse_channel(ChannelOrders& ch, const Eigen::VectorXd& t, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& angle, const OrderAnalysisOptions& o, int spr,
                     double fs) {
  const Eigen::VectorXd orders = Eigen::Map<const Eigen::VectorXd>(
      o.orders.data(), static_cast<Eigen::Index>(o.orders.size()));
  const signal::AngleDomainRecord rec = signal::resample_to_angle(t, x, angle, spr);
  ch.cuts = signal::order_cuts(rec, orders, o.revolutions_per_block, o.window, o.overlap);
  ch.map = signal::order_spectra(rec, o.revolutions_per_block, o.window, o.overlap);
  signal::WaterfallOptions wo;
  wo.block_length = o.block_length;
  wo.overlap = o.overlap;
  wo.window = o.window;
  ch.waterfall = signal::waterfall_by_angle(t, x, angle, wo);
  const auto blocks = ch.waterfall.speed_rpm.size();
  ch.block_rms.resize(blocks);
  for (Eigen::Index b = 0; b < blocks; ++b) {
    const Eigen::VectorXd seg = x.segment(b * ch.waterfall.step, o.block_length);
    ch.block_rms[b] = std::sqrt((seg.array() - seg.mean()).square().mean());
  }
  // PSD segments: at least a quarter of the record (a power of 2, at most 16384 samples) for a
  // resolution that resolves the low 1/3-octave bands; at least the waterfall block.
  int psd_length = 1;
  while (psd_length <= 8192 && 2 * psd_length <= x.size() / 4) psd_length *= 2;
  signal::WelchOptions wel;
  wel.segment_length = std::max(o.block_length, psd_length);
  wel.window = signal::Window::Hann;
  wel.overlap = 0.5;
  const signal::PowerSpectralDensity psd = signal::welch_psd(x.array() - x.mean(), fs, wel);
  ch.psd_frequency_hz = psd.frequency_hz;
  ch.psd = psd.density;
  ch.variance = (x.array() - x.mean()).square().mean();
  const std::vector<signal::OctaveBand> bands = signal::third_octave_bands();
  ch.band_power = signal::band_powers(bands, psd.frequency_hz, psd.density * psd.resolution_hz);
  ch.band_power_a = ch.band_power;
  for (std::size_t i = 0; i < bands.size(); ++i)
    ch.band_power_a[static_cast<Eigen::Index>(i)] *=
        signal::weighting_power_factor(signal::Weighting::A, bands[i].mid_hz);
}

}  // namespace

AnalysedSpan analysed_span(const Eigen::VectorXd& time_s, const Eigen::VectorXd& angle_rad,
                           Eigen::Index first_valid, Eigen::Index last_valid,
                           const OrderAnalysisOptions& o, const Context& context) {
  const Eigen::VectorXd speed = sample_speed_rpm(time_s, angle_rad);
  const Eigen::Index n_valid = last_valid - first_valid + 1;
  AnalysedSpan span;
  span.covered_min_rpm = speed.segment(first_valid, n_valid).minCoeff();
  span.covered_max_rpm = speed.segment(first_valid, n_valid).maxCoeff();
  span.start = first_valid;
  span.end = last_valid;
  if (o.speed_max_rpm > 0.0) {
    // 1 % slack: the speed at the record's ends is a one-sided difference.
    if (o.speed_min_rpm < 0.99 * span.covered_min_rpm ||
        o.speed_max_rpm > 1.01 * span.covered_max_rpm)
      throw context.error(
          "speed_range_rpm",
          fmt::format("a speed range inside the {:.1f} .. {:.1f} rpm the record covers",
                      span.covered_min_rpm, span.covered_max_rpm),
          fmt::format("[{:.6g}, {:.6g}] rpm", o.speed_min_rpm, o.speed_max_rpm));
    auto inside = [&](Eigen::Index j) {
      return speed[j] >= o.speed_min_rpm && speed[j] <= o.speed_max_rpm;
    };
    while (span.start < last_valid && !inside(span.start)) ++span.start;
    while (span.end > span.start && !inside(span.end)) --span.end;
  }
  return span;
}

OrderAnalysisResult analyse_orders(const Eigen::VectorXd& time_s, const Eigen::MatrixXd& values,
                                   const std::vector<std::string>& names,
                                   const Eigen::VectorXd& angle_rad, Eigen::Index first_valid,
                                   Eigen::Index last_valid, const OrderAnalysisOptions& o,
                                   const Context& context) {
  OrderAnalysisResult r;
  r.sample_rate_hz = signal::uniform_sample_rate(time_s);
  const AnalysedSpan span = analysed_span(time_s, angle_rad, first_valid, last_valid, o, context);
  r.covered_min_rpm = span.covered_min_rpm;
  r.covered_max_rpm = span.covered_max_rpm;
  const Eigen::Index start = span.start, end = span.end;
  r.start_s = time_s[start];
  r.end_s = time_s[end];
  r.samples_per_revolution = o.samples_per_revolution > 0
                                 ? o.samples_per_revolution
                                 : automatic_samples_per_revolution(o.orders);
  const Eigen::Index len = end - start + 1;
  const Eigen::VectorXd t = time_s.segment(start, len);
  const Eigen::VectorXd angle = angle_rad.segment(start, len);
  for (std::size_t c = 0; c < names.size(); ++c) {
    ChannelOrders ch;
    ch.name = names[c];
    const Eigen::VectorXd x = values.col(static_cast<Eigen::Index>(c)).segment(start, len);
    try {
      analyse_channel(ch, t, x, angle, o, r.samples_per_revolution, r.sample_rate_hz);
    } catch (const std::invalid_argument& e) {
      throw context.error("revolutions_per_block",
                          "blocks (revolutions_per_block, block_length) that fit in the analysed "
                          "range and orders below half the samples per revolution",
                          e.what(), "shorten the blocks or widen speed_range_rpm");
    }
    r.channels.push_back(std::move(ch));
  }
  for (const signal::OctaveBand& b : signal::third_octave_bands()) {
    r.band_nominal_hz.push_back(b.nominal_hz);
    r.band_mid_hz.push_back(b.mid_hz);
  }
  if (!r.channels.empty()) {
    const signal::Waterfall& w = r.channels.front().waterfall;
    for (Eigen::Index b = 1; b < w.speed_rpm.size(); ++b)
      r.max_rate_rpm_per_s =
          std::max(r.max_rate_rpm_per_s,
                   std::abs(w.speed_rpm[b] - w.speed_rpm[b - 1]) / (w.time_s[b] - w.time_s[b - 1]));
  }
  return r;
}

OrderAnalysisOptions options_of(const OrderAnalysisSettings& s) {
  OrderAnalysisOptions o = s.options;
  if (s.speed_range.size() == 2) {
    o.speed_min_rpm = s.speed_range[0] / units::kRadPerSecondPerRpm;
    o.speed_max_rpm = s.speed_range[1] / units::kRadPerSecondPerRpm;
  }
  return o;
}

OrderAnalysisResult run_order_analysis(const model::Model& model, const OrderAnalysisSettings& s,
                                       const Context& context) {
  Progress& progress = context.progress();
  progress.start("order analysis", 1);
  const OrderRecord record = read_order_record(model, s, context);
  const OrderReference ref = order_reference(record, s, context);
  const std::vector<Eigen::Index> cols = order_channels(record, s, ref, context);
  Eigen::MatrixXd values(record.values.rows(), static_cast<Eigen::Index>(cols.size()));
  std::vector<std::string> names;
  for (std::size_t i = 0; i < cols.size(); ++i) {
    values.col(static_cast<Eigen::Index>(i)) = record.values.col(cols[i]);
    names.push_back(record.names[static_cast<std::size_t>(cols[i])]);
  }
  const OrderAnalysisOptions o = options_of(s);
  OrderAnalysisResult r =
      analyse_orders(ref.time, values, names, ref.angle, ref.first, ref.last, o, context);
  r.reference = ref.description;
  progress.update(1);
  progress.finish();
  return r;
}

AnalysisOutput order_analysis_output(const model::Model& /*model*/, const OrderAnalysisSettings& s,
                                     const OrderAnalysisResult& result,
                                     const Context& /*context*/) {
  AnalysisOutput out;
  const OrderAnalysisOptions o = options_of(s);
  out.notes.push_back(fmt::format("Record {}; reference: {}.", s.record_file, result.reference));
  add_order_analysis_output(out, result, o, "");
  return out;
}

void check_order_analysis_inputs(const model::Model& model, const OrderAnalysisSettings& s,
                                 const Context& context) {
  const OrderRecord record = read_order_record(model, s, context);
  const OrderReference ref = order_reference(record, s, context);
  (void)order_channels(record, s, ref, context);
  const OrderAnalysisOptions o = options_of(s);
  const AnalysedSpan span = analysed_span(ref.time, ref.angle, ref.first, ref.last, o, context);
  const Eigen::Index samples = span.end - span.start + 1;
  if (samples < o.block_length)
    throw context.error("block_length",
                        fmt::format("at most the {} samples of the analysed range", samples),
                        std::to_string(o.block_length));
  const double revolutions = (ref.angle[span.end] - ref.angle[span.start]) / units::kTwoPi;
  if (revolutions < o.revolutions_per_block)
    throw context.error(
        "revolutions_per_block",
        fmt::format("at most the {:.1f} revolutions of the analysed range", revolutions),
        std::to_string(o.revolutions_per_block));
}

}  // namespace geardyn::analyses
