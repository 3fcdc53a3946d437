//! `flight`: a flight file's frames rendered to PNG files (and a video where ffmpeg is
//! installed), resumable and sliceable across machines.

use super::FlightArgs;
use super::render::{Choice, Chosen, choose};
use bevy::prelude::*;
use bevy_curved_spaces::plugin::components::{AUTO_BUDGET_SAMPLES, ActiveSpace, Quality};
use bevy_curved_spaces::plugin::offscreen::{OffscreenRender, OffscreenRenderer};
use bevy_curved_spaces::plugin::render::gpu::MAX_GPU_BUDGET;
use bevy_curved_spaces::scene::flight::{Flight, load_flight_file};
use bevy_curved_spaces::space::motion::CoverFlight;
use bevy_curved_spaces::trace::{RenderSettings, auto_budget, render_view};
use bevy_curved_spaces::view::{TraceCamera, ViewLayout};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// `A..B` (1-based, inclusive) into a range of frame numbers.
pub(super) fn parse_frames(s: &str) -> Result<(usize, usize), String> {
    let err = || format!("expected frames A..B like 1..30 (1 ≤ A ≤ B), got `{s}`");
    let (a, b) = s.split_once("..").ok_or_else(err)?;
    let a: usize = a.trim().parse().map_err(|_| err())?;
    let b: usize = b.trim().parse().map_err(|_| err())?;
    if a == 0 || b < a {
        return Err(err());
    }
    Ok((a, b))
}

/// The file of frame `n` (1-based) in `dir`.
#[must_use]
pub(super) fn frame_path(dir: &Path, n: usize) -> PathBuf {
    dir.join(format!("frame-{n:05}.png"))
}

pub(super) fn flight(args: &FlightArgs) -> Result<(), String> {
    let name = args.file.display().to_string();
    let file = load_flight_file(&args.file)?;
    let base = args.file.parent().unwrap_or(Path::new(""));
    let choice = match (&file.scene, &file.space) {
        (Some(scene), _) => choose("", Some(&base.join(scene)), None)?,
        (None, Some(space)) => choose(space, None, None)?,
        (None, None) => return Err(format!("{name}: a flight names a space or a scene")),
    };
    let chosen: Chosen = match choice {
        Choice::Constant(chosen) => chosen,
        Choice::Product(product) => return flight_product(args, &name, &file, product),
        Choice::Nil(chosen) => return flight_nil(args, &name, &file, chosen),
        Choice::Sl2r(chosen) => return flight_sl2r(args, &name, &file, chosen),
    };
    let space = &chosen.space;
    let flight = Flight::new(space, &file).map_err(|e| format!("{name}: {e}"))?;
    let total = flight.frame_count(args.fps);
    let (first, last, todo) = frames_to_do(args, total)?;
    let budget = match args.crossings {
        Some(n) => n,
        None => {
            let choice = auto_budget(
                space,
                &chosen.scene,
                Quality::High.miss_fraction(),
                AUTO_BUDGET_SAMPLES,
            );
            choice.budget as usize
        }
    };
    if !args.cpu && !(1..=MAX_GPU_BUDGET as usize).contains(&budget) {
        return Err(format!(
            "the GPU tracer takes a crossing budget from 1 to {MAX_GPU_BUDGET}, got {budget} (use --cpu for more)"
        ));
    }
    // One active space for every frame: its invariants are computed once.
    let active = ActiveSpace::new(&chosen.id, space.clone());
    let walls = args.walls.style(chosen.scene.shading.walls)?;
    render_frames(
        args,
        &format!("flight {name}: {} ({})", chosen.id, space.geometry().name()),
        (total, flight.duration()),
        (first, last, &todo),
        budget,
        |n, t, renderer| {
            let frame = flight.frame(space, t);
            let camera = TraceCamera {
                frame,
                fov_y_degrees: flight.fov,
            };
            // Moving objects where they are at the frame's time.
            let at = chosen.at(t).map_err(|e| format!("frame {n}: {e}"))?;
            let mut scene = at.scene.clone();
            scene.time = t;
            scene.shading.colour_by = args.colour_by.into();
            scene.shading.walls = walls;
            scene.set_lighting(space, args.light.lighting(scene.shading.lighting))?;
            scene.set_avatar_frame(space, frame);
            let image = match renderer {
                None => {
                    let settings = RenderSettings {
                        width: args.size.0,
                        height: args.size.1,
                        max_crossings: budget,
                    };
                    let layout =
                        ViewLayout::camera(frame, flight.fov, settings.width, settings.height);
                    render_view(space, &scene, &layout, &settings, |_, _| {})
                }
                Some(r) => r
                    .render(&OffscreenRender {
                        fog_distance: Some(chosen.scene.shading.fog_distance),
                        parts: chosen.parts,
                        base: at.base.clone(),
                        time: t,
                        colour_by: args.colour_by.into(),
                        walls,
                        lighting: Some(scene.shading.lighting),
                        ..OffscreenRender::new(active.clone(), camera, args.size, budget as u32)
                    })
                    .map_err(|e| format!("frame {n}: {e}"))?,
            };
            Ok(image)
        },
    )
}

