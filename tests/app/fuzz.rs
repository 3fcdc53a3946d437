//! The fuzz suite: every shipped scene file and glTF asset mutated (numbers replaced by
//! NaN, infinities, huge, tiny and negative values; lines and keys deleted; truncations;
//! random bytes; out-of-range indices), and every numeric command-line option given
//! hostile values. Each outcome must be a result or a clear error — never a panic, never
//! past a time bound, never a non-finite number in what loads. Deterministic seeds, bounded
//! cases, so it fits in CI; the files that once broke the loaders are kept in
//! `tests/corpus/` and replayed by `the_regression_corpus_is_refused_cleanly`.

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

fn scene_texts() -> Vec<(PathBuf, String)> {
    let dir = manifest().join("assets/scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p, text)
        })
        .collect()
}

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

/// What a loaded scene holds is finite.
fn scene_is_finite(file: &bevy_curved_spaces::scene::file::SceneFile) -> bool {
    let g: Geometry = file.space.geometry();
    file.base.objects.iter().all(|o| {
        let (c, r) = o.bounding_ball(g);
        c.is_finite() && r.is_finite()
    }) && file.base.lights.iter().all(|l| {
        l.position.is_finite()
            && l.colour.is_finite()
            && l.power.is_finite()
            && l.radius.is_finite()
    }) && file.base.shading.fog_distance.is_finite()
}

/// Parses a mutated scene text within the time bound; `true` for a scene, `false` for an
/// error. A scene must be finite.
fn outcome(text: &str, base: &Path) -> bool {
    use bevy_curved_spaces::trace::product::file::names_product_space;
    if names_product_space(text) {
        return product_outcome(text);
    }
    let started = Instant::now();
    let result = parse_scene(text, base, "fuzz.toml");
    let seconds = started.elapsed().as_secs_f64();
    assert!(seconds < 10.0, "{seconds:.1} s for:\n{text}");
    match result {
        Ok(file) => {
            assert!(scene_is_finite(&file), "a non-finite scene from:\n{text}");
            // Moving objects later on: a scene or an error, never a panic or a hang.
            for t in [2.5, 1e3] {
                if let Ok(scene) = file.scene_at(t) {
                    assert!(scene.objects.iter().all(|o| {
                        let (c, r) = o.bounding_ball(file.space.geometry());
                        c.is_finite() && r.is_finite()
                    }));
                }
            }
            assert!(
                started.elapsed().as_secs_f64() < 20.0,
                "moving objects took too long:\n{text}"
            );
            true
        }
        Err(e) => {
            assert!(e.to_string().starts_with("fuzz.toml"), "{e}");
            false
        }
    }
}

/// A mutated product scene text: a finite scene that traces a small picture without a
/// panic or a hang, or an error naming the file.
fn product_outcome(text: &str) -> bool {
    use bevy_curved_spaces::trace::product::file::parse_product_scene;
    use bevy_curved_spaces::trace::product::{ProductShape, default_camera, render_product};
    let started = Instant::now();
    match parse_product_scene(text, "fuzz.toml") {
        Ok(file) => {
            let s = &file.scene;
            assert!(
                s.objects.iter().all(|o| {
                    let shape = match o.shape {
                        ProductShape::Point(c) | ProductShape::Fibre(c) | ProductShape::Disc(c) => {
                            c.is_finite()
                        }
                        ProductShape::Geodesic { covector, height } => {
                            covector.is_finite() && height.is_finite()
                        }
                        ProductShape::Triangle(t) => t.is_finite(),
                    };
                    shape && o.radius.is_finite() && o.colour.is_finite()
                }) && s.light.is_finite()
                    && s.fog_distance.is_finite(),
                "a non-finite product scene from:\n{text}"
            );
            // Moving balls at a few times: placed where they fly (finite), or a reason.
            for t in [0.0, 1.5, 1e6] {
                if let Ok(at) = file.scene_at(t) {
                    assert!(
                        at.objects.iter().all(|o| match o.shape {
                            ProductShape::Point(c) => c.is_finite(),
                            _ => true,
                        }),
                        "a moving ball off the model at {t} s from:\n{text}"
                    );
                }
            }
            let camera = file.start.unwrap_or_else(|| default_camera(&file.space));
            assert!(camera.point.is_finite() && camera.frame.iter().all(|v| v.is_finite()));
            let image = render_product(&file.space, s, &camera, 8, 4, 16);
            assert_eq!(image.dimensions(), (8, 4));
            assert!(
                started.elapsed().as_secs_f64() < 10.0,
                "slow product scene:\n{text}"
            );
            true
        }
        Err(e) => {
            assert!(e.to_string().starts_with("fuzz.toml"), "{e}");
            false
        }
    }
}

