//! The benchmark's runs: the full one, the scene, edges and straightforward comparisons.

use super::*;

/// Times only the tracer against the straightforward one ([`StraightforwardRow`]), for
/// each of `config.spaces` and `config.budgets` at the middle of `config.sizes`.
pub fn run_straightforward(
    config: &BenchConfig,
    progress: &ProgressBar,
) -> Result<BenchReport, BenchError> {
    if config.spaces.is_empty() || config.sizes.is_empty() || config.budgets.is_empty() {
        return Err(BenchError::Empty("no spaces, sizes or budgets were named"));
    }
    let mut harness = Harness::new()?;
    progress.set_length((config.spaces.len() * config.budgets.len()) as u64);
    let mut report = BenchReport::empty(Some(&harness));
    for id in &config.spaces {
        let subject = Subject::new(id)?;
        for &budget in &config.budgets {
            announce(
                progress,
                format!(
                    "{} at {budget} crossings: against a straightforward tracer",
                    subject.id
                ),
            );
            report.straightforward.extend(straightforward_cost(
                &mut harness,
                &subject,
                budget,
                config,
            )?);
            progress.inc(1);
        }
    }
    progress.finish_and_clear();
    Ok(report)
}

/// Times only what the cell's edges cost ([`EdgesRow`]): the default view with its edges
/// culled, unculled and absent, in turn, for each of `config.spaces` at the first of
/// `config.budgets` and the middle of `config.sizes`. Seconds per space where the full
/// benchmark takes minutes, for working on the edges' cost.
pub fn run_edges(config: &BenchConfig, progress: &ProgressBar) -> Result<BenchReport, BenchError> {
    let budget = single_budget(config)?;
    let mut harness = Harness::new()?;
    progress.set_length(config.spaces.len() as u64);
    let mut report = BenchReport::empty(Some(&harness));
    for id in &config.spaces {
        let subject = Subject::new(id)?;
        announce(
            progress,
            format!("{}: edges culled, unculled and none", subject.id),
        );
        report
            .edges
            .push(edges_cost(&mut harness, &subject, budget, config)?);
        progress.inc(1);
    }
    progress.finish_and_clear();
    Ok(report)
}

/// The first of `config.budgets`, for the runs that time one budget per space at one size;
/// an error where no budget, space or size was named.
pub(super) fn single_budget(config: &BenchConfig) -> Result<u32, BenchError> {
    let budget = *config
        .budgets
        .first()
        .ok_or(BenchError::Empty("no crossing budget was given"))?;
    if config.spaces.is_empty() || config.sizes.is_empty() {
        return Err(BenchError::Empty("no spaces or sizes were named"));
    }
    Ok(budget)
}

/// Times a scene file's start view (its space, objects, lights, fog, parts, and its `fov`)
/// at each of `config.budgets` × `config.sizes`, against the trivial material in the same
/// loop: one [`TimingRow`] per budget and size, `space` being the file's name. Nothing else
/// of the benchmark is measured.
#[cfg(feature = "scene-files")]
pub fn run_scene(
    config: &BenchConfig,
    path: &std::path::Path,
    progress: &ProgressBar,
) -> Result<BenchReport, BenchError> {
    let file = crate::scene::file::load_scene_file(path)
        .map_err(|e| BenchError::SceneFile(e.to_string()))?;
    let space = file.space.clone();
    let default_view = TraceCamera::default_for(&space);
    let subject = Subject {
        id: path.file_stem().map_or_else(
            || path.display().to_string(),
            |s| s.to_string_lossy().into_owned(),
        ),
        inradius: invariants::inradius(&space),
        camera: TraceCamera {
            frame: file.start.unwrap_or(default_view.frame),
            fov_y_degrees: file.start_fov.unwrap_or(default_view.fov_y_degrees),
        },
        space,
    };
    let scene = file.base.adding_parts(&subject.space, file.parts);
    let mut harness = Harness::new()?;
    progress.set_length((config.budgets.len() * config.sizes.len()) as u64);
    let mut report = BenchReport::empty(Some(&harness));
    for &budget in &config.budgets {
        let gpu = subject.pack(&scene, budget)?;
        for &(w, h) in &config.sizes {
            announce(
                progress,
                format!("{}: budget {budget} at {w}×{h}", subject.id),
            );
            let (tracer, baseline) =
                timing::time_setting(&mut harness, &subject, &gpu, (w, h), config)?;
            report.timings.push(TimingRow {
                space: subject.id.clone(),
                geometry: subject.geometry(),
                width: w,
                height: h,
                budget,
                budget_from: "fixed".into(),
                fog_factor: scene.shading.fog_distance / subject.inradius,
                frames: tracer.frames,
                median_ms: tracer.median,
                p10_ms: tracer.p10,
                p90_ms: tracer.p90,
                baseline_ms: baseline.median,
                ratio: tracer.median / baseline.median,
            });
            progress.inc(1);
        }
    }
    progress.finish_and_clear();
    Ok(report)
}

