//! Reading `.sc` scene text into a `Scene`.
//!
//! UTF-8 text, one statement per line, `#` to end of line a comment, blank lines ignored,
//! tokens separated by spaces or tabs, a leading BOM and CRLF line ends accepted:
//!
//! ```text
//! camera eye EX EY EZ look LX LY LZ up UX UY UZ [fov DEGREES | K FX FY CX CY]
//! sphere CX CY CZ RADIUS
//! triangle AX AY AZ  BX BY BZ  CX CY CZ
//! quad AX AY AZ  BX BY BZ  CX CY CZ  DX DY DZ     # vertices in perimeter order
//! mesh PATH
//! ```
//!
//! Exactly one camera line, anywhere; any number of primitives. Errors point at
//! `FILE:LINE:COL`, the column counted in characters (after the BOM): the offending token's,
//! or for an error about a statement as a whole (too few numbers, a geometric rule, a limit)
//! its first token's.
//!
//! # In parallel, with the answers of a sequential reader
//!
//! The file is read once into one buffer (`chunks::read_file`) and cut at line ends into
//! chunks (`chunks::split`: a few per thread of the ambient rayon pool, each knowing the global
//! number of its first line from newlines counted per chunk in parallel and prefix-summed).
//! Each chunk is checked as UTF-8 and parsed on its own, in parallel (`scene_chunk.rs`): its
//! primitives with their lines, its `camera` and `mesh` lines as events, and the first error it
//! meets, where it stops. Line numbers are global from the start, so every message a chunk
//! words is final.
//!
//! `join` then walks the chunks in file order and does what needs the lines before: it counts
//! primitives against the limit (meshes included), refuses a second camera, loads each mesh
//! (itself in parallel) at its place, and returns the first error in file order, the first
//! invalid UTF-8 byte before anything else, as a whole-file check would. Last, the pieces (chunk
//! primitives and mesh triangles) are copied into the scene's vectors in parallel, in file
//! order, so a primitive's id is its position among the primitive lines, a mesh's triangles
//! taking consecutive ids at its line, as a line-by-line reading gives them.
//!
//! Memory stays bounded by the primitive limit: chunks record what they parse in a shared
//! `Budget` and stop when it runs out. In parallel that can happen out of file order, so the
//! file is then parsed again one chunk after the other, where running out means the limit
//! really is passed before that point.

use super::chunks::{self, Budget};
use super::mesh::MeshFiles;
use super::scene_chunk::{ChunkOut, Event, StopKind, parse_chunk, second_camera};
use super::shapes::{Mesh, Part, Shapes};
use super::statement::{CAMERA_SYNTAX, first_token_col};
use super::{CameraSpec, Scene, mesh};
use super::{STDIN, STDIN_NAME};
use crate::error::{Error, Result};
use crate::limits::{MAX_PRIMITIVES, MAX_SCENE_BYTES};
use crate::par::prelude::*;
use crate::words::count;
use glam::DVec3;
use std::ops::Range;
use std::path::{Path, PathBuf};

const BOM: &[u8] = "\u{feff}".as_bytes();

/// Reads and parses a scene file. The size is checked against `MAX_SCENE_BYTES` before
/// reading, and the text must be UTF-8.
pub fn load_scene(path: &Path) -> Result<Scene> {
    load_scene_meshes(path).map(|(scene, _)| scene)
}

/// [`load_scene`], with the path of every mesh file the scene read, in the order of its
/// `mesh` lines (as resolved: relative to the scene's folder).
pub fn load_scene_meshes(path: &Path) -> Result<(Scene, Vec<PathBuf>)> {
    if path == Path::new(STDIN) {
        return read_stdin_scene();
    }
    // a mesh file, by its extension alone, before anything reads the file as scene text
    if mesh::MeshFormat::of(path).is_some() {
        return load_mesh_scene(path).map(|scene| (scene, Vec::new()));
    }
    let io_err = |e| Error::io(path, "read scene", e);
    let meta = std::fs::metadata(path).map_err(io_err)?;
    if meta.len() > MAX_SCENE_BYTES {
        return Err(too_big(path, meta.len()));
    }
    let bytes = chunks::read_file(path, MAX_SCENE_BYTES, "read scene", Some(SCENE_TEXT))?;
    let mut meshes = Vec::new();
    let chunk = chunks::chunk_bytes(bytes.len());
    let scene = parse_bytes_meshes(
        &bytes,
        path,
        MAX_PRIMITIVES,
        chunk,
        MeshFiles::Disk,
        &mut meshes,
    )?;
    Ok((scene, meshes))
}

