// SPDX-License-Identifier: MIT
// results.js: the results pane - a page of tiles, one 3D view each, all orbiting together.

import { View, OrbitState, attachOrbit } from './views.js';

const MIN_TILE = 120;  // px; below this a chair is an unreadable smudge, so the grid scrolls instead
const GAP = 8;         // px, as in style.css

/** One tile: a view plus its caption (name, cluster, distance) and the "use as example" button. */
class Tile {
  constructor(pane) {
    this.shape = null;
    this.token = 0;  // bumps with every new shape or redraw, so a late answer cannot overwrite a newer one
    this.element = document.createElement('div');
    this.element.className = 'tile';
    this.element.dataset.testid = 'tile';
    this.element.innerHTML = `
      <div class="tile-caption">
        <span class="tile-name"></span>
        <span class="tile-distance" title="distance to the regions of interest"></span>
      </div>
      <div class="tile-badge">example</div>
      <button class="tile-use" data-testid="use-example" title="add this shape to the regions-of-interest pane">
        use as example</button>`;
    this.name = this.element.querySelector('.tile-name');
    this.distance = this.element.querySelector('.tile-distance');
    this.element.querySelector('.tile-use').addEventListener('click', (e) => {
      e.stopPropagation();
      if (this.shape !== null) pane.onUseExample(this.shape);
    });
    this.view = new View(this.element, { clip: pane.clip, orbit: pane.orbit });
  }
}

export class ResultsPane {
  /** grid: the tiles' container; clip: the scrolling pane; onUseExample(shape); onCameraChange(). */
  constructor({ grid, clip, renderer, onUseExample, onCameraChange }) {
    this.grid = grid;
    this.clip = clip;
    this.renderer = renderer;
    this.onUseExample = onUseExample;
    this.orbit = new OrbitState();  // ONE camera control for every tile (dissertation 4.5.2)
    this.tiles = [];
    this.onCameraChange = onCameraChange;
    // Orbit with the left button, pan with the middle button or shift: on the grid as a whole, so a drag
    // that starts in one tile keeps going when the pointer crosses into the next.
    attachOrbit(grid, this.orbit, {
      orbitButtons: [0, 2],
      accept: (e) => !e.target.closest('button'),
      onChange: () => onCameraChange(),
    });
    new ResizeObserver(() => this.layout()).observe(clip);
  }

  setPageSize(n) {
    while (this.tiles.length < n) {
      const tile = new Tile(this);
      this.tiles.push(tile);
      this.grid.appendChild(tile.element);
      this.renderer.add(tile.view);
    }
    this.layout();
  }

  /** Chooses the column count that makes the tiles of a full page as large as possible without scrolling. */
  layout() {
    const n = this.tiles.length;
    if (!n) return;
    const style = getComputedStyle(this.clip);
    const width = this.clip.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight);
    const height = this.clip.clientHeight - parseFloat(style.paddingTop) - parseFloat(style.paddingBottom);
    let best = { size: 0, columns: 1, rows: n };
    for (let columns = 1; columns <= n; ++columns) {
      const rows = Math.ceil(n / columns);
      const size = Math.min((width - GAP * (columns - 1)) / columns, (height - GAP * (rows - 1)) / rows);
      if (size > best.size) best = { size, columns, rows };
    }
    let size = Math.floor(best.size);
    let columns = best.columns;
    // Tiles may grow taller than wide (chairs are), up to a third, to use the pane's spare height.
    let tall = Math.floor(Math.min(size * 1.33, (height - GAP * (best.rows - 1)) / best.rows));
    if (size < MIN_TILE) {
      size = MIN_TILE;
      tall = MIN_TILE;
      columns = Math.max(1, Math.floor((width + GAP) / (MIN_TILE + GAP)));
    }
    this.grid.style.gridTemplateColumns = `repeat(${columns}, ${size}px)`;
    this.grid.style.gridAutoRows = `${Math.max(size, tall)}px`;
    this.renderer.requestRender();
  }

  /**
   * Gives tile k the shape shapes[k] (or hides it): caption, distance and example badge now, the mesh later
   * (the caller loads it). Returns the tiles whose shape changed.
   */
  assign(shapes, { names, clusters, distances, examples }) {
    const changed = [];
    this.tiles.forEach((tile, k) => {
      const shape = k < shapes.length ? shapes[k] : null;
      tile.element.hidden = shape === null;
      if (shape !== tile.shape) {
        tile.shape = shape;
        tile.token += 1;
        tile.view.setShape(null);
        changed.push(tile);
      }
      if (shape === null) {
        delete tile.element.dataset.shape;
        return;
      }
      tile.element.dataset.shape = String(shape);
      const cluster = clusters[shape];
      tile.name.textContent = names[shape];
      if (cluster !== null && cluster !== undefined) {
        const tag = document.createElement('span');
        tag.className = 'tile-cluster';
        tag.textContent = `c${cluster}`;
        tag.title = `cluster ${cluster}`;
        tile.name.append(' ', tag);
      }
      const d = distances ? distances.get(shape) : undefined;
      tile.distance.textContent = d === undefined ? '' : formatDistance(d);
      tile.element.classList.toggle('is-example', examples.has(shape));
    });
    this.renderer.requestRender();
    return changed;
  }

  visibleShapes() {
    return this.tiles.filter((t) => t.shape !== null).map((t) => t.shape);
  }
}

function formatDistance(d) {
  if (d === 0) return '0';
  return Math.abs(d) >= 0.01 ? d.toFixed(3) : d.toExponential(1);
}
