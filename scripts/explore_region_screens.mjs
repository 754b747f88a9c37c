#!/usr/bin/env node
// SPDX-License-Identifier: MIT
// explore_region_screens.mjs: paints a region on one shape of a running `shapestruct explore` server through
// real mouse strokes, sorts, and saves screenshots of the sorted collection and of "align to region". Made for
// the documentation's real-data figures (docs/explore.md); prints the ranking and the query's timings.
// Strokes are small circles about each given point that is visible in the example view.
//
//   node scripts/explore_region_screens.mjs --url http://127.0.0.1:PORT/ --node-modules BUILD/web/explore-npm/node_modules \
//        --example 0 --points "x,y,z;x,y,z" --screens DIR [--prefix NAME] [--brush 8]
//
// --points are model-space positions on the example (for instance benchmark feature points).

import path from 'node:path';
import fs from 'node:fs';
import { createRequire } from 'node:module';

const args = { url: null, nodeModules: null, example: null, points: null, screens: null, prefix: 'region', brush: '8' };
const names = { '--url': 'url', '--node-modules': 'nodeModules', '--example': 'example', '--points': 'points',
  '--screens': 'screens', '--prefix': 'prefix', '--brush': 'brush' };
for (let i = 2; i < process.argv.length; i += 2) {
  const key = names[process.argv[i]];
  if (!key || i + 1 >= process.argv.length) fail(`unknown or incomplete argument '${process.argv[i]}'`, 2);
  args[key] = process.argv[i + 1];
}
if (!args.url || !args.nodeModules || args.example === null || !args.points || !args.screens) {
  fail('usage: explore_region_screens.mjs --url URL --node-modules DIR --example I --points "x,y,z;..." --screens DIR', 2);
}
const example = Number(args.example);
const points = args.points.split(';').map((p) => p.split(',').map(Number));
if (points.some((p) => p.length !== 3 || p.some((x) => !Number.isFinite(x)))) fail(`bad --points '${args.points}'`, 2);

function fail(message, code = 1) {
  console.error(`explore_region_screens: ${message}`);
  process.exit(code);
}

const { chromium } = createRequire(path.join(path.resolve(args.nodeModules), 'noop.js'))('playwright-core');
fs.mkdirSync(args.screens, { recursive: true });
const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(args.url);
  await page.waitForFunction(() => window.explorer && window.explorer.ready, null, { timeout: 180_000 });
  const settle = () => page.evaluate(() => window.explorer.settled());
  const shot = async (name) => {
    await settle();
    const file = path.join(args.screens, `${args.prefix}-${name}.png`);
    await page.screenshot({ path: file });
    console.log(`screenshot ${file}`);
  };

  // The example, through its tile's button (paging until it is shown).
  const tile = page.locator(`.tile[data-shape="${example}"]`);
  for (let guard = 0; !(await tile.isVisible()); ++guard) {
    if (guard > 100) fail(`shape ${example} is on no page`);
    await page.click('[data-testid=next-page]');
    await settle();
  }
  await tile.locator('[data-testid=use-example]').click();
  await page.waitForFunction((s) => window.explorer.examples().includes(s), example);
  await settle();
  await page.locator('[data-testid=brush-radius]').fill(args.brush);

  // Strokes: a small circle about each visible point (a line between them could cross other parts).
  const projected = await page.evaluate((pts) => pts.map((p) => window.explorer.projectToScreen(0, p)), points);
  const visible = projected.filter((p) => p.visible);
  if (!visible.length) fail('none of the --points is visible in the example view');
  for (const c of visible) {
    await page.mouse.move(c.x + 6, c.y);
    await page.mouse.down();
    for (let a = 1; a <= 12; ++a) {
      await page.mouse.move(c.x + 6 * Math.cos((a * Math.PI) / 6), c.y + 6 * Math.sin((a * Math.PI) / 6));
    }
    await page.mouse.up();
  }
  await settle();
  const region = await page.evaluate(() => window.explorer.regionSamples(0));
  console.log(`painted ${region.length} samples over ${visible.length} of ${points.length} visible points`);

  await page.click('[data-testid=sort]');
  await page.waitForFunction(() => window.explorer.timings.lastSortMs !== null || window.explorer.error(), null,
    { timeout: 120_000 });
  const error = await page.evaluate(() => window.explorer.error());
  if (error) fail(`Sort failed: ${error}`);
  const timings = await page.evaluate(() => ({ ...window.explorer.timings }));
  const collection = await (await fetch(new URL('api/collection', args.url))).json();
  const ranking = await page.evaluate(() => window.explorer.ranking());
  console.log(`ranking: ${ranking.map((s) => collection.shapes[s].name).join(' ')}`);
  console.log(`query ${Math.round(timings.lastQueryMs)} ms round trip (server ${(1000 * timings.lastQuerySeconds).toFixed(1)} ms), ` +
    `sort to redrawn ${Math.round(timings.lastSortMs)} ms`);
  await shot('sorted');
  await page.click('[data-testid=align-region]');
  await page.waitForFunction(() => document.querySelector('[data-testid=align-region]').getAttribute('aria-pressed') === 'true');
  await shot('aligned');
  if (errors.length) fail(`errors in the page: ${errors.join('; ')}`);
} finally {
  await browser.close();
}
