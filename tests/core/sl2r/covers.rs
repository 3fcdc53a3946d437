//! The fibre covers' sheets: the Euler turns of the vertex cycle, the sheet counted along
//! a fibre and through the sides.

use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::sl2r::accuracy::random_start;
use bevy_curved_spaces::space::sl2r::cover::{fibre_angle, sheets_climbed};
use bevy_curved_spaces::space::sl2r::{
    Sl2rRay, Sl2rWalker, UnitTangentSpace, chart_frame, flow, on_model,
};
use bevy_curved_spaces::space::{CellWalk, Limit};
use glam::DVec4;
use std::f64::consts::{PI, TAU};

const WORDS: [&str; 3] = ["abABcdCD", "abcdABCD", "abABcdCDefEF"];

#[test]
fn the_vertex_cycle_composes_to_the_euler_number() {
    for word in WORDS {
        let space = UnitTangentSpace::new(word).expect("a surface");
        let chi = 2 - 2 * space.genus() as i64;
        let turns = space.euler_turns();
        assert_eq!(turns.len(), 1, "{word}: one vertex cycle");
        assert_eq!(
            turns[0].abs(),
            chi.abs(),
            "{word}: turns {turns:?}, χ = {chi}"
        );
    }
}

#[test]
fn a_fibre_climbs_one_sheet_per_turn() {
    for (x, y, theta) in [(0.0, 0.0, 0.3), (0.4, -0.2, -3.0), (0.1, 0.5, PI - 0.01)] {
        for c in [1.0, -1.0] {
            let ray = on_model(&Sl2rRay {
                frame: chart_frame(x, y, theta),
                velocity: [0.0, 0.0, c],
            });
            // (Ends off the cut: on it, which sheet holds Λ = ±π is the rounding's choice,
            // and only the check of Λ's change holds.)
            for t in [1.0, TAU + 0.25, 3.0 * TAU + 0.5] {
                let end = flow(&ray, t).frame;
                let climbed = sheets_climbed(&ray, t, &end).expect("a count");
                // Λ_end − Λ_start = c·t exactly along a fibre.
                let total = fibre_angle(&end) - fibre_angle(&ray.frame) + TAU * climbed as f64;
                assert!(
                    (total - c * t).abs() < 1e-9,
                    "({x}, {y}, {theta}) c = {c}, t = {t}: Λ moved {total}"
                );
                // Sheet k holds Λ in (2πk − π, 2πk + π]: the climb is the sheets' difference.
                let start = fibre_angle(&ray.frame);
                let cuts = |x: f64| ((x - PI) / TAU).ceil() as i64;
                assert_eq!(
                    climbed,
                    cuts(start + c * t) - cuts(start),
                    "t = {t}, c = {c}"
                );
            }
        }
    }
}

/// In a cover, the fibre through a point closes after `2πN`, not `2π`: a vertical walk of
/// `2π` ends on the same frame one sheet up (down going down), of `2πN` on its own sheet.
#[test]
fn the_covers_fibre_closes_after_n_turns() {
    for (word, n) in [("abABcdCD", 2), ("abABcdCDefEF", 2), ("abABcdCDefEF", 4)] {
        let space = UnitTangentSpace::cover(word, n).expect("a cover");
        let walker = Sl2rWalker::<DVec4>::new(&space);
        for c in [1.0, -1.0] {
            let start = on_model(&Sl2rRay {
                frame: chart_frame(0.2, -0.1, 0.4),
                velocity: [0.0, 0.0, c],
            });
            for (turns, sheet) in [(1, if c > 0.0 { 1 } else { n - 1 }), (n, 0)] {
                let length = TAU * f64::from(turns);
                let (end, walked) = CellWalk::walk(
                    &walker,
                    Sl2rWalker::<DVec4>::ray_on_sheet(&start, 0),
                    Limit::Distance(length),
                    |_| true,
                );
                assert_eq!(walked, length);
                assert_eq!(
                    Sl2rWalker::<DVec4>::sheet_of(&end),
                    sheet,
                    "{word} N = {n}, c = {c}"
                );
                let back = Sl2rWalker::<DVec4>::sl2r_ray(&end).frame;
                let off = (0..3)
                    .flat_map(|i| (0..3).map(move |j| (i, j)))
                    .map(|(i, j)| (back[i][j] - start.frame[i][j]).abs())
                    .fold(0.0, f64::max);
                assert!(off < 1e-12, "{word}: the fibre came back {off:e} off");
            }
        }
    }
}

