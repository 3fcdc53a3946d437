//! `light`: the fluence at a point from a unit lamp, summed over every image of the lamp
//! (the exact images within a reach, the rest by its mean with an error bound).

use super::*;
use bevy_curved_spaces::scene::Shading;
use bevy_curved_spaces::scene::light_images::{fluence, fluence_within};
use bevy_curved_spaces::space::Family;
use serde_json::json;

/// The stated bound the default reach aims for, as a fraction of the total.
const DEFAULT_BOUND_FRACTION: f64 = 0.01;

pub(super) fn light(args: &LightArgs) -> Result<(), String> {
    let named = super::space_named(&args.space)?;
    named
        .supports(bevy_curved_spaces::space::Feature::LampFluence)
        .map_err(|e| format!("{}: {e}", args.space))?;
    let space = match named {
        AnySpace::Sl2r(space) => return light_sl2r(args, &space),
        AnySpace::Constant(space) => space,
        AnySpace::Product(space) => return light_product(args, &space),
        AnySpace::Nil(space) => return light_nil(args, &space),
    };
    let g = space.geometry();
    let point = |x: DVec3, what: &str| {
        point_in_cell(
            x,
            what,
            space.name(),
            |x| g.from_chart(x).map_err(|e| e.to_string()),
            |p| space.outside_by(p),
        )
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

/// `light` in a product space (H²×R, S²×R): the same sum over the lamp's images, along
/// every geodesic to each (one in H²×R, one per way round in S²×R), each with the product's
/// falloff, and the rest by its mean. Points are given as `trace --from` gives them: the
/// surface's chart point and a height. The lamp is a point (no `--radius`), and the tail has
/// no error bound in the products yet: `--check R` measures it.
fn light_product(
    args: &LightArgs,
    space: &bevy_curved_spaces::space::product::ProductSpace,
) -> Result<(), String> {
    use bevy_curved_spaces::scene::Lighting;
    use bevy_curved_spaces::trace::product::lighting::{product_fluence, reach};
    refuse_radius(args, Family::Product, space.name())?;
    let g = space.base();
    let point = |x: DVec3, what: &str| {
        point_in_cell(
            x,
            what,
            space.name(),
            |x| bevy_curved_spaces::space::product::chart_point(g, x),
            |p| space.outside_by(p),
        )
    };
    let lamp = point(args.light, "--light")?;
    let at = point(args.at, "--at")?;
    let fog = args
        .fog
        .unwrap_or_else(|| bevy_curved_spaces::trace::product::default_scene(space).fog_distance);
    let wanted = args
        .reach
        .unwrap_or_else(|| reach(space, &Lighting::default()));
    open_light(
        args,
        (space.name(), space.geometry_name()),
        fog,
        wanted,
        |r| {
            let (paths, exact, tail, covered) = product_fluence(space, lamp, at, fog, r);
            (covered, paths, exact, tail)
        },
        (
            "the product geometries have no error bound for the rest yet: --check R measures \
             the shortcut's real error",
            None,
        ),
    )
}

/// `light` in a Nil space: the sum over the lamp's images along the shortest geodesic to
/// each (as the tracer lights), each with Nil's falloff (the geodesic sphere's area), and
/// the rest by its mean. Points are chart points, brought into the box by the lattice; the
/// lamp is a point.
fn light_nil(
    args: &LightArgs,
    space: &bevy_curved_spaces::space::nil::NilSpace,
) -> Result<(), String> {
    use bevy_curved_spaces::scene::Lighting;
    use bevy_curved_spaces::trace::nil::light::{nil_fluence, reach};
    refuse_radius(args, Family::Nil, space.name())?;
    let point = |x: DVec3, what: &str| -> Result<[f64; 3], String> {
        bevy_curved_spaces::trace::nil::chart_point(x.to_array(), what).map(|p| space.into_box(p))
    };
    let lamp = point(args.light, "--light")?;
    let at = point(args.at, "--at")?;
    let fog = args
        .fog
        .unwrap_or_else(|| bevy_curved_spaces::trace::nil::default_scene(space).fog_distance);
    let wanted = args
        .reach
        .unwrap_or_else(|| reach(space, &Lighting::default()));
    open_light(
        args,
        (space.name(), "Nil"),
        fog,
        wanted,
        |r| {
            let (paths, exact, tail, covered) = nil_fluence(space, lamp, at, fog, r);
            (covered, paths, exact, tail)
        },
        (
            "the sum follows the shortest geodesic to each image (as the tracer does), and Nil \
             has no error bound for the rest yet: --check R measures the shortcut's real error",
            None,
        ),
    )
}

/// `light` in an SL̃(2,R) space: the sum over the lamp's images along the shortest geodesic
/// to each (as the tracer lights), each with SL̃(2,R)'s falloff (the geodesic sphere's
/// area), and the rest by its mean. Points are chart points `[x, y, θ]` (the base point and
/// the fibre angle), brought into the cell by the surface group; the lamp is a point, and
/// the reach is below the injectivity radius of `UT H²` (each image has one lift there).
fn light_sl2r(
    args: &LightArgs,
    space: &bevy_curved_spaces::space::sl2r::UnitTangentSpace,
) -> Result<(), String> {
    use bevy_curved_spaces::scene::Lighting;
    use bevy_curved_spaces::trace::sl2r::light::{LampImage, MAX_LIGHT_REACH, reach, sl2r_fluence};
    refuse_radius(args, Family::Sl2r, space.name())?;
    for (flag, value) in [("--reach", args.reach), ("--check", args.check)] {
        if let Some(r) = value.filter(|r| *r > MAX_LIGHT_REACH) {
            return Err(format!(
                "{flag} {r}: an SL̃(2,R) lamp's images are summed within {MAX_LIGHT_REACH} at \
                 most (below the injectivity radius π of UT H², where the shortest geodesic to \
                 each image is the one the inverse exponential map finds); the rest is their mean"
            ));
        }
    }
    let point = |x: DVec3, what: &str| -> Result<LampImage, String> {
        let (frame, sheet) = space
            .frame_at_chart_point(x)
            .map_err(|m| format!("{what}: {m}"))?;
        Ok(LampImage { frame, sheet })
    };
    let lamp = point(args.light, "--light")?;
    let at = point(args.at, "--at")?;
    let fog = args
        .fog
        .unwrap_or_else(|| bevy_curved_spaces::trace::sl2r::default_fog_distance(space));
    let wanted = args
        .reach
        .unwrap_or_else(|| reach(space, &Lighting::default()));
    open_light(
        args,
        (space.name(), "SL2R"),
        fog,
        wanted,
        |r| {
            let (paths, exact, tail, covered) =
                sl2r_fluence(space, lamp, (&at.frame, at.sheet), fog, r);
            (covered, paths, exact, tail)
        },
        (
            "the sum follows the shortest geodesic to each image (as the tracer does) within the \
             injectivity radius, and SL̃(2,R) has no error bound for the rest yet: --check R (at \
             most 3) measures the shortcut's real error",
            Some("the reach of 3 the sum is held within (below the injectivity radius)"),
        ),
    )
}

/// `--radius`, refused where the family's lamp is a point.
fn refuse_radius(args: &LightArgs, family: Family, name: &str) -> Result<(), String> {
    if args.radius.is_some() {
        super::spaces::require(
            family,
            name,
            bevy_curved_spaces::space::Feature::SoftShadows,
        )
        .map_err(|e| format!("--radius: {e}"))?;
    }
    Ok(())
}

/// The fluence's report where geodesic spheres never close (the products, Nil): `sum(R)`
/// gives the reach covered, the paths summed, the exact sum and the tail for the reach `R`;
/// without `--reach` the reach grows until the tail is at most 1 % of the total. `no_bound`
/// says why no error bound is stated.
fn open_light(
    args: &LightArgs,
    (name, geometry): (&str, &str),
    fog: f64,
    wanted: f64,
    sum: impl Fn(f64) -> (f64, usize, f64, f64),
    (no_bound, limit): (&str, Option<&str>),
) -> Result<(), String> {
    let gathered = format!(
        "the {} the sum gathers (the tracer's limit)",
        bevy_curved_spaces::scene::lighting::MAX_LAMP_IMAGES
    );
    let limit = limit.unwrap_or(&gathered);
    if !(fog > 0.0 && fog.is_finite()) {
        return Err(format!(
            "the fog distance must be a positive, finite number, got {fog} (without fog the sum \
             over the images diverges)"
        ));
    }
    if !(wanted > 0.0 && wanted.is_finite()) {
        return Err(format!(
            "the reach must be a positive, finite number, got {wanted}"
        ));
    }
    let (mut covered, mut paths, mut exact, mut tail) = sum(wanted);
    // Without --reach: with no bound to aim for, the reach grows until the mean of the rest
    // is at most 1 % of the total, or the images the walk can gather stop it.
    if args.reach.is_none() {
        for _ in 0..6 {
            let target = DEFAULT_BOUND_FRACTION * (exact + tail);
            if !(tail > target) {
                break;
            }
            let longer = covered + fog * ((tail / target).ln() + 0.5);
            let (c, p, e, t) = sum(longer);
            if !(c > covered) {
                break;
            }
            (covered, paths, exact, tail) = (c, p, e, t);
        }
    }
    let total = exact + tail;
    let tail_note = (args.reach.is_none() && tail > DEFAULT_BOUND_FRACTION * total).then(|| {
        format!(
            "the mean of the rest is {:.1} % of the total, not within 1 %: its images lie past \
             {limit}, and the fog of {fog:.3} absorbs them slowly",
            100.0 * tail / total,
        )
    });
    if !total.is_finite() {
        return Err(format!(
            "the light is larger than f64 can hold (1.8e308): with a fog distance of {fog} it \
             is hardly absorbed; give a shorter --fog"
        ));
    }
    let check = match args.check {
        Some(r) if !(r > covered) => {
            return Err(format!(
                "--check {r} must be longer than the reach {covered}: it sums the images out to there"
            ));
        }
        Some(r) => {
            let longer = sum(r);
            if !(longer.0 > covered) {
                return Err(format!(
                    "--check {r}: the images within it are more than the {} the sum gathers (the \
                     tracer's limit), so it covers no more than the reach {covered:.4}: nothing \
                     to check against",
                    bevy_curved_spaces::scene::lighting::MAX_LAMP_IMAGES
                ));
            }
            Some(longer)
        }
        None => None,
    };
    if args.json {
        let mut out = json!({
            "space": name,
            "geometry": geometry,
            "light": args.light.to_array(),
            "at": args.at.to_array(),
            "fog": fog,
            "reach": covered,
            "images": paths,
            "exact": exact,
            "tail": tail,
            "total": total,
            "bound_note": no_bound,
        });
        if let Some(note) = &tail_note {
            out["tail_note"] = json!(note);
        }
        if let Some((r, n, e, t)) = check {
            out["check"] = json!({
                "reach": r,
                "images": n,
                "total": e + t,
                "difference": total - (e + t),
            });
        }
        println!("{out}");
    } else {
        println!(
            "fluence at {:?} from a unit lamp at {:?} in {} ({}), fog λ = {fog:.4}",
            args.at.to_array(),
            args.light.to_array(),
            name,
            geometry
        );
        println!("  {paths} paths to the images within {covered:.4} summed exactly: {exact:.9e}");
        println!("  the rest by its mean 4πλ e^(−R/λ)/vol: {tail:.9e}");
        println!("  total {total:.9e}");
        println!("  note: {no_bound}");
        if let Some(note) = &tail_note {
            println!("  note: {note}");
        }
        if let Some((r, n, e, t)) = check {
            println!(
                "  check: {n} paths within {r:.4} give {:.9e}: the shortcut is off by {:.3e}",
                e + t,
                total - (e + t)
            );
        }
    }
    Ok(())
}
