// The map canvas of the live page: the map at the vehicle's depth, the current sweep's fan, the
// track and the vehicle, a metric grid and a scale bar; north up. Knows nothing of the server
// (live.js feeds it).
//
// Frames: the map frame (x north, y west, metres); the screen is north up, east to the right:
// screen x = width/2 + (centre.y - y) * scale, screen y = height/2 + (centre.x - x) * scale, in CSS
// pixels, scale in pixels per metre.
'use strict';

// Intensity 0…255 → RGBA: a viridis-like ramp, transparent for the quiet bins and faint for the
// noise, so the map shows through the water.
const FAN_COLOURS = (() => {
  const stops = [[0, 68, 1, 84], [64, 59, 82, 139], [128, 33, 145, 140], [192, 94, 201, 98], [255, 253, 231, 37]];
  const lut = new Uint8ClampedArray(256 * 4);
  for (let i = 0; i < 256; i++) {
    let k = 0;
    while (k < stops.length - 2 && i > stops[k + 1][0]) k++;
    const [a, b] = [stops[k], stops[k + 1]];
    const t = (i - a[0]) / (b[0] - a[0]);
    for (let c = 0; c < 3; c++) lut[i * 4 + c] = a[c + 1] + t * (b[c + 1] - a[c + 1]);
    lut[i * 4 + 3] = i < 24 ? 0 : Math.min(1, (i - 24) / 100) * 230;  // a noise floor of ~50 stays faint
  }
  return lut;
})();

class MapView {
  constructor(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.dpr = 1;
    this.width = 0;   // CSS pixels
    this.height = 0;
    this.centre = { x: 0, y: 0 };
    this.scale = 0;          // pixels per metre; 0 until a beam gives the range
    this.follow = true;      // the view's centre tracks the vehicle
    this.userZoom = false;   // a zoom of the user's replaces the fit to the range
    this.showFan = true;
    this.showTrack = true;
    this.tiles = new Map();  // "i,j" → {i, j, v, bitmap}: the map at the vehicle's depth
    this.tileGrid = null;    // {cell: a pixel's edge in metres, tp: pixels along a tile's edge}
    this.beams = new Map();  // bearing bucket → beam (the newest at that bearing)
    this.newestBeam = null;
    this.fanLimit = 800;
    this.track = [];
    this.vehicle = null;     // [t, x, y, z, heading]
    this.range = 0;
  }

  // --- data --------------------------------------------------------------------------------

  clearBeams() { this.beams.clear(); this.newestBeam = null; }

  // beam: {s, t, b, l, p: [x, y, z, yaw], cw, bins: Uint8Array}
  addBeam(beam) {
    const strip = document.createElement('canvas');
    strip.width = Math.max(1, beam.bins.length);
    strip.height = 1;
    const pixels = new ImageData(strip.width, 1);
    beam.bins.forEach((v, i) => pixels.data.set(FAN_COLOURS.subarray(v * 4, v * 4 + 4), i * 4));
    strip.getContext('2d').putImageData(pixels, 0, 0);
    beam.pattern = this.ctx.createPattern(strip, 'repeat-y');
    const previous = this.newestBeam;
    let step = previous ? Math.abs(Math.atan2(Math.sin(beam.b - previous.b), Math.cos(beam.b - previous.b))) : 0;
    if (!(step > 0.0009 && step < 0.09)) step = previous ? previous.step : 0.0157;
    beam.step = step;
    this.beams.delete(Math.round(beam.b * 1800 / Math.PI));  // re-inserted last: drawn on top
    this.beams.set(Math.round(beam.b * 1800 / Math.PI), beam);
    this.newestBeam = beam;
    for (const [key, old] of this.beams) {
      if (old.s >= beam.s - this.fanLimit) break;
      this.beams.delete(key);
    }
    this.range = beam.l * beam.bins.length;
  }

  setTrack(points, replace) { this.track = replace ? points.slice() : this.track.concat(points); }

