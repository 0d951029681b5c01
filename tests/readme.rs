//! README against the program: its Library section shows `examples/library.rs` line for line
//! (CI runs the example, so the README's code is code that compiles and runs); its Tests
//! commands are CI's; the sections other files point to exist; its figures (boundary bands,
//! binary size), its example error message and its mesh formats are the program's. (The
//! ffmpeg example runs in `tests/views_cli/ffmpeg.rs`.)

mod common;

#[allow(unused_imports)] // (the binary's tests need feature `cli`)
use common::*;
use std::path::Path;

/// The body of the first ```rust block after `## Library` in README.md.
fn readme_library_block(readme: &str) -> Vec<&str> {
    let section = &readme[readme
        .find("## Library")
        .expect("README has a Library section")..];
    let start = section.find("```rust\n").expect("a rust block in Library") + "```rust\n".len();
    let len = section[start..].find("```").expect("the block ends");
    section[start..start + len].lines().collect()
}

#[test]
fn readme_library_example_is_examples_library_rs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README.md");
    let example = std::fs::read_to_string(root.join("examples/library.rs")).expect("example");
    // The example's file starts with its `//!` comment, which README's prose replaces.
    let code: Vec<&str> = example
        .lines()
        .skip_while(|l| l.starts_with("//!"))
        .collect();
    assert!(code.len() > 5, "examples/library.rs has code");
    assert_eq!(readme_library_block(&readme), code);
}

/// README.md, whole.
fn readme() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"))
        .expect("README.md")
}

/// README's lines, each with its heading (without the `#`s) when it is one: a line starting
/// with `#` outside a fenced code block.
fn lines_and_headings(readme: &str) -> Vec<(&str, Option<&str>)> {
    let mut fenced = false;
    readme
        .lines()
        .map(|l| {
            fenced ^= l.starts_with("```");
            let heading = (!fenced && l.starts_with('#')).then(|| l.trim_start_matches('#').trim());
            (l, heading)
        })
        .collect()
}

