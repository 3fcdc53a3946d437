//! Timing: GPU frame times of the tracer against the trivial material, interleaved in one
//! loop, for the budget sweep, the specialised shader, stereo and meshes.

use super::*;
use crate::plugin::render::gpu::{GpuScene, view_words};
use crate::scene::CurvedScene;
use crate::view::StereoMode;
use crate::view::stereo::{default_ipd, eye_frames};
use crate::view::{ViewKind, ViewLayout};

/// Median and spread of frame times (ms).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Stats {
    pub(super) frames: usize,
    pub(super) median: f64,
    pub(super) p10: f64,
    pub(super) p90: f64,
}

impl Stats {
    pub(super) fn of(mut times: Vec<f64>) -> Self {
        times.sort_by(f64::total_cmp);
        let at = |q: f64| times[((times.len() - 1) as f64 * q).round() as usize];
        Self {
            frames: times.len(),
            median: at(0.5),
            p10: at(0.1),
            p90: at(0.9),
        }
    }
}

/// The whole uniform of a view of `layout` onto a packed scene.
pub(super) fn uniform_words(layout: &ViewLayout, gpu: &GpuScene) -> Vec<u32> {
    let view = view_words(
        layout,
        [0, 0],
        &crate::plugin::render::gpu::ViewExtras::default(),
    );
    view.iter().chain(gpu.words.iter()).copied().collect()
}

/// Times the tracer and the baseline, alternating frame by frame so that both see the same
/// machine load; the first frame of each (pipeline compilation) is not counted.
pub(super) fn time_setting(
    harness: &mut Harness,
    subject: &Subject,
    gpu: &GpuScene,
    (w, h): (u32, u32),
    config: &BenchConfig,
) -> Result<(Stats, Stats), BenchError> {
    let tracer = Program::Tracer(gpu.key, ViewKind::Mono, Output::Colour);
    let frame = harness.frame(
        w,
        h,
        Output::Colour,
        &uniform_words(&subject.camera.layout(w, h), gpu),
        Some(gpu),
    );
    let baseline_frame = harness.frame(w, h, Output::Colour, &[], None);
    harness.draw(&tracer, &frame)?;
    harness.draw(&Program::Baseline, &baseline_frame)?;
    time_interleaved(
        harness,
        (&tracer, &frame),
        (&Program::Baseline, &baseline_frame),
        config,
    )
}

/// Times two programs frame by frame in turn (so both see the same machine load) for at
/// least `min_frames` and `min_seconds`, at most `max_frames`. Draw each once before: the
/// first frame compiles the pipeline.
pub(super) fn time_interleaved(
    harness: &mut Harness,
    a: (&Program, &Frame),
    b: (&Program, &Frame),
    config: &BenchConfig,
) -> Result<(Stats, Stats), BenchError> {
    let stats = time_in_turn(harness, &[a, b], config)?;
    Ok((stats[0], stats[1]))
}

/// [`time_interleaved`] for any number of programs, each drawn once per round.
pub(super) fn time_in_turn(
    harness: &mut Harness,
    programs: &[(&Program, &Frame)],
    config: &BenchConfig,
) -> Result<Vec<Stats>, BenchError> {
    Ok(time_rounds(harness, programs, config)?
        .into_iter()
        .map(Stats::of)
        .collect())
}

/// The median over rounds of `a[i] / b[i]`: a ratio of two programs timed in the same
/// rounds, each round's pair of frames drawn back to back, so that a slow spell of a shared
/// machine moves both.
pub(super) fn paired_ratio(a: &[f64], b: &[f64]) -> f64 {
    let ratios: Vec<f64> = a.iter().zip(b).map(|(x, y)| x / y).collect();
    Stats::of(ratios).median
}

/// Each program's frame times, drawn in turn round by round (see [`time_in_turn`]).
pub(super) fn time_rounds(
    harness: &mut Harness,
    programs: &[(&Program, &Frame)],
    config: &BenchConfig,
) -> Result<Vec<Vec<f64>>, BenchError> {
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); programs.len()];
    let start = std::time::Instant::now();
    let mut rounds = 0;
    while rounds < config.max_frames.max(1)
        && (rounds < config.min_frames.max(1) || start.elapsed().as_secs_f64() < config.min_seconds)
    {
        for ((program, frame), t) in programs.iter().zip(&mut times) {
            t.push(harness.draw(program, frame)?);
        }
        rounds += 1;
    }
    Ok(times)
}

