#include "geardyn/report/html_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "geardyn/core/version.hpp"
#include "geardyn/report/plotly_js.hpp"

namespace geardyn::report {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1))
    ++n;
  return n;
}

// The figures handed to Plotly.newPlot, as the page holds them.
nlohmann::json figures_of(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"geardyn-figures\">";
  const std::size_t begin = html.find(open);
  EXPECT_NE(begin, std::string::npos);
  const std::size_t start = begin + open.size();
  const std::size_t end = html.find("</script>", start);
  return nlohmann::json::parse(html.substr(start, end - start));
}

Plot line_plot(std::string name, std::size_t n) {
  Plot p;
  p.name = std::move(name);
  p.title = "Receptance";
  p.x_label = "frequency [Hz]";
  p.y_label = "|H| [m/N]";
  p.x_log = true;
  p.y_log = true;
  Trace t;
  t.name = "H11";
  for (std::size_t i = 0; i < n; ++i) {
    t.x.push_back(1.0 + static_cast<double>(i));
    t.y.push_back(1.0 / (1.0 + static_cast<double>(i)));
  }
  p.traces.push_back(t);
  return p;
}

std::vector<AnalysisOutput> sample_outputs() {
  AnalysisOutput frf;
  frf.name = "frf <b>&amp;</b>";
  frf.type = "harmonic";
  frf.notes = {"note with <i>markup</i> & \"quotes\""};
  frf.plots.push_back(line_plot("frf", 50));
  Plot orbit;
  orbit.name = "orbit";
  orbit.title = "Orbit at <bearing 1>";
  orbit.x_label = "y [m]";
  orbit.y_label = "z [m]";
  orbit.equal_aspect = true;
  Trace ellipse;
  ellipse.name = "1x";
  ellipse.mode = Trace::Mode::LinesMarkers;
  ellipse.dash = "dash";
  for (int i = 0; i <= 64; ++i) {
    ellipse.x.push_back(2e-6 * std::cos(i * 2 * M_PI / 64));
    ellipse.y.push_back(1e-6 * std::sin(i * 2 * M_PI / 64));
    ellipse.hover.push_back("angle " + std::to_string(i * 360 / 64) + " deg <x>");
  }
  orbit.traces.push_back(ellipse);
  frf.plots.push_back(orbit);
  Table big;
  big.name = "frf";
  big.title = "FRF samples";
  std::vector<double> f(250), h(250);
  for (std::size_t i = 0; i < 250; ++i) {
    f[i] = static_cast<double>(i);
    h[i] = i == 3 ? std::numeric_limits<double>::quiet_NaN() : 1.0 / (1.0 + f[i]);
  }
  big.add("frequency_hz", "Hz", f);
  big.add("amplitude_m_per_n", "m/N", h);
  big.add_text("comment", std::vector<std::string>(250, "a<b"));
  frf.tables.push_back(big);

  AnalysisOutput failed;
  failed.name = "transient";
  failed.type = "transient";
  failed.status = Status::Diverged;
  failed.message = "time step 1e-4 s diverged at t = 0.31 s; reduce dt";
  failed.plots.push_back(line_plot("partial", 10));
  return {frf, failed};
}

RunInfo sample_info() {
  RunInfo info;
  info.model_path = "examples/rotor <test>.toml";
  info.model_sha256 = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
  info.command_line = "geardyn run 'rotor <test>.toml'";
  return info;
}

TEST(EscapeHtml, ReplacesTheFiveSpecialCharacters) {
  EXPECT_EQ(escape_html("<a href='x'>\"&\"</a>"),
            "&lt;a href=&#39;x&#39;&gt;&quot;&amp;&quot;&lt;/a&gt;");
  EXPECT_EQ(escape_html("plain text 1.5 m/s"), "plain text 1.5 m/s");
}

TEST(EscapeScriptText, BreaksEveryScriptEndTag) {
  EXPECT_EQ(escape_script_text("var s = \"</script>\"; var t = '</SCRIPT >';"),
            "var s = \"<\\/script>\"; var t = '<\\/SCRIPT >';");
  EXPECT_EQ(escape_script_text("a < b && c </ d"), "a < b && c </ d");
}

