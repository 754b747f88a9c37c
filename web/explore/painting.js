// SPDX-License-Identifier: MIT
// painting.js: what colour each point of a shape gets (plain, parts, painted region, highlight, variance)
// and which samples a brush stroke touches. Pure functions over the typed arrays of api.getMesh: no three.js.
//
// Colour comes in two layers. The base layer is per triangle (plain grey, or the part colour of the face's
// label) and goes into vertex colours of an unindexed copy of the mesh. Everything that is defined per
// sample - the painted region, the blue highlight, the variance map - goes into an overlay: a small 3D
// texture around the shape, RGBA with alpha = how much the overlay covers the base. Per-sample fields cannot
// go on the vertices: the collections' meshes are often coarse (a generated chair has ~300 vertices for 128
// samples, a chair leg's side is two triangles), so vertex colours would smear one sample over a whole leg.
// The texture is looked up per pixel at the surface point's model coordinates (views.js), so the region's
// resolution is the voxel size whatever the triangles are.

/** sRGB byte triple from 0xRRGGBB. */
const bytes = (hex) => [(hex >> 16) & 255, (hex >> 8) & 255, hex & 255];
const toLinear = (b) => b.map((v) => {
  const c = v / 255;
  return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
});

const PLAIN = 0xc9ccd2;      // light neutral grey: shading reads well on the dark background
const PAINT = 0xff8a1f;      // the user's region: orange, as far from the highlight blue as possible
const HIGHLIGHT = 0x1f4fd8;  // "corresponding regions are highlighted in dark blue" (Fig. 4.17)

// Variance colour map, dark blue (low) to bright yellow (high), as in Fig. 4.18: stops of a perceptually
// ordered map (close to viridis), interpolated in sRGB.
const VARIANCE_STOPS = [0x1b1f6b, 0x2c4fa8, 0x21908d, 0x5ec962, 0xfde725].map(bytes);

// Part colours: a qualitative palette (Tableau 10), one per label index, repeating past ten.
const PART_COLOURS = [0x4e79a7, 0xf28e2b, 0xe15759, 0x76b7b2, 0x59a14f, 0xedc948, 0xb07aa1, 0xff9da7, 0x9c755f,
  0xbab0ac].map(bytes);

const css = ([r, g, b]) => `rgb(${Math.round(r)} ${Math.round(g)} ${Math.round(b)})`;

/** sRGB bytes of the variance colour map at t in [0, 1]. */
export function varianceColour(t) {
  const x = Math.min(1, Math.max(0, t)) * (VARIANCE_STOPS.length - 1);
  const i = Math.min(VARIANCE_STOPS.length - 2, Math.floor(x));
  const f = x - i;
  const a = VARIANCE_STOPS[i];
  const b = VARIANCE_STOPS[i + 1];
  return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
}

function partColour(label) {
  return label < 0 ? bytes(PLAIN) : PART_COLOURS[label % PART_COLOURS.length];
}

/** CSS colours for the legends. */
export const varianceCss = (t) => css(varianceColour(t));
export const partCss = (label) => css(partColour(label));

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

// ---------------------------------------------------------------------------------------------------------
// Base layer: one colour per triangle

/**
 * Linear RGB per vertex of the unindexed mesh (3 vertices per face, in face order): part colours when
 * `parts` and the mesh has face labels, else plain grey.
 */