/// A mono colour frame of `layout` onto each packed scene, with its tracer program, each
/// drawn once (compiling the pipeline and warming it up before it is timed).
pub(super) fn drawn_views(
    harness: &mut Harness,
    layout: &ViewLayout,
    (w, h): (u32, u32),
    scenes: &[&GpuScene],
) -> Result<Vec<(Program, Frame)>, BenchError> {
    let views: Vec<(Program, Frame)> = scenes
        .iter()
        .map(|gpu| {
            (
                Program::Tracer(gpu.key, ViewKind::Mono, Output::Colour),
                harness.frame(w, h, Output::Colour, &uniform_words(layout, gpu), Some(gpu)),
            )
        })
        .collect();
    for (program, frame) in &views {
        harness.draw(program, frame)?;
    }
    Ok(views)
}

/// The default view with the cell's edges culled (as drawn), unculled, and without edges,
/// timed in turn at the middle resolution.
pub(super) fn edges_cost(
    harness: &mut Harness,
    subject: &Subject,
    budget: u32,
    config: &BenchConfig,
) -> Result<EdgesRow, BenchError> {
    let with = subject.scene(DEFAULT_FOG_FACTOR);
    let without = CurvedScene::with_parts(
        &subject.space,
        DEFAULT_FOG_FACTOR * subject.inradius,
        crate::scene::SceneParts {
            edges: false,
            ..Default::default()
        },
    );
    let culled = subject.pack(&with, budget)?;
    let unculled = culled.without_culling();
    let none = subject.pack(&without, budget)?;
    let (w, h) = config.middle_size();
    let layout = subject.camera.layout(w, h);
    let runs = drawn_views(harness, &layout, (w, h), &[&culled, &unculled, &none])?;
    let programs: Vec<(&Program, &Frame)> = runs.iter().map(|(p, f)| (p, f)).collect();
    let times = time_rounds(harness, &programs, config)?;
    let ratio = paired_ratio(&times[0], &times[2]);
    let unculled_ratio = paired_ratio(&times[1], &times[2]);
    let stats: Vec<Stats> = times.into_iter().map(Stats::of).collect();
    // What each ray met, culled and not: the culling must not change it.
    let culled_ids = super::accuracy::gpu_pixels(harness, subject, &culled, budget, (w, h))?;
    let unculled_ids = super::accuracy::gpu_pixels(harness, subject, &unculled, budget, (w, h))?;
    let hit_ids_differing = culled_ids
        .ids
        .iter()
        .zip(&unculled_ids.ids)
        .filter(|(a, b)| a != b)
        .count();
    let work = super::edge_work::edge_work(subject, &with, budget, (w, h));
    Ok(EdgesRow {
        space: subject.id.clone(),
        geometry: subject.geometry(),
        width: w,
        height: h,
        budget,
        edge_objects: with.objects.len() - without.objects.len(),
        with_edges_ms: stats[0].median,
        unculled_ms: stats[1].median,
        without_edges_ms: stats[2].median,
        ratio,
        unculled_ratio,
        hit_ids_differing,
        segments_per_pixel: work.map_or(0.0, |x| x.segments_per_pixel),
        near_two_faces: work.map_or(0.0, |x| x.near_two_faces),
        blocks_near_two_faces: work.map_or(0.0, |x| x.blocks_near_two_faces),
        tests_per_segment: work.map_or(0.0, |x| x.tests_per_segment),
        segments_p90: work.map_or(0.0, |x| x.segments_p90),
        ns_per_segment: work.map_or(0.0, |x| {
            stats[0].median * 1e6 / (f64::from(w * h) * x.segments_per_pixel.max(1e-9))
        }),
        tiles: work.map_or_else(Default::default, |x| {
            super::TileShares::from_shares(x.tiles_parting)
        }),
        tiles_near_edge_before_parting: work.map_or(0.0, |x| x.tiles_near_edge_before_parting),
    })
}

