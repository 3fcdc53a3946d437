//! The sRGB transfer function, both ways: textures are decoded with it and anaglyphs are
//! mixed in linear light with it (the shader has the same formulas).

use glam::DVec3;

/// The linear value of an sRGB-encoded channel in [0, 1] (the shader's `srgb_to_linear`).
#[must_use]
pub fn srgb_channel_to_linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The sRGB transfer function's inverse (encoded → linear), per channel.
#[must_use]
pub fn srgb_to_linear(c: DVec3) -> DVec3 {
    DVec3::new(
        srgb_channel_to_linear(c.x),
        srgb_channel_to_linear(c.y),
        srgb_channel_to_linear(c.z),
    )
}

/// The sRGB transfer function (linear → encoded), per channel.
#[must_use]
pub fn linear_to_srgb(c: DVec3) -> DVec3 {
    let f = |c: f64| {
        if c <= 0.0031308 {
            12.92 * c
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        }
    };
    DVec3::new(f(c.x), f(c.y), f(c.z))
}