/// What a scene file must be, in the message that refuses a binary one.
const SCENE_TEXT: &str = "scene files";

/// A scene read from standard input (`-i -`), under the same size limit as a file, named
/// [`STDIN_NAME`] in messages; its `mesh` paths are relative to the working folder.
fn read_stdin_scene() -> Result<(Scene, Vec<PathBuf>)> {
    let name = Path::new(STDIN_NAME);
    let bytes = chunks::read_stream(
        std::io::stdin().lock(),
        name,
        MAX_SCENE_BYTES,
        "read scene",
        SCENE_TEXT,
    )?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(too_big(name, bytes.len() as u64));
    }
    let mut meshes = Vec::new();
    let chunk = chunks::chunk_bytes(bytes.len());
    let scene = parse_bytes_meshes(
        &bytes,
        name,
        MAX_PRIMITIVES,
        chunk,
        MeshFiles::Disk,
        &mut meshes,
    )?;
    Ok((scene, meshes))
}

fn too_big(path: &Path, len: u64) -> Error {
    Error::InputFile {
        file: path.to_path_buf(),
        msg: format!("scene file is {len} bytes; the limit is {MAX_SCENE_BYTES} bytes"),
    }
}

/// The message for the first invalid UTF-8 byte, at `bytes[bad]`.
fn utf8_error(path: &Path, bytes: &[u8], bad: usize) -> Error {
    let line_start = bytes[..bad]
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let line = bytes[..line_start].iter().filter(|&&b| b == b'\n').count() + 1;
    // The prefix of the line up to the bad byte is valid UTF-8.
    let prefix = std::str::from_utf8(&bytes[line_start..bad]).unwrap_or("");
    let prefix = if line == 1 {
        prefix.strip_prefix('\u{feff}').unwrap_or(prefix)
    } else {
        prefix
    };
    let msg = format!(
        "not valid UTF-8 (byte 0x{:02x}); scene files must be UTF-8 text",
        bytes[bad]
    );
    Error::input(path, line, prefix.chars().count() + 1, msg)
}

/// Parses and validates scene text. `file` only names the scene in messages and in
/// `Scene::source`.
pub fn parse_scene(text: &str, file: &Path) -> Result<Scene> {
    parse_with_limit(text, file, MAX_PRIMITIVES)
}

fn parse_with_limit(text: &str, file: &Path, max_primitives: usize) -> Result<Scene> {
    let chunk = chunks::chunk_bytes(text.len());
    parse_bytes(text.as_bytes(), file, max_primitives, chunk)
}

/// The whole parse of a file's bytes, cut into chunks of about `chunk_bytes`.
pub(super) fn parse_bytes(
    bytes: &[u8],
    file: &Path,
    max_primitives: usize,
    chunk_bytes: usize,
) -> Result<Scene> {
    parse_bytes_meshes(
        bytes,
        file,
        max_primitives,
        chunk_bytes,
        MeshFiles::Disk,
        &mut Vec::new(),
    )
}

