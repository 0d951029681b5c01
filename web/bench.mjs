// Frames per second of the page in headless Chromium (one thread: the module has none), at
// 1280x720, while orbiting: every frame moves the camera 1 degree about the look point and
// waits for the page to draw it, as a drag does: the render (in the worker), the shading, the
// pixels moved to the page and put on the canvas. The page renders by the per-eye path
// (`tiles`: `--accel auto`), by the world engine (`world`) and by its own choice (`auto`); with
// --before DIST also an older build of the page (DIST: its web/dist), in the same run. The
// programs alternate in rounds of FRAMES/3 frames, after 5 frames of warm-up each; the table
// gives the median frame over all rounds. Prints a Markdown table.
//
// The scenes: scenes/armadillo.sc (52,000 triangles) and, with --mesh OBJ, the same scene with
// OBJ as its mesh (the 832k armadillo: `python3 scripts/subdivide.py
// scenes/meshes/armadillo.obj target/scale/armadillo_2.obj 2`), opened as a user opens files.
//
// Needs web/build.sh --test. Usage:
//   node web/bench.mjs [FRAMES] [--mesh OBJ] [--before DIST]      (FRAMES: default 60, at least 3)
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const web = path.dirname(fileURLToPath(import.meta.url));
const root = path.dirname(web);
const args = process.argv.slice(2);
const flag = (name) => {
  const k = args.indexOf(name);
  if (k < 0) return null;
  const v = args[k + 1];
  args.splice(k, 2);
  if (v == null) usage(`${name} takes a value`);
  return v;
};
function usage(why) {
  console.error(`web/bench.mjs: ${why}\nusage: node web/bench.mjs [FRAMES] [--mesh OBJ] [--before DIST]`);
  process.exit(2);
}
const mesh = flag('--mesh');
const beforeDist = flag('--before');
const frames = Number(args[0] ?? 60);
if (!Number.isInteger(frames) || frames < 3) usage(`FRAMES ${args[0]}: not a whole number of at least 3`);
const [W, H] = [1280, 720];
const ROUNDS = 3;
const dists = { after: path.join(web, 'dist') };
if (beforeDist) dists.before = path.resolve(beforeDist);
for (const [name, d] of Object.entries(dists)) {
  if (!fs.existsSync(path.join(d, 'lanecast.wasm'))) usage(`${d}: no lanecast.wasm (the ${name} page; run web/build.sh --test)`);
}
if (mesh && !fs.existsSync(mesh)) usage(`--mesh ${mesh}: no such file`);