  // Map tiles (the server's TileGrid): tile (i, j) spans map x [i, i + 1) × edge and y [j, j + 1) ×
  // edge, edge = tp × cell metres, its picture north up (row 0 at x = (i + 1) × edge, column 0 at
  // y = (j + 1) × edge). bitmap: an ImageBitmap of its grey PNG; a tile older than the one held is ignored.
  setTile(i, j, v, bitmap) {
    const key = `${i},${j}`;
    const old = this.tiles.get(key);
    if (old && old.v > v) { if (bitmap.close) bitmap.close(); return; }
    if (old && old.bitmap.close) old.bitmap.close();
    this.tiles.set(key, { i, j, v, bitmap });
  }

  // Drops the tiles for which keep(i, j) is false.
  keepTiles(keep) {
    for (const [key, tile] of this.tiles) {
      if (keep(tile.i, tile.j)) continue;
      if (tile.bitmap.close) tile.bitmap.close();
      this.tiles.delete(key);
    }
  }

  clearTiles() { this.keepTiles(() => false); }

  // The vehicle's place: the latest fix, else the latest beam's sonar.
  anchor() {
    if (this.vehicle) return { x: this.vehicle[1], y: this.vehicle[2] };
    if (this.newestBeam) return { x: this.newestBeam.p[0], y: this.newestBeam.p[1] };
    return { x: 0, y: 0 };
  }

  // --- view --------------------------------------------------------------------------------

  mapToScreen(x, y) {
    return [this.width / 2 + (this.centre.y - y) * this.scale, this.height / 2 + (this.centre.x - x) * this.scale];
  }

  screenToMap(px, py) {
    return [this.centre.x - (py - this.height / 2) / this.scale, this.centre.y - (px - this.width / 2) / this.scale];
  }

  zoom(factor, px = this.width / 2, py = this.height / 2) {
    if (!this.scale) return;
    const [x, y] = this.screenToMap(px, py);
    this.scale = Math.min(Math.max(this.scale * factor, 0.2), 2000);
    const [nx, ny] = this.screenToMap(px, py);
    this.centre.x += x - nx;
    this.centre.y += y - ny;
    this.userZoom = true;
    // Zooming about another point than the centre keeps that point still: the view stops following.
    if (Math.abs(px - this.width / 2) > 1 || Math.abs(py - this.height / 2) > 1) this.follow = false;
  }

  pan(dx, dy) {
    this.centre.x += dy / this.scale;
    this.centre.y += dx / this.scale;
    this.follow = false;
  }

  fit() {
    const rect = this.canvas.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    if (rect.width !== this.width || rect.height !== this.height || dpr !== this.dpr) {
      this.width = rect.width;
      this.height = rect.height;
      this.dpr = dpr;
      this.canvas.width = Math.max(1, Math.round(rect.width * dpr));
      this.canvas.height = Math.max(1, Math.round(rect.height * dpr));
    }
    if (this.follow) this.centre = this.anchor();
    if (!this.userZoom && this.range > 0) this.scale = Math.min(this.width, this.height) / 2 / (this.range * 1.05);
  }

  // --- drawing -----------------------------------------------------------------------------

  draw() {
    this.fit();
    const ctx = this.ctx;
    ctx.setTransform(this.dpr, 0, 0, this.dpr, 0, 0);
    ctx.fillStyle = '#808080';  // unknown, as the map's unknown cells
    ctx.fillRect(0, 0, this.width, this.height);
    if (!this.scale) {
      ctx.font = '14px system-ui, sans-serif';
      ctx.textBaseline = 'middle';
      label(ctx, 'Waiting for the sonar…', this.width / 2 - 80, this.height / 2);
      return;
    }
    this.drawRaster();
    if (this.showFan) this.drawFan();
    this.drawGrid();
    if (this.showTrack) this.drawTrack();
    this.drawVehicle();
  }

