#include "geardyn/report/html_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numeric>
#include <stdexcept>

#include "geardyn/core/version.hpp"
#include "geardyn/report/plotly_js.hpp"

namespace geardyn::report {
namespace {

using nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Text helpers

// Plotly renders its strings (titles, labels, legend, hover) as a small HTML subset and decodes
// character references, so escaping & < > shows the text literally.
std::string plotly_text(std::string_view text) { return escape_html_content(text); }

// JSON placed inside a <script> element: '<' only occurs inside JSON strings, where \u003c is the
// same character, so no "</script>" or "<!--" can end or confuse the element.
std::string json_for_script(const json& value) {
  const std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size() + text.size() / 16);
  for (char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

// `value` rounded to `digits` significant digits: the double nearest to that short decimal, which
// nlohmann::json then prints in its short form (keeps the page small; plots need no more).
double round_to_digits(double value, int digits) {
  if (!std::isfinite(value) || value == 0.0) return value;
  char buffer[40];
  const auto end = fmt::format_to_n(buffer, sizeof buffer - 1, "{:.{}e}", value, digits - 1).out;
  double rounded = value;
  std::from_chars(buffer, end, rounded);
  return rounded;
}

std::string format_cell(const Column& c, std::size_t row, int digits) {
  if (c.text) return escape_html(c.texts[row]);
  const double v = c.numbers[row];
  if (std::isnan(v)) return "<span class=\"nan\">NaN</span>";
  return fmt::format("{:.{}g}", v, digits);
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds)) return "n/a";
  if (seconds < 1e-3) return "&lt; 1 ms";
  if (seconds < 1.0) return fmt::format("{:.0f} ms", seconds * 1e3);
  if (seconds < 120.0) return fmt::format("{:.2f} s", seconds);
  return fmt::format("{:.0f} min {:02.0f} s", std::floor(seconds / 60.0), std::fmod(seconds, 60.0));
}

// ok -> green, a result that exists but is incomplete -> amber, no usable result -> red.
const char* status_class(Status s) {
  switch (s) {
    case Status::Ok:
      return "ok";
    case Status::Unstable:
    case Status::NotConverged:
    case Status::FewerModes:
      return "warn";
    case Status::Singular:
    case Status::Diverged:
    case Status::Failed:
      return "bad";
  }
  return "bad";
}

// A result exists but is incomplete (fewer modes, iteration limit) or is the response of an
// unstable system: shown amber, not red, with its tables.
bool is_incomplete(Status s) {
  return s == Status::Unstable || s == Status::NotConverged || s == Status::FewerModes;
}

std::string badge(Status s) {
  return fmt::format("<span class=\"badge {}\">{}</span>", status_class(s),
                     escape_html(to_string(s)));
}

// ---------------------------------------------------------------------------------------------
// Plots

struct ThinnedTrace {
  std::vector<std::size_t> keep;  // indices kept, ascending
  bool thinned = false;
};

// Chooses the points drawn for a trace of n points when n > max_points. For x increasing (time
// histories, spectra, sweeps) every bucket keeps its smallest and largest y, so peaks and the
// envelope survive; otherwise (orbits) every k-th point is kept.
ThinnedTrace thin(const Trace& t, std::size_t max_points) {
  ThinnedTrace result;
  const std::size_t n = std::min(t.x.size(), t.y.size());
  if (max_points == 0 || n <= max_points) {
    result.keep.resize(n);
    std::iota(result.keep.begin(), result.keep.end(), std::size_t{0});
    return result;
  }
  result.thinned = true;
  max_points = std::max<std::size_t>(max_points, 4);
  bool increasing = true;
  for (std::size_t i = 1; i < n && increasing; ++i) increasing = !(t.x[i] < t.x[i - 1]);
  if (increasing) {
    const std::size_t buckets = max_points / 2;
    for (std::size_t b = 0; b < buckets; ++b) {
      const std::size_t begin = b * n / buckets, end = (b + 1) * n / buckets;
      std::size_t lo = begin, hi = begin, gap = end;
      for (std::size_t i = begin; i < end; ++i) {
        if (std::isnan(t.y[i])) {
          if (gap == end) gap = i;  // keep one NaN so a gap in the curve stays a gap
          continue;
        }
        if (std::isnan(t.y[lo]) || t.y[i] < t.y[lo]) lo = i;
        if (std::isnan(t.y[hi]) || t.y[i] > t.y[hi]) hi = i;
      }
      std::size_t picks[3] = {lo, hi, gap};
      std::sort(std::begin(picks), std::end(picks));
      for (std::size_t p : picks)
        if (p < end && (result.keep.empty() || result.keep.back() != p)) result.keep.push_back(p);
    }
  } else {
    const std::size_t stride = (n + max_points - 1) / max_points;
    for (std::size_t i = 0; i < n; i += stride) result.keep.push_back(i);
    if (result.keep.back() != n - 1) result.keep.push_back(n - 1);
  }
  return result;
}

// Largest finite |value| on one axis of a plot (0 if none).
double axis_magnitude(const Plot& plot, bool x_axis) {
  double m = 0.0;
  for (const Trace& t : plot.traces)
    for (double v : x_axis ? t.x : t.y)
      if (std::isfinite(v)) m = std::max(m, std::abs(v));
  return m;
}

// Tick labels: powers of ten on log axes; plain numbers on linear axes of everyday magnitude
// (12000 rpm, not 1.2x10^4); powers of ten again for very small or large values (2x10^-6 m).
json axis_layout(const std::string& label, bool log, double magnitude) {
  const bool plain = !log && (magnitude == 0.0 || (magnitude >= 1e-3 && magnitude < 1e6));
  return {{"title", {{"text", plotly_text(label)}, {"standoff", 8}}},
          {"type", log ? "log" : "linear"},
          {"automargin", true},
          {"showline", true},
          {"linecolor", "#8a94a6"},
          {"mirror", true},
          {"ticks", "outside"},
          {"tickcolor", "#8a94a6"},
          {"gridcolor", "#e6eaf0"},
          {"zeroline", false},
          {"exponentformat", plain ? "none" : "power"}};
}

// A heat map trace: the grid is drawn as it is (no thinning: its size is the analysis's choice);
// NaN cells become null, which plotly leaves blank. The colour bar carries the z label.
json heatmap_trace(const Trace& t, const ReportOptions& options) {
  auto rounded = [&](const std::vector<double>& v) {
    json a = json::array();
    for (double x : v)
      a.push_back(std::isfinite(x) ? json(round_to_digits(x, options.display_digits + 2))
                                   : json(nullptr));
    return a;
  };
  json z = json::array();
  for (const std::vector<double>& row : t.z) z.push_back(rounded(row));
  return {{"type", "heatmap"},
          {"name", plotly_text(t.name)},
          {"x", rounded(t.x)},
          {"y", rounded(t.y)},
          {"z", std::move(z)},
          {"colorscale", "Viridis"},
          {"hoverongaps", false},
          {"colorbar",
           {{"title", {{"text", plotly_text(t.z_label)}, {"side", "right"}}},
            {"thickness", 14},
            {"exponentformat", "power"}}},
          {"hovertemplate", "x = %{x}<br>y = %{y}<br>" + plotly_text(t.z_label) +
                                " = %{z}<extra>%{fullData.name}</extra>"}};
}

// The figure of one plot: {id, data, layout, config} for Plotly.newPlot; `thinned` is set when a
// trace was thinned for display.
json plot_figure(const Plot& plot, const std::string& div_id, const ReportOptions& options,
                 bool& thinned) {
  thinned = false;
  json data = json::array();
  bool heatmap = false;
  for (const Trace& t : plot.traces) {
    if (t.is_heatmap()) {
      data.push_back(heatmap_trace(t, options));
      heatmap = true;
      continue;
    }
    const ThinnedTrace kept = thin(t, options.max_points_per_trace);
    thinned = thinned || kept.thinned;
    json x = json::array(), y = json::array();
    for (std::size_t i : kept.keep) {
      x.push_back(round_to_digits(t.x[i], options.display_digits + 2));
      y.push_back(round_to_digits(t.y[i], options.display_digits + 2));
    }
    json trace = {{"type", "scatter"},
                  {"name", plotly_text(t.name)},
                  {"x", std::move(x)},
                  {"y", std::move(y)}};
    switch (t.mode) {
      case Trace::Mode::Lines:
        trace["mode"] = "lines";
        break;
      case Trace::Mode::Markers:
        trace["mode"] = "markers";
        break;
      case Trace::Mode::LinesMarkers:
        trace["mode"] = "lines+markers";
        break;
      case Trace::Mode::Bars:
        trace["type"] = "bar";
        break;
    }
    if (t.mode != Trace::Mode::Bars) {
      json line = {{"width", 1.8}};
      if (!t.dash.empty()) line["dash"] = t.dash;
      trace["line"] = std::move(line);
    }
    if (t.mode == Trace::Mode::Markers) trace["marker"] = {{"size", 8}};
    if (t.mode == Trace::Mode::LinesMarkers) trace["marker"] = {{"size", 5}};
    if (!t.hover.empty()) {
      json text = json::array();
      for (std::size_t i : kept.keep)
        text.push_back(i < t.hover.size() ? plotly_text(t.hover[i]) : "");
      trace["text"] = std::move(text);
      trace["hovertemplate"] = "%{text}<br>x = %{x}<br>y = %{y}<extra>%{fullData.name}</extra>";
    } else {
      trace["hovertemplate"] = "x = %{x}<br>y = %{y}<extra>%{fullData.name}</extra>";
    }
    data.push_back(std::move(trace));
  }

  json xaxis = axis_layout(plot.x_label, plot.x_log, axis_magnitude(plot, true));
  json yaxis = axis_layout(plot.y_label, plot.y_log, axis_magnitude(plot, false));
  if (plot.equal_aspect) {
    // One metre on x is one metre on y (orbits): y is tied to x, both shrink to keep the ratio.
    yaxis["scaleanchor"] = "x";
    yaxis["scaleratio"] = 1;
    xaxis["constrain"] = "domain";
    yaxis["constrain"] = "domain";
  }
  const std::size_t n_traces = plot.traces.size();
  // Many traces (a Campbell diagram: modes, order lines, crossings) put the legend under the
  // plot, where it takes height instead of width: beside the plot it squeezed the axes into a
  // third of the card. Three legend entries per row, 22 px a row.
  const bool legend_below = n_traces > 6 && !plot.equal_aspect;
  const int legend_rows = legend_below ? static_cast<int>((n_traces + 2) / 3) : 0;
  json legend = {{"font", {{"size", 11}}}, {"bgcolor", "rgba(255,255,255,0.85)"}};
  if (legend_below) {
    legend["orientation"] = "h";
    legend["x"] = 0;
    legend["xanchor"] = "left";
    legend["y"] = -0.14;
    legend["yanchor"] = "top";
  }
  json layout = {
      {"title",
       {{"text", plotly_text(plot.title)},
        {"x", 0.01},
        {"xanchor", "left"},
        {"font", {{"size", 15}}}}},
      {"xaxis", std::move(xaxis)},
      {"yaxis", std::move(yaxis)},
      {"showlegend", n_traces > 1 && !heatmap},
      {"legend", std::move(legend)},
      {"hovermode", "closest"},
      {"height", (plot.equal_aspect ? 520 : 430) + 22 * legend_rows},
      {"margin", {{"l", 64}, {"r", 16}, {"t", 46}, {"b", 52}}},
      {"paper_bgcolor", "#ffffff"},
      {"plot_bgcolor", "#ffffff"},
      {"font",
       {{"family",
         "system-ui, -apple-system, 'Segoe UI', Roboto, 'Helvetica Neue', Arial, sans-serif"},
        {"size", 12},
        {"color", "#1f2937"}}},
      {"colorway",
       {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf",
        "#7f7f7f", "#bcbd22"}}};
  json config = {{"responsive", true},
                 {"displaylogo", false},
                 {"modeBarButtonsToRemove", {"lasso2d", "select2d"}},
                 {"toImageButtonOptions", {{"format", "svg"}, {"filename", plot.name}}}};
  return {{"id", div_id},
          {"data", std::move(data)},
          {"layout", std::move(layout)},
          {"config", std::move(config)}};
}

// ---------------------------------------------------------------------------------------------
// Page parts

constexpr const char* kStyle = R"CSS(
:root {
  --ink: #1f2937; --muted: #6b7280; --line: #e5e7eb; --bg: #f4f6f9; --card: #ffffff;
  --accent: #1d4ed8; --ok: #15803d; --ok-bg: #dcfce7; --warn: #a16207; --warn-bg: #fef3c7;
  --bad: #b91c1c; --bad-bg: #fee2e2;
}
* { box-sizing: border-box; }
html { scroll-behavior: smooth; }
body { margin: 0; background: var(--bg); color: var(--ink);
  font: 14px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif; }
code, .mono { font-family: ui-monospace, SFMono-Regular, Menlo, Consolas, "Liberation Mono", monospace;
  font-size: 12.5px; }
a { color: var(--accent); text-decoration: none; }
a:hover { text-decoration: underline; }
header.page { background: #0f172a; color: #e5e7eb; padding: 18px 28px 16px; }
header.page h1 { margin: 0 0 4px; font-size: 21px; font-weight: 600; color: #fff;
  display: flex; align-items: center; gap: 12px; flex-wrap: wrap; }
header.page .subtitle { color: #9ca3af; font-size: 13px; }
header.page dl { display: grid; grid-template-columns: max-content 1fr; gap: 3px 16px;
  margin: 12px 0 0; font-size: 13px; }
header.page dt { color: #9ca3af; }
header.page dd { margin: 0; overflow-wrap: anywhere; }
header.page code { color: #e5e7eb; }
.layout { display: grid; grid-template-columns: 250px minmax(0, 1fr); gap: 24px;
  max-width: 1500px; margin: 0 auto; padding: 22px 28px 40px; }
nav.toc { position: sticky; top: 16px; align-self: start; max-height: calc(100vh - 32px);
  overflow-y: auto; background: var(--card); border: 1px solid var(--line); border-radius: 8px;
  padding: 12px 10px; }
nav.toc h2 { font-size: 12px; text-transform: uppercase; letter-spacing: .06em; color: var(--muted);
  margin: 0 6px 8px; }
nav.toc ol { list-style: none; margin: 0; padding: 0; }
nav.toc li a { display: flex; align-items: center; justify-content: space-between; gap: 8px;
  padding: 5px 6px; border-radius: 5px; color: var(--ink); }
nav.toc li a:hover { background: #eef2ff; text-decoration: none; }
nav.toc .toc-name { overflow: hidden; text-overflow: ellipsis; white-space: nowrap; }
nav.toc .toc-type { display: block; color: var(--muted); font-size: 11.5px; }
main { min-width: 0; }
section.analysis { background: var(--card); border: 1px solid var(--line); border-radius: 8px;
  padding: 18px 22px 20px; margin-bottom: 22px; scroll-margin-top: 12px; }
section.analysis.failed { border-left: 4px solid var(--bad); }
section.analysis.warned { border-left: 4px solid var(--warn); }
.section-head { display: flex; align-items: baseline; gap: 12px; flex-wrap: wrap;
  border-bottom: 1px solid var(--line); padding-bottom: 10px; margin-bottom: 14px; }
.section-head h2 { margin: 0; font-size: 18px; font-weight: 600; }
.section-head .type { color: var(--muted); font-size: 13px; }
.section-head .runtime { margin-left: auto; color: var(--muted); font-size: 12.5px; }
.badge { display: inline-block; padding: 1px 9px; border-radius: 999px; font-size: 11.5px;
  font-weight: 600; letter-spacing: .02em; white-space: nowrap; }
.badge.ok { color: var(--ok); background: var(--ok-bg); }
.badge.warn { color: var(--warn); background: var(--warn-bg); }
.badge.bad { color: var(--bad); background: var(--bad-bg); }
header.page .badge { font-size: 12.5px; padding: 2px 11px; }
.alert { border: 1px solid #fca5a5; background: var(--bad-bg); color: #7f1d1d; border-radius: 6px;
  padding: 10px 14px; margin: 0 0 14px; }
.alert.warn { border-color: #fcd34d; background: var(--warn-bg); color: #713f12; }
.alert .alert-title { font-weight: 600; margin-bottom: 4px; }
.alert .alert-message { white-space: pre-wrap; overflow-wrap: anywhere; margin: 0;
  font-family: inherit; }
.notes { background: #f8fafc; border: 1px solid var(--line); border-radius: 6px;
  padding: 8px 14px; margin: 0 0 14px; }
.notes h3 { margin: 0 0 2px; font-size: 12px; text-transform: uppercase; letter-spacing: .05em;
  color: var(--muted); }
.notes ul { margin: 0; padding-left: 18px; }
.plots { display: grid; grid-template-columns: repeat(auto-fit, minmax(460px, 1fr)); gap: 14px;
  margin-bottom: 14px; }
figure.plot-card { margin: 0; border: 1px solid var(--line); border-radius: 6px; padding: 4px;
  min-width: 0; }
figure.plot-card.equal { max-width: 640px; }
figure.plot-card figcaption { color: var(--muted); font-size: 12px; padding: 2px 8px 4px; }
.geardyn-plot { width: 100%; min-height: 200px; }
.plot-error { color: var(--bad); padding: 12px; white-space: pre-wrap; }
.table-card { border: 1px solid var(--line); border-radius: 6px; margin: 0 0 14px; overflow: hidden; }
.table-head { display: flex; align-items: baseline; gap: 10px; flex-wrap: wrap;
  padding: 8px 12px; background: #f8fafc; border-bottom: 1px solid var(--line); }
.table-head h3 { margin: 0; font-size: 14px; font-weight: 600; }
.table-head .meta { color: var(--muted); font-size: 12.5px; }
.table-head .meta a { margin-left: 4px; }
.table-scroll { overflow: auto; max-height: 460px; }
table.data { border-collapse: separate; border-spacing: 0; width: max-content;
  font-size: 12.5px; font-variant-numeric: tabular-nums; }
table.data th { position: sticky; top: 0; background: #eef1f5; text-align: right; font-weight: 600;
  padding: 5px 14px; border-bottom: 1px solid #d6dbe3; white-space: nowrap; z-index: 1; }
table.data th .unit { display: block; font-weight: 400; color: var(--muted); font-size: 11px; }
table.data td { padding: 3px 14px; text-align: right; border-bottom: 1px solid #f0f2f5;
  white-space: nowrap; }
table.data th.text, table.data td.text { text-align: left; }
table.data tbody tr:nth-child(even) td { background: #fafbfc; }
table.data tbody tr:hover td { background: #eef2ff; }
.nan { color: #9ca3af; }
.table-note { margin: 0; padding: 6px 12px; color: var(--muted); font-size: 12.5px;
  border-top: 1px solid var(--line); background: #fffbeb; }
.empty { color: var(--muted); font-style: italic; }
footer.page { color: var(--muted); font-size: 12px; text-align: center; padding: 0 28px 28px; }
@media (max-width: 900px) {
  .layout { grid-template-columns: 1fr; padding: 14px; }
  nav.toc { position: static; max-height: none; }
  .plots { grid-template-columns: 1fr; }
}
@media print {
  body { background: #fff; }
  nav.toc { display: none; }
  .layout { grid-template-columns: 1fr; }
  section.analysis, figure.plot-card, .table-card { break-inside: avoid; }
  .table-scroll { max-height: none; overflow: visible; }
}
)CSS";

// Renders every figure, then marks <body data-plots-rendered="N">; a failure is shown in the plot's
// box and logged with console.error (which the browser test treats as a failure).
constexpr const char* kRenderScript = R"JS(
(function () {
  "use strict";
  var figures = JSON.parse(document.getElementById("geardyn-figures").textContent);
  var failures = 0;
  function fail(div, error) {
    failures += 1;
    console.error("geardyn report: plot " + div.id + " failed: " + error);
    div.innerHTML = "";
    var p = document.createElement("div");
    p.className = "plot-error";
    p.textContent = "This plot could not be drawn: " + error;
    div.appendChild(p);
  }
  var pending = figures.map(function (f) {
    var div = document.getElementById(f.id);
    try {
      return Promise.resolve(Plotly.newPlot(div, f.data, f.layout, f.config))
        .catch(function (e) { fail(div, e); });
    } catch (e) {
      fail(div, e);
      return Promise.resolve();
    }
  });
  Promise.all(pending).then(function () {
    document.body.setAttribute("data-plots-failed", String(failures));
    document.body.setAttribute("data-plots-rendered", String(figures.length - failures));
  });
})();
)JS";

std::string table_html(const Table& table, const std::string& analysis_name,
                       const ReportOptions& options) {
  table.validate();
  const std::size_t rows = table.rows();
  const std::size_t shown = std::min(rows, options.max_table_rows);
  const std::string csv = analysis_name + "/" + table.name + ".csv";
  std::string out;
  out += "<div class=\"table-card\">\n<div class=\"table-head\">";
  out += fmt::format("<h3>{}</h3>", escape_html(table.title.empty() ? table.name : table.title));
  out += fmt::format(
      "<span class=\"meta\">{} row{} &times; {} column{} &middot; <a class=\"csv-link\" "
      "href=\"{}\">{}</a></span></div>\n",
      rows, rows == 1 ? "" : "s", table.columns.size(), table.columns.size() == 1 ? "" : "s",
      escape_html(csv), escape_html(csv));
  out += "<div class=\"table-scroll\"><table class=\"data\">\n<thead><tr>";
  for (const Column& c : table.columns) {
    out += fmt::format("<th{}>{}", c.text ? " class=\"text\"" : "", escape_html(c.name));
    if (!c.unit.empty()) out += fmt::format("<span class=\"unit\">{}</span>", escape_html(c.unit));
    out += "</th>";
  }
  out += "</tr></thead>\n<tbody>\n";
  for (std::size_t i = 0; i < shown; ++i) {
    out += "<tr>";
    for (const Column& c : table.columns)
      out += fmt::format("<td{}>{}</td>", c.text ? " class=\"text\"" : "",
                         format_cell(c, i, options.display_digits));
    out += "</tr>\n";
  }
  out += "</tbody></table></div>\n";
  if (shown < rows)
    out += fmt::format(
        "<p class=\"table-note\">Showing the first {} of {} rows. The file <a href=\"{}\">{}</a> "
        "holds all of them.</p>\n",
        shown, rows, escape_html(csv), escape_html(csv));
  out += "</div>\n";
  return out;
}

}  // namespace

std::string escape_script_text(std::string_view js) {
  // A "</script" in any letter case would end the element early; "<\/script" means the same
  // inside JS strings and regular expressions, the only places it can occur. plotly.js 2.35 has
  // none, so this normally copies the text unchanged.
  static constexpr std::string_view kEnd = "</script";
  std::string out;
  out.reserve(js.size());
  std::size_t start = 0;
  for (std::size_t i = 0; i + kEnd.size() <= js.size(); ++i) {
    if (js[i] != '<' || js[i + 1] != '/') continue;
    bool match = true;
    for (std::size_t k = 2; k < kEnd.size() && match; ++k)
      match = std::tolower(static_cast<unsigned char>(js[i + k])) == kEnd[k];
    if (!match) continue;
    out.append(js.substr(start, i + 1 - start));
    out += '\\';
    start = i + 1;
  }
  out.append(js.substr(start));
  return out;
}

namespace {

// The page header: model, status badge, hash, start, time and command line.
void append_page_header(std::string& out, const RunInfo& info,
                        const std::vector<AnalysisOutput>& outputs, const std::string& model_name,
                        const std::string& started, double total_time, std::size_t n_failed) {
  const bool all_ok = n_failed == 0;
  out += "<header class=\"page\">\n";
  std::string verdict = outputs.empty() ? std::string("no analyses")
                        : all_ok
                            ? fmt::format("all {} analyses ok", outputs.size())
                            : fmt::format("failed: {} of {} analyses", n_failed, outputs.size());
  const char* badge_class = all_ok ? "ok" : "bad";
  if (!info.not_run.empty()) {  // written while the run is in progress (or was killed)
    verdict = fmt::format("incomplete: {} of {} analyses finished", outputs.size(),
                          outputs.size() + info.not_run.size());
    badge_class = "warn";
  }
  out += fmt::format("<h1>{} <span class=\"badge {}\">{}</span></h1>\n", escape_html(model_name),
                     badge_class, verdict);
  out +=
      fmt::format("<div class=\"subtitle\">geardyn {} report</div>\n<dl>\n", escape_html(kVersion));
  out += fmt::format("<dt>Model</dt><dd><code>{}</code></dd>\n",
                     escape_html(info.model_path.empty() ? "-" : info.model_path.string()));
  if (!info.model_sha256.empty())
    out +=
        fmt::format("<dt>SHA-256</dt><dd><code>{}</code></dd>\n", escape_html(info.model_sha256));
  out += fmt::format("<dt>Started</dt><dd>{}</dd>\n", escape_html(started));
  if (!info.not_run.empty()) {
    std::string names;
    for (const auto& n : info.not_run) names += (names.empty() ? "" : ", ") + n;
    out += fmt::format(
        "<dt>Not run</dt><dd>{} — the run had not finished when this report was written; if "
        "geardyn is no longer running, it was stopped (killed) before them</dd>\n",
        escape_html(names));
  }
  out += fmt::format("<dt>Analysis time</dt><dd>{}</dd>\n", format_duration(total_time));
  if (!info.command_line.empty())
    out +=
        fmt::format("<dt>Command</dt><dd><code>{}</code></dd>\n", escape_html(info.command_line));
  out += "</dl>\n</header>\n";
}

// The table of contents: one link per analysis with its status.
void append_contents(std::string& out, const std::vector<AnalysisOutput>& outputs) {
  out +=
      "<div class=\"layout\">\n<nav class=\"toc\" "
      "aria-label=\"Contents\">\n<h2>Analyses</h2>\n<ol>\n";
  for (std::size_t a = 0; a < outputs.size(); ++a) {
    const auto& o = outputs[a];
    out += fmt::format(
        "<li><a href=\"#analysis-{}\"><span class=\"toc-name\">{}<span class=\"toc-type\">{}</span>"
        "</span>{}</a></li>\n",
        a + 1, escape_html(o.name), escape_html(o.type), badge(o.status));
  }
  if (outputs.empty()) out += "<li class=\"empty\">No analyses ran.</li>\n";
  out += "</ol>\n</nav>\n<main>\n";
}

// The section of analysis a (0-based): status, notes, files, plots (their figures appended to
// figures) and tables; the caller closes the section.
void append_section(std::string& out, const AnalysisOutput& o, std::size_t a,
                    const ReportOptions& options, json& figures) {
  const char* state =
      o.status == Status::Ok ? "" : (is_incomplete(o.status) ? " warned" : " failed");
  out += fmt::format("<section class=\"analysis{}\" id=\"analysis-{}\">\n", state, a + 1);
  out += fmt::format(
      "<div class=\"section-head\"><h2>{}</h2><span class=\"type\">{}</span>{}<span "
      "class=\"runtime\">run time {}</span></div>\n",
      escape_html(o.name), escape_html(o.type), badge(o.status), format_duration(o.run_time_s));
  if (o.status != Status::Ok) {
    out += fmt::format(
        "<div class=\"alert{}\" role=\"alert\"><div class=\"alert-title\">{}</div><pre "
        "class=\"alert-message\">{}</pre></div>\n",
        is_incomplete(o.status) ? " warn" : "",
        is_incomplete(o.status)
            ? fmt::format("Incomplete result ({})", escape_html(to_string(o.status)))
            : fmt::format("This analysis failed ({})", escape_html(to_string(o.status))),
        escape_html(o.message.empty() ? "(no message)" : o.message));
  } else if (!o.message.empty()) {
    out += fmt::format("<div class=\"notes\"><p>{}</p></div>\n", escape_html(o.message));
  }
  if (!o.notes.empty()) {
    out += "<div class=\"notes\"><h3>How far to trust this result</h3><ul>\n";
    for (const auto& note : o.notes) out += fmt::format("<li>{}</li>\n", escape_html(note));
    out += "</ul></div>\n";
  }
  if (!o.files.empty()) {
    out += "<div class=\"notes\"><h3>Files</h3><ul>\n";
    for (const auto& f : o.files)
      out += fmt::format("<li><a href=\"{0}/{1}\"><code>{0}/{1}</code></a>: {2}</li>\n",
                         escape_html(o.name), escape_html(f.file_name), escape_html(f.description));
    out += "</ul></div>\n";
  }
  if (!o.plots.empty()) {
    out += "<div class=\"plots\">\n";
    for (std::size_t p = 0; p < o.plots.size(); ++p) {
      const Plot& plot = o.plots[p];
      const std::string id = fmt::format("plot-{}-{}", a + 1, p + 1);
      bool thinned = false;
      figures.push_back(plot_figure(plot, id, options, thinned));
      out += fmt::format(
          "<figure class=\"plot-card{}\"><div class=\"geardyn-plot\" id=\"{}\" "
          "data-plot-name=\"{}\"></div>",
          plot.equal_aspect ? " equal" : "", id, escape_html(plot.name));
      if (thinned)
        out += fmt::format(
            "<figcaption>Long traces are thinned to at most {} points for display (peaks kept); "
            "the tables hold every point.</figcaption>",
            options.max_points_per_trace);
      out += "</figure>\n";
    }
    out += "</div>\n";
  }
  for (const Table& table : o.tables) out += table_html(table, o.name, options);
  if (o.plots.empty() && o.tables.empty() && o.status == Status::Ok)
    out += "<p class=\"empty\">This analysis produced no tables or plots.</p>\n";
}

}  // namespace

std::string render_html(const RunInfo& info, const std::vector<AnalysisOutput>& outputs,
                        const ReportOptions& options) {
  if (options.display_digits < 1 || options.display_digits > 17)
    throw std::invalid_argument(fmt::format(
        "report: display_digits must be between 1 and 17, got {}", options.display_digits));
  const std::string file_name = info.model_path.empty() ? std::string("(no model file)")
                                                        : info.model_path.filename().string();
  // The model's title when it has one (with its file), else the file name.
  const std::string model_name =
      info.model_title.empty() ? file_name : fmt::format("{} ({})", info.model_title, file_name);
  std::size_t n_failed = 0;
  double total_time = 0.0;
  for (const auto& o : outputs) {
    if (o.status != Status::Ok) ++n_failed;
    if (std::isfinite(o.run_time_s)) total_time += o.run_time_s;
  }
  const std::string started = format_utc_iso8601(info.start_time);

  std::string out;
  out.reserve(plotly_js().size() + 256 * 1024);
  out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  out += fmt::format("<meta name=\"generator\" content=\"geardyn {}\">\n", escape_html(kVersion));
  out += fmt::format("<title>{} — geardyn report</title>\n", escape_html(model_name));
  out += "<style>";
  out += kStyle;
  out += "</style>\n<script>\n";
  out += escape_script_text(plotly_js());
  out += "\n</script>\n</head>\n<body>\n";

  append_page_header(out, info, outputs, model_name, started, total_time, n_failed);

  append_contents(out, outputs);

  // Sections
  json figures = json::array();
  for (std::size_t a = 0; a < outputs.size(); ++a) {
    append_section(out, outputs[a], a, options, figures);
    out += "</section>\n";
  }
  if (outputs.empty())
    out += "<section class=\"analysis\"><p class=\"empty\">No analyses ran.</p></section>\n";
  out += "</main>\n</div>\n";

  out += fmt::format(
      "<footer class=\"page\">Generated by geardyn {} &middot; started {} &middot; interactive "
      "plots by plotly.js {} (MIT licence), embedded in this file &middot; tables show at most {} "
      "rows at {} significant digits; the CSV files next to this report hold every value at full "
      "precision.</footer>\n",
      escape_html(kVersion), escape_html(started), escape_html(plotly_version()),
      options.max_table_rows, options.display_digits);
  out += "<script type=\"application/json\" id=\"geardyn-figures\">";
  out += json_for_script(figures);
  out += "</script>\n<script>";
  out += kRenderScript;
  out += "</script>\n</body>\n</html>\n";
  return out;
}

}  // namespace geardyn::report
