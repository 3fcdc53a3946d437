//! Product scenes (H²×R, S²×R): scene files (the shipped one, every error with its line),
//! the light's falloff against the geodesic sphere's area measured from the exponential
//! map, and stereo renders against one eye's mono render.

use bevy_curved_spaces::geometry::Geometry;
use bevy_curved_spaces::space::product::motion::{camera_frame, product_dot, product_eye_frames};
use bevy_curved_spaces::trace::product::file::{load_product_scene_file, parse_product_scene};
use bevy_curved_spaces::trace::product::{
    ProductCamera, ProductParts, ProductShape, default_scene, light_spread, render_product,
    render_product_view, scene_with_parts,
};
use bevy_curved_spaces::view::ViewLayout;
use bevy_curved_spaces::view::stereo::StereoMode;
use glam::{DVec3, DVec4};
use std::path::PathBuf;

use crate::common::product;

/// Points at distance `r` round `c` in the product (a ball's surface), 26 directions.
fn ball_surface(g: Geometry, c: DVec4, r: f64) -> Vec<DVec4> {
    let mut out = Vec::new();
    for i in -1i32..=1 {
        for j in -1i32..=1 {
            for k in -1i32..=1 {
                if (i, j, k) == (0, 0, 0) {
                    continue;
                }
                let d = DVec3::new(f64::from(i), f64::from(j), f64::from(k)).normalize();
                // Surface distance r·|d.xy| from c, height r·d.z: walk it from c's frame.
                let rho = r * d.truncate().length();
                let cb = DVec3::new(c.x, c.y, c.w);
                // A unit surface tangent at c along the direction (d.x, d.y) of the chart.
                let raw = DVec3::new(d.x, d.y, 0.0);
                let form = |a: DVec3, b: DVec3| a.x * b.x + a.y * b.y + g.kappa() * a.z * b.z;
                let t = raw - cb * (form(raw, cb) / form(cb, cb));
                let point = if form(t, t) > 0.0 {
                    let t = t / form(t, t).sqrt();
                    let (co, si) = g.cs(rho);
                    cb * co + t * si
                } else {
                    cb
                };
                out.push(DVec4::new(point.x, point.y, c.z + r * d.z, point.z));
            }
        }
    }
    out
}

#[test]
fn the_shipped_product_scene_loads_and_fits_in_its_cell() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/bitorus_pillars.toml");
    let file = load_product_scene_file(&path)
        .expect("loads")
        .expect("a product scene file");
    assert_eq!(file.space.name(), "bitorus-circle");
    let edges = scene_with_parts(
        &file.space,
        ProductParts {
            edges: true,
            centre_ball: false,
        },
    )
    .objects
    .len();
    // Six objects, a prism of 3 sides (6 wall and 2 cap triangles) and a 2-triangle wall.
    assert_eq!(file.scene.objects.len(), edges + 6 + 8 + 2);
    let g = file.space.base();
    let scale = file.space.scale();
    for o in &file.scene.objects[edges..] {
        match o.shape {
            ProductShape::Point(c) => {
                for p in ball_surface(g, c, o.radius) {
                    assert!(
                        file.space.outside_by(p) <= 1e-12,
                        "{o:?} reaches out at {p}"
                    );
                }
            }
            ProductShape::Fibre(c) | ProductShape::Disc(c) => {
                for p in ball_surface(g, DVec4::new(c.x, c.y, 0.0, c.w), o.radius) {
                    let flat = DVec4::new(p.x, p.y, 0.0, p.w);
                    assert!(file.space.outside_by(flat) <= 1e-12, "{o:?}");
                }
            }
            ProductShape::Geodesic { height, .. } => {
                assert!((height - 0.45 * scale).abs() < 1e-12);
            }
            ProductShape::Triangle(t) => {
                // Every triangle of the block and the wall stands in the cell: its slice
                // or its plane's points near the corners are inside.
                assert!(matches!(
                    t,
                    bevy_curved_spaces::trace::product::triangle::ProductTriangle::Horizontal { .. }
                        | bevy_curved_spaces::trace::product::triangle::ProductTriangle::Vertical { .. }
                ));
            }
        }
    }
    // The start view: at its position, looking towards its target, the fibre up.
    let start = file.start.expect("a start view");
    assert!((start.fov_y_degrees - 75.0).abs() < 1e-12);
    assert!((start.point.z - 0.3 * scale).abs() < 1e-12);
    let frame = file.start_frame().unwrap();
    assert!(crate::common::product_frame_defect(g, frame) < 1e-12);
    assert!(
        product_dot(g, start.frame[0], DVec4::Z).abs() < 1e-12,
        "level"
    );
    assert!(
        product_dot(g, start.frame[1], DVec4::Z) > 0.5,
        "the fibre up"
    );
    assert!(file.scene.light.is_finite() && file.space.outside_by(file.scene.light) < 0.0);
}

