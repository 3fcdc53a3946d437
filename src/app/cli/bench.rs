//! `bench`: the speed-against-error benchmark, with a summary on standard output.

use super::*;
use bevy::prelude::*;
use bevy_curved_spaces::bench::BenchConfig;
use bevy_curved_spaces::plugin::offscreen::gpu_available;
use std::time::Instant;

/// Rounds of the three edge views `bench --edges` times per space, at least: ratios of a
/// few per cent need more than the sweep's timings.
const EDGES_ROUNDS: usize = 15;

pub(super) fn bench(args: &BenchArgs) -> Result<(), String> {
    if let Some(from) = &args.from {
        let (config, report) =
            bevy_curved_spaces::bench::read_report(from).map_err(|e| e.to_string())?;
        let written = bevy_curved_spaces::bench::write_report(&report, &config, &args.out)
            .map_err(|e| e.to_string())?;
        say!("wrote {} files to {}", written.len(), args.out.display());
        return Ok(());
    }
    if args.entities {
        if cfg!(debug_assertions) {
            eprintln!(
                "note: this is a debug build; for representative timings run `cargo run --release -- bench --entities`"
            );
        }
        eprintln!("timing updates with moving objects as entities…");
        let started = Instant::now();
        let (timings, builds) = bevy_curved_spaces::bench::entities::run_entities(args.quick);
        let summary =
            bevy_curved_spaces::bench::entities::write_entities(&timings, &builds, &args.out)
                .map_err(|e| format!("cannot write to {}: {e}", args.out.display()))?;
        say!("{summary}");
        say!(
            "wrote entities.csv, new_meshes.csv and entities.md to {} in {:.1} s",
            args.out.display(),
            started.elapsed().as_secs_f64()
        );
        return Ok(());
    }
    let mut config = if args.quick {
        BenchConfig::quick()
    } else {
        BenchConfig::full()
    };
    if let Some(spaces) = &args.spaces {
        for id in spaces {
            bevy_curved_spaces::bench::bench_space(id).map_err(|e| e.to_string())?;
        }
        config.spaces.clone_from(spaces);
    }
    if let Some(budgets) = &args.budgets {
        config.budgets.clone_from(budgets);
    }
    if let Some(sizes) = &args.sizes {
        config.sizes.clone_from(sizes);
    }
    config.cpu_only = args.cpu_only;
    if !config.cpu_only && !gpu_available() {
        return Err("no GPU adapter was found: install one (on Debian `apt-get install mesa-vulkan-drivers libvulkan1`) or pass --cpu-only".into());
    }
    if cfg!(debug_assertions) {
        eprintln!(
            "note: this is a debug build; for representative timings run `cargo run --release -- bench`"
        );
    }
    let started = Instant::now();
    let progress = indicatif::ProgressBar::new(0);
    if let Some(ks) = &args.nil {
        config.nil.clone_from(ks);
        let run = bevy_curved_spaces::bench::run_nil;
        let ids = format!("{ks:?}");
        return bench_family(
            &config,
            (&progress, started, &args.out),
            ("Nil", &ids),
            run,
            |r| (&r.nil, "ε(1 + t²)"),
        );
    }
    if let Some(ids) = &args.sl2r {
        config.sl2r.clone_from(ids);
        bevy_curved_spaces::bench::check_sl2r(ids).map_err(|e| e.to_string())?;
        let run = bevy_curved_spaces::bench::run_sl2r;
        let ids = format!("{ids:?}");
        return bench_family(
            &config,
            (&progress, started, &args.out),
            ("SL̃(2,R)", &ids),
            run,
            |r| (&r.sl2r, "the conditioning limit"),
        );
    }
    if let Some(products) = &args.products {
        eprintln!(
            "benchmarking product spaces {products:?} at {:?} against {}…",
            config.sizes,
            bevy_curved_spaces::bench::PRODUCT_REFERENCE_SPACE
        );
    } else if let Some(scene) = &args.scene {
        eprintln!(
            "benchmarking the start view of {} at {} size(s), budgets {:?}…",
            scene.display(),
            config.sizes.len(),
            config.budgets
        );
    } else {
        eprintln!(
            "benchmarking {} space(s) at {} size(s), budgets {:?}, fog {:?} inradii…",
            config.spaces.len(),
            config.sizes.len(),
            config.budgets,
            config.fog_factors
        );
    }
    if let Some(products) = &args.products {
        if products.len() == 1 && products[0] == "all" {
            config.products = bevy_curved_spaces::space::product::PRODUCT_ALIASES
                .iter()
                .map(|a| a.id.to_string())
                .collect();
        } else {
            config.products.clone_from(products);
        }
        bevy_curved_spaces::bench::check_products(&config.products).map_err(|e| e.to_string())?;
        let report = bevy_curved_spaces::bench::run_products(&config, &progress)
            .map_err(|e| e.to_string())?;
        for r in &report.products {
            say!(
                "{:<26} {}: {:>8.2} ms, {:.2}× {} ({} crossings), {:.2} crossings a pixel, {:.2} % of pixels differ from the CPU, walks f64 {:.2} / f32 {:.2} × conditioning (median)",
                r.space,
                r.geometry,
                r.tracer_ms,
                r.ratio,
                r.reference_space,
                r.budget,
                r.crossings_per_pixel,
                100.0 * r.differing_pixels,
                r.f64_median,
                r.f32_median
            );
        }
        let written = bevy_curved_spaces::bench::write_edges_report(&report, &config, &args.out)
            .map_err(|e| e.to_string())?;
        say_written(&written, &args.out, started);
        return Ok(());
    }
    if args.straightforward {
        if args.budgets.is_none() {
            config.budgets = vec![16, 32];
        }
        if !args.quick {
            config.min_frames = config.min_frames.max(EDGES_ROUNDS);
        }
        let report = bevy_curved_spaces::bench::run_straightforward(&config, &progress)
            .map_err(|e| e.to_string())?;
        for r in &report.straightforward {
            say!(
                "{:<24} budget {:>3}: tracer {:>8.3} ms, straightforward {:>8.3} ms: {:.2}× ({:.2} % of pixels differ)",
                r.space,
                r.budget,
                r.tracer_ms,
                r.straightforward_ms,
                r.ratio,
                100.0 * r.differing_pixels
            );
        }
        let written = bevy_curved_spaces::bench::write_edges_report(&report, &config, &args.out)
            .map_err(|e| e.to_string())?;
        say_written(&written, &args.out, started);
        return Ok(());
    }
    if args.lighting {
        if args.budgets.is_none() {
            config.budgets = vec![24];
        }
        let report = bevy_curved_spaces::bench::run_lighting(&config, &progress)
            .map_err(|e| e.to_string())?;
        for r in &report.lighting {
            say!(
                "{:<16} {:<30} {:>4} images: {:>8.3} ms ({:.2}× nearest), mean error {:.2}/255, {:.2} % of pixels off by more than 8/255",
                r.space,
                r.lighting,
                r.images,
                r.median_ms,
                r.time_ratio,
                r.mean_error,
                100.0 * r.pixels_off
            );
        }
        let written = bevy_curved_spaces::bench::write_edges_report(&report, &config, &args.out)
            .map_err(|e| e.to_string())?;
        say_written(&written, &args.out, started);
        return Ok(());
    }
    if args.edges {
        if args.budgets.is_none() {
            config.budgets = vec![32];
        }
        if !args.quick {
            config.min_frames = config.min_frames.max(EDGES_ROUNDS);
        }
        let report =
            bevy_curved_spaces::bench::run_edges(&config, &progress).map_err(|e| e.to_string())?;
        for r in &report.edges {
            say!(
                "{:<24} {:>3} edge objects: culled {:>8.3} ms ({:.2}×), unculled {:>8.3} ms ({:.2}×), without {:>8.3} ms; {:.1} segments a pixel (p90 {:.0}), {:.0} ns a pixel-segment, {:.0} % near two faces at once ({:.0} % of 4×2 blocks)",
                r.space,
                r.edge_objects,
                r.with_edges_ms,
                r.ratio,
                r.unculled_ms,
                r.unculled_ratio,
                r.without_edges_ms,
                r.segments_per_pixel,
                r.segments_p90,
                r.ns_per_segment,
                100.0 * r.near_two_faces,
                100.0 * r.blocks_near_two_faces
            );
        }
        let written = bevy_curved_spaces::bench::write_edges_report(&report, &config, &args.out)
            .map_err(|e| e.to_string())?;
        say_written(&written, &args.out, started);
        return Ok(());
    }
    if let Some(scene) = &args.scene {
        let report = bevy_curved_spaces::bench::run_scene(&config, scene, &progress)
            .map_err(|e| e.to_string())?;
        for t in &report.timings {
            say!(
                "{:<24} {:>5}×{:<5} budget {:>4}: {:>9.3} ms ({:.1}× the trivial material)",
                t.space,
                t.width,
                t.height,
                t.budget,
                t.median_ms,
                t.ratio
            );
        }
        let written = bevy_curved_spaces::bench::write_scene_report(&report, &config, &args.out)
            .map_err(|e| e.to_string())?;
        say_written(&written, &args.out, started);
        return Ok(());
    }
    let report = bevy_curved_spaces::bench::run(&config, &progress).map_err(|e| e.to_string())?;
    if let Some(device) = &report.device {
        say!(
            "device: {} ({}, {}, {}); frame times from {}",
            device.name,
            device.device_type,
            device.backend,
            device.driver,
            if device.timestamps {
                "GPU timestamps"
            } else {
                "wall time around each submission"
            }
        );
    }
    for t in report
        .timings
        .iter()
        .filter(|t| t.budget_from == "auto-high")
    {
        if t.fog_factor != bevy_curved_spaces::bench::DEFAULT_FOG_FACTOR
            || Some((t.width, t.height)) != config.sizes.iter().copied().max()
        {
            continue;
        }
        let error = report.errors.iter().find(|e| {
            e.space == t.space && e.budget_from == t.budget_from && e.fog_factor == t.fog_factor
        });
        say!(
            "{:<22} {:>4}×{:<4} budget {:>4}: {:>9.3} ms ({:>6.1}× the trivial material), hits differing from f64 {:.3} %",
            t.space,
            t.width,
            t.height,
            t.budget,
            t.median_ms,
            t.ratio,
            error.map_or(f64::NAN, |e| 100.0 * e.hit_differs)
        );
    }
    for c in &report.cutoff {
        if !c.within_bound {
            eprintln!(
                "warning: {} fog {} inradii: cut-off error {:.2e} exceeds its bound {:.2e}",
                c.space, c.fog_factor, c.max_error, c.bound
            );
        }
    }
    let written = bevy_curved_spaces::bench::write_report(&report, &config, &args.out)
        .map_err(|e| e.to_string())?;
    say_written(&written, &args.out, started);
    Ok(())
}

