//! The egui panel: space picker, tracer knobs and read-outs. F1 shows or hides it, F12 saves
//! a screenshot (without the panel) to the working directory.

use crate::components::{ActiveSpace, CurvedSpaceCamera, Quality, TracerSettings, TracerStatus};
use crate::components::{PlayerFrame, PlayerSettings};
use crate::components::{PointerOverUi, StereoSettings};
use crate::frame_rate::FrameRateTarget;
use crate::space::Holonomy;
use crate::space::SEED_SPACES;
use crate::view::StereoMode;
use crate::view::stereo::{HUMAN_IPD_METRES, default_ipd};
use bevy::diagnostic::{DiagnosticsStore, FrameTimeDiagnosticsPlugin};
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy_egui::{EguiContexts, EguiPlugin, EguiPrimaryContextPass, egui};

/// Whether the panel is shown.
#[derive(Resource, Clone, Copy, Debug, PartialEq, Eq)]
pub struct PanelVisible(pub bool);

/// Keys of the panel.
#[derive(Resource, Clone, Copy, Debug, PartialEq, Eq)]
pub struct UiKeys {
    /// Shows or hides the panel.
    pub toggle_panel: KeyCode,
    /// Saves a screenshot without the panel.
    pub screenshot: KeyCode,
    /// Steps through the stereo modes.
    pub next_stereo_mode: KeyCode,
    /// Shows or hides your ship (the avatar).
    pub toggle_avatar: KeyCode,
}

impl Default for UiKeys {
    fn default() -> Self {
        Self {
            toggle_panel: KeyCode::F1,
            screenshot: KeyCode::F12,
            next_stereo_mode: KeyCode::F3,
            toggle_avatar: KeyCode::F4,
        }
    }
}

/// The panel and its keys.
pub struct CurvedSpacesUiPlugin;

impl Plugin for CurvedSpacesUiPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<EguiPlugin>() {
            app.add_plugins(EguiPlugin::default());
        }
        if !app.is_plugin_added::<FrameTimeDiagnosticsPlugin>() {
            app.add_plugins(FrameTimeDiagnosticsPlugin::default());
        }
        app.init_resource::<PointerOverUi>()
            .init_resource::<UiKeys>()
            .insert_resource(PanelVisible(true))
            .add_systems(
                Update,
                (
                    toggle_panel,
                    take_screenshot,
                    next_stereo_mode,
                    toggle_avatar,
                ),
            )
            .add_systems(EguiPrimaryContextPass, panel);
    }
}

fn toggle_panel(keys: Res<ButtonInput<KeyCode>>, ui: Res<UiKeys>, mut shown: ResMut<PanelVisible>) {
    if keys.just_pressed(ui.toggle_panel) {
        shown.0 = !shown.0;
    }
}

fn toggle_avatar(
    keys: Res<ButtonInput<KeyCode>>,
    ui: Res<UiKeys>,
    mut settings: ResMut<TracerSettings>,
) {
    if keys.just_pressed(ui.toggle_avatar) {
        settings.parts.avatar = !settings.parts.avatar;
        info!(
            "your ship is {}",
            if settings.parts.avatar {
                "shown"
            } else {
                "hidden"
            }
        );
    }
}

fn next_stereo_mode(
    keys: Res<ButtonInput<KeyCode>>,
    ui: Res<UiKeys>,
    mut stereo: ResMut<StereoSettings>,
) {
    if keys.just_pressed(ui.next_stereo_mode) {
        let modes = StereoMode::ALL;
        let at = modes.iter().position(|m| *m == stereo.mode).unwrap_or(0);
        stereo.mode = modes[(at + 1) % modes.len()];
        info!("stereo mode: {}", stereo.mode.label());
    }
}