const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm', '.json': 'application/json' };
/** A static server over `dist`. */
async function serve(dist) {
  const server = http.createServer((req, res) => {
    const p = new URL(req.url, 'http://x').pathname;
    const file = path.join(dist, p === '/' ? 'index.html' : decodeURIComponent(p));
    if (!file.startsWith(dist) || !fs.existsSync(file)) return res.writeHead(404).end();
    res.writeHead(200, { 'content-type': TYPES[path.extname(file)] ?? 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  return server;
}

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
const servers = [];
/** A page of `dist`, its canvas W x H beside the panel (300 pixels). */
async function open(dist) {
  const server = await serve(dist);
  servers.push(server);
  const page = await browser.newPage({ viewport: { width: W + 300, height: H }, deviceScaleFactor: 1 });
  await page.goto(`http://127.0.0.1:${server.address().port}/`);
  await page.waitForFunction(() => window.lanecastApp?.ready);
  await page.waitForFunction(([w, h]) => {
    const c = document.getElementById('view');
    return c.width === w && c.height === h;
  }, [W, H]);
  return page;
}

/** Opens scenes/armadillo.sc with `obj` as its mesh in `page`, as a user picks files. */
async function openScene(page, obj) {
  const sc = fs.readFileSync(path.join(root, 'scenes/armadillo.sc'));
  await page.setInputFiles('#file', [
    { name: 'armadillo.sc', mimeType: 'text/plain', buffer: sc },
    { name: 'armadillo.obj', mimeType: 'text/plain', buffer: fs.readFileSync(obj) },
  ]);
  await page.waitForFunction(() => window.lanecastApp.sceneName === 'armadillo.sc' && !window.lanecastApp.dirty, null, { timeout: 300000 });
}

/**
 * `n` frames of the orbit in `page` (by `engine` where the page has a choice): each frame's
 * milliseconds, from the camera's move to the frame on the canvas.
 */
function orbit(page, engine, n) {
  return page.evaluate(async ([engine, n]) => {
    const app = window.lanecastApp;
    if (engine) await app.lc.setEngine(engine);
    const step = Math.PI / 180;
    const once = async () => {
      const c = app.camera;
      const [ox, oy, oz] = c.eye.map((v, k) => v - c.look[k]);
      // 1 degree about the scene's up axis (y)
      const [cs, sn] = [Math.cos(step), Math.sin(step)];
      c.eye = [c.look[0] + cs * ox + sn * oz, c.look[1] + oy, c.look[2] - sn * ox + cs * oz];
      app.dirty = true;
      const t0 = performance.now();
      const drew = await app.frame(); // the older page's frame() draws before it returns
      return [performance.now() - t0, drew, app.engine ?? 'tiles'];
    };
    for (let k = 0; k < 5; k++) await once(); // warm up: the first frame prepares the scene
    const t = [];
    let refused = 0, used = '';
    for (let k = 0; k < n; k++) {
      const [ms, drew, e] = await once();
      if (!drew) refused++; // a view the engine refuses: not a frame
      else t.push(ms);
      used = e;
    }
    return { t, refused, used, prims: app.lc.scene.primitives };
  }, [engine, n]);
}

const programs = [
  ...(dists.before ? [['before', 'before', null]] : []),
  ['tiles', 'after', 'tiles'],
  ['world', 'after', 'world'],
  ['auto', 'after', 'auto'],
];
const pages = {};
for (const name of Object.keys(dists)) pages[name] = await open(dists[name]);
const scenes = [['armadillo (52k)', path.join(root, 'scenes/meshes/armadillo.obj')]];
if (mesh) scenes.push([`armadillo (${path.basename(mesh)})`, mesh]);

const q = (a, p) => [...a].sort((x, y) => x - y)[Math.floor(p * (a.length - 1))];
console.log(`${os.cpus().length} CPUs (${os.cpus()[0].model}); load average before: ${os.loadavg().map((x) => x.toFixed(2)).join(' ')}`);
console.log(`${W}x${H}, ${frames} frames a program in ${ROUNDS} alternating rounds; frame: camera moved to frame on the canvas`);
console.log('| scene | primitives | program | engine | frame ms (median / p95) | fps (1000 / median) |');
console.log('|---|---:|---|---|---:|---:|');
for (const [label, obj] of scenes) {
  for (const p of Object.values(pages)) await openScene(p, obj);
  const got = Object.fromEntries(programs.map(([name]) => [name, { t: [], refused: 0 }]));
  for (let round = 0; round < ROUNDS; round++) {
    const n = Math.ceil(frames / ROUNDS);
    for (const [name, page, engine] of programs) {
      const r = await orbit(pages[page], engine, n);
      Object.assign(got[name], { used: r.used, prims: r.prims });
      got[name].t.push(...r.t);
      got[name].refused += r.refused;
    }
  }
  for (const [name] of programs) {
    const g = got[name];
    const m = q(g.t, 0.5);
    const refused = g.refused ? ` (${g.refused} views refused)` : '';
    console.log(`| ${label}${refused} | ${g.prims} | ${name} | ${g.used} | ${m.toFixed(1)} / ${q(g.t, 0.95).toFixed(1)} | ${(1000 / m).toFixed(1)} |`);
  }
}
console.log(`load average after: ${os.loadavg().map((x) => x.toFixed(2)).join(' ')}`);
await browser.close();
for (const s of servers) s.close();