/// Every number of a shipped scene's `[lighting]` table (the reach, the shadows, the lamps'
/// radius, the soft shadows' rays) replaced by every hostile one: a scene or an error that
/// names the file, never a panic.
#[test]
fn lighting_tables_with_every_hostile_number() {
    let mut tried = 0;
    for (path, text) in scene_texts() {
        let Some(start) = text.find("[lighting]") else {
            continue;
        };
        let end = text[start + 1..]
            .find("\n[")
            .map_or(text.len(), |e| start + 1 + e);
        for spot in numbers(&text)
            .into_iter()
            .filter(|s| s.start > start && s.end <= end)
        {
            for value in HOSTILE {
                let mutated = format!("{}{value}{}", &text[..spot.start], &text[spot.end..]);
                outcome(&mutated, path.parent().unwrap());
                tried += 1;
            }
        }
    }
    // torus_shadows.toml and torus_soft_shadows.toml at least.
    assert!(tried >= 6 * HOSTILE.len(), "{tried} mutations");
}

/// A product scene with a moving ball, each of its numbers (position, radius, velocity)
/// replaced by every hostile one: a scene whose ball flies to finite places, or an error
/// that names the file, never a panic.
#[test]
fn moving_product_balls_with_every_hostile_number() {
    let text = "space = \"bitorus-circle\"\n[[object]]\ntype = \"ball\"\n\
                position = [0.3, 0.1, 0.2]\nradius = 0.1\nvelocity = [0.9, 0.2, 0.4]\n";
    let mut tried = 0;
    for spot in numbers(text) {
        for value in HOSTILE {
            let mutated = format!("{}{value}{}", &text[..spot.start], &text[spot.end..]);
            product_outcome(&mutated);
            tried += 1;
        }
    }
    assert!(tried >= 7 * HOSTILE.len(), "{tried} mutations");
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 400,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0xf022),
        ..ProptestConfig::default()
    })]

    /// A number of a shipped scene replaced by a hostile one.
    #[test]
    fn scene_files_with_hostile_numbers(which in 0usize..16, slot in 0usize..64, value in 0usize..HOSTILE.len()) {
        let scenes = scene_texts();
        let (path, text) = &scenes[which % scenes.len()];
        let spots = numbers(text);
        let spot = spots[slot % spots.len()].clone();
        let mutated = format!("{}{}{}", &text[..spot.start], HOSTILE[value], &text[spot.end..]);
        outcome(&mutated, path.parent().unwrap());
    }

    /// A shipped scene with a line deleted, cut short, or with random characters inserted.
    #[test]
    fn scene_files_cut_and_scrambled(which in 0usize..16, line in 0usize..64, cut in 0.0f64..1.0, junk in "[ -~\\n]{0,24}") {
        let scenes = scene_texts();
        let (path, text) = &scenes[which % scenes.len()];
        let base = path.parent().unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let without: Vec<&str> = lines.iter().enumerate().filter(|(i, _)| *i != line % lines.len()).map(|(_, l)| *l).collect();
        outcome(&without.join("\n"), base);
        let mut at = (cut * text.len() as f64) as usize;
        while !text.is_char_boundary(at) {
            at -= 1;
        }
        outcome(&text[..at], base);
        outcome(&format!("{}{junk}{}", &text[..at], &text[at..]), base);
    }
}

/// Deep nesting in a scene file is an error, not a stack overflow.
#[test]
fn deeply_nested_scene_files_are_refused() {
    let base = manifest().join("assets/scenes");
    for depth in [100, 10_000, 1_000_000] {
        let text = format!(
            "space = \"torus\"\nfog = {}1{}\n",
            "[".repeat(depth),
            "]".repeat(depth)
        );
        assert!(!outcome(&text, &base), "depth {depth} accepted");
    }
}

