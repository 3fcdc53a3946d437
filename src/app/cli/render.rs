//! `render`: one picture of a space's default scene or a scene file, through the GPU tracer
//! offscreen or the f64 CPU reference. Both renderers take the same view: camera, budget,
//! stereo eyes and scene are decided once here, then handed to the one asked for.

use super::{DEFAULT_FOV, RenderArgs};
use bevy_curved_spaces::plugin::components::StereoSettings;
use bevy_curved_spaces::plugin::components::{
    AUTO_BUDGET_SAMPLES, ActiveSpace, BaseScene, Quality,
};
use bevy_curved_spaces::plugin::offscreen::{OffscreenRender, render_offscreen};
use bevy_curved_spaces::plugin::render::gpu::MAX_GPU_BUDGET;
use bevy_curved_spaces::scene::file::load_scene_file;
use bevy_curved_spaces::scene::{CurvedScene, SceneParts, Shading};
use bevy_curved_spaces::space::Space;
use bevy_curved_spaces::space::invariants::inradius;
use bevy_curved_spaces::trace::{RenderSettings, auto_budget, render_view};
use bevy_curved_spaces::view::stereo::eye_frames;
use bevy_curved_spaces::view::{TraceCamera, ViewLayout};
use glam::DMat4;
use image::RgbImage;
use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;

/// A scene file's space, scene and start view, or the named space's default scene.
pub(super) struct Chosen {
    pub(super) id: String,
    pub(super) space: Space,
    /// The whole scene (the CPU renders it).
    pub(super) scene: CurvedScene,
    /// What the plugin is given: a scene file's base scene, parts and start view (empty for
    /// the default scene).
    pub(super) base: BaseScene,
    pub(super) parts: SceneParts,
}

impl Chosen {
    /// The scene with other default parts (rebuilt from the base scene or the space).
    pub(super) fn with_parts(mut self, parts: SceneParts) -> Chosen {
        self.parts = parts;
        self.base.parts = self.base.parts.map(|_| parts);
        let fog = self.scene.shading.fog_distance;
        self.scene = match &self.base.scene {
            Some(base) => base.adding_parts(&self.space, parts),
            None => CurvedScene::with_parts(&self.space, fog, parts),
        };
        self
    }

    /// The scene with its moving objects where they are at `time` seconds (unchanged
    /// without any).
    pub(super) fn at(&self, time: f64) -> Result<Chosen, String> {
        let base = self
            .base
            .at_time(&self.space, time)
            .map_err(|e| format!("at time {time} s: {e}"))?;
        let scene = match (&base.scene, self.base.moving.is_empty()) {
            (Some(b), false) => b.adding_parts(&self.space, self.parts),
            _ => self.scene.clone(),
        };
        Ok(Chosen {
            id: self.id.clone(),
            space: self.space.clone(),
            scene,
            base,
            parts: self.parts,
        })
    }
}

/// What `render`, `walk` and `flight` show, in whichever family the space is of: a scene
/// file's space, scene and start view (the file's `space` key picks the family), or the space
/// `space_arg` names with its default scene. `fog` replaces a constant-curvature scene's fog
/// (a product scene's is set where the view is made).
pub(super) enum Choice {
    /// E³, S³, H³.
    Constant(Chosen),
    /// H²×R, S²×R.
    Product(ProductChoice),
    /// Nil.
    Nil(NilChoice),
    /// SL̃(2,R) (the CPU reference's pictures only).
    Sl2r(Sl2rChoice),
}

/// An SL̃(2,R) space with the scene and the start view shown in it.
pub(super) struct Sl2rChoice {
    /// The space.
    pub space: std::sync::Arc<bevy_curved_spaces::space::sl2r::UnitTangentSpace>,
    /// Its scene (a file's, or the default one).
    pub scene: bevy_curved_spaces::trace::sl2r::Sl2rScene,
    /// The start view.
    pub camera: bevy_curved_spaces::trace::sl2r::Sl2rCamera,
}