/// [`parse_bytes`], the `mesh` files read from `files`, recording in `meshes` the path of
/// every mesh file read.
pub(super) fn parse_bytes_meshes(
    bytes: &[u8],
    file: &Path,
    max_primitives: usize,
    chunk_bytes: usize,
    files: MeshFiles,
    meshes: &mut Vec<PathBuf>,
) -> Result<Scene> {
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(too_big(file, bytes.len() as u64));
    }
    let bom = if bytes.starts_with(BOM) { BOM.len() } else { 0 };
    let body = &bytes[bom..];
    let parts = chunks::split(body, chunk_bytes);
    let budget = Budget::new(max_primitives);
    let outs: Vec<_> = parts
        .par_iter()
        .map(|c| parse_chunk(body, c, file, &budget))
        .collect();
    if let Some(&bad) = outs.iter().find_map(|o| o.as_ref().err()) {
        return Err(utf8_error(file, bytes, bom + bad));
    }
    let outs: Vec<ChunkOut> = outs.into_iter().flatten().collect();
    let line = match join(outs, body, file, max_primitives, files, meshes) {
        Ok(scene) => return Ok(scene),
        Err(Halt::Error(e)) => return Err(e),
        Err(Halt::Rerun) => {
            // The budget ran out out of order: once more, one chunk after the other.
            let budget = Budget::new(max_primitives);
            let mut outs = Vec::new();
            for c in &parts {
                let out = parse_chunk(body, c, file, &budget)
                    .map_err(|bad| utf8_error(file, bytes, bom + bad))?;
                let stopped = out.stop.is_some();
                outs.push(out);
                if stopped {
                    break;
                }
            }
            let last = outs
                .last()
                .and_then(|o| o.stop.as_ref())
                .map_or(0, |s| s.line);
            match join(outs, body, file, max_primitives, files, meshes) {
                Ok(scene) => return Ok(scene),
                Err(Halt::Error(e)) => return Err(e),
                // In order, the budget runs out only past the limit, which `join` finds first.
                Err(Halt::Rerun) => last,
            }
        }
    };
    Err(too_many_primitives(file, body, line, max_primitives))
}

/// The primitive limit, reached on `line` of `body` (the file past its BOM): at the column of
/// the line's first token, as every error about a statement as a whole.
fn too_many_primitives(file: &Path, body: &[u8], line: usize, max: usize) -> Error {
    let msg = format!("too many primitives: a scene holds at most {max}");
    let col = chunks::lines(body)
        .nth(line.saturating_sub(1))
        .map_or(0, |r| first_token_col(&String::from_utf8_lossy(&body[r])));
    Error::input(file, line, col, msg)
}

/// Why `join` gives no scene.
enum Halt {
    Error(Error),
    /// The budget ran out in parallel: parse again in order.
    Rerun,
}

impl From<Error> for Halt {
    fn from(e: Error) -> Halt {
        Halt::Error(e)
    }
}

/// A run of the final shape list: shapes `range` of chunk `chunk`, or a mesh (all on its
/// line).
enum Piece {
    Shapes { chunk: usize, range: Range<usize> },
    Mesh(Mesh, usize),
}

