// SPDX-License-Identifier: MIT
// views.js: many 3D views drawn by ONE WebGL renderer into ONE full-window canvas.
//
// Each view is an HTML element (a results tile or an example's card) that the canvas, lying behind the page,
// shows through; every frame the renderer sets viewport and scissor to each element's rectangle and draws
// that view's scene (three.js's "multiple elements" pattern). One GL context for 24+ views is what keeps a
// page of results cheap: browsers cap the number of contexts at about 16 and each costs its own buffers.
// Frames are drawn on demand only (after an input, a fetch or a resize), never in a loop, so an idle page
// costs nothing - software WebGL (SwiftShader, headless machines) included.

import * as THREE from 'three';

const FOV = 30;  // degrees; a long lens keeps the perspective distortion between neighbouring tiles small

/**
 * Camera parameters shared by every view attached to it: spherical angles about +y (the collection's up
 * axis), a zoom factor over the distance that frames the shape, and a pan in units of the shape's radius.
 * Distances and pans are relative to each view's own shape so that one drag moves every tile the same way
 * while each keeps its shape framed, orbiting about its own centre.
 */
export class OrbitState {
  constructor({ theta = Math.PI + 0.65, phi = 1.15, zoom = 1, panX = 0, panY = 0 } = {}) {
    this.initial = { theta, phi, zoom, panX, panY };
    this.reset();
  }

  reset() {
    Object.assign(this, this.initial);
  }

  rotate(dx, dy) {
    this.theta -= dx * 0.01;
    // Stay off the poles, where the up vector and the view direction coincide and lookAt flips.
    this.phi = Math.min(Math.PI - 0.05, Math.max(0.05, this.phi - dy * 0.01));
  }

  pan(dx, dy, viewHeight) {
    const scale = (2 * this.zoom) / Math.max(1, viewHeight);
    this.panX -= dx * scale;
    this.panY += dy * scale;
  }

  dolly(wheelDelta) {
    this.zoom = Math.min(8, Math.max(0.15, this.zoom * Math.exp(wheelDelta * 0.001)));
  }
}

// The per-pixel overlay (painting.js): an RGBA 3D texture over the shape's box, sRGB colour with alpha =
// coverage, mixed over the base colour at the surface point's model coordinates.
const OVERLAY_GLSL = `
uniform highp sampler3D overlayMap;
uniform vec3 overlayOrigin;
uniform vec3 overlayScale;
varying vec3 vOverlayPos;
void applyOverlay(inout vec3 colour) {
  vec4 o = texture(overlayMap, (vOverlayPos - overlayOrigin) * overlayScale);
  vec3 linear = mix(o.rgb / 12.92, pow((o.rgb + 0.055) / 1.055, vec3(2.4)), step(0.04045, o.rgb));
  colour = mix(colour, linear, o.a);
}`;

// A transparent 1x1x1 overlay, shared by every view that has none (no region, highlight or variance yet).
let empty = null;
function emptyOverlay() {
  if (!empty) {
    empty = new THREE.Data3DTexture(new Uint8Array(4), 1, 1, 1);
    empty.needsUpdate = true;
    empty.dispose = () => {};  // shared: never released by one view
  }
  return empty;
}

// Corner positions of the unindexed mesh, once per shape (shared by its views in both panes).
const corners = new WeakMap();
function cornerPositions(shapeData) {
  if (!corners.has(shapeData)) {
    const { positions, faces } = shapeData;
    const out = new Float32Array(faces.length * 3);
    for (let i = 0; i < faces.length; ++i) out.set(positions.subarray(3 * faces[i], 3 * faces[i] + 3), 3 * i);
    corners.set(shapeData, out);
  }
  return corners.get(shapeData);
}