/// A walk through the sides and back along the reversed velocity returns to its start on
/// its own sheet: each side's turn undoes its partner's, along the way and at the ends.
#[test]
fn a_walk_and_its_reverse_return_to_the_start_sheet() {
    let mut rng = SplitMix64(29);
    let mut climbed_any = 0;
    for (word, n) in [("abABcdCD", 2), ("abABcdCDefEF", 4)] {
        let space = UnitTangentSpace::cover(word, n).expect("a cover");
        let walker = Sl2rWalker::<DVec4>::new(&space);
        for _ in 0..40 {
            let start = random_start(&space, &mut rng);
            let sheet = (rng.unit() * f64::from(n)) as u32 % n;
            let length = 1.0 + 6.0 * rng.unit();
            let mut crossed = 0;
            let (end, _) = CellWalk::walk(
                &walker,
                Sl2rWalker::<DVec4>::ray_on_sheet(&start, sheet),
                Limit::Distance(length),
                |_| {
                    crossed += 1;
                    true
                },
            );
            let there = Sl2rWalker::<DVec4>::sheet_of(&end);
            climbed_any += usize::from(there != sheet);
            let mut reversed = Sl2rWalker::<DVec4>::sl2r_ray(&end);
            reversed.velocity = reversed.velocity.map(|x| -x);
            let (home, _) = CellWalk::walk(
                &walker,
                Sl2rWalker::<DVec4>::ray_on_sheet(&reversed, there),
                Limit::Distance(length),
                |_| true,
            );
            let back = Sl2rWalker::<DVec4>::sl2r_ray(&home).frame;
            let off = (0..3)
                .flat_map(|i| (0..3).map(move |j| (i, j)))
                .map(|(i, j)| (back[i][j] - start.frame[i][j]).abs())
                .fold(0.0, f64::max);
            assert!(
                off < 1e-9 * length.exp(),
                "{word}: back {off:e} off after {crossed}"
            );
            assert_eq!(
                Sl2rWalker::<DVec4>::sheet_of(&home),
                sheet,
                "{word} N = {n}: back on another sheet after {crossed} crossings"
            );
        }
    }
    assert!(climbed_any > 10, "only {climbed_any} walks changed sheet");
}

/// The default scene's stack of balls sits on the first sheet: from the point of its fibre
/// half a turn from the stack, `UT Σ` sees the stack's violet ball straight up and its white
/// one straight down; its double cover sees the white one as close, but the violet one a
/// whole turn farther (a turn up lies on the second sheet, where no ball is).
#[test]
fn a_cover_shows_the_stack_on_its_own_sheet_only() {
    use bevy_curved_spaces::trace::sl2r::{
        Sl2rCamera, Sl2rObject, camera_ray, camera_sheet, default_scene, first_hit_on_sheet,
    };
    use glam::DVec3;
    let violet = DVec3::new(0.6, 0.3, 0.9);
    let white = DVec3::new(0.95, 0.95, 0.95);
    for n in [1, 2] {
        let space = UnitTangentSpace::cover("abABcdCD", n).expect("a cover");
        let walker = Sl2rWalker::<DVec4>::new(&space);
        let scene = default_scene(&space);
        // The stack's fibre: half way to side 2 (the +y axis for the octagon).
        let y = (0.5 * space.inradius()).sinh();
        let seen = |turn: f64| {
            let eye = DVec3::new(0.0, y, PI);
            let camera =
                Sl2rCamera::looking_at(&space, eye, eye + DVec3::Z * turn, 60.0).expect("a camera");
            let ray = camera_ray(&camera.frame, 0.0, 0.0);
            first_hit_on_sheet(&walker, &scene, ray, camera_sheet(&camera.frame), 8).and_then(
                |hit| match hit.object {
                    Sl2rObject::Ball(b) => Some((b.colour, hit.distance)),
                    Sl2rObject::Tube(_) => None,
                },
            )
        };
        let (down, below) = seen(-1.0).expect("the white ball below");
        assert_eq!(down, white, "N = {n}");
        assert!(
            (below - (PI - 0.8 - 0.22 * space.inradius())).abs() < 1e-6,
            "{below}"
        );
        let (up, above) = seen(1.0).expect("the violet ball up the fibre");
        assert_eq!(up, violet, "N = {n}");
        let turns = f64::from(n - 1);
        let expected = PI - 0.8 - 0.22 * space.inradius() + TAU * turns;
        assert!(
            (above - expected).abs() < 1e-6,
            "N = {n}: {above} against {expected}"
        );
    }
}

/// The sheets climbed along a geodesic against the 45-digit reference, which integrates the
/// chart's angle with the rest of the geodesic equations (so never wraps it): the sheet of a
/// lifted angle `Λ` is the number of cuts `π + 2πk` below it.
#[test]
fn the_sheets_climbed_are_the_references_lifted_angle() {
    let sheet = |lifted: f64| ((lifted - PI) / TAU).ceil() as i64;
    let mut climbing = 0;
    for s in super::reference() {
        let start = super::round_ray::<f64>(&s.start);
        let end = flow(&start, s.t).frame;
        let (from, to) = s.theta;
        // The chart's angle of the closed form's end is the reference's, wrapped.
        let off = (fibre_angle(&end) - to).rem_euclid(TAU);
        assert!(
            off.min(TAU - off) < 1e-12,
            "{} at {}: θ off by {off:e}",
            s.case,
            s.t
        );
        let climbed = sheets_climbed(&start, s.t, &end).expect("a count");
        assert_eq!(
            climbed,
            sheet(to) - sheet(from),
            "{} at t = {}",
            s.case,
            s.t
        );
        climbing += usize::from(climbed != 0);
    }
    assert!(climbing >= 3, "only {climbing} samples climbed a sheet");
}
