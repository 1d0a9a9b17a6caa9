// The live page: reads the session's updates (Server-Sent Events from `events`, or long polling of
// `updates` when a stream is refused or a proxy holds its events back), feeds the map canvas
// (map_view.js), shows the status and the head's settings, runs "Save map" and "Reset map", and
// tells the server what it drew and when (`ack`), so that the server can time each beam from its
// arrival to the page's pixels. Every URL is relative: the page works under a proxy's prefix.
'use strict';

const view = new MapView(document.getElementById('map'));
const $ = (id) => document.getElementById(id);

const page = {
  view,
  cursor: '',
  transport: 'connecting',
  updates: 0,
  lastDrawnSeq: -1,     // the newest beam whose fan was drawn
  drawnBeams: 0,
  rasterInfo: null,     // the map picture drawn last (all its tiles decoded)
  status: null,
  settings: null,
  saved: null,          // the last "Save map" answer
  pendingBeams: [],     // seqs added since the last frame
  pendingRasters: [],
  unacknowledged: new Set(),  // seqs and versions that came while the page was hidden: not timed
  frameRequested: false,
  rasterWanted: 0,      // the newest picture version announced
  tileRange: [0, -1, 0, -1],  // the newest picture's tiles: i0, i1, j0, j1
  id: Math.random().toString(36).slice(2, 10),  // this page's own latencies: GET latency?page=ID
};
window.sonarmapPage = page;

// --- updates ------------------------------------------------------------------------------

function decodeBins(text) {
  const raw = atob(text);
  const bins = new Uint8Array(raw.length);
  for (let i = 0; i < raw.length; i++) bins[i] = raw.charCodeAt(i);
  return bins;
}

function apply(update) {
  page.updates++;
  page.cursor = update.cursor;
  if (update.full) {
    view.clearBeams();
    page.pendingBeams = [];
  }
  view.fanLimit = update.fan_beams || view.fanLimit;
  for (const beam of update.beams) {
    beam.bins = decodeBins(beam.i);
    delete beam.i;
    view.addBeam(beam);
    page.pendingBeams.push(beam.s);
    if (document.hidden) page.unacknowledged.add(`b${beam.s}`);
  }
  if (update.track.length || update.track_full) view.setTrack(update.track, update.track_full);
  if (update.vehicle) view.vehicle = update.vehicle;
  if (update.settings) showSettings(update.settings);
  if (update.raster && update.raster.v > page.rasterWanted) applyRaster(update.raster, update.tile_data || []);
  showStatus(update.status, update.clock_s);
  requestFrame();
}

// A map picture: its tiles, i0 … i1 × j0 … j1 (info.tiles), of which those in `data` changed
// ([i, j, version, base64 PNG]). Tiles outside are dropped; a picture counts as drawn once its
// changed tiles are decoded (a tile older than the one held, or outside the newest picture's
// range when decoded, is not kept).
function applyRaster(info, data) {
  page.rasterWanted = info.v;
  if (!view.tileGrid || view.tileGrid.cell !== info.cell || view.tileGrid.tp !== info.tp) {
    view.clearTiles();
    view.tileGrid = { cell: info.cell, tp: info.tp };
  }
  page.tileRange = info.tiles;
  const inRange = (i, j) => {
    const [i0, i1, j0, j1] = page.tileRange;
    return i >= i0 && i <= i1 && j >= j0 && j <= j1;
  };
  view.keepTiles(inRange);
  const decoded = data.map(([i, j, v, png]) => createImageBitmap(new Blob([decodeBins(png)], { type: 'image/png' }))
    .then((bitmap) => {
      if (inRange(i, j)) view.setTile(i, j, v, bitmap);
      else if (bitmap.close) bitmap.close();
    }));
  Promise.all(decoded).then(() => {
    if (page.rasterInfo && page.rasterInfo.v >= info.v) return;  // a newer picture was drawn first
    page.rasterInfo = info;
    page.pendingRasters.push(info.v);
    if (document.hidden) page.unacknowledged.add(`r${info.v}`);
    requestFrame();
  }).catch((error) => console.warn('map tile:', error));
}