pub(super) fn choose(
    space_arg: &str,
    scene: Option<&Path>,
    fog: Option<f64>,
) -> Result<Choice, String> {
    use bevy_curved_spaces::space::AnySpace;
    use bevy_curved_spaces::trace::product::{default_camera, default_scene};
    if let Some(path) = scene {
        if let Some(file) = bevy_curved_spaces::trace::product::file::load_product_scene_file(path)
            .map_err(|e| e.to_string())?
        {
            let camera = file.start.unwrap_or_else(|| default_camera(&file.space));
            return Ok(Choice::Product(ProductChoice {
                base: Some(bevy_curved_spaces::BaseProductScene::from_file(&file)),
                scene: file.scene,
                camera,
                space: file.space,
            }));
        }
        if let Some(file) = bevy_curved_spaces::trace::sl2r::file::load_sl2r_scene_file(path)
            .map_err(|e| e.to_string())?
        {
            let mut scene = file.scene;
            if let Some(fog) = fog {
                scene.fog_distance = fog;
            }
            return Ok(Choice::Sl2r(Sl2rChoice {
                space: std::sync::Arc::new(file.space),
                scene,
                camera: file.start,
            }));
        }
        if let Some(file) = bevy_curved_spaces::trace::nil::file::load_nil_scene_file(path)
            .map_err(|e| e.to_string())?
        {
            let base = bevy_curved_spaces::plugin::nil::BaseNilScene::from_file(&file);
            let space = std::sync::Arc::new(file.space);
            return Ok(Choice::Nil(NilChoice::new(space, Some(base))));
        }
        let mut file = load_scene_file(path).map_err(|e| e.to_string())?;
        if let Some(fog) = fog {
            file.base.shading.fog_distance = fog;
        }
        return Ok(Choice::Constant(Chosen {
            id: file.space_id.clone(),
            scene: file.scene(),
            base: BaseScene::from_file(&file),
            parts: file.parts,
            space: file.space,
        }));
    }
    let named = super::space_named(space_arg)?;
    // The one table of what a family draws (the GPU's pictures are asked where they are
    // drawn: `render --cpu` needs only the reference's).
    named
        .supports(bevy_curved_spaces::space::Feature::ReferencePictures)
        .map_err(|e| format!("{space_arg}: {e}"))?;
    Ok(match named {
        AnySpace::Nil(space) => Choice::Nil(NilChoice::new(space, None)),
        AnySpace::Sl2r(space) => Choice::Sl2r(Sl2rChoice {
            scene: bevy_curved_spaces::trace::sl2r::default_scene(&space),
            camera: bevy_curved_spaces::trace::sl2r::default_camera(&space),
            space,
        }),
        AnySpace::Product(space) => {
            let space = std::sync::Arc::unwrap_or_clone(space);
            Choice::Product(ProductChoice {
                scene: default_scene(&space),
                camera: default_camera(&space),
                base: None,
                space,
            })
        }
        AnySpace::Constant(space) => {
            let space = std::sync::Arc::unwrap_or_clone(space);
            let fog = fog.unwrap_or_else(|| Shading::default_fog_distance(&space));
            Choice::Constant(Chosen {
                id: space_arg.to_string(),
                scene: CurvedScene::default_for(&space, fog),
                space,
                base: BaseScene::default(),
                parts: SceneParts::default(),
            })
        }
    })
}

/// The view both renderers take: camera, eyes, budget, stereo settings and the scene at
/// the requested time with the avatar at the camera.
struct View {
    camera: TraceCamera,
    eyes: [DMat4; 2],
    stereo: StereoSettings,
    settings: RenderSettings,
    scene: CurvedScene,
}

/// A product scene to render: a scene file's, or the space's default scene and view.
pub(super) struct ProductChoice {
    pub(super) space: bevy_curved_spaces::space::product::ProductSpace,
    pub(super) scene: bevy_curved_spaces::trace::product::ProductScene,
    pub(super) camera: bevy_curved_spaces::trace::product::ProductCamera,
    /// A scene file's start view and scene, for the plugin.
    pub(super) base: Option<bevy_curved_spaces::BaseProductScene>,
}

/// A Nil space with its scene and start view: a scene file's or the default ones.
pub(super) struct NilChoice {
    pub(super) space: std::sync::Arc<bevy_curved_spaces::space::nil::NilSpace>,
    pub(super) scene: bevy_curved_spaces::trace::nil::NilScene,
    pub(super) camera: bevy_curved_spaces::trace::nil::NilCamera,
    /// A scene file's scene and start view, for the plugin.
    pub(super) base: Option<bevy_curved_spaces::plugin::nil::BaseNilScene>,
}

impl NilChoice {
    /// The scene with the base scene's moving balls where they are at `time` seconds.
    pub(super) fn scene_at(
        &self,
        time: f64,
    ) -> Result<bevy_curved_spaces::trace::nil::NilScene, String> {
        match &self.base {
            Some(base) if !base.moving.is_empty() => {
                bevy_curved_spaces::trace::nil::moving::scene_at(
                    &self.space,
                    &self.scene,
                    &base.moving,
                    time,
                )
                .map_err(|e| format!("at {time} s: {e}"))
            }
            _ => Ok(self.scene.clone()),
        }
    }

