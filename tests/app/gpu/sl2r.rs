//! SL̃(2,R) on the GPU against the f64 CPU reference: the default scenes of the bitorus's
//! and the genus-3 surface's unit tangent bundles, from the default view, from one looking
//! up the fibre (its rays wind round their own fibre) and one looking down at a slant, in
//! the teaching views, lit with shadow rays and by the nearest path alone, the bitorus
//! bundle's double cover (a ball on one sheet, with walls, with shadows), and the example
//! scene file in stereo.

use super::{judge, *};
use bevy_curved_spaces::plugin::components::StereoSettings;
use bevy_curved_spaces::scene::ColourBy;
use bevy_curved_spaces::scene::lighting::{LightPaths, Lighting};
use bevy_curved_spaces::space::FrameSpace;
use bevy_curved_spaces::space::sl2r::UnitTangentSpace;
use bevy_curved_spaces::trace::sl2r::{
    Sl2rCamera, Sl2rScene, default_camera, default_scene, render_sl2r_view,
};
use bevy_curved_spaces::view::{StereoMode, ViewLayout};

const BUDGET: u32 = 24;

fn cpu(
    space: &UnitTangentSpace,
    scene: &Sl2rScene,
    camera: &Sl2rCamera,
    (w, h): (u32, u32),
    stereo: StereoSettings,
) -> RgbImage {
    let eyes = if stereo.mode.is_stereo() {
        space.eye_frames(camera.frame, stereo.ipd_for(space.scale()))
    } else {
        [camera.frame; 2]
    };
    let layout = ViewLayout::new(
        stereo.mode,
        stereo.swap_eyes,
        eyes,
        camera.fov_y_degrees,
        w,
        h,
    );
    render_sl2r_view(space, scene, &layout, BUDGET as usize)
}

/// The camera turned by `pitch` radians about its right axis (up the fibre for π/2).
fn pitched(camera: Sl2rCamera, pitch: f64) -> Sl2rCamera {
    let mut frame = camera.frame;
    let (c, s) = (pitch.cos(), pitch.sin());
    let (up, back) = (frame.y_axis.truncate(), frame.z_axis.truncate());
    let new_up = up * c + back * s;
    let new_back = back * c - up * s;
    frame.y_axis = new_up.extend(frame.y_axis.w);
    frame.z_axis = new_back.extend(frame.z_axis.w);
    Sl2rCamera { frame, ..camera }
}

/// The lighting with shadow rays walked to the four images of the lamp nearest the cell.
fn shadowed() -> Lighting {
    Lighting {
        shadows: 4,
        ..Lighting::default()
    }
}

/// The lighting along the shortest geodesic to the lamp itself only.
fn nearest() -> Lighting {
    Lighting {
        paths: LightPaths::Nearest,
        ..Lighting::default()
    }
}

/// `scene` lit as `lighting` says, its lamp where it is.
fn lit(space: &UnitTangentSpace, scene: &Sl2rScene, lighting: Lighting) -> Sl2rScene {
    let mut lit = scene.clone();
    lit.set_lighting(space, (scene.light, scene.light_sheet), lighting)
        .expect("the lighting is in range");
    lit
}