TEST(PlotlyJs, IsEmbeddedAndSafeInAScriptElement) {
  const std::string_view js = plotly_js();
  ASSERT_GT(js.size(), 1000000u);
  EXPECT_NE(js.substr(0, 200).find("plotly.js v"), std::string_view::npos);
  EXPECT_NE(js.substr(0, 200).find(plotly_version()), std::string_view::npos);
  // "<!--" followed by "<script" would switch the HTML parser into a state where "</script>"
  // no longer ends the element; escape_script_text does not handle it, so it must not occur.
  const std::string lower = [&] {
    std::string s(js);
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  }();
  EXPECT_EQ(lower.find("<!--"), std::string::npos);
  EXPECT_EQ(lower.find("<script"), std::string::npos);
}

TEST(RenderHtml, IsOneSelfContainedPage) {
  const std::string html = render_html(sample_info(), sample_outputs());
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  // plotly.js is inline, whole.
  const std::string js = escape_script_text(plotly_js());
  const std::size_t js_at = html.find(js);
  ASSERT_NE(js_at, std::string::npos);
  // Nothing is loaded from elsewhere: no script/link/img with a source in the page itself
  // (plotly.js holds URLs of map tiles and icons, used only by map plots, which geardyn has not).
  const std::string page = html.substr(0, js_at) + html.substr(js_at + js.size());
  const std::regex external(R"(<(script|link|img|iframe)\b[^>]*\b(src|href)\s*=)",
                            std::regex::icase);
  EXPECT_FALSE(std::regex_search(page, external));
  EXPECT_EQ(page.find("http://"), std::string::npos);
  EXPECT_EQ(page.find("https://"), std::string::npos);
  // Three script elements (plotly, figure data, renderer), each closed exactly once.
  EXPECT_EQ(count(html, "<script"), 3u);
  EXPECT_EQ(count(html, "</script>"), 3u);
  EXPECT_NE(html.find("</html>"), std::string::npos);
}

TEST(RenderHtml, HeaderNamesModelVersionAndOverallStatus) {
  const std::string html = render_html(sample_info(), sample_outputs());
  EXPECT_NE(html.find("rotor &lt;test&gt;.toml"), std::string::npos);
  EXPECT_NE(html.find(sample_info().model_sha256), std::string::npos);
  EXPECT_NE(html.find(std::string("geardyn ") + kVersion), std::string::npos);
  EXPECT_NE(html.find(format_utc_iso8601(sample_info().start_time).substr(0, 10)),
            std::string::npos);
  EXPECT_NE(html.find("failed: 1 of 2 analyses"), std::string::npos);
  EXPECT_NE(html.find("geardyn run &#39;rotor &lt;test&gt;.toml&#39;"), std::string::npos);
}

TEST(RenderHtml, TheModelsTitleHeadsTheReport) {
  RunInfo info = sample_info();
  info.model_title = "Central gear train <HPR>";
  const std::string html = render_html(info, sample_outputs());
  EXPECT_NE(html.find("<title>Central gear train &lt;HPR&gt; (rotor &lt;test&gt;.toml)"),
            std::string::npos);
  EXPECT_NE(html.find("<h1>Central gear train &lt;HPR&gt; (rotor &lt;test&gt;.toml)"),
            std::string::npos);
}

TEST(RenderHtml, EscapesAllText) {
  const std::string html = render_html(sample_info(), sample_outputs());
  EXPECT_EQ(html.find("<b>&amp;</b>"), std::string::npos);
  EXPECT_NE(html.find("frf &lt;b&gt;&amp;amp;&lt;/b&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<i>markup</i>"), std::string::npos);
  EXPECT_NE(html.find("note with &lt;i&gt;markup&lt;/i&gt; &amp; &quot;quotes&quot;"),
            std::string::npos);
  EXPECT_EQ(html.find("<td class=\"text\">a<b</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"text\">a&lt;b</td>"), std::string::npos);
  // In the figure data no '<' appears raw (JSON escape \u003c), so it cannot close the element.
  const std::size_t data = html.find("id=\"geardyn-figures\">");
  const std::string json_text = html.substr(data, html.find("</script>", data) - data);
  EXPECT_EQ(json_text.find('<'), std::string::npos);
  // Plotly decodes character references in its labels: text shows literally.
  const nlohmann::json figs = figures_of(html);
  EXPECT_EQ(figs[1]["layout"]["title"]["text"], "Orbit at &lt;bearing 1&gt;");
}