/// The shipped models' bytes, and their JSON and BIN chunks.
fn glb_parts(name: &str) -> (Vec<u8>, Value, Vec<u8>) {
    let bytes = std::fs::read(manifest().join("assets/models").join(name)).unwrap();
    let json_length = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: Value = serde_json::from_slice(&bytes[20..20 + json_length]).unwrap();
    let bin = bytes[20 + json_length + 8..].to_vec();
    (bytes, json, bin)
}

fn glb(doc: &Value, bin: &[u8]) -> Vec<u8> {
    bevy_curved_spaces::scene::gltf::glb_container(&serde_json::to_vec(doc).unwrap(), bin)
}

/// Loads model bytes from a file within the time bound; a loaded model is finite.
fn model_outcome(bytes: &[u8], name: &str) -> bool {
    let path = crate::common::scratch_dir("fuzz-models").join(name);
    std::fs::write(&path, bytes).unwrap();
    let started = Instant::now();
    let result = load(&path);
    let seconds = started.elapsed().as_secs_f64();
    assert!(seconds < 10.0, "{name}: {seconds:.1} s");
    match result {
        Ok(model) => {
            assert!(
                model.source.positions.iter().all(|p| p.is_finite()),
                "{name}: non-finite positions loaded"
            );
            true
        }
        Err(e) => {
            assert!(e.to_string().contains(&path.display().to_string()), "{e}");
            false
        }
    }
}

/// Every number (and index) in a JSON value, as paths into it.
fn json_numbers(v: &Value, path: &mut Vec<Value>, out: &mut Vec<Vec<Value>>) {
    match v {
        Value::Number(_) => out.push(path.clone()),
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                path.push(Value::from(i));
                json_numbers(x, path, out);
                path.pop();
            }
        }
        Value::Object(o) => {
            for (k, x) in o {
                path.push(Value::from(k.as_str()));
                json_numbers(x, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

fn at_path<'a>(v: &'a mut Value, path: &[Value]) -> &'a mut Value {
    path.iter().fold(v, |v, k| match k {
        Value::String(s) => &mut v[s.as_str()],
        k => &mut v[k.as_u64().unwrap() as usize],
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 400,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0xf022),
        ..ProptestConfig::default()
    })]

    /// A number or index of a shipped model's JSON replaced by a hostile one, or its key
    /// deleted.
    #[test]
    fn models_with_hostile_numbers(which in 0usize..2, slot in 0usize..512, value in prop_oneof![
        Just(serde_json::json!(-1)), Just(serde_json::json!(0)), Just(serde_json::json!(1u64 << 40)),
        Just(serde_json::json!(4_294_967_295u64)), Just(serde_json::json!(1e308)), Just(serde_json::json!(-1e308)),
        Just(serde_json::json!(1e-320)), Just(serde_json::json!(3)), Just(Value::Null), Just(serde_json::json!("x")),
    ], delete in any::<bool>()) {
        let name = ["cube.glb", "torus_knot.glb"][which];
        let (_, mut doc, bin) = glb_parts(name);
        let mut spots = Vec::new();
        json_numbers(&doc, &mut Vec::new(), &mut spots);
        let spot = &spots[slot % spots.len()];
        if delete {
            let (key, parent) = spot.split_last().unwrap();
            if let (Value::String(k), Some(o)) = (key, at_path(&mut doc, parent).as_object_mut()) {
                o.remove(k);
            }
        } else {
            *at_path(&mut doc, spot) = value;
        }
        model_outcome(&glb(&doc, &bin), &format!("numbers-{which}-{slot}.glb"));
    }

    /// A shipped model with random bytes overwritten, or cut short.
    #[test]
    fn models_with_random_bytes(which in 0usize..2, at in 0.0f64..1.0, bytes in proptest::collection::vec(any::<u8>(), 1..16), cut in any::<bool>()) {
        let name = ["cube.glb", "torus_knot.glb"][which];
        let (mut file, _, _) = glb_parts(name);
        let start = (at * file.len() as f64) as usize;
        if cut {
            file.truncate(start);
        } else {
            for (i, b) in bytes.iter().enumerate() {
                if let Some(x) = file.get_mut(start + i) {
                    *x = *b;
                }
            }
        }
        model_outcome(&file, &format!("bytes-{which}-{start}.glb"));
    }
}

