// lanecast.js: the loader of lanecast.wasm (the lanecast library compiled to WebAssembly),
// for browsers and node alike. No wasm-bindgen: the module exports a handful of coarse C calls
// (web/src/lib.rs) and this file wraps them.
//
//   import { init } from './lanecast.js';
//   const lc = await init(fetch('lanecast.wasm'));   // or bytes (node: fs.readFileSync)
//   lc.load('scene1.sc', text);                        // throws Error('FILE:LINE:COL: ...')
//   const f = lc.render(null, 1280, 720);              // {ids, depth, rgba, width, height, ms, engine}
//   lc.pick(640, 360);                                 // {id, type, line, face, depth, point}
//   lc.npy('ids');                                     // the frame's --ids file (or 'depth')
//
// The arrays render() and shade() return are views of the module's memory: valid until the
// next call into the module (copy them with .slice() to keep them).

const enc = new TextEncoder();
const dec = new TextDecoder();

/** Instantiates lanecast.wasm from a Response (or a promise of one), an ArrayBuffer or bytes. */
export async function init(source) {
  source = await source;
  let instance;
  if (typeof Response !== 'undefined' && source instanceof Response) {
    if (WebAssembly.instantiateStreaming && source.headers.get('content-type') === 'application/wasm') {
      instance = (await WebAssembly.instantiateStreaming(source, {})).instance;
    } else {
      instance = (await WebAssembly.instantiate(await source.arrayBuffer(), {})).instance;
    }
  } else {
    instance = (await WebAssembly.instantiate(source, {})).instance;
  }
  return new Lanecast(instance.exports);
}

const MODES = { random: 0, ordered: 1, shade: 2 };
// the engines by their number in the module's calls (0: the module's choice)
const ENGINES = ['auto', 'tiles', 'world'];
/** The command line's --accel for a frame of `engine`'s bits. */
export const ACCEL = { tiles: 'auto', world: 'world' };
const VARIATIONS = { linear: 0, log: 1 };

export class Lanecast {
  constructor(exports) {
    this.x = exports;
    this.scene = null; // the loaded scene's summary (JSON from the module)
    this.sceneText = null; // the text render(text, ...) last loaded
    this.width = 0;
    this.height = 0;
    this.camPtr = this.x.lc_alloc(112);
  }

  get memory() {
    return this.x.memory.buffer; // re-taken on every use: calls may grow memory
  }

  message() {
    const p = this.x.lc_message(), n = this.x.lc_message_len();
    return dec.decode(new Uint8Array(this.memory, p, n));
  }

  /** Copies bytes into a fresh module buffer; the module takes ownership. */
  buffer(bytes) {
    if (typeof bytes === 'string') bytes = enc.encode(bytes);
    else if (!(bytes instanceof Uint8Array)) bytes = new Uint8Array(bytes);
    const p = bytes.length ? this.x.lc_alloc(bytes.length) : 0;
    if (bytes.length) new Uint8Array(this.memory, p, bytes.length).set(bytes);
    return [p, bytes.length];
  }

  /**
   * Loads a scene: `name` (its extension picks .sc, .obj or .ply, and it names the file in
   * messages), its bytes or text, and the files its `mesh` lines name ({name: bytes}, matched
   * by path then by file name). Returns the scene's summary; throws an Error whose message is
   * the command line's (FILE:LINE:COL: ...) and keeps the previous scene.
   */
  load(name, bytes, files = {}) {
    this.x.lc_files_clear();
    for (const [k, v] of Object.entries(files)) {
      const [np, nl] = this.buffer(k);
      const [dp, dl] = this.buffer(v);
      this.x.lc_file_add(np, nl, dp, dl);
      if (nl) this.x.lc_free(np, nl);
    }
    const [np, nl] = this.buffer(name);
    const [dp, dl] = this.buffer(bytes);
    const rc = this.x.lc_load(np, nl, dp, dl);
    if (nl) this.x.lc_free(np, nl);
    this.x.lc_files_clear();
    const msg = this.message();
    if (rc !== 0) throw new Error(msg);
    this.scene = JSON.parse(msg);
    this.sceneText = null;
    return this.scene;
  }

