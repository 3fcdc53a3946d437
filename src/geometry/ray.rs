//! Rays: a point of the model with a unit tangent there, the start of a geodesic.

use super::{Geometry, GeometryError};
use glam::{DVec3, DVec4};

/// A point of the model and a unit tangent there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray<V> {
    /// A point of the model.
    pub point: V,
    /// A unit tangent at the point.
    pub tangent: V,
}

/// A ray from a chart point in a chart direction, as the f64 reference.
pub fn chart_ray(geometry: Geometry, from: DVec3, dir: DVec3) -> Result<Ray<DVec4>, GeometryError> {
    let point = geometry.from_chart(from)?;
    let tangent = geometry.tangent_from_chart(point, dir)?;
    Ok(Ray { point, tangent })
}
