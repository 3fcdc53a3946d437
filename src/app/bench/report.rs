//! The report: bench.json, the CSV tables, the charts and the summary, written from a run
//! or redrawn from an earlier bench.json.

use super::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

mod sections;
use sections::*;

/// Writing `path` failed.
fn write_error(path: &Path, e: &dyn std::fmt::Display) -> BenchError {
    BenchError::Write {
        path: path.display().to_string(),
        error: e.to_string(),
    }
}

/// Writes `text` whole to `dir/name` (`files::write_atomic`), creating `dir` first.
fn write_text(dir: &Path, name: &str, text: &str) -> Result<PathBuf, BenchError> {
    std::fs::create_dir_all(dir).map_err(|e| write_error(dir, &e))?;
    let path = dir.join(name);
    crate::files::write_atomic(&path, text.as_bytes()).map_err(|e| write_error(&path, &e))?;
    Ok(path)
}

/// `bench.json`: what was asked for and what was measured.
fn write_json(
    dir: &Path,
    config: serde_json::Value,
    report: &BenchReport,
) -> Result<PathBuf, BenchError> {
    let body = serde_json::to_string_pretty(&serde_json::json!({
        "config": config,
        "report": report,
    }))
    .map_err(|e| write_error(&dir.join("bench.json"), &e))?;
    write_text(dir, "bench.json", &body)
}

/// Writes `report` as `bench.json`, one CSV per table and the charts into `dir`.
pub fn write_report(
    report: &BenchReport,
    config: &BenchConfig,
    dir: &Path,
) -> Result<Vec<PathBuf>, BenchError> {
    let config = serde_json::to_value(config).map_err(|e| write_error(dir, &e))?;
    let mut written = vec![write_json(dir, config, report)?];
    let tables: [(&str, Vec<serde_json::Value>); 15] = [
        ("timings", to_values(&report.timings)),
        ("errors", to_values(&report.errors)),
        ("conditioning", to_values(&report.conditioning)),
        ("conditioning_curve", to_values(&report.conditioning_curve)),
        ("drift", to_values(&report.drift)),
        ("cutoff", to_values(&report.cutoff)),
        ("auto_budgets", to_values(&report.auto_budgets)),
        ("specialisation", to_values(&report.specialisation)),
        ("stereo", to_values(&report.stereo)),
        ("meshes", to_values(&report.meshes)),
        ("edges", to_values(&report.edges)),
        ("straightforward", to_values(&report.straightforward)),
        ("products", to_values(&report.products)),
        ("nil", to_values(&report.nil)),
        ("sl2r", to_values(&report.sl2r)),
    ];
    for (name, rows) in tables {
        written.push(write_text(dir, &format!("{name}.csv"), &to_csv(&rows))?);
    }
    written.push(write_text(dir, "summary.md", &summary_markdown(report))?);
    for (stem, chart) in charts(report) {
        let path = dir.join(stem);
        write_chart(&chart, &path)?;
        written.push(path.with_extension("png"));
        written.push(path.with_extension("svg"));
    }
    Ok(written)
}

/// Writes a scene benchmark ([`super::run_scene`]): `bench.json`, `timings.csv` and a
/// `summary.md` of its frame times, per budget and size.
pub fn write_scene_report(
    report: &BenchReport,
    config: &BenchConfig,
    dir: &Path,
) -> Result<Vec<PathBuf>, BenchError> {
    use std::fmt::Write as _;
    let config = serde_json::json!({"budgets": config.budgets, "sizes": config.sizes});
    let json = write_json(dir, config, report)?;
    let csv = write_text(dir, "timings.csv", &to_csv(&to_values(&report.timings)))?;
    let mut md = String::new();
    let name = report.timings.first().map_or("", |t| t.space.as_str());
    let device = report.device.as_ref().map_or_else(
        || "no GPU".to_string(),
        |d| format!("{} ({})", d.name, d.driver),
    );
    let _ = writeln!(
        md,
        "Scene {name}: its start view. Device: {device}. Build: {}.\n\n| budget | size | median ms | p10–p90 ms | trivial material ms | × trivial |\n|---:|---|---:|---:|---:|---:|",
        report.build
    );
    for t in &report.timings {
        let _ = writeln!(
            md,
            "| {} | {}×{} | {:.3} | {:.3}–{:.3} | {:.3} | {:.1} |",
            t.budget, t.width, t.height, t.median_ms, t.p10_ms, t.p90_ms, t.baseline_ms, t.ratio
        );
    }
    let summary = write_text(dir, "summary.md", &md)?;
    Ok(vec![json, csv, summary])
}

