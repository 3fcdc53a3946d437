//! The `curved-spaces` command line: outputs a script can rely on, and clear errors.

use serde_json::{Value, json};
use std::process::{Command, Output};

mod bad_input;
mod bench;
mod commands;
mod edges;
mod nil;
mod sl2r;
mod views;

fn run(args: &[&str]) -> Output {
    // Commands that render on the GPU wait for the GPU tests (one GPU user at a time).
    let _gpu = ["render", "walk", "bench"]
        .iter()
        .any(|c| args.first() == Some(c) && !args.contains(&"--cpu"))
        .then(crate::common::gpu_lock);
    Command::new(env!("CARGO_BIN_EXE_curved-spaces"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn json(args: &[&str]) -> Value {
    let out = run(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

fn fails_with(args: &[&str], needle: &str) {
    let out = run(args);
    assert!(!out.status.success(), "{args:?} should fail");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(needle), "{args:?}: `{err}` lacks `{needle}`");
    assert!(!err.contains("panicked"), "{err}");
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    crate::common::scratch_dir(&format!("cli-{name}"))
}

/// A CPU picture of `args` (a `render` or `flight` command line without its output) as
/// RGB, written under `dir` as `name`.
pub(crate) fn cpu_picture(dir: &std::path::Path, name: &str, args: &[&str]) -> image::RgbImage {
    let out = dir.join(name);
    let mut all = args.to_vec();
    all.extend(["--cpu", "--size", "40x24", "--out", out.to_str().unwrap()]);
    let output = run(&all);
    assert!(
        output.status.success(),
        "{all:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let png = if args[0] == "flight" {
        out.join("frame-00001.png")
    } else {
        out
    };
    image::open(&png).expect("a PNG").to_rgb8()
}