/// Mean and 90th percentile of the face crossings per pixel of a `HIT_ID` picture.
fn crossings_per_pixel(ids: &[[u32; 4]]) -> (f64, f64) {
    if ids.is_empty() {
        return (0.0, 0.0);
    }
    let mut c: Vec<u32> = ids.iter().map(|id| id[1]).collect();
    c.sort_unstable();
    let mean = c.iter().map(|&x| f64::from(x)).sum::<f64>() / c.len() as f64;
    let p90 = f64::from(c[((c.len() - 1) as f64 * 0.9).round() as usize]);
    (mean, p90)
}

/// The fog factor (λ / inradius) of the spaces' default fog.
pub const DEFAULT_FOG_FACTOR: f64 = crate::scene::Shading::DEFAULT_FOG_INRADII;

/// Runs the benchmark; `progress` draws a bar on a terminal (hidden otherwise).
pub fn run(config: &BenchConfig, progress: &ProgressBar) -> Result<BenchReport, BenchError> {
    if config.spaces.is_empty() {
        return Err(BenchError::Empty("no spaces were named"));
    }
    let subjects = config
        .spaces
        .iter()
        .map(|id| Subject::new(id))
        .collect::<Result<Vec<_>, _>>()?;
    let mut harness = if config.cpu_only {
        None
    } else {
        Some(Harness::new()?)
    };
    let gpu_steps = if harness.is_some() {
        (config.budgets.len() + config.fog_factors.len()) * (config.sizes.len() + 1)
            + 3
            + config.mesh_triangles.len()
    } else {
        0
    };
    let per_space = gpu_steps + 2 + config.fog_factors.len();
    let product_steps = if harness.is_some() {
        config.products.len() + config.nil.len() + config.sl2r.len()
    } else {
        0
    };
    progress.set_length((per_space * subjects.len() + product_steps) as u64);
    progress.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} {msg} (eta {eta})",
        )
        .expect("a valid progress template"),
    );
    let mut report = BenchReport::empty(harness.as_ref());
    for subject in &subjects {
        let budgets = cpu_measurements(subject, config, progress, &mut report);
        if let Some(harness) = harness.as_mut() {
            gpu_measurements(harness, subject, &budgets, config, progress, &mut report)?;
        }
    }
    if let Some(harness) = harness.as_mut() {
        report.products = products::product_rows(harness, config, progress)?;
        report.nil = nil::nil_rows(harness, config, progress)?;
        report.sl2r = sl2r::sl2r_rows(harness, config, progress)?;
    }
    progress.finish_and_clear();
    Ok(report)
}

/// What needs no GPU: the f32 drift, the automatic budgets and the fog cut-off's error.
fn cpu_measurements(
    subject: &Subject,
    config: &BenchConfig,
    progress: &ProgressBar,
    report: &mut BenchReport,
) -> ChosenBudgets {
    announce(progress, format!("{}: f32 drift", subject.id));
    report.drift.extend(drift(subject, config));
    announce(
        progress,
        format!("{}: walks against the double-double reference", subject.id),
    );
    let (rows, curve) = conditioning(subject, config);
    report.conditioning.extend(rows);
    report.conditioning_curve.extend(curve);
    progress.inc(1);
    announce(progress, format!("{}: automatic budgets", subject.id));
    let mut budgets = Vec::new();
    for &fog in &config.fog_factors {
        let scene = subject.scene(fog);
        for quality in [Quality::Low, Quality::Medium, Quality::High] {
            let allowed = quality.miss_fraction();
            let choice = auto_budget(&subject.space, &scene, allowed, config.budget_samples);
            budgets.push((fog, quality, choice.budget));
            report.auto_budgets.push(AutoBudgetRow {
                space: subject.id.clone(),
                geometry: subject.geometry(),
                quality: format!("{quality:?}").to_lowercase(),
                fog_factor: fog,
                miss_fraction_allowed: allowed,
                choice,
            });
        }
    }
    progress.inc(1);
    for &fog in &config.fog_factors {
        announce(
            progress,
            format!("{}: fog cut-off at λ = {fog} inradii", subject.id),
        );
        report.cutoff.push(cutoff(subject, fog, config.error_size));
        progress.inc(1);
    }
    budgets
}