/// The text of README's section `heading` (a `## ` or `### ` line), up to the next heading of
/// any level, with every run of white space made one space (prose wraps anywhere).
fn section(readme: &str, heading: &str) -> String {
    let mut lines = lines_and_headings(readme)
        .into_iter()
        .skip_while(|&(_, h)| h != Some(heading));
    assert!(lines.next().is_some(), "README has no section {heading:?}");
    let body: Vec<&str> = lines
        .take_while(|(_, h)| h.is_none())
        .map(|(l, _)| l)
        .collect();
    body.join(" ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// README's headings, without their `#`s.
fn headings(readme: &str) -> Vec<&str> {
    lines_and_headings(readme)
        .into_iter()
        .filter_map(|(_, h)| h)
        .collect()
}

/// Every reference to README's sections in the repository's source, scripts, docs and
/// configuration (README, a colon, then one or more quoted section names, comma-separated)
/// names a section README has: `.cargo/config.toml` once pointed at a "Build flags" section
/// that README never had.
#[test]
fn references_to_readme_sections_name_sections_it_has() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = readme();
    let headings = headings(&readme);
    let mut files = vec![root.join(".ci/run"), root.join(".cargo/config.toml")];
    let mut dirs = vec![root.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().flatten() {
            let path = entry.path();
            let name = entry.file_name().to_string_lossy().into_owned();
            if path.is_dir() {
                if !name.starts_with('.') && !["target", "node_modules", "dist"].contains(&&*name) {
                    dirs.push(path);
                }
            } else if [".rs", ".md", ".toml", ".sh", ".py", ".js", ".mjs", ".html"]
                .iter()
                .any(|e| name.ends_with(e))
            {
                files.push(path);
            }
        }
    }
    let mut checked = 0;
    for file in files {
        let Ok(text) = std::fs::read_to_string(&file) else {
            continue;
        };
        // The comment markers of a wrapped reference are not part of it.
        let text = text
            .replace("\n#", " ")
            .replace("\n//!", " ")
            .replace("\n//", " ");
        // (Spelled in two parts, so this file holds no reference itself.)
        let key = concat!("READ", "ME: ");
        for (at, _) in text.match_indices(&format!("{key}\"")) {
            let mut rest = &text[at + key.len()..];
            while let Some(quoted) = rest.strip_prefix('"') {
                let Some(end) = quoted.find('"') else { break };
                let name = quoted[..end]
                    .split_whitespace()
                    .collect::<Vec<_>>()
                    .join(" ");
                assert!(
                    headings.contains(&name.as_str()),
                    "{}: README has no section {name:?} (its sections: {headings:?})",
                    file.display()
                );
                checked += 1;
                rest = quoted[end + 1..].trim_start_matches([',', ' ']);
            }
        }
    }
    assert!(checked >= 5, "only {checked} references found");
}

/// The commands in README's "Tests" block are what CI runs, each as a line of `.ci/run`; the
/// workspace's default member is lanecast alone (a user's `cargo run`, `build` or `install`
/// does not compile the lab and its plotting crate), so the Tests commands and every cargo
/// command in `.ci/run` but `fmt --all` and `tree` name their packages.
#[test]
fn readme_test_commands_are_what_ci_runs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = readme();
    let ci = std::fs::read_to_string(root.join(".ci/run")).expect(".ci/run");
    let ci_lines: Vec<&str> = ci.lines().map(str::trim).collect();
    let tests = &readme[readme.find("\n## Tests\n").expect("a Tests section")..];
    let tests = &tests[1..];
    let tests = &tests[..tests[1..].find("\n#").map_or(tests.len(), |e| e + 1)];
    let commands: Vec<&str> = tests
        .lines()
        .filter_map(|l| l.strip_prefix("    "))
        .map(|l| l.split(" # ").next().unwrap().trim())
        .collect();
    assert!(
        !commands.is_empty(),
        "README's Tests section shows a command"
    );
    for c in &commands {
        assert!(ci_lines.contains(c), ".ci/run does not run README's {c:?}");
    }
    assert!(
        commands.iter().any(|c| c.contains("-p lanecast-lab")),
        "README's Tests commands test the lab: {commands:?}"
    );
    let cargo = std::fs::read_to_string(root.join("Cargo.toml")).expect("Cargo.toml");
    assert!(
        cargo
            .lines()
            .any(|l| l.trim() == r#"default-members = ["."]"#),
        "the workspace's default member is lanecast alone"
    );
    for line in &ci_lines {
        let Some(args) = line
            .split_whitespace()
            .skip_while(|w| w.contains('='))
            .collect::<Vec<_>>()
            .join(" ")
            .strip_prefix("cargo ")
            .map(str::to_string)
        else {
            continue;
        };
        if args.starts_with("fmt --all") || args.starts_with("tree ") {
            continue;
        }
        assert!(
            args.contains("-p ") || args.contains("--workspace"),
            ".ci/run's `cargo {args}` builds the default member alone: name its packages"
        );
    }
}

/// Both boundary bands README quotes come from their source: `compare`'s edge band is the
/// view's id band, `Camera::id_band` (`camera::ID_BAND_PIXELS`, an eighth of a pixel), and
/// `--precision auto`'s f32 band is the bound derived for it, `12u + a` (`a` =
/// `Camera::direction_error`, at 60 degrees); README names each, and quotes no other band.
#[test]
fn readme_boundary_bands_are_their_sources() {
    use lanecast::scene::CameraSpec;
    use lanecast::{Camera, experimental::camera::ID_BAND_PIXELS};
    let u = f32::EPSILON as f64 / 2.0;
    assert_eq!(
        ID_BAND_PIXELS, 0.125,
        "README says the id band is an eighth of a pixel"
    );
    let spec = CameraSpec {
        eye: glam::DVec3::new(0.0, 0.0, 5.0),
        look: glam::DVec3::ZERO,
        up: glam::DVec3::Y,
        lens: Some(lanecast::Lens::Fov(60.0)),
    };
    let a = Camera::look_at(&spec, 640, 480).unwrap().direction_error();
    let auto = format!("{:.1e}", 12.0 * u + a);
    let readme = readme();
    let compare = section(&readme, "Command line");
    let compare = &compare[compare.find("`lanecast compare` renders").expect("compare")..];
    assert!(
        compare.contains("within an eighth of a pixel of a boundary")
            && compare.contains("`Camera::id_band`"),
        "README's compare paragraph gives the id band and names it"
    );
    let accuracy = section(&readme, "Accuracy");
    assert!(
        accuracy.contains("the view's id band")
            && accuracy.contains("(an eighth of a pixel)")
            && accuracy.contains(&format!("`12u + a` ({auto} rad at 60"))
            && accuracy.contains("must fit in half of it"),
        "README's Accuracy gives the auto band ({auto} rad), names it, and relates it to \
         the id band"
    );
    let words: Vec<&str> = readme.split_whitespace().collect();
    for w in words.windows(2) {
        let band = w[0]
            .trim_start_matches('(')
            .split_once("e-")
            .is_some_and(|(m, _)| m.contains('.') && m.parse::<f64>().is_ok());
        if w[1].starts_with("rad") && band {
            assert!(
                w[0].trim_start_matches('(') == auto,
                "README quotes a band of {} rad, not {auto} (auto's f32 band)",
                w[0]
            );
        }
    }
}

/// README's scene-format synopsis names both mesh formats a `mesh` line reads.
#[test]
fn readme_mesh_synopsis_names_obj_and_ply() {
    let readme = readme();
    let line = readme
        .lines()
        .find(|l| l.trim_start().starts_with("mesh PATH "))
        .expect("README's synopsis has a mesh line");
    assert!(line.contains("OBJ") && line.contains("PLY"), "{line}");
}

/// `--help`'s first line (clap's about text) names the meshes lanecast reads, OBJ and PLY.
#[cfg(feature = "cli")]
#[test]
fn help_first_line_names_obj_and_ply() {
    let o = run(Path::new(env!("CARGO_MANIFEST_DIR")), &["--help"]);
    let help = stdout(&o);
    let first = help.lines().next().unwrap_or("");
    assert!(first.contains("OBJ") && first.contains("PLY"), "{first}");
}

/// README's example error message is the program's text for the scene it describes.
#[cfg(feature = "cli")]
#[test]
fn readme_error_message_is_the_programs() {
    let text = section(&readme(), "Exit codes");
    let (before, message) = text
        .split_once("gives `lanecast: error: ")
        .expect("README's Exit codes section quotes a message");
    let message = format!(
        "lanecast: error: {}",
        &message[..message.find('`').unwrap()]
    );
    // "a `scene.sc` whose line 3 is `sphere nan 0 0 1` gives"
    let quoted: Vec<&str> = before.split('`').collect();
    let n = quoted.len();
    let (file, statement) = (quoted[n - 4], quoted[n - 2]);
    let line: usize = quoted[n - 3]
        .trim()
        .trim_start_matches("whose line ")
        .trim_end_matches(" is")
        .parse()
        .expect("README names the line");
    let dir = TempDir::new("readme-message");
    let mut scene = String::from("camera eye 0 0 5 look 0 0 0 up 0 1 0\n");
    scene += &"sphere 0 0 0 1\n".repeat(line - 2);
    scene += &format!("{statement}\n");
    dir.write(file, &scene);
    let o = run(&dir.path, &["-i", file, "-o", "out.png"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(stderr(&o).trim_end(), message);
}

/// README's binary size is the release binary's, to 10% (release builds only: a test build's
/// binary is the release profile's under `cargo test --release`).
#[cfg(feature = "cli")]
#[test]
fn readme_binary_size_is_the_binarys() {
    if cfg!(debug_assertions) {
        eprintln!("not checked: a debug build's binary is not the release binary");
        return;
    }
    let text = section(&readme(), "Quick start");
    let at = text
        .find("The binary is ")
        .expect("README gives the binary's size");
    let mib: f64 = text[at + "The binary is ".len()..]
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .expect("a size in MiB");
    let bytes = std::fs::metadata(env!("CARGO_BIN_EXE_lanecast"))
        .unwrap()
        .len() as f64;
    let actual = bytes / (1024.0 * 1024.0);
    assert!(
        (actual / mib - 1.0).abs() <= 0.1,
        "README says {mib} MiB, the binary is {actual:.2} MiB ({bytes} bytes)"
    );
}

/// README's usage lines name every flag of `lanecast --help` (in the spelling README uses: the
/// single-dash forms of the original command line), and README and `--help` both say that an
/// `extrinsic` line takes `fov` as well as `K`.
#[cfg(feature = "cli")]
#[test]
fn readme_usage_names_every_flag_and_extrinsic_lenses() {
    let readme = readme();
    let usage: String = (readme.lines())
        .skip_while(|l| !l.starts_with("    lanecast -i SCENE.sc"))
        .take_while(|l| l.starts_with("    "))
        .collect();
    let help = stdout(&run(Path::new("."), &["--help"]));
    let single = [
        ("--input", "-i"),
        ("--output", "-o"),
        ("--size", "-size"),
        ("--fov", "-fov"),
        ("--color-mode", "-cm"),
        ("--color-variation", "-cv"),
        ("--time", "-time"),
        ("--zdepth", "--zdepth"),
    ];
    let flags = help.split(|c: char| !(c.is_ascii_alphanumeric() || c == '-'));
    for flag in flags.filter(|w| w.starts_with("--") && w.len() > 2) {
        if ["--help", "--version"].contains(&flag) {
            continue;
        }
        let spelled = single
            .iter()
            .find(|(l, _)| *l == flag)
            .map_or(flag, |(_, s)| s);
        assert!(
            usage.contains(spelled),
            "README's usage lacks {spelled}: {usage}"
        );
    }
    assert!(help.contains("extrinsic M00 .. M33 [fov DEG | K"), "{help}");
    assert!(readme.contains("extrinsic M00 .. M33 [K FX\n  FY CX CY | fov DEG]"));
}