    fn new(
        space: std::sync::Arc<bevy_curved_spaces::space::nil::NilSpace>,
        base: Option<bevy_curved_spaces::plugin::nil::BaseNilScene>,
    ) -> Self {
        use bevy_curved_spaces::trace::nil::{default_camera, default_scene};
        let scene = base
            .as_ref()
            .map_or_else(|| default_scene(&space), |b| b.scene.clone());
        let camera = base
            .as_ref()
            .and_then(|b| b.start)
            .unwrap_or_else(|| default_camera(&space));
        Self {
            space,
            scene,
            camera,
            base,
        }
    }
}

/// `render` of a product space (H²×R, S²×R): its default scene and view or a scene file's,
/// mono or stereo, on the GPU or with the CPU reference (`--cpu`).
fn render_product_command(args: &RenderArgs, chosen: ProductChoice) -> Result<(), String> {
    use bevy_curved_spaces::space::product::motion::camera_frame;
    use bevy_curved_spaces::trace::product::render_product_view;
    let ProductChoice {
        space,
        mut scene,
        mut camera,
        base,
    } = chosen;
    use bevy_curved_spaces::space::{Family, Feature};
    let refuse = |feature| {
        Family::Product
            .supports(feature)
            .map_err(|e| format!("{}: {e}", space.name()))
    };
    // A scene file's moving balls where they are at `--time`.
    if let Some(base) = &base {
        scene = base
            .at_time(&space, args.time)
            .map_err(|e| format!("at time {} s: {e}", args.time))?
            .scene;
    }
    // `--eye X,Y,Z --look-at X,Y,Z`: the surface's chart points and heights, as `trace
    // --from` takes them.
    if let (Some(eye), Some(target)) = (args.eye, args.look_at) {
        use bevy_curved_spaces::space::product::chart_point;
        let at = super::point_in_cell(
            eye,
            "camera position",
            space.name(),
            |x| chart_point(space.base(), x),
            |p| space.outside_by(p),
        )?;
        let towards = chart_point(space.base(), target)?;
        camera = bevy_curved_spaces::trace::product::file::camera_between(
            &space,
            at,
            towards,
            camera.fov_y_degrees,
        )?;
    }
    if args.view.changes_parts() {
        refuse(Feature::SceneParts)?;
    }
    if args.view.light.any() {
        let lighting = args.view.light.lighting(scene.lighting);
        let light = scene.light;
        scene.set_lighting(&space, light, lighting)?;
    }
    scene.colour_by = args.view.colour_by.into();
    if let Some(fog) = args.fog {
        scene.fog_distance = fog;
    }
    scene.walls = args
        .view
        .walls
        .style(scene.walls)?
        .filter(|w| w.opening < 1.0);
    if let Some(fov) = args.fov {
        camera.fov_y_degrees = fov;
    }
    let budget = args.crossings.unwrap_or(64);
    let stereo = args.stereo.settings_for(space.scale())?;
    say!(
        "rendering {} ({}) at {}×{} with the {} (fog λ = {:.3}, ≤ {budget} crossings{})…",
        space.name(),
        space.geometry_name(),
        args.size.0,
        args.size.1,
        if args.cpu {
            "f64 CPU reference"
        } else {
            "GPU tracer"
        },
        scene.fog_distance,
        stereo_words(&stereo, space.scale())
    );
    let started = Instant::now();
    let image = if args.cpu {
        let head = camera_frame(camera.point, camera.frame);
        let layout = head_layout(&space, head, camera.fov_y_degrees, &stereo, args.size);
        render_product_view(&space, &scene, &layout, budget)
    } else {
        let gpu_budget = gpu_budget(budget)?;
        bevy_curved_spaces::plugin::offscreen::OffscreenRenderer::new()
            .and_then(|mut r| {
                r.render_product_stereo(&space, &scene, &camera, args.size, gpu_budget, stereo)
            })
            .map_err(|e| e.to_string())?
    };
    saved(&image, args, started)
}