/// The cell seen from outside: its edges in the chart (coloured by edge cycle, as the
/// default scene draws them), each face's number at its nearest point to the centre in
/// that face's colour (the colours of `--colour-by face`, or of the walls when they are
/// shown), and the player: a white dot and
/// the direction it looks in. An oblique view of the chart, fixed so that it reads the
/// same as you move.
fn minimap(ui: &mut egui::Ui, active: &ActiveSpace, frame: &PlayerFrame, walls: bool) {
    use crate::scene::palette;
    let space = &active.space;
    // With walls shown, faces are labelled in their walls' colours (glued faces alike).
    let wall_colours = walls.then(|| {
        let (partners, reflections) = crate::scene::walls::gluing(space);
        crate::scene::walls::wall_colours(&partners, &reflections)
    });
    let g = space.geometry;
    let colour = |c: glam::DVec3| {
        let [r, gr, b] = c
            .to_array()
            .map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8);
        egui::Color32::from_rgb(r, gr, b)
    };
    let vertices: Vec<glam::DVec3> = (0..space.vertices.len())
        .map(|v| g.to_chart(space.vertex_point(v)))
        .collect();
    let extent = vertices.iter().map(|v| v.length()).fold(1e-9, f64::max);
    // An oblique view: turned 35° about y, then tipped 25° about x.
    let turn = glam::DMat3::from_rotation_x(25f64.to_radians())
        * glam::DMat3::from_rotation_y(35f64.to_radians());
    let side = 200.0;
    let (response, painter) = ui.allocate_painter(egui::vec2(side, side), egui::Sense::hover());
    let rect = response.rect;
    painter.rect_filled(rect, 4.0, egui::Color32::from_rgb(12, 14, 20));
    let to_screen = |x: glam::DVec3| {
        let p = turn * (x / extent);
        rect.center() + egui::vec2(0.45 * side * p.x as f32, -0.45 * side * p.y as f32)
    };
    for e in &space.edges {
        let [a, b] = e.vertices;
        painter.line_segment(
            [to_screen(vertices[a]), to_screen(vertices[b])],
            egui::Stroke::new(1.5, colour(palette(e.cycle))),
        );
    }
    for (f, face) in space.faces.iter().enumerate() {
        let n = face.covector;
        let normal = n.truncate();
        if normal.length_squared() < 1e-18 {
            continue;
        }
        let foot = -n.w * normal / normal.length_squared();
        painter.text(
            to_screen(foot),
            egui::Align2::CENTER_CENTER,
            f.to_string(),
            egui::FontId::proportional(11.0),
            colour(wall_colours.as_ref().map_or(palette(f), |c| c[f])),
        );
    }
    let here = g.to_chart(frame.0.w_axis);
    let ahead =
        g.to_chart((frame.0 * g.translation(glam::DVec3::NEG_Z, 0.3 * active.inradius)).w_axis);
    let (p, q) = (to_screen(here), to_screen(ahead));
    painter.line_segment([p, q], egui::Stroke::new(2.0, egui::Color32::WHITE));
    painter.circle_filled(p, 4.0, egui::Color32::WHITE);
}

