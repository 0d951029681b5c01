// The built module (web/dist/lanecast.wasm, through web/www/lanecast.js) against the native
// command line: every seed, stress and bundled mesh scene (and tests/ply's files) at two sizes,
// by each engine the page renders with, ids and depths byte for byte, as `lanecast -i SCENE
// -size WxH --accel A --ids I.npy --depth D.npy` writes them (the per-eye path: `--accel
// auto`, the default; the world engine: `--accel world`; precision auto, packet kernel); and
// the engine the module chooses gives that engine's frame. Then the API's other calls: pick, shade,
// cameras other than the scene's, and errors worded as the command line words them.
//
// Needs web/build.sh to have run, and the native binary: LANECAST_BIN, else
// target/release/lanecast (`cargo build --release`). Run: node --test web/tests/
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { init, cameraLine, ACCEL } from '../www/lanecast.js';

const web = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const root = path.dirname(web);
const wasmPath = path.join(web, 'dist', 'lanecast.wasm');
const bin = path.resolve(root, process.env.LANECAST_BIN || path.join('target', 'release', 'lanecast'));
for (const [what, p, how] of [
  ['the module', wasmPath, 'run web/build.sh'],
  ['the native binary', bin, 'run cargo build --release, or set LANECAST_BIN'],
]) {
  if (!fs.existsSync(p)) throw new Error(`${what} is missing: ${p} (${how})`);
}
const lc = await init(fs.readFileSync(wasmPath));
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'lanecast-web-'));
process.on('exit', () => fs.rmSync(tmp, { recursive: true, force: true }));

const SIZES = [[320, 180], [97, 61]];
const rel = (d) => fs.readdirSync(path.join(root, d)).filter((f) => /\.(sc|obj|ply)$/.test(f)).sort().map((f) => `${d}/${f}`);
const seeds = rel('scenes').filter((f) => /scene\d\.sc$/.test(f));
const meshScenes = rel('scenes').filter((f) => !/scene\d\.sc$/.test(f));
const stress = rel('scenes/stress');
const bareMeshes = rel('scenes/meshes');
// PLY files, valid and not (ASCII, binary both ends): the same frames, or the same refusal
const plys = rel('tests/ply');
// scenes that break one rule each: refused alike, with the same FILE:LINE:COL message
const bad = rel('tests/bad');

/** A .npy file's data bytes (the header skipped), with its dtype descriptor and shape. */
function npy(file) {
  const b = fs.readFileSync(file);
  assert.equal(b.subarray(0, 6).toString('latin1'), '\x93NUMPY');
  const hlen = b[6] === 1 ? b.readUInt16LE(8) : b.readUInt32LE(8);
  const start = b[6] === 1 ? 10 + hlen : 12 + hlen;
  const header = b.subarray(b[6] === 1 ? 10 : 12, start).toString('latin1');
  return { header, data: b.subarray(start) };
}

/**
 * The native command line's ids and depths for `scene` at w x h (`--accel accel`), or its
 * error message.
 */
function native(scene, w, h, accel = 'auto') {
  const ids = path.join(tmp, 'ids.npy');
  const depth = path.join(tmp, 'depth.npy');
  // -o into the temp folder too: without it the image would land beside the scene
  const image = path.join(tmp, 'image.bmp');
  const r = spawnSync(bin, ['-i', scene, '-size', `${w}x${h}`, '--accel', accel, '-o', image, '--ids', ids, '--depth', depth], {
    cwd: root,
    encoding: 'utf8',
  });
  if (r.status !== 0) return { error: r.stderr.trim() };
  const i = npy(ids);
  const d = npy(depth);
  assert.match(i.header, /'<i4'/);
  assert.match(d.header, /'<f4'/);
  assert.match(i.header, new RegExp(`\\(${h}, ${w}\\)`));
  return { ids: i.data, depth: d.data };
}

/** The scene's bytes and the mesh files its `mesh` lines name, by the names they are written with. */
function files(scene) {
  const bytes = fs.readFileSync(path.join(root, scene));
  const meshes = {};
  if (scene.endsWith('.sc')) {
    for (const m of bytes.toString('utf8').matchAll(/^\s*mesh\s+(\S+)/gm)) {
      meshes[m[1]] = fs.readFileSync(path.join(root, path.dirname(scene), m[1]));
    }
  }
  return { bytes, meshes };
}

const asBytes = (a) => Buffer.from(a.buffer, a.byteOffset, a.byteLength);

