#!/usr/bin/env node
// Browser test of a geardyn HTML report: opens it from file:// in headless Chromium (Debian's,
// driven by playwright-core from the repository's node_modules), with every non-file request
// blocked, waits until the page says all plots are drawn, then checks that
//   - every plot box holds a rendered plotly figure ('.main-svg') with one drawn trace per trace
//     in its data (curves and heat maps),
//   - figures asked for equal axes (scaleanchor) draw one unit of x and of y with the same length,
//   - the console logged no error and the page threw none,
//   - nothing was requested from outside the file (the report must be self-contained).
// Exits 0 when all hold, 1 otherwise (and 2 on bad usage), listing every problem.
//
// Usage: node check_report.mjs REPORT.html [--expect-plots N] [--screenshot OUT.png]
//                              [--full-page] [--timeout MS]
// Environment: GEARDYN_CHROMIUM overrides the browser (default /usr/bin/chromium).
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

function usage(message) {
  console.error(`check_report: ${message}`);
  console.error('usage: node check_report.mjs REPORT.html [--expect-plots N] [--screenshot OUT.png] [--full-page] [--timeout MS]');
  process.exit(2);
}

const options = { report: null, expectPlots: null, screenshot: null, fullPage: false, timeout: 60000 };
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; ++i) {
  const a = argv[i];
  if (a === '--expect-plots') options.expectPlots = Number(argv[++i]);
  else if (a === '--screenshot') options.screenshot = argv[++i];
  else if (a === '--full-page') options.fullPage = true;
  else if (a === '--timeout') options.timeout = Number(argv[++i]);
  else if (a.startsWith('--')) usage(`unknown option ${a}`);
  else if (options.report === null) options.report = a;
  else usage(`unexpected argument ${a}`);
}
if (options.report === null) usage('no report given');
if (options.expectPlots !== null && !Number.isInteger(options.expectPlots)) usage('--expect-plots needs an integer');
if (!Number.isFinite(options.timeout) || options.timeout <= 0) usage('--timeout needs a positive number of ms');
const reportPath = path.resolve(options.report);
if (!fs.existsSync(reportPath)) usage(`no such file: ${reportPath}`);

const executablePath = process.env.GEARDYN_CHROMIUM || '/usr/bin/chromium';
const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'geardyn-report-check-'));
const problems = [];
const external = [];
let context = null;

try {
  // launchPersistentContext is how playwright takes a --user-data-dir: a fresh one per run.
  context = await chromium.launchPersistentContext(userDataDir, {
    executablePath,
    headless: true,
    viewport: { width: 1440, height: 900 },
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  await context.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file:') || url.startsWith('data:') || url.startsWith('blob:') ||
        url.startsWith('about:')) {
      return route.continue();
    }
    external.push(url);
    return route.abort();
  });
  const page = context.pages()[0] ?? (await context.newPage());
  page.on('console', (message) => {
    if (message.type() === 'error') problems.push(`console error: ${message.text()}`);
  });
  page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));

  await page.goto(pathToFileURL(reportPath).href, { waitUntil: 'load', timeout: options.timeout });
  try {
    await page.waitForFunction(() => document.body?.hasAttribute('data-plots-rendered'), null,
                               { timeout: options.timeout });
  } catch (error) {
    problems.push(`the plots did not finish rendering within ${options.timeout} ms`);
  }

  const result = await page.evaluate(() => {
    const plots = [...document.querySelectorAll('.geardyn-plot')].map((div) => {
      const info = { id: div.id, rendered: div.querySelector('.main-svg') !== null };
      if (div._fullData) {
        info.traces = div._fullData.length;
        // Curves are drawn in the scatter layer, heat maps in the heatmap layer (class 'hm').
        info.drawnTraces = div.querySelectorAll('.scatterlayer .trace, .heatmaplayer .hm').length;
      }
      const layout = div._fullLayout;
      if (layout && layout.yaxis && layout.yaxis.scaleanchor === 'x') {
        // Pixels per data unit along x and y (plotly's internal scale factors).
        info.equal = { xScale: Math.abs(layout.xaxis._m), yScale: Math.abs(layout.yaxis._m) };
      }
      return info;
    });
    return {
      plots,
      figures: JSON.parse(document.getElementById('geardyn-figures')?.textContent ?? '[]').length,
      failed: Number(document.body.getAttribute('data-plots-failed') ?? 'NaN'),
    };
  });

  if (result.plots.length !== result.figures) {
    problems.push(`${result.plots.length} plot boxes but ${result.figures} figures in the data`);
  }
  if (options.expectPlots !== null && result.plots.length !== options.expectPlots) {
    problems.push(`expected ${options.expectPlots} plots, found ${result.plots.length}`);
  }
  if (result.failed !== 0) problems.push(`the page reports ${result.failed} failed plots`);
  for (const p of result.plots) {
    if (!p.rendered) problems.push(`plot ${p.id}: no rendered .main-svg`);
    if (p.traces !== undefined && p.drawnTraces !== p.traces) {
      problems.push(`plot ${p.id}: ${p.traces} traces in the data, ${p.drawnTraces} drawn`);
    }
    if (p.equal) {
      const ratio = p.equal.yScale / p.equal.xScale;
      if (!(Math.abs(ratio - 1) < 1e-3)) {
        problems.push(`plot ${p.id}: equal aspect asked, but y/x pixels per unit = ${ratio}`);
      }
    }
  }
  for (const url of external) problems.push(`request to outside the file: ${url}`);

  if (options.screenshot) {
    await page.screenshot({ path: options.screenshot, fullPage: options.fullPage });
  }
  const equal = result.plots.filter((p) => p.equal).length;
  console.log(`check_report: ${reportPath}: ${result.plots.filter((p) => p.rendered).length} of ` +
              `${result.plots.length} plots rendered (${equal} with equal axes), ` +
              `${problems.length} problem(s)`);
} catch (error) {
  problems.push(`browser run failed: ${error.message}`);
} finally {
  if (context) await context.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}

for (const p of problems) console.error(`check_report: ${p}`);
process.exit(problems.length === 0 ? 0 : 1);
