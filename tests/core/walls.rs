//! The walls with windows (`scene::walls`): the window is exactly the face inset by its
//! margin, measured in the face's own plane by an independent formula (the distance from a
//! point to each edge's geodesic line); the inradius is the largest such margin; glued faces
//! share a colour and a margin; the veil blends what the walls add.

use bevy_curved_spaces::geometry::Geometry;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::scene::Centrepiece;
use bevy_curved_spaces::scene::walls::MIRROR_COLOUR;
use bevy_curved_spaces::scene::{CurvedScene, SceneParts, Shading, WallPanels, WallStyle};
use bevy_curved_spaces::space::{CellWalker, SEED_SPACES, Space};
use bevy_curved_spaces::trace::{RayEnd, first_hit_walled, sample_rays};
use glam::{DVec3, DVec4};

/// The distance from the model point `x` to the geodesic line through the vertex points `a`
/// and `b`, in closed form: with `t` the unit tangent at `a` towards `b`, the nearest point
/// of the line is `x`'s projection onto the plane of `a` and `t`.
fn distance_to_line(g: Geometry, x: DVec4, a: DVec4, b: DVec4) -> f64 {
    let t = g.tangent_towards(a, b);
    match g {
        Geometry::Euclidean => {
            let d = (x - a).truncate();
            let along = d.dot(t.truncate());
            (d.length_squared() - along * along).max(0.0).sqrt()
        }
        Geometry::Spherical => {
            let (p, q) = (g.form(x, a), g.form(x, t));
            (p * p + q * q).sqrt().min(1.0).acos()
        }
        Geometry::Hyperbolic => {
            let (p, q) = (g.form(x, a), g.form(x, t));
            (p * p - q * q).max(1.0).sqrt().acosh()
        }
    }
}

/// Random points of face `f`: convex combinations of its vertices in the chart (a face is
/// flat there), as model points.
fn face_points(space: &Space, f: usize, count: usize, rng: &mut SplitMix64) -> Vec<DVec4> {
    let g = space.geometry();
    let verts: Vec<DVec3> = space.faces()[f]
        .vertices
        .iter()
        .map(|&v| space.vertices()[v])
        .collect();
    (0..count)
        .map(|_| {
            let weights: Vec<f64> = verts.iter().map(|_| rng.unit().powi(3)).collect();
            let sum: f64 = weights.iter().sum();
            let chart = verts
                .iter()
                .zip(&weights)
                .fold(DVec3::ZERO, |acc, (v, w)| acc + *v * (*w / sum));
            g.from_chart(chart).expect("inside the chart")
        })
        .collect()
}

/// The in-plane distance from a point of face `f` to the nearest line of its edges.
fn to_nearest_edge(space: &Space, f: usize, x: DVec4) -> f64 {
    space
        .edges()
        .iter()
        .filter(|e| e.faces.contains(&f))
        .map(|e| {
            distance_to_line(
                space.geometry(),
                x,
                space.vertex_point(e.vertices[0]),
                space.vertex_point(e.vertices[1]),
            )
        })
        .fold(f64::INFINITY, f64::min)
}

fn shading(space: &Space) -> Shading {
    Shading {
        fog_distance: Shading::default_fog_distance(space),
        ..Shading::default()
    }
}

#[test]
fn the_window_is_the_face_inset_by_its_margin_in_every_seed_space() {
    let mut rng = SplitMix64(17);
    for seed in SEED_SPACES {
        let space = seed.build().expect("builds");
        let g = space.geometry();
        for opening in [0.3, 0.7] {
            let style = WallStyle::new(opening).unwrap();
            let walls = WallPanels::new(&space, style, &shading(&space)).expect("walls");
            let (mut on, mut off) = (0, 0);
            for f in 0..space.faces().len() {
                let margin = (1.0 - opening) * walls.faces[f].inradius;
                for x in face_points(&space, f, 60, &mut rng) {
                    let d = to_nearest_edge(&space, f, x);
                    if (d - margin).abs() < 1e-7 {
                        continue;
                    }
                    let panel = walls.on_panel(f, x);
                    assert_eq!(
                        panel,
                        d < margin,
                        "{} face {f}, opening {opening}: a point {d} from the nearest edge, margin {margin}",
                        seed.id
                    );
                    if panel {
                        on += 1;
                    } else {
                        off += 1;
                    }
                }
            }
            assert!(
                on > 20 && off > 20,
                "{} {opening}: both panel ({on}) and window ({off}) sampled",
                seed.id
            );
            // Glued faces are congruent: one margin and one colour for both.
            for (f, face) in space.faces().iter().enumerate() {
                let (a, b) = (&walls.faces[f], &walls.faces[face.partner]);
                assert_eq!(a.margin, b.margin, "{} face {f}", seed.id);
                assert_eq!(a.colour, b.colour, "{} face {f}", seed.id);
            }
            let _ = g;
        }
    }
}

