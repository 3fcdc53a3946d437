//! The walk through the cell of `UT Σ` over the walk contract: each exit is the first point
//! where the base point leaves the polygon (against dense sampling of the flow), a walk
//! ends on the universal cover's geodesic carried by the pairings it crossed, long walks
//! stay in the cell, and the f32 walk keeps the f64 walk's sides. Words that give no
//! SL̃(2,R) space are refused with the reason.

use super::*;
use bevy_curved_spaces::geometry::Ray;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::sl2r::flow::{base_point, moved_by};
use bevy_curved_spaces::space::sl2r::{Sl2rWalker, UnitTangentSpace, side_exit};
use bevy_curved_spaces::space::{CellWalk, Limit};
use glam::{DVec4, Vec4};

const WORDS: [&str; 3] = ["abABcdCD", "abcdABCD", "abABcdCDefEF"];

/// A random ray in the cell: the base point within 0.9 inradii of the centre, `e` and the
/// body velocity at random.
fn start(rng: &mut SplitMix64, space: &UnitTangentSpace) -> Sl2rRay<f64> {
    bevy_curved_spaces::space::sl2r::accuracy::random_start(space, rng)
}

fn as_walk(r: &Sl2rRay<f64>) -> Ray<DVec4> {
    Sl2rWalker::<DVec4>::ray_of(r)
}

fn widen(r: &Sl2rRay<f64>) -> Sl2rRay<DoubleDouble> {
    super::widen(r)
}

/// How far the base point `p` lies outside the polygon (at most 0 inside), by the sides'
/// covectors.
fn outside(space: &UnitTangentSpace, p: [f64; 3]) -> f64 {
    space
        .sides()
        .iter()
        .map(|s| {
            let n = s.normal.map(|x| x.hi);
            (n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) / p[2]
        })
        .fold(f64::NEG_INFINITY, f64::max)
}

#[test]
fn each_exit_is_the_first_point_where_the_base_point_leaves_the_polygon() {
    let mut rng = SplitMix64(71);
    for word in WORDS {
        let space = UnitTangentSpace::new(word).unwrap();
        let walker = Sl2rWalker::<DVec4>::new(&space);
        for _ in 0..200 {
            let ray = start(&mut rng, &space);
            let Some(exit) = walker.exit(&as_walk(&ray), None) else {
                // The base point on a circle inside the polygon for ever: sample a period.
                for i in 1..=400 {
                    let p = base_point(&ray, f64::from(i) * 0.05);
                    assert!(outside(&space, p) <= 1e-12, "{word}: left without an exit");
                }
                continue;
            };
            let n = space.sides()[exit.face].normal.map(|x| x.hi);
            let at = base_point(&ray, exit.t);
            let on = (n[0] * at[0] + n[1] * at[1] + n[2] * at[2]) / at[2];
            assert!(on.abs() < 1e-13, "{word}: the exit is {on:e} off its side");
            for i in 1..1000 {
                let p = base_point(&ray, exit.t * f64::from(i) / 1000.0);
                assert!(
                    outside(&space, p) <= 1e-13,
                    "{word}: outside at {} before the exit at {}",
                    exit.t * f64::from(i) / 1000.0,
                    exit.t
                );
            }
            // Just past it, outside that side.
            let past = base_point(&ray, exit.t + 1e-6);
            assert!(n[0] * past[0] + n[1] * past[1] + n[2] * past[2] > 0.0);
            // The side's own root agrees (the walk's ray derives e_w and e⊥ from the rest).
            let own = side_exit(&ray, n).expect("the side's own root");
            assert!(
                (own - exit.t).abs() <= 1e-12 * (1.0 + exit.t),
                "{own} against {}",
                exit.t
            );
        }
    }
}

