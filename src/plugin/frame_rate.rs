//! Holding a frame rate: the traced resolution follows the measured frame times.
//!
//! The tracer's cost is about proportional to the pixels traced, so a frame time `t` at
//! resolution scale `σ` (a fraction of the view's width and height) predicts `t (σ'/σ)²` at
//! `σ'`. [`hold_frame_rate`] smooths the frame times, and when they leave a band around the
//! target (slower than 1.15×, or faster than 0.7×) for long enough it moves the scale
//! towards the one predicted to meet it, by at most a step, in steps of 1/32, within the
//! quality's range. The band and the wait are the hysteresis: a scale that meets the target
//! is kept, so the picture does not pump.
//!
//! Where the scale is at its floor and frames are still slow, the crossing budget gives way
//! next: [`BudgetShare`] is lowered by steps of ×0.8, and the tracer traces that share of the
//! automatic budget, never below the quality's floor budget (the one that leaves
//! [`Quality::floor_miss_fraction`] of the sampled rays short). A step that does not make
//! frames at least 5 % faster is undone and the budget left alone (on a software
//! rasteriser the floor's frame time is mostly scaling the window up, not tracing). Fast
//! frames give the budget back first, then the resolution.

use crate::plugin::components::{Quality, TracerSettings};
use bevy::prelude::*;

/// Frames the smoothed time must stay outside the band before the scale moves again.
pub const SETTLE_FRAMES: u32 = 12;

/// Slower than this × the target lowers the scale.
pub const SLOW: f64 = 1.15;

/// Faster than this × the target raises it (a scale step of 1/32 changes the time by a few
/// per cent, so the band is wide enough that one step does not cross it).
pub const FAST: f64 = 0.7;

/// The frame time to hold and what was chosen (a resource; `target_ms: None` leaves the
/// resolution scale to the settings and the panel).
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct FrameRateTarget {
    /// Frame time to hold, in ms (`1000 / fps`); `None`: off.
    pub target_ms: Option<f64>,
    /// Smoothed frame time (ms), as last measured.
    pub smoothed_ms: f64,
    /// Frames measured since the scale last moved.
    pub frames_since_change: u32,
    /// Times the scale or the budget share moved (the panel shows it; a test counts it).
    pub changes: u64,
    /// The smoothed frame time when the budget share was last lowered: the next measurement
    /// must be faster by [`BUDGET_GAIN`], or the step is undone.
    pub before_budget_step: Option<f64>,
    /// Lowering the budget did not make frames faster (the frame time is spent elsewhere,
    /// as on a software rasteriser scaling a window up): it is not lowered again until the
    /// resolution scale or the target changes.
    pub budget_futile: bool,
}

/// The least gain a step of the budget share must bring (×0.95 the frame time) to stay.
pub const BUDGET_GAIN: f64 = 0.95;

impl FrameRateTarget {
    /// Holding `fps` frames a second (`None` or not positive: off).
    #[must_use]
    pub fn fps(fps: Option<f64>) -> Self {
        Self {
            target_ms: fps.filter(|f| f.is_finite() && *f > 0.0).map(|f| 1e3 / f),
            smoothed_ms: 0.0,
            frames_since_change: 0,
            changes: 0,
            before_budget_step: None,
            budget_futile: false,
        }
    }
}

impl Default for FrameRateTarget {
    fn default() -> Self {
        Self::fps(None)
    }
}

/// The share of the automatic crossing budget that is traced (a resource; 1 unless a
/// frame-rate target lowered it). See the module's documentation; the budget it gives is
/// [`crate::trace::BudgetChoice::shared`], and a fixed budget
/// ([`TracerSettings::max_crossings`]) ignores it.
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct BudgetShare(pub f32);

impl Default for BudgetShare {
    fn default() -> Self {
        Self(1.0)
    }
}

/// The least [`BudgetShare`] a frame-rate target asks for (the quality's floor budget
/// usually stops it first).
pub const MIN_BUDGET_SHARE: f32 = 0.25;

/// The budget share after a smoothed frame time `smoothed` against `target` (ms), or `None`
/// to keep it: slower than the band, ×0.8 (down to [`MIN_BUDGET_SHARE`]); faster, ×1.25 (up
/// to 1). The caller lowers it only with the resolution scale at its floor, and raises it
/// before the scale.
#[must_use]
pub fn next_budget_share(share: f32, smoothed: f64, target: f64) -> Option<f32> {
    if !(smoothed > 0.0 && target > 0.0 && share.is_finite()) {
        return None;
    }
    let ratio = smoothed / target;
    let next = if ratio > SLOW {
        (share * 0.8).max(MIN_BUDGET_SHARE)
    } else if ratio < FAST {
        (share * 1.25).min(1.0)
    } else {
        return None;
    };
    (next != share).then_some(next)
}

