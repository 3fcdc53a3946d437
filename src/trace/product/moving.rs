//! Things that move in a product scene: a scene file's balls with a `velocity`, and the
//! images a ball near a face needs to be drawn whole.
//!
//! A moving ball flies along the product geodesic of its velocity (given in its frame at
//! the start: the centre's axes carried to its position, `z` the fibre) and comes back
//! into the cell through the faces it passes ([`crate::space::FrameSpace`]'s
//! `step_velocity` and `wrap_frame`, in the steps of [`crate::space::motion::fly`]). A still picture at a time places it there
//! ([`ProductMover::object_at`]); the plugin flies it as an entity.

use super::{ProductObject, ProductShape};
use crate::geometry::Geometry;
use crate::space::motion::{MotionError, Mover};
use crate::space::product::{ProductSpace, ProductWalker};
use glam::DVec4;

/// A ball of a product scene that moves: the ball at time 0 (its shape the point of
/// `frame`), its frame then in the cell (the centre's axes carried to it, `z` the fibre)
/// and its velocity in that frame's axes. Its frame at a time is flown in the steps the
/// plugin's entities take ([`Mover::frame_at`]), so a still picture shows it where a walk
/// does.
pub type ProductMover = Mover<ProductObject>;

impl ProductMover {
    /// The ball where it is at `time` seconds.
    pub fn object_at(&self, space: &ProductSpace, time: f64) -> Result<ProductObject, MotionError> {
        Ok(ProductObject {
            shape: ProductShape::Point(self.frame_at(space, time)?.0.w_axis),
            ..self.object
        })
    }
}

/// The images of a ball through the faces it reaches past (within its radius): the point
/// the pairing of each such face carries it to, so that a ball crossing a face is drawn
/// whole from both sides. Other shapes have none.
#[must_use]
pub fn images_through_faces(
    space: &ProductSpace,
    walker: &ProductWalker<DVec4>,
    object: &ProductObject,
) -> Vec<ProductObject> {
    let ProductShape::Point(p) = object.shape else {
        return Vec::new();
    };
    let g = space.base();
    let pb = DVec4::new(p.x, p.y, 0.0, p.w);
    let norm = (pb.x * pb.x + pb.y * pb.y + g.kappa() * pb.w * pb.w)
        .abs()
        .sqrt();
    let unit = pb / norm.max(f64::MIN_POSITIVE);
    let half = 0.5 * space.length();
    let mut out = Vec::new();
    for (k, n) in walker.covectors.iter().enumerate() {
        let x = n.dot(unit);
        // The distance past the side's line (negative inside).
        let past = match g {
            Geometry::Spherical => x.clamp(-1.0, 1.0).asin(),
            _ => x.asinh(),
        };
        if past > -object.radius {
            out.push(ProductObject {
                shape: ProductShape::Point(walker.pairings[k] * p),
                ..*object
            });
        }
    }
    if p.z > half - object.radius {
        let mut q = walker.up.0 * p;
        q.z = p.z - space.length();
        out.push(ProductObject {
            shape: ProductShape::Point(q),
            ..*object
        });
    }
    if p.z < -half + object.radius {
        let mut q = walker.down.0 * p;
        q.z = p.z + space.length();
        out.push(ProductObject {
            shape: ProductShape::Point(q),
            ..*object
        });
    }
    out
}

/// Each mover where it is at `time` seconds, with its images through the faces it reaches
/// past; an error says why a time cannot be flown (negative, not finite, too long).
pub fn movers_at(
    space: &ProductSpace,
    movers: &[ProductMover],
    time: f64,
) -> Result<Vec<ProductObject>, MotionError> {
    let walker = ProductWalker::<DVec4>::new(space);
    let mut out = Vec::with_capacity(movers.len());
    for m in movers {
        let o = m.object_at(space, time)?;
        out.extend(images_through_faces(space, &walker, &o));
        out.push(o);
    }
    Ok(out)
}