/// Every file of the regression corpus (inputs that once panicked or hung) is refused with
/// an error, quickly.
#[test]
fn the_regression_corpus_is_refused_cleanly() {
    let dir = manifest().join("tests/corpus");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).expect("tests/corpus exists") {
        let path = entry.unwrap().path();
        let started = Instant::now();
        let message = match path.extension().and_then(|e| e.to_str()) {
            Some("glb" | "gltf") => load(&path).err().map(|e| e.to_string()),
            Some("toml") => {
                match bevy_curved_spaces::trace::product::file::load_product_scene_file(&path) {
                    Err(e) => Some(e.to_string()),
                    Ok(Some(_)) => None,
                    Ok(None) => bevy_curved_spaces::scene::file::load_scene_file(&path)
                        .err()
                        .map(|e| e.to_string()),
                }
            }
            Some("json") => bevy_curved_spaces::space::file::load_space_file(&path)
                .err()
                .map(|e| e.to_string()),
            _ => continue,
        };
        assert!(message.is_some(), "{}: accepted", path.display());
        assert!(
            started.elapsed().as_secs_f64() < 5.0,
            "{}: slow",
            path.display()
        );
        seen += 1;
    }
    assert!(seen >= 8, "only {seen} corpus files");
}

/// A CPU render of `space` at 16×9 with 4 crossings and `extra` arguments: the cheapest
/// run of the renderer for a hostile option.
fn tiny_render<'a>(space: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "render",
        space,
        "--cpu",
        "--size",
        "16x9",
        "--crossings",
        "4",
    ];
    args.extend_from_slice(extra);
    args
}

