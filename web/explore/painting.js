// SPDX-License-Identifier: MIT
// painting.js: what colour each vertex gets (plain, painted region, highlight, variance, parts) and which
// samples a brush stroke touches. Pure functions over the typed arrays of api.getMesh: no three.js here.

// Colours are linear RGB in [0, 1] (three.js vertex colours are linear; the renderer converts to sRGB).
const srgb = (hex) => {
  const c = [(hex >> 16) & 255, (hex >> 8) & 255, hex & 255].map((v) => v / 255);
  return c.map((v) => (v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4));
};

export const PLAIN = srgb(0xc9ccd2);      // light neutral grey: shading reads well on the dark background
export const PAINT = srgb(0xff8a1f);      // the user's region: orange, as far from the highlight blue as possible
export const HIGHLIGHT = srgb(0x1f4fd8);  // "corresponding regions are highlighted in dark blue" (Fig. 4.17)

// Variance colour map, dark blue (low) to bright yellow (high), as in Fig. 4.18: a few stops of a
// perceptually ordered map (close to viridis), interpolated linearly.
const VARIANCE_STOPS = [0x1b1f6b, 0x2c4fa8, 0x21908d, 0x5ec962, 0xfde725].map(srgb);

// Part colours: a qualitative palette (Tableau 10), one per label index, repeating past ten.
const PART_COLOURS = [0x4e79a7, 0xf28e2b, 0xe15759, 0x76b7b2, 0x59a14f, 0xedc948, 0xb07aa1, 0xff9da7, 0x9c755f,
  0xbab0ac].map(srgb);

/** A linear colour as a CSS colour (sRGB), for legends. */
export function cssColour(linear) {
  const [r, g, b] = linear.map((v) => Math.round(255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * v ** (1 / 2.4) - 0.055)));
  return `rgb(${r} ${g} ${b})`;
}

export function partColour(label) {
  return label < 0 ? PLAIN : PART_COLOURS[label % PART_COLOURS.length];
}

export function varianceColour(t) {
  const x = Math.min(1, Math.max(0, t)) * (VARIANCE_STOPS.length - 1);
  const i = Math.min(VARIANCE_STOPS.length - 2, Math.floor(x));
  const f = x - i;
  const a = VARIANCE_STOPS[i];
  const b = VARIANCE_STOPS[i + 1];
  return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
}

function mix(a, b, t) {
  return [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t];
}

/** Axis-aligned bounds of the vertices: {min, max, centre, diagonal}. */
export function bounds(positions) {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let v = 0; v < positions.length; v += 3) {
    for (let k = 0; k < 3; ++k) {
      min[k] = Math.min(min[k], positions[v + k]);
      max[k] = Math.max(max[k], positions[v + k]);
    }
  }
  const centre = [0, 1, 2].map((k) => (min[k] + max[k]) / 2);
  const diagonal = Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
  return { min, max, centre, diagonal };
}

/**
 * Per-vertex blending weights over the few nearest samples, for smooth per-sample fields (highlight,
 * variance). With nearest-sample colouring alone, 128 samples on a chair give a visible patchwork; a Gaussian
 * over the 4 nearest samples with the sample spacing as width blends patches without reaching across the
 * shape. The nearest sample (vertex_sample) always takes part, so a vertex never loses its own sample.
 * Returns {ids: Int32Array(V*4), weights: Float32Array(V*4)}.
 */
export function sampleBlend(mesh) {
  const { positions, samples, vertexSample } = mesh;
  const V = positions.length / 3;
  const K = samples.length / 3;
  const NEAR = Math.min(4, K);
  // Typical sample spacing: mean distance from a sample to its nearest other sample.
  let spacing = 0;
  for (let a = 0; a < K; ++a) {
    let best = Infinity;
    for (let b = 0; b < K; ++b) {
      if (a === b) continue;
      const d = Math.hypot(samples[3 * a] - samples[3 * b], samples[3 * a + 1] - samples[3 * b + 1],
        samples[3 * a + 2] - samples[3 * b + 2]);
      best = Math.min(best, d);
    }
    if (Number.isFinite(best)) spacing += best;
  }
  spacing = K > 1 ? spacing / K : 1;
  const inv2s2 = 1 / (2 * spacing * spacing || 1);

  const ids = new Int32Array(V * 4).fill(-1);
  const weights = new Float32Array(V * 4);
  const bestD = new Float64Array(NEAR);
  const bestI = new Int32Array(NEAR);
  for (let v = 0; v < V; ++v) {
    const x = positions[3 * v];
    const y = positions[3 * v + 1];
    const z = positions[3 * v + 2];
    bestD.fill(Infinity);
    bestI.fill(-1);
    for (let s = 0; s < K; ++s) {
      const dx = samples[3 * s] - x;
      const dy = samples[3 * s + 1] - y;
      const dz = samples[3 * s + 2] - z;
      const d = dx * dx + dy * dy + dz * dz;
      if (d >= bestD[NEAR - 1]) continue;
      let j = NEAR - 1;
      while (j > 0 && bestD[j - 1] > d) {
        bestD[j] = bestD[j - 1];
        bestI[j] = bestI[j - 1];
        --j;
      }
      bestD[j] = d;
      bestI[j] = s;
    }
    const own = vertexSample[v];
    if (own >= 0 && !bestI.includes(own)) bestI[NEAR - 1] = own;
    let sum = 0;
    for (let j = 0; j < NEAR; ++j) {
      const s = bestI[j];
      if (s < 0) continue;
      const dx = samples[3 * s] - x;
      const dy = samples[3 * s + 1] - y;
      const dz = samples[3 * s + 2] - z;
      const w = Math.exp(-(dx * dx + dy * dy + dz * dz) * inv2s2) + (s === own ? 1e-6 : 0);
      ids[4 * v + j] = s;
      weights[4 * v + j] = w;
      sum += w;
    }
    for (let j = 0; j < NEAR; ++j) weights[4 * v + j] /= sum || 1;
  }
  return { ids, weights };
}

