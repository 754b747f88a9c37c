// SPDX-License-Identifier: MIT
// roi.js: the region-of-interest pane - example shapes, each in its own view, painted with a brush.
//
// Left-drag paints (shift or the "erase" toggle removes); right-drag, or left-drag in "rotate" mode, orbits
// that example's own camera; the middle button pans; the wheel zooms. A dab adds every sample within the brush
// radius of the surface point under the pointer, so the region is a set of sample indices - what the server's
// queries take.

import * as THREE from 'three';
import { View, OrbitState, attachOrbit } from './views.js';
import { bounds, brush } from './painting.js';

const DAB_SPACING = 4;  // px between dabs along a stroke, so a fast drag leaves no gaps

export class Example {
  constructor(pane, shape, name) {
    this.pane = pane;
    this.shape = shape;
    this.selected = new Set();
    this.mesh = null;  // api.getMesh data once loaded
    this.revision = 0;  // main.js draws only the latest colouring of this example
    this.diagonal = 1;
    this.element = document.createElement('article');
    this.element.className = 'example';
    this.element.dataset.testid = 'example';
    this.element.dataset.shape = String(shape);
    this.element.innerHTML = `
      <header>
        <span class="example-name"></span>
        <span class="example-count" data-testid="example-count"></span>
        <button data-testid="clear-example" title="unpaint every sample of this example">clear</button>
        <button data-testid="remove-example" title="take this example out of the pane">remove</button>
      </header>
      <div class="example-view"></div>`;
    this.element.querySelector('.example-name').textContent = name;
    this.count = this.element.querySelector('.example-count');
    this.viewElement = this.element.querySelector('.example-view');
    this.element.querySelector('[data-testid=clear-example]').addEventListener('click', () => {
      this.selected.clear();
      pane.regionChanged(this);
    });
    this.element.querySelector('[data-testid=remove-example]').addEventListener('click', () => pane.remove(this));
    this.view = new View(this.viewElement, { clip: pane.clip, orbit: new OrbitState(), background: 0x262a33 });
    this.cursor = new THREE.Mesh(new THREE.SphereGeometry(1, 24, 12),
      new THREE.MeshBasicMaterial({ color: 0xffa040, transparent: true, opacity: 0.28, depthWrite: false }));
    this.cursor.visible = false;
    this.attachInput();
    this.updateCount();
  }

  /** Called when the mesh arrives (or is re-created): the brush cursor lives in the mesh's model space. */
  meshReady(mesh) {
    this.mesh = mesh;
    this.diagonal = bounds(mesh.positions).diagonal;
    if (this.view.mesh) this.view.mesh.add(this.cursor);
  }

  brushRadius() {
    return this.pane.brushFraction() * this.diagonal;
  }

  updateCount() {
    this.count.textContent = this.selected.size ? `${this.selected.size} samples` : 'not painted';
  }

  attachInput() {
    const el = this.viewElement;
    const pane = this.pane;
    let stroke = null;
    attachOrbit(el, this.view.orbit, {
      orbitButtons: [0, 2],
      accept: (e) => e.button !== 0 || pane.rotateMode(),
      onChange: () => pane.renderer.requestRender(this.view),
    });
    const dab = (x, y, erase) => {
      const hit = this.view.pick(x, y);
      this.showCursor(hit);
      if (!hit || !this.mesh) return false;
      return brush(this.mesh, this.selected, hit.local.toArray(), this.brushRadius(), erase);
    };
    el.addEventListener('pointerdown', (e) => {
      if (e.button !== 0 || pane.rotateMode() || !this.mesh) return;
      stroke = { id: e.pointerId, x: e.clientX, y: e.clientY, erase: pane.eraseMode() || e.shiftKey };
      el.setPointerCapture(e.pointerId);
      e.preventDefault();
      if (dab(e.clientX, e.clientY, stroke.erase)) pane.regionChanged(this, { live: true });
    });
    el.addEventListener('pointermove', (e) => {
      if (!stroke || e.pointerId !== stroke.id) {
        // Hovering: the cursor shows where and how large a dab would be.
        if (!pane.rotateMode() && e.buttons === 0) {
          this.showCursor(this.view.pick(e.clientX, e.clientY));
          pane.renderer.requestRender(this.view);
        }
        return;
      }
      const steps = Math.max(1, Math.ceil(Math.hypot(e.clientX - stroke.x, e.clientY - stroke.y) / DAB_SPACING));
      let changed = false;
      for (let s = 1; s <= steps; ++s) {
        const t = s / steps;
        changed = dab(stroke.x + (e.clientX - stroke.x) * t, stroke.y + (e.clientY - stroke.y) * t, stroke.erase) ||
          changed;
      }
      stroke.x = e.clientX;
      stroke.y = e.clientY;
      if (changed) pane.regionChanged(this, { live: true });
      else pane.renderer.requestRender(this.view);
    });
    const end = (e) => {
      if (!stroke || e.pointerId !== stroke.id) return;
      stroke = null;
      pane.regionChanged(this);
    };
    el.addEventListener('pointerup', end);
    el.addEventListener('pointercancel', end);
    el.addEventListener('pointerleave', () => {
      if (stroke) return;
      this.cursor.visible = false;
      pane.renderer.requestRender(this.view);
    });
  }

  showCursor(hit) {
    this.cursor.visible = !!hit;
    if (!hit) return;
    this.cursor.position.copy(hit.local);
    this.cursor.scale.setScalar(this.brushRadius());
  }
}

export class RoiPane {
  /**
   * container: where example cards go; clip: the scrolling pane; controls: {brush (range input, percent of
   * the bounding-box diagonal), erase, rotate (toggle buttons)}; onAdd(example), onChange(example, {live}),
   * onRemove(example).
   */
  constructor({ container, clip, renderer, controls, onAdd, onChange, onRemove }) {
    Object.assign(this, { container, clip, renderer, controls, onAdd, onChange, onRemove });
    this.examples = [];
  }

  brushFraction() {
    return Number(this.controls.brush.value) / 100;
  }

  eraseMode() {
    return this.controls.erase.getAttribute('aria-pressed') === 'true';
  }

  rotateMode() {
    return this.controls.rotate.getAttribute('aria-pressed') === 'true';
  }

  add(shape, name) {
    const example = new Example(this, shape, name);
    this.examples.push(example);
    this.container.appendChild(example.element);
    this.renderer.add(example.view);
    this.onAdd(example);
    return example;
  }

  remove(example) {
    this.examples = this.examples.filter((e) => e !== example);
    example.element.remove();
    this.renderer.remove(example.view);
    example.view.setShape(null);
    this.onRemove(example);
  }

  regionChanged(example, { live = false } = {}) {
    example.updateCount();
    this.onChange(example, { live });
  }

  /** The query's regions: one per example with painted samples (each one facet). */
  regions() {
    return this.examples.filter((e) => e.selected.size > 0)
      .map((e) => ({ shape: e.shape, samples: [...e.selected].sort((a, b) => a - b) }));
  }
}