#[test]
fn a_walk_ends_on_the_cover_geodesic_carried_by_the_pairings_it_crossed() {
    let mut rng = SplitMix64(72);
    let mut worst = 0.0_f64;
    for word in WORDS {
        let space = UnitTangentSpace::new(word).unwrap();
        let walker = Sl2rWalker::<DVec4>::new(&space);
        let mut crossed_any = 0;
        for _ in 0..60 {
            let s = start(&mut rng, &space);
            let distance = 0.5 + 5.0 * rng.unit();
            let mut faces = Vec::new();
            let (end, walked) =
                CellWalk::walk(&walker, as_walk(&s), Limit::Distance(distance), |c| {
                    faces.push(c.face);
                    true
                });
            assert_eq!(walked, distance);
            crossed_any += faces.len();
            // G = M_k ⋯ M_1 (double-double), the cover geodesic carried by it.
            let d = DoubleDouble::new;
            let mut cover = flow(&widen(&s), d(distance));
            for f in &faces {
                let m = space.sides()[*f].pairing;
                cover = moved_by(&m, &cover);
            }
            let e = widen(&Sl2rWalker::<DVec4>::sl2r_ray(&end));
            let off = gap(&e, &cover);
            worst = worst.max(off / distance.exp());
            assert!(
                off < 1e-12 * distance.exp(),
                "{word}: the end is {off:e} off the cover geodesic after {} crossings",
                faces.len()
            );
        }
        assert!(crossed_any > 30, "{word}: only {crossed_any} crossings");
    }
    println!("walk end against the cover geodesic: worst {worst:.2e} × e^distance");
}

#[test]
fn long_walks_stay_in_the_cell_and_on_the_model() {
    let mut rng = SplitMix64(73);
    for word in WORDS {
        let space = UnitTangentSpace::new(word).unwrap();
        let walker = Sl2rWalker::<DVec4>::new(&space);
        for _ in 0..3 {
            let s = start(&mut rng, &space);
            let mut worst = 0.0_f64;
            let mut count = 0;
            let (end, _) = CellWalk::walk(&walker, as_walk(&s), Limit::Crossings(20_000), |c| {
                let r = Sl2rWalker::<DVec4>::sl2r_ray(&c.ray);
                worst = worst.max(outside(&space, r.frame[2]));
                count += 1;
                true
            });
            let r = Sl2rWalker::<DVec4>::sl2r_ray(&end);
            let [e, f, p] = r.frame;
            let lorentz = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] - u[2] * v[2];
            assert!((lorentz(p, p) + 1.0).abs() < 1e-12);
            assert!((lorentz(e, e) - 1.0).abs() < 1e-12 && lorentz(e, p).abs() < 1e-12);
            assert!(lorentz(f, e).abs() < 1e-12);
            // A ray whose base point circles inside the polygon stops crossing.
            if count == 20_000 {
                assert!(worst < 1e-12, "{word}: {worst:e} outside after a crossing");
            }
        }
    }
}

#[test]
fn the_f32_walk_keeps_the_f64_walks_sides() {
    let mut rng = SplitMix64(74);
    let (mut same, mut total) = (0, 0);
    for word in WORDS {
        let space = UnitTangentSpace::new(word).unwrap();
        let w64 = Sl2rWalker::<DVec4>::new(&space);
        let w32 = Sl2rWalker::<Vec4>::new(&space);
        for _ in 0..100 {
            let s = start(&mut rng, &space);
            let mut f64_faces = Vec::new();
            let _ = CellWalk::walk(&w64, as_walk(&s), Limit::Crossings(4), |c| {
                f64_faces.push(c.face);
                true
            });
            let s32 = Sl2rWalker::<Vec4>::ray_of(&Sl2rRay {
                frame: s.frame.map(|c| c.map(|x| x as f32)),
                velocity: s.velocity.map(|x| x as f32),
            });
            let mut f32_faces = Vec::new();
            let _ = CellWalk::walk(&w32, s32, Limit::Crossings(4), |c| {
                f32_faces.push(c.face);
                true
            });
            total += 1;
            if f32_faces == f64_faces {
                same += 1;
            }
        }
    }
    assert!(
        same * 100 >= total * 95,
        "f32 kept the sides of {same} of {total} walks"
    );
}

