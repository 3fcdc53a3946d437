//! The walk against the double-double reference (`space::accuracy`): double-double
//! arithmetic itself, every seed space's f64 and f32 walks at the conditioning limit, rays
//! grazing faces at 1e-10 rad and running along edges against the reference walk of the
//! same path, and the
//! invariants against their closed forms.

use bevy_curved_spaces::geometry::{DoubleDouble, Geometry, Ray, Real, Vector4};
use bevy_curved_spaces::space::accuracy::{same_path_error, summarize, walk_accuracy};
use bevy_curved_spaces::space::catalog::dodecahedron_offset;
use bevy_curved_spaces::space::invariants::{circumradius, edge_length, inradius};
use bevy_curved_spaces::space::{CellWalker, Limit, SEED_SPACES, Space, seed_space};
use bevy_curved_spaces::trace::sample_rays;
use glam::{DVec3, DVec4, Vec4};
use std::f64::consts::PI;

fn dd(x: f64) -> DoubleDouble {
    DoubleDouble::new(x)
}

/// `|a − b|` relative to `|b|`, in double-double.
fn rel(a: DoubleDouble, b: DoubleDouble) -> f64 {
    ((a - b) / b).abs().to_f64()
}

#[test]
fn double_double_arithmetic_holds_32_digits() {
    let tight = 1e-30;
    // π, e and ln 2 to 32 digits (their f64 parts and remainders, from the literature).
    let pi = DoubleDouble {
        hi: PI,
        lo: 1.224_646_799_147_353_2e-16,
    };
    let e = DoubleDouble {
        hi: std::f64::consts::E,
        lo: 1.445_646_891_729_250_2e-16,
    };
    let ln2 = DoubleDouble {
        hi: std::f64::consts::LN_2,
        lo: 2.319_046_813_846_299_6e-17,
    };
    assert!(rel(dd(1.0).atan2(dd(1.0)) * dd(4.0), pi) < tight);
    assert!(rel(dd(1.0).atan2(dd(-1.0)) * dd(4.0) / dd(3.0), pi) < tight);
    assert!(rel(dd(1.0).exp(), e) < tight);
    assert!(rel(dd(2.0).ln(), ln2) < tight);
    let two = dd(2.0).sqrt();
    assert!(rel(two * two, dd(2.0)) < tight);
    assert!(rel(dd(1.0) / dd(3.0) * dd(3.0), dd(1.0)) < tight);
    for x in [1e-3, 0.3, 0.7, 1.0, 2.5, 10.0, 40.0] {
        let x = dd(x) / dd(3.0);
        // ln near 1 is conditioned by 1/x: compare absolutely.
        let scale = x.to_f64().max(1.0);
        assert!((x.exp().ln() - x).abs().to_f64() < tight * scale, "{x:?}");
        let (s, c) = x.sin_cos();
        assert!((s * s + c * c - dd(1.0)).abs().to_f64() < tight, "{x:?}");
        let (ch, sh) = x.cosh_sinh();
        assert!(rel(ch * ch - sh * sh, dd(1.0)) < 1e-30 * ch.to_f64().powi(2));
        assert!(rel(s.atan2(c), x) < tight || x.to_f64() > PI / 2.0);
    }
    // Comparisons look at the low part when the high parts tie.
    assert!(dd(1.0) + dd(1e-20) > dd(1.0));
    assert!(dd(1.0) - dd(1e-20) < dd(1.0));
}

/// The target of the accuracy work: per seed space and precision, the walk's error is
/// within 2× the conditioning limit at the median crossing and 5× at the worst, over
/// sampled 30-crossing rays and a few 100-crossing ones.
#[test]
fn every_seed_space_walks_at_the_conditioning_limit() {
    for seed in SEED_SPACES {
        let space = seed.build().unwrap();
        let rays = sample_rays(&space, 16, 0xacc);
        for (name, rows) in [
            ("f64", collect::<DVec4>(&space, &rays)),
            ("f32", collect::<Vec4>(&space, &rays)),
        ] {
            let s = summarize(&rows).unwrap_or_else(|| panic!("{}: no crossing counts", seed.id));
            assert!(
                s.median <= 2.0 && s.worst <= 5.0,
                "{} {name}: error / conditioning median {:.2}, worst {:.2} over {} crossings",
                seed.id,
                s.median,
                s.worst,
                s.counted
            );
            assert!(
                s.counted >= 40,
                "{} {name}: only {} crossings count",
                seed.id,
                s.counted
            );
        }
    }
}

