// Frames per second of the page in headless Chromium (one thread: the module has none), at
// 1280x720, while orbiting: every frame moves the camera 1 degree about the look point, then
// renders (Views::render: the per-view setup and the trace), shades, and puts the pixels on
// the canvas, as a drag does. Prints a Markdown table; with the native binary (LANECAST_BIN,
// else target/release/lanecast) also the command line's one-thread render of the scene's own
// frame (`--threads 1 --repeat 20`, best render phase).
//
// Needs web/build.sh --test. Usage: node web/bench.mjs [FRAMES] (default 120 per scene)
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const web = path.dirname(fileURLToPath(import.meta.url));
const root = path.dirname(web);
const dist = path.join(web, 'dist');
const frames = Number(process.argv[2] || 120);
const bin = path.resolve(root, process.env.LANECAST_BIN || 'target/release/lanecast');
const [W, H] = [1280, 720];
if (!fs.existsSync(path.join(dist, 'lanecast.wasm'))) {
  console.error('web/dist is missing: run web/build.sh --test');
  process.exit(1);
}

const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm', '.json': 'application/json' };
const server = http.createServer((req, res) => {
  const p = new URL(req.url, 'http://x').pathname;
  const file = path.join(dist, p === '/' ? 'index.html' : decodeURIComponent(p));
  if (!file.startsWith(dist) || !fs.existsSync(file)) return res.writeHead(404).end();
  res.writeHead(200, { 'content-type': TYPES[path.extname(file)] ?? 'application/octet-stream' });
  fs.createReadStream(file).pipe(res);
});
await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
const page = await browser.newPage({ viewport: { width: W + 300, height: H }, deviceScaleFactor: 1 });
await page.goto(`http://127.0.0.1:${server.address().port}/`);
await page.waitForFunction(() => window.lanecastApp?.ready);
// the canvas, beside the panel (300 pixels), W x H
await page.waitForFunction(([w, h]) => {
  const c = document.getElementById('view');
  return c.width === w && c.height === h;
}, [W, H]);
const menu = JSON.parse(fs.readFileSync(path.join(dist, 'scenes', 'menu.json'), 'utf8'));

/**
 * The native command line on one thread: the best render phase of the scene's own frame
 * (`--repeat 20`), and the median view of a 12-view `--orbit` (per-view setup + render, as
 * the page's orbit does), in ms.
 */
function native(file) {
  if (!fs.existsSync(bin)) return null;
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'lanecast-bench-'));
  const stats = path.join(dir, 's.json');
  const run = (args) => {
    const r = spawnSync(bin, ['-i', `scenes/${file}`, '-size', `${W}x${H}`, '--threads', '1', '--stats', stats, ...args], { cwd: root, encoding: 'utf8' });
    return r.status === 0 ? JSON.parse(fs.readFileSync(stats, 'utf8')) : null;
  };
  try {
    const one = run(['--repeat', '20', '-o', path.join(dir, 'x.png')]);
    // every output into the temp folder: without -o the images would land beside the scene
    const orbit = run(['--orbit', '12', '--ids', path.join(dir, 'i_%05d.npy'), '-o', path.join(dir, 'v_%05d.bmp')]);
    const each = orbit?.views?.each?.map((v) => (v.setup_s + v.render_s) * 1e3).sort((x, y) => x - y);
    return { render: one ? one.render_best_s * 1e3 : null, view: each ? each[Math.floor(each.length / 2)] : null };
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
}

console.log(`load average before: ${os.loadavg().map((x) => x.toFixed(2)).join(' ')} on ${os.cpus().length} CPUs (${os.cpus()[0].model})`);
console.log(`| scene | primitives | frame ms (median / p95) | fps (1000 / median) | render ms (median) | native 1-thread: render ms / orbit view ms |`);
console.log(`|---|---:|---:|---:|---:|---:|`);
for (const m of menu) {
  await page.selectOption('#scene', m.name);
  await page.waitForFunction((f) => window.lanecastApp.sceneName === f && !window.lanecastApp.dirty, m.file, { timeout: 60000 });
  const r = await page.evaluate((n) => {
    const app = window.lanecastApp;
    const step = Math.PI / 180;
    const once = () => {
      const c = app.camera;
      const [ox, oy, oz] = c.eye.map((v, k) => v - c.look[k]);
      // 1 degree about the scene's up axis (y in every bundled scene)
      const [cs, sn] = [Math.cos(step), Math.sin(step)];
      c.eye = [c.look[0] + cs * ox + sn * oz, c.look[1] + oy, c.look[2] - sn * ox + cs * oz];
      app.dirty = true;
      const t0 = performance.now();
      const drew = app.frame();
      return [performance.now() - t0, app.last.renderMs, drew];
    };
    for (let k = 0; k < 5; k++) once(); // warm up
    const t = [], rt = [];
    let refused = 0;
    for (let k = 0; k < n; k++) {
      const [f, r, drew] = once();
      if (!drew) {
        refused++; // a view the engine refuses: not a frame
        continue;
      }
      t.push(f);
      rt.push(r);
    }
    app.camera = structuredClone(app.home);
    app.dirty = true;
    const q = (a, p) => [...a].sort((x, y) => x - y)[Math.floor(p * (a.length - 1))];
    return { median: q(t, 0.5), p95: q(t, 0.95), render: q(rt, 0.5), prims: app.lc.scene.primitives, refused };
  }, frames);
  const nat = native(m.file);
  console.log(`| ${m.name}${r.refused ? ` (${r.refused} of ${frames} views refused)` : ''} | ${r.prims} | ${r.median.toFixed(2)} / ${r.p95.toFixed(2)} | ${(1000 / r.median).toFixed(0)} | ${r.render.toFixed(2)} | ${nat?.render?.toFixed(2) ?? 'n/a'} / ${nat?.view?.toFixed(2) ?? 'n/a'} |`);
}
console.log(`load average after: ${os.loadavg().map((x) => x.toFixed(2)).join(' ')}`);
await browser.close();
server.close();