/// Writes an edges-only, straightforward-only, products-only, Nil-only or SL̃(2,R)-only
/// benchmark ([`super::run_edges`], [`super::run_straightforward`], [`super::run_products`],
/// [`super::run_nil`], [`super::run_sl2r`]): `bench.json`, `edges.csv`,
/// `straightforward.csv`, `products.csv`, `nil.csv` or `sl2r.csv` and a `summary.md` with
/// the table.
pub fn write_edges_report(
    report: &BenchReport,
    config: &BenchConfig,
    dir: &Path,
) -> Result<Vec<PathBuf>, BenchError> {
    let config = serde_json::to_value(config).map_err(|e| write_error(dir, &e))?;
    let json = write_json(dir, config, report)?;
    let mut written = vec![json];
    if !report.edges.is_empty() {
        written.push(write_text(
            dir,
            "edges.csv",
            &to_csv(&to_values(&report.edges)),
        )?);
    }
    if !report.straightforward.is_empty() {
        written.push(write_text(
            dir,
            "straightforward.csv",
            &to_csv(&to_values(&report.straightforward)),
        )?);
    }
    if !report.lighting.is_empty() {
        written.push(write_text(
            dir,
            "lighting.csv",
            &to_csv(&to_values(&report.lighting)),
        )?);
    }
    if !report.products.is_empty() {
        written.push(write_text(
            dir,
            "products.csv",
            &to_csv(&to_values(&report.products)),
        )?);
    }
    for (name, rows) in [("nil", &report.nil), ("sl2r", &report.sl2r)] {
        if !rows.is_empty() {
            written.push(write_text(
                dir,
                &format!("{name}.csv"),
                &to_csv(&to_values(rows)),
            )?);
        }
    }
    let device = report.device.as_ref().map_or_else(
        || "no GPU".to_string(),
        |d| format!("{} ({})", d.name, d.driver),
    );
    let mut md = format!("Device: {device}. Build: {}.\n", report.build);
    edges_section(&mut md, report);
    straightforward_section(&mut md, report);
    products_section(&mut md, report);
    families_section(&mut md, report);
    super::lighting::lighting_section(&mut md, report);
    written.push(write_text(dir, "summary.md", &md)?);
    if let Some(chart) = super::lighting::lighting_chart(report) {
        let stem = dir.join("lighting");
        write_chart(&chart, &stem)?;
        written.push(stem.with_extension("png"));
        written.push(stem.with_extension("svg"));
    }
    Ok(written)
}

/// Reads a `bench.json` written by [`write_report`] back (to redraw its charts and tables).
pub fn read_report(path: &Path) -> Result<(BenchConfig, BenchReport), BenchError> {
    let fail = |e: &dyn std::fmt::Display| BenchError::Write {
        path: path.display().to_string(),
        error: format!("cannot read it as a benchmark result: {e}"),
    };
    let text = std::fs::read_to_string(path).map_err(|e| fail(&e))?;
    #[derive(Deserialize)]
    struct File {
        config: BenchConfig,
        report: BenchReport,
    }
    let file: File = serde_json::from_str(&text).map_err(|e| fail(&e))?;
    Ok((file.config, file.report))
}

pub(super) fn pct(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if x < 0.001 {
        format!("{:.3}", 100.0 * x)
    } else {
        format!("{:.2}", 100.0 * x)
    }
}

