//! SL̃(2,R)'s lamp: the geodesic sphere's area density against central differences of the
//! exponential map, the light's reciprocity (the lamp's images found from either end, on
//! the covers' sheets too), shadows walked through the faces, and the reach held below the
//! injectivity radius.

use bevy_curved_spaces::scene::lighting::{LightPaths, Lighting};
use bevy_curved_spaces::space::FrameSpace;
use bevy_curved_spaces::space::sl2r::flow::lorentz;
use bevy_curved_spaces::space::sl2r::{Sl2rRay, Sl2rWalker, UnitTangentSpace, chart_frame, flow};
use bevy_curved_spaces::trace::sl2r::light::{
    LampImage, MAX_LIGHT_REACH, area_density, gather, lamp_images, sl2r_fluence,
};
use bevy_curved_spaces::trace::sl2r::{Sl2rBall, default_scene, scene_with_parts};
use glam::{DVec3, DVec4};

/// The end frame of the geodesic of length `r` from `chart_frame(0.3, −0.2, 0.4)` with the
/// unit body velocity at polar angles `(θ, φ)` (`c = cos θ`).
fn exp_polar(r: f64, theta: f64, phi: f64) -> [[f64; 3]; 3] {
    let start = chart_frame(0.3, -0.2, 0.4);
    let v = [
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    ];
    flow(
        &Sl2rRay {
            frame: start,
            velocity: v,
        },
        r,
    )
    .frame
}

/// The exponential map's polar Jacobian by central differences: each partial derivative of
/// the end frame, read in the end's orthonormal frame (`⟨dp, e⟩`, `⟨dp, e⊥⟩`, `⟨de, e⊥⟩`:
/// horizontal, and the turn of `e`), the determinant over `sin θ`.
fn jacobian(r: f64, theta: f64, phi: f64) -> f64 {
    let h = 1e-5;
    let end = exp_polar(r, theta, phi);
    let [e, f, _] = end;
    let column = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| {
        let d = |k: usize| [0, 1, 2].map(|i| (a[k][i] - b[k][i]) / (2.0 * h));
        let (de, dp) = (d(0), d(2));
        [lorentz(dp, e), lorentz(dp, f), lorentz(de, f)]
    };
    let cols = [
        column(exp_polar(r + h, theta, phi), exp_polar(r - h, theta, phi)),
        column(exp_polar(r, theta + h, phi), exp_polar(r, theta - h, phi)),
        column(exp_polar(r, theta, phi + h), exp_polar(r, theta, phi - h)),
    ];
    let m = glam::DMat3::from_cols_array_2d(&cols);
    m.determinant().abs() / theta.sin()
}

#[test]
fn the_area_density_is_the_exponential_maps_polar_jacobian() {
    // Horizontal, vertical-ish, ω² = 0 (c² = ½) and near it on both sides, short and long.
    let half = std::f64::consts::FRAC_1_SQRT_2;
    for &c in &[0.0, 0.3, 0.6, half - 1e-3, half, half + 1e-3, 0.85, 0.97] {
        for &r in &[0.05, 0.4, 1.0, 2.0, 2.9] {
            for &phi in &[0.3, 2.0] {
                let theta = f64::acos(c);
                let numeric = jacobian(r, theta, phi);
                let closed = area_density(r, c);
                let rel = (numeric - closed).abs() / closed;
                assert!(
                    rel < 1e-6,
                    "r {r}, c {c}, φ {phi}: closed {closed}, central differences {numeric} ({rel:e})"
                );
            }
        }
    }
    // The series and the closed form agree where they meet (|ω²r²| = ½), and the limits.
    for &c in &[0.0, 0.5, 0.8] {
        let w2: f64 = 1.0 - 2.0 * c * c;
        let r = (0.5 / w2.abs()).sqrt() * (1.0 - 1e-12);
        let a = area_density(r, c);
        let b = area_density(r * (1.0 + 1e-9), c);
        assert!((a - b).abs() < 1e-8 * a, "a seam at r {r}, c {c}: {a} {b}");
    }
    let r: f64 = 1.3;
    let horizontal = 2.0 * (r * r.sinh() - r.cosh() + 1.0);
    assert!((area_density(r, 0.0) - horizontal).abs() < 1e-14 * horizontal);
    let vertical = 2.0 * (1.0 - r.cos());
    assert!((area_density(r, 1.0) - vertical).abs() < 1e-14 * vertical);
    assert!((area_density(1e-4, 0.3) - 1e-8).abs() < 1e-15);
}