/** A per-sample field (K values) smoothed onto the vertices with sampleBlend's weights. */
export function fieldAtVertices(blend, values) {
  const V = blend.ids.length / 4;
  const out = new Float32Array(V);
  for (let v = 0; v < V; ++v) {
    let acc = 0;
    for (let j = 0; j < 4; ++j) {
      const s = blend.ids[4 * v + j];
      if (s >= 0) acc += blend.weights[4 * v + j] * (values[s] ?? 0);
    }
    out[v] = acc;
  }
  return out;
}

/**
 * Vertex colours (Float32Array, 3 per vertex) for one view.
 *   mode: 'plain' | 'variance' | 'parts'; variance: per-vertex values or null (not loaded yet -> plain);
 *   highlight: per-vertex values in [0, 1] or null; painted: Set of sample indices or null.
 * The painted region is drawn over every mode: the user must always see what they selected. The blue
 * highlight is drawn over the plain and parts colourings; in variance mode it would hide the variance map,
 * which is what the researcher asked to see, so it is left out there.
 */
export function vertexColours(mesh, { mode, variance, highlight, painted }) {
  const V = mesh.positions.length / 3;
  const out = new Float32Array(V * 3);
  const faceLabels = mode === 'parts' ? mesh.faceLabels : null;
  const vertexLabel = faceLabels ? labelsAtVertices(mesh) : null;
  for (let v = 0; v < V; ++v) {
    let c = PLAIN;
    if (mode === 'variance' && variance) c = varianceColour(variance[v]);
    else if (vertexLabel) c = partColour(vertexLabel[v]);
    if (highlight && mode !== 'variance') c = mix(c, HIGHLIGHT, Math.min(1, Math.max(0, highlight[v])));
    if (painted && painted.has(mesh.vertexSample[v])) c = PAINT;
    out[3 * v] = c[0];
    out[3 * v + 1] = c[1];
    out[3 * v + 2] = c[2];
  }
  return out;
}

// Face labels are per triangle; a vertex takes the label of the last face that uses it. The meshes are part
// soups (parts do not share vertices), so this is exact except on meshes that weld parts together.
const vertexLabelCache = new WeakMap();
function labelsAtVertices(mesh) {
  if (!vertexLabelCache.has(mesh)) {
    const labels = new Int32Array(mesh.positions.length / 3).fill(-1);
    for (let f = 0; f < mesh.faceLabels.length; ++f) {
      for (let k = 0; k < 3; ++k) labels[mesh.faces[3 * f + k]] = mesh.faceLabels[f];
    }
    vertexLabelCache.set(mesh, labels);
  }
  return vertexLabelCache.get(mesh);
}

/**
 * One brush dab: adds (or, erasing, removes) every sample within `radius` of `point` (model coordinates)
 * to the Set `selected`. Returns whether the set changed.
 */
export function brush(mesh, selected, point, radius, erase) {
  const { samples } = mesh;
  const r2 = radius * radius;
  let changed = false;
  for (let s = 0; s < samples.length / 3; ++s) {
    const dx = samples[3 * s] - point[0];
    const dy = samples[3 * s + 1] - point[1];
    const dz = samples[3 * s + 2] - point[2];
    if (dx * dx + dy * dy + dz * dz > r2) continue;
    if (erase ? selected.delete(s) : !selected.has(s)) {
      if (!erase) selected.add(s);
      changed = true;
    }
  }
  return changed;
}