/// A product scene file's `[lighting]` lights its lamp by its images within the reach (in
/// units of the scale), the light moved by the file found again.
#[test]
fn a_product_scene_file_chooses_its_lighting() {
    use bevy_curved_spaces::scene::lighting::LightPaths;
    let text = "space = \"bitorus-circle\"\n[[light]]\nposition = [0.2, 0.1, -0.3]\n\
                [lighting]\nreach = 3\nshadows = 6\ntail = false\n";
    let file = parse_product_scene(text, "l.toml").unwrap();
    let l = file.scene.lighting;
    assert_eq!((l.paths, l.shadows, l.tail), (LightPaths::Images, 6, false));
    assert!((file.scene.lamp.reach - 3.0 * file.space.scale()).abs() < 1e-12);
    // The first image is the lamp itself, where the file put it.
    let first = file.scene.lamp.images[0];
    assert!((first - file.scene.light).length() < 1e-12, "{first}");
    let nearest = parse_product_scene(
        "space = \"bitorus-circle\"\n[lighting]\npaths = \"nearest\"\n",
        "n.toml",
    )
    .unwrap();
    assert_eq!(nearest.scene.lighting.paths, LightPaths::Nearest);
    assert!(nearest.scene.lamp.images.is_empty());
}

#[test]
fn a_geodesic_object_runs_through_both_its_points() {
    for id in ["bitorus-circle", "sphere-circle"] {
        let space = product(id);
        let text = format!(
            "space = \"{id}\"\nedges = false\n[[object]]\ntype = \"geodesic\"\nfrom = [0.3, -0.2]\n\
             to = [-0.1, 0.4]\nheight = 0.25\nradius = 0.05\n"
        );
        let file = parse_product_scene(&text, "g.toml").unwrap();
        let ProductShape::Geodesic { covector, height } = file.scene.objects[0].shape else {
            panic!("a geodesic");
        };
        let g = space.base();
        assert!((height - 0.25 * space.scale()).abs() < 1e-15);
        for xy in [[0.3, -0.2], [-0.1, 0.4]] {
            let d = glam::DVec2::from_array(xy);
            let (c, s) = g.cs(d.length() * space.scale());
            let p = DVec4::new(s * d.x / d.length(), s * d.y / d.length(), 0.0, c);
            assert!(covector.dot(p).abs() < 1e-14, "{id}: {xy:?} off the line");
        }
        // A unit covector: S(distance) = covector · point.
        let dual = covector.x.powi(2) + covector.y.powi(2) + g.kappa() * covector.w.powi(2);
        assert!((dual - 1.0).abs() < 1e-14, "{id}");
    }
}