  drawRaster() {
    if (!this.tileGrid) return;
    const edge = this.tileGrid.tp * this.tileGrid.cell;
    const side = edge * this.scale;
    const ctx = this.ctx;
    ctx.imageSmoothingEnabled = false;
    for (const tile of this.tiles.values()) {
      const [left, top] = this.mapToScreen((tile.i + 1) * edge, (tile.j + 1) * edge);
      if (left > this.width || top > this.height || left + side < 0 || top + side < 0) continue;
      ctx.drawImage(tile.bitmap, left, top, side, side);
    }
  }

  // Screen angle (radians, clockwise from screen +x, y down) of a beam's direction.
  static beamAngle(beam) {
    const alpha = beam.p[3] + (beam.cw ? -beam.b : beam.b);  // map: from north towards west
    return Math.atan2(-Math.cos(alpha), -Math.sin(alpha));
  }

  drawFan() {
    const ctx = this.ctx;
    for (const beam of this.beams.values()) {
      const [ox, oy] = this.mapToScreen(beam.p[0], beam.p[1]);
      const angle = MapView.beamAngle(beam);
      const reach = beam.l * beam.bins.length * this.scale;
      const half = beam.step * 0.55;
      const c = Math.cos(angle) * this.dpr, s = Math.sin(angle) * this.dpr;
      ctx.setTransform(c, s, -s, c, ox * this.dpr, oy * this.dpr);
      beam.pattern.setTransform(new DOMMatrix([reach / beam.bins.length, 0, 0, 1, 0, 0]));
      ctx.fillStyle = beam.pattern;
      ctx.beginPath();
      ctx.moveTo(0, 0);
      ctx.arc(0, 0, reach, -half, half);
      ctx.closePath();
      ctx.fill();
    }
    ctx.setTransform(this.dpr, 0, 0, this.dpr, 0, 0);
    const newest = this.newestBeam;
    if (newest) {  // the head's current bearing
      const [ox, oy] = this.mapToScreen(newest.p[0], newest.p[1]);
      const angle = MapView.beamAngle(newest);
      const reach = newest.l * newest.bins.length * this.scale;
      ctx.strokeStyle = 'rgba(0, 229, 255, 0.9)';
      ctx.lineWidth = 1;
      ctx.beginPath();
      ctx.moveTo(ox, oy);
      ctx.lineTo(ox + reach * Math.cos(angle), oy + reach * Math.sin(angle));
      ctx.stroke();
    }
  }

  // Grid lines every "nice" distance, labelled at the left and bottom edges, and a scale bar.
  drawGrid() {
    const ctx = this.ctx;
    const target = 90 / this.scale;
    const decade = Math.pow(10, Math.floor(Math.log10(target)));
    const step = [1, 2, 5, 10].map((k) => k * decade).find((v) => v >= target * 0.7) || decade * 10;
    const [north0, west0] = this.screenToMap(0, 0);
    const [south1, west1] = this.screenToMap(this.width, this.height);
    ctx.lineWidth = 1;
    ctx.strokeStyle = 'rgba(20, 40, 60, 0.28)';
    ctx.font = '11px system-ui, sans-serif';
    ctx.textBaseline = 'middle';
    const labels = [];
    ctx.beginPath();
    for (let x = Math.ceil(south1 / step) * step; x <= north0; x += step) {
      const [, py] = this.mapToScreen(x, 0);
      ctx.moveTo(0, Math.round(py) + 0.5);
      ctx.lineTo(this.width, Math.round(py) + 0.5);
      labels.push([`${formatMetres(x)} N`, 4, py]);
    }
    for (let east = Math.ceil(-west0 / step) * step; east <= -west1; east += step) {
      const [px] = this.mapToScreen(0, -east);
      ctx.moveTo(Math.round(px) + 0.5, 0);
      ctx.lineTo(Math.round(px) + 0.5, this.height);
      labels.push([`${formatMetres(east)} E`, px + 3, this.height - 10]);
    }
    ctx.stroke();
    for (const [text, px, py] of labels) label(ctx, text, px, py);
    // Scale bar, bottom right.
    const bar = step * this.scale;
    const right = this.width - 12, base = this.height - 28;
    ctx.fillStyle = 'rgba(22, 25, 29, 0.8)';
    ctx.fillRect(right - bar - 6, base - 16, bar + 12, 24);
    ctx.strokeStyle = '#ffffff';
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(right - bar, base - 4); ctx.lineTo(right - bar, base); ctx.lineTo(right, base); ctx.lineTo(right, base - 4);
    ctx.stroke();
    ctx.fillStyle = '#ffffff';
    ctx.textAlign = 'center';
    ctx.fillText(`${formatMetres(step)} m`, right - bar / 2, base - 9);
    ctx.textAlign = 'start';
    label(ctx, 'N ↑', this.width - 34, 14);
  }

