// The page of `sonarmap live --serve` in Debian's headless Chromium, driven by playwright-core,
// against fake_session.cpp (a simulated Ping360 at 50 m, ~12 beams a second of 1200 samples, mapped
// by a real OnlineMapper). It checks that:
//  1. the page shows the head's settings and the status, and draws the beams and the map it is sent;
//  2. two screenshots of the map 40 beams apart differ inside those beams' wedge, and hardly
//     anywhere else;
//  3. the p95 of beam arrival → pixels (GET latency) is under 0.25 s for the fan (the map's is
//     reported and bounded loosely);
//  4. the map the page drew is the map "Save map" wrote: the occupied cells of its picture are the
//     .bt's occupied cells at the sonar's height (fake_session reads the file back), and on screen,
//     zoomed in with the sweep and track hidden, occupied cells are dark and free ones light;
//  5. "Reset map" asks first, then empties the map while the fan goes on;
//  6. the page works 400 px wide in an iframe under a proxy's prefix (BlueOS's /extensionv2/NAME/),
//     and by long polling when the browser has no EventSource.
// Run by run_page_test.sh (ctest: live.pageInHeadlessChromium). Writes screenshots to --work.
'use strict';
const { chromium } = require('playwright-core');
const { spawn } = require('child_process');
const fs = require('fs');
const http = require('http');
const path = require('path');
const { Proxy } = require('./page_test_proxy.js');

const args = {};
for (let i = 2; i + 1 < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
const FLAGS = ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
               '--disable-component-update', '--disable-sync'];

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
}

// fake_session on pipes: one command, one answer line.
class Session {
  constructor(program, out) {
    this.child = spawn(program, ['--out', out, '--rate', '12', '--resolution', '0.1'], { stdio: ['pipe', 'pipe', 'inherit'] });
    this.lines = [];
    this.waiting = null;
    let buffer = '';
    this.child.stdout.on('data', (chunk) => {
      buffer += chunk;
      for (let end; (end = buffer.indexOf('\n')) >= 0;) {
        this.lines.push(buffer.slice(0, end));
        buffer = buffer.slice(end + 1);
      }
      if (this.waiting && this.lines.length) { const done = this.waiting; this.waiting = null; done(); }
    });
  }
  async line() {
    if (!this.lines.length) await new Promise((done) => { this.waiting = done; });
    return this.lines.shift();
  }
  async command(text) {
    this.child.stdin.write(`${text}\n`);
    const answer = await this.line();
    return Object.fromEntries(answer.split(' ').slice(1).map((field) => field.split('=')).map(([k, v]) => [k, Number(v)]));
  }
}

function getJson(url) {
  return new Promise((resolve, reject) => {
    http.get(url, (response) => {
      let body = '';
      response.on('data', (chunk) => { body += chunk; });
      response.on('end', () => resolve(JSON.parse(body)));
    }).on('error', reject);
  });
}

function post(url) {
  return new Promise((resolve, reject) => {
    const request = http.request(url, { method: 'POST', headers: { 'X-Sonarmap': '1' } }, (response) => {
      response.resume();
      response.on('end', () => resolve(response.statusCode));
    });
    request.on('error', reject);
    request.end();
  });
}

// Waits until `probe` (run in `frame`) returns true.
async function until(frame, probe, arg, what, timeout = 20000) {
  try {
    await frame.waitForFunction(probe, arg, { timeout, polling: 50 });
    return true;
  } catch (error) {
    check(false, `${what} (timed out)`);
    return false;
  }
}

// RGBA pixels of a PNG, decoded by the browser.
async function pixelsOf(decoder, png) {
  const base64 = await decoder.evaluate(async (data) => {
    const image = new Image();
    image.src = `data:image/png;base64,${data}`;
    await image.decode();
    const canvas = Object.assign(document.createElement('canvas'), { width: image.width, height: image.height });
    const ctx = canvas.getContext('2d');
    ctx.drawImage(image, 0, 0);
    const pixels = ctx.getImageData(0, 0, image.width, image.height);
    const url = await new Promise((done) => {
      const reader = new FileReader();
      reader.onload = () => done(reader.result);
      reader.readAsDataURL(new Blob([pixels.data]));
    });
    return `${image.width} ${image.height} ${url.slice(url.indexOf(',') + 1)}`;
  }, png.toString('base64'));
  const [width, height, data] = base64.split(' ');
  return { width: Number(width), height: Number(height), data: Buffer.from(data, 'base64') };
}

