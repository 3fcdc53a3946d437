//! The product geometries H²×R and S²×R: surfaces from their words (combinatorics, errors,
//! the polygon's gluing checked vertex by vertex in double-double) and the exact walk
//! (rays along the fibre and in the base, the walk against the geodesic of the universal
//! cover, long walks, f64 against double-double).

use bevy_curved_spaces::geometry::{DdMat4, DdVec4, DoubleDouble, Geometry, Ray, Real, Vector4};
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::product::{
    ProductError, ProductSpace, ProductWalker, ray_from_centre,
};
use bevy_curved_spaces::space::surface::{Polygon, SurfaceWord, WordError};
use bevy_curved_spaces::space::{Limit, walk::NO_FACE};
use glam::{DVec3, DVec4};
use std::f64::consts::PI;

#[test]
fn words_name_their_surfaces() {
    for (word, chi, orientable, geometry) in [
        ("aA", 2, true, Geometry::Spherical),
        ("aa", 1, false, Geometry::Spherical),
        ("abab", 1, false, Geometry::Spherical),
        ("abAB", 0, true, Geometry::Euclidean),
        ("aabb", 0, false, Geometry::Euclidean),
        ("abcABC", 0, true, Geometry::Euclidean),
        ("abABcdCD", -2, true, Geometry::Hyperbolic),
        ("abABcdCDefEF", -4, true, Geometry::Hyperbolic),
        ("aabbcc", -1, false, Geometry::Hyperbolic),
        ("abcdefABCDEF", -4, true, Geometry::Hyperbolic),
        ("abcdABCD", -2, true, Geometry::Hyperbolic),
    ] {
        let w = SurfaceWord::parse(word).unwrap_or_else(|e| panic!("{word}: {e}"));
        assert_eq!(w.euler_characteristic(), chi, "{word}");
        assert_eq!(w.orientable(), orientable, "{word}");
        assert_eq!(w.geometry(), geometry, "{word}");
        // Every corner is in exactly one vertex cycle.
        let mut corners: Vec<usize> = w.vertex_cycles.iter().flatten().copied().collect();
        corners.sort_unstable();
        assert_eq!(corners, (0..w.side_count()).collect::<Vec<_>>(), "{word}");
    }
}

#[test]
fn bad_words_say_what_is_wrong() {
    assert_eq!(SurfaceWord::parse(""), Err(WordError::Empty));
    assert!(matches!(
        SurfaceWord::parse("ab-AB"),
        Err(WordError::NotALetter('-', 3))
    ));
    assert!(matches!(
        SurfaceWord::parse("abA"),
        Err(WordError::Unpaired {
            letter: 'b',
            count: 1
        })
    ));
    assert!(matches!(
        SurfaceWord::parse("aaa"),
        Err(WordError::Unpaired {
            letter: 'a',
            count: 3
        })
    ));
    assert!(matches!(
        SurfaceWord::parse("aAbB"),
        Err(WordError::UnequalCycles { .. })
    ));
    assert!(matches!(
        SurfaceWord::parse(&"aA".repeat(40)),
        Err(WordError::TooLong(80))
    ));
    for e in [
        SurfaceWord::parse("").unwrap_err(),
        SurfaceWord::parse("aAbB").unwrap_err(),
    ] {
        assert!(!e.to_string().is_empty());
    }
    let bad = |w: &str, l: f64, p: u32| ProductSpace::new("x", w, l, p).unwrap_err();
    assert!(matches!(
        bad("abABcdCD", 0.0, 1),
        ProductError::BadLength(_)
    ));
    assert!(matches!(
        bad("abABcdCD", f64::NAN, 1),
        ProductError::BadLength(_)
    ));
    assert!(matches!(
        bad("abABcdCD", f64::INFINITY, 1),
        ProductError::BadLength(_)
    ));
    assert!(matches!(bad("abABcdCD", 1.0, 0), ProductError::BadTurn(0)));
    assert!(matches!(
        bad("abABcdCD", 1.0, 3),
        ProductError::TurnNotSymmetry { .. }
    ));
    assert!(matches!(bad("abAB", 1.0, 1), ProductError::Flat { .. }));
    // abABcdCD turns onto itself by a half turn (four letters on) only; the octagon of
    // opposite sides abcdABCD by every eighth of a turn.
    assert!(ProductSpace::new("x", "abABcdCD", 1.0, 2).is_ok());
    assert!(ProductSpace::new("x", "abABcdCD", 1.0, 4).is_err());
    assert!(ProductSpace::new("x", "abcdABCD", 1.0, 8).is_ok());
}

