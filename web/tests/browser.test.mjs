// The page in a real browser: Debian's chromium, headless, driven by playwright-core, against
// web/dist served on 127.0.0.1. Loads scene1 and compares the canvas with the native command
// line's PNG of the same frame, pixel for pixel; orbits by dragging and checks the picture
// changed (and R restores it); clicks the top sphere and checks the pinned id and depth against
// the native --ids and --depth; drops a bad file and checks the command line's message (the
// scene stays); drops a scene with its mesh. Screenshots go to web/screenshots/.
//
// Needs web/build.sh --test to have run (chromium, node_modules), and the native binary:
// LANECAST_BIN, else target/release/lanecast. CHROMIUM overrides /usr/bin/chromium.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const web = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const root = path.dirname(web);
const dist = path.join(web, 'dist');
const shots = path.join(web, 'screenshots');
const bin = path.resolve(root, process.env.LANECAST_BIN || path.join('target', 'release', 'lanecast'));
const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';
for (const [what, p, how] of [
  ['the page', path.join(dist, 'index.html'), 'run web/build.sh'],
  ['the native binary', bin, 'run cargo build --release, or set LANECAST_BIN'],
  ['chromium', executablePath, 'run web/build.sh --test (apt-get install chromium)'],
]) {
  if (!fs.existsSync(p)) throw new Error(`${what} is missing: ${p} (${how})`);
}
fs.mkdirSync(shots, { recursive: true });
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'lanecast-browser-'));

const W = 640, H = 400;
const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm', '.json': 'application/json' };