/// The story of the ray through the pointer (or the screen centre while the mouse looks
/// round): the faces it crossed with the distance at each, the word of pairings, and what
/// it met. Traced on the CPU in f64, the reference the GPU is tested against.
#[allow(clippy::too_many_arguments)]
fn inspector(
    ui: &mut egui::Ui,
    active: &ActiveSpace,
    scene: &crate::scene::CurvedScene,
    camera: &CurvedSpaceCamera,
    frame: &PlayerFrame,
    window: Option<&Window>,
    grabbed: bool,
    budget: u32,
) {
    use crate::scene::Object;
    use crate::trace::{RayEnd, ray_story};
    let Some(window) = window else {
        return;
    };
    let (w, h) = (window.width().max(1.0), window.height().max(1.0));
    let at = window
        .cursor_position()
        .filter(|_| !grabbed)
        .unwrap_or(Vec2::new(w / 2.0, h / 2.0));
    let view = crate::view::TraceCamera {
        frame: frame.0,
        fov_y_degrees: camera.fov_y_degrees,
    };
    let (pw, ph) = (w.round() as u32, h.round() as u32);
    let (i, j) = (
        (at.x.max(0.0) as u32).min(pw - 1),
        (at.y.max(0.0) as u32).min(ph - 1),
    );
    let space = &active.space;
    let ray = view.ray(space.geometry, i, j, pw, ph);
    let walker = crate::space::CellWalker::<glam::DVec4>::new(space);
    let story = ray_story(&walker, scene, ray, budget.max(1) as usize);
    ui.label(format!(
        "the ray through {} ({i}, {j})",
        if grabbed {
            "the screen centre"
        } else {
            "the pointer"
        }
    ));
    let shown: Vec<String> = story
        .crossings
        .iter()
        .take(12)
        .map(|(f, d)| format!("{f} at {d:.3}"))
        .collect();
    let more = story.crossings.len().saturating_sub(12);
    ui.label(format!(
        "faces crossed ({}): {}{}",
        story.crossings.len(),
        if shown.is_empty() {
            "none".to_string()
        } else {
            shown.join(", ")
        },
        if more > 0 {
            format!(" and {more} more")
        } else {
            String::new()
        }
    ));
    if !story.crossings.is_empty() {
        let word: Vec<String> = story
            .crossings
            .iter()
            .rev()
            .take(16)
            .map(|(f, _)| format!("g{f}"))
            .collect();
        ui.label(format!(
            "holonomy word (latest first): {}{}",
            word.join(" "),
            if story.crossings.len() > 16 {
                " ..."
            } else {
                ""
            }
        ));
    }
    let ended = match &story.end {
        RayEnd::Hit(hit) => {
            let what = match scene.objects.get(hit.object) {
                Some(Object::Ball(b)) if b.texture.is_some() => "a globe".to_string(),
                Some(Object::Ball(_)) => "a ball".to_string(),
                Some(Object::Tube(_)) => "a tube".to_string(),
                Some(Object::Disc(_)) => "a disc".to_string(),
                Some(Object::Mesh(_)) => "a mesh".to_string(),
                None => "your ship".to_string(),
            };
            format!(
                "met {what} (object {}) at distance {:.4}",
                hit.object, hit.distance
            )
        }
        RayEnd::Fog(_) => "faded into the fog".to_string(),
        RayEnd::Budget(k) => format!("stopped at the crossing budget ({k})"),
    };
    ui.label(ended);
}

/// The cell's walls: on or off, how far their windows are open, how much light they stop.
/// `shown` is the walls of the scene on screen (the settings' or the base scene's own).
fn wall_controls(
    ui: &mut egui::Ui,
    settings: &mut ResMut<TracerSettings>,
    shown: Option<crate::scene::WallStyle>,
) {
    use crate::scene::WallStyle;
    // What is on screen: the settings' walls, else the base scene's own.
    let current = settings.walls.or(shown);
    let mut on = current.is_some_and(|w| w.opening < 1.0);
    let mut style = current.unwrap_or(WallStyle {
        opening: 0.5,
        opacity: crate::scene::walls::DEFAULT_WALL_OPACITY,
    });
    // Turned back on, the walls start half open.
    if style.opening >= 1.0 {
        style.opening = 0.5;
    }
    ui.checkbox(&mut on, "walls (glued faces share a colour)");
    if on {
        // Up to just short of fully open: 1 is "no walls", the checkbox.
        ui.add(egui::Slider::new(&mut style.opening, 0.0..=0.99).text("window opening"));
        ui.add(egui::Slider::new(&mut style.opacity, 0.05..=1.0).text("wall opacity"));
    }
    // Off is an opening of 1, so that a scene file's walls can be turned off too.
    let wanted = match (on, current) {
        (true, _) => Some(style),
        (false, Some(_)) => Some(WallStyle {
            opening: 1.0,
            ..style
        }),
        (false, None) => None,
    };
    if wanted != current {
        settings.walls = wanted;
    }
}