#[test]
fn product_scene_file_errors_name_the_line() {
    let cases: &[(&str, usize, &str)] = &[
        (
            "space = \"bitorus-circle\"\nfog = 2\ncolor = [1, 0, 0]\n",
            3,
            "did you mean `colour`",
        ),
        ("space = \"surface-abAB-circle-1\"\n", 1, "flat"),
        ("space = \"surface-abcA-circle-1\"\n", 1, "letter"),
        ("space = \"bitorus-circle\"\nfog = -1\n", 2, "positive"),
        (
            "space = \"bitorus-circle\"\nambient = 2\n",
            2,
            "between 0 and 1",
        ),
        (
            "space = \"bitorus-circle\"\nwall_opacity = 0.5\n",
            2,
            "needs walls",
        ),
        (
            "space = \"bitorus-circle\"\n\n[[object]]\ntype = \"ball\"\nposition = [0, 0, 0.9]\nradius = 0.3\n",
            3,
            "does not fit",
        ),
        (
            "space = \"bitorus-circle\"\n[[object]]\ntype = \"ball\"\nposition = [2, 0, 0]\nradius = 0.1\n",
            2,
            "does not fit",
        ),
        (
            "space = \"bitorus-circle\"\n[[object]]\ntype = \"ball\"\nposition = [0, 0, 0]\nradius = 0\n",
            2,
            "positive",
        ),
        (
            "space = \"bitorus-circle\"\n[[object]]\ntype = \"fibre\"\nposition = [1.5, 0]\nradius = 0.1\n",
            2,
            "polygon",
        ),
        (
            "space = \"bitorus-circle\"\n[[object]]\ntype = \"geodesic\"\nfrom = [0.1, 0]\nto = [0.1, 0]\nheight = 0\nradius = 0.1\n",
            2,
            "no one line",
        ),
        (
            "space = \"bitorus-circle\"\n[[object]]\ntype = \"cone\"\n",
            3,
            "cone",
        ),
        (
            "space = \"bitorus-circle\"\n[[light]]\nposition = [0, 0, 0]\n[[light]]\nposition = [0, 0, 0.1]\n",
            4,
            "one light",
        ),
        (
            "space = \"bitorus-circle\"\n[[light]]\nposition = [0, 0, 5]\n",
            2,
            "the light",
        ),
        (
            "space = \"bitorus-circle\"\n[lighting]\npaths = \"all\"\n",
            3,
            "\"images\" or \"nearest\"",
        ),
        (
            "space = \"bitorus-circle\"\n[lighting]\nshadows = 65\n",
            3,
            "shadows must be 0 to 64",
        ),
        (
            "space = \"bitorus-circle\"\n[lighting]\nreach = 0\n",
            3,
            "light reach",
        ),
        (
            "space = \"bitorus-circle\"\n[start]\nposition = [0.1, 0, 0]\nlook_at = [0.1, 0, 0]\n",
            2,
            "nothing to look towards",
        ),
        (
            "space = \"bitorus-circle\"\n[start]\nposition = [0.1, 0, 0]\nfov = 190\n",
            2,
            "fov",
        ),
        (
            "space = \"sphere-circle\"\n[start]\nposition = [0.1, 0, 0]\nlook_at = [-1.9, 0, 0]\n",
            2,
            "opposite",
        ),
        (
            "space = \"bitorus-circle\"\n[[object]]\ntype = \"ball\"\nposition = [nan, 0, 0]\nradius = 0.1\n",
            2,
            "finite",
        ),
    ];
    for (text, line, says) in cases {
        let e = parse_product_scene(text, "s.toml")
            .err()
            .unwrap_or_else(|| panic!("accepted:\n{text}"));
        assert_eq!(e.line, Some(*line), "{e}\n{text}");
        assert!(
            e.to_string().starts_with(&format!("s.toml:{line}: ")),
            "{e}"
        );
        assert!(e.message.contains(says), "{e} (wanted {says:?})");
    }
}

/// The geodesic sphere's area per solid angle at the light, measured from the exponential
/// map by central differences: `|∂θX ∧ ∂φX| / cos θ` in the product metric.
fn measured_spread(g: Geometry, r: f64, theta: f64) -> f64 {
    let exp = |t: f64, p: f64| {
        let rho = r * t.cos();
        let (c, s) = g.cs(rho);
        DVec4::new(s * p.cos(), s * p.sin(), r * t.sin(), c)
    };
    let (phi, h) = (0.7, 1e-5);
    let dt = (exp(theta + h, phi) - exp(theta - h, phi)) / (2.0 * h);
    let dp = (exp(theta, phi + h) - exp(theta, phi - h)) / (2.0 * h);
    let m = |a: DVec4, b: DVec4| a.x * b.x + a.y * b.y + a.z * b.z + g.kappa() * a.w * b.w;
    let area = (m(dt, dt) * m(dp, dp) - m(dt, dp).powi(2)).sqrt();
    area / theta.cos()
}

#[test]
fn the_lights_falloff_is_the_geodesic_spheres_area() {
    for g in [Geometry::Hyperbolic, Geometry::Spherical] {
        for r in [0.05, 0.5, 1.3, 2.5] {
            for theta in [-1.2, -0.4, 0.0, 0.3, 1.0, 1.5] {
                let rho = r * f64::cos(theta);
                if g == Geometry::Spherical && rho >= 3.0 {
                    continue;
                }
                let want = measured_spread(g, r, theta);
                let got = light_spread(g, rho, r * f64::sin(theta));
                assert!(
                    ((got - want) / want).abs() < 1e-7,
                    "{g:?} r {r} θ {theta}: {got} against {want}"
                );
            }
        }
        // Near the light and straight up the fibre it is the Euclidean r².
        assert!((light_spread(g, 0.0, 0.7) - 0.49).abs() < 1e-15);
        assert!((light_spread(g, 1e-6, 0.0) - 1e-12).abs() < 1e-24);
    }
    // Across H² it grows like e^ρ; on S² it closes up at the antipode.
    assert!(light_spread(Geometry::Hyperbolic, 6.0, 0.0) > 36.0 * 30.0);
    assert!(light_spread(Geometry::Spherical, std::f64::consts::PI, 0.0) < 1e-14);
}