/// The spherical cells walked in steps of π/4 (their chords pass π/2, or they reach the
/// equator) against the double-double walk of the same cell: the steps and the points past
/// the equator, which are scaled back to the sphere but never turned to their antipodes,
/// keep the walk at the conditioning limit as the seed spaces are.
#[test]
fn the_stepped_spherical_cells_walk_at_the_conditioning_limit() {
    for id in [
        "lens-7-2",
        "prism-3",
        "mirrored-tetrahedron",
        "projective-space",
        "lens-7-1",
    ] {
        let space = crate::common::library_space(id);
        assert!(space.walks_in_steps(), "{id}");
        let rays = sample_rays(&space, 16, 0x57e);
        for (name, rows) in [
            ("f64", collect::<DVec4>(&space, &rays)),
            ("f32", collect::<Vec4>(&space, &rays)),
        ] {
            let s = summarize(&rows).unwrap_or_else(|| panic!("{id}: no crossing counts"));
            assert!(
                s.median <= 2.0 && s.worst <= 5.0,
                "{id} {name}: error / conditioning median {:.2}, worst {:.2} over {} crossings",
                s.median,
                s.worst,
                s.counted
            );
            assert!(s.counted >= 40, "{id} {name}: only {} crossings", s.counted);
            eprintln!(
                "{id} {name}: error / conditioning median {:.2}, worst {:.2} ({} crossings)",
                s.median, s.worst, s.counted
            );
        }
    }
}

fn collect<V: Vector4>(
    space: &Space,
    rays: &[Ray<DVec4>],
) -> Vec<bevy_curved_spaces::space::accuracy::CrossingAccuracy> {
    rays.iter()
        .enumerate()
        .flat_map(|(i, r)| walk_accuracy::<V>(space, *r, if i < 2 { 100 } else { 30 }))
        .collect()
}

/// The bound for a walk of `n` crossings to distance `d`: a few units of rounding per
/// crossing, amplified by how far a rounding at the start can move the end (`cosh d` in
/// H³, `1 + d` in E³, 1 in S³).
fn bound(g: Geometry, epsilon: f64, n: usize, d: f64) -> f64 {
    let amplification = match g {
        Geometry::Hyperbolic => d.cosh(),
        Geometry::Euclidean => 1.0 + d,
        Geometry::Spherical => 1.0,
    };
    16.0 * epsilon * (n as f64 + 1.0) * amplification
}

/// Walks `start` to distance `d` in f64 and f32 and checks both ends against the
/// double-double walk of the same path.
fn check_against_geodesic(space: &Space, start: Ray<DVec4>, d: f64, what: &str) {
    let g = space.geometry();
    let t64 = CellWalker::<DVec4>::new(space).trace(start, Limit::Distance(d));
    let e64 = same_path_error(space, start, &t64);
    let b64 = bound(g, f64::EPSILON, t64.crossings.len(), d);
    assert!(
        e64 <= b64,
        "{what} f64: {e64:.3e} from the reference (bound {b64:.3e})"
    );
    let start32 = Ray {
        point: Vec4::from_f64(start.point),
        tangent: Vec4::from_f64(start.tangent),
    };
    let t32 = CellWalker::<Vec4>::new(space).trace(start32, Limit::Distance(d));
    let e32 = same_path_error(space, start, &t32);
    let b32 = bound(g, f64::from(f32::EPSILON), t32.crossings.len(), d);
    assert!(
        e32 <= b32,
        "{what} f32: {e32:.3e} from the reference (bound {b32:.3e})"
    );
}

fn chart_ray(g: Geometry, from: DVec3, dir: DVec3) -> Ray<DVec4> {
    bevy_curved_spaces::geometry::chart_ray(g, from, dir).unwrap()
}

