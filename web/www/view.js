// view.js: the page's camera and frame-time rules, apart from the DOM so that node can test
// them (web/tests/page.test.mjs): how far zoom and pan may go, the field of view that keeps a
// scene framed at any window shape, the camera in the URL, and the fps figure.

/** The image shape a scene's camera line is framed for: the command line's default, 640x480. */
export const REF_ASPECT = 4 / 3;

const sub = (a, b) => a.map((v, i) => v - b[i]);
const add = (a, b) => a.map((v, i) => v + b[i]);
const mul = (a, s) => a.map((v) => v * s);
const len = (a) => Math.hypot(a[0], a[1], a[2]);

/**
 * The horizontal field of view (degrees) to render a `width` x `height` canvas with, for a
 * camera whose fov is `fov`: as given up to the reference shape (4:3); wider than that, widened
 * so the frame still shows the height the reference frame shows (a wide window does not crop
 * the top and bottom of the scene). Capped at 170 degrees; 7 significant digits.
 */
export function fitFov(fov, width, height) {
  const aspect = width / height;
  if (!(aspect > REF_ASPECT)) return fov;
  const half = Math.atan((Math.tan((fov * Math.PI) / 360) * aspect) / REF_ASPECT);
  // to 7 significant digits, as a camera line writes it: the page's camera line renders the
  // frame the page shows, bit for bit
  return Number(Math.min(170, (half * 360) / Math.PI).toPrecision(7));
}

/** A scene's box as {centre, radius} from its summary's `bounds` ([min, max]). */
export function sphereOf(bounds) {
  const [lo, hi] = bounds;
  const centre = mul(add(lo, hi), 0.5);
  // a flat or point-like scene still gets a size to zoom about
  return { centre, radius: Math.max(len(sub(hi, lo)) / 2, 1e-6 * Math.max(1, len(centre))) };
}

/**
 * How close and how far the eye may be from the look point: no closer than a thousandth of
 * the scene's radius (or of the home distance), no farther than where the scene still spans a
 * tenth of the view (ten radii beyond the look point's own distance from the scene), or the
 * home distance if that is farther.
 */
export function zoomRange(home, bounds) {
  const { centre, radius } = sphereOf(bounds);
  const homeDist = len(sub(home.eye, home.look));
  const min = 1e-3 * Math.min(radius, homeDist);
  const max = Math.max(homeDist, 10 * radius + len(sub(home.look, centre)));
  return { min, max };
}

/**
 * `camera` kept where the scene stays framed and renderable: the eye's distance from the look
 * point within zoomRange, and the look point no farther from the scene's centre than four of
 * its radii (or than the home look point is). Returns a new camera.
 */
export function clampCamera(camera, home, bounds) {
  const { centre, radius } = sphereOf(bounds);
  const { min, max } = zoomRange(home, bounds);
  const reach = Math.max(4 * radius, len(sub(home.look, centre)));
  const off = sub(camera.look, centre);
  let back = sub(camera.eye, camera.look);
  const d = len(back);
  if (len(off) <= reach && d >= min && d <= max) return { ...camera }; // as it was, bit for bit
  const look = len(off) > reach ? add(centre, mul(off, reach / len(off))) : camera.look;
  if (!(d > 0)) back = sub(home.eye, home.look);
  const k = Math.min(max, Math.max(min, d)) / len(back);
  return { ...camera, eye: add(look, mul(back, k)), look };
}

/** The eye moved toward (k < 1) or away from (k > 1) the look point, then clamped. */
export function zoom(camera, k, home, bounds) {
  const eye = add(camera.look, mul(sub(camera.eye, camera.look), k));
  return clampCamera({ ...camera, eye }, home, bounds);
}

/** The camera as a URL parameter: eye, look, up and fov, ten numbers joined by commas. */
export function cameraParam(c) {
  const n = (v) => Number(v.toPrecision(9)).toString();
  return [...c.eye, ...c.look, ...c.up, c.fov].map(n).join(',');
}

/** The camera a URL parameter gives, or null when it is not ten finite numbers. */
export function parseCameraParam(s) {
  if (typeof s !== 'string') return null;
  const v = s.split(',').map((w) => (w.trim() === '' ? NaN : Number(w)));
  if (v.length !== 10 || !v.every(Number.isFinite)) return null;
  return { eye: v.slice(0, 3), look: v.slice(3, 6), up: v.slice(6, 9), fov: v[9] };
}

/**
 * Frame times of the recent frames, for the fps figure: the median of the last `n`, so one
 * slow or fast frame does not swing it, and the first frame after a reset (a new scene or
 * size, whose frame builds what the next ones reuse) left out.
 */
export class FrameTimes {
  constructor(n = 30) {
    this.n = n;
    this.reset();
  }

  /** Forgets the frames so far; the next one is left out. */
  reset() {
    this.times = [];
    this.skip = true;
  }

  /** Records a frame's milliseconds. */
  add(ms) {
    if (this.skip) {
      this.skip = false;
      return;
    }
    this.times.push(ms);
    if (this.times.length > this.n) this.times.shift();
  }

  /** The median of the recorded frames, ms; NaN before one is recorded. */
  median() {
    const t = [...this.times].sort((a, b) => a - b);
    if (!t.length) return NaN;
    const m = t.length >> 1;
    return t.length % 2 ? t[m] : (t[m - 1] + t[m]) / 2;
  }

  /** Frames per second by the median frame time; NaN before one is recorded. */
  fps() {
    return 1000 / this.median();
  }
}

/** Downloads `bytes` as a file named `name` (a browser's save dialog or download bar). */
export function download(name, bytes, type = 'application/octet-stream') {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(bytes instanceof Blob ? bytes : new Blob([bytes], { type }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}