/** One 3D view: a scene with at most one shape, lit from the camera, drawn into `element`'s rectangle. */
export class View {
  /**
   * element: where the view is drawn and receives input; clip: an ancestor whose visible rectangle bounds the
   * drawing (a scrolling pane); orbit: an OrbitState, possibly shared with other views.
   */
  constructor(element, { clip = null, orbit = new OrbitState(), background = 0x23262d } = {}) {
    this.element = element;
    this.clip = clip;
    this.orbit = orbit;
    this.background = new THREE.Color(background);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(FOV, 1, 0.01, 100);
    // Soft light: a sky/ground fill plus a key light that travels with the camera (so no side of the shape
    // ever turns black while orbiting) and a dim rim light from behind.
    this.scene.add(new THREE.HemisphereLight(0xf2f4ff, 0x3a3430, 1.6));
    const key = new THREE.DirectionalLight(0xffffff, 1.8);
    key.position.set(-0.6, 0.9, 1);
    const rim = new THREE.DirectionalLight(0xb8c8ff, 0.5);
    rim.position.set(0.8, 0.3, -1);
    this.camera.add(key, rim);
    this.scene.add(this.camera);
    this.mesh = null;
    this.shapeData = null;
    this.centreOverride = null;  // orbit centre given by the server (align to region), world coordinates
    this.frame = { centre: new THREE.Vector3(), radius: 1 };
  }

  /**
   * Shows `shapeData` (from api.getMesh) with `base` colours (linear RGB per corner of each face,
   * painting.baseColours) and no overlay; null clears the view.
   */
  setShape(shapeData, base = null) {
    if (this.mesh) {
      this.scene.remove(this.mesh);
      this.mesh.geometry.dispose();
      this.mesh.material.dispose();
      this.uniforms.overlayMap.value.dispose();
      this.mesh = null;
    }
    this.shapeData = shapeData;
    if (!shapeData) return;
    // Unindexed, so each face has its own corners and a part colour per face stays exact; the positions are
    // shared between the views of one shape. Each view has its own colours: the same shape is coloured
    // differently in the ROI pane and in the results.
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(cornerPositions(shapeData), 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(base.slice(), 3));
    geometry.computeBoundingSphere();
    geometry.computeBoundingBox();
    const uniforms = {
      overlayMap: { value: emptyOverlay() },
      overlayOrigin: { value: new THREE.Vector3() },
      overlayScale: { value: new THREE.Vector3(1, 1, 1) },
    };
    this.uniforms = uniforms;
    this.overlayDims = null;
    // Flat shading: the shapes are part soups with sharp creases, where averaged normals smear the shading.
    // Double-sided: soups are not closed and an affine alignment may mirror a shape.
    const material = new THREE.MeshStandardMaterial({
      vertexColors: true, flatShading: true, roughness: 0.75, metalness: 0, side: THREE.DoubleSide,
    });
    material.onBeforeCompile = (shader) => {
      Object.assign(shader.uniforms, uniforms);
      shader.vertexShader = `varying vec3 vOverlayPos;\n${shader.vertexShader}`.replace('#include <begin_vertex>',
        '#include <begin_vertex>\nvOverlayPos = position;');
      shader.fragmentShader = `${OVERLAY_GLSL}\n${shader.fragmentShader}`.replace('#include <color_fragment>',
        '#include <color_fragment>\napplyOverlay(diffuseColor.rgb);');
    };
    this.mesh = new THREE.Mesh(geometry, material);
    this.mesh.matrixAutoUpdate = false;
    this.scene.add(this.mesh);
    this.updateFrame();
  }

  /** New base colours for the shape shown (as setShape). */
  setBase(base) {
    if (!this.mesh) return;
    const attribute = this.mesh.geometry.getAttribute('color');
    attribute.array.set(base);
    attribute.needsUpdate = true;
  }

  /**
   * The per-sample overlay: `bytes` (RGBA per voxel, painting.overlayBytes) on `volume`'s grid
   * (painting.sampleVolume); null, null = none.
   */
  setOverlay(volume, bytes) {
    if (!this.mesh) return;
    const u = this.uniforms;
    if (!volume) {
      if (this.overlayDims) u.overlayMap.value.dispose();
      u.overlayMap.value = emptyOverlay();
      this.overlayDims = null;
      return;
    }
    if (this.overlayDims !== volume.dims) {
      if (this.overlayDims) u.overlayMap.value.dispose();
      const texture = new THREE.Data3DTexture(bytes.slice(), ...volume.dims);
      texture.format = THREE.RGBAFormat;
      texture.type = THREE.UnsignedByteType;
      texture.minFilter = THREE.LinearFilter;
      texture.magFilter = THREE.LinearFilter;
      texture.unpackAlignment = 1;
      texture.needsUpdate = true;
      u.overlayMap.value = texture;
      u.overlayOrigin.value.set(...volume.origin);
      u.overlayScale.value.set(...volume.dims.map((n) => 1 / (n * volume.size)));
      this.overlayDims = volume.dims;
    } else {
      u.overlayMap.value.image.data.set(bytes);
      u.overlayMap.value.needsUpdate = true;
    }
  }