/// The range of resolution scales a quality may hold a frame rate with: from its floor to
/// full resolution.
#[must_use]
pub fn scale_range(quality: Quality) -> (f32, f32) {
    let floor = match quality {
        Quality::Low => 0.125,
        Quality::Medium => 0.25,
        Quality::High => 0.5,
    };
    (floor, 1.0)
}

/// The scale after a smoothed frame time `smoothed` at scale `scale` against `target` (ms),
/// or `None` to keep it: outside the band, a step of at most ×1.25 down or ×1.1 up towards
/// the predicted scale, rounded to 1/32 and kept in `range`.
#[must_use]
pub fn next_scale(scale: f32, smoothed: f64, target: f64, range: (f32, f32)) -> Option<f32> {
    if !(smoothed > 0.0 && target > 0.0) {
        return None;
    }
    let ratio = smoothed / target;
    let factor = if ratio > SLOW {
        (1.0 / ratio).sqrt().max(0.8)
    } else if ratio < FAST {
        (1.0 / ratio).sqrt().min(1.1)
    } else {
        return None;
    };
    let wanted = (f64::from(scale) * factor * 32.0).round() / 32.0;
    let next = (wanted as f32).clamp(range.0, range.1);
    (next != scale).then_some(next)
}

/// Moves [`TracerSettings::resolution_scale`], then [`BudgetShare`], to hold
/// [`FrameRateTarget`] (a system in `Update`; it does nothing while the target is off). Frame times are wall-clock
/// ([`Time<Real>`]): the app's virtual time caps a frame at 250 ms.
pub fn hold_frame_rate(
    time: Res<Time<Real>>,
    mut target: ResMut<FrameRateTarget>,
    mut settings: ResMut<TracerSettings>,
    mut share: ResMut<BudgetShare>,
) {
    let Some(target_ms) = target.target_ms else {
        // No target: the whole budget again.
        if share.0 != 1.0 {
            share.0 = 1.0;
        }
        return;
    };
    let dt = 1e3 * time.delta_secs_f64();
    if !(dt > 0.0 && dt.is_finite()) {
        return;
    }
    // An exponential average over about 8 frames; the first frame starts it.
    target.smoothed_ms = if target.smoothed_ms > 0.0 {
        target.smoothed_ms + 0.125 * (dt - target.smoothed_ms)
    } else {
        dt
    };
    target.frames_since_change = target.frames_since_change.saturating_add(1);
    if target.frames_since_change < SETTLE_FRAMES {
        return;
    }
    debug!(
        "frame time {:.1} ms at resolution scale {}",
        target.smoothed_ms, settings.resolution_scale
    );
    let range = scale_range(settings.quality);
    // The budget: lowered once the scale is at its floor, given back before the scale; a
    // step that brought no gain is undone, and the budget left alone.
    if let Some(before) = target.before_budget_step.take()
        && target.smoothed_ms > BUDGET_GAIN * before
        && share.0 < 1.0
    {
        let back = (share.0 / 0.8).min(1.0);
        info!(
            "holding {:.0} fps: a smaller crossing budget did not help ({:.1} → {:.1} ms a \
             frame); share {} → {back}",
            1e3 / target_ms,
            before,
            target.smoothed_ms,
            share.0
        );
        share.0 = back;
        target.budget_futile = true;
        target.frames_since_change = 0;
        target.changes += 1;
        return;
    }
    let ratio = target.smoothed_ms / target_ms;
    let at_floor = settings.resolution_scale <= range.0;
    if (ratio > SLOW && at_floor && !target.budget_futile) || (ratio < FAST && share.0 < 1.0) {
        if let Some(next) = next_budget_share(share.0, target.smoothed_ms, target_ms) {
            info!(
                "holding {:.0} fps: crossing budget share {} → {next} ({:.1} ms a frame)",
                1e3 / target_ms,
                share.0,
                target.smoothed_ms
            );
            if next < share.0 {
                target.before_budget_step = Some(target.smoothed_ms);
            }
            share.0 = next;
            target.frames_since_change = 0;
            target.changes += 1;
        }
        return;
    }
    if let Some(next) = next_scale(
        settings.resolution_scale,
        target.smoothed_ms,
        target_ms,
        range,
    ) {
        // The frames measured so far were at the old scale: predict them at the new one.
        let s = f64::from(next / settings.resolution_scale);
        info!(
            "holding {:.0} fps: resolution scale {} → {next} ({:.1} ms a frame)",
            1e3 / target_ms,
            settings.resolution_scale,
            target.smoothed_ms
        );
        target.smoothed_ms *= s * s;
        settings.resolution_scale = next;
        target.budget_futile = false;
        target.frames_since_change = 0;
        target.changes += 1;
    }
}
