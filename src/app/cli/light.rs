//! `light`: the fluence at a point from a unit lamp, summed over every image of the lamp
//! (the exact images within a reach, the rest by its mean with an error bound).

use super::*;
use bevy_curved_spaces::scene::Shading;
use bevy_curved_spaces::scene::light_images::{fluence, fluence_within};
use glam::DVec4;
use serde_json::json;

/// The stated bound the default reach aims for, as a fraction of the total.
const DEFAULT_BOUND_FRACTION: f64 = 0.01;

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
        // A point the model cannot hold (NaN) is outside too.
        if !(space.outside_by(p) <= 1e-12) {
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
    let radius = args.radius.unwrap_or(Shading::default().near_light);
    let started = std::time::Instant::now();
    // Without --reach, the reach whose stated bound is at most 1 % of the total, where the
    // image limit allows; a note says so where it does not.
    let (f, loose) = match args.reach {
        Some(reach) => (
            fluence(&space, lamp, at, fog, reach, radius).map_err(|e| e.to_string())?,
            false,
        ),
        None => {
            let (f, within) = fluence_within(&space, lamp, at, fog, radius, DEFAULT_BOUND_FRACTION)
                .map_err(|e| e.to_string())?;
            (f, !within)
        }
    };
    let reach = f.reach;
    let loose_note = loose.then(|| {
        format!(
            "the bound is {:.1} % of the total, not within 1 %: summing enough images exactly to \
             bound the rest that tightly would take more than {} of them (in {} the count of \
             images in a shell is uncertain by a factor that does not shrink with the reach); \
             --check R measures the shortcut's real error",
            100.0 * f.bound / f.total(),
            bevy_curved_spaces::scene::light_images::MAX_IMAGES,
            g.name()
        )
    });
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
        let mut out = json!({
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
        });
        if let Some(note) = &loose_note {
            out["bound_note"] = json!(note);
        }
        println!("{out}");
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
        if let Some(note) = &loose_note {
            println!("  note: {note}");
        }
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
