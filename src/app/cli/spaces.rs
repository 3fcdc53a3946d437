//! The one door from the command line to the spaces: an argument is sent to its family by the
//! crate's registry, and a point given on the command line is checked against the cell.

use bevy_curved_spaces::space::dirichlet::DirichletOptions;
use bevy_curved_spaces::space::{AnySpace, Feature, Space};
use glam::DVec3;
use std::path::Path;

/// The basepoint given by `--basepoint`, for every space made from a generator file.
pub(super) static BASEPOINT: std::sync::OnceLock<Option<DVec3>> = std::sync::OnceLock::new();

/// The space an argument names, of any family, through the crate's one registry
/// ([`AnySpace::resolve`]): a seed space, a library member, a product space or a space file
/// (`.gen` generator file or JSON), with `--basepoint` where its family takes one.
pub(super) fn space_named(arg: &str) -> Result<AnySpace, String> {
    let basepoint = BASEPOINT.get().copied().flatten();
    let options = DirichletOptions {
        basepoint,
        ..DirichletOptions::default()
    };
    let space = AnySpace::resolve(arg, Path::new(""), &options)?;
    if basepoint.is_some() {
        space
            .supports(Feature::Basepoint)
            .map_err(|e| format!("{arg}: {e}"))?;
    }
    Ok(space)
}

/// The constant-curvature space of `space` for a feature only that family has: the family's
/// own reason where it is of another.
pub(super) fn constant_for(space: &AnySpace, feature: Feature) -> Result<&Space, String> {
    space
        .supports(feature)
        .map_err(|e| format!("{}: {e}", space.name()))?;
    space.constant().map(|s| &**s).ok_or_else(|| {
        format!(
            "{}: {} is drawn by the constant-curvature family only",
            space.name(),
            feature.name()
        )
    })
}

/// `Ok(())` where the family does `feature`, else its reason as the command line says it,
/// naming the space.
pub(super) fn require(
    family: bevy_curved_spaces::space::Family,
    name: &str,
    feature: Feature,
) -> Result<(), String> {
    family.supports(feature).map_err(|e| format!("{name}: {e}"))
}

/// The model point of the chart point `x` (option `what`), which must lie in the cell of
/// `name`: `to_model` reads the chart, `outside_by` says how far outside the cell a point
/// is (NaN, a point the model cannot hold, counts as outside).
pub(super) fn point_in_cell(
    x: DVec3,
    what: &str,
    name: &str,
    to_model: impl Fn(DVec3) -> Result<glam::DVec4, String>,
    outside_by: impl Fn(glam::DVec4) -> f64,
) -> Result<glam::DVec4, String> {
    let p = to_model(x).map_err(|e| format!("{what}: {e}"))?;
    if !(outside_by(p) <= 1e-12) {
        return Err(format!(
            "{what} {:?} is outside the cell of {name}",
            x.to_array()
        ));
    }
    Ok(p)
}
