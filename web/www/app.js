// The page: a canvas filling what the panel leaves of the window, at device pixels, rendered by
// lanecast.wasm from the scene loaded once, re-rendered from the new camera on every orbit,
// pan, zoom or control change. The module runs in a worker (worker.js, reached through
// remote.js): this thread handles input and draws the frames that come back, one frame asked
// at a time, always from the newest camera, so a slow frame never holds up the page. The
// camera rules (zoom limits, framing, the URL's camera, the fps figure) are in view.js.
import { cameraLine } from './lanecast.js';
import { Remote } from './remote.js';
import { FrameTimes, cameraParam, clampCamera, download, fitFov, parseCameraParam, zoom } from './view.js';

const $ = (id) => document.getElementById(id);
const canvas = $('view');
const ctx = canvas.getContext('2d', { alpha: false });
const ui = {
  scene: $('scene'), file: $('file'), fov: $('fov'), fovval: $('fovval'), mode: $('mode'),
  variation: $('variation'), seed: $('seed'), png: $('png'), copycam: $('copycam'),
  camline: $('camline'), stats: $('stats'), hover: $('hover'), pinned: $('pinned'),
  error: $('error'), drop: $('drop'), res: $('res'), idsnpy: $('idsnpy'), depthnpy: $('depthnpy'),
  source: $('source'), hide: $('hide'), show: $('show'), panel: $('panel'),
};

const lc = new Remote();
const app = {
  lc,
  camera: null, // {eye, look, up, fov}: fov as framed for a 4:3 frame (view.js fitFov)
  view: null, // the camera the last frame was rendered from (fov fitted to the canvas)
  home: null, // the scene's own camera
  bounds: null, // the box around the scene's primitives, [min, max]
  good: null, // the last camera that rendered
  hover: -1,
  pinned: -1,
  dirty: true, // re-render (cleared once a frame from the camera and size asked is drawn)
  reshade: false, // shade again only (hover, colours)
  loading: 0, // scenes being loaded: no frame is asked meanwhile
  frames: 0, // frames drawn (for tests and the benchmark)
  last: { frameMs: 0, renderMs: 0 },
  times: new FrameTimes(30), // the fps figure: median of the recent frames
  sceneName: '',
  menuName: '', // the bundled scene on show, '' for an opened file
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

async function setScene(name, bytes, files, menuName = '') {
  let scene;
  app.loading++;
  try {
    await inflight; // the frame asked before is drawn first
    scene = await lc.load(name, bytes, files); // throws the CLI's message; the old scene stays
  } finally {
    app.loading--;
  }
  const c = scene.camera;
  app.home = { eye: c.eye, look: c.look, up: c.up, fov: c.fov ?? scene.default_fov };
  app.camera = structuredClone(app.home);
  app.good = null;
  app.viewError = 0;
  app.bounds = scene.bounds;
  app.sceneName = name;
  app.menuName = menuName;
  ui.source.textContent = menuName ? `scene: ${name}` : `opened: ${name}`;
  opened.hidden = !!menuName;
  if (!menuName) {
    opened.textContent = `${name} (opened)`;
    ui.scene.value = '';
  }
  app.times.reset();
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
    await setScene(entry.file, await fetchBytes(`scenes/${entry.file}`), files, entry.name);
    ui.scene.value = entry.name;
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
    await setScene(scene.name, new Uint8Array(await scene.arrayBuffer()), others);
  } catch (e) {
    showError(e.message);
  }
}