/// Rays 1e-3 inradii inside each face, running along it tilted 1e-10 rad towards it (they
/// leave through it after a long graze, or through a neighbour), to π inradii (not a
/// multiple of the cell's size, where a ray through a vertex can end exactly on a face).
#[test]
fn rays_grazing_faces_at_1e_10_rad_match_the_reference() {
    for seed in SEED_SPACES {
        let s = seed.build().unwrap();
        let g = s.geometry();
        let r = inradius(&s);
        for (f, face) in s.faces().iter().enumerate() {
            let inside = g.project_point(
                g.from_chart(face.normal * face.offset).unwrap()
                    - 1e-3 * r * face.normal.extend(0.0),
            );
            let along = face.normal.any_orthonormal_vector();
            for tilt in [1e-10_f64, -1e-10, 0.0] {
                let dir = along * tilt.cos() + face.normal * tilt.sin();
                let start = chart_ray(g, g.to_chart(inside), dir);
                check_against_geodesic(
                    &s,
                    start,
                    PI * r,
                    &format!("{} face {f} tilt {tilt}", seed.id),
                );
            }
        }
    }
}

/// Rays exactly along every edge (from its midpoint towards a vertex, where three or more
/// faces meet) and rays from the centre through every vertex, to π inradii (not a
/// multiple of the cell's size, where a ray through a vertex can end exactly on a face).
#[test]
fn rays_along_edges_and_through_vertices_match_the_reference() {
    for seed in SEED_SPACES {
        let s = seed.build().unwrap();
        let g = s.geometry();
        let r = inradius(&s);
        let v = s.vertices();
        for (e, edge) in s.edges().iter().enumerate() {
            let [a, b] = edge.vertices.map(|i| v[i]);
            let start = chart_ray(g, (a + b) / 2.0, b - a);
            check_against_geodesic(&s, start, PI * r, &format!("{} along edge {e}", seed.id));
        }
        for (i, vertex) in v.iter().enumerate() {
            let start = chart_ray(g, DVec3::ZERO, *vertex);
            check_against_geodesic(
                &s,
                start,
                PI * r,
                &format!("{} through vertex {i}", seed.id),
            );
        }
    }
}

/// Inradius, circumradius and edge length of the regular dodecahedra against their closed
/// forms, evaluated in double-double, to 1e-12 relative.
///
/// In the chart the cell is a Euclidean regular dodecahedron with faces at chart distance
/// `r`, `r² = −(1/√5 + cos α)/(κ (1 + cos α))` for dihedral angle α; a Euclidean regular
/// dodecahedron of edge `a` has inradius `a √(250 + 110√5)/20` and circumradius
/// `a √3 (1 + √5)/4`, which give the chart edge `a` and vertex distance `R`. Geodesic radii
/// are `atanh` (H³) or `atan` (S³) of chart distances from the centre, and an edge of chart
/// length `a` between vertices at chart distance `R` has `cosh ℓ = 1 + a²/(2(1 − R²))` in H³,
/// `cos ℓ = 1 − a²/(2(1 + R²))` in S³.
#[test]
fn dodecahedra_invariants_match_their_closed_forms() {
    for (id, alpha) in [
        ("seifert-weber", 2.0 * PI / 5.0),
        ("mirrored-dodecahedron", PI / 2.0),
        ("poincare", 2.0 * PI / 3.0),
    ] {
        let s = seed_space(id).unwrap();
        let g = s.geometry();
        let k = dd(g.kappa());
        let one = dd(1.0);
        let sqrt5 = dd(5.0).sqrt();
        let cos_alpha = if id == "poincare" {
            // cos 120° = −½ exactly; the f64 angle is off by its rounding.
            dd(-0.5)
        } else if id == "mirrored-dodecahedron" {
            dd(0.0)
        } else {
            // cos 72° = (√5 − 1)/4.
            (sqrt5 - one) / dd(4.0)
        };
        let r2 = -(one / sqrt5 + cos_alpha) / (k * (one + cos_alpha));
        let r = r2.sqrt();
        // Euclidean regular dodecahedron of edge a: inradius a·√(250 + 110√5)/20,
        // circumradius a·√3 (1 + √5)/4.
        let in_per_edge = (dd(250.0) + dd(110.0) * sqrt5).sqrt() / dd(20.0);
        let circ_per_edge = dd(3.0).sqrt() * (one + sqrt5) / dd(4.0);
        let a = r / in_per_edge;
        let big_r = a * circ_per_edge;
        let geodesic = |x: DoubleDouble| match g {
            // atanh x = ½ ln((1 + x)/(1 − x)), atan x = atan2(x, 1).
            Geometry::Hyperbolic => dd(0.5) * ((one + x) / (one - x)).ln(),
            _ => x.atan2(one),
        };
        let cos_edge = one - k * a * a / (dd(2.0) * (one + k * big_r * big_r));
        let edge = match g {
            // ℓ = ln(c + √(c² − 1)).
            Geometry::Hyperbolic => (cos_edge + (cos_edge * cos_edge - one).sqrt()).ln(),
            _ => (one - cos_edge * cos_edge).sqrt().atan2(cos_edge),
        };
        assert!(rel(dd(inradius(&s)), geodesic(r)) < 1e-12, "{id} inradius");
        assert!(
            rel(dd(circumradius(&s)), geodesic(big_r)) < 1e-12,
            "{id} circumradius"
        );
        assert!(rel(dd(edge_length(&s).unwrap()), edge) < 1e-12, "{id} edge");
        // The catalog's offset is the same closed form in f64.
        assert!(
            rel(dd(dodecahedron_offset(g, alpha)), r) < 1e-14,
            "{id} offset"
        );
    }
}

