// worker.js: the module worker that holds lanecast.wasm and renders the page's frames, so that
// the page's thread only handles input and draws what comes back: it never waits on a frame.
//
// Messages in: {id, op, args}, answered in order by {id, ok, value} or {id, ok: false, error}.
// The ops are the loader's (lanecast.js) calls: load, render (the frame shaded: its RGBA
// pixels, moved to the page rather than copied), shade, pick, npy, ids, depth, setEngine.
import { init } from './lanecast.js';

const ready = init(fetch('lanecast.wasm'));
// the queue: one call at a time, in the order the page made them
let queue = Promise.resolve();

// each op's answer; the arrays it holds are copies out of the module's memory, moved to the
// page (transferred, not copied again)
const ops = {
  load: (lc, { name, bytes, files }) => lc.load(name, bytes, files),
  render(lc, { width, height, camera, shading }) {
    const f = lc.render(null, width, height, camera, shading);
    return { rgba: f.rgba.slice(), width, height, ms: f.ms, engine: f.engine };
  },
  shade: (lc, { shading }) => ({ rgba: lc.shade(shading).slice(), width: lc.width, height: lc.height }),
  pick: (lc, { x, y }) => lc.pick(x, y),
  npy: (lc, { which }) => lc.npy(which),
  ids: (lc) => lc.ids().slice(),
  depth: (lc) => lc.depth().slice(),
  setEngine: (lc, { which }) => lc.setEngine(which),
};

/** The buffers an answer moves to the page. */
function moves(value) {
  if (ArrayBuffer.isView(value)) return [value.buffer];
  if (ArrayBuffer.isView(value?.rgba)) return [value.rgba.buffer];
  return [];
}

self.onmessage = ({ data: { id, op, args } }) => {
  queue = queue.then(async () => {
    try {
      const lc = await ready;
      const value = ops[op](lc, args ?? {});
      self.postMessage({ id, ok: true, value }, moves(value));
    } catch (e) {
      self.postMessage({ id, ok: false, error: String(e?.message ?? e) });
    }
  });
};