#[test]
fn sl2r_spaces_render_on_the_gpu_like_the_cpu_reference() {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let size = (64, 36);
    let mut failures = Vec::new();
    for word in ["abABcdCD", "abABcdCDefEF"] {
        let space = UnitTangentSpace::new(word).unwrap();
        let scene = default_scene(&space);
        let camera = default_camera(&space);
        // Close to the stack of balls, looking at it by the inverse exponential map.
        let rho = space.inradius();
        let angle = 2.0 * std::f64::consts::PI * 2.0 / space.sides().len() as f64;
        let stack = (0.5 * rho).sinh();
        let near = Sl2rCamera::looking_at(
            &space,
            glam::DVec3::new(-0.2, 0.0, 0.0),
            glam::DVec3::new(stack * angle.cos(), stack * angle.sin(), 0.4),
            60.0,
        )
        .expect("a view of the stack");
        for (view, camera) in [
            ("default", camera),
            ("up", pitched(camera, 1.2)),
            ("down", pitched(camera, -0.6)),
            ("balls", near),
        ] {
            let reference = cpu(&space, &scene, &camera, size, StereoSettings::default());
            let gpu = renderer
                .render_sl2r(
                    &space,
                    &scene,
                    &camera,
                    size,
                    BUDGET,
                    StereoSettings::default(),
                )
                .unwrap_or_else(|e| panic!("{word}: {e}"));
            judge(
                &format!("sl2r-{word}-{view}"),
                &gpu,
                &reference,
                &out,
                &mut failures,
            );
        }
        for (name, tinted) in [
            (
                ColourBy::Crossings.name(),
                Sl2rScene {
                    colour_by: ColourBy::Crossings,
                    ..scene.clone()
                },
            ),
            (
                ColourBy::Face.name(),
                Sl2rScene {
                    colour_by: ColourBy::Face,
                    ..scene.clone()
                },
            ),
            ("shadows", lit(&space, &scene, shadowed())),
            ("nearest", lit(&space, &scene, nearest())),
        ] {
            let reference = cpu(&space, &tinted, &camera, size, StereoSettings::default());
            let gpu = renderer
                .render_sl2r(
                    &space,
                    &tinted,
                    &camera,
                    size,
                    BUDGET,
                    StereoSettings::default(),
                )
                .unwrap_or_else(|e| panic!("{word}: {e}"));
            judge(
                &format!("sl2r-{word}-{name}"),
                &gpu,
                &reference,
                &out,
                &mut failures,
            );
        }
    }
    // The bitorus bundle's double cover: the default view in the crossings view, and from the
    // stack's fibre half a turn from it, up (the second sheet: no ball where UT Σ shows the
    // violet one) and down (the white one).
    let space = UnitTangentSpace::cover("abABcdCD", 2).unwrap();
    let scene = default_scene(&space);
    let stack = glam::DVec3::new(0.0, (0.5 * space.inradius()).sinh(), std::f64::consts::PI);
    let along = |turn: f64| {
        Sl2rCamera::looking_at(&space, stack, stack + glam::DVec3::Z * turn, 60.0)
            .expect("a view along the fibre")
    };
    let crossings = Sl2rScene {
        colour_by: ColourBy::Crossings,
        ..scene.clone()
    };
    let walled = Sl2rScene {
        walls: Some(bevy_curved_spaces::scene::walls::WallStyle {
            opening: 0.5,
            opacity: 0.45,
        }),
        ..scene.clone()
    };
    let shadows = lit(&space, &scene, shadowed());
    let nearest_lamp = lit(&space, &scene, nearest());
    for (view, scene, camera) in [
        ("crossings", &crossings, default_camera(&space)),
        ("shadows", &shadows, default_camera(&space)),
        ("nearest", &nearest_lamp, along(1.0)),
        ("walls", &walled, default_camera(&space)),
        ("stack-up", &scene, along(1.0)),
        ("stack-down", &scene, along(-1.0)),
    ] {
        let reference = cpu(&space, scene, &camera, size, StereoSettings::default());
        let gpu = renderer
            .render_sl2r(
                &space,
                scene,
                &camera,
                size,
                BUDGET,
                StereoSettings::default(),
            )
            .unwrap_or_else(|e| panic!("the cover: {e}"));
        judge(
            &format!("sl2r-cover-2-{view}"),
            &gpu,
            &reference,
            &out,
            &mut failures,
        );
    }
    // The example scene file, side by side in stereo.
    let file = bevy_curved_spaces::trace::sl2r::file::load_sl2r_scene_file(
        &PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/unit_tangent_ring.toml"),
    )
    .expect("the example")
    .expect("an SL̃(2,R) scene");
    let stereo = StereoSettings {
        mode: StereoMode::SideBySide,
        ..StereoSettings::default()
    };
    let reference = cpu(&file.space, &file.scene, &file.start, (96, 27), stereo);
    let gpu = renderer
        .render_sl2r(
            &file.space,
            &file.scene,
            &file.start,
            (96, 27),
            BUDGET,
            stereo,
        )
        .unwrap_or_else(|e| panic!("the ring: {e}"));
    judge("sl2r-ring-stereo", &gpu, &reference, &out, &mut failures);
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The SL2R variant validates for three surfaces' default scenes, in the teaching views,
/// with balls and no tube and with no object at all, and in fibre covers, and the packer
/// writes exactly the layout naga computes.
#[test]
fn sl2r_variants_validate_and_match_the_packed_layout() {
    use bevy_curved_spaces::plugin::render::gpu::{GpuScene, VIEW_WORDS};
    for (word, sheets) in [
        ("abABcdCD", 1),
        ("abcdABCD", 1),
        ("abABcdCDefEF", 1),
        ("abABcdCD", 2),
        ("abABcdCDefEF", 4),
    ] {
        let space = UnitTangentSpace::cover(word, sheets).unwrap();
        let mut scene = default_scene(&space);
        for colour_by in [ColourBy::Shading, ColourBy::Crossings, ColourBy::Face] {
            scene.colour_by = colour_by;
            let gpu = GpuScene::sl2r(&space, &scene, BUDGET).expect("packs");
            assert!(gpu.key.sl2r && gpu.key.faces as usize == space.sides().len());
            assert_eq!(gpu.key.sl2r_cover, sheets > 1);
            let bytes = crate::shaders::validate(&gpu.key);
            assert_eq!(bytes, gpu.key.uniform_bytes(), "{word}");
            assert_eq!((gpu.words.len() + VIEW_WORDS) * 4, bytes, "{word}");
        }
        scene.tubes.clear();
        for balls in [true, false] {
            if !balls {
                scene.balls.clear();
            }
            let gpu = GpuScene::sl2r(&space, &scene, 8).expect("packs");
            assert_eq!(gpu.key.sl2r_balls > 0, balls);
            assert_eq!(
                crate::shaders::validate(&gpu.key),
                (gpu.words.len() + VIEW_WORDS) * 4
            );
        }
        assert!(GpuScene::sl2r(&space, &scene, 0).is_err());
    }
}