/// A player's path: `steps` random local steps (translations up to 0.05 inradii per axis,
/// turns up to 0.2 rad) or straight ahead by 0.05 inradii, wrapped into the cell as the
/// plugin does. Returns the f64 frame's drift from the double-double frame of the same path
/// (position, orientation) at the end, and the path's conditioning at half way and at the
/// end: how far the reference moves when its start is turned or moved by `ε` about or along
/// each axis (`None` when not asked for).
fn player_path(
    space: &Space,
    steps: usize,
    straight: bool,
    with_conditioning: bool,
) -> ((f64, f64), Option<(f64, f64)>) {
    use bevy_curved_spaces::plugin::components::{PlayerMotion, PlayerSettings};
    use bevy_curved_spaces::plugin::player::step_frame;
    use bevy_curved_spaces::random::SplitMix64;
    use bevy_curved_spaces::space::accuracy::ReferenceFrame;
    use bevy_curved_spaces::space::wrap_into_cell;
    let g = space.geometry();
    let r = inradius(space);
    let margin = PlayerSettings::default().wrap_margin;
    let mut rng = SplitMix64(0xC0FFEE);
    let mut next = || 2.0 * rng.unit() - 1.0;
    let mut frame = bevy_curved_spaces::view::TraceCamera::default_for(space).frame;
    let mut reference = ReferenceFrame::new(space, frame);
    let mut perturbed: Vec<ReferenceFrame> = if with_conditioning {
        [DVec3::X, DVec3::Y, DVec3::Z]
            .into_iter()
            .flat_map(|axis| {
                let (mut turned, mut moved) = (reference.clone(), reference.clone());
                turned.step(DVec3::ZERO, axis * f64::EPSILON, &[]);
                moved.step(axis * f64::EPSILON, DVec3::ZERO, &[]);
                [turned, moved]
            })
            .collect()
    } else {
        Vec::new()
    };
    let spread = |reference: &ReferenceFrame, perturbed: &[ReferenceFrame]| {
        perturbed
            .iter()
            .map(|p| {
                let (a, b) = reference.drift(p.frame());
                a.max(b)
            })
            .fold(0.0, f64::max)
    };
    let mut half = 0.0;
    for n in 1..=steps {
        let motion = if straight {
            PlayerMotion {
                translation: DVec3::new(0.0, 0.0, -0.05 * r),
                rotation: DVec3::ZERO,
            }
        } else {
            PlayerMotion {
                translation: DVec3::new(next(), next(), next()) * 0.05 * r,
                rotation: DVec3::new(next(), next(), next()) * 0.2,
            }
        };
        let (wrapped, crossed) = wrap_into_cell(space, step_frame(g, frame, &motion), margin);
        frame = wrapped;
        reference.step(motion.translation, motion.rotation, &crossed);
        for p in &mut perturbed {
            p.step(motion.translation, motion.rotation, &crossed);
        }
        if n == steps / 2 && with_conditioning {
            half = spread(&reference, &perturbed);
        }
    }
    let conditioning = with_conditioning.then(|| (half, spread(&reference, &perturbed)));
    (reference.drift(frame), conditioning)
}

