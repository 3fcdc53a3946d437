//! Parsers of the command line's values: each checks the value and names what is wrong.

use bevy::prelude::*;
use bevy_curved_spaces::view::StereoMode;
use bevy_curved_spaces::view::stereo::UnknownStereoMode;
use glam::DVec3;

pub(super) fn parse_stereo(s: &str) -> Result<StereoMode, String> {
    s.parse().map_err(|e: UnknownStereoMode| e.to_string())
}

pub(super) fn parse_vec3(s: &str) -> Result<DVec3, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!(
            "expected three comma-separated numbers like 1,0,0.5, got `{s}`"
        ));
    }
    let mut v = [0.0; 3];
    for (x, p) in v.iter_mut().zip(&parts) {
        *x = p
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("`{p}` is not a finite number"))?;
    }
    Ok(DVec3::from_array(v))
}

/// The largest scene clock accepted (seconds, either sign): a spinning globe's angle is
/// the time times its rate, and past this it would lose every digit of its fraction.
pub(super) const MAX_TIME: f64 = 1e9;

pub(super) fn parse_time(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|t| t.is_finite() && t.abs() <= MAX_TIME)
        .ok_or_else(|| {
            format!("expected a time in seconds from -{MAX_TIME:e} to {MAX_TIME:e}, got `{s}`")
        })
}

pub(super) fn parse_positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("expected a positive number, got `{s}`")),
    }
}

/// A snap turn in degrees: 0 (smooth turning) to 180.
pub(super) fn parse_snap_degrees(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && (0.0..=180.0).contains(&x) => Ok(x),
        _ => Err(format!(
            "expected a snap turn from 0 (smooth turning) to 180 degrees, got `{s}`"
        )),
    }
}

/// A frame rate to hold: 0 (off) to 1000.
pub(super) fn parse_fps(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && (0.0..=1000.0).contains(&x) => Ok(x),
        _ => Err(format!(
            "expected frames a second from 0 (off) to 1000, got `{s}`"
        )),
    }
}

/// Longer walks than this take minutes and say nothing new.
pub(super) const MAX_WALK: usize = 1_000_000;

pub(super) fn parse_crossings(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n <= MAX_WALK => Ok(n),
        _ => Err(format!(
            "expected a whole number from 0 to {MAX_WALK}, got `{s}`"
        )),
    }
}

pub(super) fn parse_distance(s: &str) -> Result<f64, String> {
    match parse_positive(s)? {
        d if d <= MAX_WALK as f64 => Ok(d),
        _ => Err(format!("expected a distance up to {MAX_WALK}, got `{s}`")),
    }
}

/// How far the walls' windows are open: 0 (solid walls) to 1 (no walls).
pub(super) fn parse_opening(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if (0.0..=1.0).contains(&x) => Ok(x),
        _ => Err(format!(
            "expected an opening from 0 (solid walls) to 1 (no walls), got `{s}`"
        )),
    }
}

/// The share of light a wall stops: above 0, at most 1.
pub(super) fn parse_opacity(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x > 0.0 && x <= 1.0 => Ok(x),
        _ => Err(format!(
            "expected an opacity above 0 and at most 1, got `{s}`"
        )),
    }
}

pub(super) fn parse_fov(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x > 0.0 && x < 180.0 => Ok(x),
        _ => Err(format!(
            "expected an angle between 0 and 180 degrees, got `{s}`"
        )),
    }
}

pub(super) fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let err = || format!("expected WIDTHxHEIGHT like 640x360 (1 to 16384 each), got `{s}`");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(err)?;
    let w: u32 = w.trim().parse().map_err(|_| err())?;
    let h: u32 = h.trim().parse().map_err(|_| err())?;
    if !(1..=16384).contains(&w) || !(1..=16384).contains(&h) {
        return Err(err());
    }
    Ok((w, h))
}
