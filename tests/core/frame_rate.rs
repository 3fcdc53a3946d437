//! Holding a frame rate (`frame_rate::hold_frame_rate`), driven headless by a fake clock whose
//! frame time follows the pixels traced: slow frames lower the resolution scale, fast ones
//! raise it, and it settles without pumping.

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_curved_spaces::plugin::components::{Quality, TracerSettings};
use bevy_curved_spaces::plugin::frame_rate::{
    BudgetShare, FrameRateTarget, MIN_BUDGET_SHARE, hold_frame_rate, next_budget_share, next_scale,
    scale_range,
};
use bevy_curved_spaces::scene::SceneParts;
use bevy_curved_spaces::trace::BudgetChoice;
use std::time::Duration;

fn app(fps: f64, quality: Quality) -> App {
    let mut app = App::new();
    app.add_plugins(bevy::time::TimePlugin)
        .insert_resource(TracerSettings {
            fog_distance: None,
            max_crossings: None,
            quality,
            resolution_scale: quality.resolution_scale(),
            parts: SceneParts::default(),
            time: None,
            colour_by: Default::default(),
            walls: None,
            lighting: None,
        })
        .insert_resource(FrameRateTarget::fps(Some(fps)))
        .init_resource::<BudgetShare>()
        .add_systems(Update, hold_frame_rate);
    app
}

fn scale(app: &App) -> f32 {
    app.world().resource::<TracerSettings>().resolution_scale
}

/// Runs `frames` frames, each taking `cost(scale)` ms on the fake clock; returns the scales.
fn run(app: &mut App, frames: usize, cost: impl Fn(f32) -> f64) -> Vec<f32> {
    (0..frames)
        .map(|_| {
            let ms = cost(scale(app));
            app.insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
                ms / 1e3,
            )));
            app.update();
            scale(app)
        })
        .collect()
}

fn share(app: &App) -> f32 {
    app.world().resource::<BudgetShare>().0
}

/// Runs `frames` frames, each taking `cost(scale, budget share)` ms; returns both per frame.
fn run_with_budget(
    app: &mut App,
    frames: usize,
    cost: impl Fn(f32, f32) -> f64,
) -> Vec<(f32, f32)> {
    (0..frames)
        .map(|_| {
            let ms = cost(scale(app), share(app));
            app.insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
                ms / 1e3,
            )));
            app.update();
            (scale(app), share(app))
        })
        .collect()
}

/// A GPU whose frame costs `full` ms at full resolution and budget, in proportion to the
/// pixels, of which 70 % follows the crossing budget.
fn gpu_with_budget(full: f64) -> impl Fn(f32, f32) -> f64 {
    move |s, b| full * f64::from(s).powi(2) * (0.3 + 0.7 * f64::from(b)) + 0.5
}

#[test]
fn at_the_scale_floor_the_budget_gives_way_and_comes_back_first() {
    let mut app = app(30.0, Quality::High);
    let (floor, _) = scale_range(Quality::High);
    // 200 ms at full resolution: 50 ms even at the floor, too slow for 30 fps.
    let slow = run_with_budget(&mut app, 400, gpu_with_budget(200.0));
    let (last_scale, last_share) = *slow.last().unwrap();
    assert_eq!(last_scale, floor);
    assert!(
        (MIN_BUDGET_SHARE..1.0).contains(&last_share),
        "share {last_share}"
    );
    // The budget moved only once the scale was at its floor.
    for &(s, b) in &slow {
        assert!(b == 1.0 || s == floor, "budget share {b} at scale {s}");
    }
    let ms = gpu_with_budget(200.0)(last_scale, last_share);
    assert!(
        (1e3 / 30.0 * 0.7..=1e3 / 30.0 * 1.15).contains(&ms),
        "settled at share {last_share}, {ms:.1} ms a frame"
    );
    assert!(
        slow[250..].iter().all(|&x| x == (last_scale, last_share)),
        "still moving: {:?}",
        &slow[250..]
    );
    // A faster scene: the whole budget comes back before the resolution rises.
    let fast = run_with_budget(&mut app, 600, gpu_with_budget(10.0));
    assert_eq!(*fast.last().unwrap(), (1.0, 1.0));
    for &(s, b) in &fast {
        assert!(
            s == floor || b == 1.0,
            "scale {s} raised at budget share {b}"
        );
    }
    // The target turned off: the whole budget at once.
    app.insert_resource(FrameRateTarget::fps(None));
    app.world_mut().resource_mut::<BudgetShare>().0 = 0.5;
    run(&mut app, 2, gpu(10.0));
    assert_eq!(share(&app), 1.0);
}