/// The teaching view and its legend: what each tint means.
fn colour_by_controls(ui: &mut egui::Ui, settings: &mut ResMut<TracerSettings>, faces: usize) {
    use crate::scene::{ColourBy, palette};
    let mut by = settings.colour_by;
    egui::ComboBox::from_label("colour by")
        .selected_text(by.name())
        .show_ui(ui, |ui| {
            for m in ColourBy::ALL {
                ui.selectable_value(&mut by, m, m.name());
            }
        });
    if by != settings.colour_by {
        settings.colour_by = by;
    }
    let swatch = |ui: &mut egui::Ui, c: glam::DVec3, text: String| {
        let [r, g, b] = c
            .to_array()
            .map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8);
        ui.colored_label(egui::Color32::from_rgb(r, g, b), text);
    };
    let (entries, what): (Vec<(glam::DVec3, String)>, &str) = match by {
        ColourBy::Shading => return,
        ColourBy::Crossings => (
            (0..8).map(|k| (palette(k), k.to_string())).collect(),
            "faces crossed:",
        ),
        ColourBy::Face => (
            std::iter::once((glam::DVec3::ONE, "none".to_string()))
                .chain((0..faces.min(16)).map(|f| (palette(f), f.to_string())))
                .collect(),
            "last face crossed:",
        ),
        ColourBy::Holonomy => (
            (0..7)
                .map(|k| {
                    let c = if k == 0 { glam::DVec3::ONE } else { palette(k) };
                    (c, format!("{}", 30 * k))
                })
                .chain((7..14).map(|k| (palette(k), format!("m{}", 30 * (k - 7)))))
                .collect(),
            "turn of the copy (degrees; m: mirrored):",
        ),
    };
    ui.label(what);
    ui.horizontal_wrapped(|ui| {
        for (c, text) in entries {
            swatch(ui, c, text);
        }
    });
}

/// The stereo mode, the eye distance (with the world scale it gives) and the eye swap.
fn stereo_controls(ui: &mut egui::Ui, stereo: &mut ResMut<StereoSettings>, inradius: f64) {
    let mut mode = stereo.mode;
    egui::ComboBox::from_label("stereo")
        .selected_text(mode.label())
        .show_ui(ui, |ui| {
            for m in StereoMode::ALL {
                ui.selectable_value(&mut mode, m, m.label());
            }
        });
    if mode != stereo.mode {
        stereo.mode = mode;
    }
    if !mode.is_stereo() {
        return;
    }
    let default_ipd = default_ipd(inradius);
    let mut ipd = stereo.ipd_for(inradius);
    if ui
        .add(
            egui::Slider::new(
                &mut ipd,
                0.1 * default_ipd..=inradius.min(10.0 * default_ipd),
            )
            .logarithmic(true)
            .text("eye distance"),
        )
        .on_hover_text(
            "Distance between the eyes in the space's units: it sets how big the cell feels",
        )
        .changed()
    {
        stereo.ipd = Some(ipd);
    }
    ui.label(format!(
        "the inradius feels like {:.2} m (eyes {:.0} mm apart)",
        inradius / stereo.units_per_metre(inradius),
        1000.0 * HUMAN_IPD_METRES
    ));
    let mut swap = stereo.swap_eyes;
    if ui
        .checkbox(&mut swap, "swap eyes (cross-eyed viewing)")
        .changed()
    {
        stereo.swap_eyes = swap;
    }
}

fn take_screenshot(
    keys: Res<ButtonInput<KeyCode>>,
    ui: Res<UiKeys>,
    active: Res<ActiveSpace>,
    mut shown: ResMut<PanelVisible>,
    mut commands: Commands,
) {
    if !keys.just_pressed(ui.screenshot) {
        return;
    }
    // The panel is hidden for the capture and stays hidden (F1 brings it back).
    shown.0 = false;
    let stamp = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let path = format!("curved-spaces-{}-{stamp}.png", active.id);
    info!("saving a screenshot to {path}");
    commands.spawn(Screenshot::primary_window()).observe(
        move |captured: On<ScreenshotCaptured>| {
            // Written whole or not at all, and a failure is reported, not lost.
            match crate::offscreen::save_screenshot(&captured.image, std::path::Path::new(&path)) {
                Ok(()) => info!("wrote {path}"),
                Err(e) => error!("cannot write the screenshot {path}: {e}"),
            }
        },
    );
}