TEST(RenderHtml, OneDivPerPlotAndMatchingFigures) {
  const std::string html = render_html(sample_info(), sample_outputs());
  EXPECT_EQ(count(html, "class=\"geardyn-plot\""), 3u);
  const nlohmann::json figs = figures_of(html);
  ASSERT_EQ(figs.size(), 3u);
  for (const auto& f : figs)
    EXPECT_NE(html.find("id=\"" + f["id"].get<std::string>() + "\""), std::string::npos);

  const auto& frf = figs[0];
  EXPECT_EQ(frf["layout"]["xaxis"]["type"], "log");
  EXPECT_EQ(frf["layout"]["yaxis"]["type"], "log");
  EXPECT_FALSE(frf["layout"]["yaxis"].contains("scaleanchor"));
  EXPECT_EQ(frf["data"][0]["mode"], "lines");
  EXPECT_EQ(frf["data"][0]["x"].size(), 50u);
  EXPECT_DOUBLE_EQ(frf["data"][0]["y"][1].get<double>(), 0.5);

  const auto& orbit = figs[1];
  EXPECT_EQ(orbit["layout"]["xaxis"]["type"], "linear");
  EXPECT_EQ(orbit["layout"]["yaxis"]["scaleanchor"], "x");
  EXPECT_EQ(orbit["layout"]["yaxis"]["scaleratio"], 1);
  EXPECT_EQ(orbit["data"][0]["mode"], "lines+markers");
  EXPECT_EQ(orbit["data"][0]["line"]["dash"], "dash");
  EXPECT_EQ(orbit["data"][0]["text"][8], "angle 45 deg &lt;x&gt;");
  EXPECT_NE(orbit["data"][0]["hovertemplate"].get<std::string>().find("%{text}"),
            std::string::npos);
}

// A plot with many traces (a Campbell diagram) gets its legend under the axes, the card taller
// by a row per three entries; with few traces the legend stays beside the plot.
TEST(RenderHtml, ManyTracesPutTheLegendUnderThePlot) {
  AnalysisOutput out;
  out.name = "campbell";
  out.type = "campbell";
  Plot many = line_plot("campbell", 20);
  for (int k = 1; k < 12; ++k) {
    Trace t = many.traces.front();
    t.name = "mode " + std::to_string(k + 1) + ", lateral forward";
    many.traces.push_back(t);
  }
  out.plots.push_back(many);
  out.plots.push_back(line_plot("frf", 20));
  const nlohmann::json figs = figures_of(render_html(sample_info(), {out}));
  ASSERT_EQ(figs.size(), 2u);
  EXPECT_EQ(figs[0]["layout"]["legend"]["orientation"], "h");
  EXPECT_EQ(figs[0]["layout"]["legend"]["yanchor"], "top");
  EXPECT_EQ(figs[0]["layout"]["height"], 430 + 22 * 4);  // 12 traces, three per row
  EXPECT_FALSE(figs[1]["layout"]["legend"].contains("orientation"));
  EXPECT_EQ(figs[1]["layout"]["height"], 430);
}

TEST(RenderHtml, FailedAnalysisShowsItsMessage) {
  const std::string html = render_html(sample_info(), sample_outputs());
  const std::size_t section = html.find("id=\"analysis-2\"");
  ASSERT_NE(section, std::string::npos);
  const std::size_t alert = html.find("role=\"alert\"", section);
  ASSERT_NE(alert, std::string::npos);
  const std::size_t message =
      html.find("time step 1e-4 s diverged at t = 0.31 s; reduce dt", alert);
  EXPECT_NE(message, std::string::npos);
  EXPECT_LT(message, html.find("class=\"geardyn-plot\"", section));  // before the plots
  EXPECT_NE(html.find("<span class=\"badge bad\">diverged</span>"), std::string::npos);
  EXPECT_NE(html.find("<span class=\"badge ok\">ok</span>"), std::string::npos);
}

