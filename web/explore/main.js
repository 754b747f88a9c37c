// SPDX-License-Identifier: MIT
// main.js: the explorer page - state, toolbar, paging, sorting, colour and alignment modes, and the
// `window.explorer` hooks the browser test drives. Dissertation section 4.5: an ROI pane where the user paints
// regions on example shapes, and a results pane with the collection sorted by similarity within them.

import * as api from './api.js';
import { ViewRenderer } from './views.js';
import { ResultsPane } from './results.js';
import { RoiPane } from './roi.js';
import { baseColours, overlayBytes, sampleVolume, partCss, varianceCss } from './painting.js';

const $ = (selector) => document.querySelector(selector);

const formatSeconds = (t) => (t < 1 ? `${(1000 * t).toFixed(t < 0.01 ? 1 : 0)} ms` : `${t.toFixed(2)} s`);

/** A hint for the user (a missing step), not a failure: shown, not logged. */
class UserError extends Error {}

const state = {
  collection: null,   // GET /api/collection
  order: [],          // shape indices in display order: collection order until the first sort
  page: 0,
  colourMode: 'plain',      // 'plain' | 'variance' | 'parts'
  alignMode: 'original',    // 'original' | 'canonical' | 'region'
  query: null,        // the last sort: {regions, order, distance: Map, details: Map(shape -> Promise), seconds, ms}
  error: null,
};

const timings = { firstRenderMs: null, lastQueryMs: null, lastQuerySeconds: null, lastSortMs: null };

// Ask for the collection first: the request overlaps the WebGL set-up below (slow with software GL).
const collectionRequest = api.getCollection();
let renderer;
try {
  renderer = new ViewRenderer($('#gl'));
} catch (err) {
  showError(new Error(`this browser cannot draw the shapes: WebGL 2 is not available (${err.message})`));
  throw err;
}
const results = new ResultsPane({
  grid: $('#grid'),
  clip: $('#results-scroll'),
  renderer,
  onUseExample: (shape) => addExample(shape),
  onCameraChange: () => renderer.requestRender(),
});
const roi = new RoiPane({
  container: $('#examples'),
  clip: $('#roi-scroll'),
  renderer,
  controls: { brush: $('#brush'), erase: $('[data-testid=erase]'), rotate: $('[data-testid=rotate]') },
  onAdd: (example) => loadExample(example).catch(showError),
  onChange: (example, { live }) => {
    colourExample(example).catch(showError);
    if (!live) updateStatus();
  },
  onRemove: () => {
    updateResultsCaptions();
    updateStatus();
  },
});

// ---------------------------------------------------------------------------------------------------------
// Colouring and alignment of one view

// Per mesh: its voxel grid of nearest samples, computed once (O(voxels x samples), ~10 ms for a chair).
const volumes = new WeakMap();
function volumeOf(mesh) {
  if (!volumes.has(mesh)) volumes.set(mesh, sampleVolume(mesh));
  return volumes.get(mesh);
}

/**
 * Colours of `shape` for the current mode: {base, volume, overlay} for View.setShape / setBase and
 * View.setOverlay (volume and overlay null when nothing needs one); `painted` (a Set) for the ROI pane, null
 * for a tile.
 */
async function coloursFor(shape, mesh, painted) {
  let variance = null;
  if (state.colourMode === 'variance') variance = await api.getVariance(shape);
  let highlight = null;
  // Results show the correspondence to the regions in blue; the ROI pane shows the regions themselves.
  if (!painted && state.query) {
    const detail = await detailFor(shape);
    if (detail) highlight = detail.highlight;
  }
  const base = baseColours(mesh, state.colourMode === 'parts');
  // The voxel grid is computed only for shapes that need an overlay: the first page shows plain shapes.
  if (!painted && !highlight && !variance) return { base, volume: null, overlay: null };
  const volume = volumeOf(mesh);
  return { base, volume, overlay: overlayBytes(volume, { mode: state.colourMode, variance, highlight, painted }) };
}

/** The model matrix and orbit centre of `shape` for the current alignment mode. */
async function alignmentFor(shape) {
  if (state.alignMode === 'canonical') {
    const canonical = await api.getCanonical();
    return { transform: canonical.transforms[shape], centre: null };
  }
  if (state.alignMode === 'region' && state.query) {
    const detail = await detailFor(shape);
    if (detail) return { transform: detail.transform, centre: detail.centre };
  }
  return { transform: null, centre: null };
}

