//! --stats.

use super::*;

#[test]
fn stats_record_is_json_with_the_run_in_it() {
    let dir = with_scene1("stats");
    // A scene name that needs escaping in JSON.
    dir.copy_in(&seed_scene(1), "we\"ird\\name.sc");
    ok(
        &dir,
        &[
            "-i",
            "we\"ird\\name.sc",
            "-o",
            "out.png",
            "-size",
            "64x48",
            "--threads",
            "1",
            "--repeat",
            "2",
            "--stats",
            "run.json",
        ],
    );
    let text = fs::read_to_string(dir.join("run.json")).unwrap();
    let v: serde_json::Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    assert_eq!(v["scene"], "we\"ird\\name.sc");
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(64), Some(48))
    );
    let [spheres, triangles, quads] = lanecast::load_scene(&seed_scene(1)).unwrap().counts();
    let count = |k: &str| v["primitives"][k].as_u64().map(|n| n as usize);
    assert_eq!(
        (count("spheres"), count("triangles"), count("quads")),
        (Some(spheres), Some(triangles), Some(quads))
    );
    assert_eq!(v["kernel"], "simd");
    assert_eq!(v["threads"].as_u64(), Some(1));
    assert_eq!(v["renders_s"].as_array().map(Vec::len), Some(2));
    let best = v["render_best_s"].as_f64().expect("a number");
    assert!(best > 0.0 && best <= v["render_median_s"].as_f64().unwrap());
    for phase in ["parse", "setup", "render", "shade", "write"] {
        assert!(
            v["phases_s"][phase].as_f64().is_some(),
            "phase {phase}: {text}"
        );
    }
}