const wrap = (angle) => ((angle % (2 * Math.PI)) + 2 * Math.PI) % (2 * Math.PI);

// Changed pixels inside and outside the wedge of bearings [from, to] (a static sonar at screen
// point `origin`, bearing 0 up, clockwise), within `reach` pixels, widened by `margin` radians and
// 3 pixels; and the share of the wedge's beams (`step` apart) with a changed pixel.
function compareShots(a, b, origin, from, to, step, reach, margin) {
  const span = wrap(to - from);
  const counts = { inside: 0, insideChanged: 0, outside: 0, outsideChanged: 0, outsideExamples: [] };
  const beams = Math.round(span / step) + 1, changedBeams = new Set();
  for (let y = 0; y < a.height; y++) {
    for (let x = 0; x < a.width; x++) {
      const i = (y * a.width + x) * 4;
      const changed = Math.max(Math.abs(a.data[i] - b.data[i]), Math.abs(a.data[i + 1] - b.data[i + 1]),
                               Math.abs(a.data[i + 2] - b.data[i + 2])) > 30;
      const dx = x + 0.5 - origin[0], dy = y + 0.5 - origin[1];
      const r = Math.hypot(dx, dy);
      const bearing = wrap(Math.atan2(dy, dx) + Math.PI / 2);
      const slack = r > 0 ? 3 / r : Math.PI;
      const inside = r <= reach + 3 && (r < 4 || wrap(bearing - from + margin + slack) <= span + 2 * (margin + slack));
      if (inside) {
        counts.inside++;
        if (changed) counts.insideChanged++;
        const beam = Math.round(wrap(bearing - from) / step);
        if (changed && beam < beams) changedBeams.add(beam);
      } else {
        counts.outside++;
        if (changed) {
          counts.outsideChanged++;
          if (counts.outsideExamples.length < 8) counts.outsideExamples.push([x, y]);
        }
      }
    }
  }
  counts.beamsChanged = changedBeams.size / beams;
  return counts;
}