/// In E³ and S³ neighbouring paths do not diverge, so the player's frame after 10⁶ random
/// steps is off the double-double frame of the same path by its rounding alone: a few units
/// of ε per step, adding up like a random walk. Bound: `16 √n ε` (measured: 3·10⁻¹³ in the
/// torus, 5·10⁻¹⁴ in Poincaré, against 3.6·10⁻¹²).
#[test]
fn the_player_drifts_by_rounding_alone_in_flat_and_spherical_spaces() {
    let steps = 1_000_000;
    let bound = 16.0 * (steps as f64).sqrt() * f64::EPSILON;
    std::thread::scope(|scope| {
        for id in ["torus", "poincare"] {
            scope.spawn(move || {
                let space = seed_space(id).unwrap();
                let ((position, orientation), _) = player_path(&space, steps, false, false);
                assert!(
                    position <= bound && orientation <= bound,
                    "{id}: after {steps} steps the frame drifted {position:.2e} in position and \
                     {orientation:.2e} in orientation (bound {bound:.2e})"
                );
            });
        }
    });
    // A straight walk through many faces: every step rounds the same way, so the errors
    // add up in step, `n ε` (measured: 1.0·10⁻¹¹ in the half-turn space, against 2.2·10⁻¹¹).
    for id in ["torus", "poincare", "half-turn"] {
        let space = seed_space(id).unwrap();
        let ((position, orientation), _) = player_path(&space, 100_000, true, false);
        let bound = 100_000.0 * f64::EPSILON;
        assert!(
            position <= bound && orientation <= bound,
            "{id} straight: {position:.2e}, {orientation:.2e}"
        );
    }
}

/// In H³ the path itself is ill-conditioned: a turn of `ε` at the start moves the end by
/// `cond = ε e^(λ n)` after `n` steps, `λ` the path's growth rate per step (measured from
/// the conditioning at half way and at the end). One rounding of `ε` per step carried to the
/// end adds up to `cond · √(1/(2λ))` when the roundings are independent (random steps) and
/// to `cond / λ` when every step rounds alike (a straight walk). The player's drift stays
/// within 4× that limit, on a random walk of 8192 steps (before the conditioning reaches the
/// cell's size) and a straight walk of 256 steps (12.7 inradii, through a dozen faces).
#[test]
fn the_player_drifts_at_the_conditioning_limit_in_hyperbolic_space() {
    for id in ["seifert-weber", "mirrored-dodecahedron"] {
        let space = seed_space(id).unwrap();
        for (steps, straight) in [(8192, false), (256, true)] {
            let ((position, orientation), conditioning) =
                player_path(&space, steps, straight, true);
            let (half, end) = conditioning.unwrap();
            let rate = ((end / half).ln() / (steps / 2) as f64).max(1.0 / steps as f64);
            // Random steps round independently (they add up as a random walk); straight
            // steps round the same way every time (they add up in step).
            let limit = if straight {
                end / rate
            } else {
                end * (1.0 / (2.0 * rate)).sqrt()
            };
            eprintln!(
                "{id} {steps} steps{}: drift {:.2e}, limit {limit:.2e} ({:.2}×)",
                if straight { " straight" } else { "" },
                position.max(orientation),
                position.max(orientation) / limit
            );
            assert!(
                position.max(orientation) <= 4.0 * limit,
                "{id} ({} {steps} steps): drift {position:.2e} / {orientation:.2e}, \
                 conditioning {end:.2e}, growth {rate:.2e} per step, limit {limit:.2e}",
                if straight { "straight" } else { "random" }
            );
            assert!(
                end < 1e-6,
                "{id}: the path saturated ({end:.2e}); shorten it"
            );
        }
    }
}