function connect() {
  if (!window.EventSource) { poll(); return; }
  const source = new EventSource('events');
  let heard = false;
  // A proxy that buffers the stream delivers nothing: poll instead.
  const silence = setTimeout(() => { if (!heard) { source.close(); poll(); } }, 6000);
  source.addEventListener('update', (event) => {
    heard = true;
    page.transport = 'events';
    setConnection('connected (event stream)', true);
    apply(JSON.parse(event.data));
  });
  source.onerror = () => {
    if (source.readyState === EventSource.CLOSED) {  // refused (too many streams): poll
      clearTimeout(silence);
      poll();
    } else {
      setConnection('reconnecting…', false);
    }
  };
}

async function poll() {
  page.transport = 'polling';
  for (;;) {
    try {
      const response = await fetch(`updates?cursor=${encodeURIComponent(page.cursor)}&wait_ms=20000`, { cache: 'no-store' });
      if (!response.ok) throw new Error(`HTTP ${response.status}`);
      apply(await response.json());
      setConnection('connected (polling)', true);
      await new Promise((done) => setTimeout(done, 100));
    } catch (error) {
      setConnection('server unreachable, retrying…', false);
      await new Promise((done) => setTimeout(done, 1000));
    }
  }
}

// --- drawing and acknowledgements ----------------------------------------------------------

function requestFrame() {
  if (page.frameRequested) return;
  page.frameRequested = true;
  requestAnimationFrame(frame);
}

function frame() {
  page.frameRequested = false;
  view.draw();
  const drawnAt = performance.now();
  const beams = page.pendingBeams, rasters = page.pendingRasters;
  page.pendingBeams = [];
  page.pendingRasters = [];
  if (beams.length) {
    page.lastDrawnSeq = Math.max(page.lastDrawnSeq, beams[beams.length - 1]);
    page.drawnBeams += beams.length;
  }
  // What came while the page was hidden waited for it to show, not for the session: not timed.
  const timed = (list, kind) => list.filter((id) => !page.unacknowledged.delete(`${kind}${id}`));
  const [ackBeams, ackRasters] = [timed(beams, 'b'), timed(rasters, 'r')];
  if (ackBeams.length || ackRasters.length) acknowledge(ackBeams, ackRasters, drawnAt);
}

function acknowledge(beams, rasters, drawnAt) {
  const body = `beams ${beams.join(' ')}\nrasters ${rasters.join(' ')}\nheld_ms ${(performance.now() - drawnAt).toFixed(2)}\n` +
               `page ${page.id}\n`;
  // The answer's body is read (empty): Chromium aborts a request whose response is left unread.
  fetch('ack', { method: 'POST', body, headers: { 'Content-Type': 'text/plain' } })
    .then((response) => response.arrayBuffer()).catch(() => {});
}

// --- panel ---------------------------------------------------------------------------------

function setConnection(text, ok) {
  const element = $('connection');
  if (element.textContent === text) return;  // a live region: announce changes only
  element.textContent = text;
  element.classList.toggle('bad', !ok);
}

function fixed(value, digits) { return value === null || value === undefined ? '–' : Number(value).toFixed(digits); }

