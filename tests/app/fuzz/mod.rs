//! The fuzz suite: every shipped scene file and glTF asset mutated (numbers replaced by
//! NaN, infinities, huge, tiny and negative values; lines and keys deleted; truncations;
//! random bytes; out-of-range indices), and every numeric command-line option given
//! hostile values. Each outcome must be a result or a clear error — never a panic, never
//! past a time bound, never a non-finite number in what loads. Deterministic seeds, bounded
//! cases, so it fits in CI; the files that once broke the loaders are kept in
//! `tests/corpus/` and replayed by `the_regression_corpus_is_refused_cleanly`.

mod cli;
mod flights;
mod models;
mod scenes;

use bevy_curved_spaces::geometry::Geometry;
use bevy_curved_spaces::scene::file::parse_scene;
use bevy_curved_spaces::scene::gltf::load;
use proptest::prelude::*;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::time::Instant;

fn manifest() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

use crate::common::HOSTILE;

/// Byte ranges of the number literals of a TOML text (outside comments and strings).
fn numbers(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let code = line.split('#').next().unwrap_or("");
        let bytes = code.as_bytes();
        let mut i = 0;
        let mut in_string = false;
        while i < bytes.len() {
            let c = bytes[i];
            if c == b'"' {
                in_string = !in_string;
            }
            let starts = !in_string
                && (c.is_ascii_digit()
                    || (c == b'-' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit)))
                && (i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_'));
            if starts {
                let start = i;
                i += 1;
                while i < bytes.len()
                    && (bytes[i].is_ascii_digit()
                        || matches!(bytes[i], b'.' | b'e' | b'E' | b'-' | b'+'))
                {
                    i += 1;
                }
                out.push(offset + start..offset + i);
            } else {
                i += 1;
            }
        }
        offset += line.len();
    }
    out
}
