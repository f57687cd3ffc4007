//! `scanvert`: render, assemble and disassemble display lists through the
//! simulated display hardware. See [`scanvert_sim::cli`].

use std::io::Write;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args_os()
        .skip(1)
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    match scanvert_sim::cli::run(&args) {
        Ok(out) => {
            let _ = std::io::stdout().write_all(out.as_bytes());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("scanvert: {e}");
            ExitCode::from(e.status)
        }
    }
}