#[test]
fn words_without_an_sl2r_bundle_are_refused_with_the_reason() {
    for (word, says) in [
        ("abAB", "flat"),
        ("aA", "spherical"),
        ("aabb", "non-orientable"),
        ("abAc", "word"),
    ] {
        let e = UnitTangentSpace::new(word).unwrap_err().to_string();
        assert!(
            e.contains(says) || (says == "word" && !e.is_empty()),
            "{word}: {e}"
        );
    }
    let bitorus = UnitTangentSpace::new("abABcdCD").unwrap();
    assert_eq!(bitorus.name(), "unit-tangent-abABcdCD");
    assert_eq!(bitorus.homology().to_string(), "Z/2 + Z + Z + Z + Z");
    assert!((bitorus.volume() - 8.0 * std::f64::consts::PI.powi(2)).abs() < 1e-12);
}

/// The walk in f64 and f32 against the double-double walk from the same start, within the
/// conditioning limit (the exact walk's own spread under one rounding of the start, sampled
/// by four perturbations: a lower estimate, so single walks may sit tens of times above it;
/// the median is about 2), over walks of up to 6 with their crossings.
#[test]
fn f64_and_f32_walks_are_within_a_few_times_the_conditioning_limit() {
    use bevy_curved_spaces::space::sl2r::accuracy::walk_error;
    let mut rng = SplitMix64(75);
    for (name, measure) in [
        (
            "f64",
            walk_error::<DVec4> as fn(&UnitTangentSpace, &Sl2rRay<f64>, f64) -> _,
        ),
        ("f32", walk_error::<Vec4>),
    ] {
        let mut ratios = Vec::new();
        let mut crossings = 0;
        for word in WORDS {
            let space = UnitTangentSpace::new(word).unwrap();
            for _ in 0..25 {
                let start = start(&mut rng, &space);
                let distance = 1.0 + 5.0 * rng.unit();
                let e = measure(&space, &start, distance);
                crossings += e.crossings;
                let eps = if name == "f64" {
                    f64::EPSILON
                } else {
                    f64::from(f32::EPSILON)
                };
                // A few roundings per crossing, carried as the limit grows.
                let own = 8.0 * eps * (1 + e.crossings) as f64;
                assert!(
                    e.error <= 150.0 * e.limit + own * (1.0 + e.limit / eps),
                    "{name} {word}: error {:e} against the limit {:e} after {} crossings",
                    e.error,
                    e.limit,
                    e.crossings
                );
                ratios.push(e.error / e.limit.max(eps));
            }
        }
        ratios.sort_by(f64::total_cmp);
        println!(
            "{name} walk over its conditioning limit: median {:.2}, worst {:.2} ({crossings} crossings)",
            ratios[ratios.len() / 2],
            ratios[ratios.len() - 1]
        );
        assert!(crossings > 50, "{name}: only {crossings} crossings");
    }
}

/// Purely horizontal rays are the surface's geodesic flow: the velocity stays `X` (c = 0
/// turns nothing) and `e` stays the base point's unit velocity, through every crossing.
#[test]
fn horizontal_rays_carry_e_as_the_velocity_of_the_base_point() {
    let mut rng = SplitMix64(76);
    for word in WORDS {
        let space = UnitTangentSpace::new(word).unwrap();
        let walker = Sl2rWalker::<DVec4>::new(&space);
        for _ in 0..20 {
            let mut s = start(&mut rng, &space);
            s.velocity = [1.0, 0.0, 0.0];
            let (end, _) = CellWalk::walk(&walker, as_walk(&s), Limit::Distance(7.0), |c| {
                let r = Sl2rWalker::<DVec4>::sl2r_ray(&c.ray);
                assert!(
                    (r.velocity[0] - 1.0).abs() < 1e-14 && r.velocity[1].abs() < 1e-14,
                    "{word}: the velocity turned: {:?}",
                    r.velocity
                );
                true
            });
            let r = Sl2rWalker::<DVec4>::sl2r_ray(&end);
            // ṗ by a central difference, against e.
            let h = 1e-5;
            let (a, b) = (base_point(&r, -h), base_point(&r, h));
            let e = r.frame[0];
            for i in 0..3 {
                let dp = (b[i] - a[i]) / (2.0 * h);
                assert!(
                    (dp - e[i]).abs() < 1e-8 * (1.0 + e[i].abs()),
                    "{word}: ṗ is not e"
                );
            }
        }
    }
}