#[test]
fn a_stereo_render_is_each_eyes_mono_render_side_by_side() {
    for id in ["bitorus-circle", "sphere-circle-turn"] {
        let space = product(id);
        let scene = default_scene(&space);
        let camera = bevy_curved_spaces::trace::product::default_camera(&space);
        let head = camera_frame(camera.point, camera.frame);
        let ipd = 0.2 * space.scale();
        let eyes = product_eye_frames(&space, head, ipd);
        let g = space.base();
        // The eyes are ipd apart, either side of the head along its right, level.
        for (e, sign) in eyes.iter().zip([-1.0, 1.0]) {
            let away = e.w_axis - head.w_axis;
            assert!(sign * product_dot(g, away, head.x_axis) > 0.0, "{id}");
            assert!(crate::common::product_frame_defect(g, *e) < 1e-12, "{id}");
            assert!((e.w_axis.z - head.w_axis.z).abs() < 1e-12, "{id}");
        }
        let (w, h) = (32u32, 12u32);
        let layout = ViewLayout::new(
            StereoMode::SideBySide,
            false,
            eyes,
            camera.fov_y_degrees,
            w,
            h,
        );
        let both = render_product_view(&space, &scene, &layout, 12);
        for (k, eye) in eyes.iter().enumerate() {
            let mono = render_product(
                &space,
                &scene,
                &ProductCamera {
                    point: eye.w_axis,
                    frame: [eye.x_axis, eye.y_axis, eye.z_axis],
                    fov_y_degrees: camera.fov_y_degrees,
                },
                w / 2,
                h,
                12,
            );
            for j in 0..h {
                for i in 0..w / 2 {
                    assert_eq!(
                        both.get_pixel(i + k as u32 * w / 2, j),
                        mono.get_pixel(i, j),
                        "{id}: eye {k} pixel ({i}, {j})"
                    );
                }
            }
        }
        // The two eyes see different pictures (the eyes are apart).
        let (left, right) = (both.view(0, 0, w / 2, h), both.view(w / 2, 0, w / 2, h));
        use image::GenericImageView;
        assert!(
            left.pixels().zip(right.pixels()).any(|(a, b)| a.2 != b.2),
            "{id}"
        );
    }
}

/// A surface point at chart-free coordinates: distance `d` from the centre towards angle `a`,
/// at height `z`.
fn point(g: Geometry, d: f64, a: f64, z: f64) -> DVec4 {
    let (c, s) = g.cs(d);
    DVec4::new(s * a.cos(), s * a.sin(), z, c)
}

/// The product distance between two points (surface distance and height).
fn product_distance(g: Geometry, p: DVec4, q: DVec4) -> f64 {
    let d = DVec4::new(p.x - q.x, p.y - q.y, 0.0, p.w - q.w);
    let chord = (d.x * d.x + d.y * d.y + g.kappa() * d.w * d.w)
        .max(0.0)
        .sqrt();
    let db = match g {
        Geometry::Spherical => 2.0 * (0.5 * chord).asin(),
        _ => 2.0 * (0.5 * chord).asinh(),
    };
    (db * db + (p.z - q.z).powi(2)).sqrt()
}

