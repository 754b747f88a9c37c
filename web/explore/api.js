// SPDX-License-Identifier: MIT
// api.js: the JSON API of `shapestruct explore` (see API.md), with per-shape caches.
//
// Meshes and variance are fetched lazily and cached by shape index: a results page only ever asks for its own
// shapes, which is what keeps a 1,000-shape collection cheap (level of detail = "only what is on screen").
// Each cache holds the promise, not the value, so two views asking for the same shape share one request.

/** An API answer with an HTTP error status; `message` is the server's human-readable `error` field. */
export class ApiError extends Error {
  constructor(status, message, path) {
    super(message);
    this.status = status;
    this.path = path;
  }
}

/** Requests in flight: the page waits for zero before it calls itself settled (tests and screenshots). */
let pending = 0;
const idleWaiters = [];

export function requestsPending() {
  return pending;
}

/** Resolves once no request is in flight. */
export function whenNoRequests() {
  if (pending === 0) return Promise.resolve();
  return new Promise((resolve) => idleWaiters.push(resolve));
}

async function request(path, options = {}) {
  pending += 1;
  try {
    const response = await fetch(path, options);
    const text = await response.text();
    let body = null;
    try {
      body = text ? JSON.parse(text) : null;
    } catch {
      // A non-JSON body (e.g. a proxy's error page) still gets reported with its status below.
    }
    if (!response.ok) {
      const message = body && typeof body.error === 'string' ? body.error : `${response.status} ${response.statusText}`;
      throw new ApiError(response.status, message, path);
    }
    if (body === null) throw new ApiError(response.status, 'the server sent no JSON', path);
    return body;
  } finally {
    pending -= 1;
    if (pending === 0) idleWaiters.splice(0).forEach((resolve) => resolve());
  }
}

function post(path, payload) {
  return request(path, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify(payload),
  });
}

/** A Map of promises that forgets failures, so a later view can retry a shape whose fetch failed. */
function cachedFetcher(makePath, convert) {
  const cache = new Map();
  return (index) => {
    if (!cache.has(index)) {
      const promise = request(makePath(index)).then(convert);
      promise.catch(() => cache.delete(index));
      cache.set(index, promise);
    }
    return cache.get(index);
  };
}

export const getCollection = () => request('api/collection');

export const getCanonical = (() => {
  let promise = null;
  return () => {
    if (!promise) {
      promise = request('api/canonical');
      promise.catch(() => (promise = null));
    }
    return promise;
  };
})();

/** The mesh as typed arrays (what three.js buffers want), converted once per shape. */
export const getMesh = cachedFetcher(
  (i) => `api/shape/${i}/mesh`,
  (m) => ({
    index: m.index,
    name: m.name,
    positions: Float32Array.from(m.positions),
    faces: Uint32Array.from(m.faces),
    vertexSample: Int32Array.from(m.vertex_sample),
    samples: Float32Array.from(m.samples),
    faceLabels: m.face_labels ? Int32Array.from(m.face_labels) : null,
  }),
);

export const getVariance = cachedFetcher(
  (i) => `api/shape/${i}/variance`,
  (v) => Float32Array.from(v.values),
);

/** regions: [{shape, samples: [...]}, ...] */
export const postQuery = (regions) => post('api/query', { regions });

export const postDetails = (regions, shapes) => post('api/details', { regions, shapes });
