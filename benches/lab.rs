//! The accuracy lab: `cargo bench --bench lab` runs every intersection method on the stress
//! scenes and the seed scenes against the f64 oracle and writes docs/lab/ (chart, table, error
//! images). Arguments after `--` go to `lanecast::lab::lab_main` (`--only SCENE`,
//! `--method NAME`, `--out DIR`).

fn main() {
    if let Err(e) = lanecast::lab::lab_main(std::env::args().skip(1)) {
        eprintln!("lab: error: {e}");
        std::process::exit(1);
    }
}