/// The chunks' results in file order: limit, cameras, meshes, the first error; then the scene.
/// Every mesh file read is recorded in `meshes` (which starts empty: a rerun reads them again).
fn join(
    mut outs: Vec<ChunkOut>,
    body: &[u8],
    file: &Path,
    max: usize,
    files: MeshFiles,
    meshes: &mut Vec<PathBuf>,
) -> std::result::Result<Scene, Halt> {
    meshes.clear();
    let mut camera: Option<(CameraSpec, usize)> = None;
    let mut camera_at = None;
    let mut pieces = Vec::new();
    let mut total = 0;
    let mut warnings = Vec::new();
    for (chunk, out) in outs.iter_mut().enumerate() {
        let stop = out.stop.take();
        // Takes the chunk's shapes `done..at`, unless one of them is past the limit.
        let mut done = 0;
        let mut place = |at: usize, total: &mut usize, pieces: &mut Vec<Piece>| {
            let range = done..at;
            if *total + range.len() > max {
                let line = out.line(range.start + (max - *total));
                return Err(too_many_primitives(file, body, line, max));
            }
            *total += range.len();
            done = at;
            pieces.push(Piece::Shapes { chunk, range });
            Ok(())
        };
        for event in &out.events {
            match *event {
                Event::Camera {
                    line,
                    col,
                    at,
                    spec,
                } => {
                    place(at, &mut total, &mut pieces)?;
                    if let Some((_, first)) = camera {
                        return Err(second_camera(file, line, col, first).into());
                    }
                    camera = Some((spec, line));
                    camera_at = Some((line, col));
                }
                Event::Mesh {
                    line,
                    col,
                    at,
                    path,
                } => {
                    place(at, &mut total, &mut pieces)?;
                    let path = file.parent().map_or_else(|| path.into(), |d| d.join(path));
                    let at = (line, col);
                    let mesh = load_mesh(file, at, &path, max - total, files, &mut warnings)?;
                    meshes.push(path);
                    total += mesh.len();
                    pieces.push(Piece::Mesh(mesh, line));
                }
            }
        }
        let Some(stop) = stop else {
            place(out.len(), &mut total, &mut pieces)?;
            continue;
        };
        place(stop.at, &mut total, &mut pieces)?;
        return Err(match stop.kind {
            StopKind::Primitive(_) if total >= max => {
                too_many_primitives(file, body, stop.line, max).into()
            }
            StopKind::Camera { col, .. } if camera.is_some() => {
                let first = camera.map_or(0, |(_, l)| l);
                second_camera(file, stop.line, col, first).into()
            }
            StopKind::Error(e) | StopKind::Primitive(e) | StopKind::Camera { err: e, .. } => {
                Halt::Error(e)
            }
            StopKind::Budget => Halt::Rerun,
        });
    }
    let Some((camera, _)) = camera else {
        return Err(Error::InputFile {
            file: file.to_path_buf(),
            msg: format!("no camera line (expected `{CAMERA_SYNTAX}`)"),
        }
        .into());
    };
    // the loose shapes, copied in parallel in file order; the meshes stay as read
    let loose: Vec<(usize, Range<usize>)> = (pieces.iter())
        .filter_map(|p| match p {
            Piece::Shapes { chunk, range } => Some((*chunk, range.clone())),
            Piece::Mesh(..) => None,
        })
        .collect();
    let lens: Vec<usize> = loose.iter().map(|(_, r)| r.len()).collect();
    let (mut shapes, mut lines) = (Vec::new(), Vec::new());
    chunks::gather(&lens, |p, j| {
        let (out, at) = (&outs[loose[p].0], loose[p].1.start + j);
        (out.shape(at), out.line(at) as u32)
    })
    .unzip_into_vecs(&mut shapes, &mut lines);
    let parts = pieces.into_iter().map(|p| match p {
        Piece::Shapes { range, .. } => Part::Loose(range.len()),
        Piece::Mesh(mesh, line) => Part::Mesh(mesh, line),
    });
    Ok(Scene {
        source: file.to_path_buf(),
        camera,
        camera_at,
        shapes: Shapes::assemble(shapes, lines, parts),
        warnings,
    })
}

/// The margin the default framing camera ([`framing_camera`]) leaves between a mesh rendered
/// alone and the border of the default 640x480 image: 5% of the width and of the height on
/// each side, the mesh inside the central 90% in both directions.
pub const FRAMING_MARGIN: f64 = 0.05;

/// The margin the default framing camera keeps on every image up to [`FRAMING_WIDEST`] wide
/// at the default field of view (so a 1920x1080 render of a mesh stays whole).
pub const FRAMING_WIDE_MARGIN: f64 = 0.02;

/// The widest image (width / height) the default framing camera keeps whole: 16:9.
pub const FRAMING_WIDEST: (u32, u32) = (16, 9);

/// An image a framing camera frames its mesh in ([`framing_camera_for`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Framing {
    /// The image's width (any unit: only width / height counts).
    pub width: u32,
    /// The image's height.
    pub height: u32,
    /// The horizontal field of view, degrees.
    pub fov_deg: f64,
    /// The share of the width and of the height left free on each side.
    pub margin: f64,
    /// Frame every view of a turntable about the camera's up axis (`--orbit`), not just the
    /// first.
    pub turntable: bool,
}

