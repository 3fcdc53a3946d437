//! `curved-spaces`: walk, list, inspect, trace and render closed 3-manifolds and orbifolds.
//!
//! Run with no command to walk the default space in a window (or, with no display, to render
//! it to `curved-spaces.png`).

use clap::Parser;
use std::process::ExitCode;

/// Prints a line to standard output; a closed pipe (`curved-spaces list | head -3`) ends
/// the program quietly instead of panicking.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if let Err(e) = writeln!(std::io::stdout().lock(), $($arg)*) {
            if e.kind() == std::io::ErrorKind::BrokenPipe {
                std::process::exit(0);
            }
            eprintln!("error: cannot write to standard output: {e}");
            std::process::exit(1);
        }
    }};
}

mod cli;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    // SAFETY: nothing else runs yet: no thread has been started that could read the
    // environment while it changes.
    unsafe { bevy_curved_spaces::plugin::offscreen::quiet_runtime_dir() };
    match cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
