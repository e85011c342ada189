// order_analysis: tables, plots and notes (shared with drivetrain_transient's order analysis).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "geardyn/analyses/order_analysis.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/signal/octave.hpp"
#include "geardyn/signal/waterfall.hpp"

namespace geardyn::analyses {
namespace {

std::vector<double> to_std(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

std::string order_label(double o) {
  std::string s = fmt::format("{:g}", o);
  std::replace(s.begin(), s.end(), '.', 'p');
  return s;
}

double level_db(double power, double reference) {
  return power > 0.0 ? signal::power_level_db(power, reference) : std::nan("");
}

// Frequencies shown in the waterfall: up to 1.25 times the highest order line (all bins when no
// order is cut).
Eigen::Index shown_bins(const signal::Waterfall& w, const OrderAnalysisOptions& o) {
  const double top = o.orders.empty() ? 0.0 : *std::max_element(o.orders.begin(), o.orders.end());
  const double fmax = 1.25 * top * w.speed_rpm.maxCoeff() / 60.0;
  const Eigen::Index all = w.frequency_hz.size();
  if (!(fmax > 0.0)) return all;
  return std::min(all, static_cast<Eigen::Index>(std::ceil(fmax / w.resolution_hz)) + 1);
}

void add_order_cuts(AnalysisOutput& out, const OrderAnalysisResult& r,
                    const OrderAnalysisOptions& o, const std::string& prefix) {
  if (r.channels.empty() || o.orders.empty()) return;
  Table t;
  t.name = prefix + "order_cuts";
  t.title = "Order cuts: 0-peak amplitude of each order vs mean speed of each block";
  const signal::OrderCuts& c0 = r.channels.front().cuts;
  t.add("speed_rpm", "rpm", to_std(c0.speed_rpm));
  t.add("time_s", "s", to_std(c0.time_s));
  for (const ChannelOrders& ch : r.channels) {
    Plot p;
    p.name = prefix + "order_cuts_" + ch.name;
    p.title = "Order cuts of " + ch.name;
    p.x_label = "speed [rpm]";
    p.y_label = ch.name + " (0-peak)";
    for (std::size_t k = 0; k < o.orders.size(); ++k) {
      const auto col = static_cast<Eigen::Index>(k);
      t.add("order_" + order_label(o.orders[k]) + "_" + ch.name, "",
            to_std(ch.cuts.amplitude.col(col)));
      Trace tr;
      tr.name = fmt::format("order {:g}", o.orders[k]);
      tr.x = to_std(ch.cuts.speed_rpm);
      tr.y = to_std(ch.cuts.amplitude.col(col));
      p.traces.push_back(std::move(tr));
    }
    out.plots.push_back(std::move(p));
  }
  out.tables.push_back(std::move(t));
}

void add_order_map(AnalysisOutput& out, const ChannelOrders& ch, const OrderAnalysisOptions& o,
                   const std::string& prefix) {
  const signal::OrderSpectra& m = ch.map;
  const double top = o.orders.empty() ? 0.0 : *std::max_element(o.orders.begin(), o.orders.end());
  Eigen::Index bins = m.order.size();
  if (top > 0.0)
    bins = std::min(bins,
                    static_cast<Eigen::Index>(std::ceil(1.25 * top * m.revolutions_per_block)) + 1);
  Table t;
  t.name = prefix + "order_map_" + ch.name;
  t.title = "Order map (order spectra vs speed, the 3-D FFT) of " + ch.name;
  Trace h;
  h.name = ch.name;
  h.z_label = ch.name + " (0-peak)";
  h.x = to_std(m.order.head(bins));
  std::vector<double> speed, order, amp;
  for (Eigen::Index b = 0; b < m.amplitude.rows(); ++b) {
    h.y.push_back(m.speed_rpm[b]);
    h.z.push_back(to_std(m.amplitude.row(b).head(bins).transpose()));
    for (Eigen::Index k = 0; k < bins; ++k) {
      speed.push_back(m.speed_rpm[b]);
      order.push_back(m.order[k]);
      amp.push_back(m.amplitude(b, k));
    }
  }
  t.add("speed_rpm", "rpm", std::move(speed));
  t.add("order", "", std::move(order));
  t.add("amplitude_" + ch.name, "", std::move(amp));
  out.tables.push_back(std::move(t));
  Plot p;
  p.name = prefix + "order_map_" + ch.name;
  p.title = "Order map of " + ch.name;
  p.x_label = "order [1/rev]";
  p.y_label = "speed [rpm]";
  p.traces.push_back(std::move(h));
  out.plots.push_back(std::move(p));
}

void add_waterfall(AnalysisOutput& out, const ChannelOrders& ch, const OrderAnalysisOptions& o,
                   const std::string& prefix) {
  const signal::Waterfall& w = ch.waterfall;
  const Eigen::Index bins = shown_bins(w, o);
  Table t;
  t.name = prefix + "waterfall_" + ch.name;
  t.title = "Waterfall (short-time amplitude spectra vs mean speed) of " + ch.name;
  Trace h;
  h.name = ch.name;
  h.z_label = ch.name + " (0-peak)";
  h.x = to_std(w.frequency_hz.head(bins));
  std::vector<double> speed, time, freq, amp;
  for (Eigen::Index b = 0; b < w.amplitude.rows(); ++b) {
    h.y.push_back(w.speed_rpm[b]);
    h.z.push_back(to_std(w.amplitude.row(b).head(bins).transpose()));
    for (Eigen::Index k = 0; k < bins; ++k) {
      speed.push_back(w.speed_rpm[b]);
      time.push_back(w.time_s[b]);
      freq.push_back(w.frequency_hz[k]);
      amp.push_back(w.amplitude(b, k));
    }
  }
  // A heat map needs increasing y: a run-down is drawn in time order, labelled by speed.
  const bool increasing = std::is_sorted(h.y.begin(), h.y.end()) &&
                          std::adjacent_find(h.y.begin(), h.y.end()) == h.y.end();
  t.add("speed_rpm", "rpm", std::move(speed));
  t.add("time_s", "s", std::move(time));
  t.add("frequency_hz", "Hz", std::move(freq));
  t.add("amplitude_" + ch.name, "", std::move(amp));
  out.tables.push_back(std::move(t));
  Plot p;
  p.name = prefix + "waterfall_" + ch.name;
  p.title = "Waterfall of " + ch.name + " with order lines";
  p.x_label = "frequency [Hz]";
  p.y_label = increasing ? "speed [rpm]" : "time [s]";
  if (!increasing) h.y = to_std(w.time_s);
  const std::vector<double> rows = h.y;
  p.traces.push_back(std::move(h));
  for (double order : o.orders) {
    Trace line;
    line.name = fmt::format("order {:g}", order);
    line.dash = "dot";
    const Eigen::VectorXd f = signal::order_line_hz(order, w.speed_rpm);
    for (Eigen::Index b = 0; b < f.size(); ++b) {
      line.x.push_back(f[b]);
      line.y.push_back(rows[static_cast<std::size_t>(b)]);
      line.hover.push_back(
          fmt::format("order {:g} at {:.0f} rpm: {:.1f} Hz", order, w.speed_rpm[b], f[b]));
    }
    p.traces.push_back(std::move(line));
  }
  out.plots.push_back(std::move(p));
}

void add_levels(AnalysisOutput& out, const OrderAnalysisResult& r, const OrderAnalysisOptions& o,
                const std::string& prefix) {
  Table t;
  t.name = prefix + "levels";
  t.title = fmt::format("Overall level of each waterfall block (RMS, mean removed; dB re {:g})",
                        o.db_reference);
  const signal::Waterfall& w0 = r.channels.front().waterfall;
  t.add("speed_rpm", "rpm", to_std(w0.speed_rpm));
  t.add("time_s", "s", to_std(w0.time_s));
  Plot p;
  p.name = prefix + "levels";
  p.title = fmt::format("Overall level vs speed (dB re {:g})", o.db_reference);
  p.x_label = "speed [rpm]";
  p.y_label = fmt::format("level [dB re {:g}]", o.db_reference);
  for (const ChannelOrders& ch : r.channels) {
    std::vector<double> db;
    for (Eigen::Index b = 0; b < ch.block_rms.size(); ++b)
      db.push_back(level_db(ch.block_rms[b] * ch.block_rms[b], o.db_reference));
    t.add("rms_" + ch.name, "", to_std(ch.block_rms));
    t.add("level_" + ch.name + "_db", "dB", db);
    Trace tr;
    tr.name = ch.name;
    tr.x = to_std(ch.waterfall.speed_rpm);
    tr.y = std::move(db);
    p.traces.push_back(std::move(tr));
  }
  out.tables.push_back(std::move(t));
  out.plots.push_back(std::move(p));
}

void add_bands_and_psd(AnalysisOutput& out, const OrderAnalysisResult& r,
                       const OrderAnalysisOptions& o, const std::string& prefix) {
  Table bands;
  bands.name = prefix + "third_octave";
  bands.title =
      fmt::format("1/3-octave band levels of the analysed range (dB re {:g})", o.db_reference);
  bands.add("nominal_hz", "Hz", r.band_nominal_hz);
  bands.add("mid_hz", "Hz", r.band_mid_hz);
  Table psd;
  psd.name = prefix + "psd";
  psd.title =
      "Power spectral density of the analysed range (Welch, Hann, 50 % overlap, segments of a "
      "quarter of the range up to 16384 samples)";
  psd.add("frequency_hz", "Hz", to_std(r.channels.front().psd_frequency_hz));
  Plot pp;
  pp.name = prefix + "psd";
  pp.title = "Power spectral density";
  pp.x_label = "frequency [Hz]";
  pp.y_label = "PSD [unit^2/Hz]";
  pp.y_log = true;
  for (const ChannelOrders& ch : r.channels) {
    std::vector<double> lin, aw;
    const double nyquist = 0.5 * r.sample_rate_hz;
    for (Eigen::Index b = 0; b < ch.band_power.size(); ++b) {
      // A band reaching above fs/2 is not covered by the record: left blank.
      const bool covered =
          r.band_mid_hz[static_cast<std::size_t>(b)] * std::pow(10.0, 0.05) <= nyquist;
      lin.push_back(covered ? level_db(ch.band_power[b], o.db_reference) : std::nan(""));
      aw.push_back(covered ? level_db(ch.band_power_a[b], o.db_reference) : std::nan(""));
    }
    Plot p;
    p.name = prefix + "third_octave_" + ch.name;
    p.title = "1/3-octave band levels of " + ch.name;
    p.x_label = "band [Hz]";
    p.y_label = fmt::format("level [dB re {:g}]", o.db_reference);
    p.x_log = true;
    Trace tl;
    tl.name = "linear";
    tl.mode = Trace::Mode::Bars;
    tl.x = r.band_nominal_hz;
    tl.y = lin;
    p.traces.push_back(std::move(tl));
    bands.add("level_" + ch.name + "_db", "dB", std::move(lin));
    if (o.a_weighting) {
      Trace ta;
      ta.name = "A-weighted";
      ta.mode = Trace::Mode::Bars;
      ta.x = r.band_nominal_hz;
      ta.y = aw;
      p.traces.push_back(std::move(ta));
      bands.add("level_" + ch.name + "_dba", "dB(A)", std::move(aw));
    }
    out.plots.push_back(std::move(p));
    psd.add("psd_" + ch.name, "unit^2/Hz", to_std(ch.psd));
    Trace tr;
    tr.name = ch.name;
    tr.x = to_std(ch.psd_frequency_hz);
    tr.y = to_std(ch.psd);
    pp.traces.push_back(std::move(tr));
  }
  out.tables.push_back(std::move(bands));
  out.tables.push_back(std::move(psd));
  out.plots.push_back(std::move(pp));
}

void add_notes(AnalysisOutput& out, const OrderAnalysisResult& r, const OrderAnalysisOptions& o) {
  const signal::Waterfall& w = r.channels.front().waterfall;
  const double block_s = o.block_length / r.sample_rate_hz;
  const double top = o.orders.empty() ? 1.0 : *std::max_element(o.orders.begin(), o.orders.end());
  const double smear_hz = top * r.max_rate_rpm_per_s * block_s / 60.0;
  out.notes.push_back(fmt::format(
      "Analysed {:.4g} .. {:.4g} s, speeds {:.1f} .. {:.1f} rpm (the record covers {:.1f} .. "
      "{:.1f} rpm); samples outside are not analysed.",
      r.start_s, r.end_s, w.speed_rpm.minCoeff(), w.speed_rpm.maxCoeff(), r.covered_min_rpm,
      r.covered_max_rpm));
  out.notes.push_back(fmt::format(
      "Waterfall: blocks of {} samples ({:.4g} s, resolution {:.4g} Hz, {} window, {:.0f} % "
      "overlap). The speed changes by up to {:.4g} rpm/s, so order {:g} sweeps {:.3g} Hz = "
      "{:.2g} bins per block{}.",
      o.block_length, block_s, w.resolution_hz, signal::to_string(o.window), 100 * o.overlap,
      r.max_rate_rpm_per_s, top, smear_hz, smear_hz / w.resolution_hz,
      smear_hz > 2 * w.resolution_hz ? ": its peaks are smeared and read low; shorten block_length"
                                     : ""));
  const signal::OrderSpectra& m = r.channels.front().map;
  out.notes.push_back(fmt::format(
      "Order cuts and order map: computed order tracking ({} samples per revolution, 4-point "
      "interpolation), blocks of {} revolutions (order resolution {:.4g}); at {:.0f} rpm a block "
      "lasts {:.3g} s. Amplitudes are 0-peak in the unit of each channel.",
      r.samples_per_revolution, o.revolutions_per_block, 1.0 / o.revolutions_per_block,
      m.speed_rpm.minCoeff(), o.revolutions_per_block * 60.0 / m.speed_rpm.minCoeff()));
  // Four-point Lagrange interpolation of a sinusoid with omega h per sample loses up to
  // 0.0234 (omega h)^4 of its amplitude (docs/theory.md §14): the highest order at the top speed.
  const double f_top = top * m.speed_rpm.maxCoeff() / 60.0;
  const double wh = units::kTwoPi * f_top / r.sample_rate_hz;
  const double loss = 0.0234 * wh * wh * wh * wh;
  out.notes.push_back(fmt::format(
      "Order {:g} at {:.0f} rpm is {:.1f} Hz, {:.1f} samples per cycle of the record: the "
      "resampling's interpolation may lose up to {:.2g} % of its amplitude there{}.",
      top, m.speed_rpm.maxCoeff(), f_top, r.sample_rate_hz / f_top, 100 * std::min(loss, 1.0),
      loss > 0.01 ? " (more than 1 %: record at a higher sample rate or cut lower orders)" : ""));
  const double psd_df = r.channels.front().psd_frequency_hz[1];
  double lowest_band = 0.0;
  for (std::size_t i = 0; i < r.band_mid_hz.size(); ++i)
    if (r.band_mid_hz[i] * (std::pow(10.0, 0.05) - std::pow(10.0, -0.05)) >= 8 * psd_df) {
      lowest_band = r.band_nominal_hz[i];
      break;
    }
  out.notes.push_back(fmt::format(
      "Levels in dB re {:g} (the unit of the channels: e.g. 1e-6 m/s^2 for acceleration, ISO "
      "1683; 2e-5 Pa for sound pressure; set db_reference). 1/3-octave bands (IEC 61260-1) by "
      "summing the Welch PSD (resolution {:.4g} Hz): bands from {:g} Hz up are at least 8 bins "
      "wide and meet the class-1 filter mask (docs/theory.md §14); narrower bands are coarse; "
      "bands above fs/2 = {:.4g} Hz are blank. A-weighting (IEC 61672-1) applied at each band's "
      "mid frequency.",
      o.db_reference, psd_df, lowest_band, 0.5 * r.sample_rate_hz));
}

}  // namespace

void add_order_analysis_output(AnalysisOutput& out, const OrderAnalysisResult& r,
                               const OrderAnalysisOptions& o, const std::string& prefix) {
  if (r.channels.empty()) return;
  add_order_cuts(out, r, o, prefix);
  for (const ChannelOrders& ch : r.channels) {
    add_order_map(out, ch, o, prefix);
    add_waterfall(out, ch, o, prefix);
  }
  add_levels(out, r, o, prefix);
  add_bands_and_psd(out, r, o, prefix);
  add_notes(out, r, o);
}

}  // namespace geardyn::analyses
