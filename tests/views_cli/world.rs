//! `--accel world`: a view's ids, depths and image depend only on the scene, its camera, the
//! size and the precision. The same camera gives the same bytes alone (`--eye/--look/--up`)
//! and inside a views file, whatever the views' order and the thread count.

use super::*;

fn world_views(dir: &TempDir, scene: &str, views: &Path, threads: &str, prefix: &str) {
    let o = run(
        &dir.path,
        &[
            "-i",
            scene,
            "--views",
            views.to_str().unwrap(),
            "-size",
            "96x64",
            "--accel",
            "world",
            "--threads",
            threads,
            "-o",
            &format!("{prefix}f%d.bmp"),
            "--ids",
            &format!("{prefix}i%d.npy"),
            "--depth",
            &format!("{prefix}d%d.npy"),
        ],
    );
    assert_success(&o, &format!("{scene} world {threads} threads"));
}

#[test]
fn world_views_depend_on_their_camera_alone() {
    let dir = TempDir::new("views-world");
    let mesh = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/teapot.sc");
    for scene in [seed_scene(2), seed_scene(4), mesh] {
        let scene_s = scene.to_str().unwrap();
        let (text, flags) = views_of(&scene, 5);
        let views = dir.write("views.txt", &text);
        // the same cameras, last first
        let mut lines: Vec<&str> = text.lines().filter(|l| l.starts_with("camera")).collect();
        lines.reverse();
        let reversed = dir.write("reversed.txt", &(lines.join("\n") + "\n"));
        world_views(&dir, scene_s, &views, "2", "a");
        world_views(&dir, scene_s, &reversed, "1", "b");
        world_views(&dir, scene_s, &views, "3", "c");
        let n = flags.len();
        for (k, camera) in flags.iter().enumerate() {
            one_view(&dir, scene_s, camera, "world");
            let r = n - 1 - k;
            for (kind, one) in [("f", "one.bmp"), ("i", "one_i.npy"), ("d", "one_d.npy")] {
                let ext = if kind == "f" { "bmp" } else { "npy" };
                let alone = read(&dir.join(one));
                for many in [
                    format!("a{kind}{k}.{ext}"),
                    format!("b{kind}{r}.{ext}"),
                    format!("c{kind}{k}.{ext}"),
                ] {
                    assert!(
                        read(&dir.join(&many)) == alone,
                        "{scene_s} view {k}: {many}"
                    );
                }
            }
        }
    }
}