/// Rays from the centre straight at a vertex of the polygon (where several cells meet)
/// and along a side's line: they cross consistently, stay in the cell and end on the cover
/// geodesic carried by the pairings crossed.
#[test]
fn rays_through_corners_cross_consistently() {
    for word in WORDS {
        let space = UnitTangentSpace::new(word).unwrap();
        let walker = Sl2rWalker::<DVec4>::new(&space);
        let n = space.sides().len();
        for k in 0..n {
            for half_turns in [2 * k as i64 - 1, 2 * k as i64] {
                // Vertex k at angle (2k − 1)π/n, side k's midpoint at 2kπ/n.
                let angle = half_turns as f64 * std::f64::consts::PI / n as f64;
                let s = Sl2rRay {
                    frame: frame_of([0.0, 0.0, 1.0], [angle.cos(), angle.sin(), 0.0]),
                    velocity: [1.0, 0.0, 0.0],
                };
                let mut faces = Vec::new();
                let mut worst = 0.0_f64;
                let (end, walked) =
                    CellWalk::walk(&walker, as_walk(&s), Limit::Distance(9.0), |c| {
                        faces.push(c.face);
                        let r = Sl2rWalker::<DVec4>::sl2r_ray(&c.ray);
                        worst = worst.max(outside(&space, r.frame[2]));
                        true
                    });
                assert_eq!(walked, 9.0);
                assert!(worst < 1e-9, "{word}: {worst:e} outside the cell");
                let mut cover = flow(&widen(&s), DoubleDouble::new(9.0));
                for f in &faces {
                    cover = moved_by(&space.sides()[*f].pairing, &cover);
                }
                let e = widen(&Sl2rWalker::<DVec4>::sl2r_ray(&end));
                let off = gap(&e, &cover);
                assert!(
                    off < 1e-12 * 9f64.exp(),
                    "{word} at {angle}: {off:e} off the cover geodesic"
                );
            }
        }
    }
}

/// The injectivity radius is `min(π, sys/2)`: half the surface's systole here (the same
/// systole a product with a long circle has), and the two facts behind the π: a geodesic
/// whose base point circles (`c > 1/√2`) comes back to its fibre after `2π/√(2c² − 1)`,
/// its `e` turned by `2π(2c/√(2c² − 1) − 1)`, which is `2π` only for the fibre itself.
#[test]
fn the_injectivity_radius_is_half_the_systole_at_most_pi() {
    use bevy_curved_spaces::space::product::{ProductOrFlat, product_space};
    for word in WORDS {
        let space = UnitTangentSpace::new(word).unwrap();
        let inj = space
            .injectivity_radius(200_000)
            .expect("a searchable group");
        let Some(Ok(ProductOrFlat::Product(product))) =
            product_space(&format!("surface-{word}-circle-100"))
        else {
            panic!("{word}: no product");
        };
        let half_systole = product.injectivity_radius(200_000).unwrap();
        assert!(
            (inj - half_systole.min(std::f64::consts::PI)).abs() < 1e-12,
            "{word}"
        );
        assert!(inj > 0.0 && inj <= std::f64::consts::PI);
    }
    for c in [0.72, 0.8, 0.9, 0.99, 0.999_999] {
        let a = (1.0 - c * c).sqrt();
        let ray = Sl2rRay {
            frame: frame_of(
                [
                    DoubleDouble::new(0.0),
                    DoubleDouble::new(0.0),
                    DoubleDouble::new(1.0),
                ],
                [
                    DoubleDouble::new(1.0),
                    DoubleDouble::new(0.0),
                    DoubleDouble::new(0.0),
                ],
            ),
            velocity: [a, 0.0, c].map(DoubleDouble::new),
        };
        let root = (2.0 * c * c - 1.0).sqrt();
        let period = 2.0 * std::f64::consts::PI / root;
        let turned = 2.0 * std::f64::consts::PI * (2.0 * c / root - 1.0);
        assert!(turned >= 2.0 * std::f64::consts::PI - 1e-9);
        let end = flow(&ray, DoubleDouble::new(period));
        let [e, _, p] = end.frame.map(|v| v.map(|x| x.to_f64()));
        assert!(
            p[0].abs() < 1e-12 && p[1].abs() < 1e-12,
            "c = {c}: the base point did not come back: {p:?}"
        );
        let angle = e[1].atan2(e[0]);
        let want = turned.rem_euclid(std::f64::consts::TAU);
        let diff = (angle.rem_euclid(std::f64::consts::TAU) - want).abs();
        assert!(
            diff < 1e-9 || (std::f64::consts::TAU - diff) < 1e-9,
            "c = {c}: e turned by {angle}, not {turned}"
        );
    }
}

