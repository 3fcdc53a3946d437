//! `bench --lighting`: what each way of gathering the lamps' light costs against what it
//! gets wrong. Per space, the default view is timed on the GPU with each lighting (the
//! nearest copy, every image within a few reaches with and without the tail, shadows capped
//! at a few counts), all in the same rounds, and each is rendered on the CPU against a
//! reference that sums every image within a long reach and shadows as many as it can.

use super::*;
use crate::scene::lighting::{LightPaths, Lighting};
use crate::trace::RenderSettings;

/// The CPU pictures the errors are measured on (small: the reference walks many shadow
/// rays per pixel).
pub const LIGHTING_ERROR_SIZE: (u32, u32) = (160, 90);

/// The reference lighting: every image within 16 inradii (or the 256 nearest, where fewer
/// reach that far), the tail beyond, the first 64 shadowed.
pub const REFERENCE_LIGHTING: Lighting = Lighting {
    paths: LightPaths::Images,
    reach_inradii: 16.0,
    tail: true,
    shadows: Lighting::MAX_SHADOWS,
    lamp_radius_inradii: 0.0,
    soft_samples: 1,
};

/// The soft shadows measured: a lamp of this radius (inradii), this many shadowed images.
pub const SOFT_LAMP: (f64, u32) = (0.25, 4);

/// The soft shadows' reference: the same lamp and shadowed images (so that only the
/// penumbra's sampling differs), with the most shadow rays.
pub const SOFT_REFERENCE: Lighting = Lighting {
    paths: LightPaths::Images,
    reach_inradii: Lighting::DEFAULT_REACH_INRADII,
    tail: true,
    shadows: SOFT_LAMP.1,
    lamp_radius_inradii: SOFT_LAMP.0,
    soft_samples: Lighting::MAX_SOFT_SAMPLES,
};

/// One lighting in one space: its frame time and its error against the reference.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LightingRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// What was measured: `nearest`, or `images R=…` with the tail and shadows.
    pub lighting: String,
    /// `nearest` or `images`.
    pub paths: String,
    /// The reach asked for, in inradii.
    pub reach_inradii: f64,
    /// The reach the images cover (shorter where the 256 nearest do not reach), in inradii.
    pub covered_inradii: f64,
    /// Images of the lamp summed per point (the light's `cover`; its images through the
    /// faces for `nearest`).
    pub images: usize,
    /// Whether the images beyond the reach are added by their mean.
    pub tail: bool,
    /// Images shadowed per point.
    pub shadows: u32,
    /// The lamp's radius in inradii (0: a point).
    pub lamp_radius_inradii: f64,
    /// Shadow rays per shadowed image (soft shadows; 1: hard).
    pub soft_samples: u32,
    /// What its error is measured against: `points` ([`REFERENCE_LIGHTING`]) or `soft`
    /// ([`SOFT_REFERENCE`], for a lamp with a radius).
    pub reference: String,
    /// Timed picture size.
    pub width: u32,
    /// Timed picture height.
    pub height: u32,
    /// Crossing budget per ray.
    pub budget: u32,
    /// Median GPU frame time, ms.
    pub median_ms: f64,
    /// The frame time as a multiple of the nearest copy's (the median over rounds of each
    /// round's ratio).
    pub time_ratio: f64,
    /// Mean colour error per channel against the reference, in 1/255.
    pub mean_error: f64,
    /// Share of pixels off by more than 8/255 in some channel.
    pub pixels_off: f64,
    /// Largest channel error, in 1/255.
    pub max_error: u8,
}

