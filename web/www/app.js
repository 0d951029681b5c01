// The page: a canvas the size of the window, rendered by lanecast.wasm from the scene loaded
// once, re-rendered from the new camera on every orbit, pan, zoom or control change.
import { init, cameraLine } from './lanecast.js';

const $ = (id) => document.getElementById(id);
const canvas = $('view');
const ctx = canvas.getContext('2d', { alpha: false });
const ui = {
  scene: $('scene'), file: $('file'), fov: $('fov'), fovval: $('fovval'), mode: $('mode'),
  variation: $('variation'), seed: $('seed'), png: $('png'), copycam: $('copycam'),
  camline: $('camline'), stats: $('stats'), hover: $('hover'), pinned: $('pinned'),
  error: $('error'), drop: $('drop'),
};

const lc = await init(fetch('lanecast.wasm'));
const app = {
  lc,
  camera: null, // {eye, look, up, fov}
  home: null, // the scene's own camera
  hover: -1,
  pinned: -1,
  dirty: true, // re-render
  reshade: false, // shade again only (hover, colours)
  frames: 0, // frames drawn (for tests and the benchmark)
  last: { frameMs: 0, renderMs: 0 },
  fpsEma: 0,
  sceneName: '',
};
window.lanecastApp = app;

// ---- vectors --------------------------------------------------------------------------------
const sub = (a, b) => a.map((v, i) => v - b[i]);
const add = (a, b) => a.map((v, i) => v + b[i]);
const mul = (a, s) => a.map((v) => v * s);
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const len = (a) => Math.sqrt(dot(a, a));
const norm = (a) => mul(a, 1 / len(a));
// Rodrigues: v rotated by angle t about unit axis k
function rotate(v, k, t) {
  const c = Math.cos(t), s = Math.sin(t);
  return add(add(mul(v, c), mul(cross(k, v), s)), mul(k, dot(k, v) * (1 - c)));
}

// ---- scenes ---------------------------------------------------------------------------------
function showError(msg) {
  ui.error.textContent = msg;
  ui.error.hidden = !msg;
}

function setScene(name, bytes, files) {
  const scene = lc.load(name, bytes, files); // throws the CLI's message; the old scene stays
  const c = scene.camera;
  app.home = { eye: c.eye, look: c.look, up: c.up, fov: c.fov ?? scene.default_fov };
  app.camera = structuredClone(app.home);
  app.sceneName = name;
  app.fpsEma = 0;
  app.pinned = -1;
  app.hover = -1;
  ui.pinned.textContent = '';
  ui.hover.textContent = '';
  showError(scene.warnings.join('\n'));
  ui.error.classList.toggle('warn', scene.warnings.length > 0);
  syncFov();
  app.dirty = true;
  return scene;
}

async function fetchBytes(url) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return new Uint8Array(await r.arrayBuffer());
}

async function openMenu(entry) {
  try {
    const files = {};
    for (const m of entry.meshes) files[m] = await fetchBytes(`scenes/${m}`);
    setScene(entry.file, await fetchBytes(`scenes/${entry.file}`), files);
  } catch (e) {
    showError(e.message);
  }
}

/** Opens dropped or picked files: the first .sc with the others as its meshes, else a mesh. */
async function openFiles(list) {
  const files = [...list];
  const scene = files.find((f) => /\.sc$/i.test(f.name)) ?? files.find((f) => /\.(obj|ply)$/i.test(f.name));
  if (!scene) {
    showError(`${files.map((f) => f.name).join(', ')}: not a .sc, .obj or .ply file`);
    return;
  }
  const others = {};
  for (const f of files) if (f !== scene) others[f.name] = new Uint8Array(await f.arrayBuffer());
  try {
    setScene(scene.name, new Uint8Array(await scene.arrayBuffer()), others);
    ui.scene.value = '';
  } catch (e) {
    showError(e.message);
  }
}