#[test]
fn triangles_are_met_where_the_geodesic_to_them_ends() {
    use bevy_curved_spaces::geometry::Ray;
    use bevy_curved_spaces::space::product::ProductWalker;
    use bevy_curved_spaces::trace::product::triangle::ProductTriangle;
    use bevy_curved_spaces::trace::product::{
        ProductObject, ProductRayEnd, first_product_hit, tangent_towards,
    };
    for id in ["bitorus-circle", "sphere-circle-turn", "crosscaps-circle"] {
        let space = product(id);
        let g = space.base();
        let r = 0.5 * space.scale();
        let h = 0.2 * space.length();
        // A slice's triangle and a vertical one over the geodesic through two points.
        let flat = [
            point(g, r, 0.2, -h),
            point(g, r, 2.3, -h),
            point(g, r, 4.2, -h),
        ];
        let (p, q) = (point(g, r, -0.4, 0.0), point(g, 0.8 * r, 1.9, 0.0));
        let upright = [
            DVec4::new(p.x, p.y, -h, p.w),
            DVec4::new(q.x, q.y, -h, q.w),
            DVec4::new(q.x, q.y, h, q.w),
        ];
        for corners in [flat, upright] {
            let triangle = ProductTriangle::new(g, corners).unwrap_or_else(|e| panic!("{id}: {e}"));
            // Its corners' centroid by the barycentric weights is inside; a point past a
            // corner is not.
            let centroid = match triangle {
                ProductTriangle::Horizontal { .. } => {
                    let m = (corners[0] + corners[1] + corners[2]) / 3.0;
                    let b = DVec4::new(m.x, m.y, 0.0, m.w);
                    let n = (b.x * b.x + b.y * b.y + g.kappa() * b.w * b.w).abs().sqrt();
                    DVec4::new(m.x / n, m.y / n, m.z, m.w / n)
                }
                ProductTriangle::Vertical { .. } => {
                    // In (s, z) from p the corners are (0, −h), (D, −h), (D, h): the point
                    // (2D/3, −h/3) is inside.
                    let d = product_distance(g, p, q);
                    let t = tangent_towards(g, p, q);
                    let (c, sn) = g.cs(2.0 * d / 3.0);
                    let b = p * c + t * sn;
                    DVec4::new(b.x, b.y, -h / 3.0, b.w)
                }
            };
            assert!(
                triangle.contains(g, centroid),
                "{id}: {triangle:?} lacks {centroid}"
            );
            let beyond = point(g, 1.8 * r, 0.2, -h);
            assert!(
                !triangle.contains(g, beyond)
                    || matches!(triangle, ProductTriangle::Vertical { .. })
            );
            // A ray from a point of the cell towards the centroid meets the triangle there,
            // at the product distance (the geodesic's length), to f64's precision.
            let scene = bevy_curved_spaces::trace::product::ProductScene {
                objects: vec![ProductObject {
                    shape: ProductShape::Triangle(triangle),
                    radius: 0.0,
                    colour: DVec3::ONE,
                }],
                ..scene_with_parts(
                    &space,
                    ProductParts {
                        edges: false,
                        centre_ball: false,
                    },
                )
            };
            let walker = ProductWalker::<DVec4>::new(&space);
            for eye in [
                point(g, 0.3 * r, 1.0, 0.35 * h),
                point(g, 0.6 * r, -2.0, -0.1 * h),
            ] {
                let ray = Ray {
                    point: eye,
                    tangent: tangent_towards(g, eye, centroid),
                };
                let want = product_distance(g, eye, centroid);
                match first_product_hit(&walker, &scene, ray, 4) {
                    ProductRayEnd::Hit { distance, at, .. } => {
                        assert!(
                            (distance - want).abs() < 1e-12,
                            "{id}: {distance} against {want}"
                        );
                        assert!(
                            (at - centroid).abs().max_element() < 1e-12,
                            "{id}: {at} against {centroid}"
                        );
                    }
                    other => panic!("{id}: {other:?} instead of the triangle"),
                }
            }
        }
    }
}

#[test]
fn only_exact_triangles_are_taken() {
    use bevy_curved_spaces::trace::product::triangle::ProductTriangle;
    let g = Geometry::Hyperbolic;
    let (a, b, c) = (
        point(g, 0.5, 0.0, 0.0),
        point(g, 0.5, 2.0, 0.0),
        point(g, 0.5, 4.0, 0.0),
    );
    assert!(ProductTriangle::new(g, [a, b, c]).is_ok());
    let lifted = DVec4::new(c.x, c.y, 0.3, c.w);
    let e = ProductTriangle::new(g, [a, b, lifted]).unwrap_err();
    assert!(e.contains("curved"), "{e}");
    let e = ProductTriangle::new(g, [a, a, DVec4::new(a.x, a.y, 0.5, a.w)]).unwrap_err();
    assert!(e.contains("one surface point"), "{e}");
    let e = ProductTriangle::new(g, [a, b, a]).unwrap_err();
    assert!(e.contains("no area"), "{e}");
    // Over a geodesic: corners at p, q and q lifted.
    let vertical = ProductTriangle::new(g, [a, b, DVec4::new(b.x, b.y, 0.4, b.w)]).unwrap();
    let ProductTriangle::Vertical { origin, along, .. } = vertical else {
        panic!("vertical");
    };
    // Its arclength coordinate is the surface distance along the geodesic.
    let form = |x: DVec4, y: DVec4| x.x * y.x + x.y * y.y - x.w * y.w;
    let at = |s: f64| origin * s.cosh() + along * s.sinh();
    for s in [0.1, 0.7, 1.3] {
        let x = at(s);
        assert!((form(x, along).asinh() - s).abs() < 1e-13);
    }
}

