//! The lanecast binary: parse, run, print any error once, exit with its code.

use std::io::Write;

fn main() {
    if let Err(e) = lanecast::run(std::env::args_os()) {
        // a standard error that cannot be written (`2>/dev/full`) leaves the exit code alone
        let _ = writeln!(std::io::stderr().lock(), "lanecast: error: {e}");
        std::process::exit(e.exit_code());
    }
}
