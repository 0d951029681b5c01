//! `lab-render`: one scene with any of the lab's intersection methods, against the f64 oracle
//! (`lanecast_lab::render`). `cargo run -p lanecast-lab --release --bin lab-render -- -h`.

use std::process::ExitCode;

fn main() -> ExitCode {
    let run = || -> lanecast::Result<()> {
        match lanecast_lab::render::parse_args(std::env::args().skip(1))? {
            Some(args) => lanecast_lab::render::lab_render(&args),
            None => {
                println!("{}", lanecast_lab::render::USAGE);
                Ok(())
            }
        }
    };
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("lab-render: error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}
