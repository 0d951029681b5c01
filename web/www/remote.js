// remote.js: the page's side of worker.js. Each call posts a message to the worker and
// resolves with its answer (or rejects with the module's message, the command line's words);
// the worker answers in the order the calls were made.

export class Remote {
  constructor(url = new URL('./worker.js', import.meta.url)) {
    this.worker = new Worker(url, { type: 'module' });
    this.next = 0;
    this.waiting = new Map();
    this.scene = null; // the loaded scene's summary
    this.width = 0; // the last frame's size
    this.height = 0;
    this.worker.onmessage = ({ data: { id, ok, value, error } }) => {
      const w = this.waiting.get(id);
      this.waiting.delete(id);
      if (ok) w.resolve(value);
      else w.reject(new Error(error));
    };
    this.worker.onerror = (e) => {
      // the worker failed to start (or threw outside a call): every call waiting fails
      for (const w of this.waiting.values()) w.reject(new Error(`worker: ${e.message}`));
      this.waiting.clear();
    };
  }

  call(op, args, transfer = []) {
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.waiting.set(id, { resolve, reject });
      this.worker.postMessage({ id, op, args }, transfer);
    });
  }

  /** The scene's summary; throws the command line's message, and the previous scene stays. */
  async load(name, bytes, files = {}) {
    this.scene = await this.call('load', { name, bytes, files });
    return this.scene;
  }

  /** A frame: {rgba: Uint8ClampedArray (the page's own), width, height, ms, engine}. */
  async render(width, height, camera, shading) {
    const f = await this.call('render', { width, height, camera, shading });
    this.width = f.width;
    this.height = f.height;
    return f;
  }

  /** The last frame shaded again: {rgba, width, height}. */
  shade(shading) {
    return this.call('shade', { shading });
  }

  /** What the last frame shows at (x, y), or null. */
  pick(x, y) {
    return this.call('pick', { x, y });
  }

  /** The last frame's ids ('ids') or depths ('depth') as the command line's .npy file. */
  npy(which) {
    return this.call('npy', { which });
  }

  /** The last frame's ids, a copy. */
  ids() {
    return this.call('ids');
  }

  /** The last frame's depths, a copy. */
  depth() {
    return this.call('depth');
  }

  /** The engine later frames are rendered by: 'auto', 'tiles' or 'world'. */
  setEngine(which) {
    return this.call('setEngine', { which });
  }
}