const menu = await (await fetch('scenes/menu.json')).json();
const opened = new Option('', ''); // the opened file, by its name
opened.hidden = true;
ui.scene.append(opened);
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
ui.res.oninput = () => resize();
const stem = () => app.sceneName.replace(/^.*\//, '').replace(/\.[^.]*$/, '') || 'lanecast';
ui.png.onclick = () => canvas.toBlob((blob) => download(`${stem()}.png`, blob), 'image/png');
// the frame's buffers, as the command line's --ids and --depth write them
ui.idsnpy.onclick = async () => download(`${stem()}-ids.npy`, await lc.npy('ids'));
ui.depthnpy.onclick = async () => download(`${stem()}-depth.npy`, await lc.npy('depth'));

// the panel: hidden and shown by H, or by its buttons (a click or a tap)
function setPanel(open) {
  ui.panel.hidden = !open;
  ui.show.hidden = open;
  document.body.classList.toggle('collapsed', !open);
  resize();
}
ui.hide.onclick = () => setPanel(false);
ui.show.onclick = () => setPanel(true);
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
  const k = Math.exp(Math.max(-1, Math.min(1, e.deltaY * 0.001)));
  // no nearer than where the look point is still resolved, no farther than the scene framed
  app.camera = zoom(app.camera, k, app.home, app.bounds);
  app.dirty = true;
}, { passive: false });
window.addEventListener('keydown', (e) => {
  if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
  if (e.key === 'h' || e.key === 'H') setPanel(ui.panel.hidden);
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
  // dx, dy in CSS pixels; the frame spans the fitted fov across the canvas's CSS width
  const fov = fitFov(c.fov, canvas.width, canvas.height);
  const perPixel = (2 * len(fwd) * Math.tan((fov * Math.PI) / 360)) / canvas.clientWidth;
  const move = add(mul(right, -dx * perPixel), mul(camUp, dy * perPixel));
  // the look point stays near the scene
  app.camera = clampCamera({ ...c, eye: add(c.eye, move), look: add(c.look, move) }, app.home, app.bounds);
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

// the newest pick asked: an answer to an older one (the pointer moved on) is dropped
let picks = 0;
let picking = Promise.resolve(); // the newest pick, answered
function ask(x, y) {
  const asked = ++picks;
  const p = lc.pick(x, y);
  picking = p.catch(() => null);
  return p.then((v) => (asked === picks ? v : undefined));
}

async function hoverAt(x, y) {
  const p = await ask(x, y);
  if (p === undefined) return;
  const id = p ? p.id : -1;
  ui.hover.textContent = p ? `under cursor: id ${p.id} ${p.type}` : '';
  if (id !== app.hover) {
    app.hover = id;
    app.reshade = true;
  }
}

async function pin(x, y) {
  const p = await ask(x, y);
  if (p === undefined) return;
  app.pinned = p ? p.id : -1;
  app.pick = p;
  ui.pinned.textContent = p ? `pinned: ${describe(p)}` : '';
  ui.pinned.dataset.id = p ? p.id : '';
  app.reshade = true;
}

// ---- the frame loop -------------------------------------------------------------------------
// The canvas at device pixels (a DPR 2 screen gets twice the CSS size each way), or a half or
// quarter of them when the resolution control asks for speed.
function resize() {
  const k = (window.devicePixelRatio || 1) * Number(ui.res.value || 1);
  const w = Math.max(1, Math.round(canvas.clientWidth * k));
  const h = Math.max(1, Math.round(canvas.clientHeight * k));
  if (w !== canvas.width || h !== canvas.height) {
    canvas.width = w;
    canvas.height = h;
    app.times.reset();
    app.dirty = true;
  }
}
new ResizeObserver(resize).observe(canvas);
window.addEventListener('resize', resize); // a zoom of the page changes the device pixel ratio

function shading() {
  return {
    mode: ui.mode.value, variation: ui.variation.value, seed: Math.max(0, Math.floor(Number(ui.seed.value) || 0)),
    hover: app.hover, pinned: app.pinned,
  };
}

// the frame asked of the worker and not yet drawn (a promise of whether it drew), or null
let inflight = null;

/**
 * Asks for a frame when the camera, the size or the shading changed, and draws it; resolves
 * to whether it drew. One frame is asked at a time: a call while one is on its way waits for
 * it, then asks for the newest camera's.
 */
async function frame() {
  while (inflight) await inflight;
  resize();
  if (!app.camera || app.loading || !(app.dirty || app.reshade)) return false;
  inflight = draw();
  try {
    return await inflight;
  } finally {
    inflight = null;
  }
}
app.frame = frame;

/**
 * Resolves once the page shows everything asked of it: the picks answered, and frames drawn
 * until none is due (for the tests, and for a script driving the page).
 */
app.settle = async () => {
  for (;;) {
    await picking;
    while (app.loading || inflight) await (inflight ?? new Promise((ok) => setTimeout(ok, 5)));
    const drew = await frame();
    if (!drew && !app.loading && !inflight && !(app.dirty || app.reshade)) return;
    if (!drew) await new Promise((ok) => setTimeout(ok, 5));
  }
};

async function draw() {
  const t0 = performance.now();
  const w = canvas.width, h = canvas.height;
  // what this frame shows; a change made while it is on its way asks for the next
  const camera = JSON.stringify(app.camera);
  const style = shading();
  let renderMs = app.last.renderMs;
  let f;
  const rendered = app.dirty;
  if (rendered) {
    // the scene's framing kept at any window shape: a wide canvas gets the fov that shows the
    // height a 4:3 frame shows
    const view = { ...app.camera, fov: fitFov(app.camera.fov, w, h) };
    try {
      f = await lc.render(w, h, view, style);
    } catch (e) {
      // a view the engine refuses (which the zoom and pan limits should leave none of): its
      // message, which names the camera and not the scene, and back to the last camera that
      // rendered (the scene's own before any did)
      showError(e.message);
      app.viewError = 2; // shown until a view after the restored one renders
      const back = app.good ?? app.home;
      if (JSON.stringify(app.camera) !== JSON.stringify(back)) {
        app.camera = structuredClone(back);
        syncFov();
      } else {
        app.dirty = false;
      }
      return false;
    }
    if (app.viewError && !--app.viewError) showError('');
    app.good = JSON.parse(camera);
    app.view = view;
    app.engine = f.engine;
    renderMs = f.ms;
    ui.camline.value = cameraLine(view);
    fitCamline();
    shareView();
  } else {
    f = await lc.shade(style);
    if (f.rgba.length !== w * h * 4) {
      app.reshade = false; // no frame to shade (the last view was refused) or an old size
      return false;
    }
  }
  // the canvas may have been resized while the frame was on its way: draw what came
  if (canvas.width === f.width && canvas.height === f.height) {
    ctx.putImageData(new ImageData(f.rgba, f.width, f.height), 0, 0);
  }
  const frameMs = performance.now() - t0;
  const same = (canvas.width === w && canvas.height === h && JSON.stringify(app.camera) === camera);
  if (same) app.dirty = false;
  if (JSON.stringify(shading()) === JSON.stringify(style)) app.reshade = false;
  app.frames++;
  if (rendered) {
    app.last = { frameMs, renderMs };
    app.times.add(frameMs); // the first frame of a scene or size is left out
    const rays = (w * h) / (frameMs / 1000);
    const fps = app.times.fps();
    const n = app.times.times.length;
    ui.stats.textContent =
      `${w}x${h}  frame ${frameMs.toFixed(1)} ms (render ${renderMs.toFixed(1)}, ${f.engine})\n` +
      `${(rays / 1e6).toFixed(1)} Mrays/s  ` +
      (n ? `${fps.toFixed(0)} fps (median of ${n})` : 'fps –') +
      `  ${lc.scene.primitives} primitives`;
  }
  return true;
}


/**
 * The camera line's field grows to show the whole line: by CSS (field-sizing) where the
 * browser has it, else measured here (a layout per frame).
 */
const sizedByCss = globalThis.CSS?.supports?.('field-sizing', 'content') ?? false;
function fitCamline() {
  if (sizedByCss) return;
  ui.camline.style.height = 'auto';
  ui.camline.style.height = `${ui.camline.scrollHeight + 2}px`;
}

// The view in the URL (?scene=NAME&cam=eye,look,up,fov), to share it or reload it; a file
// opened from disk cannot be named there, so its views leave the URL bare.
let shareTimer = 0;
function shareView() {
  if (shareTimer) return;
  shareTimer = setTimeout(() => {
    shareTimer = 0;
    const q = new URLSearchParams();
    if (app.menuName) {
      q.set('scene', app.menuName);
      q.set('cam', cameraParam(app.camera));
    }
    const url = `${location.pathname}${q.size ? `?${q}` : ''}`;
    if (url !== `${location.pathname}${location.search}`) history.replaceState(null, '', url);
  }, 150);
}

function loop() {
  if (!inflight) frame();
  requestAnimationFrame(loop);
}

// ?scene=NAME (else the first menu entry) and ?cam=eye,look,up,fov (else the scene's camera);
// what cannot be had is said, and the first scene or the scene's camera shown instead
const params = new URLSearchParams(location.search);
const wanted = params.get('scene');
const first = wanted == null ? menu[0] : menu.find((m) => m.name === wanted);
await openMenu(first ?? menu[0]);
const notes = [];
if (!first) {
  notes.push(`?scene=${wanted}: no such scene (the bundled ones: ${menu.map((m) => m.name).join(', ')}); showing ${menu[0].name}`);
}
if (params.has('cam')) {
  const cam = parseCameraParam(params.get('cam'));
  if (!cam) notes.push(`?cam=${params.get('cam')}: not a camera (ten numbers: eye, look, up, fov); showing the scene's own`);
  else if (first) {
    app.camera = cam;
    syncFov();
  }
}
if (notes.length) {
  ui.error.classList.remove('warn');
  showError(notes.join('\n'));
}
app.ready = true;
requestAnimationFrame(loop);
