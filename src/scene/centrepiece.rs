//! The default scene's centrepieces that are more than plain objects: the spinning globe
//! (the built-in Earth-like texture) and the spiral galaxy (one mesh of small glowing stars).
//! See [`Centrepiece`](crate::scene::Centrepiece).

use crate::geometry::Geometry;
use crate::random::SplitMix64;
use crate::scene::mesh::MeshSource;
use crate::scene::texture::Texture;
use crate::scene::{Model, SurfaceMaterial};
use glam::{DVec2, DVec3};
use std::sync::{Arc, OnceLock};

/// The globe's texture, built into the crate (`assets/textures/globe.png`).
const GLOBE_PNG: &[u8] = include_bytes!("../../assets/textures/globe.png");

/// The globe centrepiece's spin, radians per second.
pub const GLOBE_SPIN: f64 = 0.25;

/// The built-in globe texture, decoded once.
#[must_use]
pub fn globe_texture() -> Arc<Texture> {
    static TEXTURE: OnceLock<Arc<Texture>> = OnceLock::new();
    TEXTURE
        .get_or_init(|| {
            let image = image::load_from_memory(GLOBE_PNG).expect("the built-in globe is a PNG");
            Arc::new(Texture::from_image(&image).expect("the built-in globe fits a texture"))
        })
        .clone()
}

/// Stars in the galaxy: a bulge and two arms.
pub const GALAXY_STARS: usize = 900;

/// A star's size (its octahedron's half-diagonal) in units of the galaxy's radius.
const STAR_SIZE: f64 = 0.02;

/// A spiral galaxy of radius 1 (model units) in the `xz` plane: [`GALAXY_STARS`] small
/// octahedra with emissive materials (yellow-white bulge, blue-white arms, pink star-forming
/// knots), placed by a fixed random sequence so that every scene and both tracers see the
/// same stars. Placed as one mesh ([`crate::scene::CurvedScene::add_model`]), its hierarchy
/// is the galaxy's own bounds test: a ray that misses the galaxy's box costs one box test.
#[must_use]
pub fn galaxy_model() -> Model {
    let mut rng = SplitMix64(0x6a1a_c7e5);
    let mut source = MeshSource::default();
    let gaussian = |rng: &mut SplitMix64| {
        // Box–Muller, one of the pair.
        let (u, v) = (rng.unit().max(1e-12), rng.unit());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    };
    let bulge = GALAXY_STARS / 4;
    for k in 0..GALAXY_STARS {
        let (centre, material, size) = if k < bulge {
            let r = (0.16 * gaussian(&mut rng)).abs().min(0.4);
            let d = rng.direction();
            (DVec3::new(d.x, 0.55 * d.y, d.z) * r, 0, 1.2)
        } else {
            let arm = (k % 2) as f64 * std::f64::consts::PI;
            let r = 0.18 + 0.8 * rng.unit().powf(0.8);
            // A logarithmic spiral, jittered more near the centre.
            let angle = arm + 1.9 * (r / 0.18).ln() + 0.35 * gaussian(&mut rng) * (1.1 - r);
            let y = 0.03 * gaussian(&mut rng);
            let material = match rng.unit() {
                u if u < 0.12 => 3,
                u if u < 0.45 => 2,
                _ => 1,
            };
            (
                DVec3::new(r * angle.cos(), y, r * angle.sin()),
                material,
                1.0,
            )
        };
        source.append(octahedron(centre, STAR_SIZE * size, material));
    }
    let glow = |c: DVec3| SurfaceMaterial {
        colour: DVec3::ZERO,
        texture: None,
        emission: c,
        reflectance: 0.0,
    };
    Model {
        source,
        materials: vec![
            glow(DVec3::new(1.0, 0.85, 0.55)),
            glow(DVec3::new(0.65, 0.78, 1.0)),
            glow(DVec3::new(0.95, 0.95, 1.0)),
            glow(DVec3::new(1.0, 0.45, 0.7)),
        ],
        textures: Vec::new(),
    }
}

/// An octahedron of half-diagonal `h` centred at `c`, 8 triangles of `material`.
fn octahedron(c: DVec3, h: f64, material: u32) -> MeshSource {
    let axes = [
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ];
    let mut indices = Vec::new();
    for x in [0u32, 1] {
        for y in [2u32, 3] {
            for z in [4u32, 5] {
                // Counter-clockwise seen from outside: flip where the octant's parity flips.
                if (x + y + z) % 2 == 0 {
                    indices.push([x, y, z]);
                } else {
                    indices.push([x, z, y]);
                }
            }
        }
    }
    MeshSource {
        positions: axes.iter().map(|a| c + *a * h).collect(),
        normals: None,
        uvs: Some(vec![DVec2::ZERO; 6]),
        indices,
        materials: vec![material; 8],
    }
}

/// The galaxy's radius for a cell whose inradius, capped as the centrepieces are
/// ([`crate::space::invariants::inradius_at_most`] with π/4), is `inradius` (the gyroscope's
/// ring is 0.45 inradii): well inside the cell, so it has no images.
#[must_use]
pub fn galaxy_radius(inradius: f64) -> f64 {
    0.55 * inradius
}

/// The frame the centrepiece at the cell's centre is turned by: tilted towards the default
/// view, so that a disc or an axis is seen at an angle.
#[must_use]
pub fn centrepiece_tilt(geometry: Geometry) -> glam::DMat4 {
    let _ = geometry;
    glam::DMat4::from_rotation_z(0.41) * glam::DMat4::from_rotation_x(0.5)
}
