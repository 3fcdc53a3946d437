//! The headset mode against a real OpenXR runtime: `scripts/test-headset.sh` starts Monado's
//! service (null compositor, simulated headset and controllers) and runs this binary with
//! `--features xr`. Without a runtime it fails: the OpenXR backend would otherwise carry on
//! without a headset and test nothing.
//!
//! An OpenXR instance holds one session per process, so one test walks through the phases in
//! order: the session reaches `Running`; the frame-rate target follows the display; both eyes
//! are traced into the runtime's swapchain and read back (compared at the end with the CPU
//! reference from the same eye frames and frusta, and with each other for parallax); the
//! simulated head's own motion carries the head through a face with the pairing's holonomy;
//! the thumbsticks walk and snap-turn; the frame time is measured; last, in a product space
//! (H²×R) the thumbstick walks the head along the product's geodesics and both eyes are
//! compared with the product's CPU reference.

#[allow(dead_code)]
#[path = "../common/mod.rs"]
mod common;

use bevy::camera::ManualTextureViewHandle;
use bevy::prelude::*;
use bevy::render::pipelined_rendering::PipelinedRenderingPlugin;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use bevy_curved_spaces::geometry::Geometry;
use bevy_curved_spaces::plugin::CurvedSpacesPlugin;
use bevy_curved_spaces::plugin::components::{
    ActiveSpace, CurvedSpaceEye, CurvedSpacesSystems, PlayerFrame, Quality, TracerSettings,
};
use bevy_curved_spaces::plugin::frame_rate::FrameRateTarget;
use bevy_curved_spaces::plugin::xr::{
    CurvedSpacesXrPlugin, PlayArea, TurnStyle, XrComfort, XrDisplayPeriod, XrHead, XrSticks,
    xr_plugins,
};
use bevy_curved_spaces::scene::{CurvedScene, SceneParts, Shading};
use bevy_curved_spaces::space::AnySpace;
use bevy_curved_spaces::trace::{RenderSettings, render_view};
use bevy_curved_spaces::view::headset::{RoomPose, local_motion};
use bevy_curved_spaces::view::{Lens, ViewLayout};
use bevy_mod_openxr::render::XR_TEXTURE_INDEX;
use bevy_mod_openxr::resources::{OxrCurrentSessionConfig, OxrFrameState, OxrViews};
use bevy_mod_xr::camera::XrCamera;
use bevy_mod_xr::session::XrState;
use common::compare;
use glam::{DMat4, DQuat, DVec3};
use image::RgbImage;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// The crossing budget of both tracers.
const CROSSINGS: u32 = 24;
/// A pixel differs from the CPU reference when a channel is off by more than this.
const TOLERANCE: u8 = 10;
/// At most this fraction of an eye's pixels may differ from the CPU reference.
const MAX_DIFFERING: f64 = 0.01;
/// Updates allowed for the session to reach `Running` (the null compositor paces at 20 Hz).
const MAX_UPDATES_TO_RUN: usize = 200;

/// The resolution scale while the head walks and its pictures are not read back.
const WALK_SCALE: f32 = 0.25;

/// The sticks the test pushes, written over what the runtime reported.
#[derive(Resource, Default)]
struct PushedSticks(Option<XrSticks>);

/// Whether the runtime reported the sticks bound to a controller, seen before the override.
#[derive(Resource, Default)]
struct RuntimeBound(bool);

fn push_sticks(
    pushed: Res<PushedSticks>,
    mut sticks: ResMut<XrSticks>,
    mut bound: ResMut<RuntimeBound>,
) {
    bound.0 |= sticks.bound;
    if let Some(p) = pushed.0 {
        *sticks = p;
    }
}

fn tracer_settings() -> TracerSettings {
    TracerSettings {
        fog_distance: None,
        max_crossings: Some(CROSSINGS),
        quality: Quality::High,
        resolution_scale: 1.0,
        parts: SceneParts {
            avatar: false,
            ..SceneParts::default()
        },
        time: Some(0.0),
        colour_by: Default::default(),
        walls: None,
        lighting: None,
    }
}

