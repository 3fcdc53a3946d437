//! Numerically hard rays and walks, in f64 (the reference) and f32 (what the GPU computes):
//! grazing rays, rays starting on faces, edges and vertices, rays of 10⁴ crossings,
//! directions that are not unit, near-ideal hyperbolic cells, spherical cells reaching the
//! chart's equator, and a player standing on a face or wiggling across an edge.
//!
//! Every case asserts: no NaN, the walk stays in the cell (to a stated tolerance), and it
//! ends (the budget bounds every loop). The tolerances are the precision's rounding scaled by
//! the case's conditioning, stated next to each assertion.

use bevy_curved_spaces::geometry::Ray;
use bevy_curved_spaces::geometry::{Geometry, Vector4};
use bevy_curved_spaces::plugin::components::PlayerMotion;
use bevy_curved_spaces::plugin::player::step_frame;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::catalog::{dodecahedron_normals, dodecahedron_offset};
use bevy_curved_spaces::space::invariants::inradius;
use bevy_curved_spaces::space::wrap_into_cell;
use bevy_curved_spaces::space::{CellWalker, Limit, Trace};
use bevy_curved_spaces::space::{SEED_SPACES, Space};
use bevy_curved_spaces::trace::sample_rays;
use glam::{DVec3, DVec4, Vec4};

/// How far outside the cell a walk's points may be: `N·X/X.w` over the faces (chart
/// units). f64 rounding gives ~1e-15 per step; f32's `ε = 1.2e-7` times the chart scale.
const F64_OUTSIDE: f64 = 1e-11;
const F32_OUTSIDE: f64 = 2e-5;

fn to_f32(ray: Ray<DVec4>) -> Ray<Vec4> {
    Ray {
        point: Vec4::from_f64(ray.point),
        tangent: Vec4::from_f64(ray.tangent),
    }
}

/// Rounding unit of a precision.
fn epsilon<V: Vector4>() -> f64 {
    if std::mem::size_of::<V>() == std::mem::size_of::<Vec4>() {
        f64::from(f32::EPSILON)
    } else {
        f64::EPSILON
    }
}

/// The largest `N·X / X.w` over a trace's points, checking finiteness and unit tangents.
///
/// A tangent is unit to `8 ε max(1, w²)`: the form of vectors whose entries are about `w`
/// (in H³ `w = cosh` of the distance from the chart origin) is only known to `ε w²`.
fn check_trace<V: Vector4>(walker: &CellWalker<V>, trace: &Trace<V>, what: &str) -> f64 {
    let g = walker.geometry;
    let eps = epsilon::<V>();
    let mut worst = f64::NEG_INFINITY;
    for (i, c) in trace.crossings.iter().enumerate() {
        let p = c.ray.point.to_f64();
        let v = c.ray.tangent.to_f64();
        assert!(
            p.is_finite() && v.is_finite() && c.distance.is_finite(),
            "{what}: NaN at crossing {i}"
        );
        let unit = g.form(v, v);
        let tolerance = 8.0 * eps * (p.w * p.w).max(1.0);
        assert!(
            (unit - 1.0).abs() <= tolerance,
            "{what}: tangent of length² {unit} at crossing {i} (tolerance {tolerance:e})"
        );
        // Outside the cell the crossing entered (every face in a space of one cell).
        let cell = (!walker.face_cells.is_empty()).then_some(c.cell);
        let outside = walker
            .covectors
            .iter()
            .enumerate()
            .filter(|(f, _)| cell.is_none_or(|cell| walker.face_cells[*f] == cell))
            .map(|(_, n)| n.to_f64().dot(p / p.w))
            .fold(f64::NEG_INFINITY, f64::max);
        worst = worst.max(outside);
    }
    worst
}

/// Traces in f64 and f32 and checks both stay in the cell.
fn trace_both(space: &Space, start: Ray<DVec4>, crossings: usize, what: &str) {
    let w64 = CellWalker::<DVec4>::new(space);
    let w32 = CellWalker::<Vec4>::new(space);
    let t64 = w64.trace(start, Limit::Crossings(crossings));
    let t32 = w32.trace(to_f32(start), Limit::Crossings(crossings));
    for (n, t) in [(t64.crossings.len(), "f64"), (t32.crossings.len(), "f32")] {
        assert_eq!(
            n, crossings,
            "{what} ({t}): the walk stopped after {n} crossings"
        );
    }
    let out64 = check_trace(&w64, &t64, &format!("{what} (f64)"));
    let out32 = check_trace(&w32, &t32, &format!("{what} (f32)"));
    assert!(
        out64 <= F64_OUTSIDE,
        "{what}: f64 {out64:e} outside the cell"
    );
    assert!(
        out32 <= F32_OUTSIDE,
        "{what}: f32 {out32:e} outside the cell"
    );
}