/// The frames to render: `--frames` within the flight's `total`, less those on disk.
fn frames_to_do(args: &FlightArgs, total: usize) -> Result<(usize, usize, Vec<usize>), String> {
    let (first, last) = match args.frames {
        Some((a, b)) if a > total => {
            return Err(format!(
                "--frames {a}..{b}: the flight has {total} frames at {} fps",
                args.fps
            ));
        }
        Some((a, b)) => (a, b.min(total)),
        None => (1, total),
    };
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create folder {}: {e}", args.out.display()))?;
    let todo: Vec<usize> = (first..=last)
        .filter(|&n| !frame_path(&args.out, n).exists())
        .collect();
    if todo.len() < last + 1 - first {
        say!(
            "{} of the frames are rendered already; rendering the other {}",
            last + 1 - first - todo.len(),
            todo.len()
        );
    }
    Ok((first, last, todo))
}

/// Says what the flight renders (`what` names the file and the space), starts the GPU
/// renderer unless `--cpu`, and a progress bar over the frames to do.
fn start_frames(
    args: &FlightArgs,
    what: &str,
    (total, duration): (usize, f64),
    (first, last, todo): (usize, usize, usize),
    budget: usize,
) -> Result<(Option<OffscreenRenderer>, indicatif::ProgressBar), String> {
    say!(
        "{what}, {total} frames at {} fps ({duration:.2} s), frames {first}..{last} at {}×{} by the {} tracer, ≤ {budget} crossings, into {}",
        args.fps,
        args.size.0,
        args.size.1,
        if args.cpu { "f64 CPU" } else { "GPU" },
        args.out.display()
    );
    let renderer = if args.cpu {
        None
    } else {
        Some(OffscreenRenderer::new().map_err(|e| e.to_string())?)
    };
    Ok((renderer, frame_progress(todo)?))
}

/// Renders the frames `todo` of a flight: says what (`what` names the file and the space),
/// starts the GPU renderer unless `--cpu`, draws each frame by `frame(n, t, renderer)` (its
/// number and time; the renderer where the GPU draws), writes it, and finishes with the
/// summary and the video.
fn render_frames(
    args: &FlightArgs,
    what: &str,
    (total, duration): (usize, f64),
    (first, last, todo): (usize, usize, &[usize]),
    budget: usize,
    mut frame: impl FnMut(usize, f64, Option<&mut OffscreenRenderer>) -> Result<image::RgbImage, String>,
) -> Result<(), String> {
    let (mut renderer, progress) = start_frames(
        args,
        what,
        (total, duration),
        (first, last, todo.len()),
        budget,
    )?;
    let started = Instant::now();
    for &n in todo {
        let t = (n - 1) as f64 / args.fps;
        let image = frame(n, t, renderer.as_mut())?;
        let path = frame_path(&args.out, n);
        bevy_curved_spaces::files::write_png(&path, &image)
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        progress.inc(1);
    }
    progress.finish_and_clear();
    finish_frames(args, todo.len(), started, (first, last, total));
    Ok(())
}

/// A progress bar over `n` frames.
fn frame_progress(n: usize) -> Result<indicatif::ProgressBar, String> {
    let progress = indicatif::ProgressBar::new(n as u64);
    progress.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:30} {pos}/{len} frames ({elapsed} elapsed, eta {eta}) {msg}",
        )
        .map_err(|e| e.to_string())?,
    );
    Ok(progress)
}

/// The summary after the frames, and the video once all are there.
fn finish_frames(
    args: &FlightArgs,
    done: usize,
    started: Instant,
    (first, last, total): (usize, usize, usize),
) {
    say!(
        "rendered {done} frames in {:.1} s into {}",
        started.elapsed().as_secs_f64(),
        args.out.display()
    );
    if (first, last) == (1, total) {
        encode_video(&args.out, args.fps);
    } else {
        say!(
            "frames {first}..{last} of {total}: the video is made when all are rendered (run without --frames, or ffmpeg by hand)"
        );
    }
}

