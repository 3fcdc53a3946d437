//! Colour textures: RGBA8 texels in sRGB, sampled bilinearly in linear RGB. The WGSL
//! tracer reads the same texels (from a GPU texture, or from the scene data buffer past the
//! texture slots) and filters them with the same formula (`sample_texture`), so CPU and GPU
//! pictures agree.

use crate::colour::srgb_channel_to_linear;
use glam::{DVec2, DVec3};
use std::path::Path;

/// The largest texture side accepted: the side every GPU's 2D textures are guaranteed to
/// reach. The GPU tracer binds a scene's first eight textures as textures of their own, so
/// an 8192×8192 picture (256 MiB) draws there too; further textures share the scene data
/// buffer's guaranteed 128 MiB with the meshes.
pub const MAX_TEXTURE_SIDE: u32 = 8192;

/// A texture could not be made.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    /// Cannot read the image `path`: `source`.
    #[error("cannot read the image {path}: {source}")]
    Read {
        path: String,
        #[source]
        source: image::ImageError,
    },
    /// The texture's size (width × height, attached) is empty or too large.
    #[error("the texture is {0}×{1} texels; it must be 1 to {MAX_TEXTURE_SIDE} on each side")]
    Size(u32, u32),
    /// The texel bytes (their count, width, height attached) do not make an RGBA8 texture of that size.
    #[error("{0} bytes of texels do not make a {1}×{2} RGBA8 texture")]
    Length(usize, u32, u32),
}

/// An RGBA8 texture in sRGB, its texels packed little-endian (`r | g << 8 | b << 16 | a << 24`)
/// row by row from the top.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Texels row by row, RGBA8 packed little-endian, sRGB-encoded.
    pub texels: Vec<u32>,
}

impl Texture {
    /// A texture of `width × height` RGBA8 texels (sRGB), rows from the top.
    pub fn from_rgba8(width: u32, height: u32, bytes: &[u8]) -> Result<Self, TextureError> {
        if width == 0 || height == 0 || width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
            return Err(TextureError::Size(width, height));
        }
        if bytes.len() != 4 * width as usize * height as usize {
            return Err(TextureError::Length(bytes.len(), width, height));
        }
        let texels = bytes
            .chunks_exact(4)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        Ok(Self {
            width,
            height,
            texels,
        })
    }

    /// A texture from an image in memory (any colour type; taken as sRGB).
    pub fn from_image(image: &image::DynamicImage) -> Result<Self, TextureError> {
        let rgba = image.to_rgba8();
        Self::from_rgba8(rgba.width(), rgba.height(), rgba.as_raw())
    }

    /// Reads a PNG (or another format the `image` crate was built with).
    pub fn load(path: &Path) -> Result<Self, TextureError> {
        let image = image::open(path).map_err(|source| TextureError::Read {
            path: path.display().to_string(),
            source,
        })?;
        Self::from_image(&image)
    }

    /// The linear colour of texel `(x, y)`.
    #[must_use]
    pub fn texel(&self, x: u32, y: u32) -> DVec3 {
        let t = self.texels[(y * self.width + x) as usize];
        let channel = |shift: u32| srgb_channel_to_linear(f64::from((t >> shift) & 0xff) / 255.0);
        DVec3::new(channel(0), channel(8), channel(16))
    }

    /// The linear colour at `uv` (u across, wrapping; v down, clamped), bilinear between
    /// the four nearest texel centres.
    #[must_use]
    pub fn sample(&self, uv: DVec2) -> DVec3 {
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let x = (uv.x - uv.x.floor()) * w - 0.5;
        let y = (uv.y.clamp(0.0, 1.0) * h - 0.5).clamp(0.0, h - 1.0);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let wrap = |i: f64| (i.rem_euclid(w)) as u32;
        let (xa, xb) = (wrap(x0), wrap(x0 + 1.0));
        let (ya, yb) = (y0 as u32, ((y0 + 1.0).min(h - 1.0)) as u32);
        let top = self.texel(xa, ya).lerp(self.texel(xb, ya), fx);
        let bottom = self.texel(xa, yb).lerp(self.texel(xb, yb), fx);
        top.lerp(bottom, fy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_between_texel_centres_and_wrapping_in_u() {
        // Black and white columns: halfway between the centres is the mean of the linear
        // values; across the seam u = 0 it wraps to the last column.
        let bytes = [0, 0, 0, 255, 255, 255, 255, 255];
        let t = Texture::from_rgba8(2, 1, &bytes).unwrap();
        assert!((t.sample(DVec2::new(0.25, 0.5)).x - 0.0).abs() < 1e-12);
        assert!((t.sample(DVec2::new(0.75, 0.5)).x - 1.0).abs() < 1e-12);
        assert!((t.sample(DVec2::new(0.5, 0.5)).x - 0.5).abs() < 1e-12);
        assert!((t.sample(DVec2::new(0.0, 0.5)).x - 0.5).abs() < 1e-12);
        assert!((t.sample(DVec2::new(1.25, 0.5)).x - 0.0).abs() < 1e-12);
    }

    #[test]
    fn bad_sizes_are_named() {
        assert!(matches!(
            Texture::from_rgba8(0, 4, &[]),
            Err(TextureError::Size(0, 4))
        ));
        assert!(matches!(
            Texture::from_rgba8(1, 1, &[1, 2, 3]),
            Err(TextureError::Length(3, 1, 1))
        ));
    }
}
