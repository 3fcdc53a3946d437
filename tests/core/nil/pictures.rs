//! The Nil tracer: its scene's lattice images, its walk to the first object against the
//! universal cover, the swept discs' gradients, the light's area density against the
//! exponential map's central differences, and pictures.

use super::*;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::nil::{NilSpace, NilWalker};
use bevy_curved_spaces::trace::nil::{
    NilObject, NilRayEnd, NilShape, area_density, default_scene, first_nil_hit,
};
use glam::{DVec3, DVec4};

/// The default scene's base objects moved by every lattice element near the box (a wide
/// range, independent of the scene's own choice of images).
fn brute_images(space: &NilSpace) -> Vec<NilObject> {
    let k = f64::from(space.k());
    let scene = default_scene(space);
    // The base objects: the first of each kind the scene lists unmoved.
    let base: Vec<NilObject> = scene
        .objects
        .iter()
        .filter(|o| match o.shape {
            NilShape::Edge { image, .. } => image == [0.0; 3],
            NilShape::Ball(c) => c.iter().all(|x| x.abs() <= 0.5),
            NilShape::Fibre(_) => true,
        })
        .copied()
        .collect();
    let mut out = Vec::new();
    for p in -2i32..=2 {
        for q in -2i32..=2 {
            let (p, q) = (f64::from(p), f64::from(q));
            let ms = -3 * i64::from(space.k()) - 3;
            for m in ms..=-ms {
                let g = [p, q, 0.5 * p * q + m as f64 / k];
                for o in &base {
                    let shape = match o.shape {
                        NilShape::Ball(c) => NilShape::Ball(group_product(g, c)),
                        NilShape::Fibre(b) if m == 0 => NilShape::Fibre([b[0] + p, b[1] + q]),
                        NilShape::Fibre(_) => continue,
                        NilShape::Edge {
                            image,
                            along,
                            offset,
                            height,
                        } => NilShape::Edge {
                            image: group_product(g, image),
                            along,
                            offset,
                            height,
                        },
                    };
                    out.push(NilObject { shape, ..*o });
                }
            }
        }
    }
    out
}

fn inside(objects: &[NilObject], p: [f64; 3]) -> bool {
    objects.iter().any(|o| o.contains(p))
}

#[test]
fn the_scene_holds_every_image_that_reaches_into_the_box() {
    for k in [1, 3] {
        let space = NilSpace::new(k);
        let h = space.half_height();
        let scene = default_scene(&space);
        let all = brute_images(&space);
        let mut rng = SplitMix64(61 + u64::from(k));
        let mut inside_count = 0;
        for _ in 0..4000 {
            let p = [
                rng.unit() - 0.5,
                rng.unit() - 0.5,
                (2.0 * rng.unit() - 1.0) * h,
            ];
            let ours = inside(&scene.objects, p);
            assert_eq!(ours, inside(&all, p), "nil-{k} at {p:?}");
            inside_count += usize::from(ours);
        }
        assert!(
            inside_count > 100,
            "nil-{k}: only {inside_count} points inside objects"
        );
    }
}

#[test]
fn walked_hits_match_the_universal_cover() {
    // Each walked ray's end, followed in the cover (no walker) and brought back into the
    // box, lies on the object met; and no sample before it is inside any object.
    for k in [1, 3] {
        let space = NilSpace::new(k);
        let h = space.half_height();
        let scene = default_scene(&space);
        let walker = NilWalker::<DVec4>::new(k);
        let mut rng = SplitMix64(67 + u64::from(k));
        let (mut hits, mut fog) = (0, 0);
        for _ in 0..60 {
            let start = NilRay {
                point: [
                    rng.unit() - 0.5,
                    rng.unit() - 0.5,
                    (2.0 * rng.unit() - 1.0) * h,
                ],
                velocity: rng.direction().to_array(),
            };
            if inside(&scene.objects, start.point) {
                continue;
            }
            let length = 3.0;
            let end = first_nil_hit(&walker, &scene, start, length, 100_000);
            let until = match end {
                NilRayEnd::Hit {
                    distance, object, ..
                } => {
                    hits += 1;
                    let p = space.into_box(flow(&start, distance).point);
                    let gap = object.gap_at(p);
                    assert!(gap.abs() < 1e-9, "nil-{k}: the hit is {gap} off its object");
                    distance
                }
                NilRayEnd::Fog => {
                    fog += 1;
                    length
                }
                NilRayEnd::Budget(n) => panic!("ran out of {n} crossings"),
            };
            let steps = (until / 2e-3) as usize;
            for i in 0..steps {
                let t = until * i as f64 / steps as f64;
                let p = space.into_box(flow(&start, t).point);
                assert!(
                    !inside(&scene.objects, p),
                    "nil-{k}: inside an object at {t} before the hit at {until}"
                );
            }
        }
        assert!(
            hits > 10 && fog > 0 || hits > 30,
            "nil-{k}: {hits} hits, {fog} misses"
        );
    }
}

#[test]
fn swept_disc_normals_are_the_gap_s_gradient() {
    // The rates of the gap along E₁, E₂, E₃ (central differences of the flow) point
    // along the normal.
    let space = NilSpace::new(2);
    let scene = default_scene(&space);
    let mut rng = SplitMix64(71);
    let mut checked = 0;
    for object in scene
        .objects
        .iter()
        .filter(|o| matches!(o.shape, NilShape::Edge { .. }))
    {
        for _ in 0..20 {
            let p = [
                rng.unit() - 0.5,
                rng.unit() - 0.5,
                (2.0 * rng.unit() - 1.0) * 0.25,
            ];
            let e = 1e-6;
            let rate = |v: [f64; 3]| {
                let ray = NilRay {
                    point: p,
                    velocity: v,
                };
                let gap = |t: f64| object.gap_at(flow(&ray, t).point);
                (gap(e) - gap(-e)) / (2.0 * e)
            };
            if object.clearance(p) < 1e-3 {
                continue;
            }
            let numeric = DVec3::new(
                rate([1.0, 0.0, 0.0]),
                rate([0.0, 1.0, 0.0]),
                rate([0.0, 0.0, 1.0]),
            );
            let n = object.normal(p);
            let cos = numeric.normalize().dot(n);
            assert!(
                cos > 1.0 - 1e-6,
                "normal {n} against the gradient {numeric} at {p:?}"
            );
            checked += 1;
        }
    }
    assert!(checked > 100, "only {checked} checked");
}

