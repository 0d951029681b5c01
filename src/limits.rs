//! Every resource limit lanecast enforces, in one place. Each is checked before the allocation
//! it guards, and README's "Limits" table quotes these values.

/// Longest side of an image, in pixels.
pub const MAX_SIDE: u32 = 65_536;
/// Most pixels in one image (16384 x 16384). A render needs about `BYTES_PER_PIXEL` per pixel.
pub const MAX_PIXELS: u64 = 1 << 28;
/// Working memory per pixel: id (4) + depth (4) + RGB (3) + encoder slack (1).
pub const BYTES_PER_PIXEL: u64 = 12;
/// Most primitives in one scene (ids are i32 in the `.npy` buffers; 2^24 keeps every id exact
/// in f32 too).
pub const MAX_PRIMITIVES: usize = 1 << 24;
/// Longest line in a scene file, in bytes.
pub const MAX_LINE_BYTES: usize = 4096;
/// Largest scene file, in bytes.
pub const MAX_SCENE_BYTES: u64 = 1 << 30;