/// The tracer against the straightforward one on the plainest view (see
/// [`StraightforwardRow`]) at the middle timed resolution, or `None` where the space's
/// scene cannot be drawn by the straightforward variant (a step cap).
pub(super) fn straightforward_cost(
    harness: &mut Harness,
    subject: &Subject,
    budget: u32,
    config: &BenchConfig,
) -> Result<Option<StraightforwardRow>, BenchError> {
    let g = subject.space.geometry();
    let mut scene = CurvedScene::with_parts(
        &subject.space,
        DEFAULT_FOG_FACTOR * subject.inradius,
        crate::scene::SceneParts {
            edges: false,
            centrepiece: crate::scene::Centrepiece::None,
            ..Default::default()
        },
    );
    scene
        .objects
        .push(crate::scene::Object::Ball(crate::scene::Ball::new(
            g,
            subject.space.centre(),
            0.3 * subject.inradius,
            glam::DVec3::new(1.0, 0.78, 0.45),
        )));
    let ours = subject.pack(&scene, budget)?;
    let Some(plain) = ours.straightforward() else {
        return Ok(None);
    };
    let (w, h) = config.middle_size();
    // A 90° horizontal field of view.
    let camera = crate::view::TraceCamera {
        fov_y_degrees: 2.0 * (f64::from(h) / f64::from(w)).atan().to_degrees(),
        ..subject.camera
    };
    let layout = camera.layout(w, h);
    let frames = drawn_views(harness, &layout, (w, h), &[&ours, &plain])?;
    let pixels: Vec<Vec<u8>> = frames
        .iter()
        .map(|(_, f)| harness.read_pixels(f))
        .collect::<Result<_, _>>()?;
    let differing = pixels[0]
        .chunks_exact(4)
        .zip(pixels[1].chunks_exact(4))
        .filter(|(x, y)| x.iter().zip(*y).any(|(a, b)| a.abs_diff(*b) > 2))
        .count();
    let programs: Vec<(&Program, &Frame)> = frames.iter().map(|(p, f)| (p, f)).collect();
    let times = time_rounds(harness, &programs, config)?;
    let ratio = paired_ratio(&times[0], &times[1]);
    let stats: Vec<Stats> = times.into_iter().map(Stats::of).collect();
    Ok(Some(StraightforwardRow {
        space: subject.id.clone(),
        geometry: subject.geometry(),
        width: w,
        height: h,
        budget,
        tracer_ms: stats[0].median,
        straightforward_ms: stats[1].median,
        ratio,
        differing_pixels: differing as f64 / f64::from(w * h),
    }))
}

/// Times the specialised and the unspecialised shader on the same view, interleaved, at the
/// middle timed resolution; `None` where the general shader cannot draw the scene (more
/// faces or objects than it holds, or several cells).
pub(super) fn specialisation(
    harness: &mut Harness,
    subject: &Subject,
    budget: u32,
    config: &BenchConfig,
) -> Result<Option<SpecialisationRow>, BenchError> {
    let scene = subject.scene(DEFAULT_FOG_FACTOR);
    let special = subject.pack(&scene, budget)?;
    let Some(general) = special.generalised() else {
        return Ok(None);
    };
    let (w, h) = config.middle_size();
    let mono = subject.camera.layout(w, h);
    let a = harness.frame(
        w,
        h,
        Output::Colour,
        &uniform_words(&mono, &special),
        Some(&special),
    );
    let b = harness.frame(
        w,
        h,
        Output::Colour,
        &uniform_words(&mono, &general),
        Some(&general),
    );
    let (pa, pb) = (
        Program::Tracer(special.key, ViewKind::Mono, Output::Colour),
        Program::Tracer(general.key, ViewKind::Mono, Output::Colour),
    );
    harness.draw(&pa, &a)?;
    harness.draw(&pb, &b)?;
    let pixels_a = harness.read_pixels(&a)?;
    let pixels_b = harness.read_pixels(&b)?;
    let differing = pixels_a
        .chunks_exact(4)
        .zip(pixels_b.chunks_exact(4))
        .filter(|(x, y)| x != y)
        .count();
    let (sa, sb) = time_interleaved(harness, (&pa, &a), (&pb, &b), config)?;
    Ok(Some(SpecialisationRow {
        space: subject.id.clone(),
        geometry: subject.geometry(),
        width: w,
        height: h,
        budget,
        specialised_ms: sa.median,
        general_ms: sb.median,
        gain: sb.median / sa.median,
        specialised_uniform_bytes: special.key.uniform_bytes(),
        general_uniform_bytes: general.key.uniform_bytes(),
        differing_pixels: differing as f64 / f64::from(w * h),
    }))
}

