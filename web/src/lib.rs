//! lanecast in the browser: the library compiled to WebAssembly behind a handful of coarse
//! `extern "C"` calls, for the hand-written loader `web/www/lanecast.js` (no wasm-bindgen).
//!
//! No renderer of its own: this crate only converts (bytes and numbers in, pointers to frames out) and
//! delegates to the `lanecast` library. The session owns the scene loaded once and what is
//! prepared from it for every camera (the world engine's [`lanecast::world::World`], the range
//! check's cluster bounds): nothing is re-parsed or re-prepared when only the camera moves.
//! `engine` chooses which engine renders a frame, from the scene and the image size alone.
//!
//! The modules: `abi` holds the `extern "C"` calls (listed there, in the order a page makes
//! them) and the memory handoff; `state` the session that holds the scene, its last frame
//! and the files its `mesh` lines name; `engine` which engine renders a frame; `report` the pick and the scene summary as JSON.

mod abi;
pub mod engine;
mod report;
mod state;

pub use abi::{
    lc_alloc, lc_depth, lc_engine, lc_file_add, lc_files_clear, lc_free, lc_ids, lc_load,
    lc_message, lc_message_len, lc_npy, lc_npy_len, lc_pick, lc_render, lc_set_engine, lc_shade,
};
pub use report::{Pick, scene_json};
pub use state::{Loaded, State};