/**
 * The last query's details for `shape`, fetched in batches: requestDetails() asks for a whole page at once
 * and this only waits for the answer; a shape nobody asked for yet gets a request of its own.
 */
function detailFor(shape) {
  const query = state.query;
  if (!query) return Promise.resolve(null);
  if (!query.details.has(shape)) requestDetails([shape]);
  return query.details.get(shape);
}

function requestDetails(shapes) {
  const query = state.query;
  const missing = [...new Set(shapes)].filter((s) => !query.details.has(s));
  if (!missing.length) return;
  const batch = api.postDetails(query.regions, missing).then((answer) => {
    const byShape = new Map(answer.details.map((d) => [d.shape, d]));
    return byShape;
  });
  for (const s of missing) {
    const promise = batch.then((byShape) => byShape.get(s) ?? null);
    // A failed batch is forgotten, so that the next page or mode change asks again.
    promise.catch(() => query.details.delete(s));
    query.details.set(s, promise);
  }
}

/**
 * (Re)draws one results tile: mesh, colours, alignment. Only the latest call for a tile applies its answer:
 * a slow one (a variance fetch) must not overwrite what a later mode change or page drew.
 */
async function updateTile(tile) {
  const shape = tile.shape;
  if (shape === null) return;
  const token = ++tile.token;
  const mesh = await api.getMesh(shape);
  const [colours, alignment] = await Promise.all([coloursFor(shape, mesh, null), alignmentFor(shape)]);
  if (token !== tile.token) return;
  if (tile.view.shapeData !== mesh) tile.view.setShape(mesh, colours.base);
  else tile.view.setBase(colours.base);
  tile.view.setOverlay(colours.volume, colours.overlay);
  tile.view.setTransform(alignment.transform, alignment.centre);
  renderer.requestRender(tile.view);
}

async function loadExample(example) {
  const mesh = await api.getMesh(example.shape);
  await colourExample(example, mesh);
  updateResultsCaptions();
  updateStatus();
}

async function colourExample(example, mesh = example.mesh) {
  if (!mesh) return;
  const revision = ++example.revision;
  const [colours, alignment] = await Promise.all([coloursFor(example.shape, mesh, example.selected),
    alignmentFor(example.shape)]);
  // Removed meanwhile, or a later call (the next brush dab, a mode change) has drawn it already.
  if (!roi.examples.includes(example) || revision !== example.revision) return;
  if (example.view.shapeData !== mesh) {
    example.view.setShape(mesh, colours.base);
    example.meshReady(mesh);
  } else {
    example.view.setBase(colours.base);
  }
  example.view.setOverlay(colours.volume, colours.overlay);
  example.view.setTransform(alignment.transform, alignment.centre);
  renderer.requestRender(example.view);
}

// ---------------------------------------------------------------------------------------------------------
// Pages

const pageCount = () => Math.max(1, Math.ceil(state.order.length / state.collection.page_size));

function pageShapes() {
  const size = state.collection.page_size;
  return state.order.slice(state.page * size, (state.page + 1) * size);
}

function captionData() {
  const shapes = state.collection.shapes;
  return {
    names: shapes.map((s) => s.name),
    clusters: shapes.map((s) => s.cluster),
    distances: state.query ? state.query.distance : null,
    examples: new Set(roi.examples.map((e) => e.shape)),
  };
}

function updateResultsCaptions() {
  results.assign(pageShapes(), captionData());
}

/** Shows the current page: only its shapes are fetched (cached), which is what scales to 1,000 shapes. */
async function showPage() {
  const shapes = pageShapes();
  $('#page-label').textContent = `page ${state.page + 1} of ${pageCount()}`;
  $('[data-testid=prev-page]').disabled = state.page === 0;
  $('[data-testid=next-page]').disabled = state.page >= pageCount() - 1;
  if (state.query) requestDetails([...shapes, ...roi.examples.map((e) => e.shape)]);
  results.assign(shapes, captionData());
  await Promise.all(results.tiles.map(updateTile));
  await renderer.nextFrame();
  updateStatus();
}

