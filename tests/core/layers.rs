//! The crate's layers, read from its source: the maths core never names Bevy, the plugin or
//! the app; the plugin never names the app; no two sibling modules name each other (every
//! dependency runs one way); and no source or shader file grows past 800 lines.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const SRC: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/src");
const SHADERS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/shaders");

/// The maths core: no Bevy at compile time.
const CORE: [&str; 8] = [
    "geometry", "space", "scene", "trace", "view", "files", "colour", "random",
];

fn files(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("a source folder") {
        let path = entry.expect("a folder entry").path();
        if path.is_dir() {
            files(&path, ext, out);
        } else if path.extension().is_some_and(|e| e == ext) {
            out.push(path);
        }
    }
}

/// The module path of a source file (`src/space/orbit.rs` → `["space", "orbit"]`); the
/// library's bench lives at `src/app/bench` but is the module `bench`.
fn module_of(path: &Path) -> Vec<String> {
    let rel = path.strip_prefix(SRC).expect("under src");
    let mut parts: Vec<String> = rel
        .with_extension("")
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    if parts.first().is_some_and(|p| p == "app") && parts.get(1).is_some_and(|p| p == "bench") {
        parts.remove(0);
    }
    if parts == ["lib"] {
        parts.clear();
    }
    parts
}

/// The code of a file without its comments (doc comments included) and string literals.
fn code_of(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let mut code = String::new();
        let mut in_string = false;
        let mut chars = line.chars().peekable();
        while let Some(c) = chars.next() {
            if in_string {
                if c == '\\' {
                    chars.next();
                } else if c == '"' {
                    in_string = false;
                }
                continue;
            }
            if c == '"' {
                in_string = true;
                continue;
            }
            if c == '/' && chars.peek() == Some(&'/') {
                break;
            }
            code.push(c);
        }
        out.push_str(&code);
        out.push('\n');
    }
    out
}

/// The modules a file's code names through `crate::` and `super::` paths.
fn named_modules(module: &[String], code: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let words: Vec<&str> = code
        .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
        .filter(|w| w.contains("::"))
        .collect();
    for w in words {
        let mut parts: Vec<&str> = w.split("::").filter(|p| !p.is_empty()).collect();
        let mut base: Vec<String> = if parts.first() == Some(&"crate") {
            parts.remove(0);
            Vec::new()
        } else if parts.first() == Some(&"super") {
            let mut b = module.to_vec();
            while parts.first() == Some(&"super") {
                parts.remove(0);
                b.pop();
            }
            b
        } else {
            continue;
        };
        base.extend(parts.iter().map(|p| (*p).to_string()));
        out.push(base);
    }
    out
}

#[test]
fn the_core_names_neither_bevy_nor_the_layers_above_it() {
    let mut sources = Vec::new();
    files(Path::new(SRC), "rs", &mut sources);
    let mut offences = Vec::new();
    for path in &sources {
        let module = module_of(path);
        let Some(top) = module.first() else { continue };
        let text = std::fs::read_to_string(path).expect("readable source");
        let code = code_of(&text);
        let mut forbidden: Vec<&str> = Vec::new();
        if CORE.contains(&top.as_str()) {
            forbidden.extend([
                "bevy::",
                "bevy_egui",
                "bevy_mod_",
                "crate::plugin",
                "crate::bench",
            ]);
        } else if top == "plugin" {
            forbidden.push("crate::bench");
        }
        for f in forbidden {
            // Intra-doc links count too: a core page linking up is a dependency up.
            let in_docs = text
                .lines()
                .filter(|l| l.trim_start().starts_with("//"))
                .any(|l| l.contains(&format!("[`{f}")) || l.contains(&format!("({f}")));
            if code.contains(f) || in_docs {
                offences.push(format!("{} names {f}", path.display()));
            }
        }
    }
    assert!(
        offences.is_empty(),
        "layering broken:\n{}",
        offences.join("\n")
    );
}

#[test]
fn every_dependency_between_sibling_modules_runs_one_way() {
    let mut sources = Vec::new();
    files(Path::new(SRC), "rs", &mut sources);
    let modules: BTreeSet<Vec<String>> = sources.iter().map(|p| module_of(p)).collect();
    // Edges between siblings: (parent, from child, to child).
    let mut edges: BTreeMap<Vec<String>, BTreeSet<(String, String)>> = BTreeMap::new();
    for path in &sources {
        if path.ends_with("main.rs") || path.starts_with(Path::new(SRC).join("app/cli")) {
            continue;
        }
        let module = module_of(path);
        let code = code_of(&std::fs::read_to_string(path).expect("readable source"));
        for named in named_modules(&module, &code) {
            // The longest prefix that is a module.
            let Some(target) = (1..=named.len())
                .rev()
                .map(|k| named[..k].to_vec())
                .find(|m| modules.contains(m))
            else {
                continue;
            };
            let common = module
                .iter()
                .zip(&target)
                .take_while(|(a, b)| a == b)
                .count();
            if common < module.len() && common < target.len() {
                edges
                    .entry(module[..common].to_vec())
                    .or_default()
                    .insert((module[common].clone(), target[common].clone()));
            }
        }
    }
    assert!(
        edges.get(&Vec::new()).is_some_and(|e| e.len() > 10),
        "the scan found the crate's top-level dependencies"
    );
    let mut circles = Vec::new();
    for (parent, pairs) in &edges {
        // Depth-first search for a cycle among the siblings.
        let nodes: BTreeSet<&String> = pairs.iter().flat_map(|(a, b)| [a, b]).collect();
        let next = |n: &String| -> Vec<&String> {
            pairs
                .iter()
                .filter(|(a, _)| a == n)
                .map(|(_, b)| b)
                .collect()
        };
        for start in &nodes {
            let mut stack = vec![(*start, vec![(*start).clone()])];
            let mut seen = BTreeSet::new();
            while let Some((n, path)) = stack.pop() {
                for m in next(n) {
                    if m == *start {
                        circles.push(format!(
                            "{}: {} → {}",
                            parent.join("::"),
                            path.join(" → "),
                            m
                        ));
                    } else if seen.insert(m.clone()) {
                        let mut p = path.clone();
                        p.push(m.clone());
                        stack.push((m, p));
                    }
                }
            }
        }
    }
    circles.sort();
    circles.dedup();
    assert!(
        circles.is_empty(),
        "import circles:\n{}",
        circles.join("\n")
    );
}

#[test]
fn no_source_or_shader_file_is_longer_than_800_lines() {
    let mut paths = Vec::new();
    files(Path::new(SRC), "rs", &mut paths);
    files(Path::new(SHADERS), "wgsl", &mut paths);
    let long: Vec<String> = paths
        .iter()
        .filter_map(|p| {
            let n = std::fs::read_to_string(p)
                .expect("readable")
                .lines()
                .count();
            (n > 800).then(|| format!("{}: {n} lines", p.display()))
        })
        .collect();
    assert!(
        long.is_empty(),
        "files to split by concept:\n{}",
        long.join("\n")
    );
}
