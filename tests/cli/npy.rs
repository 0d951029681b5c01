//! .npy side outputs and known pixels.

use super::*;

/// A parsed `.npy` (format 1.0) file: its header dict and its data bytes.
struct Npy {
    dict: String,
    data: Vec<u8>,
}

fn read_npy(path: &Path) -> Npy {
    let bytes = fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&bytes[..6], b"\x93NUMPY", "magic");
    assert_eq!(bytes[6], 1, "major version 1");
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    assert_eq!((10 + len) % 64, 0, "header padded to a multiple of 64");
    let dict = std::str::from_utf8(&bytes[10..10 + len])
        .unwrap()
        .to_string();
    assert!(dict.ends_with('\n'), "{dict:?}");
    assert!(dict.contains("'fortran_order': False"), "{dict:?}");
    Npy {
        dict,
        data: bytes[10 + len..].to_vec(),
    }
}

impl Npy {
    fn check(&self, descr: &str, w: usize, h: usize) {
        assert!(
            self.dict.contains(&format!("'descr': '{descr}'")),
            "{:?}",
            self.dict
        );
        assert!(
            self.dict.contains(&format!("'shape': ({h}, {w})")),
            "{:?}",
            self.dict
        );
        assert_eq!(self.data.len(), w * h * 4);
    }

    fn i32s(&self) -> Vec<i32> {
        let c = self.data.chunks_exact(4);
        c.map(|b| i32::from_le_bytes(b.try_into().unwrap()))
            .collect()
    }

    fn f32s(&self) -> Vec<f32> {
        let c = self.data.chunks_exact(4);
        c.map(|b| f32::from_le_bytes(b.try_into().unwrap()))
            .collect()
    }
}

/// Eye (0, 0, 5) looking down -z, fov 90 (half_w = 1); a unit sphere at the origin (id 0) and
/// one quad per quadrant behind it, each at its own depth, clear of the axes so that rays in
/// the plane y = 0 see the background: top-left z = -10 (id 1), top-right z = -12 (id 2),
/// bottom-left z = -14 (id 3), bottom-right z = -16 (id 4).
pub(crate) const KNOWN: &str = "\
# known pixels
camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 90
sphere 0 0 0 1
quad -100 2 -10  -2 2 -10  -2 100 -10  -100 100 -10
quad 2 2 -12  100 2 -12  100 100 -12  2 100 -12
quad -100 -100 -14  -2 -100 -14  -2 -2 -14  -100 -2 -14
quad 2 -100 -16  100 -100 -16  100 -2 -16  2 -2 -16
";

const KW: usize = 65;
const KH: usize = 49;

/// The camera formula by hand, in f64: the unit direction of pixel (x, y) for the KNOWN camera
/// (f = -z, r = +x, u = +y, half_w = tan(45 deg) = 1, half_h = H / W).
fn known_dir(x: usize, y: usize) -> [f64; 3] {
    let half_w = 1.0;
    let sx = (2.0 * (x as f64 + 0.5) / KW as f64 - 1.0) * half_w;
    let sy = (1.0 - 2.0 * (y as f64 + 0.5) / KH as f64) * half_w * KH as f64 / KW as f64;
    let v = [sx, sy, -1.0];
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / len)
}