/// The product phase's settings: a shorter fog, so that the far cover's thin tubes (dense in
/// H²×R, where f32 and f64 round their silhouettes apart) fade before they count against
/// the CPU comparison; the frames and frusta are what the phase checks.
fn product_settings() -> TracerSettings {
    TracerSettings {
        fog_distance: Some(1.5),
        ..tracer_settings()
    }
}

fn headset_app(space: &str) -> App {
    let mut app = App::new();
    app.add_plugins(
        xr_plugins(
            DefaultPlugins
                .build()
                .disable::<WinitPlugin>()
                .disable::<PipelinedRenderingPlugin>(),
            PlayArea::Standing,
        )
        .set(WindowPlugin {
            primary_window: None,
            exit_condition: ExitCondition::DontExit,
            close_when_requested: false,
            ..default()
        }),
    );
    // The OpenXR backend falls back to a plain renderer when it finds no runtime: say so.
    let state = app.world().get_resource::<XrState>().copied();
    assert!(
        matches!(state, Some(s) if s != XrState::Unavailable),
        "no OpenXR runtime was found (XrState {state:?}): run the headset tests through \
         scripts/test-headset.sh, which starts Monado"
    );
    app.insert_resource(ActiveSpace::seed(space).expect("a seed space"))
        .add_plugins(CurvedSpacesPlugin {
            controls: false,
            ui: false,
            ..default()
        })
        .add_plugins(CurvedSpacesXrPlugin {
            mirror: false,
            ..default()
        })
        .insert_resource(tracer_settings())
        .init_resource::<PushedSticks>()
        .init_resource::<RuntimeBound>()
        .add_systems(Update, push_sticks.before(CurvedSpacesSystems::Move));
    app.finish();
    app.cleanup();
    app
}

/// The head between the two views the runtime gave this frame.
fn head_pose(app: &App) -> Option<RoomPose> {
    let views = app.world().get_resource::<OxrViews>()?;
    let [l, r] = views.as_slice() else {
        return None;
    };
    let pose = |p: &openxr::Posef| {
        RoomPose::new(
            DVec3::new(
                f64::from(p.position.x),
                f64::from(p.position.y),
                f64::from(p.position.z),
            ),
            DQuat::from_xyzw(
                f64::from(p.orientation.x),
                f64::from(p.orientation.y),
                f64::from(p.orientation.z),
                f64::from(p.orientation.w),
            ),
        )
    };
    Some(RoomPose::between(&pose(&l.pose), &pose(&r.pose)))
}

/// The frame period the runtime predicts now, in milliseconds.
fn predicted_period_ms(app: &App) -> f64 {
    app.world()
        .resource::<OxrFrameState>()
        .predicted_display_period
        .as_nanos() as f64
        / 1e6
}

fn head(app: &App) -> &bevy_curved_spaces::view::headset::HeadTracker {
    &app.world().resource::<XrHead>().0
}

/// The head's frame in the universal cover (its frame with the holonomy undone).
fn head_in_cover(app: &App) -> DMat4 {
    let space = &app.world().resource::<ActiveSpace>().constant().unwrap();
    let h = head(app);
    space.geometry().inverse(h.holonomy.matrix) * h.frame
}

fn max_entry(m: DMat4) -> f64 {
    m.to_cols_array()
        .iter()
        .fold(0.0_f64, |a, x| a.max(x.abs()))
}

fn out_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("headset");
    std::fs::create_dir_all(&dir).expect("create the output folder");
    dir
}