  /** A 3x4 row-major affine matrix (API.md) as the mesh's model matrix; null = identity. */
  setTransform(rows, centre = null) {
    this.centreOverride = centre ? new THREE.Vector3(...centre) : null;
    if (!this.mesh) return;
    const m = new THREE.Matrix4();
    if (rows) {
      m.set(rows[0], rows[1], rows[2], rows[3], rows[4], rows[5], rows[6], rows[7], rows[8], rows[9], rows[10],
        rows[11], 0, 0, 0, 1);
    }
    this.mesh.matrix.copy(m);
    this.mesh.matrixWorldNeedsUpdate = true;
    this.mesh.updateMatrixWorld(true);
    this.updateFrame();
  }

  /** Orbit centre (bounding-box centre or the server's) and the radius about it that must stay in view. */
  updateFrame() {
    if (!this.mesh) return;
    // From the geometry alone: the ROI pane hangs a brush cursor under the mesh, which must not count.
    const box = this.mesh.geometry.boundingBox.clone().applyMatrix4(this.mesh.matrixWorld);
    const centre = this.centreOverride ? this.centreOverride.clone() : box.getCenter(new THREE.Vector3());
    const p = new THREE.Vector3();
    const positions = this.shapeData.positions;
    const world = this.mesh.matrixWorld;
    let r2 = 0;
    for (let v = 0; v < positions.length; v += 3) {
      p.set(positions[v], positions[v + 1], positions[v + 2]).applyMatrix4(world);
      r2 = Math.max(r2, p.distanceToSquared(centre));
    }
    const corners = [];
    for (const x of [box.min.x, box.max.x]) {
      for (const y of [box.min.y, box.max.y]) {
        for (const z of [box.min.z, box.max.z]) corners.push(new THREE.Vector3(x, y, z).sub(centre));
      }
    }
    this.frame = { centre, radius: Math.sqrt(r2) || 1, corners, fit: null };
  }

  /**
   * Camera distance that fits the bounding box, computed for the view direction at the time the shape was
   * framed and then kept: a distance recomputed every frame would make the shape swell and shrink while the
   * user orbits. The box fits tighter than the bounding sphere, which wastes much of a tall narrow view.
   */
  fitDistance(aspect, dir, right, up) {
    const f = this.frame;
    if (f.fit && Math.abs(f.fit.aspect - aspect) < 0.01 * aspect) return f.fit.distance;
    const tanV = Math.tan(THREE.MathUtils.degToRad(FOV / 2));
    const tanH = tanV * aspect;
    let distance = 0;
    for (const c of f.corners) {
      const z = c.dot(dir);
      distance = Math.max(distance, z + Math.abs(c.dot(right)) / tanH, z + Math.abs(c.dot(up)) / tanV);
    }
    // Never inside the bounding sphere (near plane), and a margin so the silhouette does not touch the edges.
    distance = Math.max(distance * 1.08, 1.2 * f.radius);
    f.fit = { aspect, distance };
    return distance;
  }

