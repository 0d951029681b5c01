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
const page = await browser.newPage({ viewport: { width: W, height: H }, deviceScaleFactor: 1 });
await page.goto(`http://127.0.0.1:${server.address().port}/`);
await page.waitForFunction(() => window.lanecastApp?.ready);
const menu = JSON.parse(fs.readFileSync(path.join(dist, 'scenes', 'menu.json'), 'utf8'));

/** The native command line's best one-thread render phase for the scene's frame, in ms. */
function native(file) {
  if (!fs.existsSync(bin)) return null;
  const stats = path.join(os.tmpdir(), `lanecast-bench-${process.pid}.json`);
  const r = spawnSync(bin, ['-i', `scenes/${file}`, '-size', `${W}x${H}`, '--threads', '1', '--repeat', '20', '--stats', stats], { cwd: root, encoding: 'utf8' });
  if (r.status !== 0) return null;
  const s = JSON.parse(fs.readFileSync(stats, 'utf8'));
  fs.rmSync(stats, { force: true });
  const best = s.render_best_s ?? s.timings?.render_best_s;
  return best != null ? best * 1e3 : null;
}

console.log(`| scene | primitives | frame ms (mean / p95) | fps | render ms (mean) | native 1-thread render ms |`);
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
      app.frame();
      return [performance.now() - t0, app.last.renderMs];
    };
    for (let k = 0; k < 5; k++) once(); // warm up
    const t = [], rt = [];
    for (let k = 0; k < n; k++) {
      const [f, r] = once();
      t.push(f);
      rt.push(r);
    }
    app.camera = structuredClone(app.home);
    app.dirty = true;
    const mean = (a) => a.reduce((x, y) => x + y, 0) / a.length;
    const sorted = [...t].sort((a, b) => a - b);
    return { mean: mean(t), p95: sorted[Math.floor(0.95 * (sorted.length - 1))], render: mean(rt), prims: app.lc.scene.primitives };
  }, frames);
  const nat = native(m.file);
  console.log(`| ${m.name} | ${r.prims} | ${r.mean.toFixed(2)} / ${r.p95.toFixed(2)} | ${(1000 / r.mean).toFixed(0)} | ${r.render.toFixed(2)} | ${nat == null ? 'n/a' : nat.toFixed(2)} |`);
}
await browser.close();
server.close();
