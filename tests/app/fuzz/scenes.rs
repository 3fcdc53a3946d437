//! Scene files (constant-curvature, product, Nil and SL̃(2,R)): every number made hostile, lines cut and
//! scrambled, tables nested past the parser's depth.

use super::*;

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
    if bevy_curved_spaces::trace::nil::file::names_nil_space(text) {
        return nil_outcome(text);
    }
    if bevy_curved_spaces::trace::sl2r::file::names_sl2r_space(text) {
        return sl2r_outcome(text);
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

/// A mutated SL̃(2,R) scene file: a finite scene that draws, or an error naming the file.
fn sl2r_outcome(text: &str) -> bool {
    use bevy_curved_spaces::trace::sl2r::file::parse_sl2r_scene;
    use bevy_curved_spaces::trace::sl2r::{camera_ray, camera_sheet, trace_sl2r_pixel};
    let started = Instant::now();
    match parse_sl2r_scene(text, "fuzz.toml") {
        Ok(file) => {
            let s = &file.scene;
            assert!(
                s.tubes.iter().all(|t| t.base.iter().all(|x| x.is_finite())
                    && t.radius.is_finite()
                    && t.colour.is_finite())
                    && s.balls
                        .iter()
                        .all(|b| b.centre.iter().flatten().all(|x| x.is_finite())
                            && b.radius > 0.0
                            && b.radius <= 0.5
                            && b.colour.is_finite())
                    && s.fog_distance.is_finite()
                    && s.light.iter().flatten().all(|x| x.is_finite())
                    && s.power.is_finite()
                    && file.start.frame.is_finite(),
                "a non-finite SL̃(2,R) scene from:\n{text}"
            );
            // A few camera rays walk, meet what they meet and are lit (shadow rays walked),
            // never panic, and give a colour.
            let walker =
                bevy_curved_spaces::space::sl2r::Sl2rWalker::<glam::DVec4>::new(&file.space);
            for (x, y) in [(0.0, 0.0), (0.4, -0.3), (-0.7, 0.5)] {
                let colour = trace_sl2r_pixel(
                    (&walker, None),
                    s,
                    camera_ray(&file.start.frame, x, y),
                    camera_sheet(&file.start.frame),
                    8,
                );
                assert!(colour.is_finite(), "a colour {colour} from:\n{text}");
            }
            assert!(started.elapsed().as_secs_f64() < 10.0, "slow:\n{text}");
            true
        }
        Err(e) => {
            assert!(e.to_string().contains("fuzz.toml"), "{e}");
            false
        }
    }
}

/// A mutated Nil scene file: a finite scene that draws, or an error naming the file.
fn nil_outcome(text: &str) -> bool {
    use bevy_curved_spaces::trace::nil::file::parse_nil_scene;
    use bevy_curved_spaces::trace::nil::{NilShape, default_camera, render_nil_view};
    let started = Instant::now();
    match parse_nil_scene(text, "fuzz.toml") {
        Ok(file) => {
            let s = &file.scene;
            assert!(
                s.objects.iter().all(|o| {
                    let shape = match o.shape {
                        NilShape::Ball(c) => c.iter().all(|x| x.is_finite()),
                        NilShape::Fibre(b) => b.iter().all(|x| x.is_finite()),
                        NilShape::Edge { image, .. } => image.iter().all(|x| x.is_finite()),
                    };
                    shape && o.radius.is_finite() && o.colour.is_finite()
                }) && s.light.iter().all(|x| x.is_finite())
                    && s.fog_distance.is_finite()
                    && s.power.is_finite(),
                "a non-finite Nil scene from:\n{text}"
            );
            // Moving balls later on: a scene or an error, never a panic or a hang.
            for t in [2.5, 1e3] {
                if let Ok(at) = file.scene_at(t) {
                    assert!(at.objects.iter().all(|o| match o.shape {
                        NilShape::Ball(c) => c.iter().all(|x| x.is_finite()),
                        _ => true,
                    }));
                }
            }
            let camera = file.start.unwrap_or_else(|| default_camera(&file.space));
            assert!(camera.frame.is_finite());
            let layout = bevy_curved_spaces::view::ViewLayout::new(
                Default::default(),
                false,
                [camera.frame; 2],
                camera.fov_y_degrees,
                8,
                4,
            );
            let image = render_nil_view(&file.space, s, &layout, 16);
            assert_eq!(image.dimensions(), (8, 4));
            assert!(
                started.elapsed().as_secs_f64() < 10.0,
                "slow Nil scene:\n{text}"
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
