//! The `extern "C"` surface and the memory handoff: the module's state between calls, and the
//! calls, each converting its arguments and delegating to [`State`].
//!
//! The calls, in the order a page makes them:
//!
//! - `lc_alloc(len)` / `lc_free(ptr, len)`: buffers in wasm memory for JS to fill.
//! - `lc_file_add(name, len, data, len)`: a file that a scene's `mesh` lines may name
//!   (ownership of `data` passes to the module), matched against the path a `mesh` line
//!   resolves to by its trailing components (`meshes/x.obj` or `x.obj` matches
//!   `scenes/meshes/x.obj`); `lc_files_clear()` forgets them all.
//! - `lc_load(name, len, data, len)`: a `.sc` scene, or a bare `.obj` / `.ply` by its name;
//!   0 on success (scene info as JSON in the message), 1 on failure (the command line's
//!   `FILE:LINE:COL: message` in the message; the previous scene stays).
//! - `lc_render(width, height, camera)`: camera points at 14 f64 (eye, look, up, fov, then the
//!   intrinsics fx, fy, cx, cy; NaN for the lens not given: no lens means the scene's, else
//!   the default), or is null for the scene's own camera.
//! - `lc_set_engine(which)`: every later frame by the per-eye path (1), by the world engine
//!   (2), or by the engine `engine::choose` names for the scene and size (0, the default);
//!   `lc_engine()`: the engine of the last frame (0: none yet, 1, 2).
//! - `lc_ids()`, `lc_depth()`: the last frame's ids (i32) and depths (f32), row-major.
//! - `lc_shade(mode, variation, seed, hover, pinned)`: the last frame as RGBA, with the
//!   primitives `hover` and `pinned` (-1: none) highlighted; returns its pointer.
//! - `lc_npy(which)`, `lc_npy_len()`: the last frame's ids (0) or depths (1) as a `.npy`
//!   file, the command line's `--ids` / `--depth` bytes.
//! - `lc_pick(x, y)`: the id at pixel (x, y) of the last frame, with id, type, scene line,
//!   mesh face, depth and hit point as JSON in the message.
//! - `lc_message()`, `lc_message_len()`: the last message (UTF-8).

use crate::engine::Engine;
use crate::report::scene_json;
use crate::state::State;
use lanecast::{CameraSpec, ColorMode, Variation};
use std::cell::RefCell;

thread_local! {
    static STATE: RefCell<State> = RefCell::new(State::default());
}

fn with<T>(f: impl FnOnce(&mut State) -> T) -> T {
    STATE.with(|s| f(&mut s.borrow_mut()))
}

/// # Safety
/// `ptr` must point at `len` readable bytes.
unsafe fn str_at<'a>(ptr: *const u8, len: usize) -> &'a str {
    if len == 0 {
        return "";
    }
    let bytes = unsafe { std::slice::from_raw_parts(ptr, len) };
    std::str::from_utf8(bytes).unwrap_or("<name not UTF-8>")
}

/// # Safety
/// `ptr`/`len` must come from [`lc_alloc`] (or be null/0); ownership passes to the caller.
unsafe fn take_buffer(ptr: *mut u8, len: usize) -> Vec<u8> {
    if ptr.is_null() || len == 0 {
        return Vec::new();
    }
    unsafe { Vec::from_raw_parts(ptr, len, len) }
}

/// A buffer of `len` bytes in wasm memory, for JS to fill.
#[unsafe(no_mangle)]
pub extern "C" fn lc_alloc(len: usize) -> *mut u8 {
    let mut v = vec![0u8; len].into_boxed_slice();
    let p = v.as_mut_ptr();
    std::mem::forget(v);
    p
}

/// Frees a buffer from [`lc_alloc`].
///
/// # Safety
/// `ptr` and `len` must be those of one [`lc_alloc`] call, not passed on to another call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn lc_free(ptr: *mut u8, len: usize) {
    drop(unsafe { take_buffer(ptr, len) });
}

/// Adds a file that `mesh` lines may name; the module takes `data` (from [`lc_alloc`]).
///
/// # Safety
/// `name` points at `name_len` bytes; `data`/`data_len` come from one [`lc_alloc`] call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn lc_file_add(
    name: *const u8,
    name_len: usize,
    data: *mut u8,
    data_len: usize,
) {
    let name = unsafe { str_at(name, name_len) }.to_string();
    let data = unsafe { take_buffer(data, data_len) };
    with(|s| s.files.insert(name, data));
}

/// Forgets every file added by [`lc_file_add`].
#[unsafe(no_mangle)]
pub extern "C" fn lc_files_clear() {
    with(|s| s.files.clear());
}

/// Loads a scene (or a bare mesh, by its extension) named `name` from `data` (taken, from
/// [`lc_alloc`]). 0: loaded, scene JSON in the message; 1: refused, the command line's error
/// in the message, and the previous scene stays.
///
/// # Safety
/// `name` points at `name_len` bytes; `data`/`data_len` come from one [`lc_alloc`] call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn lc_load(
    name: *const u8,
    name_len: usize,
    data: *mut u8,
    data_len: usize,
) -> i32 {
    let name = unsafe { str_at(name, name_len) }.to_string();
    let data = unsafe { take_buffer(data, data_len) };
    with(|s| match s.load(&name, &data) {
        Ok(loaded) => {
            s.message = scene_json(loaded.scene(), loaded.bounds());
            0
        }
        Err(e) => {
            s.message = e;
            1
        }
    })
}