/// The lightings measured, in order; the first is the base of the time ratios.
fn lightings() -> Vec<(String, Lighting)> {
    let images = |reach_inradii: f64, tail: bool, shadows: u32| Lighting {
        paths: LightPaths::Images,
        reach_inradii,
        tail,
        shadows,
        ..Lighting::default()
    };
    let mut out = vec![("nearest".to_string(), Lighting::NEAREST)];
    for (reach, tail, shadows) in [
        (2.0, true, 0),
        (4.0, false, 0),
        (4.0, true, 0),
        (8.0, true, 0),
        (4.0, true, 4),
        (4.0, true, 16),
        (8.0, true, 16),
    ] {
        // No commas: the name is a CSV field.
        let name = format!(
            "images R={reach}{}{}",
            if tail { "" } else { " no tail" },
            if shadows > 0 {
                format!(" + {shadows} shadows")
            } else {
                String::new()
            }
        );
        out.push((name, images(reach, tail, shadows)));
    }
    // Soft shadows: one ray to the lamp's centre (the hard shadow), then a few over its disc.
    for samples in [1, 4, 8, 16] {
        out.push((
            format!(
                "images R=2 + {} shadows lamp {} rays {samples}",
                SOFT_LAMP.1, SOFT_LAMP.0
            ),
            Lighting {
                soft_samples: samples,
                ..SOFT_REFERENCE
            },
        ));
    }
    out
}

/// Mean channel error (1/255), share of pixels off by more than 8/255, largest error.
fn picture_error(a: &image::RgbImage, b: &image::RgbImage) -> (f64, f64, u8) {
    let (mut sum, mut off, mut max) = (0u64, 0usize, 0u8);
    for (p, q) in a.pixels().zip(b.pixels()) {
        let mut worst = 0u8;
        for c in 0..3 {
            let d = p.0[c].abs_diff(q.0[c]);
            sum += u64::from(d);
            worst = worst.max(d);
        }
        max = max.max(worst);
        if worst > 8 {
            off += 1;
        }
    }
    let n = (a.width() * a.height()).max(1) as f64;
    (sum as f64 / (3.0 * n), off as f64 / n, max)
}

/// Times and measures every lighting for each of `config.spaces` at the first of
/// `config.budgets` and the middle of `config.sizes` ([`LightingRow`]).
pub fn run_lighting(
    config: &BenchConfig,
    progress: &ProgressBar,
) -> Result<BenchReport, BenchError> {
    let budget = super::runs::single_budget(config)?;
    let variants = lightings();
    let mut harness = Harness::new()?;
    progress.set_length((config.spaces.len() * (variants.len() + 1)) as u64);
    let mut report = BenchReport::empty(Some(&harness));
    let (ew, eh) = LIGHTING_ERROR_SIZE;
    let settings = RenderSettings {
        width: ew,
        height: eh,
        max_crossings: budget as usize,
    };
    for id in &config.spaces {
        let subject = Subject::new(id)?;
        let lit = |lighting: Lighting| -> Result<CurvedScene, BenchError> {
            let mut scene = subject.scene(DEFAULT_FOG_FACTOR);
            scene
                .set_lighting(&subject.space, lighting)
                .map_err(BenchError::Lighting)?;
            Ok(scene)
        };
        announce(progress, format!("{}: the reference lighting", subject.id));
        let reference = crate::trace::render(
            &subject.space,
            &lit(REFERENCE_LIGHTING)?,
            &subject.camera,
            &settings,
        );
        progress.inc(1);
        announce(
            progress,
            format!("{}: the soft shadows' reference", subject.id),
        );
        let soft_reference = crate::trace::render(
            &subject.space,
            &lit(SOFT_REFERENCE)?,
            &subject.camera,
            &settings,
        );
        let mut scenes = Vec::new();
        let mut packed = Vec::new();
        for (name, lighting) in &variants {
            announce(progress, format!("{}: {name}", subject.id));
            let scene = lit(*lighting)?;
            packed.push(subject.pack(&scene, budget)?);
            let picture = crate::trace::render(&subject.space, &scene, &subject.camera, &settings);
            let against = if lighting.lamp_radius_inradii > 0.0 {
                &soft_reference
            } else {
                &reference
            };
            scenes.push((scene, picture_error(&picture, against)));
            progress.inc(1);
        }
        let (w, h) = config.middle_size();
        let layout = subject.camera.layout(w, h);
        let refs: Vec<&GpuScene> = packed.iter().collect();
        let runs = drawn_views(&mut harness, &layout, (w, h), &refs)?;
        let programs: Vec<(&Program, &Frame)> = runs.iter().map(|(p, f)| (p, f)).collect();
        let times = time_rounds(&mut harness, &programs, config)?;
        for (k, ((name, lighting), (scene, (mean_error, pixels_off, max_error)))) in
            variants.iter().zip(&scenes).enumerate()
        {
            let light = &scene.lights[0];
            let nearest = lighting.paths == LightPaths::Nearest;
            report.lighting.push(LightingRow {
                space: subject.id.clone(),
                geometry: subject.geometry(),
                lighting: name.clone(),
                paths: lighting.paths.name().to_string(),
                reach_inradii: lighting.reach_inradii,
                covered_inradii: light.reach / subject.inradius,
                images: if nearest {
                    light.images.len()
                } else {
                    light.cover.len()
                },
                tail: lighting.tail,
                shadows: lighting.shadows,
                lamp_radius_inradii: lighting.lamp_radius_inradii,
                soft_samples: lighting.soft_samples,
                reference: if lighting.lamp_radius_inradii > 0.0 {
                    "soft"
                } else {
                    "points"
                }
                .to_string(),
                width: w,
                height: h,
                budget,
                median_ms: Stats::of(times[k].clone()).median,
                time_ratio: paired_ratio(&times[k], &times[0]),
                mean_error: *mean_error,
                pixels_off: *pixels_off,
                max_error: *max_error,
            });
        }
    }
    progress.finish_and_clear();
    Ok(report)
}

