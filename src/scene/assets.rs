//! The project's own assets, made by code: the globe's texture (an invented planet), a
//! textured cube and a torus knot. `cargo run --example generate_assets` writes them under
//! `assets/`; the benchmark and tests make meshes of any size the same way.

use super::mesh::MeshSource;
use glam::{DVec2, DVec3};
use image::{Rgba, RgbaImage};

/// A smooth value noise on R³ (trilinear between hashed lattice values, smoothstepped).
fn noise(p: DVec3) -> f64 {
    let hash = |x: i64, y: i64, z: i64| {
        let mut h = (x.wrapping_mul(73_856_093)
            ^ y.wrapping_mul(19_349_663)
            ^ z.wrapping_mul(83_492_791)) as u64;
        h ^= h >> 33;
        h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
        h ^= h >> 33;
        (h & 0xffff) as f64 / 65535.0
    };
    let f = p.floor();
    let t = p - f;
    let s = t * t * (DVec3::splat(3.0) - 2.0 * t);
    let (x, y, z) = (f.x as i64, f.y as i64, f.z as i64);
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let c = |dx, dy, dz| hash(x + dx, y + dy, z + dz);
    lerp(
        lerp(
            lerp(c(0, 0, 0), c(1, 0, 0), s.x),
            lerp(c(0, 1, 0), c(1, 1, 0), s.x),
            s.y,
        ),
        lerp(
            lerp(c(0, 0, 1), c(1, 0, 1), s.x),
            lerp(c(0, 1, 1), c(1, 1, 1), s.x),
            s.y,
        ),
        s.z,
    )
}

fn fractal(p: DVec3) -> f64 {
    (0..6)
        .map(|o| {
            noise(p * f64::from(1 << o) + DVec3::splat(17.0 * f64::from(o))) / f64::from(1 << o)
        })
        .sum::<f64>()
        / 1.96875
}

/// An equirectangular picture of an invented planet (`width × height`, longitude across
/// from −180°, north up): seas, continents, ice caps, a faint graticule every 30° and a red
/// prime meridian, so that orientation and spin read at a glance.
#[must_use]
pub fn globe_texture(width: u32, height: u32) -> RgbaImage {
    RgbaImage::from_fn(width, height, |i, j| {
        let lon =
            (f64::from(i) + 0.5) / f64::from(width) * std::f64::consts::TAU - std::f64::consts::PI;
        let colat = (f64::from(j) + 0.5) / f64::from(height) * std::f64::consts::PI;
        // The point on the unit sphere in the ball's frame (BallTexture::uv's convention).
        let d = DVec3::new(
            colat.sin() * lon.sin(),
            colat.cos(),
            colat.sin() * lon.cos(),
        );
        let h = fractal(d * 2.2 + DVec3::splat(5.0));
        let lat = 90.0 - colat.to_degrees();
        let mut c = if lat.abs() + 12.0 * h > 76.0 {
            DVec3::new(0.93, 0.95, 0.97)
        } else if h > 0.53 {
            let t = ((h - 0.53) / 0.2).min(1.0);
            DVec3::new(0.2, 0.55, 0.18).lerp(DVec3::new(0.62, 0.5, 0.3), t)
        } else {
            let t = (h / 0.53).powi(3);
            DVec3::new(0.03, 0.1, 0.35).lerp(DVec3::new(0.1, 0.38, 0.62), t)
        };
        let lon_deg = lon.to_degrees();
        let near = |x: f64, step: f64| {
            let r = (x / step).round() * step;
            (x - r).abs()
        };
        let px = 360.0 / f64::from(width);
        if lon_deg.abs() < 1.2 * px {
            c = DVec3::new(0.9, 0.1, 0.1);
        } else if near(lon_deg, 30.0) < 0.6 * px || near(lat, 30.0) < 0.6 * px {
            c = c.lerp(DVec3::ONE, 0.35);
        }
        let b = c
            .to_array()
            .map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8);
        Rgba([b[0], b[1], b[2], 255])
    })
}