/** Redraws everything after a mode change (colours, alignment). */
async function refreshAll() {
  if (state.query) requestDetails([...pageShapes(), ...roi.examples.map((e) => e.shape)]);
  await Promise.all([...results.tiles.map(updateTile), ...roi.examples.map((e) => colourExample(e))]);
  await renderer.nextFrame();
}

function goToPage(page) {
  state.page = Math.min(pageCount() - 1, Math.max(0, page));
  showPage().catch(showError);
}

// ---------------------------------------------------------------------------------------------------------
// Actions

function addExample(shape) {
  const name = state.collection.shapes[shape].name;
  roi.add(shape, name);
  $('#roi-empty').hidden = true;
}

async function sort() {
  const regions = roi.regions();
  if (!regions.length) {
    showError(new UserError('Paint a region on an example first: add one with "use as example", then drag on it.'));
    return;
  }
  clearError();
  const started = performance.now();
  setBusy(true);
  try {
    const answer = await api.postQuery(regions);
    const roundTrip = performance.now() - started;
    state.query = {
      regions,
      order: answer.order,
      distance: new Map(answer.order.map((shape, k) => [shape, answer.distance[k]])),
      details: new Map(),
      seconds: answer.seconds,
    };
    state.order = answer.order.slice();
    state.page = 0;
    timings.lastQueryMs = roundTrip;
    timings.lastQuerySeconds = answer.seconds;
    clearError();
    // The new first page and the examples (whose region alignment follows the new query); showPage asks for
    // the details of both in one request.
    await Promise.all([showPage(), ...roi.examples.map((e) => colourExample(e))]);
    timings.lastSortMs = performance.now() - started;
  } catch (err) {
    showError(err);
  } finally {
    setBusy(false);
    updateStatus();
  }
}

function setColourMode(mode) {
  state.colourMode = state.colourMode === mode ? 'plain' : mode;
  $('[data-testid=variance]').setAttribute('aria-pressed', String(state.colourMode === 'variance'));
  $('[data-testid=parts]').setAttribute('aria-pressed', String(state.colourMode === 'parts'));
  updateLegend();
  refreshAll().catch(showError);
}

function setAlignMode(mode) {
  if (mode === 'region' && !state.query) {
    showError(new UserError('Align to region needs a sort first: paint a region and press Sort.'));
    return;
  }
  state.alignMode = mode;
  for (const m of ['original', 'canonical', 'region']) {
    $(`[data-testid=align-${m}]`).setAttribute('aria-pressed', String(m === mode));
  }
  // A new alignment puts the shapes in new places: frame them afresh.
  results.orbit.panX = 0;
  results.orbit.panY = 0;
  clearError();
  refreshAll().catch(showError);
}

function toggle(button) {
  button.setAttribute('aria-pressed', String(button.getAttribute('aria-pressed') !== 'true'));
}

// ---------------------------------------------------------------------------------------------------------
// Status line, legend, errors

function setBusy(busy) {
  $('[data-testid=sort]').disabled = busy;
  document.body.classList.toggle('busy', busy);
}

function updateStatus() {
  if (!state.collection) return;
  const c = state.collection;
  const painted = roi.examples.reduce((n, e) => n + e.selected.size, 0);
  const facets = roi.regions().length;
  const parts = [
    `${c.shape_count} shapes (${c.mode})`,
    `${roi.examples.length} example${roi.examples.length === 1 ? '' : 's'}, ${painted} samples painted` +
      (facets > 1 ? ` in ${facets} regions` : ''),
  ];
  if (state.query) {
    parts.push(`sorted by ${state.query.regions.length} region${state.query.regions.length === 1 ? '' : 's'}` +
      ` - query ${formatSeconds(state.query.seconds)} on the server, ${Math.round(timings.lastQueryMs)} ms round trip`);
  } else {
    parts.push('collection order');
  }
  $('#status-text').textContent = parts.join('  ·  ');
}

function showError(err) {
  const status = err instanceof api.ApiError ? ` (HTTP ${err.status})` : '';
  state.error = `${err.message}${status}`;
  const el = $('[data-testid=error]');
  el.textContent = state.error;
  el.hidden = false;
  if (!(err instanceof UserError)) console.error(err);
}

function clearError() {
  state.error = null;
  $('[data-testid=error]').hidden = true;
}