/// A chart point of the space as a lamp image in the cell.
fn point(space: &UnitTangentSpace, x: [f64; 3]) -> LampImage {
    let ray = space
        .chart_ray(DVec3::from_array(x), DVec3::X)
        .expect("a point");
    LampImage {
        frame: Sl2rWalker::<DVec4>::sl2r_ray(&ray).frame,
        sheet: Sl2rWalker::<DVec4>::sheet_of(&ray),
    }
}

/// The light's sum is symmetric in its two ends: from the lamp at `y` to `x` by the images
/// of `y`, and from `x` to `y` by the images of `x` (`d(x, γy) = d(γ⁻¹x, y)`, and the
/// density depends on `c²` only). A missing image on either side breaks it; in the covers a
/// path ending on the wrong sheet breaks it too.
#[test]
fn the_light_is_the_same_from_either_end() {
    let pairs = [
        ([0.2, 0.0, 0.0], [-0.3, 0.4, 0.3]),
        ([0.9, 0.3, 1.0], [-0.8, -0.2, -2.0]),
        ([0.0, -1.1, 2.5], [0.4, 1.0, -0.5]),
        ([0.6, 0.6, 4.0], [0.6, 0.55, 0.0]),
    ];
    for (word, sheets) in [("abABcdCD", 1), ("abABcdCD", 2), ("abABcdCDefEF", 4)] {
        let space = if sheets == 1 {
            UnitTangentSpace::new(word).unwrap()
        } else {
            UnitTangentSpace::cover(word, sheets).unwrap()
        };
        for (x, y) in pairs {
            for reach in [1.5, MAX_LIGHT_REACH] {
                let (px, py) = (point(&space, x), point(&space, y));
                let there = sl2r_fluence(&space, py, (&px.frame, px.sheet), 1.5, reach);
                let back = sl2r_fluence(&space, px, (&py.frame, py.sheet), 1.5, reach);
                assert_eq!(there.3, back.3, "{word} {sheets}: the reach covered");
                assert_eq!(there.0, back.0, "{word} {sheets} {x:?} {y:?}: paths");
                assert!(
                    (there.1 - back.1).abs() <= 1e-9 * there.1.max(1e-300),
                    "{word} {sheets} {x:?} {y:?} within {reach}: {} against {}",
                    there.1,
                    back.1
                );
            }
        }
    }
}

/// The images are the lamp's orbit: each brought into the cell is the lamp, on its sheet,
/// and they are distinct; the reach never passes the injectivity radius.
#[test]
fn the_images_are_the_lamp_moved_by_the_group() {
    let space = UnitTangentSpace::cover("abABcdCD", 2).unwrap();
    let lamp = point(&space, [-0.5, 0.3, 4.0]);
    let (images, covered) = lamp_images(&space, lamp, 10.0);
    assert_eq!(covered, MAX_LIGHT_REACH, "the reach is held below π");
    assert!(images.len() > 20, "{} images", images.len());
    for image in &images {
        let back = space.into_cell(&Sl2rRay {
            frame: image.frame,
            velocity: [1.0, 0.0, 0.0],
        });
        let apart = (0..3)
            .flat_map(|k| (0..3).map(move |i| (k, i)))
            .map(|(k, i)| (back.frame[k][i] - lamp.frame[k][i]).abs())
            .fold(0.0, f64::max);
        assert!(apart < 1e-9, "an image is not the lamp: {apart}");
        let sheet = bevy_curved_spaces::space::sl2r::cover::sheet_plus(
            image.sheet,
            i64::from(space.sheets_into_cell(&image.frame)),
            2,
        );
        assert_eq!(sheet, lamp.sheet, "an image on the wrong sheet");
    }
    for (i, a) in images.iter().enumerate() {
        for b in &images[i + 1..] {
            let d = (0..3)
                .map(|k| (a.frame[2][k] - b.frame[2][k]).abs())
                .fold(0.0, f64::max);
            assert!(d > 1e-6, "an image twice");
        }
    }
}