/// Renders the loaded scene at `width` x `height` from `camera` (14 f64: eye, look, up, fov,
/// fx, fy, cx, cy; the lens is the fov when it is not NaN, else the intrinsics when fx is not
/// NaN, else the scene's or the default), or from the scene's camera when null. A camera
/// giving both a fov and intrinsics is refused. 0: rendered; 1: refused, the reason in the
/// message.
///
/// # Safety
/// `camera` is null or points at 14 readable f64.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn lc_render(width: u32, height: u32, camera: *const f64) -> i32 {
    let spec = (!camera.is_null()).then(|| {
        let c = unsafe { std::slice::from_raw_parts(camera, 14) };
        let v = |i: usize| glam::DVec3::new(c[i], c[i + 1], c[i + 2]);
        let lens = match (c[9].is_nan(), c[10].is_nan()) {
            (false, false) => return Err("camera: give a fov or intrinsics, not both".to_string()),
            (false, true) => Some(lanecast::Lens::Fov(c[9])),
            (true, false) => Some(lanecast::Lens::Pinhole(lanecast::scene::Intrinsics {
                fx: c[10],
                fy: c[11],
                cx: c[12],
                cy: c[13],
            })),
            (true, true) => None,
        };
        Ok(CameraSpec {
            eye: v(0),
            look: v(3),
            up: v(6),
            lens,
        })
    });
    let spec = match spec.transpose() {
        Ok(spec) => spec,
        Err(e) => {
            return with(|s| {
                s.message = e;
                1
            });
        }
    };
    with(|s| {
        let spec = spec.map(|sp| CameraSpec {
            lens: sp.lens.or_else(|| s.loaded.as_ref()?.scene().camera.lens),
            ..sp
        });
        match s.render(width, height, spec) {
            Ok(_) => 0,
            Err(e) => {
                s.message = e;
                1
            }
        }
    })
}

/// Every later frame by the per-eye path (`which` 1), by the world engine (2), or by the
/// engine [`crate::engine::choose`] names (0, and any other value).
#[unsafe(no_mangle)]
pub extern "C" fn lc_set_engine(which: u32) {
    with(|s| {
        s.force = match which {
            1 => Some(Engine::Tiles),
            2 => Some(Engine::World),
            _ => None,
        }
    })
}

/// The engine that rendered the last frame: 0 none yet, 1 the per-eye path, 2 the world
/// engine.
#[unsafe(no_mangle)]
pub extern "C" fn lc_engine() -> u32 {
    with(|s| match s.engine {
        None => 0,
        Some(Engine::Tiles) => 1,
        Some(Engine::World) => 2,
    })
}

/// The last frame's ids (`width * height` i32, row-major, -1 background), or null.
#[unsafe(no_mangle)]
pub extern "C" fn lc_ids() -> *const i32 {
    with(|s| {
        s.frame
            .as_ref()
            .map_or(std::ptr::null(), |f| f.0.ids.as_ptr())
    })
}

/// The last frame's depths (`width * height` f32, +inf background), or null.
#[unsafe(no_mangle)]
pub extern "C" fn lc_depth() -> *const f32 {
    with(|s| {
        s.frame
            .as_ref()
            .map_or(std::ptr::null(), |f| f.0.depth.as_ptr())
    })
}

/// The last frame shaded as RGBA (`width * height * 4` bytes): `mode` 0 random, 1 ordered, 2 shade;
/// `variation` 0 linear, 1 log; `hover` and `pinned` ids highlighted (-1: none).
#[unsafe(no_mangle)]
pub extern "C" fn lc_shade(
    mode: u32,
    variation: u32,
    seed: f64,
    hover: i32,
    pinned: i32,
) -> *const u8 {
    let mode = match mode {
        1 => ColorMode::Ordered,
        2 => ColorMode::Shade,
        _ => ColorMode::Random,
    };
    let variation = if variation == 1 {
        Variation::Log
    } else {
        Variation::Linear
    };
    let seed = if seed.is_finite() && seed >= 0.0 {
        seed as u64
    } else {
        0
    };
    with(|s| s.shade(mode, variation, seed, hover, pinned).as_ptr())
}

/// The last frame's ids (`which` 0) or depths (1) as a `.npy` file, as the command line's
/// `--ids` and `--depth` write them; its length is [`lc_npy_len`]. Valid until the next call.
#[unsafe(no_mangle)]
pub extern "C" fn lc_npy(which: u32) -> *const u8 {
    with(|s| s.npy(which == 1).as_ptr())
}

/// The length in bytes of the `.npy` file [`lc_npy`] last made (0: no frame).
#[unsafe(no_mangle)]
pub extern "C" fn lc_npy_len() -> usize {
    with(|s| s.npy_len())
}

/// The id at pixel (x, y) of the last frame (-1: background or outside), with the pick as
/// JSON in the message (`null` when none).
#[unsafe(no_mangle)]
pub extern "C" fn lc_pick(x: u32, y: u32) -> i32 {
    with(|s| match s.pick(x, y) {
        Some(p) => {
            s.message = p.json();
            p.id
        }
        None => {
            s.message = "null".into();
            -1
        }
    })
}

/// The last message: scene JSON, pick JSON or an error.
#[unsafe(no_mangle)]
pub extern "C" fn lc_message() -> *const u8 {
    with(|s| s.message.as_ptr())
}

/// The last message's length in bytes.
#[unsafe(no_mangle)]
pub extern "C" fn lc_message_len() -> usize {
    with(|s| s.message.len())
}