/// The headset's head in an SL̃(2,R) space (`walk --xr`): walking straight ahead in the room
/// walks one geodesic of `UT Σ` through the sides — the head ends where the walker's ray of
/// the same start and direction ends (base point and `e`, through the same pairings) — and
/// stays in the cell with an orthonormal frame.
#[test]
fn a_headset_walks_sl2r_geodesics_through_the_sides() {
    use bevy_curved_spaces::space::FrameSpace;
    use bevy_curved_spaces::space::sl2r::{Sl2rWalker, sl2r_space};
    use bevy_curved_spaces::space::walk::{CellWalk, Limit};
    use bevy_curved_spaces::trace::sl2r::{camera_ray, default_camera};
    use bevy_curved_spaces::view::headset::{HeadTracker, RoomPose};
    use glam::{DQuat, DVec3, DVec4};
    let space = sl2r_space("unit-tangent-bitorus").unwrap().unwrap();
    let start = default_camera(&space).frame;
    let units = 0.8;
    let mut head = HeadTracker::new(start, units, 1e-6);
    head.track(&space, RoomPose::IDENTITY);
    let metres = 8.0;
    let steps = 800;
    for k in 1..=steps {
        let z = -metres * f64::from(k) / f64::from(steps);
        head.track(
            &space,
            RoomPose::new(DVec3::new(0.0, 0.0, z), DQuat::IDENTITY),
        );
        assert!(space.outside_by(head.frame.w_axis) <= 1e-6 + 1e-12);
        assert!(space.frame_defect(head.frame) < 1e-9);
    }
    assert!(
        head.holonomy.crossings >= 2,
        "{} crossings",
        head.holonomy.crossings
    );
    // The walker from the same start along the view's centre, as far.
    let walker = Sl2rWalker::<DVec4>::new(&space);
    let (end, _) = walker.walk(
        Sl2rWalker::<DVec4>::ray_of(&camera_ray(&start, 0.0, 0.0)),
        Limit::Distance(metres * units),
        |_| true,
    );
    let end = Sl2rWalker::<DVec4>::sl2r_ray(&end);
    let f = head.frame;
    let p = [f.w_axis.x, f.w_axis.y, f.w_axis.z];
    let e = [f.x_axis.w, f.y_axis.w, f.z_axis.w];
    let gap = (0..3)
        .map(|i| {
            (p[i] - end.frame[2][i])
                .abs()
                .max((e[i] - end.frame[0][i]).abs())
        })
        .fold(0.0, f64::max);
    assert!(gap < 1e-7, "the head ends {gap:e} from the walked ray");
    // Turning the head as it walks turns only the viewer's axes: `e` and the base point
    // stay a point of UT H², the axes orthonormal (the frame keeps `e` in the axes' fourth
    // entries, which a plain product with the rotation would mix).
    for k in 1..=400 {
        let s = f64::from(k) / 400.0;
        let turn = DQuat::from_rotation_y(3.0 * s) * DQuat::from_rotation_x(0.4 * (5.0 * s).sin());
        head.track(
            &space,
            RoomPose::new(DVec3::new(0.3 * s, 0.0, -metres - 2.0 * s), turn),
        );
        assert!(
            space.frame_defect(head.frame) < 1e-9,
            "{}",
            space.frame_defect(head.frame)
        );
        assert!(space.outside_by(head.frame.w_axis) <= 1e-6 + 1e-12);
    }
}