/// The report's main tables as Markdown (for docs/performance.md).
#[must_use]
pub fn summary_markdown(report: &BenchReport) -> String {
    use std::fmt::Write as _;
    let mut md = String::new();
    let device = report.device.as_ref().map_or_else(
        || "no GPU (CPU measurements only)".to_string(),
        |d| {
            format!(
                "{} ({}, {}, {}); frame times from {}",
                d.name,
                d.device_type,
                d.backend,
                d.driver,
                if d.timestamps {
                    "GPU timestamps around the pass"
                } else {
                    "wall time around each synchronised submission"
                }
            )
        },
    );
    let _ = writeln!(
        md,
        "Device: {device}. Build: {}, {} CPU threads.\n",
        report.build, report.cpu_threads
    );
    let mut spaces: Vec<&String> = report.timings.iter().map(|t| &t.space).collect();
    spaces.dedup();
    let mut sizes: Vec<(u32, u32)> = report.timings.iter().map(|t| (t.width, t.height)).collect();
    sizes.sort_unstable();
    sizes.dedup();
    timings_section(&mut md, report, &spaces, &sizes);
    work_section(&mut md, report);
    edges_section(&mut md, report);
    straightforward_section(&mut md, report);
    products_section(&mut md, report);
    families_section(&mut md, report);
    specialisation_section(&mut md, report);
    stereo_section(&mut md, report);
    mesh_section(&mut md, report);
    conditioning_section(&mut md, report);
    drift_section(&mut md, report);
    cutoff_section(&mut md, report);
    auto_budget_section(&mut md, report);
    md
}

pub(super) fn to_values<T: Serialize>(rows: &[T]) -> Vec<serde_json::Value> {
    rows.iter()
        .map(|r| serde_json::to_value(r).expect("rows are plain data"))
        .collect()
}