/// Every numeric option of the command line at 0, negative, NaN, ±inf, 1e308 and 1e-320:
/// a result or an error message, exit status 0 or 1 — never a panic (101) or a signal.
#[test]
fn hostile_numbers_on_the_command_line() {
    let values = ["0", "-1", "nan", "inf", "-inf", "1e308", "1e-320", "-0"];
    let mut outcomes = (0, 0);
    let moving = format!(
        "{}/assets/scenes/seifert_weber_knot.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    for value in values {
        let vec3 = format!("{value},0,0");
        let circle = format!("surface-abABcdCD-circle-{value}");
        let turned = format!("surface-aA-circle-1-turn-{value}");
        let cases: Vec<Vec<&str>> = vec![
            // Every numeric option of the fluence sum.
            vec!["light", "torus", "--at", &vec3],
            vec!["light", "torus", "--light", &vec3, "--at", "0.1,0,0"],
            vec!["light", "torus", "--at", "0.1,0,0", "--fog", value],
            vec!["light", "torus", "--at", "0.1,0,0", "--reach", value],
            vec!["light", "torus", "--at", "0.1,0,0", "--radius", value],
            vec![
                "light", "torus", "--at", "0.1,0,0", "--reach", "1", "--check", value,
            ],
            vec!["light", "poincare", "--at", "0.1,0,0", "--fog", value],
            // A scene with a moving object at a hostile time.
            vec![
                "render",
                "--scene",
                &moving,
                "--cpu",
                "--size",
                "16x9",
                "--crossings",
                "4",
                "--time",
                value,
            ],
            tiny_render("torus", &["--fov", value]),
            tiny_render("torus", &["--time", value]),
            tiny_render("torus", &["--fog", value]),
            tiny_render("torus", &["--ipd", value, "--stereo", "anaglyph"]),
            vec![
                "render",
                "torus",
                "--cpu",
                "--size",
                "16x9",
                "--crossings",
                value,
            ],
            tiny_render("torus", &["--eye", &vec3, "--look-at", "0.1,0.1,0.1"]),
            // The light's reach and shadow count at hostile numbers, in each geometry.
            tiny_render("torus", &["--light-reach", value]),
            tiny_render("seifert-weber", &["--shadows", value]),
            tiny_render("poincare", &["--light-reach", value, "--shadows", "2"]),
            // Soft shadows: a hostile lamp radius and ray count, in each geometry.
            tiny_render("torus", &["--shadows", "2", "--lamp-radius", value]),
            tiny_render(
                "seifert-weber",
                &[
                    "--shadows",
                    "1",
                    "--lamp-radius",
                    "0.3",
                    "--soft-samples",
                    value,
                ],
            ),
            tiny_render(
                "poincare",
                &[
                    "--shadows",
                    "1",
                    "--soft-samples",
                    "3",
                    "--lamp-radius",
                    value,
                ],
            ),
            // A product space's lamp is a point: a radius is refused.
            tiny_render("bitorus-circle", &["--lamp-radius", value]),
            // A product space's lighting at hostile values.
            tiny_render(
                "bitorus-circle",
                &["--light-reach", value, "--shadows", "2"],
            ),
            tiny_render("sphere-circle-turn", &["--shadows", value]),
            // Walls at a hostile opening and opacity.
            tiny_render("poincare", &["--walls", value]),
            tiny_render(
                "mirrored-cube",
                &["--walls", "0.5", "--wall-opacity", value],
            ),
            vec![
                "walk",
                "torus",
                "--record",
                "fuzz.toml",
                "--record-interval",
                value,
            ],
            vec!["trace", "seifert-weber", "--dir", &vec3, "--crossings", "3"],
            vec![
                "trace",
                "seifert-weber",
                "--from",
                &vec3,
                "--dir",
                "1,0,0",
                "--crossings",
                "3",
            ],
            vec!["trace", "torus", "--dir", "1,0,0", "--distance", value],
            vec!["trace", "torus", "--dir", "1,0,0", "--crossings", value],
            // Product spaces: a hostile length, turn, direction and start.
            vec!["info", &circle],
            vec!["info", &turned],
            vec![
                "trace",
                "bitorus-circle",
                "--dir",
                &vec3,
                "--crossings",
                "3",
            ],
            vec![
                "trace",
                "sphere-circle",
                "--from",
                &vec3,
                "--dir",
                "0,1,0.5",
                "--distance",
                "2",
            ],
            vec![
                "trace",
                "projective-plane-circle",
                "--dir",
                "1,0,0.2",
                "--distance",
                value,
            ],
            tiny_render("crosscaps-circle", &["--fog", value]),
        ];
        for mut args in cases {
            let out_dir = crate::common::scratch_dir("fuzz-cli");
            let png = out_dir.join("fuzz.png");
            if args[0] == "render" {
                args.extend(["--out", png.to_str().unwrap()]);
            }
            let started = Instant::now();
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_curved-spaces"))
                .args(&args)
                .output()
                .expect("the binary runs");
            let err = String::from_utf8_lossy(&out.stderr);
            match out.status.code() {
                Some(0) => outcomes.0 += 1,
                Some(1 | 2) => {
                    assert!(err.contains("error"), "{args:?}: no message: {err}");
                    outcomes.1 += 1;
                }
                other => panic!("{args:?}: exit {other:?}\n{err}"),
            }
            assert!(started.elapsed().as_secs_f64() < 30.0, "{args:?}: slow");
        }
    }
    eprintln!(
        "command lines: {} ran, {} refused with a message",
        outcomes.0, outcomes.1
    );
}

/// The shipped flight file, and a recorded-style one with `up`, as texts.
fn flight_texts() -> Vec<String> {
    let shipped = std::fs::read_to_string(
        manifest().join("assets/flights/seifert_weber_through_a_face.toml"),
    )
    .unwrap();
    let recorded = "space = \"poincare\"\nfov = 70\n\n[[key]]\ntime = 0.0\nposition = [0.1, 0.0, 0.2]\n\
                    look_at = [0.1, 0.0, -0.3]\nup = [0.1, 0.5, 0.2]\n\n[[key]]\ntime = 1.5\n\
                    position = [0.1, 0.2, -0.6]\nlook_at = [0.1, 0.2, -1.1]\nup = [0.1, 0.7, -0.6]\n"
        .to_string();
    let product =
        |name: &str| std::fs::read_to_string(manifest().join("assets/flights").join(name)).unwrap();
    vec![
        shipped,
        recorded,
        product("bitorus_through_a_side.toml"),
        product("turned_sphere_up_the_fibre.toml"),
    ]
}