/// Frame times and errors on the GPU: the specialised shader, stereo and meshes at the
/// automatic budget, then the budget sweep at the default fog and the fog sweep at the
/// automatic budget, each timed and compared with the f64 reference.
fn gpu_measurements(
    harness: &mut Harness,
    subject: &Subject,
    budgets: &ChosenBudgets,
    config: &BenchConfig,
    progress: &ProgressBar,
    report: &mut BenchReport,
) -> Result<(), BenchError> {
    // The budget sweep at the default fog, then the fog sweep at the automatic budget.
    let mut settings: Vec<(u32, String, f64)> = config
        .budgets
        .iter()
        .map(|&b| (b, "fixed".to_string(), DEFAULT_FOG_FACTOR))
        .collect();
    for &fog in &config.fog_factors {
        let budget = budgets
            .iter()
            .find(|(f, q, _)| *f == fog && *q == Quality::High)
            .map_or(64, |b| b.2);
        settings.push((budget, "auto-high".to_string(), fog));
    }
    announce(
        progress,
        format!("{}: specialised against general shader", subject.id),
    );
    let auto_default = budgets
        .iter()
        .find(|(f, q, _)| *f == DEFAULT_FOG_FACTOR && *q == Quality::High)
        .map_or(32, |b| b.2);
    match specialisation(harness, subject, auto_default, config)? {
        Some(row) => report.specialisation.push(row),
        None => announce(
            progress,
            format!(
                "{}: no general-shader row (the general shader walks one cell of at most \
                 128 faces, balls and tubes only)",
                subject.id
            ),
        ),
    }
    progress.inc(1);
    announce(progress, format!("{}: stereo against mono", subject.id));
    report
        .stereo
        .push(stereo_cost(harness, subject, auto_default, config)?);
    progress.inc(1);
    announce(
        progress,
        format!("{}: edges culled, unculled and none", subject.id),
    );
    report
        .edges
        .push(edges_cost(harness, subject, auto_default, config)?);
    progress.inc(1);
    for budget in [16, 32] {
        if config.budgets.contains(&budget) {
            announce(
                progress,
                format!(
                    "{} at {budget} crossings: against a straightforward tracer",
                    subject.id
                ),
            );
            report
                .straightforward
                .extend(straightforward_cost(harness, subject, budget, config)?);
        }
    }
    for &triangles in &config.mesh_triangles {
        announce(
            progress,
            format!("{}: a mesh of {triangles} triangles", subject.id),
        );
        report.meshes.push(mesh_cost(
            harness,
            subject,
            triangles,
            auto_default,
            config,
        )?);
        progress.inc(1);
    }
    let mut exact_cache: Vec<(f64, Reference)> = Vec::new();
    for (budget, from, fog) in settings {
        let scene = subject.scene(fog);
        let gpu = subject.pack(&scene, budget)?;
        for &(w, h) in &config.sizes {
            announce(
                progress,
                format!(
                    "{}: {w}×{h}, budget {budget}, λ = {fog} inradii",
                    subject.id
                ),
            );
            let (stats, baseline) = time_setting(harness, subject, &gpu, (w, h), config)?;
            report.timings.push(TimingRow {
                space: subject.id.clone(),
                geometry: subject.geometry(),
                width: w,
                height: h,
                budget,
                budget_from: from.clone(),
                fog_factor: fog,
                frames: stats.frames,
                median_ms: stats.median,
                p10_ms: stats.p10,
                p90_ms: stats.p90,
                baseline_ms: baseline.median,
                ratio: stats.median / baseline.median,
            });
            progress.inc(1);
        }
        announce(
            progress,
            format!(
                "{}: accuracy, budget {budget}, λ = {fog} inradii",
                subject.id
            ),
        );
        let exact = match exact_cache.iter().find(|(f, _)| *f == fog) {
            Some((_, r)) => r.clone(),
            None => {
                let r = Reference::trace(subject, &scene, config.error_size, EXACT_BUDGET, false);
                exact_cache.push((fog, r.clone()));
                r
            }
        };
        let same = Reference::trace(subject, &scene, config.error_size, budget as usize, false);
        let rounded = Reference::trace(subject, &scene, config.error_size, budget as usize, true);
        let measured = gpu_pixels(harness, subject, &gpu, budget, config.error_size)?;
        let against_exact = measured.compare(&exact);
        let work = crossings_per_pixel(&measured.ids);
        let against_same = measured.compare(&same);
        report.errors.push(ErrorRow {
            space: subject.id.clone(),
            geometry: subject.geometry(),
            budget,
            budget_from: from,
            fog_factor: fog,
            width: config.error_size.0,
            height: config.error_size.1,
            hit_differs: against_exact.hit_differs,
            hit_differs_same_budget: against_same.hit_differs,
            hit_floor_f32: rounded.compare(&same).hit_differs,
            budget_exhausted: measured.exhausted as f64
                / f64::from(config.error_size.0 * config.error_size.1),
            mean_levels: against_exact.mean_levels,
            max_levels: against_exact.max_levels,
            over_2_levels: against_exact.over_2_levels,
            over_10_levels: against_exact.over_10_levels,
            mean_crossings: work.0,
            p90_crossings: work.1,
        });
        progress.inc(1);
    }
    Ok(())
}