#[test]
fn a_smaller_budget_that_does_not_help_is_undone() {
    let mut app = app(30.0, Quality::Medium);
    let (floor, _) = scale_range(Quality::Medium);
    // Like lavapipe scaling a window up: 150 ms a frame at any budget once at the floor.
    let frames = run_with_budget(&mut app, 400, |s, _| 150.0 + 400.0 * f64::from(s).powi(2));
    assert_eq!(
        *frames.last().unwrap(),
        (floor, 1.0),
        "{:?}",
        &frames[300..]
    );
    assert!(app.world().resource::<FrameRateTarget>().budget_futile);
    // It tried once, then left the budget alone.
    let lowered = frames.windows(2).filter(|w| w[1].1 < w[0].1).count();
    assert_eq!(lowered, 1, "lowered {lowered} times");
}

#[test]
fn a_budget_share_keeps_to_the_floor_and_the_budget() {
    let choice = BudgetChoice {
        budget: 40,
        missed_fraction: 0.0,
        most_needed: 40,
        samples: 100,
        floor: 18,
    };
    assert_eq!(choice.shared(1.0), 40);
    assert_eq!(choice.shared(0.8), 32);
    assert_eq!(choice.shared(0.51), 21, "rounded up");
    assert_eq!(choice.shared(0.25), 18, "never below the floor");
    for odd in [0.0, -1.0, 2.0, f32::NAN, f32::INFINITY] {
        let b = choice.shared(odd);
        assert!((18..=40).contains(&b), "{odd}: {b}");
    }
    assert_eq!(next_budget_share(1.0, 33.0, 33.3), None, "inside the band");
    assert_eq!(next_budget_share(1.0, 50.0, 33.3), Some(0.8));
    assert_eq!(next_budget_share(MIN_BUDGET_SHARE, 50.0, 33.3), None);
    assert_eq!(next_budget_share(0.8, 10.0, 33.3), Some(1.0));
    assert_eq!(next_budget_share(0.8, f64::NAN, 33.3), None);
}

/// A GPU whose frame costs `full` ms at full resolution, in proportion to the pixels.
fn gpu(full: f64) -> impl Fn(f32) -> f64 {
    move |s| full * f64::from(s).powi(2) + 0.5
}

#[test]
fn slow_frames_lower_the_scale_and_it_settles_at_the_target() {
    let mut app = app(30.0, Quality::High);
    // 80 ms at full resolution: 30 fps needs about 0.64 of it.
    let scales = run(&mut app, 400, gpu(80.0));
    let last = *scales.last().unwrap();
    assert!(last < 1.0, "the scale did not move: {last}");
    let ms = gpu(80.0)(last);
    assert!(
        (1e3 / 30.0 * 0.7..=1e3 / 30.0 * 1.15).contains(&ms),
        "settled at scale {last}, {ms:.1} ms a frame, outside the band around 33.3 ms"
    );
    // Settled: no change in the last 200 frames (no pumping).
    assert!(
        scales[200..].iter().all(|&s| s == last),
        "the scale still moves: {:?}",
        &scales[200..]
    );
}

#[test]
fn fast_frames_raise_the_scale_to_full_resolution() {
    let mut app = app(30.0, Quality::Low);
    assert_eq!(scale(&app), 0.5);
    let scales = run(&mut app, 300, gpu(5.0));
    assert_eq!(*scales.last().unwrap(), 1.0);
    // Steps up are small: at most ×1.1, one per settling period.
    for pair in scales.windows(2) {
        assert!(pair[1] <= pair[0] * 1.1 + 1.0 / 64.0, "jumped {pair:?}");
    }
}

#[test]
fn the_scale_stays_within_the_quality_range() {
    for quality in Quality::ALL {
        let (floor, top) = scale_range(quality);
        let mut app = app(60.0, quality);
        // Far too slow even at the floor.
        let scales = run(&mut app, 300, gpu(2000.0));
        assert_eq!(*scales.last().unwrap(), floor, "{quality:?}");
        assert!(scales.iter().all(|&s| (floor..=top).contains(&s)));
    }
}

#[test]
fn a_target_that_is_off_leaves_the_scale_alone() {
    let mut app = app(30.0, Quality::Medium);
    app.insert_resource(FrameRateTarget::fps(None));
    let scales = run(&mut app, 100, gpu(500.0));
    assert!(
        scales
            .iter()
            .all(|&s| s == Quality::Medium.resolution_scale())
    );
    // Nonsense rates are off too.
    for fps in [0.0, -5.0, f64::NAN, f64::INFINITY] {
        assert_eq!(FrameRateTarget::fps(Some(fps)).target_ms, None, "{fps}");
    }
}

#[test]
fn inside_the_band_the_scale_is_kept() {
    let range = (0.25, 1.0);
    assert_eq!(next_scale(0.75, 33.0, 33.3, range), None);
    assert_eq!(next_scale(0.75, 37.0, 33.3, range), None);
    assert_eq!(next_scale(0.75, 25.0, 33.3, range), None);
    assert!(next_scale(0.75, 40.0, 33.3, range).unwrap() < 0.75);
    assert!(next_scale(0.75, 20.0, 33.3, range).unwrap() > 0.75);
    assert_eq!(next_scale(0.75, f64::NAN, 33.3, range), None);
}