/** A static server over web/dist, as any static host (or python3 -m http.server) serves it. */
function serve() {
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://x');
    const file = path.join(dist, decodeURIComponent(url.pathname === '/' ? '/index.html' : url.pathname));
    if (!file.startsWith(dist) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { 'content-type': TYPES[path.extname(file)] ?? 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  return new Promise((ok) => server.listen(0, '127.0.0.1', () => ok(server)));
}

/** The native command line on `scene`: the PNG's bytes, ids and depths at W x H. */
function native(scene, extra = []) {
  const out = (n) => path.join(tmp, n);
  const r = spawnSync(bin, ['-i', scene, '-size', `${W}x${H}`, '-o', out('n.png'), '--ids', out('i.npy'), '--depth', out('d.npy'), ...extra], { cwd: root, encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  const body = (f) => {
    const b = fs.readFileSync(f);
    return b.subarray(10 + b.readUInt16LE(8));
  };
  const i = body(out('i.npy')), d = body(out('d.npy'));
  return {
    png: fs.readFileSync(out('n.png')),
    ids: new Int32Array(i.buffer, i.byteOffset, W * H),
    depth: new Float32Array(d.buffer.slice(d.byteOffset, d.byteOffset + 4 * W * H)),
  };
}

let server, browser, page, base;
before(async () => {
  server = await serve();
  base = `http://127.0.0.1:${server.address().port}/`;
  browser = await chromium.launch({
    executablePath,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  page = await browser.newPage({ viewport: { width: W, height: H }, deviceScaleFactor: 1 });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(`${base}?scene=scene1`);
  await page.waitForFunction(() => window.lanecastApp?.ready && window.lanecastApp.frames > 0, null, { timeout: 30000 });
  await page.evaluate(() => {
    window.btoaBytes = (a) => {
      const u = new Uint8Array(a.buffer, a.byteOffset, a.byteLength);
      let s = '';
      for (let k = 0; k < u.length; k += 0x8000) s += String.fromCharCode(...u.subarray(k, k + 0x8000));
      return btoa(s);
    };
  });
  assert.deepEqual(errors, []);
});
after(async () => {
  await browser?.close();
  server?.close();
  fs.rmSync(tmp, { recursive: true, force: true });
});

/** Keeps a copy of the canvas's RGBA pixels in the page as `name` (big arrays stay there). */
const snap = (name) => page.evaluate((name) => {
  const c = document.getElementById('view');
  (window.snaps ??= {})[name] = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
  return window.snaps[name].length;
}, name);
/** How many bytes differ between two snapshots. */
const differing = (a, b) => page.evaluate(([a, b]) => {
  const [x, y] = [window.snaps[a], window.snaps[b]];
  let n = x.length === y.length ? 0 : Infinity;
  for (let k = 0; k < x.length; k++) n += x[k] !== y[k];
  return n;
}, [a, b]);
/** Waits until the page has drawn a frame after `fn`. */
async function drawn(fn) {
  const n = await page.evaluate(() => window.lanecastApp.frames);
  await fn();
  await page.waitForFunction((k) => window.lanecastApp.frames > k, n, { timeout: 10000 });
}

test('the canvas shows scene1 as the command line renders it, pixel for pixel', async () => {
  const size = await page.evaluate(() => [document.getElementById('view').width, document.getElementById('view').height]);
  assert.deepEqual(size, [W, H]);
  const want = native('scenes/scene1.sc');
  // the browser decodes the command line's PNG
  await page.evaluate(async (b64) => {
    const blob = await (await fetch(`data:image/png;base64,${b64}`)).blob();
    const bmp = await createImageBitmap(blob);
    const c = new OffscreenCanvas(bmp.width, bmp.height);
    const g = c.getContext('2d');
    g.drawImage(bmp, 0, 0);
    (window.snaps ??= {}).native = g.getImageData(0, 0, bmp.width, bmp.height).data;
  }, want.png.toString('base64'));
  assert.equal(await snap('first'), W * H * 4);
  assert.equal(await differing('first', 'native'), 0, 'canvas differs from the native PNG');
  const ids = Buffer.from(await page.evaluate(() => window.btoaBytes(window.lanecastApp.lc.ids())), 'base64');
  assert.ok(ids.equals(Buffer.from(want.ids.buffer, want.ids.byteOffset, 4 * W * H)), 'ids differ from --ids');
  const seen = want.ids.filter((i) => i >= 0).length;
  assert.ok(seen > W * H * 0.05, `the scene covers ${seen} pixels`);
  const stats = await page.textContent('#stats');
  assert.match(stats, /frame [\d.]+ ms/);
  assert.match(stats, /Mrays\/s/);
  await page.screenshot({ path: path.join(shots, 'scene1.png') });
});

test('clicking the top sphere pins id 5 with the native depth there', async () => {
  const want = native('scenes/scene1.sc');
  // the centre of the top sphere's pixels (id 5) in the native frame
  let sx = 0, sy = 0, n = 0;
  want.ids.forEach((id, k) => {
    if (id === 5) { sx += k % W; sy += Math.floor(k / W); n++; }
  });
  assert.ok(n > 100, `the top sphere covers ${n} pixels`);
  const [x, y] = [Math.round(sx / n), Math.round(sy / n)];
  assert.equal(want.ids[y * W + x], 5);
  await page.mouse.move(x, y);
  await page.waitForFunction(() => window.lanecastApp.hover === 5);
  await drawn(() => page.mouse.click(x, y));
  assert.equal(await page.getAttribute('#pinned', 'data-id'), '5');
  const text = await page.textContent('#pinned');
  assert.match(text, /id 5\s+sphere\s+scene line (\d+)/);
  const line = Number(text.match(/scene line (\d+)/)[1]);
  const sceneLines = fs.readFileSync(path.join(root, 'scenes/scene1.sc'), 'utf8').split('\n');
  assert.match(sceneLines[line - 1], /^sphere 0 6 0 1/);
  const depth = Number(text.match(/depth (\S+)/)[1]);
  assert.equal(Math.fround(depth), want.depth[y * W + x], `${text} vs ${want.depth[y * W + x]}`);
  // highlighted: the pinned sphere's pixels changed, nothing else did
  await snap('lit');
  const [inside, outside] = await page.evaluate(() => {
    const [a, b] = [window.snaps.first, window.snaps.lit];
    const ids = window.lanecastApp.lc.ids();
    let inside = 0, outside = 0;
    for (let k = 0; k < ids.length; k++) {
      const d = a[4 * k] !== b[4 * k] || a[4 * k + 1] !== b[4 * k + 1] || a[4 * k + 2] !== b[4 * k + 2];
      if (d && ids[k] === 5) inside++;
      if (d && ids[k] !== 5) outside++;
    }
    return [inside, outside];
  });
  assert.ok(inside > n / 2, `${inside} of ${n} sphere pixels highlighted`);
  assert.equal(outside, 0);
  await page.screenshot({ path: path.join(shots, 'pinned.png') });
});

test('dragging orbits the camera, and R resets it', async () => {
  await page.mouse.move(10, 390); // off the scene's primitives: no hover highlight
  await page.evaluate(() => window.lanecastApp.frame());
  await snap('before');
  const cam0 = await page.evaluate(() => structuredClone(window.lanecastApp.camera));
  // right of the control panel
  await page.mouse.move(420, 250);
  await page.mouse.down();
  for (let k = 1; k <= 8; k++) await page.mouse.move(420 + 15 * k, 250 - 4 * k);
  await page.mouse.up();
  await page.evaluate(() => window.lanecastApp.frame());
  const cam1 = await page.evaluate(() => structuredClone(window.lanecastApp.camera));
  assert.notDeepEqual(cam1.eye, cam0.eye);
  assert.deepEqual(cam1.look, cam0.look, 'orbiting keeps the look point');
  const dist = (c) => Math.hypot(...c.eye.map((v, k) => v - c.look[k]));
  assert.ok(Math.abs(dist(cam1) - dist(cam0)) < 1e-9 * dist(cam0), 'orbiting keeps the distance');
  await snap('after');
  const changed = (await differing('after', 'before')) / (W * H * 4);
  assert.ok(changed > 0.05, `only ${(changed * 100).toFixed(1)}% of the picture changed`);
  assert.match(await page.inputValue('#camline'), /^camera eye \S+ \S+ \S+ look -0\.69 1\.77 0\.87 up 0 1 0 fov 60$/);
  await page.screenshot({ path: path.join(shots, 'orbit.png') });
  await page.mouse.move(10, 390);
  await page.keyboard.press('r');
  await page.evaluate(() => window.lanecastApp.frame());
  assert.deepEqual(await page.evaluate(() => window.lanecastApp.camera), cam0);
  await snap('reset');
  assert.equal(await differing('reset', 'before'), 0, 'R restores the picture');
});

/** Drops files (name -> text) on the page as a drag-and-drop from the desktop does. */
async function drop(files) {
  await page.evaluate((files) => {
    const dt = new DataTransfer();
    for (const [name, text] of Object.entries(files)) dt.items.add(new File([text], name));
    window.dispatchEvent(new DragEvent('dragenter', { dataTransfer: dt, bubbles: true }));
    window.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, files);
}

test('a dropped bad file shows the command line\'s FILE:LINE:COL message and the scene stays', async () => {
  const bad = 'camera eye 0 0 5 look 0 0 0 up 0 1 0\nsphere 0 0 0 1\ntriangle 0 0 0  1 0 0  0 1 zero\n';
  fs.writeFileSync(path.join(tmp, 'bad.sc'), bad);
  const r = spawnSync(bin, ['-i', 'bad.sc', '-size', '8x8', '-o', 'x.png'], { cwd: tmp, encoding: 'utf8' });
  assert.notEqual(r.status, 0);
  await snap('kept');
  await drop({ 'bad.sc': bad });
  await page.waitForFunction(() => !document.getElementById('error').hidden);
  const msg = await page.textContent('#error');
  assert.match(msg, /^bad\.sc:3:\d+: /);
  assert.ok(r.stderr.includes(msg), `CLI: ${r.stderr}\npage: ${msg}`);
  assert.equal(await page.evaluate(() => window.lanecastApp.sceneName), 'scene1.sc');
  await page.evaluate(() => window.lanecastApp.frame());
  await snap('still');
  assert.equal(await differing('still', 'kept'), 0, 'the previous scene is still shown');
  await page.screenshot({ path: path.join(shots, 'error.png') });
});

test('a dropped scene takes its mesh dropped with it', async () => {
  const sc = fs.readFileSync(path.join(root, 'scenes/teapot.sc'), 'utf8');
  const obj = fs.readFileSync(path.join(root, 'scenes/meshes/teapot.obj'), 'utf8');
  await drawn(() => drop({ 'teapot.sc': sc, 'teapot.obj': obj }));
  assert.equal(await page.evaluate(() => window.lanecastApp.sceneName), 'teapot.sc');
  assert.equal(await page.isHidden('#error'), true);
  const want = native('scenes/teapot.sc');
  const ids = Buffer.from(await page.evaluate(() => window.btoaBytes(window.lanecastApp.lc.ids())), 'base64');
  assert.ok(ids.equals(Buffer.from(want.ids.buffer, want.ids.byteOffset, 4 * W * H)), 'ids differ from --ids');
  await page.screenshot({ path: path.join(shots, 'teapot.png') });
});

test('Export PNG saves the frame; the camera line is one a scene accepts', async () => {
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#png')]);
  const file = path.join(tmp, 'export.png');
  await download.saveAs(file);
  const png = fs.readFileSync(file);
  assert.equal(png.subarray(1, 4).toString('latin1'), 'PNG');
  assert.deepEqual([png.readUInt32BE(16), png.readUInt32BE(20)], [W, H]); // IHDR
  // after an orbit, the camera line pasted into the scene renders the view the page shows
  await page.mouse.move(420, 250);
  await page.mouse.down();
  for (let k = 1; k <= 5; k++) await page.mouse.move(420 - 12 * k, 250 + 3 * k);
  await page.mouse.up();
  await page.evaluate(() => window.lanecastApp.frame());
  const line = await page.inputValue('#camline');
  const nums = line.split(/\s+/).filter((w) => /^[-+\d.]/.test(w)).map(Number);
  assert.equal(nums.length, 10, line);
  const cam = await page.evaluate(() => window.lanecastApp.camera);
  [...cam.eye, ...cam.look, ...cam.up, cam.fov].forEach((v, k) => {
    assert.ok(Math.abs(v - nums[k]) <= 1e-6 * Math.max(1, Math.abs(v)), `${line} vs ${v}`);
  });
  const obj = path.join(root, 'scenes/meshes/teapot.obj');
  const sc = fs.readFileSync(path.join(root, 'scenes/teapot.sc'), 'utf8').replace(/^camera .*$/m, line).replace(/^mesh .*$/m, `mesh ${obj}`);
  fs.writeFileSync(path.join(tmp, 'pasted.sc'), sc);
  await page.evaluate((n) => {
    const app = window.lanecastApp;
    app.camera = { eye: n.slice(0, 3), look: n.slice(3, 6), up: n.slice(6, 9), fov: n[9] };
    app.dirty = true;
    app.frame();
  }, nums);
  const want = native(path.join(tmp, 'pasted.sc'));
  const ids = Buffer.from(await page.evaluate(() => window.btoaBytes(window.lanecastApp.lc.ids())), 'base64');
  assert.ok(ids.equals(Buffer.from(want.ids.buffer, want.ids.byteOffset, 4 * W * H)), 'the pasted camera renders another view');
  assert.ok(want.ids.some((i) => i >= 0));
});

test('the file picker opens a bare .obj with its framing camera, as -i x.obj does', async () => {
  const obj = fs.readFileSync(path.join(root, 'scenes/meshes/bunny.obj'));
  await page.setInputFiles('#file', [{ name: 'bunny.obj', mimeType: 'text/plain', buffer: obj }]);
  await page.waitForFunction(() => window.lanecastApp.sceneName === 'bunny.obj' && !window.lanecastApp.dirty);
  await page.evaluate(() => window.lanecastApp.frame());
  const want = native('scenes/meshes/bunny.obj');
  const ids = Buffer.from(await page.evaluate(() => window.btoaBytes(window.lanecastApp.lc.ids())), 'base64');
  assert.ok(ids.equals(Buffer.from(want.ids.buffer, want.ids.byteOffset, 4 * W * H)), 'ids differ from --ids');
  await page.screenshot({ path: path.join(shots, 'bunny-obj.png') });
});

test('the colour controls shade as -cm, -cv and --seed do', async () => {
  await page.mouse.move(5, 395);
  await page.selectOption('#scene', 'scene4');
  await page.waitForFunction(() => window.lanecastApp.sceneName === 'scene4.sc' && !window.lanecastApp.dirty);
  for (const [mode, variation, seed, flags] of [
    ['ordered', 'log', '0', ['-cm', 'ordered', '-cv', 'log']],
    ['random', 'log', '7', ['-cv', 'log', '--seed', '7']],
    ['random', 'linear', '0', []],
  ]) {
    await page.selectOption('#mode', mode);
    await page.selectOption('#variation', variation);
    await page.fill('#seed', seed);
    await page.evaluate(() => { window.lanecastApp.reshade = true; window.lanecastApp.frame(); });
    const want = native('scenes/scene4.sc', flags);
    await page.evaluate(async (b64) => {
      const bmp = await createImageBitmap(await (await fetch(`data:image/png;base64,${b64}`)).blob());
      const g = new OffscreenCanvas(bmp.width, bmp.height).getContext('2d');
      g.drawImage(bmp, 0, 0);
      window.snaps.native = g.getImageData(0, 0, bmp.width, bmp.height).data;
    }, want.png.toString('base64'));
    await snap('controls');
    assert.equal(await differing('controls', 'native'), 0, `${flags.join(' ')}: canvas differs from the CLI's PNG`);
  }
});

test('a 1280x720 view of the bunny: hover and pin a mesh face (the README screenshot)', async () => {
  await page.setViewportSize({ width: 1280, height: 720 });
  await drawn(() => page.selectOption('#scene', 'bunny'));
  // the bunny's frame at the full size, drawn, before the cursor moves: the hover is picked
  // from the last frame when the cursor moves (a frame still at another height missed it)
  await page.waitForFunction(() => {
    const app = window.lanecastApp;
    return app.sceneName === 'bunny.sc' && app.lc.width === 1280 && app.lc.height === 720 && !app.dirty;
  });
  await page.mouse.move(700, 300);
  await page.evaluate(() => window.lanecastApp.frame());
  const hover = await page.evaluate(() => window.lanecastApp.hover);
  assert.ok(hover >= 0, 'the cursor is on the bunny');
  assert.match(await page.textContent('#hover'), new RegExp(`id ${hover} triangle`));
  // a click pins the face: its mesh face index and the scene's `mesh` line
  await page.evaluate(() => document.activeElement?.blur());
  await page.mouse.click(700, 300);
  await page.evaluate(() => window.lanecastApp.frame());
  const meshLine = fs.readFileSync(path.join(root, 'scenes/bunny.sc'), 'utf8').split('\n').findIndex((l) => /^mesh /.test(l)) + 1;
  assert.match(await page.textContent('#pinned'), new RegExp(`id ${hover}  triangle  mesh face ${hover} \\(scene line ${meshLine}\\)`));
  await page.mouse.move(560, 420);
  await page.evaluate(() => window.lanecastApp.frame());
  await page.screenshot({ path: path.join(shots, 'bunny-1280x720.png') });
});