for (const [group, scenes] of [['seed scenes', seeds], ['stress scenes', stress], ['mesh scenes', meshScenes], ['bare meshes', bareMeshes], ['PLY files of tests/ply', plys], ['bad scenes of tests/bad', bad]]) {
  test(`${group}: ids and depths byte for byte as the native CLI's, by either engine, or its refusal word for word`, (t) => {
    assert.ok(scenes.length > 0, `no ${group} found`);
    let compared = 0;
    let refused = 0;
    const chosen = { tiles: 0, world: 0 };
    for (const scene of scenes) {
      const { bytes, meshes } = files(scene);
      for (const [w, h] of SIZES) {
        const frames = {};
        for (const engine of ['tiles', 'world']) {
          const want = native(scene, w, h, ACCEL[engine]);
          let got;
          try {
            lc.setEngine(engine);
            lc.load(scene, bytes, meshes);
            got = lc.render(null, w, h);
          } catch (e) {
            // the module refuses exactly what the command line refuses, with its message
            assert.ok(want.error, `${scene} ${w}x${h}: the module refused what the CLI renders: ${e.message}`);
            assert.ok(want.error.includes(e.message), `${scene}: CLI said ${want.error}, module said ${e.message}`);
            refused++;
            continue;
          }
          const what = `${scene} ${w}x${h} by ${engine}`;
          assert.ok(!want.error, `${what}: the CLI refused (${want.error}) what the module rendered`);
          assert.equal(got.engine, engine);
          assert.equal(got.ids.length, w * h);
          assert.ok(asBytes(got.ids).equals(want.ids), `${what}: ids differ`);
          assert.ok(asBytes(got.depth).equals(want.depth), `${what}: depths differ`);
          assert.ok(got.ids.some((id) => id >= 0), `${what}: shows nothing`);
          frames[engine] = want;
          compared++;
        }
        if (!frames.tiles) continue;
        // the module's own choice: one of the two, its frame that engine's
        lc.setEngine('auto');
        const got = lc.render(null, w, h);
        chosen[got.engine]++;
        assert.ok(asBytes(got.ids).equals(frames[got.engine].ids), `${scene} ${w}x${h}: the chosen ${got.engine} frame differs`);
      }
    }
    lc.setEngine('auto');
    assert.ok(compared > 0, `no ${group} frame compared`);
    t.diagnostic(`${scenes.length} files, ${compared} frames identical, ${refused} refused alike; chosen: ${JSON.stringify(chosen)}`);
  });
}

test('a camera other than the scene\'s renders as the CLI renders a scene with that camera line', () => {
  const text = fs.readFileSync(path.join(root, 'scenes/scene1.sc'), 'utf8');
  const camera = { eye: [-9.5, 4.25, 7.0], look: [0.3, 2.0, -0.4], up: [0, 1, 0], fov: 47 };
  const moved = text.replace(/^camera .*$/m, cameraLine(camera));
  assert.notEqual(moved, text);
  const file = path.join(tmp, 'moved.sc');
  fs.writeFileSync(file, moved);
  const got = lc.render(text, 200, 150, camera); // the module's API: text, size, camera
  const want = native(file, 200, 150, ACCEL[got.engine]);
  assert.ok(!want.error, want.error);
  assert.ok(asBytes(got.ids).equals(want.ids), 'ids differ');
  assert.ok(asBytes(got.depth).equals(want.depth), 'depths differ');
  // and the scene's own camera differs from it
  const own = lc.render(text, 200, 150);
  assert.ok(!asBytes(own.ids).equals(want.ids));
});

test('a camera given by intrinsics (off-centre, non-square pixels) renders as the CLI renders its K line', () => {
  const text = fs.readFileSync(path.join(root, 'scenes/scene3.sc'), 'utf8');
  for (const intrinsics of [[180, 150, 93.5, 80.25], [260, 300, 140, 40]]) {
    const camera = { eye: [0.5, 1, 9], look: [0, 0, 0], up: [0, 1, 0], intrinsics };
    const moved = text.replace(/^camera .*$/m, cameraLine(camera));
    assert.match(moved, / K /);
    const file = path.join(tmp, 'pinhole.sc');
    fs.writeFileSync(file, moved);
    const got = lc.render(text, 200, 150, camera);
    const want = native(file, 200, 150, ACCEL[got.engine]);
    assert.ok(!want.error, want.error);
    assert.ok(asBytes(got.ids).equals(want.ids), 'ids differ');
    assert.ok(asBytes(got.depth).equals(want.depth), 'depths differ');
    assert.ok(got.ids.some((id) => id >= 0), 'something is hit');
  }
  assert.throws(() => lc.render(text, 200, 150, { eye: [0, 0, 9], look: [0, 0, 0], up: [0, 1, 0], fov: 40, intrinsics: [100, 100, 100, 75] }), /fov or intrinsics, not both/);
  assert.throws(() => lc.render(text, 200, 150, { eye: [0, 0, 9], look: [0, 0, 0], up: [0, 1, 0], intrinsics: [-100, 100, 100, 75] }));
});