  /** Places the camera from the orbit state, framing the shape's sphere about its orbit centre. */
  updateCamera(aspect) {
    const { centre, radius } = this.frame;
    const o = this.orbit;
    this.camera.aspect = aspect;
    const dir = new THREE.Vector3(Math.sin(o.phi) * Math.sin(o.theta), Math.cos(o.phi),
      Math.sin(o.phi) * Math.cos(o.theta));
    const right = new THREE.Vector3(0, 1, 0).cross(dir).normalize();
    const up = dir.clone().cross(right).normalize();
    const distance = this.fitDistance(aspect, dir, right, up) * o.zoom;
    const target = centre.clone();
    // Pan in the camera's own right/up directions, scaled by the shape's radius.
    target.addScaledVector(right, o.panX * radius).addScaledVector(up, o.panY * radius);
    this.camera.position.copy(target).addScaledVector(dir, distance);
    this.camera.up.set(0, 1, 0);
    this.camera.lookAt(target);
    this.camera.near = Math.max(distance - 2 * radius, distance * 0.02);
    this.camera.far = distance + 2 * radius;
    this.camera.updateProjectionMatrix();
    this.camera.updateMatrixWorld(true);
  }

  /** The element's rectangle on the page and the part of it that is visible (inside `clip`), or null. */
  rectangles() {
    const rect = this.element.getBoundingClientRect();
    if (rect.width < 1 || rect.height < 1 || !this.element.isConnected) return null;
    let visible = { left: rect.left, top: rect.top, right: rect.right, bottom: rect.bottom };
    if (this.clip) {
      const c = this.clip.getBoundingClientRect();
      visible = {
        left: Math.max(visible.left, c.left), top: Math.max(visible.top, c.top),
        right: Math.min(visible.right, c.right), bottom: Math.min(visible.bottom, c.bottom),
      };
    }
    if (visible.right <= visible.left || visible.bottom <= visible.top) return null;
    return { rect, visible };
  }

  /** First hit of the ray through page point (x, y): {point (world), local (model coords), distance} or null. */
  pick(x, y) {
    const r = this.rectangles();
    if (!r || !this.mesh) return null;
    const { rect } = r;
    this.updateCamera(rect.width / rect.height);
    const ndc = new THREE.Vector2(((x - rect.left) / rect.width) * 2 - 1, -((y - rect.top) / rect.height) * 2 + 1);
    const raycaster = new THREE.Raycaster();
    raycaster.setFromCamera(ndc, this.camera);
    const hit = raycaster.intersectObject(this.mesh, false)[0];
    if (!hit) return null;
    return { point: hit.point, local: this.mesh.worldToLocal(hit.point.clone()), distance: hit.distance };
  }

  /** Page coordinates of a model-space point, and whether it is the first surface seen along its ray. */
  project(modelPoint) {
    const r = this.rectangles();
    if (!r || !this.mesh) return { x: NaN, y: NaN, visible: false };
    const { rect, visible: clipRect } = r;
    this.updateCamera(rect.width / rect.height);
    const world = new THREE.Vector3(...modelPoint).applyMatrix4(this.mesh.matrixWorld);
    const ndc = world.clone().project(this.camera);
    const x = rect.left + ((ndc.x + 1) / 2) * rect.width;
    const y = rect.top + ((1 - ndc.y) / 2) * rect.height;
    const inside = ndc.z > -1 && ndc.z < 1 && x >= clipRect.left && x < clipRect.right && y >= clipRect.top &&
      y < clipRect.bottom;
    if (!inside) return { x, y, visible: false };
    const hit = this.pick(x, y);
    // Visible when the first hit along the pixel's ray is the point itself; the tolerance (about 1% of the
    // shape's diagonal) absorbs the ray passing a hair beside a point that lies exactly on an edge.
    const tolerance = 0.02 * this.frame.radius;
    const depth = world.distanceTo(this.camera.position);
    return { x, y, visible: !!hit && Math.abs(hit.distance - depth) < tolerance };
  }
}

/**
 * The one renderer: owns the canvas and draws the registered views on demand. The drawing buffer is kept
 * between frames, so a change to one view (a brush dab, a tile whose mesh arrived) redraws that view alone;
 * anything that may move views around (layout, scrolling, a shared camera) redraws them all. With software
 * GL a full frame of 25 views costs a few hundred milliseconds, one view a few dozen.
 */
