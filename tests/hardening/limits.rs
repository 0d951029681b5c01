//! Limits (src/limits.rs), each refused before the allocation it guards.

use super::*;

#[test]
fn image_limits_are_refused_before_any_work() {
    use lanecast::limits::{MAX_PIXELS, MAX_SIDE};
    let dir = TempDir::new("limits");
    let scene = good_scene(&dir, "s.sc");
    let out = dir.join("o.png");
    let too_wide = format!("{}x1", MAX_SIDE + 1);
    let side = (MAX_PIXELS as f64).sqrt() as u64 + 1;
    let too_many = format!("{side}x{side}");
    for size in [too_wide.as_str(), too_many.as_str()] {
        let t = std::time::Instant::now();
        let o = run(&[
            "-i".as_ref(),
            scene.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
            "-size".as_ref(),
            size.as_ref(),
        ]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{size}: {err}");
        assert!(err.starts_with("lanecast: error: -size"), "{err}");
        assert!(t.elapsed().as_secs() < 5, "{size}: refused late");
    }
    assert_eq!(dir.entries(), ["s.sc"]);
}

#[test]
fn scene_file_over_the_size_limit_is_refused_before_reading() {
    use lanecast::limits::MAX_SCENE_BYTES;
    let dir = TempDir::new("bigfile");
    let path = dir.join("huge.sc");
    // A sparse file: no disk space used, and lanecast must not read it.
    fs::File::create(&path)
        .unwrap()
        .set_len(MAX_SCENE_BYTES + 1)
        .unwrap();
    let out = TempDir::new("bigfile-out");
    let t = std::time::Instant::now();
    let o = render_into(&path, &out);
    assert_rejected(&path, None, &o, &out);
    assert!(stderr(&o).contains("limit"), "{}", stderr(&o));
    assert!(t.elapsed().as_secs() < 5);
}