const menu = await (await fetch('scenes/menu.json')).json();
ui.scene.append(new Option('(opened file)', ''));
for (const m of menu) ui.scene.append(new Option(m.name, m.name));
ui.scene.onchange = () => {
  const m = menu.find((e) => e.name === ui.scene.value);
  if (m) openMenu(m);
};
ui.file.onchange = () => ui.file.files.length && openFiles(ui.file.files);
let dragDepth = 0;
window.addEventListener('dragenter', (e) => { e.preventDefault(); dragDepth++; ui.drop.hidden = false; });
window.addEventListener('dragleave', () => { if (--dragDepth <= 0) { dragDepth = 0; ui.drop.hidden = true; } });
window.addEventListener('dragover', (e) => e.preventDefault());
window.addEventListener('drop', (e) => {
  e.preventDefault();
  dragDepth = 0;
  ui.drop.hidden = true;
  if (e.dataTransfer.files.length) openFiles(e.dataTransfer.files);
});

// ---- controls -------------------------------------------------------------------------------
function syncFov() {
  ui.fov.value = app.camera.fov;
  ui.fovval.textContent = Math.round(app.camera.fov * 10) / 10;
}
ui.fov.oninput = () => {
  app.camera.fov = Number(ui.fov.value);
  ui.fovval.textContent = ui.fov.value;
  app.dirty = true;
};
for (const el of [ui.mode, ui.variation, ui.seed]) el.oninput = () => { app.reshade = true; };
ui.png.onclick = () => {
  canvas.toBlob((blob) => {
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob);
    a.download = `${app.sceneName.replace(/\.[^.]*$/, '') || 'lanecast'}.png`;
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }, 'image/png');
};
ui.copycam.onclick = async () => {
  ui.camline.select();
  try {
    await navigator.clipboard.writeText(ui.camline.value);
    ui.copycam.textContent = 'Copied';
  } catch {
    document.execCommand?.('copy');
    ui.copycam.textContent = 'Copied (selected)';
  }
  setTimeout(() => { ui.copycam.textContent = 'Copy camera'; }, 1200);
};

// orbit about the look point, pan, zoom
let drag = null;
canvas.addEventListener('contextmenu', (e) => e.preventDefault());
canvas.addEventListener('pointerdown', (e) => {
  canvas.setPointerCapture(e.pointerId);
  canvas.focus();
  drag = { x: e.clientX, y: e.clientY, x0: e.clientX, y0: e.clientY, pan: e.shiftKey || e.button === 2, moved: false };
});
canvas.addEventListener('pointermove', (e) => {
  const { x, y } = pixel(e);
  if (!drag) {
    hoverAt(x, y);
    return;
  }
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  drag.x = e.clientX;
  drag.y = e.clientY;
  if (Math.abs(e.clientX - drag.x0) + Math.abs(e.clientY - drag.y0) > 3) drag.moved = true;
  if (drag.pan) pan(dx, dy);
  else orbit(dx, dy);
});
canvas.addEventListener('pointerup', (e) => {
  if (drag && !drag.moved) {
    const { x, y } = pixel(e);
    pin(x, y);
  }
  drag = null;
});
canvas.addEventListener('wheel', (e) => {
  e.preventDefault();
  const c = app.camera;
  const k = Math.exp(Math.max(-1, Math.min(1, e.deltaY * 0.001)));
  c.eye = add(c.look, mul(sub(c.eye, c.look), k));
  app.dirty = true;
}, { passive: false });
window.addEventListener('keydown', (e) => {
  if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
  if (e.key === 'h' || e.key === 'H') $('panel').hidden = !$('panel').hidden;
  if (e.key === 'r' || e.key === 'R') {
    app.camera = structuredClone(app.home);
    syncFov();
    app.dirty = true;
  }
});

function pixel(e) {
  const r = canvas.getBoundingClientRect();
  return {
    x: Math.floor(((e.clientX - r.left) * canvas.width) / r.width),
    y: Math.floor(((e.clientY - r.top) * canvas.height) / r.height),
  };
}

function orbit(dx, dy) {
  const c = app.camera;
  const up = norm(c.up);
  let off = sub(c.eye, c.look);
  off = rotate(off, up, -dx * 0.008);
  const right = norm(cross(mul(off, -1), up));
  const pitched = rotate(off, right, -dy * 0.008);
  // stay off the up axis: the camera's up must not be parallel to the view
  if (Math.abs(dot(norm(pitched), up)) < 0.995) off = pitched;
  c.eye = add(c.look, off);
  app.dirty = true;
}