export function baseColours(mesh, parts) {
  const faceCount = mesh.faces.length / 3;
  const out = new Float32Array(faceCount * 9);
  const plain = toLinear(bytes(PLAIN));
  const palette = new Map();
  for (let f = 0; f < faceCount; ++f) {
    let c = plain;
    if (parts && mesh.faceLabels) {
      const label = mesh.faceLabels[f];
      if (!palette.has(label)) palette.set(label, toLinear(partColour(label)));
      c = palette.get(label);
    }
    for (let k = 0; k < 3; ++k) out.set(c, 9 * f + 3 * k);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------
// Overlay: per-sample values on a voxel grid

const VOXELS_ALONG_LONGEST = 56;  // ~2% of the shape per voxel: finer than the samples' spacing (~8%)
const NEAR = 4;                   // samples blended per voxel

/**
 * The voxel grid of a shape: a one-voxel margin around its bounding box; per voxel centre its nearest sample
 * (what the painted region shows: the samples' cells, like vertex_sample on vertices) and Gaussian weights
 * over its 4 nearest samples (what smooth fields - highlight, variance - show; width = the samples'
 * typical spacing, so neighbouring cells blend without reaching across the shape).
 * Returns {origin, size, dims: [nx, ny, nz], ids (Int16Array, NEAR per voxel), weights (Float32Array)}.
 */
export function sampleVolume(mesh) {
  const { min, max } = bounds(mesh.positions);
  const longest = Math.max(max[0] - min[0], max[1] - min[1], max[2] - min[2]) || 1;
  const size = longest / VOXELS_ALONG_LONGEST;
  const dims = [0, 1, 2].map((k) => Math.ceil((max[k] - min[k]) / size) + 2);
  const origin = [0, 1, 2].map((k) => min[k] - size);
  const S = mesh.samples;
  const K = S.length / 3;
  const n = Math.min(NEAR, K);

  let spacing = 0;
  for (let a = 0; a < K; ++a) {
    let best = Infinity;
    for (let b = 0; b < K; ++b) {
      if (a !== b) best = Math.min(best, (S[3 * a] - S[3 * b]) ** 2 + (S[3 * a + 1] - S[3 * b + 1]) ** 2 + (S[3 * a + 2] - S[3 * b + 2]) ** 2);
    }
    if (Number.isFinite(best)) spacing += Math.sqrt(best);
  }
  spacing = K > 1 ? spacing / K : longest / 10;
  const inv2s2 = 1 / (2 * spacing * spacing);

  const count = dims[0] * dims[1] * dims[2];
  const surface = surfaceVoxels(mesh, origin, size, dims);
  const ids = new Int16Array(count * NEAR).fill(-1);
  const weights = new Float32Array(count * NEAR);
  const bestD = new Float64Array(n);
  const bestI = new Int32Array(n);
  let voxel = 0;
  for (let z = 0; z < dims[2]; ++z) {
    const pz = origin[2] + (z + 0.5) * size;
    for (let y = 0; y < dims[1]; ++y) {
      const py = origin[1] + (y + 0.5) * size;
      for (let x = 0; x < dims[0]; ++x, ++voxel) {
        if (!surface[voxel]) continue;
        const px = origin[0] + (x + 0.5) * size;
        bestD.fill(Infinity);
        for (let s = 0; s < K; ++s) {
          const dx = S[3 * s] - px;
          const dy = S[3 * s + 1] - py;
          const dz = S[3 * s + 2] - pz;
          const d = dx * dx + dy * dy + dz * dz;
          if (d >= bestD[n - 1]) continue;
          let j = n - 1;
          while (j > 0 && bestD[j - 1] > d) {
            bestD[j] = bestD[j - 1];
            bestI[j] = bestI[j - 1];
            --j;
          }
          bestD[j] = d;
          bestI[j] = s;
        }
        let sum = 0;
        for (let j = 0; j < n; ++j) {
          const w = Math.exp(-(bestD[j] - bestD[0]) * inv2s2);  // relative to the nearest: no underflow far out
          ids[NEAR * voxel + j] = bestI[j];
          weights[NEAR * voxel + j] = w;
          sum += w;
        }
        for (let j = 0; j < n; ++j) weights[NEAR * voxel + j] /= sum;
      }
    }
  }
  return { origin, size, dims, ids, weights };
}

/**
 * Marks the voxels that a lookup on the surface can touch: with linear filtering, the 8 voxels around each
 * surface point. Only these need their nearest samples - about a tenth of the grid for a chair. The surface
 * is walked at half the voxel size so no voxel is skipped.
 */
function surfaceVoxels(mesh, origin, size, dims) {
  const { positions: P, faces: F } = mesh;
  const mark = new Uint8Array(dims[0] * dims[1] * dims[2]);
  const step = size / 2;
  const cell = [0, 0, 0];
  for (let f = 0; f < F.length; f += 3) {
    const a = 3 * F[f];
    const b = 3 * F[f + 1];
    const c = 3 * F[f + 2];
    const longest = Math.sqrt(Math.max(
      (P[a] - P[b]) ** 2 + (P[a + 1] - P[b + 1]) ** 2 + (P[a + 2] - P[b + 2]) ** 2,
      (P[b] - P[c]) ** 2 + (P[b + 1] - P[c + 1]) ** 2 + (P[b + 2] - P[c + 2]) ** 2,
      (P[c] - P[a]) ** 2 + (P[c + 1] - P[a + 1]) ** 2 + (P[c + 2] - P[a + 2]) ** 2));
    const n = Math.max(1, Math.ceil(longest / step));
    for (let i = 0; i <= n; ++i) {
      for (let j = 0; i + j <= n; ++j) {
        const u = i / n;
        const v = j / n;
        for (let k = 0; k < 3; ++k) {
          const p = P[a + k] + (P[b + k] - P[a + k]) * u + (P[c + k] - P[a + k]) * v;
          cell[k] = Math.floor((p - origin[k]) / size - 0.5);  // texel centres sit at (i + 0.5) * size
        }
        for (let dz = 0; dz < 2; ++dz) {
          const z = Math.min(dims[2] - 1, Math.max(0, cell[2] + dz));
          for (let dy = 0; dy < 2; ++dy) {
            const y = Math.min(dims[1] - 1, Math.max(0, cell[1] + dy));
            for (let dx = 0; dx < 2; ++dx) {
              const x = Math.min(dims[0] - 1, Math.max(0, cell[0] + dx));
              mark[(z * dims[1] + y) * dims[0] + x] = 1;
            }
          }
        }
      }
    }
  }
  return mark;
}

/**
 * The overlay's RGBA bytes (sRGB colour, alpha = coverage) for one view.
 *   mode: 'plain' | 'variance' | 'parts'; variance: per-sample values or null (not loaded: no overlay);
 *   highlight: per-sample values in [0, 1] or null; painted: Set of sample indices or null.
 * The painted region is drawn in every mode: the user must always see what they selected. The blue
 * highlight is drawn over the plain and parts colourings; in variance mode it would hide the variance map,
 * which is what the researcher asked to see, so it is left out there.
 */
export function overlayBytes(volume, { mode, variance, highlight, painted }, out = null) {
  const count = volume.ids.length / NEAR;
  const rgba = out ?? new Uint8Array(count * 4);
  const paint = bytes(PAINT);
  const blue = bytes(HIGHLIGHT);
  const field = (values, voxel) => {
    let acc = 0;
    for (let j = 0; j < NEAR; ++j) {
      const s = volume.ids[NEAR * voxel + j];
      if (s >= 0) acc += volume.weights[NEAR * voxel + j] * (values[s] ?? 0);
    }
    return acc;
  };
  const showVariance = mode === 'variance' && variance;
  const showHighlight = mode !== 'variance' && highlight;
  // Where the overlay is off, its colour is the plain grey: linear filtering then fades a painted border
  // into grey rather than into some unrelated hue.
  const none = showHighlight ? blue : bytes(PLAIN);
  for (let v = 0; v < count; ++v) {
    let c = none;
    let a = 0;
    if (painted && painted.has(volume.ids[NEAR * v])) {
      c = paint;
      a = 1;
    } else if (showVariance) {
      c = varianceColour(field(variance, v));
      a = 1;
    } else if (showHighlight) {
      a = Math.min(1, Math.max(0, field(highlight, v)));
    }
    rgba[4 * v] = c[0];
    rgba[4 * v + 1] = c[1];
    rgba[4 * v + 2] = c[2];
    rgba[4 * v + 3] = Math.round(255 * a);
  }
  return rgba;
}

// ---------------------------------------------------------------------------------------------------------
// Brush

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
    if (erase) {
      changed = selected.delete(s) || changed;
    } else if (!selected.has(s)) {
      selected.add(s);
      changed = true;
    }
  }
  return changed;
}
