// The two engines the page renders with, against each other, in the built module under node
// (one thread): the render alone (`lc_render`, ms), median of FRAMES frames a case, at the
// scene's own distance (a 3-degree-a-frame orbit) and close up (the eye moved to 0.1 and 0.03 of
// its distance from the look point). The figures behind web/src/engine.rs's rule. Prints a
// Markdown table.
//
// Needs web/build.sh. Usage: node web/engines.mjs WxH [FRAMES] SCENE.sc[=MESH.obj] ...
//   e.g. node web/engines.mjs 1280x720 5 scenes/bunny.sc scenes/armadillo.sc \
//          scenes/armadillo.sc=target/scale/armadillo_2.obj
// (a scene's `mesh` line is read from the scene's folder, or from MESH.obj when given)
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { init } from './www/lanecast.js';

const web = path.dirname(fileURLToPath(import.meta.url));
const [size, ...rest] = process.argv.slice(2);
const frames = /^\d+$/.test(rest[0] ?? '') ? Number(rest.shift()) : 5;
const m = /^(\d+)x(\d+)$/.exec(size ?? '');
if (!m || !rest.length || frames < 1) {
  console.error('usage: node web/engines.mjs WxH [FRAMES] SCENE.sc[=MESH.obj] ...');
  process.exit(2);
}
const [W, H] = [Number(m[1]), Number(m[2])];
const lc = await init(fs.readFileSync(path.join(web, 'dist', 'lanecast.wasm')));
const median = (a) => [...a].sort((x, y) => x - y)[a.length >> 1];

console.log(`${W}x${H}, render ms (median of ${frames}), per-eye path / world engine`);
console.log('| scene | primitives | view | per-eye ms | world ms | world / per-eye |');
console.log('|---|---:|---|---:|---:|---:|');
for (const arg of rest) {
  const [sc, mesh] = arg.split('=');
  const text = fs.readFileSync(sc, 'utf8');
  const files = {};
  for (const [, name] of text.matchAll(/^\s*mesh\s+(\S+)/gm)) {
    files[name] = fs.readFileSync(mesh ?? path.join(path.dirname(sc), name));
  }
  const scene = lc.load(sc, text, files);
  const c = scene.camera;
  for (const [view, k] of [['orbit', 1], ['close 0.1', 0.1], ['close 0.03', 0.03]]) {
    const ms = {};
    for (const engine of ['tiles', 'world']) {
      lc.setEngine(engine);
      const t = [];
      for (let f = -1; f < frames; f++) {
        // about the up axis (y in the bundled scenes), 3 degrees a frame; the first frame,
        // which prepares the scene, left out
        const a = (Math.max(f, 0) * 3 * Math.PI) / 180;
        const [ox, oy, oz] = c.eye.map((v, i) => (v - c.look[i]) * k);
        const eye = [c.look[0] + Math.cos(a) * ox + Math.sin(a) * oz, c.look[1] + oy, c.look[2] - Math.sin(a) * ox + Math.cos(a) * oz];
        const r = lc.render(null, W, H, { eye, look: c.look, up: c.up, fov: c.fov });
        if (f >= 0) t.push(r.ms);
      }
      ms[engine] = median(t);
    }
    const name = mesh ? `${sc} with ${path.basename(mesh)}` : sc;
    console.log(`| ${name} | ${scene.primitives} | ${view} | ${ms.tiles.toFixed(1)} | ${ms.world.toFixed(1)} | ${(ms.world / ms.tiles).toFixed(2)} |`);
  }
}
lc.setEngine('auto');
