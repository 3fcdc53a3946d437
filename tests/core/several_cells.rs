//! Spaces of several cells: `torus-two-cells` (the unit cube cut at `x = 0` into two
//! half-cubes, each a cell) is the 3-torus, so everything that does not look at the cells
//! must come out as the one-cell `torus`'s — its invariants, where its geodesics end, the
//! frames a player walks to, its pictures — while the walk crosses the seam between the
//! cells and names the cell it enters. Bad cells (overlapping, the origin in none, not
//! glued together) are refused with the reason.

use bevy_curved_spaces::geometry::{Geometry, Ray};
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::scene::file::parse_scene;
use bevy_curved_spaces::scene::light_images::lamp_images;
use bevy_curved_spaces::space::invariants::Invariants;
use bevy_curved_spaces::space::{
    CellWalk, CellWalker, FaceSpec, FrameMotion, FrameSpace, Limit, Space, SpaceError, seed_space,
};
use bevy_curved_spaces::trace::{RenderSettings, render};
use bevy_curved_spaces::view::TraceCamera;
use glam::{DMat4, DVec3, DVec4};

fn both() -> (Space, Space) {
    (
        seed_space("torus").expect("the torus"),
        seed_space("torus-two-cells").expect("the torus of two cells"),
    )
}

fn random_direction(rng: &mut SplitMix64) -> DVec3 {
    rng.direction()
}

/// Two chart points of the torus are one point when they differ by a vector of integers.
fn lattice_gap(a: DVec3, b: DVec3) -> f64 {
    let d = a - b;
    (d - d.round()).abs().max_element()
}

#[test]
fn the_two_cells_have_the_torus_invariants() {
    let (one, two) = both();
    let (a, b) = (Invariants::compute(&one), Invariants::compute(&two));
    assert_eq!((a.cells, b.cells), (1, 2));
    assert!(
        (a.volume - b.volume).abs() < 1e-14,
        "{} {}",
        a.volume,
        b.volume
    );
    assert_eq!(a.inradius, b.inradius);
    assert_eq!(a.circumradius, b.circumradius);
    assert_eq!(a.homology, b.homology);
    assert_eq!(a.orientable, b.orientable);
    assert_eq!(a.manifold, b.manifold);
    assert_eq!(a.holonomy_order, b.holonomy_order);
    assert_eq!(a.injectivity_radius, b.injectivity_radius);
    // The lamp's images in the cover are the same lattice.
    let lamp = DVec4::new(0.1, -0.2, 0.3, 1.0);
    let near = |s: &Space| lamp_images(s, lamp, 3.0, 100_000).expect("few images");
    let (ia, ib) = (near(&one), near(&two));
    assert_eq!(ia.len(), ib.len());
    for ((p, d), (q, e)) in ia.iter().zip(&ib) {
        assert!((d - e).abs() < 1e-12, "{d} {e}");
        let _ = (p, q);
    }
    // The seam is glued by the identity and is a seam; the x faces are glued across cells
    // by a translation and are not.
    let seams: Vec<usize> = (0..two.faces().len()).filter(|&f| two.is_seam(f)).collect();
    assert_eq!(seams.len(), 2, "the cut's two sides");
    for f in seams {
        assert_eq!(two.faces()[f].offset, 0.0);
        assert_ne!(
            two.faces()[f].cell,
            two.faces()[two.faces()[f].partner].cell
        );
    }
}