/// Says how many files a run wrote, where (the folder made absolute where it can be) and
/// in how long.
fn say_written(written: &[std::path::PathBuf], out: &std::path::Path, started: Instant) {
    say!(
        "wrote {} files to {} in {:.1} s",
        written.len(),
        std::fs::canonicalize(out)
            .unwrap_or_else(|_| out.to_path_buf())
            .display(),
        started.elapsed().as_secs_f64()
    );
}

/// One family's rows (Nil's, SL̃(2,R)'s): measured by `run`, said a line each (`rows` gives
/// them and what their walks' error is divided by) and written with the summary.
fn bench_family(
    config: &bevy_curved_spaces::bench::BenchConfig,
    (progress, started, out): (&indicatif::ProgressBar, Instant, &std::path::Path),
    (family, ids): (&str, &str),
    run: impl Fn(
        &bevy_curved_spaces::bench::BenchConfig,
        &indicatif::ProgressBar,
    ) -> Result<
        bevy_curved_spaces::bench::BenchReport,
        bevy_curved_spaces::bench::BenchError,
    >,
    rows: impl Fn(
        &bevy_curved_spaces::bench::BenchReport,
    ) -> (&[bevy_curved_spaces::bench::FamilyRow], &'static str),
) -> Result<(), String> {
    eprintln!(
        "benchmarking {family} spaces {ids} at {:?} against {}…",
        config.sizes,
        bevy_curved_spaces::bench::PRODUCT_REFERENCE_SPACE
    );
    let report = run(config, progress).map_err(|e| e.to_string())?;
    let (rows, bound) = rows(&report);
    for r in rows {
        say!(
            "{:<8} {:>8.2} ms, {:.2}× {} ({} objects, budget {}), {:.2} crossings and {:.1} root iterations a pixel, {:.2} % of pixels differ from the CPU, walks f64 {:.3} / f32 {:.3} × {bound} (median)",
            r.space,
            r.tracer_ms,
            r.ratio,
            r.reference_space,
            r.objects,
            r.budget,
            r.crossings_per_pixel,
            r.root_iterations_per_pixel,
            100.0 * r.differing_pixels,
            r.f64_median,
            r.f32_median
        );
    }
    let written = bevy_curved_spaces::bench::write_edges_report(&report, config, out)
        .map_err(|e| e.to_string())?;
    say_written(&written, out, started);
    Ok(())
}