fn dd(x: f64) -> DoubleDouble {
    DoubleDouble::new(x)
}

/// Vertex `m` of the regular polygon (between sides m − 1 and m), as a model point.
fn vertex(polygon: &Polygon, n: usize, m: usize) -> DdVec4 {
    let r = polygon.circumradius;
    let (c, s) = match polygon.geometry {
        Geometry::Spherical => (r.cos_sin().0, r.cos_sin().1),
        _ => r.cosh_sinh(),
    };
    let (ct, st) = DoubleDouble::cos_sin_pi(2 * m as i64 - 1, n as i64);
    DdVec4([s * ct, s * st, dd(0.0), c])
}

fn max_abs(v: DdVec4) -> f64 {
    v.0.iter().fold(0.0_f64, |m, x| m.max(x.abs().to_f64()))
}

/// Each side's pairing maps the side's two ends onto the partner's, the right way round
/// for the kind of gluing, carries the cell beyond the partner and is the inverse of the
/// partner's pairing, all to 28 digits; the vertex cycles close with angle sum 2π.
#[test]
fn the_polygon_of_every_word_is_glued_as_it_says() {
    for word in [
        "abABcdCD",
        "abABcdCDefEF",
        "aabbcc",
        "abcdefABCDEF",
        "aabbccdd",
    ] {
        let w = SurfaceWord::parse(word).unwrap();
        let polygon = Polygon::of(&w);
        let n = w.side_count();
        let k = w.corners_per_vertex() as f64;
        let angle = polygon.angle.to_f64();
        assert!((angle * k - 2.0 * PI).abs() < 1e-12, "{word}");
        let centre = DdVec4([dd(0.0), dd(0.0), dd(0.0), dd(1.0)]);
        for (i, side) in polygon.sides.iter().enumerate() {
            let g = side.pairing;
            let j = side.partner;
            let back = polygon.sides[j].pairing;
            assert!(
                (back * g - DdMat4::IDENTITY).max_abs() < 1e-28,
                "{word} side {i}"
            );
            let (a, b) = (vertex(&polygon, n, i), vertex(&polygon, n, (i + 1) % n));
            let (ja, jb) = (vertex(&polygon, n, j), vertex(&polygon, n, (j + 1) % n));
            let preserving = w.sides[i].preserving;
            let (to_a, to_b) = if preserving { (jb, ja) } else { (ja, jb) };
            assert!(
                max_abs(g * a - to_a) < 1e-28,
                "{word} side {i}: start vertex"
            );
            assert!(max_abs(g * b - to_b) < 1e-28, "{word} side {i}: end vertex");
            // The image of the centre lies beyond the partner side.
            let cov = DdVec4([
                polygon.sides[j].normal[0],
                polygon.sides[j].normal[1],
                dd(0.0),
                -polygon.sides[j].offset,
            ]);
            assert!(cov.dot(g * centre).to_f64() > 0.0, "{word} side {i}");
            // The fibre is fixed.
            assert!((g.at(2, 2) - dd(1.0)).abs().to_f64() < 1e-30);
        }
    }
}

fn spaces() -> Vec<ProductSpace> {
    [
        ("bitorus-circle", "abABcdCD", 1.0, 1),
        ("bitorus-circle-turn", "abABcdCD", 0.7, 2),
        ("octagon-quarter-turn", "abcdABCD", 0.9, 4),
        ("genus-three", "abABcdCDefEF", 1.5, 1),
        ("three-crosscaps", "aabbcc", 1.0, 1),
        ("sphere-circle", "aA", 2.0, 1),
        ("sphere-turn", "aA", 1.0, 5),
        ("projective-plane-circle", "aa", 1.0, 1),
        ("projective-plane-turn", "abab", 1.2, 3),
    ]
    .into_iter()
    .map(|(name, w, l, p)| ProductSpace::new(name, w, l, p).unwrap())
    .collect()
}

fn random_direction(rng: &mut SplitMix64) -> DVec3 {
    loop {
        let d = DVec3::new(rng.unit(), rng.unit(), rng.unit()) * 2.0 - 1.0;
        if d.length() > 0.1 && d.length() <= 1.0 {
            return d.normalize();
        }
    }
}