/// `flight` in a product space (H²×R, S²×R): its default scene or its scene file's along
/// the flight.
fn flight_product(
    args: &FlightArgs,
    name: &str,
    file: &bevy_curved_spaces::scene::flight::FlightFile,
    chosen: super::render::ProductChoice,
) -> Result<(), String> {
    use bevy_curved_spaces::trace::product::flight::ProductFlight;
    use bevy_curved_spaces::trace::product::{product_auto_budget, render_product};
    let space = &chosen.space;
    let flight = ProductFlight::new(space, file).map_err(|e| format!("{name}: {e}"))?;
    let total = flight.frame_count(args.fps);
    let (first, last, todo) = frames_to_do(args, total)?;
    let mut scene = chosen.scene;
    scene.walls = args.walls.style(scene.walls)?.filter(|w| w.opening < 1.0);
    scene.colour_by = args.colour_by.into();
    // A scene file's moving balls fly as the frames go on.
    let moving = chosen.base.map(|b| b.moving).unwrap_or_default();
    let scene_at = |t: f64| -> Result<_, String> {
        let mut at = scene.clone();
        at.objects.extend(
            bevy_curved_spaces::trace::product::moving::movers_at(space, &moving, t)
                .map_err(|e| format!("at {t} s: {e}"))?,
        );
        Ok(at)
    };
    let budget = match args.crossings {
        Some(n) => n,
        None => {
            let eye = flight.camera(space, 0.0).point;
            product_auto_budget(
                space,
                &scene,
                eye,
                Quality::High.miss_fraction(),
                AUTO_BUDGET_SAMPLES,
            )
            .budget as usize
        }
    };
    if !args.cpu && !(1..=MAX_GPU_BUDGET as usize).contains(&budget) {
        return Err(format!(
            "the GPU tracer takes a crossing budget from 1 to {MAX_GPU_BUDGET}, got {budget} (use --cpu for more)"
        ));
    }
    render_frames(
        args,
        &format!(
            "flight {name}: {} ({})",
            space.name(),
            space.geometry_name()
        ),
        (total, flight.duration()),
        (first, last, &todo),
        budget,
        |n, t, renderer| {
            let camera = flight.camera(space, t);
            let scene = scene_at(t).map_err(|e| format!("frame {n}: {e}"))?;
            let image = match renderer {
                None => render_product(space, &scene, &camera, args.size.0, args.size.1, budget),
                Some(r) => r
                    .render_product(space, &scene, &camera, args.size, budget as u32)
                    .map_err(|e| format!("frame {n}: {e}"))?,
            };
            Ok(image)
        },
    )
}

/// `flight` in a Nil space: its default scene or its scene file's along the flight, with
/// the f64 CPU reference (`--cpu`) or on the GPU.
fn flight_nil(
    args: &FlightArgs,
    name: &str,
    file: &bevy_curved_spaces::scene::flight::FlightFile,
    chosen: super::render::NilChoice,
) -> Result<(), String> {
    use bevy_curved_spaces::space::{Family, Feature};
    use bevy_curved_spaces::trace::nil::flight::NilFlight;
    use bevy_curved_spaces::trace::nil::{NilCamera, render_nil_view};
    let space = &*chosen.space;
    let refuse = |feature| super::spaces::require(Family::Nil, space.name(), feature);
    if args.colour_by == super::ColourByArg::Holonomy {
        refuse(Feature::HolonomyView)?;
    }
    let flight = NilFlight::new(space, file).map_err(|e| format!("{name}: {e}"))?;
    // The scene at a frame's time: its moving balls where they are, the flight's options.
    let walls = args
        .walls
        .style(chosen.scene.walls)?
        .filter(|w| w.opening < 1.0);
    let scene_at = |t: f64| -> Result<_, String> {
        let mut scene = chosen.scene_at(t)?;
        scene.walls = walls;
        scene.colour_by = args.colour_by.into();
        if args.light.any() {
            let lighting = args.light.lighting(scene.lighting);
            let light = scene.light;
            scene.set_lighting(space, light, lighting)?;
        }
        Ok(scene)
    };
    let budget = args
        .crossings
        .unwrap_or_else(|| bevy_curved_spaces::plugin::nil::default_nil_budget(space) as usize);
    fly_own_tracer(
        args,
        &format!("flight {name}: {} (Nil)", space.name()),
        (&flight, space, flight.fov),
        budget,
        |n, t, layout| {
            let scene = scene_at(t).map_err(|e| format!("frame {n}: {e}"))?;
            Ok(render_nil_view(space, &scene, layout, budget))
        },
        |n, t, renderer, frame, gpu_budget| {
            let scene = scene_at(t).map_err(|e| format!("frame {n}: {e}"))?;
            let camera = NilCamera {
                frame,
                fov_y_degrees: flight.fov,
            };
            renderer
                .render_nil(
                    space,
                    &scene,
                    &camera,
                    args.size,
                    gpu_budget,
                    Default::default(),
                )
                .map_err(|e| format!("frame {n}: {e}"))
        },
    )
}

