//! README's dataset example ("Many views"), run as written (the scene's path absolute): an
//! orbit's ids, depths, z-depths and normals, its views file (`--save-views`) and poses
//! (`--stats`); then the views file renders the same ids again.

use super::*;
use std::process::Command;

/// README's two dataset commands: the one with `--save-views` (with its continuation line)
/// and the one reading the views file back.
fn readme_commands(root: &Path) -> [String; 2] {
    let readme = fs::read_to_string(root.join("README.md")).unwrap();
    let lines: Vec<&str> = readme.lines().map(str::trim).collect();
    let at = lines
        .iter()
        .position(|l| l.starts_with("lanecast ") && l.contains("--save-views"))
        .expect("README's Many views saves an orbit's views file");
    let save = format!("{} {}", lines[at].trim_end_matches('\\'), lines[at + 1]);
    let again = lines
        .iter()
        .find(|l| l.starts_with("lanecast ") && l.contains("--views rig.txt"))
        .expect("README's Many views renders the views file again");
    let again = again.split(" # ").next().unwrap().to_string();
    [save, again]
}

#[test]
fn readme_dataset_example_saves_its_poses_and_renders_again_bit_for_bit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = TempDir::new("views-dataset");
    for sub in ["frames", "ids", "depth", "n"] {
        fs::create_dir_all(dir.path.join(sub)).unwrap();
    }
    let commands = readme_commands(root);
    for command in &commands {
        let args: Vec<String> = command
            .split_whitespace()
            .skip(1)
            .map(|a| match a.strip_prefix("scenes/") {
                Some(rest) => root.join("scenes").join(rest).display().to_string(),
                None => a.to_string(),
            })
            .collect();
        let o = Command::new(env!("CARGO_BIN_EXE_lanecast"))
            .args(&args)
            .current_dir(&dir.path)
            .output()
            .unwrap();
        assert_success(&o, command);
    }
    let views = fs::read_to_string(dir.path.join("rig.txt")).unwrap();
    let n = views.lines().filter(|l| l.starts_with("camera ")).count();
    assert_eq!(n, 24, "{views}");
    let stats: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(dir.path.join("rig.json")).unwrap()).unwrap();
    let records = stats["views"].as_array().expect("views[] in --stats");
    assert_eq!(records.len(), 24);
    for (i, v) in records.iter().enumerate() {
        let k = v["K"].as_array().expect("views[i].K");
        let m = v["world_to_camera"]
            .as_array()
            .expect("views[i].world_to_camera");
        assert!(
            k.len() == 3 && k.iter().all(|r| r.as_array().unwrap().len() == 3),
            "{i}"
        );
        assert!(
            m.len() == 4 && m.iter().all(|r| r.as_array().unwrap().len() == 4),
            "{i}"
        );
        let first = format!("ids/{i:05}.npy");
        let again = format!("ids/again_{i:05}.npy");
        assert_eq!(
            read(&dir.path.join(&first)),
            read(&dir.path.join(&again)),
            "{first}"
        );
        for out in [
            format!("depth/z{i:05}.npy"),
            format!("n/{i:05}.npy"),
            format!("frames/{i}.png"),
        ] {
            assert!(dir.path.join(&out).is_file(), "{out}");
        }
    }
}