function showStatus(status, clock) {
  page.status = status;
  $('rate').textContent = fixed(status.rate, 1);
  // Before its first sweep the mapper has no water background to detect against: the beams wait
  // for it, which is not lag.
  const calibrating = status.sweeps === 0 && status.waiting > 0;
  $('lag').textContent = calibrating ? 'calibrating on the first sweep'
    : status.lag === null ? '–' : `${fixed(status.lag, 2)} s`;
  $('beams').textContent = String(status.beams);
  $('waiting').textContent = calibrating ? `${status.waiting} (first sweep)` : String(status.waiting);
  $('sweeps').textContent = String(status.sweeps);
  const info = page.rasterInfo;
  $('slice').textContent = info ? `z ${fixed(info.z, 2)} m, ${fixed(info.cell * 100, 0)} cm cells` : '–';
  $('clock').textContent = `${fixed(clock, 0)} s`;
  $('recording').textContent = status.recording || '–';
  const list = $('warnings');
  const texts = status.warnings || [];
  if (list.dataset.shown !== JSON.stringify(texts)) {
    list.dataset.shown = JSON.stringify(texts);
    list.replaceChildren(...texts.map((text) => Object.assign(document.createElement('li'), { textContent: text })));
  }
}

function showSettings(settings) {
  page.settings = settings;
  $('device').textContent = settings.device || 'unknown sonar';
  const rows = settings.fields.map(([name, value]) => {
    const row = document.createElement('tr');
    row.append(Object.assign(document.createElement('th'), { scope: 'row', textContent: name }),
               Object.assign(document.createElement('td'), { textContent: value }));
    return row;
  });
  $('settings').querySelector('tbody').replaceChildren(...rows);
}

async function act(name) {
  const result = $('action-result');
  result.textContent = name === 'save' ? 'Saving…' : 'Resetting…';
  try {
    const response = await fetch(name, { method: 'POST', headers: { 'X-Sonarmap': '1' } });
    const answer = await response.json();
    if (!answer.ok) throw new Error(answer.error || `HTTP ${response.status}`);
    if (name === 'save') {
      page.saved = answer.paths;
      result.textContent = 'Saved: ' + Object.entries(answer.paths).map(([what, path]) => `${what} ${path}`).join(', ');
    } else {
      result.textContent = 'Map reset.';
    }
  } catch (error) {
    result.textContent = `${name === 'save' ? 'Save' : 'Reset'} failed: ${error.message}`;
  }
}

// --- controls ------------------------------------------------------------------------------

$('save').addEventListener('click', () => act('save'));
$('reset').addEventListener('click', () => { $('confirm-reset').hidden = false; $('confirm-reset-yes').focus(); });
$('confirm-reset-no').addEventListener('click', () => { $('confirm-reset').hidden = true; $('reset').focus(); });
$('confirm-reset-yes').addEventListener('click', () => { $('confirm-reset').hidden = true; act('reset'); });
$('zoom-in').addEventListener('click', () => { view.zoom(1.5); requestFrame(); });
$('zoom-out').addEventListener('click', () => { view.zoom(1 / 1.5); requestFrame(); });
$('follow').addEventListener('click', () => {
  view.follow = true;
  view.userZoom = false;
  $('follow').setAttribute('aria-pressed', 'true');
  requestFrame();
});
$('show-fan').addEventListener('change', (event) => { view.showFan = event.target.checked; requestFrame(); });
$('show-track').addEventListener('change', (event) => { view.showTrack = event.target.checked; requestFrame(); });

const canvas = $('map');
canvas.addEventListener('wheel', (event) => {
  event.preventDefault();
  const rect = canvas.getBoundingClientRect();
  view.zoom(event.deltaY < 0 ? 1.2 : 1 / 1.2, event.clientX - rect.left, event.clientY - rect.top);
  $('follow').setAttribute('aria-pressed', String(view.follow));
  requestFrame();
}, { passive: false });
let dragFrom = null;
canvas.addEventListener('pointerdown', (event) => { dragFrom = [event.clientX, event.clientY]; canvas.setPointerCapture(event.pointerId); });
canvas.addEventListener('pointerup', () => { dragFrom = null; });
canvas.addEventListener('pointermove', (event) => {
  if (!dragFrom) return;
  view.pan(event.clientX - dragFrom[0], event.clientY - dragFrom[1]);
  dragFrom = [event.clientX, event.clientY];
  $('follow').setAttribute('aria-pressed', 'false');
  requestFrame();
});
new ResizeObserver(() => requestFrame()).observe(canvas);

connect();
