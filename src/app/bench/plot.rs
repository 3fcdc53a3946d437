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
    /// Legend entry.
    pub name: String,
    /// The points, in order.
    pub points: Vec<(f64, f64)>,
    /// Drawn dashed and without markers (a bound, not a measurement).
    pub dashed: bool,
}

/// A chart: title, axis labels, log axes and its lines.
#[derive(Clone, Debug, PartialEq)]
pub struct Chart {
    /// The chart's title.
    pub title: String,
    /// Label of the x axis.
    pub x_label: String,
    /// Label of the y axis.
    pub y_label: String,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// The lines.
    pub series: Vec<Series>,
    /// Where the legend goes (a corner the lines leave free).
    pub legend: Corner,
}

/// A corner of the plotting area.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Corner {
    /// Top left.
    UpperLeft,
    /// Top right.
    UpperRight,
    /// Bottom left.
    LowerLeft,
    /// Bottom right.
    LowerRight,
}

/// An axis label: plain numbers from 0.001 to 9999 (up to three significant digits, no
/// trailing zeros), powers of ten in `1e-5` form outside.
fn tick(v: f64) -> String {
    let a = v.abs();
    // A linear axis through zero puts its tick at a rounding residue like -2e-16.
    if a < 1e-15 {
        return "0".into();
    }
    if (1e-3..1e4).contains(&a) {
        let digits = (2 - a.log10().floor() as i32).max(0) as usize;
        let text = format!("{v:.digits$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            text
        }
    } else {
        format!("{v:.0e}")
    }
}

/// The chart could not be drawn or written.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// Drawing a chart failed (its name and the reason are attached).
    #[error("drawing the chart {0} failed: {1}")]
    Draw(String, String),
    /// Writing a file failed (its path and the reason are attached).
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
    let picture = image::RgbImage::from_raw(SIZE.0, SIZE.1, buffer)
        .ok_or_else(|| PlotError::Draw(chart.title.clone(), "wrong buffer size".into()))?;
    crate::files::write_png(&png, &picture)
        .map_err(|e| PlotError::Write(png.display().to_string(), e.to_string()))?;
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, SIZE).into_drawing_area();
        draw(chart, &root)?;
        root.present()
            .map_err(|e| PlotError::Write(svg.display().to_string(), e.to_string()))?;
    }
    crate::files::write_atomic(&svg, text.as_bytes())
        .map_err(|e| PlotError::Write(svg.display().to_string(), e.to_string()))?;
    Ok(())
}

/// The range of the values on one axis (already log10 on a log axis), padded.
fn axis_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.06).max(0.05);
    (lo - pad, hi + pad)
}

/// A log axis is drawn as a linear axis of log10 values with labels `10^v`.
fn to_axis(v: f64, log: bool) -> f64 {
    if log { v.log10() } else { v }
}

fn draw<DB: DrawingBackend>(chart: &Chart, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    let fail = |e: &dyn std::fmt::Display| PlotError::Draw(chart.title.clone(), e.to_string());
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let series: Vec<(&Series, Vec<(f64, f64)>)> = chart
        .series
        .iter()
        .map(|s| {
            let pts = s
                .points
                .iter()
                .filter(|(a, b)| (!chart.log_x || *a > 0.0) && (!chart.log_y || *b > 0.0))
                .map(|&(a, b)| (to_axis(a, chart.log_x), to_axis(b, chart.log_y)))
                .filter(|(a, b)| a.is_finite() && b.is_finite())
                .collect();
            (s, pts)
        })
        .collect();
    let x = axis_range(series.iter().flat_map(|s| s.1.iter().map(|p| p.0)));
    let y = axis_range(series.iter().flat_map(|s| s.1.iter().map(|p| p.1)));
    let label = |v: f64, log: bool| tick(if log { 10f64.powf(v) } else { v });
    let mut ctx = ChartBuilder::on(root)
        .caption(&chart.title, (FONT, 24))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(78)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(|e| fail(&e))?;
    ctx.configure_mesh()
        .x_labels(10)
        .y_labels(10)
        .x_label_formatter(&|v| label(*v, chart.log_x))
        .y_label_formatter(&|v| label(*v, chart.log_y))
        .x_desc(chart.x_label.as_str())
        .y_desc(chart.y_label.as_str())
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 17))
        .draw()
        .map_err(|e| fail(&e))?;
    for (i, (s, pts)) in series.into_iter().enumerate() {
        let (r, g, b) = COLOURS[i % COLOURS.len()];
        let colour = RGBColor(r, g, b).to_rgba();
        let legend = move |(x, y): (i32, i32)| {
            PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
        };
        if s.dashed {
            ctx.draw_series(DashedLineSeries::new(pts, 8, 6, colour.stroke_width(2)))
                .map_err(|e| fail(&e))?
                .label(s.name.as_str())
                .legend(legend);
        } else {
            ctx.draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2)))
                .map_err(|e| fail(&e))?
                .label(s.name.as_str())
                .legend(legend);
            ctx.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, colour.filled())))
                .map_err(|e| fail(&e))?;
        }
    }
    ctx.configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font((FONT, 14))
        .position(match chart.legend {
            Corner::UpperLeft => SeriesLabelPosition::UpperLeft,
            Corner::UpperRight => SeriesLabelPosition::UpperRight,
            Corner::LowerLeft => SeriesLabelPosition::LowerLeft,
            Corner::LowerRight => SeriesLabelPosition::LowerRight,
        })
        .draw()
        .map_err(|e| fail(&e))?;
    Ok(())
}