/// A ball placed on the shortest geodesic from a point to the lamp shadows it: the point's
/// light from that image is gone with shadow rays, and whole without them; a ball off the
/// path leaves it.
#[test]
fn a_ball_on_the_way_to_the_lamp_casts_its_shadow() {
    let space = UnitTangentSpace::new("abABcdCD").unwrap();
    let mut scene = scene_with_parts(
        &space,
        bevy_curved_spaces::trace::sl2r::Sl2rParts {
            edges: false,
            centre_pillar: false,
            pillars: false,
            ball_stack: false,
        },
    );
    let lamp = point(&space, [0.6, 0.1, 0.2]);
    let x = point(&space, [-0.4, -0.2, -0.3]);
    let lighting = Lighting {
        shadows: 8,
        tail: false,
        ..Lighting::default()
    };
    scene
        .set_lighting(&space, (lamp.frame, lamp.sheet), lighting)
        .unwrap();
    let (r, l) = bevy_curved_spaces::space::sl2r::distance::shortest(&x.frame, &lamp.frame)
        .expect("a path within reach");
    let walker = Sl2rWalker::<DVec4>::new(&space);
    let lit = |scene: &bevy_curved_spaces::trace::sl2r::Sl2rScene| {
        let mut occluded = |ray: Sl2rRay<f64>, sheet: u32, length: f64| {
            let hit =
                bevy_curved_spaces::trace::sl2r::first_hit_on_sheet(&walker, scene, ray, sheet, 24);
            hit.is_some_and(|h| h.distance <= length)
        };
        gather(scene, (&x.frame, 0, 1), DVec3::from_array(l), &mut occluded)
    };
    let open = lit(&scene);
    assert!(open > 0.0, "the point is lit");
    let mid = flow(
        &Sl2rRay {
            frame: x.frame,
            velocity: l,
        },
        0.5 * r,
    );
    let ball = |centre| Sl2rBall {
        centre,
        radius: 0.1,
        colour: DVec3::ONE,
        sheet: 0,
    };
    let mut blocked = scene.clone();
    blocked.balls.push(ball(mid.frame));
    let shadowed = lit(&blocked);
    // The light along that path (the normal is the path's start: a cosine of 1).
    let floor = scene.near_light * scene.near_light;
    let direct = (-r / scene.fog_distance).exp() / area_density(r, l[2]).max(floor);
    assert!(
        open - shadowed >= direct * (1.0 - 1e-9),
        "a ball on the path leaves the light {shadowed} of {open} (the path brings {direct})"
    );
    let aside = chart_frame(0.0, 1.2, 0.0);
    let mut off = scene.clone();
    off.balls.push(ball(aside));
    assert_eq!(lit(&off), open, "a ball off the path changes the light");
    // Without shadow rays the ball on the path changes nothing.
    let mut plain = blocked.clone();
    plain
        .set_lighting(
            &space,
            (lamp.frame, lamp.sheet),
            Lighting {
                shadows: 0,
                ..lighting
            },
        )
        .unwrap();
    assert_eq!(lit(&plain), open);
}

/// The default scene is lit by a lamp in the cell, and the nearest path sums one geodesic.
#[test]
fn the_default_scene_has_a_lamp_in_the_cell() {
    for space in [
        UnitTangentSpace::new("abABcdCD").unwrap(),
        UnitTangentSpace::cover("abABcdCDefEF", 4).unwrap(),
    ] {
        let scene = default_scene(&space);
        let q = scene.light[2];
        assert!(
            q[2].acosh() < space.inradius(),
            "the lamp is in the polygon"
        );
        assert!(scene.light_sheet < space.sheets());
        assert!(!scene.lamp.images.is_empty());
        assert!(scene.lamp.reach <= MAX_LIGHT_REACH);
        assert!(scene.power > 0.0 && scene.power.is_finite());
        let mut nearest = scene.clone();
        nearest
            .set_lighting(
                &space,
                (scene.light, scene.light_sheet),
                Lighting {
                    paths: LightPaths::Nearest,
                    ..Lighting::default()
                },
            )
            .unwrap();
        assert!(nearest.lamp.images.is_empty());
    }
    // Lamps that are no point, or on no sheet, are refused by name.
    let space = UnitTangentSpace::cover("abABcdCD", 2).unwrap();
    let mut scene = default_scene(&space);
    let e = scene
        .set_lighting(&space, ([[f64::NAN; 3]; 3], 0), Lighting::default())
        .unwrap_err();
    assert!(e.contains("no point"), "{e}");
    let e = scene
        .set_lighting(&space, (chart_frame(0.0, 0.0, 0.0), 2), Lighting::default())
        .unwrap_err();
    assert!(e.contains("sheet"), "{e}");
}
