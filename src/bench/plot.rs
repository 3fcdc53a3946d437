//! The benchmark's charts: lines of points with optional log axes, written as PNG (drawn
//! into an RGB buffer, encoded with `image`) and SVG. Text uses the font egui ships
//! (Ubuntu Light), so no system font libraries are needed.

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// One named line of a chart.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// Drawn dashed and without markers (a bound, not a measurement).
    pub dashed: bool,
}

/// A chart: title, axis labels, log axes and its lines.
#[derive(Clone, Debug, PartialEq)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_x: bool,
    pub log_y: bool,
    pub series: Vec<Series>,
}

/// The chart could not be drawn or written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    #[error("drawing the chart {0} failed: {1}")]
    Draw(String, String),
    #[error("writing {0} failed: {1}")]
    Write(String, String),
}

const FONT: &str = "sans-serif";

/// Distinct, dark-enough line colours (Tableau 10).
const COLOURS: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];
const SIZE: (u32, u32) = (900, 560);

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bytes are a valid TrueType font shipped by egui; if registration failed the
        // charts would only lose their text, so the error is not fatal.
        let _ = plotters::style::register_font(
            FONT,
            FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        );
    });
}

/// Writes `chart` to `stem.png` and `stem.svg`.
pub fn write_chart(chart: &Chart, stem: &Path) -> Result<(), PlotError> {
    register_font();
    let png = stem.with_extension("png");
    let svg = stem.with_extension("svg");
    let mut buffer = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, SIZE).into_drawing_area();
        draw(chart, &root)?;
        root.present()
            .map_err(|e| PlotError::Draw(chart.title.clone(), e.to_string()))?;
    }
    image::save_buffer(
        &png,
        &buffer,
        SIZE.0,
        SIZE.1,
        image::ExtendedColorType::Rgb8,
    )
    .map_err(|e| PlotError::Write(png.display().to_string(), e.to_string()))?;
    {
        let root = SVGBackend::new(&svg, SIZE).into_drawing_area();
        draw(chart, &root)?;
        root.present()
            .map_err(|e| PlotError::Write(svg.display().to_string(), e.to_string()))?;
    }
    Ok(())
}

/// The range of the values on one axis, padded; positive values only on a log axis.
fn axis_range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        (lo, hi) = if log { (0.1, 10.0) } else { (0.0, 1.0) };
    }
    if log {
        (lo / 1.6, hi * 1.6)
    } else {
        let pad = ((hi - lo) * 0.06).max(1e-12);
        (lo - pad, hi + pad)
    }
}

fn draw<DB: DrawingBackend>(chart: &Chart, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    let fail = |e: &dyn std::fmt::Display| PlotError::Draw(chart.title.clone(), e.to_string());
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let points = || chart.series.iter().flat_map(|s| s.points.iter());
    let x = axis_range(points().map(|p| p.0), chart.log_x);
    let y = axis_range(points().map(|p| p.1), chart.log_y);
    let mut builder = ChartBuilder::on(root);
    builder
        .caption(&chart.title, (FONT, 24))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(78);
    // One drawing routine for the four axis kinds.
    macro_rules! plot_with {
        ($x:expr, $y:expr) => {{
            let mut ctx = builder.build_cartesian_2d($x, $y).map_err(|e| fail(&e))?;
            ctx.configure_mesh()
                .x_desc(chart.x_label.as_str())
                .y_desc(chart.y_label.as_str())
                .label_style((FONT, 15))
                .axis_desc_style((FONT, 17))
                .draw()
                .map_err(|e| fail(&e))?;
            for (i, s) in chart.series.iter().enumerate() {
                let (r, g, b) = COLOURS[i % COLOURS.len()];
                let colour = RGBColor(r, g, b).to_rgba();
                let pts: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .copied()
                    .filter(|(a, b)| {
                        a.is_finite()
                            && b.is_finite()
                            && (!chart.log_x || *a > 0.0)
                            && (!chart.log_y || *b > 0.0)
                    })
                    .collect();
                if s.dashed {
                    ctx.draw_series(DashedLineSeries::new(pts, 8, 6, colour.stroke_width(2)))
                        .map_err(|e| fail(&e))?
                        .label(s.name.as_str())
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
                        });
                } else {
                    ctx.draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2)))
                        .map_err(|e| fail(&e))?
                        .label(s.name.as_str())
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
                        });
                    ctx.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, colour.filled())))
                        .map_err(|e| fail(&e))?;
                }
            }
            ctx.configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.4))
                .label_font((FONT, 14))
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(|e| fail(&e))?;
        }};
    }
    match (chart.log_x, chart.log_y) {
        (false, false) => plot_with!(x.0..x.1, y.0..y.1),
        (true, false) => plot_with!((x.0..x.1).log_scale(), y.0..y.1),
        (false, true) => plot_with!(x.0..x.1, (y.0..y.1).log_scale()),
        (true, true) => plot_with!((x.0..x.1).log_scale(), (y.0..y.1).log_scale()),
    }
    Ok(())
}
