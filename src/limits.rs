//! Every resource limit lanecast enforces, in one place. Each is checked before the allocation
//! it guards, and README's "Limits" table quotes these values.

/// Longest side of an image, in pixels.
pub const MAX_SIDE: u32 = 65_536;
/// Most pixels in one image (16384 x 16384). A render needs about `BYTES_PER_PIXEL` per pixel.
pub const MAX_PIXELS: u64 = 1 << 28;
/// The image-size rules, in one place: each side 1 to [`MAX_SIDE`], at most [`MAX_PIXELS`] in
/// all. The reason, when refused, for the caller to prefix with what it checked (`--size 0x5`,
/// or `image size 0x5`).
pub(crate) fn check_size(width: u64, height: u64) -> Result<(), String> {
    if width == 0 || height == 0 {
        return Err("width and height must be at least 1".into());
    }
    if width > MAX_SIDE as u64 || height > MAX_SIDE as u64 {
        return Err(format!("a side may be at most {MAX_SIDE} pixels"));
    }
    if width * height > MAX_PIXELS {
        return Err(format!("at most {MAX_PIXELS} pixels per image"));
    }
    Ok(())
}

/// Narrowest and widest screen a pinhole's intrinsics may give, at distance 1: `W / fx` and
/// `H / fy` (twice the tangent of the half-angle each axis spans, for a centred principal
/// point) lie in `[MIN_SCREEN, MAX_SCREEN]`. Every screen coordinate and its f32 rounding then
/// stays a normal number with room (a field of view within (0, 180) degrees spans 0 to ~1e16).
pub const MIN_SCREEN: f64 = 1e-9;
/// See [`MIN_SCREEN`].
pub const MAX_SCREEN: f64 = 1e9;
/// Farthest a pinhole's principal point may lie from the image's centre, in image widths
/// (`|cx - W/2| / W`) and heights (`|cy - H/2| / H`): lens shifts and crops stay well inside;
/// the projections' rounding grows with it (`world::raster`'s margin follows it).
pub const MAX_PRINCIPAL_OFFSET: f64 = 1e3;

/// The size-dependent rules for pinhole intrinsics (the rest: `scene::validate::intrinsics`),
/// in one place: the reason, when refused.
pub(crate) fn check_lens(
    fx: f64,
    fy: f64,
    cx: f64,
    cy: f64,
    width: u32,
    height: u32,
) -> Result<(), String> {
    let (w, h) = (width as f64, height as f64);
    for (name, side, f) in [("W / fx", w, fx), ("H / fy", h, fy)] {
        let screen = side / f;
        if !(MIN_SCREEN..=MAX_SCREEN).contains(&screen) {
            return Err(format!(
                "{name} = {screen:.3e} for a {width}x{height} image: the screen at distance 1 must \
                 span {MIN_SCREEN:e} to {MAX_SCREEN:e}"
            ));
        }
    }
    for (name, side, c) in [("cx", w, cx), ("cy", h, cy)] {
        let within = (c - side / 2.0).abs() <= MAX_PRINCIPAL_OFFSET * side;
        if !within {
            return Err(format!(
                "principal point {name} = {c} is more than {MAX_PRINCIPAL_OFFSET:e} image sizes \
                 from the centre of a {width}x{height} image"
            ));
        }
    }
    Ok(())
}

/// Most worker threads (`--threads`): each costs a stack and a start; far more than any machine
/// lanecast targets has cores, and far below what an operating system refuses to start.
pub const MAX_THREADS: usize = 1024;

/// Working memory per pixel: id (4) + depth (4) + RGB (3) + encoder slack (1).
pub const BYTES_PER_PIXEL: u64 = 12;
/// Most primitives in one scene (ids are i32 in the `.npy` buffers; 2^24 keeps every id exact
/// in f32 too).
pub const MAX_PRIMITIVES: usize = 1 << 24;
/// Most views in one run (`--views` lines, `--orbit N`): output names are numbered, and each
/// view's camera is kept in memory (about 100 bytes each).
pub const MAX_VIEWS: usize = 1_000_000;
/// Longest line in a scene file, in bytes.
pub const MAX_LINE_BYTES: usize = 4096;
/// Largest scene file, in bytes.
pub const MAX_SCENE_BYTES: u64 = 1 << 30;
/// Farthest any point of a primitive may be from the eye (a sphere's centre distance plus its
/// radius, a polygon vertex's distance). The f32 kernels work on eye-relative values rounded
/// from f64 and square them (sphere: `|oc|^2`, `l . l`): 3 * (1e18)^2 = 3e36 stays well inside
/// f32 (max 3.4e38), with room for the rounding of a three-term sum.
pub const MAX_EYE_DISTANCE: f64 = 1e18;
/// Smallest sphere radius: the f32 kernels use `radius^2`, which must stay a normal f32
/// (>= 1.2e-38): (1e-18)^2 = 1e-36.
pub const MIN_RADIUS: f64 = 1e-18;
/// Smallest angle, in radians (as the sine), that a polygon edge may subtend seen from the eye.
/// The kernels' edge planes are `normalize((V_i - eye) x (V_i+1 - eye))` in f64; below this
/// angle that cross product is mostly rounding noise (relative error ~1e-16 / angle), and where
/// the subtraction has merged two vertices it is zero, which turns the polygon into an endless
/// wedge (found by fuzzing: a 12-unit triangle seen from 5e17 away drew a line across the image).
pub const MIN_EDGE_ANGLE: f64 = 1e-12;