#[test]
fn mesh_and_prism_mistakes_name_their_line() {
    for (text, says) in [
        (
            "[[object]]\ntype = \"mesh\"\nvertices = [[0, 0, 0], [0.3, 0, 0], [0, 0.3, 0.2]]\ntriangles = [[0, 1, 2]]\n",
            "curved",
        ),
        (
            "[[object]]\ntype = \"mesh\"\nvertices = [[0, 0, 0], [0.3, 0, 0], [0, 0.3, 0]]\ntriangles = [[0, 1, 3]]\n",
            "names vertex 3",
        ),
        (
            "[[object]]\ntype = \"mesh\"\nvertices = [[0, 0, 0]]\ntriangles = []\n",
            "no triangles",
        ),
        (
            "[[object]]\ntype = \"mesh\"\nvertices = [[0, 0, 0], [3, 0, 0], [0, 0.3, 0]]\ntriangles = [[0, 1, 2]]\n",
            "vertex 1",
        ),
        (
            "[[object]]\ntype = \"prism\"\ncorners = [[0, 0], [0.3, 0], [0.3, 0.3], [0.1, 0.05]]\nbottom = 0\ntop = 0.2\n",
            "convex",
        ),
        (
            "[[object]]\ntype = \"prism\"\ncorners = [[0, 0], [0.3, 0], [0, 0.3]]\nbottom = 0.2\ntop = 0.2\n",
            "below its top",
        ),
        (
            "[[object]]\ntype = \"prism\"\ncorners = [[0, 0], [0.3, 0]]\nbottom = 0\ntop = 0.2\n",
            "3 corners",
        ),
    ] {
        let text = format!("space = \"bitorus-circle\"\n{text}");
        let e = parse_product_scene(&text, "m.toml")
            .err()
            .unwrap_or_else(|| panic!("accepted {text}"));
        assert_eq!(e.line, Some(2), "{e}");
        assert!(e.message.contains(says), "{e} (wanted {says:?})");
    }
    // A prism is its walls (two triangles a side) and two fans.
    let ok = parse_product_scene(
        "space = \"bitorus-circle\"\nedges = false\n[[object]]\ntype = \"prism\"\ncorners = [[0, 0], [0.3, 0], [0.3, 0.3], [0, 0.3]]\nbottom = -0.2\ntop = 0.2\n",
        "p.toml",
    )
    .unwrap();
    assert_eq!(ok.scene.objects.len(), 4 * 2 + 2 * 2);
}

#[test]
fn a_hit_knows_its_crossings_last_face_and_the_copy_it_was_seen_in() {
    use bevy_curved_spaces::geometry::Ray;
    use bevy_curved_spaces::scene::{ColourBy, holonomy_bin};
    use bevy_curved_spaces::space::product::ProductWalker;
    use bevy_curved_spaces::trace::product::{ProductRayEnd, first_product_hit};
    let space = product("sphere-circle-turn");
    let g = space.base();
    let walker = ProductWalker::<DVec4>::new(&space);
    let scene = default_scene(&space);
    // Straight up the fibre from above the centre ball: through the top, in through the
    // bottom turned by the quarter turn, onto the ball from below.
    let ball = scene.objects.last().unwrap().radius;
    let ray = Ray {
        point: DVec4::new(0.0, 0.0, 1.5 * ball, 1.0),
        tangent: DVec4::Z,
    };
    let ProductRayEnd::Hit {
        crossings,
        last_face,
        held,
        ..
    } = first_product_hit(&walker, &scene, ray, 4)
    else {
        panic!("the ball is met");
    };
    assert_eq!((crossings, last_face), (1, Some(walker.top())));
    assert!((held - walker.up.0).abs_diff_eq(glam::DMat4::ZERO, 1e-15));
    // A quarter turn: the holonomy view's 90° bin (3 of 30°), not mirrored.
    assert_eq!(holonomy_bin(g, held), 3);
    assert_eq!(
        ColourBy::Holonomy.tint(g, crossings, last_face, held),
        bevy_curved_spaces::scene::palette(3)
    );
}