fn spaces() -> impl Iterator<Item = (&'static str, Space)> {
    SEED_SPACES
        .iter()
        .map(|s| (s.id, s.build().expect("seed space builds")))
}

/// A ray in the model from a chart point and a chart direction.
fn ray(g: Geometry, from: DVec3, dir: DVec3) -> Ray<DVec4> {
    let point = g.from_chart(from).expect("inside the model");
    Ray {
        point,
        tangent: g.tangent_from_chart(point, dir).expect("a direction"),
    }
}

/// The f64 and f32 walkers of a cell whose faces are all mirrors (a billiard: the walk only
/// needs faces and reflections, not a valid orbifold).
fn mirrored_walkers(g: Geometry, covectors: &[DVec4]) -> (CellWalker<DVec4>, CellWalker<Vec4>) {
    let pairings: Vec<_> = covectors.iter().map(|c| g.reflection(*c)).collect();
    let partners: Vec<usize> = (0..covectors.len()).collect();
    (
        CellWalker::from_parts(g, covectors, &pairings, partners.clone()),
        CellWalker::from_parts(g, covectors, &pairings, partners),
    )
}

/// A ray running along a face at 1e-7 rad towards it, 1e-3 inradii inside.
#[test]
fn grazing_rays_stay_in_the_cell() {
    for (id, s) in spaces() {
        let g = s.geometry();
        let r = inradius(&s);
        for face in s.faces() {
            let centre = face.normal * face.offset;
            // Any direction in the face's plane (chart), tilted by 1e-7 towards the face.
            let along = face.normal.any_orthonormal_vector();
            let from = g.to_chart(
                g.project_point(g.from_chart(centre).unwrap() - 1e-3 * r * face.normal.extend(0.0)),
            );
            let dir = along * 1e-7f64.cos() + face.normal * 1e-7f64.sin();
            trace_both(&s, ray(g, from, dir), 200, &format!("{id}: grazing"));
        }
    }
}

/// Rays from the centre exactly through every vertex and every edge midpoint, in f64 and
/// f32: they hop around the vertex or edge and go on, inside the cell.
#[test]
fn rays_exactly_through_edges_and_vertices_in_both_precisions() {
    for (id, s) in spaces() {
        let g = s.geometry();
        let mut targets: Vec<DVec3> = s.vertices().to_vec();
        targets.extend(
            s.edges()
                .iter()
                .map(|e| (s.vertices()[e.vertices[0]] + s.vertices()[e.vertices[1]]) / 2.0),
        );
        for (i, target) in targets.iter().enumerate() {
            trace_both(
                &s,
                ray(g, DVec3::ZERO, *target),
                100,
                &format!("{id}: target {i}"),
            );
        }
    }
}

/// Rays starting exactly on a face centre, an edge midpoint and a vertex, in 64 directions
/// each (half of them pointing out of the cell: they cross at once).
#[test]
fn rays_starting_on_faces_edges_and_vertices() {
    for (id, s) in spaces() {
        let g = s.geometry();
        let mut starts: Vec<(String, DVec3)> = Vec::new();
        for (f, face) in s.faces().iter().enumerate() {
            starts.push((format!("face {f}"), face.normal * face.offset));
        }
        for (e, edge) in s.edges().iter().enumerate() {
            let mid = (s.vertices()[edge.vertices[0]] + s.vertices()[edge.vertices[1]]) / 2.0;
            starts.push((format!("edge {e}"), mid));
        }
        for (v, vertex) in s.vertices().iter().enumerate() {
            starts.push((format!("vertex {v}"), *vertex));
        }
        let mut rng = SplitMix64(7);
        for (what, at) in &starts {
            for _ in 0..64 {
                trace_both(
                    &s,
                    ray(g, *at, rng.direction()),
                    60,
                    &format!("{id}: from {what}"),
                );
            }
        }
    }
}