/// Rows of JSON objects as CSV (columns in the first row's order).
pub(super) fn to_csv(rows: &[serde_json::Value]) -> String {
    let Some(serde_json::Value::Object(first)) = rows.first() else {
        return String::new();
    };
    let columns: Vec<&String> = first.keys().collect();
    let mut out = columns
        .iter()
        .map(|c| c.as_str())
        .collect::<Vec<_>>()
        .join(",");
    out.push('\n');
    for row in rows {
        let cells: Vec<String> = columns
            .iter()
            .map(|c| match row.get(c.as_str()) {
                Some(serde_json::Value::String(s)) => s.clone(),
                Some(serde_json::Value::Null) | None => String::new(),
                Some(v) => v.to_string(),
            })
            .collect();
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// One number read off an accuracy row (a chart's y axis).
pub(super) type ErrorMeasure = fn(&ErrorRow) -> f64;

/// The charts of a report: speed against error, error against crossings.
#[must_use]
pub fn charts(report: &BenchReport) -> Vec<(&'static str, Chart)> {
    let mut charts = Vec::new();
    let spaces: Vec<&String> = {
        let mut s: Vec<&String> = report.errors.iter().map(|e| &e.space).collect();
        s.dedup();
        s
    };
    // Speed against error at the largest timed resolution, fixed budgets at the default fog.
    if let Some(size) = report.timings.iter().map(|t| (t.width, t.height)).max() {
        let measures: [(&str, &str, ErrorMeasure); 2] = [
            (
                "speed_vs_colour_error",
                "mean colour error against f64 (8-bit levels)",
                |e| e.mean_levels.max(1e-3),
            ),
            (
                "speed_vs_hit_error",
                "pixels whose hit differs from f64 (%)",
                |e| 100.0 * e.hit_differs.max(1e-5),
            ),
        ];
        for (stem, y_label, measure) in measures {
            let series = spaces
                .iter()
                .map(|space| {
                    let points = report
                        .errors
                        .iter()
                        .filter(|e| &&e.space == space && e.budget_from == "fixed")
                        .filter_map(|e| {
                            let t = report.timings.iter().find(|t| {
                                &t.space == *space
                                    && t.budget == e.budget
                                    && t.budget_from == "fixed"
                                    && (t.width, t.height) == size
                            })?;
                            Some((t.median_ms, measure(e)))
                        })
                        .collect();
                    Series {
                        name: space.to_string(),
                        points,
                        dashed: false,
                    }
                })
                .collect();
            charts.push((
                stem,
                Chart {
                    title: format!(
                        "Speed against error, {}×{}, budgets {}",
                        size.0,
                        size.1,
                        budget_list(report)
                    ),
                    x_label: "GPU frame time (ms)".into(),
                    y_label: y_label.into(),
                    log_x: true,
                    log_y: true,
                    series,
                    legend: Corner::LowerLeft,
                },
            ));
        }
    }
    // f32 drift against crossings, with the conditioning bound.
    let series = series_per_space(
        &report.drift,
        |d| &d.space,
        |d| Some((d.crossings as f64, d.median_position_error?.max(1e-12))),
    );
    charts.push((
        "drift",
        Chart {
            title: "f32 against f64: median position error of long rays".into(),
            x_label: "face crossings".into(),
            y_label: "geodesic distance f32 to f64".into(),
            log_x: true,
            log_y: true,
            series,
            legend: Corner::LowerRight,
        },
    ));
    // Digits lost beyond conditioning against distance, for the curved spaces and the torus.
    if !report.conditioning_curve.is_empty() {
        let mut series = Vec::new();
        for space in [
            "seifert-weber",
            "mirrored-dodecahedron",
            "poincare",
            "torus",
        ] {
            for (precision, pairing) in [
                ("f64", "compensated"),
                ("f32", "compensated"),
                ("f64", "plain"),
            ] {
                if pairing == "plain" && space != "seifert-weber" {
                    continue;
                }
                let points: Vec<(f64, f64)> = report
                    .conditioning_curve
                    .iter()
                    .filter(|p| {
                        p.space == space && p.precision == precision && p.pairing == pairing
                    })
                    .map(|p| (p.distance, p.median_digits))
                    .collect();
                if points.is_empty() {
                    continue;
                }
                series.push(Series {
                    name: if pairing == "plain" {
                        format!("{space} {precision}, plain pairing")
                    } else {
                        format!("{space} {precision}")
                    },
                    points,
                    dashed: pairing == "plain",
                });
            }
        }
        charts.push((
            "digits_lost",
            Chart {
                title: "Digits lost beyond the conditioning limit (median log10 error / limit)"
                    .into(),
                x_label: "geodesic distance along the ray".into(),
                y_label: "log10(error / conditioning limit)".into(),
                log_x: false,
                log_y: false,
                series,
                legend: Corner::UpperRight,
            },
        ));
    }
    // Mesh scenes: frame time against triangle count.
    if !report.meshes.is_empty() {
        let series = series_per_space(
            &report.meshes,
            |m| &m.space,
            |m| Some((m.triangles as f64, m.ratio)),
        );
        let size = report
            .meshes
            .first()
            .map(|m| format!("{}×{}", m.width, m.height))
            .unwrap_or_default();
        charts.push((
            "mesh_triangles",
            Chart {
                title: format!(
                    "A mesh at the cell's centre: GPU frame time against the same view without it ({size})"
                ),
                x_label: "triangles".into(),
                y_label: "frame time with / without the mesh".into(),
                log_x: true,
                log_y: true,
                series,
                legend: Corner::UpperLeft,
            },
        ));
    }
    charts
}

/// One series per space (in the rows' order of spaces) of the points `point` gives.
pub(super) fn series_per_space<T>(
    rows: &[T],
    space: impl Fn(&T) -> &String,
    point: impl Fn(&T) -> Option<(f64, f64)>,
) -> Vec<Series> {
    let mut spaces: Vec<&String> = rows.iter().map(&space).collect();
    spaces.dedup();
    spaces
        .into_iter()
        .map(|name| Series {
            name: name.to_string(),
            points: rows
                .iter()
                .filter(|r| space(r) == name)
                .filter_map(&point)
                .collect(),
            dashed: false,
        })
        .collect()
}

pub(super) fn budget_list(report: &BenchReport) -> String {
    let mut b: Vec<u32> = report
        .errors
        .iter()
        .filter(|e| e.budget_from == "fixed")
        .map(|e| e.budget)
        .collect();
    b.sort_unstable();
    b.dedup();
    b.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
}
