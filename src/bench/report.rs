//! The report: bench.json, the CSV tables, the charts and the summary, written from a run
//! or redrawn from an earlier bench.json.

use super::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

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
    let tables: [(&str, Vec<serde_json::Value>); 12] = [
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

/// Writes an edges-only or straightforward-only benchmark ([`super::run_edges`],
/// [`super::run_straightforward`]): `bench.json`, `edges.csv` or `straightforward.csv`
/// and a `summary.md` with the table.
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
    let device = report.device.as_ref().map_or_else(
        || "no GPU".to_string(),
        |d| format!("{} ({})", d.name, d.driver),
    );
    let mut md = format!("Device: {device}. Build: {}.\n", report.build);
    edges_section(&mut md, report);
    straightforward_section(&mut md, report);
    written.push(write_text(dir, "summary.md", &md)?);
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
    specialisation_section(&mut md, report);
    stereo_section(&mut md, report);
    mesh_section(&mut md, report);
    conditioning_section(&mut md, report);
    drift_section(&mut md, report);
    cutoff_section(&mut md, report);
    auto_budget_section(&mut md, report);
    md
}

/// The work per pixel and its cost, so that runs on other machines compare by what they do.
fn work_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    let rows: Vec<(&ErrorRow, &TimingRow)> = report
        .errors
        .iter()
        .filter(|e| e.budget_from == "auto-high" && e.fog_factor == DEFAULT_FOG_FACTOR)
        .filter_map(|e| {
            let t = report
                .timings
                .iter()
                .filter(|t| {
                    t.space == e.space
                        && t.budget_from == e.budget_from
                        && t.fog_factor == e.fog_factor
                })
                .max_by_key(|t| t.width * t.height)?;
            Some((e, t))
        })
        .collect();
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(
        *md,
        "\n### Work per pixel at the automatic budget (quality High, fog {DEFAULT_FOG_FACTOR} inradii)\n\n| space | budget | mean crossings / pixel | 90th percentile | frame ms at | ns per pixel-crossing |\n|---|---:|---:|---:|---|---:|"
    );
    for (e, t) in rows {
        let pixel_crossings = f64::from(t.width * t.height) * e.mean_crossings.max(1.0);
        let _ = writeln!(
            *md,
            "| {} | {} | {:.2} | {:.0} | {:.2} ({}×{}) | {:.1} |",
            e.space,
            e.budget,
            e.mean_crossings,
            e.p90_crossings,
            t.median_ms,
            t.width,
            t.height,
            t.median_ms * 1e6 / pixel_crossings
        );
    }
}

/// Frame times at the automatic budget, and speed against error.
fn timings_section(
    md: &mut String,
    report: &BenchReport,
    spaces: &[&String],
    sizes: &[(u32, u32)],
) {
    use std::fmt::Write as _;
    if !spaces.is_empty() {
        let _ = writeln!(
            *md,
            "### Frame time at the automatic budget (quality High, fog {DEFAULT_FOG_FACTOR} inradii)\n"
        );
        let mut header = "| space | budget |".to_string();
        let mut rule = "|---|---:|".to_string();
        for (w, h) in sizes {
            let _ = write!(header, " {w}×{h} ms (× trivial) |");
            rule.push_str("---:|");
        }
        let _ = writeln!(*md, "{header}\n{rule}");
        for space in spaces {
            let rows: Vec<&TimingRow> = report
                .timings
                .iter()
                .filter(|t| {
                    &t.space == *space
                        && t.budget_from == "auto-high"
                        && t.fog_factor == DEFAULT_FOG_FACTOR
                })
                .collect();
            let Some(first) = rows.first() else { continue };
            let mut line = format!("| {space} | {} |", first.budget);
            for size in sizes {
                match rows.iter().find(|t| (t.width, t.height) == *size) {
                    Some(t) => {
                        let _ = write!(line, " {:.2} ({:.0}×) |", t.median_ms, t.ratio);
                    }
                    None => line.push_str(" – |"),
                }
            }
            let _ = writeln!(*md, "{line}");
        }
        let mid = sizes[sizes.len() / 2];
        let _ = writeln!(
            *md,
            "\n### Speed against error ({}×{} timings; errors at {}×{} against the f64 reference)\n",
            mid.0,
            mid.1,
            report.errors.first().map_or(0, |e| e.width),
            report.errors.first().map_or(0, |e| e.height)
        );
        let _ = writeln!(
            *md,
            "| space | budget | fog (inradii) | ms | rays out of budget % | hit differs % | f32 share % | f32 floor % | mean levels | max levels | > 10 levels % |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
        );
        for e in &report.errors {
            let ms = report
                .timings
                .iter()
                .find(|t| {
                    t.space == e.space
                        && t.budget == e.budget
                        && t.fog_factor == e.fog_factor
                        && t.budget_from == e.budget_from
                        && (t.width, t.height) == mid
                })
                .map_or(f64::NAN, |t| t.median_ms);
            let _ = writeln!(
                *md,
                "| {} | {}{} | {} | {:.2} | {} | {} | {} | {} | {:.2} | {} | {} |",
                e.space,
                e.budget,
                if e.budget_from == "fixed" {
                    ""
                } else {
                    " (auto)"
                },
                e.fog_factor,
                ms,
                pct(e.budget_exhausted),
                pct(e.hit_differs),
                pct(e.hit_differs_same_budget),
                pct(e.hit_floor_f32),
                e.mean_levels,
                e.max_levels,
                pct(e.over_10_levels)
            );
        }
    }
}