/// Rays of 10⁴ crossings from random points: no NaN, still in the cell, still unit.
#[test]
fn rays_of_ten_thousand_crossings() {
    for (id, s) in spaces() {
        for (i, start) in sample_rays(&s, 8, 11).into_iter().enumerate() {
            trace_both(&s, start, 10_000, &format!("{id}: long ray {i}"));
        }
    }
}

/// A tangent of length 10⁻³ or 10³, or with a component along the point (not tangent),
/// walks exactly as the unit tangent does.
#[test]
fn directions_that_are_not_unit_walk_like_unit_ones() {
    for (id, s) in spaces() {
        let g = s.geometry();
        let walker = CellWalker::<DVec4>::new(&s);
        for start in sample_rays(&s, 16, 3) {
            let reference = walker.trace(start, Limit::Crossings(20));
            for (what, tangent) in [
                ("short", start.tangent * 1e-3),
                ("long", start.tangent * 1e3),
                ("off the tangent space", start.tangent + 0.3 * start.point),
                ("not quite unit", start.tangent * (1.0 + 1e-6)),
            ] {
                let t = walker.trace(
                    Ray {
                        point: start.point,
                        tangent,
                    },
                    Limit::Crossings(20),
                );
                for (a, b) in reference.crossings.iter().zip(&t.crossings) {
                    assert_eq!(a.face, b.face, "{id}: {what} tangent took another face");
                    // Same faces; points agree to rounding grown by the conditioning of
                    // docs/design.md §3: 1e-13 · G(d) (about 500 ε G(d)), G = e^d in H³,
                    // 1 + d in E³, 1 in S³.
                    let growth = match g {
                        Geometry::Hyperbolic => a.distance.exp(),
                        Geometry::Euclidean => 1.0 + a.distance,
                        Geometry::Spherical => 1.0,
                    };
                    let d = g.distance(a.ray.point, b.ray.point);
                    assert!(
                        d < 1e-13 * growth,
                        "{id}: {what} tangent drifted {d:e} at distance {}",
                        a.distance
                    );
                }
            }
        }
    }
}

/// A mirrored regular hyperbolic dodecahedron (a billiard: the walk only needs faces and
/// reflections) with dihedral angles approaching 60°, where the vertices approach the sphere
/// at infinity (the Klein chart's unit sphere).
///
/// f64 and f32 stay in the cell for every angle down to 60.00005°, whose vertices lie
/// 1.5·10⁻⁷ from the sphere at infinity (f32's resolution of the chart radius). With the
/// plain pairing product f32 failed from 60.005° on (vertices 1.5·10⁻⁵ from it): the
/// reflections there have entries near 10⁵, and their product cancelled all of f32's
/// digits; the compensated product with the pairing's f32 residual keeps them.
#[test]
fn near_ideal_hyperbolic_dodecahedra() {
    let g = Geometry::Hyperbolic;
    for dihedral_degrees in [62.0, 60.5, 60.05, 60.005, 60.0005, 60.00005] {
        let r = dodecahedron_offset(g, f64::to_radians(dihedral_degrees));
        let covectors: Vec<DVec4> = dodecahedron_normals()
            .iter()
            .map(|n| n.extend(-r))
            .collect();
        // The vertex nearest infinity: the chart point on three faces.
        let vertex_radius = {
            let n = dodecahedron_normals();
            let m = glam::DMat3::from_cols(n[0], n[2], n[4]).transpose();
            (m.inverse() * DVec3::splat(r)).length()
        };
        let (walker, w32) = mirrored_walkers(g, &covectors);
        let what =
            format!("dihedral {dihedral_degrees}° (vertex at chart radius {vertex_radius:.8})");
        assert!(vertex_radius < 1.0, "{what}: not a compact cell");
        let mut rng = SplitMix64(5);
        let mut worst32 = f64::NEG_INFINITY;
        for _ in 0..16 {
            let start = ray(g, DVec3::ZERO, rng.direction());
            let t64 = walker.trace(start, Limit::Crossings(2000));
            let out64 = check_trace(&walker, &t64, &format!("{what}, f64"));
            assert!(out64 <= F64_OUTSIDE, "{what}: f64 {out64:e} outside");
            assert_eq!(t64.crossings.len(), 2000, "{what}: f64 stopped");
            let t32 = w32.trace(to_f32(start), Limit::Crossings(2000));
            assert_eq!(t32.crossings.len(), 2000, "{what}: f32 stopped");
            worst32 = worst32.max(check_trace(&w32, &t32, &format!("{what}, f32")));
        }
        eprintln!("{what}: f32 worst outside {worst32:e}");
        assert!(worst32 <= F32_OUTSIDE, "{what}: f32 {worst32:e} outside");
    }
}