#[allow(clippy::too_many_arguments)]
fn panel(
    mut contexts: EguiContexts,
    shown: Res<PanelVisible>,
    mut over_ui: ResMut<PointerOverUi>,
    mut active: ResMut<ActiveSpace>,
    mut settings: ResMut<TracerSettings>,
    mut player: ResMut<PlayerSettings>,
    status: Res<TracerStatus>,
    mut stereo: ResMut<StereoSettings>,
    diagnostics: Res<DiagnosticsStore>,
    mut cameras: Query<(&mut CurvedSpaceCamera, &PlayerFrame, &Holonomy)>,
    (mut frame_rate, budget_share): (ResMut<FrameRateTarget>, Res<crate::frame_rate::BudgetShare>),
    mut picker: Local<SpacePicker>,
    entities: Res<crate::objects::EntityObjects>,
    shown_scene: Option<Res<crate::render::upload::ShownScene>>,
    windows: Query<&Window, With<bevy::window::PrimaryWindow>>,
    look: Res<crate::components::MouseLook>,
) -> Result {
    let ctx = contexts.ctx_mut()?;
    if !shown.0 {
        over_ui.0 = false;
        return Ok(());
    }
    egui::Window::new("Curved spaces")
        .default_pos((12.0, 12.0))
        .default_width(300.0)
        .vscroll(true)
        .default_height(690.0)
        .show(ctx, |ui| {
            if let Some(id) = space_picker(ui, &active, &mut picker)
                && id != active.id
            {
                match ActiveSpace::named(&id) {
                    Ok(space) => {
                        *active = space;
                        picker.error = None;
                    }
                    Err(e) => {
                        error!("{e}");
                        picker.error = Some(e);
                    }
                }
            }
            ui.separator();
            let default_fog = crate::scene::Shading::default_fog_distance(&active.space);
            let in_use = if status.fog_distance > 0.0 { status.fog_distance } else { default_fog };
            let mut fog = settings.fog_distance.unwrap_or(in_use);
            if ui
                .add(
                    egui::Slider::new(&mut fog, 0.05 * default_fog..=4.0 * default_fog)
                        .text("fog distance"),
                )
                .changed()
            {
                settings.fog_distance = Some(fog);
            }
            let mut quality = settings.quality;
            egui::ComboBox::from_label("quality")
                .selected_text(format!("{quality:?}"))
                .show_ui(ui, |ui| {
                    for q in Quality::ALL {
                        ui.selectable_value(&mut quality, q, format!("{q:?}"));
                    }
                });
            if quality != settings.quality {
                settings.quality = quality;
                settings.resolution_scale = quality.resolution_scale();
            }
            let mut automatic = settings.max_crossings.is_none();
            ui.horizontal(|ui| {
                ui.checkbox(&mut automatic, "automatic crossing budget");
                if let Some(auto) = status.auto_budget {
                    ui.label(format!(
                        "{} ({:.1} % of rays short)",
                        auto.budget,
                        100.0 * auto.missed_fraction
                    ))
                    .on_hover_text(
                        "The smallest budget with which the quality's share of sampled rays \
                         at most shows fog instead of a far object",
                    );
                }
            });
            if automatic != settings.max_crossings.is_none() {
                settings.max_crossings = (!automatic).then_some(status.budget.max(1));
            }
            if let Some(fixed) = settings.max_crossings {
                let mut budget = fixed;
                if ui
                    .add(egui::Slider::new(&mut budget, 1..=256).text("crossing budget"))
                    .changed()
                {
                    settings.max_crossings = Some(budget);
                }
            }
            let mut hold = frame_rate.target_ms.is_some();
            let mut fps = frame_rate.target_ms.map_or(30.0, |ms| 1e3 / ms);
            ui.horizontal(|ui| {
                ui.checkbox(&mut hold, "hold");
                ui.add_enabled(hold, egui::Slider::new(&mut fps, 10.0..=144.0).text("fps"))
                    .on_hover_text(
                        "Lowers or raises the traced resolution, within the quality's range, \
                         to keep this frame rate; at the lowest resolution, the crossing budget \
                         next (never below the quality's floor)",
                    );
            });
            if hold && budget_share.0 < 1.0 && settings.max_crossings.is_none() {
                ui.label(format!(
                    "crossing budget lowered to {} ({:.0} % of the automatic one) to hold it",
                    status.budget,
                    100.0 * budget_share.0
                ));
            }
            let target_ms = hold.then_some(1e3 / fps);
            if target_ms != frame_rate.target_ms {
                frame_rate.target_ms = target_ms;
                frame_rate.frames_since_change = 0;
                frame_rate.budget_futile = false;
            }
            let mut scale = settings.resolution_scale;
            let slider = egui::Slider::new(&mut scale, 0.125..=1.0).text(if hold {
                "resolution scale (chosen)"
            } else {
                "resolution scale"
            });
            if ui.add_enabled(!hold, slider).changed() {
                settings.resolution_scale = scale;
            }
            ui.add(egui::Slider::new(&mut player.speed, 0.01..=20.0).logarithmic(true).text("speed (inradii/s)"));
            for (mut camera, _, _) in &mut cameras {
                let mut fov = camera.fov_y_degrees;
                if ui
                    .add(egui::Slider::new(&mut fov, 20.0..=120.0).text("field of view (°)"))
                    .changed()
                {
                    camera.fov_y_degrees = fov;
                }
            }
            let mut parts = settings.parts;
            ui.checkbox(&mut parts.edges, "cell edges");
            egui::ComboBox::from_label("centrepiece")
                .selected_text(parts.centrepiece.name())
                .show_ui(ui, |ui| {
                    for c in crate::scene::Centrepiece::ALL {
                        ui.selectable_value(&mut parts.centrepiece, c, c.name());
                    }
                });
            ui.checkbox(&mut parts.avatar, "your ship (seen round the space)");
            if active.space.geometry == crate::geometry::Geometry::Spherical {
                ui.checkbox(&mut parts.clifford, "Clifford parallels");
            }
            if parts != settings.parts {
                settings.parts = parts;
            }
            let shown_walls = shown_scene.as_ref().and_then(|s| s.0.shading.walls);
            wall_controls(ui, &mut settings, shown_walls);
            let walls_shown = settings
                .walls
                .or(shown_walls)
                .is_some_and(|w| w.opening < 1.0);
            ui.separator();
            stereo_controls(ui, &mut stereo, active.inradius);
            colour_by_controls(ui, &mut settings, active.space.faces.len());
            ui.separator();
            let fps = diagnostics
                .get(&FrameTimeDiagnosticsPlugin::FPS)
                .and_then(|d| d.smoothed());
            let ms = diagnostics
                .get(&FrameTimeDiagnosticsPlugin::FRAME_TIME)
                .and_then(|d| d.smoothed());
            if let (Some(fps), Some(ms)) = (fps, ms) {
                ui.label(format!("{fps:.0} fps, {ms:.1} ms per frame"));
            }
            for (_, frame, holonomy) in &cameras {
                let chart = active.space.geometry.to_chart(frame.0.w_axis);
                ui.label(format!(
                    "position in the cell: ({:+.3}, {:+.3}, {:+.3})",
                    chart.x, chart.y, chart.z
                ));
                let last = holonomy
                    .last_face
                    .map_or_else(|| "none".to_string(), |f| f.to_string());
                ui.label(format!(
                    "crossings: {} (last face {last})",
                    holonomy.crossings
                ));
            }
            ui.label(format!(
                "{} geometry, volume {:.6}",
                active.space.geometry.name(),
                active.volume
            ));
            match active.injectivity_radius {
                Some(r) => ui.label(format!("injectivity radius {r:.6}")),
                None => ui.label("injectivity radius: not enumerated"),
            };
            if let Some((_, frame, _)) = cameras.iter().next()
                && !active.space.vertices.is_empty()
            {
                egui::CollapsingHeader::new("mini-map").default_open(true).show(ui, |ui| {
                    minimap(ui, &active, frame, walls_shown);
                });
            }
            if let (Some(scene), Some((camera, frame, _))) =
                (shown_scene.as_deref(), cameras.iter().next())
            {
                egui::CollapsingHeader::new("inspector").default_open(true).show(ui, |ui| {
                    let window = windows.iter().next();
                    inspector(ui, &active, &scene.0, camera, frame, window, look.grabbed, status.budget);
                });
            }
            if !entities.objects.is_empty() || entities.pending > 0 {
                ui.label(format!(
                    "objects: {} drawn, {} meshes loading",
                    entities.objects.len(),
                    entities.pending
                ));
            }
            for e in [&status.error, &status.stereo_error].into_iter().flatten() {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
            }
            ui.label(
                egui::RichText::new(
                    "click: mouse look · Esc: release · WASD, Space/Shift, Q/E · scroll: speed · F1: panel · F3: stereo mode · F4: your ship · F12: screenshot",
                )
                .small(),
            );
        });
    over_ui.0 = ctx.is_pointer_over_egui();
    Ok(())
}