test('pick reports id, type, scene line, depth and hit point as --ids and --depth give them', () => {
  const text = fs.readFileSync(path.join(root, 'scenes/scene1.sc'), 'utf8');
  const lines = text.split('\n');
  const [w, h] = [320, 180];
  const f = lc.render(text, w, h);
  const ids = f.ids.slice();
  const depth = f.depth.slice();
  const seen = new Set();
  for (let y = 0; y < h; y += 7) {
    for (let x = 0; x < w; x += 5) {
      const p = lc.pick(x, y);
      const at = y * w + x;
      if (ids[at] < 0) {
        assert.equal(p, null);
        continue;
      }
      assert.equal(p.id, ids[at]);
      assert.equal(Math.fround(p.depth), depth[at]);
      const word = lines[p.line - 1].trim().split(/\s+/)[0];
      assert.equal(word, p.type, `line ${p.line} is a ${word}`);
      // the hit point lies at that depth from the eye
      const eye = lc.scene.camera.eye;
      const dist = Math.hypot(...p.point.map((v, k) => v - eye[k]));
      assert.ok(Math.abs(dist - p.depth) < 1e-4 * p.depth, `${dist} vs ${p.depth}`);
      seen.add(p.id);
    }
  }
  assert.ok(seen.has(5), 'the top sphere (id 5) was picked');
  assert.ok(seen.size >= 5, `only ids ${[...seen]}`);
  // a mesh face: its mesh line and face index
  const bunny = files('scenes/bunny.sc');
  lc.load('scenes/bunny.sc', bunny.bytes, bunny.meshes);
  const g = lc.render(null, 160, 120);
  const at = g.ids.findIndex((id) => id >= 0);
  const p = lc.pick(at % 160, Math.floor(at / 160));
  const text2 = bunny.bytes.toString('utf8').split('\n');
  const meshLine = text2.findIndex((l) => /^\s*mesh\s/.test(l)) + 1;
  // the mesh's first face takes the id after the primitives written before its line
  const before = text2.slice(0, meshLine - 1).filter((l) => /^\s*(sphere|triangle|quad)\s/.test(l)).length;
  assert.equal(p.type, 'triangle');
  assert.equal(p.line, meshLine);
  assert.equal(p.face, p.id - before);
});

test('shade follows -cm, -cv and --seed and highlights the hovered primitive', () => {
  const text = fs.readFileSync(path.join(root, 'scenes/scene2.sc'), 'utf8');
  const f = lc.render(text, 160, 90);
  const ids = f.ids.slice();
  const a = lc.shade({ mode: 'random', seed: 1 }).slice();
  const b = lc.shade({ mode: 'random', seed: 2 }).slice();
  const c = lc.shade({ mode: 'ordered', variation: 'log' }).slice();
  assert.notDeepEqual(a, b);
  assert.notDeepEqual(a, c);
  const id = ids.find((i) => i >= 0);
  const lit = lc.shade({ mode: 'random', seed: 1, hover: id }).slice();
  // its pixels, and a ring 3 pixels wide around them: nothing farther changes
  const own = [];
  ids.forEach((i, k) => { if (i === id) own.push([k % 160, Math.floor(k / 160)]); });
  let ring = 0;
  for (let k = 0; k < ids.length; k++) {
    const same = [0, 1, 2, 3].every((j) => lit[4 * k + j] === a[4 * k + j]);
    if (ids[k] === id || same) continue;
    const [x, y] = [k % 160, Math.floor(k / 160)];
    assert.ok(own.some(([u, v]) => (u - x) ** 2 + (v - y) ** 2 <= 9), `pixel ${k} (id ${ids[k]}) changed`);
    ring++;
  }
  assert.ok(ring > 0, 'no ring around the hovered primitive');
  assert.notDeepEqual(lit, a);
  // the command line's PNG of the same frame, same colours
  const png = path.join(tmp, 's.png');
  execFileSync(bin, ['-i', 'scenes/scene2.sc', '-size', '160x90', '-o', png, '-cm', 'ordered', '-cv', 'log'], { cwd: root });
  assert.ok(fs.statSync(png).size > 0);
});