#[test]
fn the_inradius_is_the_largest_margin_a_face_holds() {
    let mut rng = SplitMix64(5);
    for seed in SEED_SPACES {
        let space = seed.build().expect("builds");
        let walls =
            WallPanels::new(&space, WallStyle::new(0.5).unwrap(), &shading(&space)).expect("walls");
        for f in 0..space.faces().len() {
            let rho = walls.faces[f].inradius;
            // No point of the face is farther than ρ from every edge, and sampling comes close.
            let best = face_points(&space, f, 4000, &mut rng)
                .into_iter()
                .map(|x| to_nearest_edge(&space, f, x))
                .fold(0.0, f64::max);
            assert!(
                best <= rho + 1e-9,
                "{} face {f}: a point {best} from every edge, inradius {rho}",
                seed.id
            );
            assert!(
                best >= 0.9 * rho,
                "{} face {f}: sampled best {best} against inradius {rho}",
                seed.id
            );
        }
    }
    // The torus's faces are squares of side 2r (r the cell's inradius): inradius r exactly.
    let torus = bevy_curved_spaces::space::seed_space("torus").unwrap();
    let r = bevy_curved_spaces::space::invariants::inradius(&torus);
    let walls = WallPanels::new(&torus, WallStyle::new(0.5).unwrap(), &shading(&torus)).unwrap();
    for face in &walls.faces {
        assert!(
            (face.inradius - r).abs() < 1e-7,
            "{} against {r}",
            face.inradius
        );
    }
}

#[test]
fn walls_open_fully_are_none_closed_ones_cover_the_face_and_mirrors_are_silver() {
    let space = bevy_curved_spaces::space::seed_space("mirrored-cube").unwrap();
    let sh = shading(&space);
    assert!(WallPanels::new(&space, WallStyle::new(1.0).unwrap(), &sh).is_none());
    let solid = WallPanels::new(&space, WallStyle::new(0.0).unwrap(), &sh).unwrap();
    let mut rng = SplitMix64(3);
    for f in 0..space.faces().len() {
        assert!(solid.faces[f].mirror);
        assert_eq!(solid.faces[f].colour, MIRROR_COLOUR);
        for x in face_points(&space, f, 50, &mut rng) {
            assert!(solid.on_panel(f, x), "face {f}");
        }
    }
    for bad in [-0.1, 1.5, f64::NAN] {
        assert!(WallStyle::new(bad).is_err(), "{bad}");
    }
    for bad in [0.0, -1.0, 1.01, f64::NAN] {
        assert!(WallStyle::with_opacity(0.5, bad).is_err(), "{bad}");
    }
    let three_sphere = bevy_curved_spaces::space::resolve_space(
        "three-sphere",
        std::path::Path::new(""),
        &Default::default(),
    )
    .unwrap();
    assert!(WallPanels::new(&three_sphere, WallStyle::new(0.0).unwrap(), &sh).is_none());
}

#[test]
fn the_veil_holds_what_each_wall_crossed_adds_and_stops_when_little_gets_through() {
    let nothing = SceneParts {
        edges: false,
        centrepiece: Centrepiece::None,
        avatar: false,
        clifford: false,
    };
    for id in ["seifert-weber", "half-turn", "poincare"] {
        let space = bevy_curved_spaces::space::seed_space(id).unwrap();
        let walker = CellWalker::<DVec4>::new(&space);
        let mut scene =
            CurvedScene::with_parts(&space, Shading::default_fog_distance(&space), nothing);
        let alpha = 0.3;
        let style = WallStyle::with_opacity(0.0, alpha).unwrap();
        scene.shading.walls = Some(style);
        let walls = WallPanels::new(&space, style, &scene.shading).unwrap();
        let stop_after = (walls.stop_below.ln() / (1.0 - alpha).ln()).ceil() as usize;
        for ray in sample_rays(&space, 50, 9) {
            let traced = first_hit_walled(&walker, &scene, None, Some(&walls), ray, 64);
            // Solid walls: every crossing passes a panel.
            let RayEnd::Fog(crossings) = traced.end else {
                panic!("{id}: no object, so the ray fades ({:?})", traced.end)
            };
            let through = (1.0 - alpha).powi(crossings as i32);
            assert!((traced.veil.through - through).abs() < 1e-12, "{id}");
            assert!(crossings <= stop_after, "{id}: {crossings} crossings");
            assert!(traced.veil.colour.max_element() > 0.0);
            assert!(traced.veil.colour.max_element() <= 1.0 - through + 1e-12);
        }
    }
}

/// The plugin's scene takes the walls set in `TracerSettings`, else the base scene's own (a
/// scene file's), and an opening of 1 turns either off.
#[test]
fn the_plugin_shows_the_settings_walls_else_the_base_scenes() {
    use bevy_curved_spaces::plugin::components::TracerSettings;
    use bevy_curved_spaces::plugin::render::upload::build_scene;
    let space = bevy_curved_spaces::space::seed_space("poincare").unwrap();
    let mut base = CurvedScene::with_parts(
        &space,
        Shading::default_fog_distance(&space),
        SceneParts::default(),
    );
    let file_walls = WallStyle::with_opacity(0.3, 0.7).unwrap();
    base.shading.walls = Some(file_walls);
    let mut settings = TracerSettings {
        fog_distance: None,
        max_crossings: Some(8),
        quality: Default::default(),
        resolution_scale: 1.0,
        parts: SceneParts::default(),
        time: Some(0.0),
        colour_by: Default::default(),
        walls: None,
        lighting: None,
    };
    let shown = |settings: &TracerSettings, base: Option<&CurvedScene>| {
        build_scene(&space, settings, &[], base).0.shading.walls
    };
    assert_eq!(shown(&settings, None), None);
    assert_eq!(shown(&settings, Some(&base)), Some(file_walls));
    let mine = WallStyle::new(0.8).unwrap();
    settings.walls = Some(mine);
    assert_eq!(shown(&settings, Some(&base)), Some(mine));
    assert_eq!(shown(&settings, None), Some(mine));
    settings.walls = Some(WallStyle::new(1.0).unwrap());
    assert_eq!(shown(&settings, Some(&base)), None);
}