  /**
   * Renders a frame. `sceneText`: scene text to load first (named scene.sc), or null for the
   * scene loaded. `camera`: {eye, look, up, fov} or {eye, look, up, intrinsics: [fx, fy, cx,
   * cy]} (pixels of this image, as the command line's `K`; no lens: the scene's, else fov 60),
   * or omitted for the scene's own. Returns {ids: Int32Array, depth: Float32Array,
   * rgba: Uint8ClampedArray, width, height, ms} (ms: the render alone).
   */
  render(sceneText, width, height, camera, shading = {}) {
    if (sceneText != null && sceneText !== this.sceneText) {
      this.load('scene.sc', sceneText);
      this.sceneText = sceneText;
    }
    let cam = 0;
    if (camera) {
      cam = this.camPtr;
      const c = new Float64Array(this.memory, cam, 14);
      const k = camera.intrinsics ?? [NaN, NaN, NaN, NaN];
      if (k.length !== 4) throw new Error('camera.intrinsics: give [fx, fy, cx, cy]');
      c.set([...camera.eye, ...camera.look, ...camera.up, camera.fov ?? NaN, ...k]);
    }
    const t0 = now();
    const rc = this.x.lc_render(width, height, cam);
    const ms = now() - t0;
    if (rc !== 0) throw new Error(this.message());
    this.width = width;
    this.height = height;
    const rgba = this.shade(shading);
    return { ids: this.ids(), depth: this.depth(), rgba, width, height, ms, engine: this.engine() };
  }

  /**
   * The engine later frames are rendered by: 'tiles' (the per-eye path, the command line's
   * default), 'world' (`--accel world`), or 'auto' (the module's choice from the scene and
   * the image size).
   */
  setEngine(which) {
    this.x.lc_set_engine(ENGINES.indexOf(which) > 0 ? ENGINES.indexOf(which) : 0);
  }

  /** The engine of the last frame: 'tiles' or 'world' ('auto' before a frame). */
  engine() {
    return ENGINES[this.x.lc_engine()] ?? 'auto';
  }

  /** The last frame's ids (-1: background), row-major. */
  ids() {
    return new Int32Array(this.memory, this.x.lc_ids(), this.width * this.height);
  }

  /** The last frame's depths (distance along the ray; +Infinity: background). */
  depth() {
    return new Float32Array(this.memory, this.x.lc_depth(), this.width * this.height);
  }

  /**
   * The last frame shaded as RGBA: {mode: 'random'|'ordered'|'shade', variation: 'linear'|'log',
   * seed, hover, pinned} as the command line's -cm, -cv and --seed; ids `hover` and `pinned`
   * highlighted.
   */
  shade({ mode = 'random', variation = 'linear', seed = 0, hover = -1, pinned = -1 } = {}) {
    const p = this.x.lc_shade(MODES[mode] ?? 0, VARIATIONS[variation] ?? 0, Number(seed), hover, pinned);
    return new Uint8ClampedArray(this.memory, p, this.width * this.height * 4);
  }

  /**
   * The last frame's ids ('ids') or depths ('depth') as a `.npy` file: a copy of the bytes
   * the command line's --ids or --depth writes for the same frame.
   */
  npy(which) {
    const p = this.x.lc_npy(which === 'depth' ? 1 : 0);
    return new Uint8Array(this.memory, p, this.x.lc_npy_len()).slice();
  }

  /**
   * What the last frame shows at pixel (x, y): {id, type, line, face, depth, point}, as the
   * command line's --ids and --depth give it (line: the scene line, a mesh's faces that of
   * their `mesh` line and `face` their index in the mesh); null on the background.
   */
  pick(x, y) {
    if (x < 0 || y < 0 || x >= this.width || y >= this.height) return null;
    this.x.lc_pick(x | 0, y | 0);
    return JSON.parse(this.message());
  }
}

/** A `camera` line for a scene file (or a views file) from {eye, look, up, fov or intrinsics}. */
export function cameraLine(c) {
  const n = (v) => {
    const s = Number(v.toPrecision(7)).toString();
    return s === '-0' ? '0' : s;
  };
  const v = (a) => a.map(n).join(' ');
  let line = `camera eye ${v(c.eye)} look ${v(c.look)} up ${v(c.up)}`;
  if (c.fov != null) line += ` fov ${n(c.fov)}`;
  else if (c.intrinsics != null) line += ` K ${v(c.intrinsics)}`;
  return line;
}

function now() {
  return typeof performance !== 'undefined' ? performance.now() : Date.now();
}