/// A geodesic walked in the two cells ends where it ends in the one cell (modulo the
/// lattice), with the same tangent, and each crossing names the cell that holds its ray.
#[test]
fn walks_end_where_the_torus_walks_end() {
    let (one, two) = both();
    let (w1, w2) = (
        CellWalker::<DVec4>::new(&one),
        CellWalker::<DVec4>::new(&two),
    );
    let mut rng = SplitMix64(48);
    let mut seam_crossings = 0;
    for _ in 0..300 {
        let from = DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5) * 0.98;
        let dir = random_direction(&mut rng);
        let ray = one.chart_ray(from, dir).expect("a ray");
        let distance = 0.5 + 30.0 * rng.unit();
        let (end1, d1) = CellWalk::walk(&w1, ray, Limit::Distance(distance), |_| true);
        let mut cells_ok = true;
        let (end2, d2) = CellWalk::walk(&w2, ray, Limit::Distance(distance), |c| {
            let p = c.ray.point.truncate() / c.ray.point.w;
            // On the face it entered: inside that cell to rounding.
            let cell = &two.cells()[c.cell];
            cells_ok &= two.faces()[cell.clone()]
                .iter()
                .all(|f| f.normal.dot(p) - f.offset <= 1e-12);
            if two.is_seam(c.face) {
                seam_crossings += 1;
            }
            true
        });
        assert!(
            cells_ok,
            "a crossing named a cell that does not hold its ray"
        );
        assert_eq!(d1, d2);
        let gap = lattice_gap(end1.point.truncate(), end2.point.truncate());
        assert!(
            gap < 1e-11 * (1.0 + distance),
            "ends {gap:e} apart at {distance}"
        );
        assert!((end1.tangent - end2.tangent).abs().max_element() < 1e-14);
        assert!(two.outside_by(end2.point) <= 1e-12);
    }
    assert!(
        seam_crossings > 100,
        "the walks crossed the seam {seam_crossings} times"
    );
}

/// A player's frame, stepped and wrapped, stays in the union of the cells and stays the
/// torus player's frame modulo the lattice; a seam adds no crossing to the holonomy.
#[test]
fn a_player_walks_as_in_the_torus() {
    let (one, two) = both();
    let mut rng = SplitMix64(7);
    let start = DMat4::from_translation(DVec3::new(0.1, 0.2, -0.1));
    let (mut f1, mut f2) = (start, start);
    let (mut n1, mut n2) = (0, 0);
    for _ in 0..2000 {
        let motion = FrameMotion {
            translation: DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.3) * 0.2,
            rotation: DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, 0.0) * 0.3,
            level: false,
        };
        let (a, ca) = one.wrap_frame(one.step_frame(f1, &motion), 0.0);
        let (b, cb) = two.wrap_frame(two.step_frame(f2, &motion), 0.0);
        (f1, f2) = (a, b);
        n1 += ca.len();
        n2 += cb.len();
        assert!(cb.iter().all(|c| !two.is_seam(c.face)));
        assert!(two.outside_by(f2.w_axis) <= 1e-12);
        assert!(lattice_gap(f1.w_axis.truncate(), f2.w_axis.truncate()) < 1e-9);
        assert!((f1.x_axis - f2.x_axis).abs().max_element() < 1e-9);
    }
    assert!(n1 > 50, "the player crossed {n1} faces");
    // Where the torus's frame crosses a face the two cells' crosses one too (the x faces
    // of the torus are the outer x faces of the two halves).
    assert_eq!(n1, n2);
}

/// The torus scene with shadows, drawn in both spaces by the CPU reference: the same
/// picture (the two-cell walk crosses the seam as well, so it needs a larger budget).
#[test]
fn the_cpu_draws_the_torus_picture() {
    let text = std::fs::read_to_string("assets/scenes/torus_shadows.toml").expect("the scene");
    let base = std::path::Path::new("assets/scenes");
    let picture = |id: &str| {
        let file = parse_scene(
            &text.replace("space = \"torus\"", &format!("space = \"{id}\"")),
            base,
            "torus_shadows.toml",
        )
        .expect("the scene");
        let camera = TraceCamera {
            frame: file.start.expect("a start view"),
            fov_y_degrees: 70.0,
        };
        let settings = RenderSettings {
            width: 96,
            height: 54,
            max_crossings: 64,
        };
        render(&file.space, &file.scene(), &camera, &settings)
    };
    let (a, b) = (picture("torus"), picture("torus-two-cells"));
    let differing = crate::common::differing_fraction(&a, &b, 2);
    assert!(
        differing == 0.0,
        "{:.3} % of pixels differ",
        100.0 * differing
    );
}

