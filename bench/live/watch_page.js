// Opens the page of a running `sonarmap live --serve` in Debian's headless Chromium (playwright-core
// from tests/live/node_modules, `npm ci` there) for a while, as a pilot's browser would, and prints
// what the server measured of it: beam arrival → pixels for the fan and for the map (GET /latency),
// as one JSON line. The latencies are reset once the page has shown its first map, so the first
// sweep's calibration wait is not counted.
//
//   node bench/live/watch_page.js URL SECONDS [CHROMIUM]
'use strict';
const path = require('path');
const http = require('http');
const { chromium } = require(path.join(__dirname, '..', '..', 'tests', 'live', 'node_modules', 'playwright-core'));

const [url, seconds, executable = '/usr/bin/chromium'] = process.argv.slice(2);

function request(method, address) {
  return new Promise((resolve, reject) => {
    const r = http.request(address, { method, headers: { 'X-Sonarmap': '1' } }, (response) => {
      let body = '';
      response.on('data', (chunk) => { body += chunk; });
      response.on('end', () => resolve(body));
    });
    r.on('error', reject);
    r.end();
  });
}

(async () => {
  const browser = await chromium.launch({
    executablePath: executable,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync'],
  });
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  await page.goto(url);
  // The first map picture: from then on every beam is shown as it arrives.
  for (let i = 0; i < 1200; i++) {
    const state = JSON.parse(await request('GET', new URL('latency', url)));
    if (state.map && state.map.count > 0) break;
    await new Promise((done) => setTimeout(done, 100));
  }
  await request('POST', new URL('latency/reset', url));
  await new Promise((done) => setTimeout(done, Number(seconds) * 1000));
  console.log(await request('GET', new URL('latency', url)));
  await browser.close();
})().catch((error) => { console.error(error); process.exit(1); });
