//! README's ffmpeg example ("Many views"): `-o -` streams a turntable into ffmpeg, and the
//! H.264 it makes is yuv420p, the pixel format players and browsers accept (ffmpeg keeps PNG's
//! full-resolution colour, yuv444p, unless told).

use super::*;
use std::process::Command;

/// Whether `tool -version` runs.
fn on_path(tool: &str) -> bool {
    Command::new(tool)
        .arg("-version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// README's line that pipes lanecast into ffmpeg, run as written (but for 8 views of its 120,
/// lanecast this build's binary and the scene's path absolute); ffprobe reads the video back.
#[test]
fn readme_ffmpeg_example_makes_yuv420p_h264() {
    if !on_path("ffmpeg") || !on_path("ffprobe") {
        eprintln!("skipped: ffmpeg and ffprobe are not both on PATH (README's ffmpeg example)");
        return;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = fs::read_to_string(root.join("README.md")).unwrap();
    let example = readme
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with("lanecast ") && l.contains("| ffmpeg "))
        .expect("README's Many views pipes lanecast into ffmpeg");
    let command = example.split(" # ").next().unwrap();
    let output = command
        .split_whitespace()
        .last()
        .expect("ffmpeg's output file");
    // into README's scratch folder `$d`, here the test's own
    assert!(
        output.starts_with("$d/") && output.ends_with(".mp4"),
        "{command}"
    );
    let output = &output["$d/".len()..];
    let replaced = command
        .replacen(
            "lanecast ",
            &format!("'{}' ", env!("CARGO_BIN_EXE_lanecast")),
            1,
        )
        .replace(" scenes/", &format!(" '{}/scenes/'", root.display()))
        .replace("--orbit 120", "--orbit 8");
    assert!(
        replaced.contains("--orbit 8") && replaced.contains(&*root.to_string_lossy()),
        "README's example changed shape: {command}"
    );
    let dir = TempDir::new("views-ffmpeg");
    let o = Command::new("bash")
        .args(["-c", &format!("set -o pipefail; d=.; {replaced}")])
        .current_dir(&dir.path)
        .output()
        .unwrap();
    assert_success(&o, &replaced);
    let probe = Command::new("ffprobe")
        .args([
            "-v",
            "error",
            "-select_streams",
            "v:0",
            "-count_frames",
            "-show_entries",
            "stream=codec_name,pix_fmt,nb_read_frames",
            "-of",
            "default=noprint_wrappers=1",
            output,
        ])
        .current_dir(&dir.path)
        .output()
        .unwrap();
    assert_success(&probe, "ffprobe");
    let info = stdout(&probe);
    for want in ["codec_name=h264", "pix_fmt=yuv420p", "nb_read_frames=8"] {
        assert!(info.lines().any(|l| l == want), "{want} not in:\n{info}");
    }
}