#[test]
fn product_volumes_are_the_surface_area_times_the_circle() {
    for s in spaces() {
        let chi = s.word().euler_characteristic() as f64;
        assert!((s.volume() - 2.0 * PI * chi.abs() * s.length()).abs() < 1e-12);
    }
}

/// The walk is the geodesic of the universal cover: undoing the pairings crossed takes the
/// end back to `C(λd) p + S(λd)/λ · v` at height `z + μd`, for rays in every direction.
#[test]
fn walks_follow_the_geodesic_of_the_cover() {
    let mut rng = SplitMix64(0x9e0);
    for s in spaces() {
        let walker = ProductWalker::<DVec4>::new(&s);
        let g = s.base();
        for _ in 0..24 {
            let d = random_direction(&mut rng);
            let start = ray_from_centre(d);
            let distance = 6.0;
            let trace = walker.trace(start, Limit::Distance(distance));
            // Undo the crossings, latest first, with the exact pairings in double-double.
            let sides = s.side_faces();
            let up = s.top_pairing();
            let down = bevy_curved_spaces::space::exact::inverse(g, &up);
            let mut back = DdMat4::IDENTITY;
            let mut height = 0.0;
            for c in &trace.crossings {
                let m = if c.face == walker.top() {
                    height += s.length();
                    up
                } else if c.face == walker.bottom() {
                    height -= s.length();
                    down
                } else {
                    sides[c.face].pairing
                };
                back = m * back;
            }
            let undo = bevy_curved_spaces::space::exact::inverse(g, &back);
            let end = (undo * DdVec4::from_f64(trace.end.point)).to_f64();
            let lambda = (d.x * d.x + d.y * d.y).sqrt();
            let (c, sn) = g.cs(lambda * distance);
            let vb = DVec4::new(d.x, d.y, 0.0, 0.0) / lambda.max(1e-300);
            let want = DVec4::W * c + vb * sn;
            let base_err = (DVec4::new(end.x, end.y, 0.0, end.w) - want).length();
            assert!(
                base_err < 1e-9 * c.abs().max(1.0),
                "{}: base off by {base_err:e}",
                s.name()
            );
            let z = end.z + height;
            assert!(
                (z - d.z * distance).abs() < 1e-9,
                "{}: height {z} not {}",
                s.name(),
                d.z * distance
            );
            assert!(s.outside_by(trace.end.point) < 1e-9);
        }
    }
}

#[test]
fn rays_along_the_fibre_cross_only_the_top_and_keep_their_place() {
    for s in spaces() {
        let walker = ProductWalker::<DVec4>::new(&s);
        let trace = walker.trace(ray_from_centre(DVec3::Z), Limit::Crossings(12));
        assert_eq!(trace.crossings.len(), 12);
        for (i, c) in trace.crossings.iter().enumerate() {
            assert_eq!(c.face, walker.top(), "{}", s.name());
            let want = s.length() * (i as f64 + 0.5);
            assert!((c.distance - want).abs() < 1e-12 * want.max(1.0));
            // The turn fixes the centre: the ray stays on the centre's fibre.
            assert!(c.ray.point.x.abs() + c.ray.point.y.abs() < 1e-12);
        }
        let down = walker.trace(ray_from_centre(-DVec3::Z), Limit::Crossings(3));
        assert!(down.crossings.iter().all(|c| c.face == walker.bottom()));
    }
}

#[test]
fn rays_in_the_base_never_reach_the_top() {
    for s in spaces() {
        let walker = ProductWalker::<DVec4>::new(&s);
        for a in [0.0, 0.3, 1.1, 2.9] {
            let ray = ray_from_centre(DVec3::new(f64::cos(a), f64::sin(a), 0.0));
            let trace = walker.trace(ray, Limit::Distance(20.0));
            assert!(
                trace.crossings.iter().all(|c| c.face < walker.top()),
                "{}",
                s.name()
            );
            assert!(trace.end.point.z.abs() < 1e-12);
            if s.base() == Geometry::Spherical && s.word().corners_per_vertex() == 1 {
                // On S²×S¹ it circles without crossing, and comes back after 2π.
                assert!(trace.crossings.is_empty());
                let round = walker.trace(ray, Limit::Distance(2.0 * PI));
                assert!((round.end.point - ray.point).length() < 1e-12);
                assert!(walker.trace(ray, Limit::Crossings(5)).crossings.is_empty());
            }
        }
    }
}

