//! Every space of each geometry family on the GPU against the CPU reference: the seed
//! spaces, the library, the product spaces, a reduced resolution, grazing rays.

use super::*;

#[test]
fn every_seed_space_renders_on_the_gpu_like_the_cpu_reference() {
    let spaces: Vec<(String, Space)> = SEED_SPACES
        .iter()
        .map(|seed| {
            (
                seed.id.to_string(),
                seed.build().expect("seed space builds"),
            )
        })
        .collect();
    spaces_render_alike(&spaces);
}

/// Spaces from groups (spherical, flat non-orientable, hyperbolic census) render alike.
#[test]
fn library_spaces_render_on_the_gpu_like_the_cpu_reference() {
    let spaces: Vec<(String, Space)> = [
        "three-sphere",
        "projective-space",
        "lens-7-1",
        "lens-7-2",
        "prism-5",
        "binary-octahedral",
        "second-amphidicosm",
        "weeks",
    ]
    .iter()
    .map(|id| {
        let space = bevy_curved_spaces::space::resolve_space(
            id,
            std::path::Path::new(""),
            &Default::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        (id.to_string(), space)
    })
    .collect();
    spaces_render_alike(&spaces);
}

#[test]
fn a_reduced_resolution_is_traced_and_scaled_up() {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let space = SEED_SPACES[0].build().expect("seed space builds");
    let camera = TraceCamera::default_for(&space);
    let mut request = OffscreenRender::new(
        ActiveSpace::new("torus", space.clone()),
        camera,
        (WIDTH, HEIGHT),
        24,
    );
    let full = renderer.render(&request).expect("full resolution");
    request.resolution_scale = 0.25;
    let reduced = renderer.render(&request).expect("quarter resolution");
    let (c, _) = compare(&reduced, &full, TOLERANCE);
    println!(
        "quarter resolution vs full: {:.1} % of pixels differ, mean error {:.2}/255",
        100.0 * c.differing,
        c.mean_error
    );
    // Scaled up from 40×23, the picture is the same scene (a small mean error; another view
    // of the scene errs by tens of levels) but blurred at every edge: visibly not the
    // full-resolution trace.
    assert!(
        c.mean_error < 15.0,
        "the reduced picture shows another scene"
    );
    assert!(c.differing > 0.02, "the resolution scale had no effect");
}

/// The product spaces (H²×R, S²×R) on the GPU's `PRODUCT` variant against the f64 CPU
/// reference, default scene and view, 96×54 (the CPU reference's bracketed search is
/// slower than the constant-curvature tracer's closed forms).
/// The hard case of the product spaces' object search: rays that graze a ball, a fibre's
/// tube and a horizontal geodesic's tube, seen at their limbs through a narrow field of view
/// so that most pixels of the picture are nearly tangent. The GPU's searches (Newton's steps
/// in H²×R, a golden section and a bisection on S²) must find the same silhouettes as the
/// f64 reference: only the pixels the limb passes through may differ.
#[test]
fn grazing_rays_meet_product_objects_on_the_gpu_where_the_cpu_reference_does() {
    use bevy_curved_spaces::trace::product::{
        ProductCamera, ProductObject, ProductShape, default_scene, render_product,
    };
    use glam::{DVec3, DVec4};
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let (w, h) = (96, 54);
    // Two crossings: the object in the cell and its nearest copies, the rest fog (far copies
    // a pixel wide differ between f32 and f64 by aliasing, not by the search).
    const BUDGET: usize = 2;
    let mut failures = Vec::new();
    for id in ["bitorus-circle", "sphere-circle-turn"] {
        let space = crate::common::product(id);
        let g = space.base();
        // A point at surface distance d from the centre in direction θ, at height z.
        let at = |d: f64, theta: f64, z: f64| {
            let (c, s) = g.cs(d);
            DVec4::new(s * theta.cos(), s * theta.sin(), z, c)
        };
        let size = (0.25 * space.length()).min(0.3);
        let eye = at(1.1, 0.0, 0.1 * size);
        let views = [
            (
                "ball",
                ProductShape::Point(DVec4::W),
                size,
                at(size, 0.5 * std::f64::consts::PI, 0.05 * size),
            ),
            (
                "fibre",
                ProductShape::Fibre(DVec4::W),
                0.7 * size,
                at(0.7 * size, 0.5 * std::f64::consts::PI, 0.3 * size),
            ),
            (
                "geodesic",
                ProductShape::Geodesic {
                    covector: DVec4::X,
                    height: -0.5 * size,
                },
                0.5 * size,
                at(0.2, 0.5 * std::f64::consts::PI, 0.0),
            ),
        ];
        for (name, shape, radius, target) in views {
            let mut scene = default_scene(&space);
            scene.objects = vec![ProductObject {
                shape,
                radius,
                colour: DVec3::new(0.9, 0.6, 0.3),
            }];
            let camera = ProductCamera::looking_at(g, eye, target, 4.0);
            let cpu = render_product(&space, &scene, &camera, w, h, BUDGET);
            let gpu = renderer
                .render_product(&space, &scene, &camera, (w, h), BUDGET as u32)
                .unwrap_or_else(|e| panic!("{id} {name}: {e}"));
            // What the view shows without the object: the pixels alike are its misses.
            let mut empty = scene.clone();
            empty.objects.clear();
            let background = render_product(&space, &empty, &camera, w, h, BUDGET);
            let (hit, missed) =
                cpu.pixels()
                    .zip(background.pixels())
                    .fold((0, 0), |(a, b), (p, q)| {
                        if p.0.iter().zip(q.0).all(|(x, y)| x.abs_diff(y) <= 2) {
                            (a, b + 1)
                        } else {
                            (a + 1, b)
                        }
                    });
            // The limb crosses the picture: both sides of it are in view.
            assert!(
                hit > 200 && missed > 200,
                "{id} {name}: the view shows {hit} pixels of the object and {missed} of fog"
            );
            let (c, diff) = compare(&gpu, &cpu, TOLERANCE);
            println!(
                "{id:<20} {name:<8} object {hit} px, fog {missed} px, differing {} px",
                c.differing_pixels
            );
            // At most an eighth of the pixels along the limb: a search that misses grazing
            // rays, or stops short of the root, moves the whole silhouette.
            if c.differing_pixels > w.max(h) as usize / 8 {
                std::fs::create_dir_all(&out).expect("create output folder");
                for (kind, img) in [("gpu", &gpu), ("cpu", &cpu), ("diff", &diff)] {
                    img.save(out.join(format!("{id}-grazing-{name}-{kind}.png")))
                        .expect("write image");
                }
                failures.push(format!(
                    "{id} {name}: {} pixels differ by more than {TOLERANCE}/255",
                    c.differing_pixels
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "GPU and CPU disagree at the limbs (images in {}):\n{}",
        out.display(),
        failures.join("\n")
    );
}

#[test]
fn product_spaces_render_on_the_gpu_like_the_cpu_reference() {
    use bevy_curved_spaces::trace::product::{
        ProductObject, ProductShape, default_camera, default_scene, render_product,
    };
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let (w, h) = (96, 54);
    let mut failures = Vec::new();
    for id in [
        "bitorus-circle",
        "projective-plane-circle",
        "sphere-circle-turn",
        "crosscaps-circle",
    ] {
        let space = crate::common::product(id);
        let scene = default_scene(&space);
        let camera = default_camera(&space);
        let plain = render_product(&space, &scene, &camera, w, h, 24);
        let gpu = renderer
            .render_product(&space, &scene, &camera, (w, h), 24)
            .unwrap_or_else(|e| panic!("{id}: {e}"));
        judge(id, &gpu, &plain, &out, &mut failures);
        // Horizontal discs: a floor below the view and a smaller one above, met where the
        // ray's height reaches their slice (and through the faces, in the next cells).
        let mut floors = scene.clone();
        let r = space.base_inradius().min(1.2);
        for (height, radius, colour) in [
            (-0.3, 0.8 * r, [0.3, 0.8, 0.4]),
            (0.45, 0.4 * r, [0.9, 0.3, 0.3]),
        ] {
            floors.objects.push(ProductObject {
                shape: ProductShape::Disc(glam::DVec4::new(0.0, 0.0, height * space.length(), 1.0)),
                radius,
                colour: glam::DVec3::from_array(colour),
            });
        }
        let cpu = render_product(&space, &floors, &camera, w, h, 24);
        let gpu = renderer
            .render_product(&space, &floors, &camera, (w, h), 24)
            .unwrap_or_else(|e| panic!("{id} with discs: {e}"));
        let shown = cpu
            .pixels()
            .zip(plain.pixels())
            .filter(|(p, q)| p != q)
            .count();
        assert!(shown > 20, "{id}: the discs change {shown} pixels");
        judge(&format!("{id}-discs"), &gpu, &cpu, &out, &mut failures);
        // Every image shadowed by the discs and the ball, walked through the faces; and the
        // older model, the lamp in the cell only.
        for (name, lighting) in [
            (
                "shadows",
                bevy_curved_spaces::scene::lighting::Lighting {
                    shadows: 8,
                    ..Default::default()
                },
            ),
            (
                "nearest",
                bevy_curved_spaces::scene::lighting::Lighting::NEAREST,
            ),
        ] {
            let mut lit = floors.clone();
            lit.set_lighting(&space, floors.light, lighting)
                .unwrap_or_else(|e| panic!("{e}"));
            let cpu_lit = render_product(&space, &lit, &camera, w, h, 24);
            let gpu = renderer
                .render_product(&space, &lit, &camera, (w, h), 24)
                .unwrap_or_else(|e| panic!("{id} with {name}: {e}"));
            let changed = cpu_lit
                .pixels()
                .zip(cpu.pixels())
                .filter(|(p, q)| p != q)
                .count();
            assert!(changed > 20, "{id}: {name} changes {changed} pixels");
            judge(&format!("{id}-{name}"), &gpu, &cpu_lit, &out, &mut failures);
        }
        // Walls with windows half open: panels met where the ray crosses a face.
        let mut walled = scene.clone();
        walled.walls = Some(bevy_curved_spaces::scene::WallStyle::new(0.5).expect("style"));
        let cpu = render_product(&space, &walled, &camera, w, h, 24);
        let gpu = renderer
            .render_product(&space, &walled, &camera, (w, h), 24)
            .unwrap_or_else(|e| panic!("{id} with walls: {e}"));
        let shown = cpu
            .pixels()
            .zip(plain.pixels())
            .filter(|(p, q)| p != q)
            .count();
        assert!(shown > 200, "{id}: the walls change {shown} pixels");
        judge(&format!("{id}-walls"), &gpu, &cpu, &out, &mut failures);
    }
    // The renderer goes back to constant curvature afterwards.
    let space = bevy_curved_spaces::space::seed_space("torus").expect("seed");
    let back = renderer.render(&OffscreenRender::new(
        ActiveSpace::new("torus", space.clone()),
        TraceCamera::default_for(&space),
        (32, 18),
        8,
    ));
    assert!(back.is_ok(), "after a product render: {back:?}");
    assert!(
        failures.is_empty(),
        "GPU and CPU disagree (images in {}):\n{}",
        out.display(),
        failures.join("\n")
    );
}

/// A space of several cells draws the picture of the same space in one cell on the GPU too:
/// the torus's shadowed scene in `torus-two-cells` (the cube cut into two half-cubes) and
/// in `torus`, from the same view, to the GPU's rounding; the walk looks for each exit among
/// the faces of the cell it is in, and crosses the seam without a trace.
#[test]
fn the_torus_of_two_cells_draws_the_torus_picture_on_the_gpu() {
    use bevy_curved_spaces::plugin::components::BaseScene;
    use bevy_curved_spaces::scene::file::parse_scene;
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let text = std::fs::read_to_string(dir.join("torus_shadows.toml")).expect("the scene");
    let mut picture = |id: &str| {
        let file = parse_scene(
            &text.replace("space = \"torus\"", &format!("space = \"{id}\"")),
            &dir,
            "torus_shadows.toml",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let frame = file.start.expect("a start view");
        renderer
            .render(&OffscreenRender {
                fog_distance: Some(file.base.shading.fog_distance),
                parts: SceneParts {
                    edges: false,
                    centrepiece: Centrepiece::None,
                    avatar: false,
                    clifford: false,
                },
                base: BaseScene {
                    space_id: id.to_string(),
                    scene: Some(std::sync::Arc::new(file.scene())),
                    start: None,
                    parts: None,
                    fov: None,
                    moving: Vec::new(),
                },
                ..OffscreenRender::new(
                    ActiveSpace::new(id, file.space.clone()),
                    TraceCamera {
                        frame,
                        fov_y_degrees: 70.0,
                    },
                    (WIDTH, HEIGHT),
                    64,
                )
            })
            .unwrap_or_else(|e| panic!("{id}: {e}"))
    };
    let (one, two) = (picture("torus"), picture("torus-two-cells"));
    let (c, diff) = compare(&two, &one, 2);
    println!(
        "torus-two-cells against torus on the GPU: differing {:.3} %, max {}",
        100.0 * c.differing,
        c.max_error
    );
    if c.differing > 0.0005 {
        let out = crate::common::scratch_dir("two-cells");
        let _ = diff.save(out.join("diff.png"));
        let _ = two.save(out.join("torus-two-cells.png"));
        let _ = one.save(out.join("torus.png"));
        panic!(
            "{:.3} % of pixels differ by more than 2/255 (pictures in {})",
            100.0 * c.differing,
            out.display()
        );
    }
}