TEST(RenderHtml, LongTablesShowTheirFirstRowsAndPointToTheCsv) {
  const std::string html = render_html(sample_info(), sample_outputs());
  const std::size_t begin = html.find("<tbody>"), end = html.find("</tbody>");
  EXPECT_EQ(count(html.substr(begin, end - begin), "<tr>"), 200u);
  EXPECT_NE(html.find("Showing the first 200 of 250 rows"), std::string::npos);
  EXPECT_NE(html.find("href=\"frf &lt;b&gt;&amp;amp;&lt;/b&gt;/frf.csv\""), std::string::npos);
  EXPECT_NE(html.find("<span class=\"nan\">NaN</span>"), std::string::npos);

  ReportOptions all_rows;
  all_rows.max_table_rows = 1000;
  const std::string full = render_html(sample_info(), sample_outputs(), all_rows);
  const std::size_t b = full.find("<tbody>"), e = full.find("</tbody>");
  EXPECT_EQ(count(full.substr(b, e - b), "<tr>"), 250u);
  EXPECT_EQ(full.find("Showing the first"), std::string::npos);
}

TEST(RenderHtml, LongTracesAreThinnedKeepingPeaks) {
  // A time history of 200 001 samples with one narrow spike of height 7 at sample 123 457: the
  // thinned trace must stay under the point budget and still reach the spike and the minimum.
  AnalysisOutput out;
  out.name = "transient";
  out.type = "transient";
  Plot p;
  p.name = "history";
  Trace t;
  const std::size_t n = 200001;
  for (std::size_t i = 0; i < n; ++i) {
    t.x.push_back(1e-5 * static_cast<double>(i));
    t.y.push_back(std::sin(1e-3 * static_cast<double>(i)));
  }
  t.y[123457] = 7.0;
  p.traces.push_back(t);
  Trace orbit;  // x not increasing: every k-th point
  for (std::size_t i = 0; i < n; ++i) {
    orbit.x.push_back(std::cos(1e-3 * static_cast<double>(i)));
    orbit.y.push_back(std::sin(1e-3 * static_cast<double>(i)));
  }
  p.traces.push_back(orbit);
  out.plots.push_back(p);
  ReportOptions options;
  options.max_points_per_trace = 2000;
  const std::string html = render_html(RunInfo{}, {out}, options);
  const nlohmann::json figs = figures_of(html);
  const auto& y = figs[0]["data"][0]["y"];
  EXPECT_LE(y.size(), 2000u);
  EXPECT_GE(y.size(), 1000u);
  double max_y = -1e9, min_y = 1e9;
  for (const auto& v : y) {
    max_y = std::max(max_y, v.get<double>());
    min_y = std::min(min_y, v.get<double>());
  }
  EXPECT_EQ(max_y, 7.0);
  EXPECT_NEAR(min_y, -1.0, 1e-6);
  const auto& ox = figs[0]["data"][1]["x"];
  EXPECT_LE(ox.size(), 2001u);
  EXPECT_NEAR(ox.back().get<double>(), std::cos(200.0), 1e-8);  // the last point is kept
  EXPECT_NE(html.find("thinned to at most 2000 points"), std::string::npos);
}

TEST(RenderHtml, OptionsOutOfRangeAreRejected) {
  ReportOptions options;
  options.display_digits = 0;
  EXPECT_THROW(render_html(RunInfo{}, sample_outputs(), options), std::invalid_argument);
  options.display_digits = 18;
  EXPECT_THROW(render_html(RunInfo{}, sample_outputs(), options), std::invalid_argument);
}

TEST(RenderHtml, ZeroPointBudgetDrawsEveryPoint) {
  AnalysisOutput out;
  out.name = "a";
  out.type = "transient";
  out.plots.push_back(line_plot("long", 30000));
  ReportOptions options;
  options.max_points_per_trace = 0;
  const std::string html = render_html(RunInfo{}, {out}, options);
  EXPECT_EQ(figures_of(html)[0]["data"][0]["x"].size(), 30000u);
  EXPECT_EQ(html.find("thinned to at most"), std::string::npos);
}

TEST(RenderHtml, NonFiniteValuesBecomeGaps) {
  AnalysisOutput out;
  out.name = "a";
  out.type = "modal";
  Plot p;
  p.name = "p";
  Trace t;
  t.x = {1, 2, 3};
  t.y = {1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()};
  p.traces.push_back(t);
  out.plots.push_back(p);
  const nlohmann::json figs = figures_of(render_html(RunInfo{}, {out}));
  EXPECT_TRUE(figs[0]["data"][0]["y"][1].is_null());
  EXPECT_TRUE(figs[0]["data"][0]["y"][2].is_null());
}