impl Framing {
    /// The images the default framing camera frames ([`framing_camera`]): the default
    /// 640x480 at 60 degrees with [`FRAMING_MARGIN`], and the widest image it keeps whole,
    /// [`FRAMING_WIDEST`] at 60 degrees with [`FRAMING_WIDE_MARGIN`].
    pub const DEFAULT: [Framing; 2] = [
        Framing {
            width: 640,
            height: 480,
            fov_deg: 60.0,
            margin: FRAMING_MARGIN,
            turntable: false,
        },
        Framing {
            width: FRAMING_WIDEST.0,
            height: FRAMING_WIDEST.1,
            fov_deg: 60.0,
            margin: FRAMING_WIDE_MARGIN,
            turntable: false,
        },
    ];
}

/// An OBJ or PLY file rendered on its own (`lanecast -i mesh.obj`, `-i scan.ply`): its faces as
/// triangles, in file order, seen by [`framing_camera`]. Shapes carry line 0 (no scene line); range errors name the
/// face instead (`range::f32_range`).
fn load_mesh_scene(path: &Path) -> Result<Scene> {
    mesh_scene(path, mesh::load_mesh(path, MAX_PRIMITIVES)?)
}

/// The scene of a mesh rendered on its own, from its triangles and degenerate count as read
/// from `path` ([`load_mesh_scene`]).
pub(super) fn mesh_scene(path: &Path, (mesh, degenerate): (Mesh, usize)) -> Result<Scene> {
    let camera = framing_camera(&mesh).ok_or_else(|| Error::InputFile {
        file: path.to_path_buf(),
        msg: "no faces with extent to frame; a mesh to render alone needs at least one".into(),
    })?;
    let mut warnings = Vec::new();
    if degenerate > 0 {
        warnings.push(format!(
            "{}: {} kept (never hit)",
            path.display(),
            count(degenerate, "degenerate triangle", "degenerate triangles")
        ));
    }
    let mut shapes = Shapes::new();
    shapes.push_mesh(mesh, 0);
    Ok(Scene {
        source: path.to_path_buf(),
        camera,
        camera_at: None,
        shapes,
        warnings,
    })
}

/// The default camera of a mesh rendered alone, every front's: [`framing_camera_for`] the
/// images of [`Framing::DEFAULT`].
pub fn framing_camera(mesh: &Mesh) -> Option<CameraSpec> {
    framing_camera_for(mesh, &Framing::DEFAULT)
}

/// The camera that frames a mesh rendered alone in each image of `images`: looking at the
/// centre of the triangles' bounding box along -z (from the +z side, the usual front of an OBJ
/// model), up +y, from as near as keeps every vertex inside each image's margin (README
/// "Camera"). For a turntable, every angle about the vertical axis through the look point
/// keeps the mesh inside. `None` when the box is a point (or there are no faces).
pub fn framing_camera_for(mesh: &Mesh, images: &[Framing]) -> Option<CameraSpec> {
    let each = |visit: &mut dyn FnMut(DVec3)| {
        for &i in mesh.faces.iter().flatten() {
            visit(mesh.vertices[i as usize]);
        }
    };
    frame_points(each, images)
}

/// [`framing_camera`] for any points (the vertices of primitives of every type, as
/// `scene_from_arrays` gives them).
pub fn framing_camera_of(points: impl IntoIterator<Item = DVec3>) -> Option<CameraSpec> {
    let points: Vec<DVec3> = points.into_iter().collect();
    frame_points(
        |visit: &mut dyn FnMut(DVec3)| points.iter().for_each(|&p| visit(p)),
        &Framing::DEFAULT,
    )
}