#[test]
fn ids_and_depth_npy_hold_known_pixels_in_every_kernel() {
    let dir = TempDir::new("known");
    dir.write("known.sc", KNOWN);
    let size = format!("{KW}x{KH}");
    for kernel in ["simd", "scalar", "scalar-f32"] {
        let (ids_name, depth_name) = (format!("ids-{kernel}.npy"), format!("depth-{kernel}.npy"));
        let png = format!("{kernel}.png");
        ok(
            &dir,
            &[
                "-i",
                "known.sc",
                "-size",
                &size,
                "--kernel",
                kernel,
                "-o",
                &png,
                "--ids",
                &ids_name,
                "--depth",
                &depth_name,
                "-cm",
                "ordered",
            ],
        );
        let ids = read_npy(&dir.join(&ids_name));
        ids.check("<i4", KW, KH);
        let depth = read_npy(&dir.join(&depth_name));
        depth.check("<f4", KW, KH);
        let (ids, depth) = (ids.i32s(), depth.f32s());
        let at = |x: usize, y: usize| (ids[y * KW + x], depth[y * KW + x]);

        // Centre pixel: with W and H odd, sx = sy = 0, the ray is exactly the view direction
        // and hits the sphere's front at distance 5 - 1 = 4.
        let (id, t) = at(KW / 2, KH / 2);
        assert_eq!(id, 0, "{kernel}: centre id");
        assert!((t - 4.0).abs() <= 1e-6, "{kernel}: centre depth {t}");

        // The left and right ends of the middle row (y = 0 plane) see the background.
        for x in [0, KW - 1] {
            let (id, t) = at(x, KH / 2);
            assert_eq!(id, -1, "{kernel}: ({x}, {}) background id", KH / 2);
            assert_eq!(t, f32::INFINITY, "{kernel}: background depth");
        }

        // Corners: row 0 is the top. Depth = (5 - z_plane) / -d.z, from the formula by hand.
        for (x, y, id_want, z_plane) in [
            (0, 0, 1, -10.0),
            (KW - 1, 0, 2, -12.0),
            (0, KH - 1, 3, -14.0),
            (KW - 1, KH - 1, 4, -16.0),
        ] {
            let d = known_dir(x, y);
            let want = (5.0 - z_plane) / -d[2];
            let (id, t) = at(x, y);
            assert_eq!(id, id_want, "{kernel}: ({x}, {y}) id");
            let rel = (t as f64 - want).abs() / want;
            assert!(
                rel <= 1e-6,
                "{kernel}: ({x}, {y}) depth {t}, by hand {want}"
            );
        }

        // The image agrees: background black, the rest not.
        let img = image_of(&dir.join(&png), KW as u32, KH as u32);
        for (i, p) in img.pixels().enumerate() {
            assert_eq!(
                p.0 == [0, 0, 0],
                ids[i] < 0,
                "{kernel}: pixel {i}: {:?}",
                p.0
            );
        }
    }
    // The kernels agree on every id here (no pixel is near an edge at this size).
    let simd = read_npy(&dir.join("ids-simd.npy")).i32s();
    assert_eq!(simd, read_npy(&dir.join("ids-scalar.npy")).i32s());
    assert_eq!(simd, read_npy(&dir.join("ids-scalar-f32.npy")).i32s());
}

#[test]
fn npy_of_a_seed_scene_matches_its_image() {
    let dir = with_scene1("npy");
    ok(
        &dir,
        &[
            "-i",
            "scene1.sc",
            "-size",
            "160x120",
            "--ids",
            "ids.npy",
            "--depth",
            "depth.npy",
        ],
    );
    let ids = read_npy(&dir.join("ids.npy"));
    ids.check("<i4", 160, 120);
    let depth = read_npy(&dir.join("depth.npy"));
    depth.check("<f4", 160, 120);
    let (ids, depth) = (ids.i32s(), depth.f32s());
    let img = image_of(&dir.join("scene1.png"), 160, 120);
    let scene = lanecast::scene::load_scene(&dir.join("scene1.sc")).unwrap();
    assert!(ids.iter().any(|&i| i >= 0) && ids.contains(&-1));
    for (i, (&id, &t)) in ids.iter().zip(&depth).enumerate() {
        if id < 0 {
            assert_eq!(t, f32::INFINITY, "pixel {i}");
            assert_eq!(img.as_raw()[3 * i..3 * i + 3], [0, 0, 0], "pixel {i}");
        } else {
            assert!((id as usize) < scene.shapes.len(), "pixel {i}: id {id}");
            assert!(t.is_finite() && t > 0.0, "pixel {i}: depth {t}");
        }
    }
}