/// The specialised shader against the general one.
fn specialisation_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    if !report.specialisation.is_empty() {
        let _ = writeln!(
            *md,
            "\n### Specialised shader against the unspecialised one\n\n| space | size | budget | specialised ms | general ms | gain | uniform bytes (spec. / general) | pixels differing % |\n|---|---|---:|---:|---:|---:|---:|---:|"
        );
        for r in &report.specialisation {
            let _ = writeln!(
                *md,
                "| {} | {}×{} | {} | {:.2} | {:.2} | {:.2}× | {} / {} | {} |",
                r.space,
                r.width,
                r.height,
                r.budget,
                r.specialised_ms,
                r.general_ms,
                r.gain,
                r.specialised_uniform_bytes,
                r.general_uniform_bytes,
                pct(r.differing_pixels)
            );
        }
    }
}

/// Stereo layouts against mono.
fn stereo_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    if !report.stereo.is_empty() {
        let _ = writeln!(
            *md,
            "\n### Stereo against mono (same head and scene, each timed interleaved with mono)\n\n| space | size | budget | mono ms | side by side ms | × mono | anaglyph ms | × mono |\n|---|---|---:|---:|---:|---:|---:|---:|"
        );
        for r in &report.stereo {
            let _ = writeln!(
                *md,
                "| {} | {}×{} | {} | {:.2} | {:.2} | {:.2}× | {:.2} | {:.2}× |",
                r.space,
                r.width,
                r.height,
                r.budget,
                r.mono_ms,
                r.side_by_side_ms,
                r.side_by_side_ratio,
                r.anaglyph_ms,
                r.anaglyph_ratio
            );
        }
    }
}

/// What the cell's edges cost, culled and not, against the view without them.
fn edges_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    if report.edges.is_empty() {
        return;
    }
    let _ = writeln!(
        *md,
        "\n### The cell's edges: the default view with its edge tubes and vertex balls (culled by face masks, as drawn; and every one tested in every cell) against the same view without them, timed in turn (× without: the median over rounds of each round's ratio)\n\n| space | size | budget | edge objects | with edges ms | × without | unculled ms | × without | without edges ms | hit ids differing, culled against unculled | segments per pixel | near two faces at once | 4×2 blocks near two faces | edge tests per segment, culled |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in &report.edges {
        let _ = writeln!(
            *md,
            "| {} | {}×{} | {} | {} | {:.2} | {:.2}× | {:.2} | {:.2}× | {:.2} | {} | {:.1} | {:.0} % | {:.0} % | {:.2} |",
            r.space,
            r.width,
            r.height,
            r.budget,
            r.edge_objects,
            r.with_edges_ms,
            r.ratio,
            r.unculled_ms,
            r.unculled_ratio,
            r.without_edges_ms,
            r.hit_ids_differing,
            r.segments_per_pixel,
            100.0 * r.near_two_faces,
            100.0 * r.blocks_near_two_faces,
            r.tests_per_segment
        );
    }
}

/// The tracer against a straightforward one on the plainest view.
fn straightforward_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    if report.straightforward.is_empty() {
        return;
    }
    let _ = writeln!(
        *md,
        "\n### The tracer against a straightforward tracer of the same walk (arc length and trigonometric functions, a division a face, plain f32 pairings): the camera at the centre looking along −z, 90° across, one ball of 0.3 inradii at the centre, fog at 2 inradii, no edges; timed in turn\n\n| space | size | budget | tracer ms | straightforward ms | × straightforward | pixels differing |\n|---|---|---:|---:|---:|---:|---:|"
    );
    for r in &report.straightforward {
        let _ = writeln!(
            *md,
            "| {} | {}×{} | {} | {:.2} | {:.2} | {:.2}× | {:.2} % |",
            r.space,
            r.width,
            r.height,
            r.budget,
            r.tracer_ms,
            r.straightforward_ms,
            r.ratio,
            100.0 * r.differing_pixels
        );
    }
}