/// Each reference geodesic (45-digit integration, stored at 40 digits) walked through the
/// cell of the bitorus's bundle and of its double cover in f64: the walk's end is the
/// reference's end brought into the cell by the group (its frame and body velocity), and in
/// the cover on the sheet the reference's lifted angle names — the rays' ends against the
/// independent reference modulo the group, not f64 against f64.
#[test]
fn walked_reference_geodesics_end_where_the_reference_does_modulo_the_group() {
    use bevy_curved_spaces::space::sl2r::cover::sheet_plus;
    use std::f64::consts::{PI, TAU};
    // The sheet of a lifted angle: the number of cuts π + 2πk below it.
    let sheet_of_angle = |lifted: f64| ((lifted - PI) / TAU).ceil() as i64;
    let mut worst = 0.0_f64;
    let mut crossings = 0;
    for sheets in [1, 2] {
        let space = if sheets == 1 {
            UnitTangentSpace::new("abABcdCD").unwrap()
        } else {
            UnitTangentSpace::cover("abABcdCD", 2).unwrap()
        };
        let walker = Sl2rWalker::<DVec4>::new(&space);
        let n = i64::from(sheets);
        for s in super::reference() {
            // The start in the cell, on the sheet of its lifted angle.
            let start = round_ray::<f64>(&s.start);
            let into = space.sheets_into_cell(&start.frame);
            let start_sheet = sheet_plus(0, sheet_of_angle(s.theta.0).rem_euclid(n), sheets);
            let in_cell = Sl2rWalker::<DVec4>::ray_on_sheet(
                &space.into_cell(&start),
                sheet_plus(start_sheet, i64::from(into), sheets),
            );
            let (end, walked) = CellWalk::walk(&walker, in_cell, Limit::Distance(s.t), |_| {
                crossings += 1;
                true
            });
            assert_eq!(walked, s.t);
            // Both brought into the cell once more (an end on a side may sit either way).
            let ours = Sl2rWalker::<DVec4>::sl2r_ray(&end);
            let ours_in = space.into_cell(&ours);
            let ours_sheet = sheet_plus(
                Sl2rWalker::<DVec4>::sheet_of(&end),
                i64::from(space.sheets_into_cell(&ours.frame)),
                sheets,
            );
            let theirs = round_ray::<f64>(&s.end);
            let theirs_in = space.into_cell(&theirs);
            let theirs_sheet = sheet_plus(
                sheet_plus(0, sheet_of_angle(s.theta.1).rem_euclid(n), sheets),
                i64::from(space.sheets_into_cell(&theirs.frame)),
                sheets,
            );
            let off = gap(&widen(&ours_in), &widen(&theirs_in));
            worst = worst.max(off / s.t.exp());
            assert!(
                off < 1e-12 * s.t.exp(),
                "{} at t = {} (N = {sheets}): the walk's end is {off:e} off the reference's",
                s.case,
                s.t
            );
            assert_eq!(
                ours_sheet, theirs_sheet,
                "{} at t = {} (N = {sheets}): the sheet",
                s.case, s.t
            );
        }
    }
    assert!(crossings > 20, "only {crossings} crossings");
    println!("walked reference geodesics: worst {worst:.2e} × e^t off the reference");
}