pub(super) fn render_command(args: &RenderArgs) -> Result<(), String> {
    let mut chosen = match choose(&args.space, args.scene.as_deref(), args.fog)? {
        Choice::Product(chosen) => return render_product_command(args, chosen),
        Choice::Nil(chosen) => return super::render_nil::render_nil_command(args, chosen),
        Choice::Sl2r(chosen) => return super::render_sl2r::render_sl2r_command(args, chosen),
        Choice::Constant(chosen) => chosen.at(args.time)?,
    };
    if args.view.changes_parts() {
        let parts = args.view.parts(chosen.parts);
        chosen = chosen.with_parts(parts);
    }
    let view = view(args, &chosen)?;
    let started = Instant::now();
    let image = if args.cpu {
        render_cpu(&chosen.space, &view)
    } else {
        render_gpu(args, &chosen, &view)?
    };
    save(&image, &args.out)?;
    let shown = std::fs::canonicalize(&args.out).unwrap_or_else(|_| args.out.clone());
    say!(
        "wrote {} ({}×{}, {:.2} s)",
        shown.display(),
        view.settings.width,
        view.settings.height,
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Decides the view from the arguments and the chosen scene.
fn view(args: &RenderArgs, chosen: &Chosen) -> Result<View, String> {
    let space = &chosen.space;
    let mut scene = chosen.scene.clone();
    scene.time = args.time;
    scene.shading.colour_by = args.view.colour_by.into();
    scene.shading.walls = args.view.walls.style(scene.shading.walls)?;
    let lighting = args.view.light.lighting(scene.shading.lighting);
    scene.set_lighting(space, lighting)?;
    let camera = camera(args, chosen)?;
    scene.set_avatar_frame(space, camera.frame);
    let max_crossings = match args.crossings {
        Some(n) => n,
        None => {
            let choice = auto_budget(
                space,
                &scene,
                Quality::High.miss_fraction(),
                AUTO_BUDGET_SAMPLES,
            );
            eprintln!(
                "automatic crossing budget: {} (the most any of {} sampled rays needs to reach an object before the fog cut-off)",
                choice.budget, choice.samples
            );
            choice.budget as usize
        }
    };
    let stereo = args.stereo.settings(space)?;
    Ok(View {
        eyes: eyes(space, &stereo, camera.frame),
        camera,
        stereo,
        settings: RenderSettings {
            width: args.size.0,
            height: args.size.1,
            max_crossings,
        },
        scene,
    })
}

/// The camera from `--eye`/`--look-at`, else the scene's start view, else the space's
/// default view.
fn camera(args: &RenderArgs, chosen: &Chosen) -> Result<TraceCamera, String> {
    let space = &chosen.space;
    // `--fov`, else the scene file's, else the default.
    let fov = args.fov.or(chosen.base.fov).unwrap_or(DEFAULT_FOV);
    let (Some(eye), Some(target)) = (args.eye, args.look_at) else {
        return Ok(TraceCamera {
            fov_y_degrees: fov,
            frame: chosen
                .base
                .start
                .unwrap_or_else(|| TraceCamera::default_for(space).frame),
        });
    };
    super::point_in_cell(
        eye,
        "camera position",
        space.name(),
        |x| space.geometry().from_chart(x).map_err(|e| e.to_string()),
        |p| space.outside_by(p),
    )?;
    TraceCamera::looking_at(space.geometry(), eye, target, fov).map_err(|e| e.to_string())
}

/// The eyes' frames (both the camera's in mono), saying where an eye was wrapped.
fn eyes(space: &Space, stereo: &StereoSettings, head: DMat4) -> [DMat4; 2] {
    if !stereo.mode.is_stereo() {
        return [head; 2];
    }
    let inradius = inradius(space);
    let ipd = stereo.ipd_for(inradius);
    let eyes = eye_frames(space, head, ipd);
    let wrapped: Vec<String> = eyes
        .iter()
        .zip(["left", "right"])
        .filter(|(e, _)| !e.crossed.is_empty())
        .map(|(e, name)| format!("the {name} eye is wrapped through face(s) {:?}", e.crossed))
        .collect();
    eprintln!(
        "stereo {}: eyes {ipd:.4} apart (the inradius feels like {:.2} m){}",
        stereo.mode,
        inradius / stereo.units_per_metre(inradius),
        if wrapped.is_empty() {
            String::new()
        } else {
            format!("; {}", wrapped.join(", "))
        }
    );
    eyes.map(|e| e.frame)
}

/// The f64 CPU reference, with a percentage on a terminal (nothing in logs).
fn render_cpu(space: &Space, view: &View) -> RgbImage {
    let settings = &view.settings;
    eprintln!(
        "rendering {} ({}) at {}×{} with the f64 CPU reference on {} threads (fog λ = {:.3}, ≤ {} crossings)…",
        space.name(),
        space.geometry().name(),
        settings.width,
        settings.height,
        rayon::current_num_threads(),
        view.scene.shading.fog_distance,
        settings.max_crossings
    );
    let tty = std::io::stderr().is_terminal();
    let layout = ViewLayout::new(
        view.stereo.mode,
        view.stereo.swap_eyes,
        view.eyes,
        view.camera.fov_y_degrees,
        settings.width,
        settings.height,
    );
    render_view(space, &view.scene, &layout, settings, |done, rows| {
        if tty && (done * 20 / rows != (done - 1) * 20 / rows || done == rows) {
            eprint!("\r{:>3} %", done * 100 / rows);
            if done == rows {
                eprintln!();
            }
        }
    })
}

/// The GPU tracer through the plugin, offscreen.
fn render_gpu(args: &RenderArgs, chosen: &Chosen, view: &View) -> Result<RgbImage, String> {
    let settings = &view.settings;
    let space = &chosen.space;
    let fog = view.scene.shading.fog_distance;
    eprintln!(
        "rendering {} ({}) at {}×{} with the GPU tracer (fog λ = {fog:.3}, ≤ {} crossings)…",
        space.name(),
        space.geometry().name(),
        settings.width,
        settings.height,
        settings.max_crossings
    );
    let max_crossings = gpu_budget(settings.max_crossings)?;
    render_offscreen(&OffscreenRender {
        fog_distance: Some(fog),
        parts: chosen.parts,
        base: chosen.base.clone(),
        time: args.time,
        stereo: view.stereo,
        colour_by: args.view.colour_by.into(),
        walls: view.scene.shading.walls,
        lighting: Some(view.scene.shading.lighting),
        ..OffscreenRender::new(
            ActiveSpace::new(&chosen.id, space.clone()),
            view.camera,
            args.size,
            max_crossings,
        )
    })
    .map_err(|e| e.to_string())
}

/// The view of a head frame for the CPU reference: in a stereo mode both eyes, each carried
/// half the eye distance along the head's right and wrapped into the cell by the family's
/// contract ([`FrameSpace::eye_frames`]), else the head for both.
pub(super) fn head_layout(
    space: &dyn bevy_curved_spaces::space::FrameSpace,
    head: glam::DMat4,
    fov_y_degrees: f64,
    stereo: &StereoSettings,
    size: (u32, u32),
) -> ViewLayout {
    let eyes = if stereo.mode.is_stereo() {
        space.eye_frames(head, stereo.ipd_for(space.scale()))
    } else {
        [head; 2]
    };
    ViewLayout::new(
        stereo.mode,
        stereo.swap_eyes,
        eyes,
        fov_y_degrees,
        size.0,
        size.1,
    )
}

/// `, stereo MODE: eyes B apart` for a stereo view of a space of size `scale`, else nothing.
pub(super) fn stereo_words(stereo: &StereoSettings, scale: f64) -> String {
    if stereo.mode.is_stereo() {
        format!(
            ", stereo {}: eyes {:.4} apart",
            stereo.mode,
            stereo.ipd_for(scale)
        )
    } else {
        String::new()
    }
}

/// Writes `render`'s picture and says where, its size and the time since `started`.
pub(super) fn saved(image: &RgbImage, args: &RenderArgs, started: Instant) -> Result<(), String> {
    save(image, &args.out)?;
    let shown = std::fs::canonicalize(&args.out).unwrap_or_else(|_| args.out.clone());
    say!(
        "wrote {} ({}×{}, {:.2} s)",
        shown.display(),
        args.size.0,
        args.size.1,
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// A crossing budget the GPU tracer takes (1 to [`MAX_GPU_BUDGET`]), or why not.
pub(super) fn gpu_budget(budget: usize) -> Result<u32, String> {
    u32::try_from(budget)
        .ok()
        .filter(|&n| (1..=MAX_GPU_BUDGET).contains(&n))
        .ok_or_else(|| {
            format!(
                "the GPU tracer takes a crossing budget from 1 to {MAX_GPU_BUDGET}, got {budget} (use --cpu for more)"
            )
        })
}

/// Writes the picture, creating its folder.
pub(super) fn save(image: &RgbImage, out: &Path) -> Result<(), String> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create folder {}: {e}", dir.display()))?;
    }
    bevy_curved_spaces::files::write_png(out, image)
        .map_err(|e| format!("cannot write {}: {e}", out.display()))
}