/// Rays aimed at the polygon's corners (the vertical edges) and along them stay in the
/// cell; 10⁵ crossings of random rays too.
#[test]
fn corners_and_long_walks_stay_in_the_cell() {
    let mut rng = SplitMix64(0xc0e);
    for s in spaces() {
        let walker = ProductWalker::<DVec4>::new(&s);
        let n = s.word().side_count();
        for m in 0..n {
            let a = PI * (2.0 * m as f64 - 1.0) / n as f64;
            for tilt in [0.0, 0.4, -0.9] {
                let ray = ray_from_centre(DVec3::new(a.cos(), a.sin(), tilt));
                let trace = walker.trace(ray, Limit::Crossings(40));
                for c in &trace.crossings {
                    assert!(s.outside_by(c.ray.point) < 1e-9, "{} corner {m}", s.name());
                }
            }
        }
        let ray = ray_from_centre(random_direction(&mut rng));
        let mut worst = f64::NEG_INFINITY;
        let mut count = 0;
        walker.walk(ray, Limit::Crossings(100_000), |c| {
            worst = worst.max(s.outside_by(c.ray.point));
            count += 1;
            true
        });
        assert!(
            worst < 1e-9,
            "{}: {worst:e} outside after {count} crossings",
            s.name()
        );
    }
}

/// f64 and f32 walks against the double-double walk of the same cell: the same faces for
/// 20 crossings (f64) and a few (f32), their points close.
#[test]
fn f64_and_f32_walks_agree_with_double_double() {
    let mut rng = SplitMix64(0xdd);
    for s in spaces() {
        let reference = ProductWalker::<DdVec4>::new(&s);
        let w64 = ProductWalker::<DVec4>::new(&s);
        for _ in 0..8 {
            let start = ray_from_centre(random_direction(&mut rng));
            let to_dd = |r: &Ray<DVec4>| Ray {
                point: DdVec4::from_f64(r.point),
                tangent: DdVec4::from_f64(r.tangent),
            };
            let exact = reference.trace(to_dd(&start), Limit::Crossings(20));
            let ours = w64.trace(start, Limit::Crossings(20));
            for (n, (a, b)) in exact.crossings.iter().zip(&ours.crossings).enumerate() {
                if a.face != b.face {
                    break;
                }
                let off = (a.ray.point.to_f64() - b.ray.point).length();
                // A few units of rounding per crossing, grown like cosh² of the distance
                // in H² (the point's size times its sensitivity).
                let grow = match s.base() {
                    Geometry::Hyperbolic => a.distance.cosh().powi(2),
                    _ => 1.0 + a.distance,
                };
                let bound = 64.0 * f64::EPSILON * (n as f64 + 1.0) * grow;
                assert!(
                    off < bound,
                    "{} crossing {n}: {off:e} > {bound:e}",
                    s.name()
                );
            }
        }
        let w32 = ProductWalker::<glam::Vec4>::new(&s);
        let t32 = w32.trace(
            Ray {
                point: glam::Vec4::W,
                tangent: glam::Vec4::new(0.6, 0.0, 0.8, 0.0),
            },
            Limit::Crossings(4),
        );
        assert!(!t32.crossings.is_empty());
        assert!(t32.crossings.iter().all(|c| c.face != NO_FACE));
    }
}

/// H₁ from the word and the turn: the surface's homology plus the circle, the turn's
/// action on the letters taken out.
#[test]
fn product_homology_is_the_surfaces_plus_the_circle() {
    use bevy_curved_spaces::space::product::{ProductOrFlat, product_space};
    for (id, want) in [
        ("bitorus-circle", "Z + Z + Z + Z + Z"),
        ("genus-three-circle", "Z + Z + Z + Z + Z + Z + Z"),
        ("crosscaps-circle", "Z/2 + Z + Z + Z"),
        ("sphere-circle", "Z"),
        ("sphere-circle-turn", "Z"),
        ("projective-plane-circle", "Z/2 + Z"),
        // A half turn of abABcdCD swaps the two handles: a = c, b = d.
        ("bitorus-circle-turn", "Z + Z + Z"),
    ] {
        let Some(Ok(ProductOrFlat::Product(space))) = product_space(id) else {
            panic!("{id} is no product space");
        };
        assert_eq!(space.homology().to_string(), want, "{id}");
    }
    // Ids with their parts wrong are errors naming the part; a flat word is a flat space.
    for bad in [
        "surface-abc-circle-1",
        "surface-abABcdCD-circle-0",
        "surface-abABcdCD-circle-x",
        "surface-abABcdCD-circle-1-turn-3",
        "surface-abABcdCD-circle-1-turn-q",
        "surface-abAB-circle-1-turn-0",
        "surface-abAB-circle-1-turn-3",
        "surface-abABcdCD",
        "surface--circle-1",
    ] {
        match product_space(bad) {
            Some(Err(e)) => assert!(e.starts_with(bad), "{bad}: {e}"),
            other => panic!("{bad}: {other:?}"),
        }
    }
    assert!(product_space("lens-7-1").is_none());
    match product_space("surface-abAB-circle-1.5") {
        Some(Ok(ProductOrFlat::Flat(space))) => {
            assert_eq!(space.geometry(), Geometry::Euclidean);
            assert!((bevy_curved_spaces::space::invariants::volume(&space) - 1.5).abs() < 1e-12);
        }
        other => panic!("a flat word: {other:?}"),
    }
    match product_space("surface-abcABC-circle-1-turn-6") {
        Some(Ok(ProductOrFlat::Flat(space))) => assert!(space.orientable()),
        other => panic!("the sixth-turn space: {other:?}"),
    }
}