/// Frame time against triangle count.
fn mesh_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    if !report.meshes.is_empty() {
        let _ = writeln!(
            *md,
            "\n### A mesh at the cell's centre: frame time against triangle count (each timed interleaved with the same scene without the mesh)\n\n| space | size | budget | triangles | nodes | depth | build ms | with mesh ms | without ms | × without |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
        );
        for r in &report.meshes {
            let _ = writeln!(
                *md,
                "| {} | {}×{} | {} | {} | {} | {} | {:.1} | {:.2} | {:.2} | {:.2}× |",
                r.space,
                r.width,
                r.height,
                r.budget,
                r.triangles,
                r.nodes,
                r.depth,
                r.build_ms,
                r.with_mesh_ms,
                r.without_mesh_ms,
                r.ratio
            );
        }
    }
}

/// Walks against the double-double reference: error / conditioning, compensated and plain.
fn conditioning_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    if report.conditioning.is_empty() {
        return;
    }
    let _ = writeln!(
        *md,
        "\n### Error / conditioning limit against the double-double reference (1 = the limit, 10 = a digit lost)\n\n| space | precision | crossings | median | worst | plain pairing: median | plain: worst | crossings counted (left out) |\n|---|---|---:|---:|---:|---:|---:|---:|"
    );
    for row in report
        .conditioning
        .iter()
        .filter(|r| r.pairing == "compensated")
    {
        let plain = report.conditioning.iter().find(|p| {
            p.pairing == "plain"
                && p.space == row.space
                && p.precision == row.precision
                && p.crossings == row.crossings
        });
        let f = |x: Option<f64>| x.map_or_else(|| "–".to_string(), |x| format!("{x:.2}"));
        let _ = writeln!(
            *md,
            "| {} | {} | {} | {:.2} | {:.2} | {} | {} | {} ({}) |",
            row.space,
            row.precision,
            row.crossings,
            row.median,
            row.worst,
            f(plain.map(|p| p.median)),
            f(plain.map(|p| p.worst)),
            row.counted,
            row.left_out
        );
    }
}

/// The f32 drift of long rays against its bound.
fn drift_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    let _ = writeln!(
        *md,
        "\n### f32 against f64 along long rays (median over rays that keep the f64 faces)\n\n| space | crossings | same faces % | median distance | median position error | max position error | median direction error (rad) | bound 4ε·n·G(d) at the median distance | worst error / own bound |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for d in &report.drift {
        let e = |x: Option<f64>| x.map_or_else(|| "–".to_string(), |x| format!("{x:.1e}"));
        let _ = writeln!(
            *md,
            "| {} | {} | {:.0} | {:.1} | {} | {} | {} | {} | {} |",
            d.space,
            d.crossings,
            100.0 * d.same_faces,
            d.median_distance,
            e(d.median_position_error),
            e(d.max_position_error),
            e(d.median_direction_error),
            e(d.bound),
            d.worst_bound_ratio
                .map_or_else(|| "–".to_string(), |r| format!("{r:.2}"))
        );
    }
}

/// The fog cut-off's error against its bound.
fn cutoff_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    let _ = writeln!(
        *md,
        "\n### The fog cut-off against its bound (f64, no cut-off as reference)\n\n| space | fog (inradii) | λ | cut-off distance | bound | max error | mean error | within |\n|---|---:|---:|---:|---:|---:|---:|---|"
    );
    for c in &report.cutoff {
        let _ = writeln!(
            *md,
            "| {} | {} | {:.3} | {:.2} | {:.2e} | {:.2e} | {:.1e} | {} |",
            c.space,
            c.fog_factor,
            c.fog_distance,
            c.cutoff_distance,
            c.bound,
            c.max_error,
            c.mean_error,
            if c.within_bound { "yes" } else { "**no**" }
        );
    }
}

/// The automatic budgets.
fn auto_budget_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    let _ = writeln!(
        *md,
        "\n### Automatic budgets (crossings) by quality and fog\n\n| space | fog (inradii) | low | medium | high | most needed |\n|---|---:|---:|---:|---:|---:|"
    );
    let mut keys: Vec<(&String, f64)> = report
        .auto_budgets
        .iter()
        .map(|b| (&b.space, b.fog_factor))
        .collect();
    keys.dedup();
    for (space, fog) in keys {
        let of = |q: &str| {
            report
                .auto_budgets
                .iter()
                .find(|b| &b.space == space && b.fog_factor == fog && b.quality == q)
                .map_or_else(|| "–".to_string(), |b| b.choice.budget.to_string())
        };
        let most = report
            .auto_budgets
            .iter()
            .find(|b| &b.space == space && b.fog_factor == fog)
            .map_or(0, |b| b.choice.most_needed);
        let _ = writeln!(
            *md,
            "| {space} | {fog} | {} | {} | {} | {most} |",
            of("low"),
            of("medium"),
            of("high")
        );
    }
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
