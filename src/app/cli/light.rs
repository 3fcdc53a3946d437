//! `light`: the fluence at a point from a unit lamp, summed over every image of the lamp
//! (the exact images within a reach, the rest by its mean with an error bound).

use super::*;
use bevy_curved_spaces::scene::Shading;
use bevy_curved_spaces::scene::light_images::{ball_volume, fluence};
use bevy_curved_spaces::space::invariants::volume;
use glam::DVec4;
use serde_json::json;

/// The reach within which about 200 images lie (`V(R) = 200 vol(M)`), at most eight fog
/// distances: beyond it the tail's mean stands in.
fn default_reach(space: &Space, fog: f64) -> f64 {
    let g = space.geometry();
    let want = 200.0 * volume(space);
    let (mut lo, mut hi) = (0.0, 8.0 * fog);
    if ball_volume(g, hi) <= want {
        return hi;
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if ball_volume(g, mid) < want {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

pub(super) fn light(args: &LightArgs) -> Result<(), String> {
    if super::product(&args.space)?.is_some() {
        return Err(
            "light sums the images of a lamp in the constant-curvature spaces; the product \
             spaces (H²×R, S²×R) do not take it yet"
                .into(),
        );
    }
    let space = resolve_space(&args.space)?;
    let g = space.geometry();
    let point = |x: DVec3, what: &str| -> Result<DVec4, String> {
        let p = g.from_chart(x).map_err(|e| format!("{what}: {e}"))?;
        if space.outside_by(p) > 1e-12 {
            return Err(format!(
                "{what} {:?} is outside the cell of {}",
                x.to_array(),
                space.name()
            ));
        }
        Ok(p)
    };
    let lamp = point(args.light, "--light")?;
    let at = point(args.at, "--at")?;
    let fog = args
        .fog
        .unwrap_or_else(|| Shading::default_fog_distance(&space));
    let reach = args.reach.unwrap_or_else(|| default_reach(&space, fog));
    let radius = args.radius.unwrap_or(Shading::default().near_light);
    let started = std::time::Instant::now();
    let f = fluence(&space, lamp, at, fog, reach, radius).map_err(|e| e.to_string())?;
    // The shortcut's error measured: the exact sum out to a longer reach, with its tail.
    let check = match args.check {
        Some(r) if r <= reach => {
            return Err(format!(
                "--check {r} must be longer than the reach {reach}: it sums the images out to there"
            ));
        }
        Some(r) => Some(fluence(&space, lamp, at, fog, r, radius).map_err(|e| e.to_string())?),
        None => None,
    };
    if args.json {
        println!(
            "{}",
            json!({
                "space": space.name(),
                "geometry": g.name(),
                "light": args.light.to_array(),
                "at": args.at.to_array(),
                "fog": fog,
                "radius": radius,
                "reach": f.reach,
                "images": f.images,
                "exact": f.exact,
                "tail": f.tail,
                "bound": f.bound,
                "total": f.total(),
                "check": check.map(|c| json!({
                    "reach": c.reach,
                    "images": c.images,
                    "total": c.total(),
                    "bound": c.bound,
                    "difference": f.total() - c.total(),
                })),
            })
        );
    } else {
        println!(
            "fluence at {:?} from a unit lamp at {:?} in {} ({}), fog λ = {fog:.4}, lamp radius {radius}",
            args.at.to_array(),
            args.light.to_array(),
            space.name(),
            g.name()
        );
        println!(
            "  {} images within {:.4} summed exactly: {:.9e}",
            f.images, f.reach, f.exact
        );
        if g == bevy_curved_spaces::geometry::Geometry::Spherical {
            println!("  every image and every turn round the great circles: nothing left over");
        } else {
            println!(
                "  the rest by its mean 4πλ e^(−R/λ)/vol: {:.9e} ± {:.3e}",
                f.tail, f.bound
            );
        }
        println!(
            "  total {:.9e} ({:.2} s)",
            f.total(),
            started.elapsed().as_secs_f64()
        );
        if let Some(c) = check {
            println!(
                "  check: {} images within {:.4} give {:.9e} (tail ± {:.3e}): the shortcut is off by {:.3e}",
                c.images,
                c.reach,
                c.total(),
                c.bound,
                f.total() - c.total()
            );
        }
    }
    Ok(())
}
