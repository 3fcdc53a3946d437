//! Helpers shared by the test crates: comparing pictures, serialising GPU work, scratch
//! folders.

use image::RgbImage;
use std::path::PathBuf;

/// How two pictures of the same size differ.
#[derive(Clone, Copy, Debug)]
pub struct Comparison {
    /// Fraction of the pixels with a channel off by more than the tolerance.
    pub differing: f64,
    /// Pixels with a channel off by more than the tolerance.
    pub differing_pixels: usize,
    /// Mean absolute channel error, in levels of 255.
    pub mean_error: f64,
    /// Largest channel error.
    pub max_error: u8,
}

/// Compares two pictures channel by channel; a pixel differs when a channel is off by more
/// than `tolerance` (of 255). Also returns a difference picture: differing pixels magenta,
/// the others their error ×16.
pub fn compare(a: &RgbImage, b: &RgbImage, tolerance: u8) -> (Comparison, RgbImage) {
    assert_eq!(
        a.dimensions(),
        b.dimensions(),
        "pictures of different sizes"
    );
    let mut diff = RgbImage::new(a.width(), a.height());
    let (mut differing, mut sum, mut max) = (0usize, 0u64, 0u8);
    for ((p, q), d) in a.pixels().zip(b.pixels()).zip(diff.pixels_mut()) {
        let e: [u8; 3] = std::array::from_fn(|k| p.0[k].abs_diff(q.0[k]));
        let worst = *e.iter().max().expect("three channels");
        sum += e.iter().map(|&x| u64::from(x)).sum::<u64>();
        max = max.max(worst);
        if worst > tolerance {
            differing += 1;
            *d = image::Rgb([255, 0, 255]);
        } else {
            *d = image::Rgb(e.map(|x| x.saturating_mul(16)));
        }
    }
    let n = f64::from(a.width() * a.height());
    (
        Comparison {
            differing: differing as f64 / n,
            differing_pixels: differing,
            mean_error: sum as f64 / (3.0 * n),
            max_error: max,
        },
        diff,
    )
}

/// The fraction of pixels with a channel off by more than `tolerance`.
pub fn differing_fraction(a: &RgbImage, b: &RgbImage, tolerance: u8) -> f64 {
    compare(a, b, tolerance).0.differing
}

/// One GPU render at a time: several headless apps rendering at once on lavapipe starve each
/// other's frames (a capture then raced the tracer now and then).
pub fn gpu_lock() -> std::sync::MutexGuard<'static, ()> {
    static GPU: std::sync::Mutex<()> = std::sync::Mutex::new(());
    GPU.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// A fresh scratch folder for one test under the target directory's temporary folder.
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir =
        PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create a scratch folder");
    dir
}

/// The number literals a fuzz mutation puts in place of a number (scene files, glTF,
/// generator files).
pub const HOSTILE: [&str; 10] = [
    "nan",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "1e-320",
    "0",
    "-1",
    "123456789",
    "-0.0",
];

/// The largest deviation of a product frame's columns (right, up, back) from orthonormal in
/// the product metric of the surface's geometry `g`.
pub fn product_frame_defect(g: bevy_curved_spaces::geometry::Geometry, f: glam::DMat4) -> f64 {
    bevy_curved_spaces::space::product::motion::product_frame_defect(g, f)
}

/// A space by id (a seed space or one of the library's), with the default Dirichlet options.
pub fn library_space(id: &str) -> bevy_curved_spaces::space::Space {
    bevy_curved_spaces::space::resolve_space(
        id,
        std::path::Path::new(""),
        &bevy_curved_spaces::space::dirichlet::DirichletOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{id}: {e}"))
}

/// A product space (H²×R, S²×R) by id; panics naming the id where it is not one.
pub fn product(id: &str) -> bevy_curved_spaces::space::product::ProductSpace {
    match bevy_curved_spaces::space::product::product_space(id) {
        Some(Ok(bevy_curved_spaces::space::product::ProductOrFlat::Product(p))) => *p,
        other => panic!("{id} is not a product space: {other:?}"),
    }
}

/// The constant-curvature space a plugin app shows.
pub fn shown_constant(app: &bevy::app::App) -> std::sync::Arc<bevy_curved_spaces::space::Space> {
    app.world()
        .resource::<bevy_curved_spaces::plugin::components::ActiveSpace>()
        .constant()
        .expect("a constant-curvature space is shown")
        .clone()
}

/// The product space a plugin app shows.
pub fn shown_product(
    app: &bevy::app::App,
) -> std::sync::Arc<bevy_curved_spaces::space::product::ProductSpace> {
    app.world()
        .resource::<bevy_curved_spaces::plugin::components::ActiveSpace>()
        .product()
        .expect("a product space is shown")
        .clone()
}
