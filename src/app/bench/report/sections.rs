//! The sections of the report's summary, one function each.

use super::*;

/// The work per pixel and its cost, so that runs on other machines compare by what they do.
pub(super) fn work_section(md: &mut String, report: &BenchReport) {
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
pub(super) fn timings_section(
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
pub(super) fn specialisation_section(md: &mut String, report: &BenchReport) {
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
pub(super) fn stereo_section(md: &mut String, report: &BenchReport) {
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
pub(super) fn edges_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    if report.edges.is_empty() {
        return;
    }
    let _ = writeln!(
        *md,
        "\n### The cell's edges: the default view with its edge tubes and vertex balls (culled by face masks, as drawn; and every one tested in every cell) against the same view without them, timed in turn (× without: the median over rounds of each round's ratio)\n\n| space | size | budget | edge objects | with edges ms | × without | unculled ms | × without | without edges ms | hit ids differing, culled against unculled | segments per pixel | p90 | ns per pixel-segment, culled | near two faces at once | 4×2 blocks near two faces | edge tests per segment, culled |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in &report.edges {
        let _ = writeln!(
            *md,
            "| {} | {}×{} | {} | {} | {:.2} | {:.2}× | {:.2} | {:.2}× | {:.2} | {} | {:.1} | {:.0} | {:.0} | {:.0} % | {:.0} % | {:.2} |",
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
            r.segments_p90,
            r.ns_per_segment,
            100.0 * r.near_two_faces,
            100.0 * r.blocks_near_two_faces,
            r.tests_per_segment
        );
    }
    let measured = |r: &&EdgesRow| r.tiles.shares().iter().sum::<f64>() > 0.0;
    if !report.edges.iter().any(|r| measured(&r)) {
        return;
    }
    let _ = writeln!(
        *md,
        "\n#### What neighbouring pixels share: 8×8 tiles by the crossing at which their four corner rays first leave a cell copy by different faces (CPU reference; while they agree, every ray of the tile leaves by the same face), and the tiles with a pixel near an edge or vertex before that\n\n| space | parting at 0 | at 1 | at 2 | at 3 | at 4 or later | never | near an edge before parting |\n|---|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in report.edges.iter().filter(measured) {
        let shares: Vec<String> = r
            .tiles
            .shares()
            .iter()
            .map(|x| format!("{:.0} %", 100.0 * x))
            .collect();
        let _ = writeln!(
            *md,
            "| {} | {} | {:.0} % |",
            r.space,
            shares.join(" | "),
            100.0 * r.tiles_near_edge_before_parting
        );
    }
}

/// The tracer against a straightforward one on the plainest view.
pub(super) fn straightforward_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    if report.straightforward.is_empty() {
        return;
    }
    let _ = writeln!(
        *md,
        "\n### The tracer against a straightforward tracer of the same walk (arc length and trigonometric functions, a division a face, plain f32 pairings, every lamp image summed): the camera at the centre looking along −z, 90° across, one ball of 0.3 inradii at the centre, fog at 2 inradii, no edges; timed in turn\n\n| space | size | budget | tracer ms | straightforward ms | × straightforward | pixels differing |\n|---|---|---:|---:|---:|---:|---:|"
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
pub(super) fn mesh_section(md: &mut String, report: &BenchReport) {
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
pub(super) fn conditioning_section(md: &mut String, report: &BenchReport) {
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
pub(super) fn drift_section(md: &mut String, report: &BenchReport) {
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
pub(super) fn cutoff_section(md: &mut String, report: &BenchReport) {
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
pub(super) fn auto_budget_section(md: &mut String, report: &BenchReport) {
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

/// The product spaces: speed against a constant-curvature view, and error.
pub(super) fn products_section(md: &mut String, report: &BenchReport) {
    use std::fmt::Write as _;
    if report.products.is_empty() {
        return;
    }
    let reference = &report.products[0].reference_space;
    let _ = writeln!(
        *md,
        "\n### Product spaces (H²×R, S²×R): each default view timed in the same rounds as {reference}'s default view at the same size (both at their automatic budgets, quality High); crossings a pixel makes; the GPU picture against the f64 CPU reference (pixels off by more than 10/255); the f64 and f32 walks against double-double over 100 crossings, as error / conditioning limit\n\n| space | geometry | size | budget | ms | {reference} ms | × {reference} | crossings / pixel | root iterations / pixel | safe steps / pixel | pixels differing | mean error /255 | f64 median / worst | f32 median / worst |\n|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in &report.products {
        let _ = writeln!(
            *md,
            "| {} | {} | {}×{} | {} | {:.2} | {:.2} | {:.2}× | {:.2} | {} % | {:.2} | {:.2} / {:.2} | {:.2} / {:.2} |",
            r.space,
            r.geometry,
            r.width,
            r.height,
            r.budget,
            r.tracer_ms,
            r.reference_ms,
            r.ratio,
            r.crossings_per_pixel,
            super::pct(r.differing_pixels),
            r.mean_error,
            r.f64_median,
            r.f64_worst,
            r.f32_median,
            r.f32_worst
        );
    }
}

/// The families with their own tracer (Nil, SL̃(2,R)): speed against a constant-curvature
/// view, and error.
pub(super) fn families_section(md: &mut String, report: &BenchReport) {
    family_section(
        md,
        &report.nil,
        "Nil",
        &format!(
            "the f64 and f32 walks ({} long) against the exact geodesic in double-double, as error / (ε (1 + t²))",
            super::super::nil::WALK_DISTANCE
        ),
    );
    family_section(
        md,
        &report.sl2r,
        "SL̃(2,R)",
        &format!(
            "the f64 and f32 walks ({} long) against the double-double walk, as error / the conditioning limit (the exact walk's spread under one rounding of its start)",
            super::super::sl2r::WALK_DISTANCE
        ),
    );
}

/// One family's table, `accuracy` saying what its walk columns measure.
fn family_section(md: &mut String, rows: &[super::super::FamilyRow], family: &str, accuracy: &str) {
    use std::fmt::Write as _;
    let Some(first) = rows.first() else {
        return;
    };
    let reference = &first.reference_space;
    let _ = writeln!(
        *md,
        "\n### {family} spaces: each default view timed in the same rounds as {reference}'s default view at the same size ({family} at the plugin's default budget, {reference} at its automatic one); objects in the scene; crossings a pixel makes, and the root finders' iterations and the safe steps towards objects a pixel takes (the f64 CPU tracer, shadow rays included); the GPU picture against the f64 CPU reference (pixels off by more than 10/255); {accuracy}\n\n| space | size | budget | objects | ms | {reference} ms | × {reference} | crossings / pixel | root iterations / pixel | safe steps / pixel | pixels differing | mean error /255 | f64 median / worst | f32 median / worst |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in rows {
        let _ = writeln!(
            *md,
            "| {} | {}×{} | {} | {} | {:.2} | {:.2} | {:.2}× | {:.2} | {:.1} | {:.1} | {} % | {:.2} | {:.3} / {:.3} | {:.3} / {:.3} |",
            r.space,
            r.width,
            r.height,
            r.budget,
            r.objects,
            r.tracer_ms,
            r.reference_ms,
            r.ratio,
            r.crossings_per_pixel,
            r.root_iterations_per_pixel,
            r.safe_steps_per_pixel,
            super::pct(r.differing_pixels),
            r.mean_error,
            r.f64_median,
            r.f64_worst,
            r.f32_median,
            r.f32_worst
        );
    }
}