/// A flight text parsed, made for its space and sampled: a flight or an error, never a
/// panic, within the time bound.
fn flight_outcome(text: &str) {
    use bevy_curved_spaces::scene::flight::{Flight, parse_flight};
    use bevy_curved_spaces::space::product::{ProductOrFlat, product_space};
    use bevy_curved_spaces::trace::product::flight::ProductFlight;
    let started = Instant::now();
    if let Ok(file) = parse_flight(text, "fuzz.toml")
        && let Some(id) = &file.space
        && let Ok(space) =
            bevy_curved_spaces::space::resolve_space(id, Path::new(""), &Default::default())
        && let Ok(flight) = Flight::new(&space, &file)
    {
        for t in [0.0, 0.5 * flight.duration(), flight.duration(), 1e9] {
            let f = flight.frame(&space, t);
            assert!(f.is_finite(), "a non-finite frame at {t} s from:\n{text}");
        }
    }
    // A product space's flight: the frames stay finite and in the cell.
    if let Ok(file) = parse_flight(text, "fuzz.toml")
        && let Some(id) = &file.space
        && let Some(Ok(ProductOrFlat::Product(space))) = product_space(id)
        && let Ok(flight) = ProductFlight::new(&space, &file)
    {
        for t in [0.0, 0.5 * flight.duration(), flight.duration(), 1e9] {
            let f = flight.frame(&space, t);
            assert!(f.is_finite(), "a non-finite frame at {t} s from:\n{text}");
            assert!(
                space.outside_by(f.w_axis) < 1e-6,
                "a frame outside the cell at {t} s from:\n{text}"
            );
        }
    }
    let seconds = started.elapsed().as_secs_f64();
    assert!(seconds < 10.0, "{seconds:.1} s for:\n{text}");
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 200,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0xf117),
        ..ProptestConfig::default()
    })]

    /// A number of a flight file replaced by a hostile one.
    #[test]
    fn flight_files_with_hostile_numbers(which in 0usize..4, slot in 0usize..64, value in 0usize..HOSTILE.len()) {
        let texts = flight_texts();
        let text = &texts[which];
        let spots = numbers(text);
        let spot = spots[slot % spots.len()].clone();
        flight_outcome(&format!("{}{}{}", &text[..spot.start], HOSTILE[value], &text[spot.end..]));
    }

    /// A flight file cut short, or with random characters inserted.
    #[test]
    fn flight_files_cut_and_scrambled(which in 0usize..4, cut in 0.0f64..1.0, junk in "[ -~\\n]{0,24}") {
        let texts = flight_texts();
        let text = &texts[which];
        let mut at = (cut * text.len() as f64) as usize;
        while !text.is_char_boundary(at) {
            at -= 1;
        }
        flight_outcome(&text[..at]);
        flight_outcome(&format!("{}{junk}{}", &text[..at], &text[at..]));
    }
}

