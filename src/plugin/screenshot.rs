//! Saving a captured frame (Bevy's `Screenshot`) as a PNG: the panel's F12, `walk
//! --screenshot` and the offscreen renders read pictures back the same way.

use bevy::prelude::Image;
use image::RgbImage;

/// A captured picture as 8-bit RGB; the error says why it cannot be converted.
pub fn image_to_rgb(image: &Image) -> Result<RgbImage, String> {
    let dynamic = image
        .clone()
        .try_into_dynamic()
        .map_err(|e| e.to_string())?;
    Ok(dynamic.to_rgb8())
}

/// Writes a captured picture (a screenshot) as an 8-bit RGB PNG, whole or not at all
/// (`files::write_png`); the error says what failed.
pub fn save_screenshot(image: &Image, path: &std::path::Path) -> Result<(), String> {
    let rgb = image_to_rgb(image)?;
    crate::files::write_png(path, &rgb).map_err(|e| e.to_string())
}