function pan(dx, dy) {
  const c = app.camera;
  const fwd = sub(c.look, c.eye);
  const right = norm(cross(fwd, c.up));
  const camUp = norm(cross(right, fwd));
  const perPixel = (2 * len(fwd) * Math.tan((c.fov * Math.PI) / 360)) / canvas.width;
  const move = add(mul(right, -dx * perPixel), mul(camUp, dy * perPixel));
  c.eye = add(c.eye, move);
  c.look = add(c.look, move);
  app.dirty = true;
}

function describe(p) {
  if (!p) return '';
  const where = p.face != null
    ? (p.line ? `mesh face ${p.face} (scene line ${p.line})` : `mesh face ${p.face}`)
    : `scene line ${p.line}`;
  const pt = p.point.map((v) => v.toPrecision(6)).join(' ');
  return `id ${p.id}  ${p.type}  ${where}\ndepth ${p.depth}\nhit ${pt}`;
}

function hoverAt(x, y) {
  const p = lc.pick(x, y);
  const id = p ? p.id : -1;
  ui.hover.textContent = p ? `under cursor: id ${p.id} ${p.type}` : '';
  if (id !== app.hover) {
    app.hover = id;
    app.reshade = true;
  }
}

function pin(x, y) {
  const p = lc.pick(x, y);
  app.pinned = p ? p.id : -1;
  app.pick = p;
  ui.pinned.textContent = p ? `pinned: ${describe(p)}` : '';
  ui.pinned.dataset.id = p ? p.id : '';
  app.reshade = true;
}

// ---- the frame loop -------------------------------------------------------------------------
function resize() {
  const w = Math.max(1, Math.round(canvas.clientWidth));
  const h = Math.max(1, Math.round(canvas.clientHeight));
  if (w !== canvas.width || h !== canvas.height) {
    canvas.width = w;
    canvas.height = h;
    app.fpsEma = 0;
    app.dirty = true;
  }
}
new ResizeObserver(resize).observe(canvas);

function shading() {
  return {
    mode: ui.mode.value, variation: ui.variation.value, seed: Math.max(0, Math.floor(Number(ui.seed.value) || 0)),
    hover: app.hover, pinned: app.pinned,
  };
}

/** Renders (when the camera or size changed) and draws; returns whether it drew. */
function frame() {
  resize();
  if (!app.camera || !(app.dirty || app.reshade)) return false;
  const t0 = performance.now();
  const w = canvas.width, h = canvas.height;
  let renderMs = app.last.renderMs;
  let rgba;
  if (app.dirty) {
    let f;
    try {
      f = lc.render(null, w, h, app.camera, shading());
    } catch (e) {
      // a view the engine refuses (an eye out of f32 range, a triangle too thin to resolve
      // from it): the message, and the last frame stays until a view renders again
      showError(e.message);
      app.viewError = true;
      app.dirty = false;
      return false;
    }
    if (app.viewError) {
      showError('');
      app.viewError = false;
    }
    renderMs = f.ms;
    rgba = f.rgba;
    ui.camline.value = cameraLine(app.camera);
  } else {
    rgba = lc.shade(shading());
  }
  // straight from wasm memory, no copy (the view is fresh: taken after the calls)
  ctx.putImageData(new ImageData(rgba, w, h), 0, 0);
  const frameMs = performance.now() - t0;
  const rendered = app.dirty;
  app.dirty = app.reshade = false;
  app.frames++;
  if (rendered) {
    app.last = { frameMs, renderMs };
    app.fpsEma = app.fpsEma ? 0.9 * app.fpsEma + 0.1 * (1000 / frameMs) : 1000 / frameMs;
    const rays = (w * h) / (frameMs / 1000);
    ui.stats.textContent =
      `${w}x${h}  frame ${frameMs.toFixed(1)} ms (render ${renderMs.toFixed(1)})\n` +
      `${(rays / 1e6).toFixed(1)} Mrays/s  ${app.fpsEma.toFixed(0)} fps  ${lc.scene.primitives} primitives`;
  }
  return true;
}
app.frame = frame;

function loop() {
  frame();
  requestAnimationFrame(loop);
}

// the first menu entry, or ?scene=NAME
const wanted = new URLSearchParams(location.search).get('scene');
const first = menu.find((m) => m.name === wanted) ?? menu[0];
ui.scene.value = first.name;
await openMenu(first);
app.ready = true;
requestAnimationFrame(loop);