/// Times side-by-side and anaglyph stereo against mono at the middle timed resolution, each
/// interleaved with mono.
pub(super) fn stereo_cost(
    harness: &mut Harness,
    subject: &Subject,
    budget: u32,
    config: &BenchConfig,
) -> Result<StereoRow, BenchError> {
    let scene = subject.scene(DEFAULT_FOG_FACTOR);
    let gpu = subject.pack(&scene, budget)?;
    let (w, h) = config.middle_size();
    let ipd = default_ipd(subject.inradius);
    let eyes = eye_frames(&subject.space, subject.camera.frame, ipd).map(|e| e.frame);
    let frame_of = |harness: &mut Harness, mode: StereoMode| {
        let layout = ViewLayout::new(mode, false, eyes, subject.camera.fov_y_degrees, w, h);
        let words = uniform_words(&layout, &gpu);
        let program = Program::Tracer(gpu.key, mode.kind(), Output::Colour);
        (
            program,
            harness.frame(w, h, Output::Colour, &words, Some(&gpu)),
        )
    };
    let mono = frame_of(harness, StereoMode::Mono);
    let mut measured = Vec::new();
    for mode in [StereoMode::SideBySide, StereoMode::AnaglyphDubois] {
        let other = frame_of(harness, mode);
        harness.draw(&mono.0, &mono.1)?;
        harness.draw(&other.0, &other.1)?;
        let (m, o) = time_interleaved(harness, (&mono.0, &mono.1), (&other.0, &other.1), config)?;
        measured.push((m.median, o.median));
    }
    let [(mono_a, sbs), (mono_b, anaglyph)] = [measured[0], measured[1]];
    Ok(StereoRow {
        space: subject.id.clone(),
        geometry: subject.geometry(),
        width: w,
        height: h,
        budget,
        mono_ms: 0.5 * (mono_a + mono_b),
        side_by_side_ms: sbs,
        side_by_side_ratio: sbs / mono_a,
        anaglyph_ms: anaglyph,
        anaglyph_ratio: anaglyph / mono_b,
    })
}

/// The mesh of about `triangles` triangles: the cube for 12, else a torus knot whose
/// segments and sides give that count (`2·segments·sides`).
#[must_use]
pub fn bench_mesh(triangles: usize) -> crate::scene::mesh::MeshSource {
    if triangles <= 12 {
        return crate::scene::mesh::cube_source(1.0, 0);
    }
    let sides = ((triangles as f64 / 8.0).sqrt().round() as u32).max(3);
    let segments = ((triangles as f64 / (2.0 * f64::from(sides))).round() as u32).max(3);
    crate::scene::assets::torus_knot(3, 2, segments, sides)
}

