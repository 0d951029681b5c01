//! The lanecast binary: parse, run, print any error once, exit with its code.

fn main() {
    if let Err(e) = lanecast::run(std::env::args_os()) {
        eprintln!("lanecast: error: {e}");
        std::process::exit(e.exit_code());
    }
}