function updateLegend() {
  const legend = $('#legend');
  legend.replaceChildren();
  if (state.colourMode === 'variance') {
    const stops = [0, 0.25, 0.5, 0.75, 1].map(varianceCss);
    legend.innerHTML = `<span>low variance</span>
      <span class="ramp" style="background: linear-gradient(90deg, ${stops.join(', ')})"></span><span>high</span>`;
  } else if (state.colourMode === 'parts') {
    state.collection.label_names.forEach((name, label) => {
      const item = document.createElement('span');
      item.className = 'swatch';
      item.style.setProperty('--swatch', partCss(label));
      item.textContent = name;
      legend.appendChild(item);
    });
  }
  legend.hidden = legend.childElementCount === 0;
}

// ---------------------------------------------------------------------------------------------------------
// Wiring and start

function wire() {
  $('[data-testid=sort]').addEventListener('click', () => sort());
  $('[data-testid=variance]').addEventListener('click', () => setColourMode('variance'));
  $('[data-testid=parts]').addEventListener('click', () => setColourMode('parts'));
  for (const m of ['original', 'canonical', 'region']) {
    $(`[data-testid=align-${m}]`).addEventListener('click', () => setAlignMode(m));
  }
  $('[data-testid=erase]').addEventListener('click', (e) => toggle(e.currentTarget));
  $('[data-testid=rotate]').addEventListener('click', (e) => {
    toggle(e.currentTarget);
    document.body.classList.toggle('rotate-mode', e.currentTarget.getAttribute('aria-pressed') === 'true');
  });
  $('#brush').addEventListener('input', () => {
    $('#brush-value').textContent = `${$('#brush').value}%`;
  });
  $('[data-testid=prev-page]').addEventListener('click', () => goToPage(state.page - 1));
  $('[data-testid=next-page]').addEventListener('click', () => goToPage(state.page + 1));
  $('[data-testid=error]').addEventListener('click', clearError);
  window.addEventListener('resize', () => renderer.requestRender());
  // Views drawn alone (a brush dab) assume nothing moved; a pane that changes size moves its views.
  new ResizeObserver(() => renderer.requestRender()).observe($('#roi-scroll'));
  new ResizeObserver(() => renderer.requestRender()).observe($('#examples'));
  for (const pane of [$('#results-scroll'), $('#roi-scroll')]) {
    pane.addEventListener('scroll', () => renderer.requestRender(), { passive: true });
  }
}

async function start() {
  wire();
  try {
    state.collection = await collectionRequest;
  } catch (err) {
    showError(err);
    return;
  }
  const c = state.collection;
  state.order = c.shapes.map((s) => s.index);
  $('[data-testid=parts]').hidden = !(c.label_names && c.label_names.length);
  results.setPageSize(c.page_size);
  updateStatus();
  try {
    await showPage();
    timings.firstRenderMs = performance.now();  // ms since navigation start
    explorer.ready = true;
  } catch (err) {
    showError(err);
  }
}

// ---------------------------------------------------------------------------------------------------------
// Hooks for tests (and the console)

const explorer = {
  ready: false,
  timings,
  /** Page coordinates of a model-space point in example `slot`'s view; visible = not hidden by the surface. */
  projectToScreen(slot, point) {
    const example = roi.examples[slot];
    if (!example) throw new Error(`no example in slot ${slot}`);
    return example.view.project(point);
  },
  ranking: () => state.order.slice(),
  lastFrameMs: () => renderer.lastFrameMs,
  regionSamples(slot) {
    const example = roi.examples[slot];
    return example ? [...example.selected].sort((a, b) => a - b) : [];
  },
  examples: () => roi.examples.map((e) => e.shape),
  page: () => ({ page: state.page, pages: pageCount(), shapes: pageShapes() }),
  modes: () => ({ colour: state.colourMode, align: state.alignMode }),
  camera: () => ({ theta: results.orbit.theta, phi: results.orbit.phi, zoom: results.orbit.zoom }),
  error: () => state.error,
  /** Resolves when no request is in flight and the frame after that has been drawn. */
  async settled() {
    for (;;) {
      await api.whenNoRequests();
      await renderer.nextFrame();
      // Answers arriving during the frame may have queued more work (a colour after a mesh): wait again.
      await new Promise((resolve) => setTimeout(resolve, 30));
      if (api.requestsPending() === 0 && !renderer.scheduled) return;
    }
  },
};
window.explorer = explorer;

start();