/// Every named product space renders its default scene on the CPU: a third of the pixels show
/// something, the centre ball is in view, and a second render is the same picture.
#[test]
fn every_named_product_space_renders() {
    use bevy_curved_spaces::space::product::{PRODUCT_ALIASES, ProductOrFlat, product_space};
    use bevy_curved_spaces::trace::product::{
        default_camera, default_scene, render_product, trace_product_pixel,
    };
    for alias in PRODUCT_ALIASES {
        let Some(Ok(ProductOrFlat::Product(space))) = product_space(alias.id) else {
            panic!("{}", alias.id);
        };
        let scene = default_scene(&space);
        let camera = default_camera(&space);
        let (w, h) = (48, 27);
        let image = render_product(&space, &scene, &camera, w, h, 24);
        let fog = scene
            .fog_colour
            .to_array()
            .map(|x| (x * 255.0).round() as u8);
        let shown = image.pixels().filter(|p| p.0 != fog).count();
        assert!(
            shown > (w * h / 3) as usize,
            "{}: {shown} pixels show anything",
            alias.id
        );
        assert_eq!(image, render_product(&space, &scene, &camera, w, h, 24));
        // The ray through the middle meets the centre ball, first, inside the cell.
        let walker = ProductWalker::<DVec4>::new(&space);
        let middle = trace_product_pixel(&walker, None, &scene, camera.ray(w / 2, h / 2, w, h), 24);
        let ball = scene.objects.last().unwrap().colour;
        assert!(
            middle.dot(ball) > 0.05 && middle.max_element() > 0.1,
            "{}: {middle:?}",
            alias.id
        );
    }
}

/// Random and mutated ids: every one is a product space that walks, a flat space, or an
/// error naming the problem; never a panic.
#[test]
fn random_product_ids_are_spaces_or_clear_errors() {
    use bevy_curved_spaces::space::product::{ProductOrFlat, product_space};
    let mut rng = SplitMix64(0x5eed);
    let mut pick = |n: usize| ((rng.unit() * n as f64) as usize).min(n - 1);
    let letters: Vec<char> = "aAbBcCdD-1 é".chars().collect();
    let numbers = [
        "1", "0", "-2", "nan", "inf", "1e308", "1e-320", "0.5", "x", "",
    ];
    let (mut built, mut refused) = (0, 0);
    for case in 0..600 {
        let words = [
            "abABcdCD", "aabbcc", "aa", "aA", "abAB", "abcABC", "abcdABCD", "abab",
        ];
        let mut word: Vec<char> = words[pick(words.len())].chars().collect();
        match case % 4 {
            // Kept as it is: most of these build.
            0 => {}
            // A letter changed, dropped or added.
            1 => {
                let i = pick(word.len());
                word[i] = letters[pick(letters.len())];
            }
            2 => {
                word.remove(pick(word.len()));
            }
            _ => word.insert(pick(word.len() + 1), letters[pick(letters.len())]),
        }
        let word: String = word.into_iter().collect();
        let l = numbers[pick(numbers.len())];
        let id = if case % 3 == 0 {
            format!(
                "surface-{word}-circle-{l}-turn-{}",
                numbers[pick(numbers.len())]
            )
        } else {
            format!("surface-{word}-circle-{l}")
        };
        match product_space(&id) {
            Some(Ok(ProductOrFlat::Product(space))) => {
                built += 1;
                let walker = ProductWalker::<DVec4>::new(&space);
                let trace = walker.trace(
                    ray_from_centre(DVec3::new(0.5, 0.3, 0.4)),
                    Limit::Crossings(8),
                );
                assert!(trace.end.point.is_finite(), "{id}");
            }
            Some(Ok(ProductOrFlat::Flat(_))) => built += 1,
            Some(Err(e)) => {
                refused += 1;
                assert!(e.starts_with(&id) && e.len() > id.len() + 10, "{id}: {e}");
            }
            None => panic!("{id}: not recognised as a product id"),
        }
    }
    eprintln!("product ids: {built} built, {refused} refused");
    assert!(built > 0 && refused > 0);
}