/// The horizontal shift (pixels) that best lays `right` over `left`: `left(x) ≈ right(x − s)`.
fn best_shift(left: &RgbImage, right: &RgbImage, max: i64) -> (i64, f64) {
    let (w, h) = left.dimensions();
    let luma = |p: &image::Rgb<u8>| p.0.iter().map(|&c| f64::from(c)).sum::<f64>();
    (-max..=max)
        .map(|s| {
            let mut sum = 0.0;
            let mut n = 0.0;
            for y in 0..h {
                for x in 0..w {
                    let xr = x as i64 - s;
                    if xr < 0 || xr >= i64::from(w) {
                        continue;
                    }
                    sum += (luma(left.get_pixel(x, y)) - luma(right.get_pixel(xr as u32, y))).abs();
                    n += 1.0;
                }
            }
            (s, sum / n)
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("shifts")
}

struct EyeShot {
    index: u32,
    frame: DMat4,
    lens: Lens,
    image: Arc<Mutex<Option<Image>>>,
}

/// Both eyes' pictures as the runtime's swapchain received them, with the frames and frusta
/// they were traced from.
fn read_back_eyes(app: &mut App) -> Vec<(EyeShot, RgbImage)> {
    let shots: Vec<Arc<Mutex<Option<Image>>>> = (0..2).map(|_| Arc::default()).collect();
    for (index, slot) in shots.iter().enumerate() {
        let slot = slot.clone();
        app.world_mut()
            .spawn(Screenshot::texture_view(ManualTextureViewHandle(
                XR_TEXTURE_INDEX + index as u32,
            )))
            .observe(move |captured: On<ScreenshotCaptured>| {
                *slot.lock().expect("slot") = Some(captured.image.clone());
            });
    }
    app.update();
    // The frames this update drew with (extracted at its end).
    let mut eyes: Vec<EyeShot> = app
        .world_mut()
        .query::<(&XrCamera, &PlayerFrame, &CurvedSpaceEye)>()
        .iter(app.world())
        .map(|(camera, frame, eye)| EyeShot {
            index: camera.0,
            frame: frame.0,
            lens: eye.lens,
            image: shots[camera.0 as usize].clone(),
        })
        .collect();
    eyes.sort_by_key(|e| e.index);
    assert_eq!(eyes.len(), 2, "two eye cameras");
    for _ in 0..40 {
        if eyes.iter().all(|e| e.image.lock().expect("slot").is_some()) {
            break;
        }
        app.update();
    }
    eyes.into_iter()
        .map(|eye| {
            let image = eye
                .image
                .lock()
                .expect("slot")
                .take()
                .unwrap_or_else(|| panic!("eye {} was not captured in 40 frames", eye.index));
            let format = image.texture_descriptor.format;
            let rgb = image
                .try_into_dynamic()
                .unwrap_or_else(|e| panic!("eye {}: swapchain format {format:?}: {e}", eye.index))
                .to_rgb8();
            (eye, rgb)
        })
        .collect()
}

#[test]
fn a_headset_session_runs_traces_both_eyes_and_walks_through_faces() {
    if let Ok(runtime) = std::env::var("CURVED_SPACES_XR_RUNTIME") {
        println!("runtime: {runtime}");
    }
    let out = out_dir();
    let mut phase = Instant::now();
    let mut app = headset_app("seifert-weber");

    // 1. The session reaches Running.
    let start = Instant::now();
    let mut updates = 0;
    while app.world().get_resource::<XrState>() != Some(&XrState::Running) {
        assert!(
            updates < MAX_UPDATES_TO_RUN,
            "the OpenXR session did not reach Running in {MAX_UPDATES_TO_RUN} updates \
             (it is {:?})",
            app.world().get_resource::<XrState>()
        );
        app.update();
        updates += 1;
    }
    println!(
        "XrState::Running after {updates} updates ({:.2} s)",
        start.elapsed().as_secs_f64()
    );
    // The views, the eye cameras and the head.
    for _ in 0..40 {
        let ready = app.world().contains_resource::<XrHead>()
            && app
                .world_mut()
                .query::<&CurvedSpaceEye>()
                .iter(app.world())
                .count()
                == 2;
        if ready {
            break;
        }
        app.update();
    }
    assert!(
        app.world().contains_resource::<XrHead>(),
        "the head is tracked"
    );
    let config = *app.world().resource::<OxrCurrentSessionConfig>();
    let views = app.world().resource::<OxrViews>().0.clone();
    assert_eq!(views.len(), 2, "two views");
    let room_ipd = {
        let (a, b) = (views[0].pose.position, views[1].pose.position);
        DVec3::new(
            f64::from(a.x - b.x),
            f64::from(a.y - b.y),
            f64::from(a.z - b.z),
        )
        .length()
    };
    println!(
        "swapchain {}×{} {:?}; eye distance {:.1} mm; fov of the left view {:?}",
        config.resolution.x,
        config.resolution.y,
        config.format,
        room_ipd * 1e3,
        views[0].fov
    );
    assert!(
        (0.04..0.09).contains(&room_ipd),
        "the runtime's eyes are {room_ipd} m apart"
    );

    lap(&mut phase, "1. running");
    // 2. The frame-rate target follows the display.
    let predicted_ms = predicted_period_ms(&app);
    let period_ms = app
        .world()
        .resource::<XrDisplayPeriod>()
        .ms
        .expect("the display period is known");
    let target = app.world().resource::<FrameRateTarget>().target_ms;
    println!(
        "display period {period_ms:.2} ms (the runtime predicts {predicted_ms:.2} ms now); frame-rate target {target:?} ms"
    );
    assert_eq!(target, Some(period_ms), "the target is the display's rate");
    assert!(
        period_ms <= predicted_ms && period_ms < 100.0,
        "a display period of {period_ms} ms"
    );
    // From here the tracer keeps its full budget and resolution: the pictures are compared
    // with the CPU reference, and the frame time is measured without the target lowering it
    // (on lavapipe each lowered budget is a new shader, compiled for a second or two).
    app.world_mut()
        .resource_mut::<XrComfort>()
        .display_rate_target = false;
    app.world_mut().resource_mut::<FrameRateTarget>().target_ms = None;
    app.world_mut()
        .resource_mut::<TracerSettings>()
        .resolution_scale = 1.0;

    lap(&mut phase, "2. frame-rate target");
    // 3. Both eyes, read back from what the swapchain received. They are compared with the
    //    CPU reference at the end: its seconds of work would stall the session's pacing.
    for _ in 0..3 {
        app.update();
    }
    let active = app.world().resource::<ActiveSpace>().clone();
    let eyes = read_back_eyes(&mut app);
    let (w, h) = (config.resolution.x, config.resolution.y);
    for (eye, gpu) in &eyes {
        assert_eq!(
            gpu.dimensions(),
            (w, h),
            "eye {}: the swapchain's size",
            eye.index
        );
    }

    lap(&mut phase, "3. both eyes");
    // 4. The head's own motion (Monado's simulated head sways a few centimetres) carries it
    //    through a face of the quarter-turn space, whose z faces are glued with a turn.
    app.insert_resource(ActiveSpace::seed("quarter-turn").expect("a seed space"));
    for _ in 0..3 {
        app.update();
    }
    crossing_by_head_motion(&mut app);

    lap(&mut phase, "4. crossing by head motion");
    // 5. The thumbsticks: walk forward, then two snap turns.
    thumbsticks(&mut app);

    lap(&mut phase, "5. thumbsticks");
    // 6. Frame pacing: the wall time of each update (the runtime's wait for the next frame
    //    included) over 10 frames at full resolution, after 5 to settle.
    app.world_mut()
        .resource_mut::<TracerSettings>()
        .resolution_scale = 1.0;
    for _ in 0..5 {
        app.update();
    }
    let mut times = Vec::new();
    for _ in 0..10 {
        let start = Instant::now();
        app.update();
        times.push(1e3 * start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    let predicted_ms = predicted_period_ms(&app);
    println!(
        "frame time with both eyes traced at {w}×{h}: min {:.1} ms, median {:.1} ms, max {:.1} ms (the runtime's display period {period_ms:.1} ms; it predicts {predicted_ms:.1} ms now)",
        times[0],
        times[times.len() / 2],
        times[times.len() - 1],
    );
    lap(&mut phase, "6. frame pacing");
    // 6b. A product space (H²×R), after the timing (its frames are slower on a software
    //     rasteriser): the head walks along the product's geodesics and stays in the cell,
    //     and both eyes are traced (compared with the CPU reference below).
    let (product, product_eyes) = family_walk(&mut app, "bitorus-circle", product_settings());
    lap(&mut phase, "6b. the product space");
    // 6c. An SL̃(2,R) space (the unit tangent bundle of the bitorus) likewise.
    let (sl2r, sl2r_eyes) = family_walk(&mut app, "unit-tangent-bitorus", product_settings());
    lap(&mut phase, "6c. the SL̃(2,R) space");
    // The session is done with; dropping the app ends it.
    drop(app);

    lap(&mut phase, "the session's end");
    // 7. The eyes against the CPU reference from the same frames and frusta, and each other.
    let space = active.constant().unwrap();
    let fog = Shading::default_fog_distance(space);
    let scene = CurvedScene::with_parts(space, fog, tracer_settings().parts);
    for (eye, gpu) in &eyes {
        let layout = ViewLayout::mono(eye.frame, eye.lens, w, h);
        let settings = RenderSettings {
            width: w,
            height: h,
            max_crossings: CROSSINGS as usize,
        };
        let cpu = render_view(space, &scene, &layout, &settings, |_, _| {});
        judge_eye(&format!("eye{}", eye.index), gpu, &cpu, &out);
        let spread = {
            let lum: Vec<f64> = gpu
                .pixels()
                .map(|p| p.0.iter().map(|&c| f64::from(c)).sum::<f64>())
                .collect();
            let mean = lum.iter().sum::<f64>() / lum.len() as f64;
            (lum.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lum.len() as f64).sqrt()
        };
        assert!(spread > 5.0, "eye {} is blank (spread {spread})", eye.index);
    }
    // The product space's eyes against its CPU reference, from the same frames and frusta.
    let space = product.product().expect("a product space");
    let scene =
        bevy_curved_spaces::plugin::product::product_scene(space, &product_settings(), None);
    for (eye, gpu) in &product_eyes {
        let layout = ViewLayout::mono(eye.frame, eye.lens, w, h);
        let cpu = bevy_curved_spaces::trace::product::render_product_view(
            space,
            &scene,
            &layout,
            CROSSINGS as usize,
        );
        judge_eye(&format!("product-eye{}", eye.index), gpu, &cpu, &out);
    }
    // The SL̃(2,R) space's eyes against its CPU reference (balls and tubes met exactly).
    let AnySpace::Sl2r(space) = &sl2r.space else {
        panic!("an SL̃(2,R) space");
    };
    let scene = bevy_curved_spaces::plugin::sl2r::sl2r_scene(space, &product_settings(), None);
    for (eye, gpu) in &sl2r_eyes {
        let layout = ViewLayout::mono(eye.frame, eye.lens, w, h);
        let cpu = bevy_curved_spaces::trace::sl2r::render_sl2r_view(
            space,
            &scene,
            &layout,
            CROSSINGS as usize,
        );
        judge_eye(&format!("sl2r-eye{}", eye.index), gpu, &cpu, &out);
    }
    lap(&mut phase, "7. the CPU references");
    let (left, right) = (&eyes[0].1, &eyes[1].1);
    let between = common::differing_fraction(left, right, TOLERANCE);
    let (shift, residual) = best_shift(left, right, i64::from(w) / 8);
    println!(
        "the eyes differ in {:.2} % of pixels; the right eye's picture moved {shift} px right lays it over the left's (residual {residual:.1})",
        100.0 * between
    );
    assert!(between > 0.01, "the two eyes show the same picture");
    assert!(
        shift > 0,
        "parallax: near things must sit further right in the left eye (best shift {shift})"
    );
}

/// Prints how long the phase that just ended took (the CI log shows where the minutes go)
/// and starts the next.
fn lap(phase: &mut Instant, label: &str) {
    println!("phase {label}: {:.1} s", phase.elapsed().as_secs_f64());
    *phase = Instant::now();
}

/// An eye's picture against its CPU reference: the figures printed, the three pictures
/// written to `out` as `{name}-headset.png`, `-cpu`, `-diff`, and at most
/// [`MAX_DIFFERING`] of the pixels may differ.
fn judge_eye(name: &str, gpu: &RgbImage, cpu: &RgbImage, out: &std::path::Path) {
    let (c, diff) = compare(gpu, cpu, TOLERANCE);
    println!(
        "{name}: against the CPU reference {:.3} % of pixels differ, mean error {:.3}/255, max {}",
        100.0 * c.differing,
        c.mean_error,
        c.max_error
    );
    for (kind, img) in [("headset", gpu), ("cpu", cpu), ("diff", &diff)] {
        img.save(out.join(format!("{name}-{kind}.png")))
            .expect("write the picture");
    }
    assert!(
        c.differing <= MAX_DIFFERING,
        "{name}: {:.2} % of pixels differ from the CPU reference (pictures in {})",
        100.0 * c.differing,
        out.display()
    );
}

/// The left stick pushed forward for `updates` updates, then released.
fn walk_forward(app: &mut App, updates: usize) {
    app.world_mut().resource_mut::<PushedSticks>().0 = Some(XrSticks {
        walk: Vec2::new(0.0, 1.0),
        ..default()
    });
    for _ in 0..updates {
        app.update();
    }
    app.world_mut().resource_mut::<PushedSticks>().0 = Some(XrSticks::default());
}

/// Switches the session to the space `id` of another family (with `settings`), walks the
/// head forward with the left stick, and reads back both eyes: the head moves, stays in the
/// cell with an orthonormal frame, and the two eyes differ.
fn family_walk(
    app: &mut App,
    id: &str,
    settings: TracerSettings,
) -> (ActiveSpace, Vec<(EyeShot, RgbImage)>) {
    // The walk at a sixteenth of the pixels (its pictures are not looked at; on a software
    // rasteriser a full frame takes seconds), the eyes read back at full resolution.
    app.insert_resource(ActiveSpace::named(id).expect("a space"))
        .insert_resource(TracerSettings {
            resolution_scale: WALK_SCALE,
            ..settings
        });
    for _ in 0..3 {
        app.update();
    }
    let active = app.world().resource::<ActiveSpace>().clone();
    let space = active.space.frames();
    let margin = head(app).wrap_margin;
    let before = head(app).frame;
    assert!(
        space.outside_by(before.w_axis) <= 2.0 * margin,
        "the head starts in the cell of {id}"
    );
    walk_forward(app, 20);
    let after = head(app).frame;
    let moved = (after.w_axis - before.w_axis).abs().max_element();
    println!(
        "in {}: the left stick moved the head {moved:.4} (model entries), {} crossings",
        active.id,
        head(app).holonomy.crossings
    );
    assert!(moved > 1e-3, "the stick walks the head in {id}");
    app.insert_resource(settings);
    assert!(space.outside_by(after.w_axis) <= 2.0 * margin);
    assert!(
        space.frame_defect(after) < 1e-9,
        "{}",
        space.frame_defect(after)
    );
    let eyes = read_back_eyes(app);
    for (eye, _) in &eyes {
        assert!(space.frame_defect(eye.frame) < 1e-9, "eye {}", eye.index);
        assert!(
            space.outside_by(eye.frame.w_axis) <= 1e-9,
            "eye {}",
            eye.index
        );
    }
    let between = common::differing_fraction(&eyes[0].1, &eyes[1].1, TOLERANCE);
    println!(
        "the eyes in {id} differ in {:.2} % of pixels",
        100.0 * between
    );
    assert!(between > 0.01, "the two eyes in {id} show the same picture");
    (active, eyes)
}

/// Places the head just inside a z face in the direction the simulated head is moving and
/// follows it until it crosses; the tracker's frame, undone by its holonomy, must be the
/// room motion applied step by step in the cover.
///
/// Monado's simulated head sways on a Lissajous figure (periods of 8 s and 4 s), so its
/// direction turns within a second: the direction is its last single update's motion, and
/// the head starts inside the face by a tenth of that step (a longer window's chord can
/// point where the head no longer goes when an update is slow).
fn crossing_by_head_motion(app: &mut App) {
    let active = app.world().resource::<ActiveSpace>().clone();
    let space = active.constant().unwrap();
    let g = space.geometry();
    let scale = head(app).units_per_metre;
    let wrap_margin = head(app).wrap_margin;
    for attempt in 0..8 {
        // Which way is the head going? Its motion over the last update, in its own axes.
        app.update();
        let first = head_pose(app).expect("views");
        let clock = Instant::now();
        app.update();
        let last = head_pose(app).expect("views");
        let step_s = clock.elapsed().as_secs_f64();
        let (t, _) = first.relative(&last);
        if t.length() < 1e-5 {
            println!("attempt {attempt}: the head stood still for an update; again");
            continue;
        }
        // The head's motion direction becomes the space's +z, and the head starts inside the
        // +z face by a tenth of its last step.
        let direction = t.normalize();
        let turn = DQuat::from_rotation_arc(direction, DVec3::Z);
        let margin = 0.1 * t.length() * scale;
        let placed = g.translation(DVec3::Z, active.inradius - margin) * DMat4::from_quat(turn);
        {
            let mut h = app.world_mut().resource_mut::<XrHead>();
            h.0.frame = placed;
            h.0.holonomy = default();
        }
        // The room poses the tracker receives from here, the last one above its reference.
        let mut cover = placed;
        let mut previous = last;
        let mut crossed = false;
        // How far past the face's plane the head got, in units (it wraps past the margin).
        let mut furthest = f64::NEG_INFINITY;
        for _ in 0..20 {
            app.update();
            let now = head_pose(app).expect("views");
            let (t, r) = previous.relative(&now);
            cover = local_motion(g, cover, t * scale, r);
            previous = now;
            if head(app).holonomy.crossings > 0 {
                crossed = true;
                break;
            }
            furthest = furthest.max(space.outside_by(head(app).frame.w_axis));
        }
        if !crossed {
            println!(
                "attempt {attempt}: the head turned back before the face (step {:.2} mm in {step_s:.2} s, \
                 it came within {:.2e} units of the plane, wrap margin {wrap_margin:e}); again",
                1e3 * t.length(),
                -furthest,
            );
            continue;
        }
        let h = head(app);
        let gap = max_entry(head_in_cover(app) - cover);
        let face = h.holonomy.last_face.expect("a face was crossed");
        println!(
            "the head crossed {} face(s), the last {face} (normal {:?}); its frame is {gap:.2e} from the room motion walked in the cover",
            h.holonomy.crossings,
            space.faces()[face].normal
        );
        assert!(gap < 1e-9, "{gap:e} from the room motion in the cover");
        assert!(
            space.outside_by(h.frame.w_axis) <= h.wrap_margin + 1e-12,
            "the head is inside the cell"
        );
        // A z face of the quarter-turn space turns as it glues: the holonomy is no translation.
        let rotation = DMat4::from_cols(
            h.holonomy.matrix.x_axis,
            h.holonomy.matrix.y_axis,
            h.holonomy.matrix.z_axis,
            glam::DVec4::W,
        );
        assert!(
            max_entry(rotation - DMat4::IDENTITY) > 0.5,
            "the crossing applied the pairing's quarter turn"
        );
        return;
    }
    panic!("the simulated head never carried the head through the face");
}

fn thumbsticks(app: &mut App) {
    // At a sixteenth of the pixels: what moves is checked, not the pictures.
    app.world_mut()
        .resource_mut::<TracerSettings>()
        .resolution_scale = WALK_SCALE;
    let active = app.world().resource::<ActiveSpace>().clone();
    let g = active.constant().unwrap().geometry();
    println!(
        "the runtime reported the sticks bound to a controller: {}",
        app.world().resource::<RuntimeBound>().0
    );
    // Walk: the left stick pushed forward for a second.
    let before = head_in_cover(app);
    let start = app.world().resource::<Time>().elapsed_secs_f64();
    walk_forward(app, 20);
    let elapsed = app.world().resource::<Time>().elapsed_secs_f64() - start;
    let after = head_in_cover(app);
    let walked = g.distance(before.w_axis, after.w_axis);
    let expected = app.world().resource::<XrComfort>().speed * active.inradius * elapsed;
    // The simulated head sways by at most 10 cm meanwhile.
    let sway = 0.1 * head(app).units_per_metre;
    let ahead = before_axes(g, before, g.tangent_towards(before.w_axis, after.w_axis));
    println!(
        "the left stick walked {walked:.4} in {elapsed:.2} s (expected {expected:.4} ± {sway:.4}), direction in the head's axes {ahead:.3?}"
    );
    assert!(
        (walked - expected).abs() <= sway + 0.05 * expected,
        "walked {walked}, expected {expected}"
    );
    assert!(
        ahead.z < -0.9,
        "the walk goes where the head looks: {ahead:?}"
    );

    // Snap turns: the right stick pushed right, released, pushed again.
    let before = head_in_cover(app);
    let room_before = head_pose(app).expect("views");
    for (stick, frames) in [(1.0, 4), (0.0, 2), (0.9, 4), (0.0, 2)] {
        app.world_mut().resource_mut::<PushedSticks>().0 = Some(XrSticks {
            turn: Vec2::new(stick, 0.0),
            ..default()
        });
        for _ in 0..frames {
            app.update();
        }
    }
    let after = head_in_cover(app);
    let room_after = head_pose(app).expect("views");
    // The forward direction before and after, in the frame before: a turn about its up axis
    // (rightwards positive), less the simulated head's own turn in the room meanwhile (its
    // sway nods and rolls by under a degree, so the two yaws add).
    let yaw_of = |f: DVec3| f.x.atan2(-f.z).to_degrees();
    let turned = yaw_of(before_axes(g, before, -after.z_axis));
    let (_, room_turn) = room_before.relative(&room_after);
    let swayed = yaw_of(room_turn * -DVec3::Z);
    let TurnStyle::Snap { degrees } = TurnStyle::default() else {
        unreachable!("snap turning is the default")
    };
    println!(
        "two pushes of the right stick turned the head {:.2}° (snaps of {degrees}°; {turned:.2}° in all, {swayed:.2}° of it the head's own turn in the room)",
        turned - swayed
    );
    assert!(
        (turned - swayed - 2.0 * degrees).abs() < 1.0,
        "two snaps to the right: {}°",
        turned - swayed
    );
}

/// A direction at `before`'s position written in `before`'s axes, after moving it there
/// (the frames are a few hundredths of a unit apart: parallel transport is the identity
/// to well under a degree).
fn before_axes(g: Geometry, before: DMat4, direction: glam::DVec4) -> DVec3 {
    let m = g.inverse(before);
    let d = m * direction;
    DVec3::new(d.x, d.y, d.z).normalize()
}
