//! `curved-spaces`: walk, list, inspect, trace and render closed 3-manifolds and orbifolds.
//!
//! Run with no command to walk the default space in a window (or, with no display, to render
//! it to `curved-spaces.png`).

// `!(x <= tol)` is how the app, like the crate, rejects NaN along with large values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

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
    let code = match cli::run(cli) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("error: {e}");
            1
        }
    };
    exit_now(code)
}

/// Ends the process with `code` once its output is written, without running the exit
/// handlers that libraries registered. A Vulkan driver (lavapipe, through LLVM) registers
/// one and may be unloaded with the last Vulkan instance before the process ends: its
/// handler then crashed the process with SIGSEGV after a refusal had been printed, in about
/// half the runs, and the shell saw 139 instead of the command's own code. Nothing of ours
/// runs at exit: every file is written and closed before `run` returns.
fn exit_now(code: u8) -> ExitCode {
    use std::io::Write as _;
    let _ = std::io::stdout().flush();
    let _ = std::io::stderr().flush();
    #[cfg(unix)]
    {
        // SAFETY: `_exit` ends the process at once; the standard streams are flushed.
        unsafe { libc::_exit(i32::from(code)) }
    }
    #[cfg(not(unix))]
    ExitCode::from(code)
}