/// The injectivity radius: the Bolza surface (the regular octagon with opposite sides
/// glued, `abcdABCD`) has systole `2 acosh(1 + √2)`, so times a long circle its injectivity
/// radius is `acosh(1 + √2)`, and times a short one half the circle; S²×S¹ and RP²×S¹ from
/// the fibre and the antipodal map.
#[test]
fn product_injectivity_radii() {
    let bolza = (1.0 + 2f64.sqrt()).acosh();
    let long = ProductSpace::new("bolza", "abcdABCD", 10.0, 1).unwrap();
    let r = long.injectivity_radius(200_000).unwrap();
    assert!((r - bolza).abs() < 1e-9, "{r} against {bolza}");
    let short = ProductSpace::new("bolza", "abcdABCD", 1.0, 4).unwrap();
    assert!((short.injectivity_radius(200_000).unwrap() - 0.5).abs() < 1e-12);
    let sphere = ProductSpace::new("s", "aA", PI, 1).unwrap();
    assert!((sphere.injectivity_radius(10).unwrap() - PI / 2.0).abs() < 1e-12);
    let long_sphere = ProductSpace::new("s", "aA", 10.0, 1).unwrap();
    assert!((long_sphere.injectivity_radius(10).unwrap() - PI).abs() < 1e-12);
    let pp = ProductSpace::new("p", "aa", 10.0, 1).unwrap();
    assert!((pp.injectivity_radius(10).unwrap() - PI / 2.0).abs() < 1e-12);
    // The bitorus word's octagon: at most the Bolza value (its translations across sides).
    let bitorus = ProductSpace::new("b", "abABcdCD", 10.0, 1).unwrap();
    let rb = bitorus.injectivity_radius(200_000).unwrap();
    assert!(rb > 0.3 && rb <= bolza + 1e-9, "{rb}");
}

/// The product walks against the double-double walk of the same cell, in units of the
/// conditioning limit: the target of the constant-curvature walk (2× median, 5× worst), in
/// both geometries and both precisions.
#[test]
fn product_walks_stay_near_the_conditioning_limit() {
    const MEDIAN_BOUND: f64 = 2.0;
    const WORST_BOUND: f64 = 5.0;
    use bevy_curved_spaces::space::accuracy::summarize;
    use bevy_curved_spaces::space::product::accuracy::product_walk_accuracy;
    let mut rng = SplitMix64(0xacc);
    for s in spaces() {
        let rays: Vec<Ray<DVec4>> = (0..10)
            .map(|_| ray_from_centre(random_direction(&mut rng)))
            .collect();
        for (name, rows) in [
            (
                "f64",
                rays.iter()
                    .flat_map(|r| product_walk_accuracy::<DVec4>(&s, *r, 24))
                    .collect::<Vec<_>>(),
            ),
            (
                "f32",
                rays.iter()
                    .flat_map(|r| product_walk_accuracy::<glam::Vec4>(&s, *r, 24))
                    .collect(),
            ),
        ] {
            let sum =
                summarize(&rows).unwrap_or_else(|| panic!("{} {name}: none counts", s.name()));
            eprintln!(
                "{} {name}: median {:.2}, worst {:.2} over {} crossings ({} left out)",
                s.name(),
                sum.median,
                sum.worst,
                sum.counted,
                sum.left_out
            );
            assert!(
                sum.median <= MEDIAN_BOUND && sum.worst <= WORST_BOUND,
                "{} {name}: median {:.2}, worst {:.2}",
                s.name(),
                sum.median,
                sum.worst
            );
            assert!(
                sum.counted >= 40,
                "{} {name}: only {} count",
                s.name(),
                sum.counted
            );
        }
    }
}