/// [`framing_camera_for`] for the points `each` visits (twice: the box, then the distance).
fn frame_points(each: impl Fn(&mut dyn FnMut(DVec3)), images: &[Framing]) -> Option<CameraSpec> {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    each(&mut |v| {
        lo = lo.min(v);
        hi = hi.max(v);
    });
    let radius = (hi - lo).length() / 2.0;
    if !(radius > 0.0 && radius.is_finite()) {
        return None;
    }
    let look = (lo + hi) / 2.0;
    // A point p (from the look point) is in an image's central part when |p.x| <= kx (d - p.z)
    // and |p.y| <= ky (d - p.z), d the eye's distance along +z: when d >= p.z + |p.x| / kx and
    // d >= p.z + |p.y| / ky.
    let slopes: Vec<(f64, f64, bool)> = (images.iter())
        .map(|f| {
            let kx = (1.0 - 2.0 * f.margin) * (f.fov_deg.to_radians() / 2.0).tan();
            (kx, kx * f.height as f64 / f.width as f64, f.turntable)
        })
        .collect();
    let need = |p: DVec3, (kx, ky, turntable): (f64, f64, bool)| {
        if turntable {
            // turned about +y, p.x and p.z take any values with p.x^2 + p.z^2 = rho^2: the
            // largest p.z + |p.x| / kx over the circle is rho * sqrt(1 + 1 / kx^2), and the
            // nearest p.z is rho
            let rho = p.x.hypot(p.z);
            (rho * (1.0 + 1.0 / (kx * kx)).sqrt()).max(rho + p.y.abs() / ky)
        } else {
            (p.z + p.x.abs() / kx).max(p.z + p.y.abs() / ky)
        }
    };
    // never on or behind a point: at least a little in front of the box
    let mut distance = (hi.z - look.z) + 1e-3 * radius;
    each(&mut |v| {
        for &k in &slopes {
            distance = distance.max(need(v - look, k));
        }
    });
    Some(CameraSpec {
        eye: look + DVec3::Z * distance,
        look,
        up: DVec3::Y,
        lens: None,
    })
}

/// The triangles of the mesh named on `line` (its path at column `col`), with room for `room`
/// of them. A file that yields no triangle at all (a `.sc` file, a text file, an OBJ of `v`
/// lines alone) is refused there: it would add nothing, silently.
fn load_mesh(
    file: &Path,
    (line, col): (usize, usize),
    path: &Path,
    room: usize,
    files: MeshFiles,
    warnings: &mut Vec<String>,
) -> Result<Mesh> {
    // A mesh that cannot be read is an I/O error like a scene that cannot be read (exit 1),
    // reported at the line naming it.
    let (mesh, degenerate) = files.load(path, room).map_err(|e| match e {
        Error::Io { source, .. } => Error::IoAt {
            file: file.to_path_buf(),
            line,
            col,
            path: path.to_path_buf(),
            action: "read mesh",
            source,
        },
        other => other,
    })?;
    if mesh.is_empty() {
        let what = match mesh::MeshFormat::of(path) {
            Some(mesh::MeshFormat::Ply) => "a PLY file with a face element",
            _ => "a Wavefront OBJ file with `f` lines, or a .ply file",
        };
        return Err(Error::input(
            file,
            line,
            col,
            format!(
                "mesh {}: the file holds no triangles (a mesh must be {what})",
                path.display()
            ),
        ));
    }
    if degenerate > 0 {
        warnings.push(format!(
            "{}:{line}: mesh {}: {} kept (never hit)",
            file.display(),
            path.display(),
            count(degenerate, "degenerate triangle", "degenerate triangles")
        ));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primitive_limit_counts_primitives_not_lines() {
        let text = "camera eye 0 0 5 look 0 0 0 up 0 1 0\n# c\nsphere 0 0 0 1\n\nsphere 0 0 0 1\n";
        let f = Path::new("s.sc");
        assert_eq!(parse_with_limit(text, f, 2).unwrap().shapes.len(), 2);
        let more = format!("{text}triangle 0 0 0 1 0 0 0 1 0\n");
        let e = parse_with_limit(&more, f, 2).unwrap_err().to_string();
        assert!(e.starts_with("s.sc:6:1: too many primitives"), "{e}");
    }
}
