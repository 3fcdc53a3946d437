//! Nil on the GPU against the f64 CPU reference: the default scenes of nil-1, nil-3 and
//! nil-50 (a box 1/50 high, crossed often), nil-1's with every lamp image shadowed and
//! with the nearest copy only, from the default view and from one aimed straight up the fibre,
//! with walls and in the teaching views.

use super::{judge, *};
use bevy_curved_spaces::plugin::components::StereoSettings;
use bevy_curved_spaces::scene::lighting::Lighting;
use bevy_curved_spaces::space::nil::NilSpace;
use bevy_curved_spaces::trace::nil::{
    NilCamera, NilScene, default_camera, default_scene, render_nil_view,
};
use bevy_curved_spaces::view::{StereoMode, ViewLayout};

fn cpu(
    space: &NilSpace,
    scene: &NilScene,
    camera: &NilCamera,
    (w, h): (u32, u32),
    budget: u32,
) -> RgbImage {
    let layout = ViewLayout::new(
        StereoMode::Mono,
        false,
        [camera.frame; 2],
        camera.fov_y_degrees,
        w,
        h,
    );
    render_nil_view(space, scene, &layout, budget as usize)
}

#[test]
fn nil_spaces_render_on_the_gpu_like_the_cpu_reference() {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let size = (64, 36);
    let mut failures = Vec::new();
    for k in [1, 3, 50] {
        let space = NilSpace::new(k);
        let scene = default_scene(&space);
        let camera = default_camera(&space);
        let budget = bevy_curved_spaces::plugin::nil::default_nil_budget(&space);
        let mut views = vec![("default", camera)];
        // Up the fibre: the rays wind round it.
        let mut up = camera;
        up.frame = glam::DMat4::from_cols(
            glam::DVec4::X,
            glam::DVec4::Y,
            glam::DVec4::new(0.0, 0.0, -1.0, 0.0),
            camera.frame.w_axis,
        );
        views.push(("up", up));
        for (view, camera) in views {
            let reference = cpu(&space, &scene, &camera, size, budget);
            let gpu = renderer
                .render_nil(
                    &space,
                    &scene,
                    &camera,
                    size,
                    budget,
                    StereoSettings::default(),
                )
                .unwrap_or_else(|e| panic!("nil-{k}: {e}"));
            judge(
                &format!("nil-{k}-{view}"),
                &gpu,
                &reference,
                &out,
                &mut failures,
            );
        }
        if k == 1 {
            // A brighter lamp without the tail, so its shadows show.
            let mut bright = scene.clone();
            bright.power = 0.35 * 0.35;
            let unlit = Lighting {
                tail: false,
                ..Default::default()
            };
            bright
                .set_lighting(&space, scene.light, unlit)
                .expect("lighting");
            let plain = cpu(&space, &bright, &camera, size, budget);
            for (name, lighting) in [
                (
                    "shadows",
                    Lighting {
                        shadows: 8,
                        ..unlit
                    },
                ),
                ("nearest", Lighting::NEAREST),
            ] {
                let mut lit = bright.clone();
                lit.set_lighting(&space, scene.light, lighting)
                    .expect("lighting");
                let reference = cpu(&space, &lit, &camera, size, budget);
                let changed = reference
                    .pixels()
                    .zip(plain.pixels())
                    .filter(|(p, q)| p != q)
                    .count();
                assert!(changed > 20, "{name} changes {changed} pixels");
                let gpu = renderer
                    .render_nil(
                        &space,
                        &lit,
                        &camera,
                        size,
                        budget,
                        StereoSettings::default(),
                    )
                    .unwrap_or_else(|e| panic!("nil-{k} with {name}: {e}"));
                judge(
                    &format!("nil-{k}-{name}"),
                    &gpu,
                    &reference,
                    &out,
                    &mut failures,
                );
            }
        }
        // The teaching views (the surfaces tinted by the crossings and by the last face) and
        // walls with windows (the sides' shear makes the panels a pair's own).
        let plain = cpu(&space, &scene, &camera, size, budget);
        let mut variants = Vec::new();
        for colour_by in [
            bevy_curved_spaces::scene::ColourBy::Crossings,
            bevy_curved_spaces::scene::ColourBy::Face,
        ] {
            let mut tinted = scene.clone();
            tinted.colour_by = colour_by;
            variants.push((colour_by.name(), tinted));
        }
        let mut walled = scene.clone();
        walled.walls = Some(bevy_curved_spaces::scene::WallStyle::new(0.55).expect("an opening"));
        variants.push(("walls", walled));
        for (name, variant) in variants {
            let reference = cpu(&space, &variant, &camera, size, budget);
            let changed = reference
                .pixels()
                .zip(plain.pixels())
                .filter(|(p, q)| p != q)
                .count();
            assert!(changed > 100, "nil-{k}: {name} changes {changed} pixels");
            let gpu = renderer
                .render_nil(
                    &space,
                    &variant,
                    &camera,
                    size,
                    budget,
                    StereoSettings::default(),
                )
                .unwrap_or_else(|e| panic!("nil-{k} with {name}: {e}"));
            judge(
                &format!("nil-{k}-{name}"),
                &gpu,
                &reference,
                &out,
                &mut failures,
            );
        }
    }
    assert!(
        failures.is_empty(),
        "GPU and CPU disagree (images in {}):\n{}",
        out.display(),
        failures.join("\n")
    );
}
