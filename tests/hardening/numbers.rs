//! Numbers that parse but break f32 arithmetic (README: "Limits").

use super::*;

fn scene_in(dir: &TempDir, body: &str) -> PathBuf {
    let p = dir.join("s.sc");
    fs::write(&p, body).unwrap();
    p
}

/// Renders `body` 64x48 with both the packet and the f64 scalar kernel; returns the id buffers
/// and asserts no NaN depth, and that `lanecast compare` finds no unexcused mismatch.
pub(crate) fn render_both(body: &str) -> Vec<Vec<i32>> {
    let dir = TempDir::new("numeric");
    let scene = scene_in(&dir, body);
    let o = run(&[
        "compare".as_ref(),
        "-i".as_ref(),
        scene.as_os_str(),
        "-size".as_ref(),
        "64x48".as_ref(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "compare: {}{}",
        String::from_utf8_lossy(&o.stdout),
        stderr(&o)
    );
    let mut all = Vec::new();
    for kernel in ["simd", "scalar"] {
        let (png, ids, depth) = (dir.join("o.png"), dir.join("i.npy"), dir.join("d.npy"));
        let extra = ["-size", "64x48", "--kernel", kernel];
        let o = render_outputs(&scene, [&png, &ids, &depth], &extra);
        assert_eq!(o.status.code(), Some(0), "{kernel}: {}", stderr(&o));
        let d = fs::read(&depth).unwrap();
        let nan = d[128..]
            .chunks(4)
            .any(|c| f32::from_le_bytes(c.try_into().unwrap()).is_nan());
        assert!(!nan, "{kernel}: NaN depth");
        let i = fs::read(&ids).unwrap();
        all.push(
            i[128..]
                .chunks(4)
                .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
                .collect(),
        );
    }
    all
}

pub(crate) fn rejected_with(body: &str, line: usize, words: &[&str]) {
    let dir = TempDir::new("numeric-bad");
    let scene = scene_in(&dir, body);
    let out = TempDir::new("numeric-bad-out");
    let o = render_into(&scene, &out);
    assert_rejected(&scene, Some(line), &o, &out);
    for w in words {
        assert!(stderr(&o).contains(w), "{w:?} not in {}", stderr(&o));
    }
}

#[test]
fn coordinates_near_f32_max_far_from_the_eye_are_rejected() {
    rejected_with(
        &format!("{CAM}sphere 3e38 0 0 1\n"),
        2,
        &["from the camera eye"],
    );
    rejected_with(
        &format!("{CAM}sphere 0 0 0 1\nquad 0 0 -3e38  1 0 -3e38  1 1 -3e38  0 1 -3e38\n"),
        3,
        &["vertex A", "from the camera eye"],
    );
    rejected_with(
        &format!("{CAM}sphere 0 0 0 2e18\n"),
        2,
        &["from the camera eye"],
    );
}

#[test]
fn huge_coordinates_near_the_eye_render() {
    // Absolute coordinates of 1e33 (f32 could not even place them: its spacing there is 1e26),
    // but eye-relative values of at most 6e17: the kernels subtract the eye in f64, so this
    // renders. (Near 3e38 itself, f64's own spacing is 6e22 > MAX_EYE_DISTANCE, so a scene
    // there is always rejected unless a primitive sits exactly on the eye.)
    let far = "camera eye 1e33 1e33 1.0000000000000005e33 look 1e33 1e33 1e33 up 0 1 0\n\
               sphere 1e33 1e33 1e33 1e17\n";
    let ids = render_both(far);
    assert!(ids[0].contains(&0) && ids[0].contains(&-1));
}

#[test]
fn radius_below_the_f32_limit_is_rejected() {
    rejected_with(
        &format!("{CAM}sphere 0 0 0 1e-30\n"),
        2,
        &["radius", "1e-30"],
    );
    // At the limit a tiny sphere seen from close up renders, identically in both kernels.
    let ids = render_both("camera eye 0 0 5e-18 look 0 0 0 up 0 1 0\nsphere 0 0 0 1e-18\n");
    assert!(ids[0].contains(&0) && ids[1].contains(&0));
}

#[test]
fn triangle_whose_area_underflows_f32_renders() {
    // Sides of 1e-20: twice the area is 1e-40, below the smallest normal f32 (1.2e-38) but
    // fine in f64. The edge planes are normalised in f64 before rounding, so the f32 kernel
    // sees unit normals and renders it like the same triangle at scale 1.
    let tiny = "camera eye 0 0 5e-20 look 0 0 0 up 0 1 0\n\
                triangle -1e-20 -1e-20 0  1e-20 -1e-20 0  0 1e-20 0\n";
    let unit = "camera eye 0 0 5 look 0 0 0 up 0 1 0\ntriangle -1 -1 0  1 -1 0  0 1 0\n";
    let (a, b) = (render_both(tiny), render_both(unit));
    let hits = |ids: &[i32]| ids.iter().filter(|&&i| i == 0).count();
    assert!(hits(&a[0]) > 100);
    // Scale 1e-20 renders as scale 1, up to rounding on edge pixels.
    assert!(
        hits(&a[0]).abs_diff(hits(&b[0])) <= 4,
        "{} vs {}",
        hits(&a[0]),
        hits(&b[0])
    );
}

#[test]
fn eye_a_hair_off_a_polygon_plane_is_rejected() {
    rejected_with(
        "camera eye 0.2 0.2 1e-300 look 0 0 -1 up 0 1 0\ntriangle 0 0 0  1 0 0  0 1 0\n",
        2,
        &["plane", "f32"],
    );
    // In the plane exactly: accepted (seen edge-on, the triangle covers no pixel).
    let ids = render_both("camera eye 5 5 0 look 0 0 -1 up 0 1 0\ntriangle 0 0 0  1 0 0  0 1 0\n");
    assert!(ids[0].iter().all(|&i| i == -1));
}