/// `flight` in an SL̃(2,R) space: its default scene or its scene file's along the flight,
/// with the f64 CPU reference (`--cpu`) or on the GPU.
fn flight_sl2r(
    args: &FlightArgs,
    name: &str,
    file: &bevy_curved_spaces::scene::flight::FlightFile,
    chosen: super::render::Sl2rChoice,
) -> Result<(), String> {
    use bevy_curved_spaces::space::{Family, Feature};
    use bevy_curved_spaces::trace::sl2r::flight::Sl2rFlight;
    use bevy_curved_spaces::trace::sl2r::{Sl2rCamera, render_sl2r_view};
    let space = &*chosen.space;
    let refuse = |feature| super::spaces::require(Family::Sl2r, space.name(), feature);
    if args.colour_by == super::ColourByArg::Holonomy {
        refuse(Feature::HolonomyView)?;
    }
    let flight = Sl2rFlight::new(file)
        .map_err(|e| format!("{name}: {e}"))?
        .in_space(space);
    let mut scene = chosen.scene;
    if args.light.any() {
        let lighting = args.light.lighting(scene.lighting);
        let light = (scene.light, scene.light_sheet);
        scene
            .set_lighting(space, light, lighting)
            .map_err(|e| format!("{name}: {e}"))?;
    }
    scene.colour_by = args.colour_by.into();
    scene.walls = args.walls.style(scene.walls)?.filter(|w| w.opening < 1.0);
    let budget = args
        .crossings
        .unwrap_or(bevy_curved_spaces::plugin::sl2r::DEFAULT_SL2R_BUDGET as usize);
    fly_own_tracer(
        args,
        &format!("flight {name}: {} (SL̃(2,R))", space.name()),
        (&flight, space, flight.fov),
        budget,
        |_, _, layout| Ok(render_sl2r_view(space, &scene, layout, budget)),
        |n, _, renderer, frame, gpu_budget| {
            let camera = Sl2rCamera {
                frame,
                fov_y_degrees: flight.fov,
            };
            renderer
                .render_sl2r(
                    space,
                    &scene,
                    &camera,
                    args.size,
                    gpu_budget,
                    Default::default(),
                )
                .map_err(|e| format!("frame {n}: {e}"))
        },
    )
}

/// The frames of a flight in a family with its own tracer (Nil, SL̃(2,R)): at each frame's
/// time the camera's frame in the cell, drawn by `cpu` on the view of that camera
/// (`--cpu`) or by `gpu` with the renderer and the budget checked for it.
fn fly_own_tracer<F: CoverFlight>(
    args: &FlightArgs,
    what: &str,
    (flight, space, fov): (&F, &F::Space, f64),
    budget: usize,
    cpu: impl Fn(usize, f64, &bevy_curved_spaces::view::ViewLayout) -> Result<image::RgbImage, String>,
    gpu: impl Fn(
        usize,
        f64,
        &mut OffscreenRenderer,
        glam::DMat4,
        u32,
    ) -> Result<image::RgbImage, String>,
) -> Result<(), String> {
    let total = flight.frame_count(args.fps);
    let (first, last, todo) = frames_to_do(args, total)?;
    let gpu_budget = if args.cpu {
        0
    } else {
        super::render::gpu_budget(budget)?
    };
    render_frames(
        args,
        what,
        (total, flight.duration()),
        (first, last, &todo),
        budget,
        |n, t, renderer| {
            let frame = flight.frame_in_cell(space, t).0;
            match renderer {
                None => cpu(
                    n,
                    t,
                    &bevy_curved_spaces::view::ViewLayout::camera(
                        frame,
                        fov,
                        args.size.0,
                        args.size.1,
                    ),
                ),
                Some(r) => gpu(n, t, r, frame, gpu_budget),
            }
        },
    )
}

/// `DIR/flight.mp4` from the frames, where ffmpeg is installed (else a note how).
fn encode_video(dir: &Path, fps: f64) {
    let video = dir.join("flight.mp4");
    let status = Command::new("ffmpeg")
        .args(["-y", "-loglevel", "error", "-framerate"])
        .arg(format!("{fps}"))
        .arg("-i")
        .arg(dir.join("frame-%05d.png"))
        .args([
            "-vf",
            "pad=ceil(iw/2)*2:ceil(ih/2)*2",
            "-pix_fmt",
            "yuv420p",
        ])
        .arg(&video)
        .status();
    match status {
        Ok(s) if s.success() => say!("wrote {}", video.display()),
        Ok(s) => say!("ffmpeg failed ({s}); the PNG frames are the result"),
        Err(_) => {
            say!("ffmpeg is not installed (apt-get install ffmpeg): the PNG frames are the result")
        }
    }
}
