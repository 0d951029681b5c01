//! README's dataset example ("Many views"), run as written (the scene's path absolute, the
//! scratch folder `$d` a temporary one): an
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
        .find(|l| l.starts_with("lanecast ") && l.contains("--views $d/rig.txt"))
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
    let scenes = || {
        let mut names: Vec<_> = (fs::read_dir(root.join("scenes")).unwrap())
            .map(|e| e.unwrap().file_name())
            .collect();
        names.sort();
        names
    };
    let before = scenes();
    for command in &commands {
        let words: Vec<&str> = command.split_whitespace().collect();
        for pair in words.windows(2) {
            // every file the commands write (or read back) is in the scratch folder `$d`
            if pair[0].starts_with('-') && !["-i", "--orbit"].contains(&pair[0]) {
                assert!(
                    pair[1].starts_with("$d/"),
                    "{command}: {} {}",
                    pair[0],
                    pair[1]
                );
            }
        }
        let args: Vec<String> = (words.iter().skip(1))
            .map(
                |a| match (a.strip_prefix("scenes/"), a.strip_prefix("$d/")) {
                    (Some(rest), _) => root.join("scenes").join(rest).display().to_string(),
                    (_, Some(rest)) => rest.to_string(),
                    _ => a.to_string(),
                },
            )
            .collect();
        let o = Command::new(env!("CARGO_BIN_EXE_lanecast"))
            .args(&args)
            .current_dir(&dir.path)
            .output()
            .unwrap();
        assert_success(&o, command);
    }
    // the views file's run names only ids: it writes no image (beside the scene or anywhere)
    assert_eq!(scenes(), before, "files written into scenes/");
    let pngs = |d: &Path| {
        (fs::read_dir(d).unwrap())
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .path()
                    .extension()
                    .is_some_and(|x| x == "png")
            })
            .count()
    };
    assert_eq!(pngs(&dir.path.join("frames")), 24);
    assert_eq!(pngs(&dir.path), 0);
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
