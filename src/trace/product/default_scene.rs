//! The default scene and view of a product space, and a scene with some of its parts.

use super::{ProductCamera, ProductObject, ProductScene, ProductShape};
use crate::space::product::{ProductSpace, ProductWalker};
use glam::{DVec3, DVec4};

/// Which parts of the default scene a product scene has ([`scene_with_parts`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProductParts {
    /// The cell's vertical and horizontal edges (the sphere's ring of balls instead).
    pub edges: bool,
    /// The ball at the centre.
    pub centre_ball: bool,
}

impl Default for ProductParts {
    /// Both parts: the default scene.
    fn default() -> Self {
        Self {
            edges: true,
            centre_ball: true,
        }
    }
}

/// The default scene: a ball at the centre, the cell's vertical edges (fibre tubes over the
/// polygon's corners) and its horizontal edges (the polygon's sides in the top and bottom
/// slices), a light above and beside the ball. The sphere has neither edge: a ring of balls
/// round the equator marks its directions.
#[must_use]
pub fn default_scene(space: &ProductSpace) -> ProductScene {
    scene_with_parts(space, ProductParts::default())
}

/// The default scene's light, ambient light and fog with the parts asked for.
#[must_use]
pub fn scene_with_parts(space: &ProductSpace, parts: ProductParts) -> ProductScene {
    let g = space.base();
    let walker = ProductWalker::<DVec4>::new(space);
    let size = space
        .base_inradius()
        .min(std::f64::consts::FRAC_PI_2)
        .min(space.length());
    let mut objects = Vec::new();
    let polygon = space.polygon();
    let n = polygon.sides.len();
    let edge = 0.04 * size;
    let h = 0.5 * space.length();
    if !parts.edges {
        // No edges: only what else is asked for.
    } else if n > 0 && !space.hemisphere() {
        let r = crate::geometry::Real::to_f64(polygon.circumradius);
        let (c, s) = g.cs(r);
        for m in 0..n {
            let a = std::f64::consts::PI * (2.0 * m as f64 - 1.0) / n as f64;
            let corner = DVec4::new(s * a.cos(), s * a.sin(), 0.0, c);
            objects.push(ProductObject {
                shape: ProductShape::Fibre(corner),
                radius: edge,
                colour: DVec3::new(0.85, 0.55, 0.25),
            });
        }
        for cov in &walker.covectors {
            for height in [-h, h] {
                objects.push(ProductObject {
                    shape: ProductShape::Geodesic {
                        covector: *cov,
                        height,
                    },
                    radius: edge,
                    colour: DVec3::new(0.3, 0.6, 0.9),
                });
            }
        }
    } else {
        // No corner to draw: small balls round the surface's equator-like circle at the
        // centre's height mark the directions.
        let ring = 0.6 * size.min(std::f64::consts::FRAC_PI_4 * 1.5);
        let (c, s) = g.cs(ring);
        for m in 0..6 {
            let a = std::f64::consts::TAU * m as f64 / 6.0;
            objects.push(ProductObject {
                shape: ProductShape::Point(DVec4::new(s * a.cos(), s * a.sin(), 0.0, c)),
                radius: 0.08 * size,
                colour: DVec3::new(0.3, 0.6, 0.9),
            });
        }
    }
    if parts.centre_ball {
        objects.push(ProductObject {
            shape: ProductShape::Point(DVec4::W),
            radius: 0.25 * size,
            colour: DVec3::new(1.0, 0.78, 0.45),
        });
    }
    let (c, s) = g.cs(0.5 * size);
    let light = DVec4::new(s * 0.8, s * 0.6, 0.3 * h, c);
    let lighting = crate::scene::lighting::Lighting::default();
    ProductScene {
        objects,
        light,
        lighting,
        lamp: super::lighting::ProductLamp::new(space, light, &lighting),
        ambient: 0.3,
        fog_distance: 3.0 * size.max(0.5 * h),
        fog_colour: DVec3::new(0.04, 0.05, 0.08),
        walls: None,
        colour_by: crate::scene::ColourBy::Shading,
    }
}

/// The default camera: three quarters of the way to the side from the centre, a little
/// above it, looking at the ball.
#[must_use]
pub fn default_camera(space: &ProductSpace) -> ProductCamera {
    let g = space.base();
    let size = space.base_inradius().min(std::f64::consts::FRAC_PI_2);
    let (c, s) = g.cs(0.7 * size);
    let a: f64 = 0.35;
    let eye = DVec4::new(s * a.cos(), s * a.sin(), 0.2 * space.length(), c);
    ProductCamera::looking_at(g, eye, DVec4::W, 70.0)
}