  drawTrack() {
    if (this.track.length < 2) return;
    const ctx = this.ctx;
    ctx.strokeStyle = '#ff8a00';
    ctx.lineWidth = 2;
    ctx.beginPath();
    this.track.forEach((p, i) => {
      const [px, py] = this.mapToScreen(p[1], p[2]);
      if (i === 0) ctx.moveTo(px, py); else ctx.lineTo(px, py);
    });
    ctx.stroke();
  }

  drawVehicle() {
    const ctx = this.ctx;
    const at = this.anchor();
    const [px, py] = this.mapToScreen(at.x, at.y);
    ctx.lineWidth = 1.5;
    ctx.strokeStyle = '#000000';
    ctx.fillStyle = '#ff8a00';
    ctx.beginPath();
    if (this.vehicle) {  // a triangle along the heading (clockwise from north)
      const h = this.vehicle[4];
      const fx = Math.sin(h), fy = -Math.cos(h);
      ctx.moveTo(px + 11 * fx, py + 11 * fy);
      ctx.lineTo(px - 7 * fx + 6 * fy, py - 7 * fy - 6 * fx);
      ctx.lineTo(px - 7 * fx - 6 * fy, py - 7 * fy + 6 * fx);
      ctx.closePath();
    } else {
      ctx.arc(px, py, 5, 0, 2 * Math.PI);
    }
    ctx.fill();
    ctx.stroke();
  }

  // --- probes (tests, and anyone curious) --------------------------------------------------

  // Centres [x, y] (map frame, metres) of the map picture's cells whose grey level is below 64
  // (occupied) or, with free = true, above 192.
  rasterCells(free = false) {
    if (!this.tileGrid) return [];
    const { cell, tp } = this.tileGrid;
    const scratch = document.createElement('canvas');
    scratch.width = tp;
    scratch.height = tp;
    const ctx = scratch.getContext('2d', { willReadFrequently: true });
    const cells = [];
    for (const tile of this.tiles.values()) {
      ctx.clearRect(0, 0, tp, tp);
      ctx.drawImage(tile.bitmap, 0, 0);
      const data = ctx.getImageData(0, 0, tp, tp).data;
      const north = (tile.i + 1) * tp * cell, west = (tile.j + 1) * tp * cell;
      for (let row = 0; row < tp; row++) {
        for (let col = 0; col < tp; col++) {
          const grey = data[(row * tp + col) * 4];
          if (free ? grey > 192 : grey < 64) cells.push([north - (row + 0.5) * cell, west - (col + 0.5) * cell]);
        }
      }
    }
    return cells;
  }
}

function formatMetres(value) {
  const rounded = Math.round(value * 1000) / 1000;
  return Object.is(rounded, -0) ? '0' : String(rounded);
}

// Text on a dark box, legible over any map colour.
function label(ctx, text, x, y) {
  const width = ctx.measureText(text).width;
  ctx.fillStyle = 'rgba(22, 25, 29, 0.8)';
  ctx.fillRect(x - 2, y - 8, width + 4, 16);
  ctx.fillStyle = '#ffffff';
  ctx.fillText(text, x, y);
}

window.MapView = MapView;