test('shade mode is the command line\'s -cm shade, byte for byte', () => {
  const [w, h] = [96, 64];
  for (const scene of ['scenes/scene4.sc', 'scenes/teapot.sc']) {
    const f = files(scene);
    lc.load(scene, f.bytes, f.meshes);
    const ids = lc.render(null, w, h).ids.slice();
    const rgba = lc.shade({ mode: 'shade', variation: 'log' }).slice();
    const bmp = path.join(tmp, 'shade.bmp');
    execFileSync(bin, ['-i', scene, '-size', `${w}x${h}`, '-o', bmp, '-cm', 'shade', '-cv', 'log'], { cwd: root });
    // 24-bit BMP: rows bottom-up, BGR, each padded to 4 bytes
    const b = fs.readFileSync(bmp);
    const [at, row] = [b.readUInt32LE(10), Math.ceil((3 * w) / 4) * 4];
    let hits = 0;
    for (let k = 0; k < w * h; k++) {
      const [x, y] = [k % w, Math.floor(k / w)];
      const o = at + (h - 1 - y) * row + 3 * x;
      assert.deepEqual([rgba[4 * k], rgba[4 * k + 1], rgba[4 * k + 2]], [b[o + 2], b[o + 1], b[o]], `${scene} pixel ${k}`);
      assert.ok(rgba[4 * k] === rgba[4 * k + 1] && rgba[4 * k + 1] === rgba[4 * k + 2], `${scene} pixel ${k}: grey`);
      if (ids[k] < 0) assert.equal(rgba[4 * k], 0, `${scene} pixel ${k}: background`);
      else hits++;
    }
    assert.ok(hits > 100, `${scene}: ${hits} hits`);
  }
});

test('bad files: the command line\'s FILE:LINE:COL message, and the previous scene stays', () => {
  const good = files('scenes/scene3.sc');
  lc.load('scenes/scene3.sc', good.bytes);
  const before = lc.render(null, 64, 48).ids.slice();
  const cases = {
    'bad.sc': 'camera eye 0 0 5 look 0 0 0 up 0 1 0\nsphere 0 0 0 -1\n',
    'nocam.sc': 'sphere 0 0 0 1\n',
    'mesh.sc': 'camera eye 0 0 5 look 0 0 0 up 0 1 0\nmesh gone.obj\n',
    'bad.obj': 'v 0 0 0\nf 1 2 3\n',
  };
  for (const [name, text] of Object.entries(cases)) {
    const file = path.join(tmp, name);
    fs.writeFileSync(file, text);
    const r = spawnSync(bin, ['-i', name, '-size', '8x8', '--ids', 'x.npy'], { cwd: tmp, encoding: 'utf8' });
    assert.notEqual(r.status, 0, `${name}: the CLI accepted it`);
    assert.throws(() => lc.load(name, text), (e) => {
      assert.ok(r.stderr.includes(e.message.split(': cannot read mesh')[0]), `CLI: ${r.stderr} module: ${e.message}`);
      assert.ok(e.message.startsWith(name + ':'), e.message);
      return true;
    });
  }
  assert.deepEqual(lc.render(null, 64, 48).ids.slice(), before);
  assert.equal(lc.scene.source, 'scenes/scene3.sc');
});

test('npy gives the frame\'s ids and depths as the command line\'s --ids and --depth files, byte for byte', () => {
  for (const scene of ['scenes/scene1.sc', 'scenes/bunny.sc']) {
    const { bytes, meshes } = files(scene);
    lc.load(scene, bytes, meshes);
    const { engine } = lc.render(null, 97, 61);
    const ids = path.join(tmp, 'n-ids.npy');
    const depth = path.join(tmp, 'n-depth.npy');
    execFileSync(bin, ['-i', scene, '-size', '97x61', '--accel', ACCEL[engine], '-o', path.join(tmp, 'n.png'), '--ids', ids, '--depth', depth], { cwd: root });
    assert.ok(Buffer.from(lc.npy('ids')).equals(fs.readFileSync(ids)), `${scene}: ids .npy differs`);
    assert.ok(Buffer.from(lc.npy('depth')).equals(fs.readFileSync(depth)), `${scene}: depth .npy differs`);
  }
});