fn half_cube(x: (f64, f64), first: usize, partner_cell: usize) -> Vec<FaceSpec> {
    let t = DMat4::from_translation;
    vec![
        FaceSpec::paired(DVec3::X, x.1, partner_cell + 1, DMat4::IDENTITY),
        FaceSpec::paired(DVec3::NEG_X, -x.0, partner_cell, DMat4::IDENTITY),
        FaceSpec::paired(DVec3::Y, 0.5, first + 3, t(DVec3::NEG_Y)),
        FaceSpec::paired(DVec3::NEG_Y, 0.5, first + 2, t(DVec3::Y)),
        FaceSpec::paired(DVec3::Z, 0.5, first + 5, t(DVec3::NEG_Z)),
        FaceSpec::paired(DVec3::NEG_Z, 0.5, first + 4, t(DVec3::Z)),
    ]
}

#[test]
fn bad_cells_are_refused_with_the_reason() {
    let build = |cells: &[Vec<FaceSpec>]| Space::new_cells("bad", "", Geometry::Euclidean, cells);
    // Two half-cubes lying on top of each other.
    let overlapping = build(&[half_cube((-0.5, 0.0), 0, 6), half_cube((-0.4, 0.1), 6, 0)]);
    assert!(
        matches!(overlapping, Err(SpaceError::CellsOverlap { a: 0, b: 1 })),
        "{overlapping:?}"
    );
    // Both cells beside the origin.
    let away = build(&[half_cube((0.5, 1.0), 0, 6), half_cube((1.0, 1.5), 6, 0)]);
    assert!(
        matches!(away, Err(SpaceError::OriginInNoCell { .. })),
        "{away:?}"
    );
    let message = SpaceError::CellsNotJoined { cell: 1 }.to_string();
    assert!(message.contains("cell 1"), "{message}");
    // Each cell a torus of its own: glued to itself only.
    let apart = |first: usize, x: (f64, f64)| {
        let t = DMat4::from_translation;
        let w = x.1 - x.0;
        vec![
            FaceSpec::paired(DVec3::X, x.1, first + 1, t(DVec3::NEG_X * w)),
            FaceSpec::paired(DVec3::NEG_X, -x.0, first, t(DVec3::X * w)),
            FaceSpec::paired(DVec3::Y, 0.5, first + 3, t(DVec3::NEG_Y)),
            FaceSpec::paired(DVec3::NEG_Y, 0.5, first + 2, t(DVec3::Y)),
            FaceSpec::paired(DVec3::Z, 0.5, first + 5, t(DVec3::NEG_Z)),
            FaceSpec::paired(DVec3::NEG_Z, 0.5, first + 4, t(DVec3::Z)),
        ]
    };
    let unjoined = build(&[apart(0, (-0.5, 0.0)), apart(6, (0.0, 0.5))]);
    assert!(
        matches!(unjoined, Err(SpaceError::CellsNotJoined { cell: 1 })),
        "{unjoined:?}"
    );
}

/// Rays from every start see through the seam: starting on it, in either cell, or just
/// past a face, the exit is found in the cell that holds the point.
#[test]
fn rays_starting_on_the_seam_walk_on() {
    let (_, two) = both();
    let walker = CellWalker::<DVec4>::new(&two);
    let mut rng = SplitMix64(3);
    for _ in 0..500 {
        let from = DVec3::new(0.0, rng.unit() - 0.5, rng.unit() - 0.5);
        let dir = random_direction(&mut rng);
        let ray: Ray<DVec4> = two.chart_ray(from, dir).expect("a ray");
        let trace = walker.trace(ray, Limit::Crossings(6));
        assert_eq!(trace.crossings.len(), 6);
        assert!(two.outside_by(trace.end.point) <= 1e-12);
    }
}

/// The two cells' numbers are exact in binary (no closed form to round: halves and units),
/// so the f32 walker and the GPU hold the same cell as f64.
#[test]
fn the_two_cells_are_exact_in_binary() {
    let (_, two) = both();
    for f in two.faces() {
        assert!(f.offset == 0.0 || f.offset == 0.5, "{}", f.offset);
        for x in f
            .pairing
            .to_cols_array()
            .into_iter()
            .chain(f.normal.to_array())
        {
            assert!(x == f64::from(x as f32) && (x * 2.0).fract() == 0.0, "{x}");
        }
    }
}
