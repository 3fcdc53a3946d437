//! The walls with windows of a unit tangent bundle's cell: a side's window is the middle of
//! the band the side sweeps round the fibre, carried by the pairing onto its partner's, and
//! a ray meets the panel exactly where it crosses the side.

use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::scene::walls::{Veil, WallStyle};
use bevy_curved_spaces::space::sl2r::{Sl2rWalker, UnitTangentSpace};
use bevy_curved_spaces::space::{CellWalk, NextExit};
use bevy_curved_spaces::trace::sl2r::walls::Sl2rWalls;
use bevy_curved_spaces::trace::sl2r::{default_scene, first_hit_past_walls};
use glam::DVec4;

fn apply(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

/// The point of side `f` at distance `s` along it from its midpoint.
fn on_side(space: &UnitTangentSpace, f: usize, s: f64) -> [f64; 3] {
    let n = space.sides().len() as f64;
    let angle = std::f64::consts::TAU * f as f64 / n;
    let rho = space.inradius();
    let m = [
        rho.sinh() * angle.cos(),
        rho.sinh() * angle.sin(),
        rho.cosh(),
    ];
    let t = [-angle.sin(), angle.cos(), 0.0];
    [0, 1, 2].map(|i| s.cosh() * m[i] + s.sinh() * t[i])
}

#[test]
fn a_window_is_the_middle_of_the_side_and_its_partners_window() {
    let mut rng = SplitMix64(5);
    for word in ["abABcdCD", "abcdABCD", "abABcdCDefEF"] {
        let space = UnitTangentSpace::new(word).unwrap();
        let half = (space.circumradius().cosh() / space.inradius().cosh()).acosh();
        let style = WallStyle {
            opening: 0.6,
            opacity: 0.5,
        };
        let walls = Sl2rWalls::new(&space, style, 0.01).expect("walls");
        for (f, side) in space.sides().iter().enumerate() {
            let g = side.pairing.map(|r| r.map(|x| x.hi));
            for _ in 0..20 {
                let s = (2.0 * rng.unit() - 1.0) * half;
                let p = on_side(&space, f, s);
                // On the side, and on the panel exactly past the window's reach.
                let n = side.normal.map(|x| x.hi);
                assert!((n[0] * p[0] + n[1] * p[1] + n[2] * p[2]).abs() < 1e-12);
                if (s.abs() - 0.6 * half).abs() > 1e-9 {
                    assert_eq!(
                        walls.on_panel(f, p),
                        s.abs() > 0.6 * half,
                        "{word} side {f}"
                    );
                }
                // The pairing carries the window onto the partner's.
                let q = apply(&g, p);
                if (s.abs() - 0.6 * half).abs() > 1e-9 {
                    assert_eq!(walls.on_panel(f, p), walls.on_panel(side.partner, q));
                }
            }
        }
        // Glued sides share a colour.
        for (f, side) in space.sides().iter().enumerate() {
            assert_eq!(walls.colours[f], walls.colours[side.partner]);
        }
        assert!(
            Sl2rWalls::new(
                &space,
                WallStyle {
                    opening: 1.0,
                    opacity: 0.5
                },
                0.01
            )
            .is_none()
        );
    }
}

/// Solid, opaque walls: every ray stops at its first crossing, and the veil holds that
/// panel's colour lit and fogged there; through windows that fill the side nothing is added.
#[test]
fn solid_walls_stop_each_ray_where_it_first_crosses_a_side() {
    let space = UnitTangentSpace::new("abABcdCD").unwrap();
    let mut scene = default_scene(&space);
    scene.tubes.clear();
    scene.balls.clear();
    let walker = Sl2rWalker::<DVec4>::new(&space);
    let solid = Sl2rWalls::new(
        &space,
        WallStyle {
            opening: 0.0,
            opacity: 1.0,
        },
        0.01,
    )
    .unwrap();
    let mut rng = SplitMix64(17);
    for _ in 0..50 {
        let start = bevy_curved_spaces::space::sl2r::accuracy::random_start(&space, &mut rng);
        let ray = Sl2rWalker::<DVec4>::ray_of(&start);
        let NextExit::Exit(exit) = walker.next_exit(&ray, None, 0) else {
            continue;
        };
        let mut veil = Veil::CLEAR;
        let hit = first_hit_past_walls(&walker, &scene, (start, 0), 8, Some((&solid, &mut veil)));
        assert!(hit.is_none());
        if exit.t >= scene.cutoff_distance() {
            continue;
        }
        assert_eq!(veil.through, 0.0);
        let at = bevy_curved_spaces::space::sl2r::flow(&start, exit.t);
        let fog = (-exit.t / scene.fog_distance).exp();
        let want = fog * solid.lit_colour(exit.face, &at) + (1.0 - fog) * scene.fog_colour;
        assert!(
            (veil.colour - want).abs().max_element() < 1e-12,
            "{} {}",
            veil.colour,
            want
        );
    }
}