async function main() {
  const work = args.work;
  const session = new Session(args.session, work);
  const listening = await session.line();
  const base = listening.split(' ')[1];
  console.log(`fake session: ${base}`);
  // A whole sweep to calibrate on, and 30 beams of the next, shown on the provisional layer.
  const warm = await session.command('fast 430');
  check(warm.sweeps === 1 && warm.shown === 430, `warm-up: a sweep integrated, 430 beams shown (${JSON.stringify(warm)})`);

  const browser = await chromium.launch({ executablePath: args.chromium, headless: true, args: FLAGS });
  const context = await browser.newContext({ viewport: { width: 1000, height: 760 }, deviceScaleFactor: 1 });
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (error) => errors.push(String(error)));
  page.on('console', (message) => { if (message.type() === 'error') errors.push(message.text()); });
  // Requests the browser gave up on (Chromium aborts a fetch whose response is left unread).
  const aborted = [];
  context.on('requestfailed', (request) => aborted.push(`${new URL(request.url()).pathname}: ${request.failure().errorText}`));
  // Screenshots are decoded in a page of their own context: using another page of the main page's
  // context leaves the main page's animation frames throttled to about one a second in headless
  // Chromium (while it reports itself visible), which the latencies would show.
  const decoder = await (await browser.newContext()).newPage();

  // 1. What the page shows.
  await page.goto(base);
  await until(page, (shown) => window.sonarmapPage && sonarmapPage.lastDrawnSeq === 429 && sonarmapPage.rasterInfo &&
                sonarmapPage.rasterInfo.beams >= shown, warm.shown, 'the page draws the beams and the map it is sent');
  const panel = await page.evaluate(() => ({
    device: document.getElementById('device').textContent,
    settings: Array.from(document.querySelectorAll('#settings tbody tr')).map((row) => row.textContent),
    beams: document.getElementById('beams').textContent,
    transport: sonarmapPage.transport,
  }));
  check(panel.device.includes('ping360'), `the device is named (${panel.device})`);
  check(panel.settings.some((row) => row.includes('range_m') && row.includes('50')), `the settings are listed (${panel.settings})`);
  check(panel.beams === '430', `the status counts the beams (${panel.beams})`);
  check(panel.transport === 'events', `updates come by event stream (${panel.transport})`);

  // 2. Two screenshots 40 beams apart.
  const canvas = page.locator('#map');
  const shotA = await canvas.screenshot({ path: path.join(work, 'before.png') });
  await post(`${base}latency/reset`);
  const fed = await session.command('feed 40');
  await until(page, ([last, shown]) => sonarmapPage.lastDrawnSeq === last && sonarmapPage.rasterInfo.beams >= shown,
              [fed.last, fed.shown], 'the page draws the 40 new beams and their map');
  const shotB = await canvas.screenshot({ path: path.join(work, 'after.png') });
  const geometry = await page.evaluate(() => ({ origin: sonarmapPage.view.mapToScreen(0, 0), scale: sonarmapPage.view.scale }));
  const [a, b] = [await pixelsOf(decoder, shotA), await pixelsOf(decoder, shotB)];
  const step = 2 * Math.PI / 400;
  const diff = compareShots(a, b, geometry.origin, fed.bearing_from - step, fed.bearing_to, step, 50 * geometry.scale,
                            3 * Math.PI / 180);
  const insideShare = diff.insideChanged / diff.inside, outsideShare = diff.outsideChanged / diff.outside;
  console.log(`     screenshots: ${a.width}x${a.height}, wedge of ${diff.inside} px: ${(100 * insideShare).toFixed(1)}% changed, ` +
              `in ${(100 * diff.beamsChanged).toFixed(0)}% of its beams; ` +
              `elsewhere ${diff.outsideChanged} of ${diff.outside} px changed ${JSON.stringify(diff.outsideExamples)}`);
  check(insideShare > 0.01 && diff.beamsChanged > 0.8, 'the new beams changed the picture all along their wedge');
  check(outsideShare < 0.002, 'and hardly anywhere else (< 0.2 % of the other pixels)');

  // 3. Beam arrival → pixels at the head's pace.
  await page.bringToFront();
  const timed = await session.command('feed 120');
  await until(page, ([last, shown]) => sonarmapPage.lastDrawnSeq === last && sonarmapPage.rasterInfo.beams >= shown,
              [timed.last, timed.shown], 'the page keeps up with 12 beams a second');
  await page.waitForTimeout(300);  // the last acknowledgements
  const latency = await getJson(`${base}latency`);
  const ms = (s) => (1000 * s).toFixed(1);
  console.log(`     arrival → pixels over ${latency.fan.count} beams: fan median ${ms(latency.fan.median_s)} ms, ` +
              `p95 ${ms(latency.fan.p95_s)} ms, max ${ms(latency.fan.max_s)} ms; map median ${ms(latency.map.median_s)} ms, ` +
              `p95 ${ms(latency.map.p95_s)} ms, max ${ms(latency.map.max_s)} ms (${latency.map.count} beams); ` +
              `map picture median ${ms(latency.render.median_s)} ms (copy ${ms(latency.copy.median_s)} ms), ` +
              `p95 ${ms(latency.render.p95_s)} ms, ` +
              `${latency.last_png_bytes} bytes`);
  check(latency.fan.count >= 150, `every beam's fan was acknowledged (${latency.fan.count} of 160)`);
  check(latency.fan.p95_s < 0.25, 'fan: p95 of arrival → pixels under 0.25 s');
  check(latency.map.count >= 150 && latency.map.p95_s < 1.0, 'map: p95 of arrival → pixels under 1 s');

  // 4. The map drawn is the map saved.
  await page.click('#save');
  await until(page, () => document.getElementById('action-result').textContent.startsWith('Saved'), null, '"Save map" answers');
  const saved = await page.evaluate(() => sonarmapPage.saved);
  check(saved && fs.existsSync(saved.map) && fs.existsSync(saved.log), `"Save map" wrote ${JSON.stringify(saved)}`);
  const file = JSON.parse(fs.readFileSync(saved.cells, 'utf8'));
  const key = ([x, y]) => `${Math.floor(x / file.resolution + 1e-6)},${Math.floor(y / file.resolution + 1e-6)}`;
  const inFile = new Set(file.occupied.map(key));
  const drawn = await page.evaluate(() => sonarmapPage.view.rasterCells());
  const onPage = new Set(drawn.map(key));
  const missing = [...inFile].filter((cell) => !onPage.has(cell)).length;
  const extra = [...onPage].filter((cell) => !inFile.has(cell)).length;
  console.log(`     occupied cells: ${inFile.size} in the .bt at z 0, ${onPage.size} in the page's picture; ${missing} missing, ${extra} extra`);
  check(inFile.size > 100 && missing === 0 && extra === 0, 'the page\'s map is the saved map, cell for cell');

  // Zoomed in on a wall with the mouse wheel, the sweep and the track hidden.
  await page.click('label:has(#show-fan)');
  await page.click('label:has(#show-track)');
  const wall = await page.evaluate(() => {
    const cells = sonarmapPage.view.rasterCells();
    const middle = cells[Math.floor(cells.length / 2)];
    return sonarmapPage.view.mapToScreen(middle[0], middle[1]);
  });
  const box = await canvas.boundingBox();
  await page.mouse.move(box.x + wall[0], box.y + wall[1]);
  for (let i = 0; i < 6; i++) {
    await page.mouse.wheel(0, -100);
    await page.waitForTimeout(50);
  }
  await page.waitForTimeout(200);
  const zoomed = await pixelsOf(decoder, await canvas.screenshot({ path: path.join(work, 'zoomed.png') }));
  const samples = await page.evaluate(() => {
    const view = sonarmapPage.view;
    const at = (cells) => cells.map(([x, y]) => view.mapToScreen(x, y)).filter(([px, py]) =>
      px > 4 && py > 60 && px < view.width - 90 && py < view.height - 40);  // clear of the tools, labels and scale bar
    return { occupied: at(view.rasterCells()), free: at(view.rasterCells(true)), scale: view.scale };
  });
  const grey = ([px, py]) => zoomed.data[(Math.floor(py) * zoomed.width + Math.floor(px)) * 4];
  const dark = samples.occupied.filter((p) => grey(p) < 90).length;
  const light = samples.free.filter((p) => grey(p) > 160).length;
  console.log(`     zoomed to ${samples.scale.toFixed(1)} px/m: ${dark} of ${samples.occupied.length} occupied cells dark, ` +
              `${light} of ${samples.free.length} free cells light`);
  check(samples.occupied.length > 20 && dark >= 0.95 * samples.occupied.length, 'occupied cells are drawn dark');
  check(samples.free.length > 100 && light >= 0.95 * samples.free.length, 'free cells are drawn light');

  // 5. Reset, after a confirmation.
  const versionBefore = await page.evaluate(() => sonarmapPage.rasterInfo.v);
  await page.click('#reset');
  check(await page.isVisible('#confirm-reset'), '"Reset map" asks first');
  await page.click('#confirm-reset-no');
  check(!(await page.isVisible('#confirm-reset')) && (await page.evaluate(() => sonarmapPage.rasterInfo.v)) === versionBefore,
        'cancelling leaves the map');
  await page.click('#reset');
  await page.click('#confirm-reset-yes');
  await until(page, (v) => document.getElementById('action-result').textContent === 'Map reset.' &&
                sonarmapPage.rasterInfo.v > v && sonarmapPage.view.rasterCells().length === 0, versionBefore,
              'the map is empty after "Reset map"');
  const after = await session.command('feed 12');
  await until(page, (last) => sonarmapPage.lastDrawnSeq === last, after.last, 'the fan goes on after a reset');
  check((await page.evaluate(() => sonarmapPage.view.rasterCells().length)) === 0,
        'the new map stays empty until its first sweep is calibrated');
  await until(page, () => document.getElementById('lag').textContent === 'calibrating on the first sweep' &&
                document.getElementById('waiting').textContent.endsWith('(first sweep)'), null,
              'the page says the new map is calibrating on its first sweep, not lagging');

  // 6. 400 px wide in an iframe under BlueOS's prefix, and by long polling.
  const proxy = new Proxy(base, '/extensionv2/sonarmap/');
  const proxyBase = await proxy.listen();
  const host = await context.newPage();
  await host.goto(proxyBase);
  const frame = host.frameLocator('iframe');
  await frame.locator('#map').waitFor();
  const framed = host.frames().find((f) => f.url().includes('/extensionv2/sonarmap'));
  const fedFramed = await session.command('feed 6');
  await until(framed, (last) => window.sonarmapPage && sonarmapPage.lastDrawnSeq === last, fedFramed.last,
              'the framed page under the prefix draws the beams');
  const layout = await framed.evaluate(() => {
    const box = (id) => document.getElementById(id).getBoundingClientRect();
    const inView = (id) => box(id).bottom <= window.innerHeight && box(id).right <= window.innerWidth && box(id).top >= 0;
    return {
      scrollWidth: document.documentElement.scrollWidth,
      canvas: [box('map').width, box('map').height],
      save: box('save').right,
      inView: ['rate', 'lag', 'waiting', 'save', 'reset', 'warnings'].filter(inView),
      toolbar: document.querySelector('.tools').getBoundingClientRect().height,
      transport: sonarmapPage.transport,
    };
  });
  check(layout.scrollWidth <= 400 && layout.canvas[0] >= 380 && layout.save <= 400,
        `it fits 400 px (scroll width ${layout.scrollWidth}, canvas ${layout.canvas[0]}, Save's right edge ${layout.save})`);
  check(layout.inView.length === 6 && layout.canvas[1] >= 120 && layout.toolbar <= 34,
        `in a 400 × 300 px frame the rate, lag, waiting beams, Save, Reset and warnings are in view ` +
        `(${layout.inView}), over a map ${layout.canvas[1]} px tall, a toolbar ${layout.toolbar} px tall`);
  check(layout.transport === 'events', `its event stream passes the proxy (${layout.transport})`);
  check(proxy.outsidePrefix.length === 0, `every request stayed under the prefix (${proxy.outsidePrefix})`);
  await host.screenshot({ path: path.join(work, 'iframe.png') });

  const polling = await context.newPage();
  await polling.addInitScript(() => { delete window.EventSource; });
  await polling.goto(base);
  await until(polling, () => window.sonarmapPage && sonarmapPage.updates > 0, null, 'the polling page gets its first update');
  const fedPolled = await session.command('feed 6');
  await until(polling, (last) => sonarmapPage.transport === 'polling' && sonarmapPage.lastDrawnSeq === last, fedPolled.last,
              'without EventSource the page polls and draws the beams');

  check(errors.length === 0, `no script errors (${errors.join(' | ')})`);
  const acks = aborted.filter((entry) => entry.includes('/ack'));
  check(acks.length === 0, `no acknowledgement aborted by the browser (${acks.length}: ${acks.slice(0, 3)})`);
  const bye = await session.command('quit');
  console.log(`     the server stopped in ${bye.stop_ms.toFixed(1)} ms with 3 pages open`);
  check(bye.stop_ms < 1000, 'the server stops promptly with pages connected');
  await browser.close();
  proxy.close();
  console.log(failures ? `${failures} checks failed` : 'all checks passed');
  process.exit(failures ? 1 : 0);
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
