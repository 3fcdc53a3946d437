//! The player's avatar: a small dart-shaped ship round the eye, seen only where rays come
//! back round the space (a ray reaches the copy the eye sits in within a few times
//! the ship's radius and passes through it).

use super::mesh::{MeshSource, Model};
use super::shading::SurfaceMaterial;
use glam::DVec3;

/// The ship's length in model units (nose at `z = −1`, tail at `z = 0.5`).
pub(crate) const SHIP_LENGTH: f64 = 1.5;

/// Hits on the avatar nearer to the eye than this many times its radius are the eye's own
/// copy (with room for a stereo eye's offset) and are not drawn.
pub(crate) const SKIP_FACTOR: f64 = 2.0;

/// The ship: a dart pointing along `−z` (where the camera looks) with fins, a light hull
/// and a glowing engine at the back, the eye at the origin inside it.
#[must_use]
pub fn ship() -> Model {
    let nose = DVec3::new(0.0, 0.0, -1.0);
    let left = DVec3::new(-0.75, -0.05, 0.5);
    let right = DVec3::new(0.75, -0.05, 0.5);
    let top = DVec3::new(0.0, 0.3, 0.45);
    let bottom = DVec3::new(0.0, -0.18, 0.4);
    let positions = vec![nose, left, right, top, bottom];
    let (hull, engine) = (0, 1);
    let triangles = [
        ([0, 1, 3], hull),
        ([0, 3, 2], hull),
        ([0, 2, 4], hull),
        ([0, 4, 1], hull),
        ([1, 4, 3], engine),
        ([3, 4, 2], engine),
    ];
    let source = MeshSource {
        positions,
        normals: None,
        uvs: None,
        indices: triangles.iter().map(|t| t.0).collect(),
        materials: triangles.iter().map(|t| t.1).collect(),
    };
    Model {
        source,
        materials: vec![
            SurfaceMaterial {
                colour: DVec3::new(0.85, 0.86, 0.9),
                texture: None,
                emission: DVec3::ZERO,
                reflectance: 0.0,
            },
            SurfaceMaterial {
                colour: DVec3::new(0.3, 0.15, 0.05),
                texture: None,
                emission: DVec3::new(1.0, 0.45, 0.1),
                reflectance: 0.0,
            },
        ],
        textures: Vec::new(),
    }
}
