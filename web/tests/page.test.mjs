// The page's camera and frame-time rules (web/www/view.js), in node: zoom and pan limits that
// keep every scene framed and renderable (checked by rendering through the built module), the
// field of view that keeps a scene framed in a wide window, the camera in the URL, and the fps
// figure (the median of recent frames, the first left out).
//
// Needs web/build.sh to have run. Run: node --test web/tests/
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { init } from '../www/lanecast.js';
import { FrameTimes, REF_ASPECT, cameraParam, clampCamera, fitFov, parseCameraParam, zoom, zoomRange } from '../www/view.js';

const web = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const root = path.dirname(web);
const wasmPath = path.join(web, 'dist', 'lanecast.wasm');
if (!fs.existsSync(wasmPath)) throw new Error(`the module is missing: ${wasmPath} (run web/build.sh)`);
const lc = await init(fs.readFileSync(wasmPath));

const dist = (c) => Math.hypot(...c.eye.map((v, k) => v - c.look[k]));

/** Loads a bundled scene with its meshes; returns the page's home camera and bounds. */
function open(name) {
  const file = path.join(root, 'scenes', name);
  const text = fs.readFileSync(file);
  const meshes = {};
  for (const m of text.toString('utf8').matchAll(/^\s*mesh\s+(\S+)/gm)) {
    meshes[m[1]] = fs.readFileSync(path.join(root, 'scenes', m[1]));
  }
  const s = lc.load(name, text, meshes);
  const c = s.camera;
  return { home: { eye: c.eye, look: c.look, up: c.up, fov: c.fov ?? s.default_fov }, bounds: s.bounds };
}

for (const name of ['armadillo.sc', 'bunny.sc', 'scene1.sc', 'scene6.sc']) {
  test(`${name}: zooming out or in as far as the wheel goes keeps the scene framed and renderable`, () => {
    const { home, bounds } = open(name);
    const { min, max } = zoomRange(home, bounds);
    assert.ok(min > 0 && min < dist(home) && max >= dist(home), `${min} ${max}`);
    for (const [k, towards] of [[Math.E, max], [1 / Math.E, min]]) {
      let c = structuredClone(home);
      // 200 wheel notches at the page's largest step (e^1 each): e^200 unclamped
      for (let n = 0; n < 200; n++) c = zoom(c, k, home, bounds);
      assert.ok(Math.abs(dist(c) - towards) <= 1e-9 * towards, `${dist(c)} vs ${towards}`);
      assert.deepEqual(c.look, home.look);
      const f = lc.render(null, 160, 120, c); // throws if the engine refuses the view
      const shown = f.ids.filter((i) => i >= 0).length;
      assert.ok(shown > 0, `${name} at distance ${dist(c)}: nothing shown`);
      if (k > 1) assert.ok(shown >= 0.003 * 160 * 120, `${name} zoomed out: only ${shown} pixels`);
    }
  });
}

test('panning far away stops with the look point near the scene', () => {
  const { home, bounds } = open('armadillo.sc');
  let c = structuredClone(home);
  for (let n = 0; n < 1000; n++) {
    c = clampCamera({ ...c, eye: c.eye.map((v) => v + 1e6), look: c.look.map((v) => v + 1e6) }, home, bounds);
  }
  const [lo, hi] = bounds;
  const centre = lo.map((v, k) => (v + hi[k]) / 2);
  const r = Math.hypot(...hi.map((v, k) => v - lo[k])) / 2;
  assert.ok(Math.hypot(...c.look.map((v, k) => v - centre[k])) <= 4 * r * (1 + 1e-12));
  lc.render(null, 64, 48, c);
  // a camera within the limits comes back bit for bit
  assert.deepEqual(clampCamera(home, home, bounds), home);
});

test('a wide canvas widens the fov to show the height a 4:3 frame shows; others keep it', () => {
  assert.equal(fitFov(40, 640, 480), 40);
  assert.equal(fitFov(40, 300, 600), 40);
  for (const [w, h] of [[1280, 720], [2560, 800], [981, 720]]) {
    const f = fitFov(40, w, h);
    assert.ok(f > 40);
    // the screen's half-height at distance 1 is that of the 4:3 frame
    const halfH = (Math.tan((f * Math.PI) / 360) * h) / w;
    assert.ok(Math.abs(halfH - Math.tan((40 * Math.PI) / 360) / REF_ASPECT) < 1e-7, `${w}x${h}`);
    assert.equal(Number(f.toPrecision(7)), f); // as a camera line writes it
  }
  assert.ok(fitFov(160, 4000, 100) <= 170);
});

test('the armadillo is not cropped at 1280x720 with the fitted fov (it was with the scene\'s)', () => {
  const { home } = open('armadillo.sc');
  const rows = (c) => {
    const f = lc.render(null, 320, 180, c);
    let top = 180, bottom = -1;
    f.ids.forEach((id, k) => {
      if (id >= 0) {
        top = Math.min(top, Math.floor(k / 320));
        bottom = Math.max(bottom, Math.floor(k / 320));
      }
    });
    return [top, bottom];
  };
  const [t0, b0] = rows(home);
  assert.ok(t0 === 0 || b0 === 179, `the scene's fov at 16:9 crops it (rows ${t0}-${b0})`);
  const [t1, b1] = rows({ ...home, fov: fitFov(home.fov, 320, 180) });
  assert.ok(t1 > 0 && b1 < 179, `rows ${t1}-${b1}`);
});

test('the camera in the URL comes back as it went, and a bad one is refused', () => {
  const c = { eye: [60.5, -1e-7, -330.123456789], look: [0, 22, 0], up: [0, 1, 0], fov: 40 };
  const back = parseCameraParam(cameraParam(c));
  for (const k of ['eye', 'look', 'up']) {
    back[k].forEach((v, i) => assert.ok(Math.abs(v - c[k][i]) <= 1e-8 * Math.max(1, Math.abs(v))));
  }
  assert.equal(back.fov, 40);
  assert.deepEqual(parseCameraParam(cameraParam(back)), back);
  for (const bad of [null, '', '1,2,3', '1,2,3,4,5,6,7,8,9,x', '1,2,3,4,5,6,7,8,9,10,11', '1,2,3,4,5,6,7,8,9,', 'NaN,2,3,4,5,6,7,8,9,10']) {
    assert.equal(parseCameraParam(bad), null, bad);
  }
});

test('fps: the median of the recent frames, the first frame of a scene or size left out', () => {
  const t = new FrameTimes(5);
  assert.ok(Number.isNaN(t.fps()));
  t.add(900); // the first: building what the next frames reuse
  assert.ok(Number.isNaN(t.median()));
  t.add(10);
  assert.equal(t.fps(), 100);
  for (const ms of [12, 11, 500, 13]) t.add(ms); // one slow frame does not swing it
  assert.equal(t.median(), 12);
  for (const ms of [20, 20, 20]) t.add(ms); // only the last five count
  assert.deepEqual(t.times, [500, 13, 20, 20, 20]);
  assert.equal(t.median(), 20);
  t.reset();
  t.add(1);
  assert.ok(Number.isNaN(t.median()));
});