/// The lighting table of the summary.
pub(super) fn lighting_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    if report.lighting.is_empty() {
        return;
    }
    let (ew, eh) = LIGHTING_ERROR_SIZE;
    let _ = writeln!(
        *md,
        "\n### Light through the manifold: frame time against error per lighting\n\nEach lighting of the default view timed in the same rounds (× nearest: the median over rounds of each round's ratio), and its CPU picture at {ew}×{eh} against a reference: for point lamps (reference `points`) every image within {} inradii (at most 256), the tail and {} shadows; for the soft shadows of a lamp of {} inradii (reference `soft`) the same lamp and {} shadowed images with {} rays each, so that only the penumbra's sampling differs.\n\n| space | lighting | images | covered (inradii) | ms | × nearest | reference | mean error /255 | pixels off > 8/255 | max /255 |\n|---|---|---:|---:|---:|---:|---|---:|---:|---:|",
        REFERENCE_LIGHTING.reach_inradii,
        REFERENCE_LIGHTING.shadows,
        SOFT_REFERENCE.lamp_radius_inradii,
        SOFT_REFERENCE.shadows,
        SOFT_REFERENCE.soft_samples
    );
    for r in &report.lighting {
        let _ = writeln!(
            *md,
            "| {} | {} | {} | {} | {:.2} | {:.2}× | {} | {:.2} | {:.2} % | {} |",
            r.space,
            r.lighting,
            r.images,
            // The nearest copy sums no images in the cover: it covers no reach.
            if r.paths == "nearest" {
                "–".to_string()
            } else {
                format!("{:.2}", r.covered_inradii)
            },
            r.median_ms,
            r.time_ratio,
            r.reference,
            r.mean_error,
            100.0 * r.pixels_off,
            r.max_error
        );
    }
}

/// Error against time, a line per space through its lightings from the cheapest.
pub(super) fn lighting_chart(report: &BenchReport) -> Option<Chart> {
    if report.lighting.is_empty() {
        return None;
    }
    let mut spaces: Vec<&str> = report.lighting.iter().map(|r| r.space.as_str()).collect();
    spaces.dedup();
    let series = spaces
        .iter()
        .map(|s| {
            let mut points: Vec<(f64, f64)> = report
                .lighting
                .iter()
                // Against the one reference of point lamps (the soft rows have their own).
                .filter(|r| r.space == *s && r.reference == "points")
                .map(|r| (r.time_ratio, r.mean_error.max(1e-3)))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series {
                name: (*s).to_string(),
                points,
                dashed: false,
            }
        })
        .collect();
    Some(Chart {
        title: "Lighting: error against frame time".into(),
        x_label: "frame time × the nearest copy's".into(),
        y_label: "mean error against the reference (1/255)".into(),
        log_x: true,
        log_y: true,
        series,
        legend: Corner::UpperRight,
    })
}