/// Measures only the product spaces ([`ProductRow`]): each default view timed against
/// [`products::PRODUCT_REFERENCE_SPACE`]'s in the same rounds, the GPU against the CPU
/// reference, and the walks against double-double.
pub fn run_products(
    config: &BenchConfig,
    progress: &ProgressBar,
) -> Result<BenchReport, BenchError> {
    if config.products.is_empty() || config.sizes.is_empty() {
        return Err(BenchError::Empty("no product spaces or sizes were named"));
    }
    products::check_products(&config.products)?;
    let mut harness = Harness::new()?;
    progress.set_length(config.products.len() as u64);
    let mut report = BenchReport::empty(Some(&harness));
    report.products = products::product_rows(&mut harness, config, progress)?;
    progress.finish_and_clear();
    Ok(report)
}

/// Only the Nil spaces of `config.nil`: each default view timed against
/// [`products::PRODUCT_REFERENCE_SPACE`]'s in the same rounds, the GPU against the CPU
/// reference, the walks against the exact geodesic ([`super::FamilyRow`]).
pub fn run_nil(config: &BenchConfig, progress: &ProgressBar) -> Result<BenchReport, BenchError> {
    if config.nil.is_empty() || config.sizes.is_empty() {
        return Err(BenchError::Empty("no Nil spaces or sizes were named"));
    }
    nil::check_nil(&config.nil)?;
    let mut harness = Harness::new()?;
    progress.set_length(config.nil.len() as u64);
    let mut report = BenchReport::empty(Some(&harness));
    report.nil = nil::nil_rows(&mut harness, config, progress)?;
    progress.finish_and_clear();
    Ok(report)
}

/// Only the SL̃(2,R) spaces of `config.sl2r`: each default view timed against
/// [`products::PRODUCT_REFERENCE_SPACE`]'s in the same rounds, the GPU against the CPU
/// reference, the walks against the double-double walk over the conditioning limit
/// ([`super::FamilyRow`]).
pub fn run_sl2r(config: &BenchConfig, progress: &ProgressBar) -> Result<BenchReport, BenchError> {
    if config.sl2r.is_empty() || config.sizes.is_empty() {
        return Err(BenchError::Empty("no SL̃(2,R) spaces or sizes were named"));
    }
    sl2r::check_sl2r(&config.sl2r)?;
    let mut harness = Harness::new()?;
    progress.set_length(config.sl2r.len() as u64);
    let mut report = BenchReport::empty(Some(&harness));
    report.sl2r = sl2r::sl2r_rows(&mut harness, config, progress)?;
    progress.finish_and_clear();
    Ok(report)
}