/// A Bevy mesh built from fuzzed data: positions (some hostile), normals and UVs of the
/// right or a wrong length, indices some of which may point past the vertices, and a
/// topology that may not be a triangle list.
fn fuzzed_bevy_mesh(
    positions: &[[f32; 3]],
    normals: Option<usize>,
    uvs: Option<usize>,
    indices: Option<&[u32]>,
    strip: bool,
) -> bevy::mesh::Mesh {
    use bevy::asset::RenderAssetUsages;
    use bevy::mesh::{Indices, Mesh, PrimitiveTopology};
    let topology = if strip {
        PrimitiveTopology::TriangleStrip
    } else {
        PrimitiveTopology::TriangleList
    };
    let mut mesh = Mesh::new(topology, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions.to_vec());
    if let Some(n) = normals {
        mesh.insert_attribute(Mesh::ATTRIBUTE_NORMAL, vec![[0.0f32, 1.0, 0.0]; n]);
    }
    if let Some(n) = uvs {
        mesh.insert_attribute(Mesh::ATTRIBUTE_UV_0, vec![[0.5f32, 0.5]; n]);
    }
    if let Some(i) = indices {
        mesh.insert_indices(Indices::U32(i.to_vec()));
    }
    mesh
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, failure_persistence: None, ..ProptestConfig::default() })]

    /// Bevy meshes with hostile data (the path of `CurvedObject` with a `Handle<Mesh>`): a
    /// model or a named error, then a traced model or a named error in every geometry —
    /// never a panic, never a non-finite triangle.
    #[test]
    fn bevy_meshes_with_hostile_data(
        raw in proptest::collection::vec((any::<u8>(), -2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0), 0..24),
        normals_off in prop_oneof![Just(None), Just(Some(0usize)), Just(Some(1usize))],
        uvs_off in prop_oneof![Just(None), Just(Some(0usize)), Just(Some(2usize))],
        indices in proptest::option::of(proptest::collection::vec(0u32..30, 0..36)),
        strip in proptest::bool::weighted(0.1),
        size in prop_oneof![Just(0.3f64), Just(0.0), Just(-1.0), Just(f64::NAN), Just(1e300), Just(3.0)],
    ) {
        use bevy_curved_spaces::plugin::objects::model_from_bevy_mesh;
        use bevy_curved_spaces::scene::TracedModel;
        let hostile = [f32::NAN, f32::INFINITY, -f32::INFINITY, 1e38, -1e38, 1e-40, 0.0];
        let positions: Vec<[f32; 3]> = raw
            .iter()
            .map(|&(k, x, y, z)| {
                // One vertex in eight gets a hostile coordinate.
                if k % 8 == 0 {
                    [hostile[usize::from(k / 8) % hostile.len()], y, z]
                } else {
                    [x, y, z]
                }
            })
            .collect();
        let n = positions.len();
        let mesh = fuzzed_bevy_mesh(
            &positions,
            normals_off.map(|d: usize| n + d),
            uvs_off.map(|d: usize| n.saturating_sub(d)),
            indices.as_deref(),
            strip,
        );
        let started = Instant::now();
        if let Ok(model) = model_from_bevy_mesh(&mesh, None) {
            for g in Geometry::ALL {
                if let Ok(traced) = TracedModel::new(g, &model, size) {
                    for t in &traced.mesh.triangles {
                        prop_assert!(t.corners.iter().all(|c| c.is_finite()), "{g:?}: {t:?}");
                    }
                }
            }
        }
        prop_assert!(started.elapsed().as_secs_f64() < 5.0);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    /// Any model of finite triangles goes to a Bevy mesh and back to the same traced
    /// triangles, in every geometry: the asset path and the file path draw alike.
    #[test]
    fn models_round_trip_through_bevy_meshes(
        corners in proptest::collection::vec((-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0), 3..30),
    ) {
        use bevy_curved_spaces::plugin::objects::{bevy_mesh_from_model, model_from_bevy_mesh};
        use bevy_curved_spaces::scene::mesh::MeshSource;
        use bevy_curved_spaces::scene::{Model, SurfaceMaterial, TracedModel};
        use glam::DVec3;
        let positions: Vec<DVec3> = corners
            .iter()
            .map(|&(x, y, z)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)))
            .collect();
        let triangles = positions.len() / 3;
        let model = Model {
            source: MeshSource {
                indices: (0..triangles as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
                materials: vec![0; triangles],
                positions,
                normals: None,
                uvs: None,
            },
            materials: vec![SurfaceMaterial::default()],
            textures: Vec::new(),
        };
        let back = model_from_bevy_mesh(&bevy_mesh_from_model(&model), None).expect("our own mesh");
        for g in Geometry::ALL {
            match (TracedModel::new(g, &model, 0.3), TracedModel::new(g, &back, 0.3)) {
                (Ok(a), Ok(b)) => prop_assert_eq!(&a.mesh, &b.mesh, "{:?}", g),
                (Err(a), Err(b)) => prop_assert_eq!(a.to_string(), b.to_string()),
                (a, b) => prop_assert!(false, "{g:?}: {:?} against {:?}", a.is_ok(), b.is_ok()),
            }
        }
    }
}