/// A ball with a `velocity` flies along the product geodesic and through the faces: at a
/// time it is where the exact flight (`space::motion::fly`, the plugin's steps) puts it,
/// inside the cell, drawn with its images where it reaches through a face; the plugin
/// flies it as an entity to the same place; a time that cannot be flown is refused.
#[test]
fn a_moving_ball_flies_through_the_faces_in_pictures_and_in_the_plugin() {
    use bevy_curved_spaces::space::Holonomy;
    use bevy_curved_spaces::space::motion::fly;
    let text = r#"
space = "bitorus-circle"
[[object]]
type = "ball"
position = [0.3, 0.1, 0.2]
radius = 0.1
colour = [1.0, 0.3, 0.2]
velocity = [0.9, 0.2, 0.4]
"#;
    let file = parse_product_scene(text, "moving.toml").expect("a product scene");
    assert_eq!(file.moving.len(), 1);
    let space = &file.space;
    let mover = file.moving[0];
    let still = file.scene.objects.len();
    // At the start: the ball where the file puts it.
    let at0 = file.scene_at(0.0).expect("time 0");
    let ProductShape::Point(p0) = at0.objects[still].shape else {
        panic!("a ball")
    };
    assert!((p0 - mover.frame.w_axis).abs().max_element() < 1e-15);
    // Later: where the flight puts it, in the cell, after crossing faces.
    for t in [0.7, 2.5, 6.0] {
        let mut h = Holonomy::default();
        let flown = fly(space, mover.frame, &mover.velocity, t, 1e-4, &mut h).expect("flies");
        let scene = file.scene_at(t).expect("a time");
        let ball = scene.objects[still..]
            .iter()
            .rev()
            .find_map(|o| match o.shape {
                ProductShape::Point(p) if space.outside_by(p) <= 1e-4 => Some(p),
                _ => None,
            })
            .expect("the ball in the cell");
        assert!(
            (ball - flown.w_axis).abs().max_element() < 1e-12,
            "at {t} s: {ball:?} against {:?}",
            flown.w_axis
        );
        if t >= 2.5 {
            assert!(h.crossings >= 1, "at {t} s it has crossed a face");
        }
    }
    // The plugin flies it as an entity to the same place.
    {
        use bevy::prelude::*;
        use bevy::time::TimeUpdateStrategy;
        use bevy_curved_spaces::plugin::objects::CurvedTransform;
        use bevy_curved_spaces::prelude::{BaseProductScene, CurvedSpacesPlugin};
        let mut app = App::new();
        app.add_plugins(MinimalPlugins)
            .insert_resource(TimeUpdateStrategy::ManualDuration(
                std::time::Duration::from_secs_f64(1.0 / 64.0),
            ))
            .insert_resource(BaseProductScene::from_file(&file))
            .add_plugins(CurvedSpacesPlugin {
                space: "bitorus-circle".into(),
                controls: false,
                ..default()
            });
        app.finish();
        for _ in 0..130 {
            app.update();
        }
        let frames: Vec<glam::DMat4> = app
            .world_mut()
            .query::<&CurvedTransform>()
            .iter(app.world())
            .map(|t| t.0)
            .collect();
        assert_eq!(frames.len(), 1, "one entity for the one moving ball");
        let elapsed = app.world().resource::<Time<Fixed>>().elapsed_secs_f64();
        let mut h = Holonomy::default();
        let flown = fly(space, mover.frame, &mover.velocity, elapsed, 1e-4, &mut h).unwrap();
        let gap = (frames[0].w_axis - flown.w_axis).abs().max_element();
        assert!(
            gap < 1e-9,
            "after {elapsed} s the entity is {gap:e} from the flight"
        );
    }
    // Times that cannot be flown.
    assert!(file.scene_at(-1.0).is_err());
    assert!(file.scene_at(f64::NAN).is_err());
    assert!(file.scene_at(1e12).is_err());
    // A moving ball must start in the cell, and its velocity must be finite.
    let outside = text.replace("[0.3, 0.1, 0.2]", "[9.0, 0.0, 0.0]");
    assert!(parse_product_scene(&outside, "m.toml").is_err());
}