// A heat map (the contact pattern of tooth_contact): a plotly heatmap trace with the grid as
// given (z has one row per y, one value per x; no thinning, even beyond the point budget), NaN
// cells null (blank), the z label on the colour bar and in the hover text, no legend.
TEST(RenderHtml, HeatMapsKeepTheirGridAndLabelTheColourBar) {
  AnalysisOutput out;
  out.name = "pattern";
  out.type = "tooth_contact";
  Plot p;
  p.name = "line_load_map";
  p.title = "Line load";
  p.x_label = "face position [mm]";
  p.y_label = "roll angle of gear 1 [deg]";
  Trace t;
  t.name = "200 N m";
  t.z_label = "line load <N/mm>";
  t.x = {0.5, 1.5, 2.5};
  t.y = {10.0, 11.0};
  t.z = {{1.0, 2.0, 3.0}, {4.0, std::numeric_limits<double>::quiet_NaN(), 6.123456789}};
  p.traces.push_back(t);
  out.plots.push_back(p);
  ReportOptions options;
  options.max_points_per_trace = 2;  // below the 6 cells: a heat map is still drawn whole
  const std::string html = render_html(RunInfo{}, {out}, options);
  const nlohmann::json figs = figures_of(html);
  ASSERT_EQ(figs.size(), 1u);
  const nlohmann::json& d = figs[0]["data"][0];
  EXPECT_EQ(d["type"], "heatmap");
  EXPECT_EQ(d["x"], nlohmann::json({0.5, 1.5, 2.5}));
  EXPECT_EQ(d["y"], nlohmann::json({10.0, 11.0}));
  ASSERT_EQ(d["z"].size(), 2u);
  ASSERT_EQ(d["z"][1].size(), 3u);
  EXPECT_EQ(d["z"][0][2], 3.0);
  EXPECT_TRUE(d["z"][1][1].is_null());
  // Rounded to display_digits + 2 = 8 significant digits, like the curves.
  EXPECT_DOUBLE_EQ(d["z"][1][2].get<double>(), 6.1234568);
  EXPECT_EQ(d["colorbar"]["title"]["text"], "line load &lt;N/mm&gt;");
  EXPECT_NE(d["hovertemplate"].get<std::string>().find("line load &lt;N/mm&gt; = %{z}"),
            std::string::npos);
  EXPECT_FALSE(figs[0]["layout"]["showlegend"].get<bool>());
  EXPECT_EQ(html.find("thinned to at most"), std::string::npos);
  EXPECT_EQ(count(html, "class=\"geardyn-plot\""), 1u);
}

// A bar trace (1/3-octave band levels of order_analysis): a plotly "bar" trace with its x and y,
// no line style and no scatter mode.
TEST(RenderHtml, BarTracesArePlotlyBars) {
  AnalysisOutput out;
  out.name = "bands";
  out.type = "order_analysis";
  Plot p;
  p.name = "third_octave";
  Trace t;
  t.name = "A-weighted";
  t.mode = Trace::Mode::Bars;
  t.x = {100.0, 125.0, 160.0};
  t.y = {60.0, 62.5, 58.0};
  p.traces.push_back(t);
  out.plots.push_back(p);
  const nlohmann::json figs = figures_of(render_html(RunInfo{}, {out}));
  ASSERT_EQ(figs.size(), 1u);
  const nlohmann::json& d = figs[0]["data"][0];
  EXPECT_EQ(d["type"], "bar");
  EXPECT_EQ(d["x"], nlohmann::json({100.0, 125.0, 160.0}));
  EXPECT_EQ(d["y"], nlohmann::json({60.0, 62.5, 58.0}));
  EXPECT_FALSE(d.contains("mode"));
  EXPECT_FALSE(d.contains("line"));
}

TEST(RenderHtml, NoAnalysesIsStillAPage) {
  const std::string html = render_html(RunInfo{}, {});
  EXPECT_NE(html.find("No analyses ran."), std::string::npos);
  EXPECT_NE(html.find(">no analyses</span>"), std::string::npos);
  EXPECT_TRUE(figures_of(html).empty());
}

}  // namespace
}  // namespace geardyn::report