/// A crate-like texture for the cube: a light board with a dark frame and a diagonal, the
/// corner at `u = v = 0` marked red (so a face's orientation shows).
#[must_use]
pub fn crate_texture(size: u32) -> RgbaImage {
    RgbaImage::from_fn(size, size, |i, j| {
        let (u, v) = (
            (f64::from(i) + 0.5) / f64::from(size),
            (f64::from(j) + 0.5) / f64::from(size),
        );
        let frame = u.min(v).min(1.0 - u).min(1.0 - v) < 0.1;
        let diagonal = (u - v).abs() < 0.06;
        let corner = u < 0.2 && v < 0.2;
        let c: [u8; 3] = if corner {
            [200, 40, 30]
        } else if frame || diagonal {
            [110, 70, 35]
        } else {
            let grain = (noise(DVec3::new(u * 3.0, v * 40.0, 0.5)) * 40.0) as u8;
            [190 + grain / 2, 150 + grain / 2, 90 + grain / 3]
        };
        Rgba([c[0], c[1], c[2], 255])
    })
}

/// A `(p, q)` torus knot tube: `segments` steps along the knot, `sides` round the tube, with
/// smooth normals and texture coordinates; `2·segments·sides` triangles.
#[must_use]
pub fn torus_knot(p: u32, q: u32, segments: u32, sides: u32) -> MeshSource {
    let (p, q) = (f64::from(p), f64::from(q));
    let curve = |t: f64| {
        let r = 0.6 + 0.25 * (q * t).cos();
        DVec3::new(r * (p * t).cos(), 0.25 * (q * t).sin(), r * (p * t).sin())
    };
    let tube = 0.12;
    let mut s = MeshSource::default();
    let (mut normals, mut uvs) = (Vec::new(), Vec::new());
    for i in 0..segments {
        let t = f64::from(i) / f64::from(segments) * std::f64::consts::TAU;
        let c = curve(t);
        let tangent = (curve(t + 1e-4) - curve(t - 1e-4)).normalize();
        let n = (curve(t + 1e-4) + curve(t - 1e-4) - 2.0 * c).normalize_or(DVec3::Y);
        let n = (n - tangent * n.dot(tangent)).normalize();
        let b = tangent.cross(n);
        for k in 0..sides {
            let a = f64::from(k) / f64::from(sides) * std::f64::consts::TAU;
            let dir = n * a.cos() + b * a.sin();
            s.positions.push(c + dir * tube);
            normals.push(dir);
            uvs.push(DVec2::new(
                f64::from(i) / f64::from(segments),
                f64::from(k) / f64::from(sides),
            ));
        }
    }
    for i in 0..segments {
        for k in 0..sides {
            let at = |i: u32, k: u32| (i % segments) * sides + (k % sides);
            let (a, b, c, d) = (at(i, k), at(i + 1, k), at(i + 1, k + 1), at(i, k + 1));
            s.indices.push([a, b, c]);
            s.indices.push([a, c, d]);
            s.materials.extend([0, 0]);
        }
    }
    s.normals = Some(normals);
    s.uvs = Some(uvs);
    s
}

/// A PNG file's bytes of an image.
#[must_use]
pub fn png_bytes(image: &RgbaImage) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut out, image::ImageFormat::Png)
        .expect("encoding a PNG in memory cannot fail");
    out.into_inner()
}

/// Writes a mesh source (one material) as a `.glb`.
#[cfg(feature = "gltf")]
pub fn write_source_glb(
    path: &std::path::Path,
    source: &MeshSource,
    base_colour: [f32; 4],
    texture_png: Option<&[u8]>,
) -> std::io::Result<()> {
    let f3 = |v: &DVec3| v.as_vec3().to_array();
    let positions: Vec<[f32; 3]> = source.positions.iter().map(f3).collect();
    let normals: Option<Vec<[f32; 3]>> =
        source.normals.as_ref().map(|n| n.iter().map(f3).collect());
    let uvs: Option<Vec<[f32; 2]>> = source
        .uvs
        .as_ref()
        .map(|u| u.iter().map(|t| t.as_vec2().to_array()).collect());
    let indices: Vec<u32> = source.indices.iter().flatten().copied().collect();
    super::gltf::write_glb(
        path,
        &super::gltf::GlbMesh {
            positions: &positions,
            normals: normals.as_deref(),
            uvs: uvs.as_deref(),
            indices: &indices,
            base_colour,
            emission: [0.0; 3],
            texture_png,
            omit_positions: false,
        },
    )
}