export class ViewRenderer {
  constructor(canvas) {
    this.canvas = canvas;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, alpha: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(2, window.devicePixelRatio || 1));
    this.renderer.setClearColor(0x000000, 0);
    this.views = new Set();
    this.dirty = new Set();
    this.everything = true;  // the next frame redraws every view
    this.scheduled = false;
    this.frameWaiters = [];
    this.framesDrawn = 0;
    this.lastFrameMs = null;
  }

  add(view) {
    this.views.add(view);
    this.requestRender();
  }

  remove(view) {
    this.views.delete(view);
    this.requestRender();
  }

  /** Schedules a frame: for `view` alone when given (its rectangle has not moved), else for every view. */
  requestRender(view = null) {
    if (view) this.dirty.add(view);
    else this.everything = true;
    this.schedule();
  }

  schedule() {
    if (this.scheduled) return;
    this.scheduled = true;
    requestAnimationFrame(() => this.render());
  }

  /** Resolves after the next frame has been drawn (which may draw nothing new). */
  nextFrame() {
    this.schedule();
    return new Promise((resolve) => this.frameWaiters.push(resolve));
  }

  render() {
    this.scheduled = false;
    const started = performance.now();
    const r = this.renderer;
    const width = this.canvas.clientWidth;
    const height = this.canvas.clientHeight;
    const size = r.getSize(new THREE.Vector2());
    if (size.x !== width || size.y !== height) {
      r.setSize(width, height, false);
      this.everything = true;
    }
    const views = this.everything ? this.views : this.dirty;
    if (this.everything) {
      r.setScissorTest(false);
      r.setClearColor(0x000000, 0);
      r.clear();
    }
    r.setScissorTest(true);
    for (const view of views) {
      if (!this.views.has(view)) continue;
      const rects = view.rectangles();
      if (!rects) continue;
      const { rect, visible } = rects;
      // three.js viewports count y from the bottom of the canvas.
      r.setViewport(rect.left, height - rect.bottom, rect.width, rect.height);
      r.setScissor(visible.left, height - visible.bottom, visible.right - visible.left, visible.bottom - visible.top);
      r.setClearColor(view.background, 1);
      r.clear();
      if (view.mesh) {
        view.updateCamera(rect.width / rect.height);
        r.render(view.scene, view.camera);
      }
    }
    r.setClearColor(0x000000, 0);
    this.everything = false;
    this.dirty.clear();
    this.lastFrameMs = performance.now() - started;  // CPU side only: GL work may finish later
    this.framesDrawn += 1;
    this.frameWaiters.splice(0).forEach((resolve) => resolve());
  }
}

/**
 * Mouse orbit / pan / zoom on `element` for `orbit`: `orbitButton` drags rotate (0 = left, 2 = right),
 * middle or shift drags pan, the wheel zooms. `accept(event)` may veto a drag (e.g. the ROI pane's left
 * button paints). Calls onChange after every change.
 */
export function attachOrbit(element, orbit, { orbitButtons = [0], accept = () => true, onChange }) {
  let drag = null;
  element.addEventListener('pointerdown', (e) => {
    const panning = e.button === 1 || (e.shiftKey && orbitButtons.includes(e.button));
    if (!panning && !orbitButtons.includes(e.button)) return;
    if (!accept(e)) return;
    drag = { x: e.clientX, y: e.clientY, panning, id: e.pointerId };
    element.setPointerCapture(e.pointerId);
    e.preventDefault();
  });
  element.addEventListener('pointermove', (e) => {
    if (!drag || e.pointerId !== drag.id) return;
    const dx = e.clientX - drag.x;
    const dy = e.clientY - drag.y;
    drag.x = e.clientX;
    drag.y = e.clientY;
    if (drag.panning) orbit.pan(dx, dy, element.clientHeight);
    else orbit.rotate(dx, dy);
    onChange();
  });
  const end = (e) => {
    if (drag && e.pointerId === drag.id) drag = null;
  };
  element.addEventListener('pointerup', end);
  element.addEventListener('pointercancel', end);
  element.addEventListener('wheel', (e) => {
    e.preventDefault();
    orbit.dolly(e.deltaY);
    onChange();
  }, { passive: false });
  element.addEventListener('dblclick', () => {
    orbit.reset();
    onChange();
  });
  element.addEventListener('contextmenu', (e) => e.preventDefault());
}
