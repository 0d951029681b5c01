//! The accuracy lab: `cargo bench -p lanecast-lab --bench lab` runs every intersection method
//! on the stress scenes and the seed scenes against the f64 oracle and writes docs/lab/ (chart,
//! table, error images). Arguments after `--` go to `lanecast_lab::lab_main` (`--only SCENE`,
//! `--method NAME`, `--out DIR`).
//!
//! `cargo bench` passes `--bench`; `cargo test --all-targets` runs this target without it, and
//! then it does nothing (so a test run never rewrites docs/lab).

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if !args.iter().any(|a| a == "--bench") {
        eprintln!(
            "lab: not run (no --bench: start it with `cargo bench -p lanecast-lab --bench lab`)"
        );
        return;
    }
    if let Err(e) = lanecast_lab::lab_main(args) {
        eprintln!("lab: error: {e}");
        std::process::exit(1);
    }
}