#[test]
fn the_area_density_is_the_exponential_map_s_jacobian() {
    // |det ∂(x, y, z)/∂(t, α, θ)| / sin θ by central differences of the flow from the origin,
    // against the closed form, over lengths and elevations (c = cos θ) including c = 0, ±1.
    let at = |t: f64, alpha: f64, theta: f64| {
        let v = [
            theta.sin() * alpha.cos(),
            theta.sin() * alpha.sin(),
            theta.cos(),
        ];
        DVec3::from_array(
            flow(
                &NilRay {
                    point: [0.0; 3],
                    velocity: v,
                },
                t,
            )
            .point,
        )
    };
    let mut worst = 0.0_f64;
    for &t in &[0.05, 0.3, 1.0, 2.5, 5.0, 9.0] {
        for &theta in &[0.2, 0.7, 1.2, std::f64::consts::FRAC_PI_2, 2.0, 2.9] {
            let e = 1e-5;
            let dt = (at(t + e, 0.3, theta) - at(t - e, 0.3, theta)) / (2.0 * e);
            let da = (at(t, 0.3 + e, theta) - at(t, 0.3 - e, theta)) / (2.0 * e);
            let dth = (at(t, 0.3, theta + e) - at(t, 0.3, theta - e)) / (2.0 * e);
            let numeric = glam::DMat3::from_cols(dt, da, dth).determinant().abs() / theta.sin();
            let closed = area_density(t, theta.cos());
            let rel = (numeric - closed).abs() / closed.max(1e-3 * t * t);
            worst = worst.max(rel);
            assert!(rel < 1e-5, "t {t} θ {theta}: {numeric} against {closed}");
        }
    }
    // Near the centre it is the flat r², along horizontal lines r² + r⁴/12.
    assert!((area_density(1e-3, 0.4) / 1e-6 - 1.0).abs() < 1e-6);
    assert!((area_density(2.0, 0.0) - (4.0 + 16.0 / 12.0)).abs() < 1e-12);
    eprintln!("area density against central differences: worst relative {worst:.2e}");
}

/// A pair of glued faces is one wall: a ray crossing it and the ray coming back the other
/// way through the same point find the same panel or window (the panel is judged on the
/// pair's face at −½ on both ways), and a crossing's decision follows the window's chart
/// rule there.
#[test]
fn walls_are_one_panel_seen_from_either_side() {
    use bevy_curved_spaces::scene::WallStyle;
    use bevy_curved_spaces::space::nil::{NilRay, flow};
    use bevy_curved_spaces::space::walk::CellWalk;
    use bevy_curved_spaces::trace::nil::walls::{NilWalls, panel_face};
    for k in [1, 3] {
        let space = NilSpace::new(k);
        let walls =
            NilWalls::new(&space, WallStyle::new(0.5).expect("an opening"), 0.01).expect("walls");
        let walker = NilWalker::<DVec4>::new(k);
        let mut panels = 0;
        let mut windows = 0;
        for i in 0..400 {
            let f = |m: u32| ((i * m) % 101) as f64 / 101.0 - 0.5;
            let start = walker.on_model(bevy_curved_spaces::geometry::Ray {
                point: DVec4::new(
                    0.8 * f(7),
                    0.8 * f(13),
                    0.8 * space.half_height() * f(29),
                    1.0,
                ),
                tangent: DVec3::new(f(31), f(37), f(41)).normalize().extend(0.0),
            });
            let Some(exit) = walker.exit(&start) else {
                continue;
            };
            let here = NilRay {
                point: start.point.truncate().to_array(),
                velocity: start.tangent.truncate().to_array(),
            };
            let left = flow(&here, exit.t);
            let entered = walker.through(&start, &exit);
            let entered_point = entered.point.truncate().to_array();
            // Forward: judged where the panel's face is met.
            let forward = if exit.face & 1 == 1 {
                left.point
            } else {
                entered_point
            };
            // Backward from the entered point: leaves through the partner face there.
            let back_face = exit.face ^ 1;
            let backward = if back_face & 1 == 1 {
                entered_point
            } else {
                left.point
            };
            assert_eq!(panel_face(exit.face), panel_face(back_face));
            let a = walls.on_panel(exit.face, forward);
            let b = walls.on_panel(back_face, backward);
            assert_eq!(a, b, "nil-{k}, ray {i}: face {} at {left:?}", exit.face);
            // The chart rule on the panel's face.
            let [x, y, z] = forward;
            let h = space.half_height();
            let room = match exit.face / 2 {
                0 => (0.5 - y.abs()).min(h - z.abs()),
                1 => (0.5 - x.abs()).min(h - z.abs()),
                _ => (0.5 - x.abs()).min(0.5 - y.abs()),
            };
            let margin = 0.5 * if exit.face < 4 { h.min(0.5) } else { 0.5 };
            assert_eq!(a, room < margin);
            if a {
                panels += 1;
            } else {
                windows += 1;
            }
        }
        assert!(panels > 20 && windows > 20, "nil-{k}: {panels} / {windows}");
    }
}