/// A mirrored spherical cube whose chart half-width reaches 10³: its corners lie 6·10⁻⁴
/// from the chart's equator (`w → 0`), where chart coordinates blow up.
#[test]
fn spherical_cells_reaching_the_chart_equator() {
    let g = Geometry::Spherical;
    for half_width in [10.0, 100.0, 1000.0] {
        let covectors: Vec<DVec4> = [DVec3::X, DVec3::Y, DVec3::Z]
            .into_iter()
            .flat_map(|a| [a, -a])
            .map(|n| n.extend(-half_width))
            .collect();
        let corner_w = 1.0 / (1.0 + 3.0 * half_width * half_width).sqrt();
        let what = format!("half-width {half_width} (corner w = {corner_w:.1e})");
        let (walker, w32) = mirrored_walkers(g, &covectors);
        let mut rng = SplitMix64(9);
        for _ in 0..16 {
            let start = ray(g, DVec3::ZERO, rng.direction());
            let t64 = walker.trace(start, Limit::Crossings(2000));
            let t32 = w32.trace(to_f32(start), Limit::Crossings(2000));
            // Chart coordinates scale with the half-width: the tolerance is relative to it.
            let out64 = check_trace(&walker, &t64, &what) / half_width;
            let out32 = check_trace(&w32, &t32, &what) / half_width;
            assert!(
                out64 <= F64_OUTSIDE,
                "{what}: f64 {out64:e} (relative) outside"
            );
            assert!(
                out32 <= F32_OUTSIDE,
                "{what}: f32 {out32:e} (relative) outside"
            );
            // Each point is on the model: |X| = 1, even where w is 6e-4.
            for c in &t64.crossings {
                assert!((c.ray.point.length() - 1.0).abs() < 1e-12, "{what}: off S³");
            }
        }
    }
}

/// The player stands on a face for 10⁴ frames, jittering by 10⁻⁶ (well inside the wrap
/// margin of 10⁻⁴): it crosses at most once; then it wiggles across an edge by twice the
/// margin for 10⁴ frames: every wrap lands inside, the frame stays an isometry.
#[test]
fn standing_on_a_face_and_wiggling_across_an_edge() {
    let margin = 1e-4;
    for (id, s) in spaces() {
        let g = s.geometry();
        let face = &s.faces()[0];
        let on_face = g.from_chart(face.normal * face.offset).unwrap();
        let mut frame = g.translation_to(on_face);
        let mut crossings = 0;
        let mut rng = SplitMix64(1);
        for _ in 0..10_000 {
            let jitter = PlayerMotion {
                translation: rng.direction() * 1e-6,
                rotation: DVec3::ZERO,
            };
            let (next, crossed) = wrap_into_cell(&s, step_frame(g, frame, &jitter), margin);
            crossings += crossed.len();
            frame = next;
        }
        assert!(
            crossings <= 1,
            "{id}: {crossings} crossings while standing on a face"
        );
        assert!(g.frame_defect(frame) < 1e-9, "{id}: frame defect");

        let edge = &s.edges()[0];
        let mid = (s.vertices()[edge.vertices[0]] + s.vertices()[edge.vertices[1]]) / 2.0;
        let mut frame = g.translation_to(g.from_chart(mid * (1.0 - 1e-6)).unwrap());
        let outward = mid.normalize();
        let mut worst = f64::NEG_INFINITY;
        for k in 0..10_000 {
            // Out and back along the edge's outward direction, by twice the margin.
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            let tangent = g.tangent_from_chart(frame.w_axis, outward).unwrap();
            let local = (g.inverse(frame) * tangent).truncate();
            let step = PlayerMotion {
                translation: local.normalize_or_zero() * (2.0 * margin * sign),
                rotation: DVec3::ZERO,
            };
            let (next, _) = wrap_into_cell(&s, step_frame(g, frame, &step), margin);
            frame = g.orthonormalize_frame(next);
            worst = worst.max(s.outside_by(frame.w_axis));
        }
        assert!(
            worst <= margin,
            "{id}: {worst:e} outside after wiggling across an edge"
        );
        assert!(
            g.frame_defect(frame) < 1e-9,
            "{id}: frame defect after wiggling"
        );
    }
}