/// Times the default scene (without its centre ball) with and without a mesh of about
/// `triangles` triangles at the cell's centre, interleaved, at the middle timed resolution.
pub(super) fn mesh_cost(
    harness: &mut Harness,
    subject: &Subject,
    triangles: usize,
    budget: u32,
    config: &BenchConfig,
) -> Result<MeshRow, BenchError> {
    use crate::scene::{MeshInstance, Object, SurfaceMaterial};
    let g = subject.space.geometry;
    let mut without = CurvedScene::with_parts(
        &subject.space,
        DEFAULT_FOG_FACTOR * subject.inradius,
        crate::scene::SceneParts {
            centrepiece: crate::scene::Centrepiece::None,
            ..Default::default()
        },
    );
    without.materials.push(SurfaceMaterial {
        colour: glam::DVec3::new(0.9, 0.6, 0.3),
        ..SurfaceMaterial::default()
    });
    let source = bench_mesh(triangles);
    let radius = source
        .positions
        .iter()
        .map(|p| p.length())
        .fold(0.0, f64::max);
    let started = std::time::Instant::now();
    let mesh = source
        .place(g, 0.5 * subject.inradius / radius)
        .map_err(|_| BenchError::Empty("the benchmark mesh could not be placed"))?;
    let build_ms = 1e3 * started.elapsed().as_secs_f64();
    let (nodes, depth, count) = (mesh.nodes.len(), mesh.depth(), mesh.triangles.len());
    let mut with = without.clone();
    let mesh_radius = mesh.radius;
    with.meshes.push(std::sync::Arc::new(mesh));
    with.objects.push(Object::Mesh(MeshInstance::new(
        g,
        0,
        g.rotation(glam::DVec3::new(1.0, 0.3, 0.2), 0.6),
        mesh_radius,
    )));
    let (w, h) = config.middle_size();
    let layout = subject.camera.layout(w, h);
    let frame_of = |harness: &mut Harness, scene: &CurvedScene| -> Result<_, BenchError> {
        let gpu = subject.pack(scene, budget)?;
        let program = Program::Tracer(gpu.key, ViewKind::Mono, Output::Colour);
        let frame = harness.frame(
            w,
            h,
            Output::Colour,
            &uniform_words(&layout, &gpu),
            Some(&gpu),
        );
        Ok((program, frame))
    };
    let a = frame_of(harness, &with)?;
    let b = frame_of(harness, &without)?;
    harness.draw(&a.0, &a.1)?;
    harness.draw(&b.0, &b.1)?;
    let (sa, sb) = time_interleaved(harness, (&a.0, &a.1), (&b.0, &b.1), config)?;
    Ok(MeshRow {
        space: subject.id.clone(),
        geometry: subject.geometry(),
        width: w,
        height: h,
        budget,
        triangles: count,
        nodes,
        depth,
        build_ms,
        with_mesh_ms: sa.median,
        without_mesh_ms: sb.median,
        ratio: sa.median / sb.median,
    })
}

/// A view timed in the same rounds as a reference view at `(w, h)`: each a packed scene and
/// the layout of its view. Returns the median over rounds of the view's time over the
/// reference's, and the two medians (ms).
pub(super) fn against_reference(
    harness: &mut Harness,
    config: &BenchConfig,
    (w, h): (u32, u32),
    (gpu, layout): (&GpuScene, &ViewLayout),
    (reference_gpu, reference_layout): (&GpuScene, &ViewLayout),
) -> Result<(f64, f64, f64), BenchError> {
    let program = Program::Tracer(gpu.key, ViewKind::Mono, Output::Colour);
    let reference_program = Program::Tracer(reference_gpu.key, ViewKind::Mono, Output::Colour);
    let timed = harness.frame(w, h, Output::Colour, &uniform_words(layout, gpu), Some(gpu));
    let reference_frame = harness.frame(
        w,
        h,
        Output::Colour,
        &uniform_words(reference_layout, reference_gpu),
        Some(reference_gpu),
    );
    harness.draw(&program, &timed)?;
    harness.draw(&reference_program, &reference_frame)?;
    let times = time_rounds(
        harness,
        &[(&program, &timed), (&reference_program, &reference_frame)],
        config,
    )?;
    let ratio = paired_ratio(&times[0], &times[1]);
    let stats: Vec<Stats> = times.into_iter().map(Stats::of).collect();
    Ok((ratio, stats[0].median, stats[1].median))
}

/// The GPU picture of a packed scene in `layout` against the CPU reference's `cpu` (same
/// size): the share of pixels whose largest channel difference passes `level` (of 255),
/// and the mean of that difference.
pub(super) fn gpu_against_cpu(
    harness: &mut Harness,
    gpu: &GpuScene,
    layout: &ViewLayout,
    cpu: &image::RgbImage,
    level: u8,
) -> Result<(f64, f64), BenchError> {
    let (w, h) = cpu.dimensions();
    let program = Program::Tracer(gpu.key, ViewKind::Mono, Output::Colour);
    let compared = harness.frame(w, h, Output::Colour, &uniform_words(layout, gpu), Some(gpu));
    harness.draw(&program, &compared)?;
    let gpu_pixels = harness.read_pixels(&compared)?;
    let (mut differing, mut sum) = (0usize, 0u64);
    for (g, c) in gpu_pixels.chunks_exact(4).zip(cpu.pixels()) {
        let worst = (0..3).map(|k| g[k].abs_diff(c.0[k])).max().unwrap_or(0);
        differing += usize::from(worst > level);
        sum += u64::from(worst);
    }
    let n = f64::from(w * h);
    Ok((differing as f64 / n, sum as f64 / n))
}