/// The space picker's fields: the family parameters and the file path being typed, and the
/// last error.
#[derive(Debug)]
pub struct SpacePicker {
    lens_p: u32,
    lens_q: u32,
    prism_n: u32,
    census: usize,
    path: String,
    error: Option<String>,
}

impl Default for SpacePicker {
    fn default() -> Self {
        Self {
            lens_p: 7,
            lens_q: 2,
            prism_n: 3,
            census: 1,
            path: String::new(),
            error: None,
        }
    }
}

/// The library members without parameters, as the picker lists them.
const LIBRARY_FIXED: &[&str] = &[
    "three-sphere",
    "projective-space",
    "binary-tetrahedral",
    "binary-octahedral",
    "binary-icosahedral",
    "mirrored-tetrahedron",
    "torus-hexagonal",
    "torus-fcc",
    "torus-bcc",
    "first-amphicosm",
    "second-amphicosm",
    "first-amphidicosm",
    "second-amphidicosm",
    "weeks",
    "seifert-weber-group",
];

/// The space picker: the seed spaces and library members in a list, the families with
/// parameters as fields, and a path field for a `.gen` or JSON file. Returns the id chosen.
fn space_picker(
    ui: &mut egui::Ui,
    active: &ActiveSpace,
    picker: &mut SpacePicker,
) -> Option<String> {
    let mut chosen = None;
    egui::ComboBox::from_label("space")
        .selected_text(active.id.as_str())
        .show_ui(ui, |ui| {
            for seed in SEED_SPACES {
                let r = ui
                    .selectable_label(active.id == seed.id, seed.id)
                    .on_hover_text(seed.summary);
                if r.clicked() {
                    chosen = Some(seed.id.to_string());
                }
            }
            ui.separator();
            for &id in LIBRARY_FIXED {
                let summary = crate::space::library::FAMILIES
                    .iter()
                    .find(|f| f.pattern == id)
                    .map_or("", |f| f.summary);
                if ui
                    .selectable_label(active.id == id, id)
                    .on_hover_text(summary)
                    .clicked()
                {
                    chosen = Some(id.to_string());
                }
            }
        });
    if let Some(summary) = SEED_SPACES.iter().find(|s| s.id == active.id) {
        ui.label(egui::RichText::new(summary.summary).small());
    } else if !active.space.description().is_empty() {
        ui.label(egui::RichText::new(active.space.description()).small());
    }
    ui.collapsing("families and files", |ui| {
        ui.horizontal(|ui| {
            ui.label("lens");
            ui.add(
                egui::DragValue::new(&mut picker.lens_p)
                    .range(2..=crate::space::library::MAX_LENS_ORDER)
                    .prefix("P "),
            );
            ui.add(
                egui::DragValue::new(&mut picker.lens_q)
                    .range(1..=picker.lens_p.saturating_sub(1).max(1))
                    .prefix("Q "),
            );
            if ui.button("go").clicked() {
                chosen = Some(format!("lens-{}-{}", picker.lens_p, picker.lens_q));
            }
        });
        ui.horizontal(|ui| {
            ui.label("prism");
            ui.add(
                egui::DragValue::new(&mut picker.prism_n)
                    .range(2..=crate::space::library::MAX_PRISM)
                    .prefix("N "),
            );
            if ui.button("go").clicked() {
                chosen = Some(format!("prism-{}", picker.prism_n));
            }
        });
        ui.horizontal(|ui| {
            ui.label("census");
            ui.add(
                egui::DragValue::new(&mut picker.census)
                    .range(1..=crate::space::library::CENSUS.len())
                    .prefix("N "),
            );
            if ui.button("go").clicked() {
                chosen = Some(format!("census-{}", picker.census));
            }
        });
        ui.horizontal(|ui| {
            ui.label("file");
            let edit = ui.add(
                egui::TextEdit::singleline(&mut picker.path)
                    .hint_text(".gen or .json path")
                    .desired_width(150.0),
            );
            let enter = edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if (ui.button("load").clicked() || enter) && !picker.path.trim().is_empty() {
                chosen = Some(picker.path.trim().to_string());
            }
        });
        if let Some(e) = &picker.error {
            ui.colored_label(egui::Color32::LIGHT_RED, e);
        }
    });
    chosen
}
