//! lanecast in the browser: the library compiled to WebAssembly behind a handful of coarse
//! `extern "C"` calls, for the hand-written loader `web/www/lanecast.js` (no wasm-bindgen).
//!
//! One engine: this crate only converts (bytes and numbers in, pointers to frames out) and
//! delegates to the `lanecast` library. Every render goes through the one [`lanecast::Views`]
//! kept with the scene loaded once: nothing is re-parsed or re-bounded when only the camera
//! moves, and each frame leaves out what the one before showed hidden.
//!
//! The modules: `abi` holds the `extern "C"` calls (listed there, in the order a page makes
//! them) and the memory handoff; `state` the session that holds the scene, its last frame
//! and the files its `mesh` lines name; `report` the pick and the scene summary as JSON.

mod abi;
mod report;
mod state;

pub use abi::{
    lc_alloc, lc_depth, lc_file_add, lc_files_clear, lc_free, lc_ids, lc_load, lc_message,
    lc_message_len, lc_npy, lc_npy_len, lc_pick, lc_render, lc_shade,
};
pub use report::{Pick, scene_json};
pub use state::{Loaded, State};
