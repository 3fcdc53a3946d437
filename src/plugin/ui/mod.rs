//! The egui panel: space picker, tracer knobs and read-outs. F1 shows or hides it, F12 saves
//! a screenshot (without the panel) to the working directory.

use crate::plugin::components::{
    ActiveSpace, CurvedSpaceCamera, Quality, TracerSettings, TracerStatus,
};
use crate::plugin::components::{PlayerFrame, PlayerSettings};
use crate::plugin::components::{PointerOverUi, StereoSettings};
use crate::plugin::frame_rate::FrameRateTarget;
use crate::space::Holonomy;
use crate::space::{Family, SEED_SPACES};
use crate::view::StereoMode;
use crate::view::stereo::{HUMAN_IPD_METRES, default_ipd};
use bevy::diagnostic::{DiagnosticsStore, FrameTimeDiagnosticsPlugin};
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy_egui::{EguiContexts, EguiPlugin, EguiPrimaryContextPass, egui};

mod controls;
mod minimap;
mod nil;
mod picker;
mod product;
mod sl2r;

use controls::{
    colour_by_controls, lighting_controls, stereo_controls, tracer_controls, wall_controls,
};
use minimap::{inspector, minimap};
pub use picker::SpacePicker;
use picker::{family_window, space_picker, switch_space};

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
            .add_systems(
                EguiPrimaryContextPass,
                (
                    panel.run_if(ActiveSpace::shows(Family::Constant)),
                    product::product_panel.run_if(ActiveSpace::shows(Family::Product)),
                    nil::nil_panel.run_if(ActiveSpace::shows(Family::Nil)),
                    sl2r::sl2r_panel.run_if(ActiveSpace::shows(Family::Sl2r)),
                ),
            );
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

fn take_screenshot(
    keys: Res<ButtonInput<KeyCode>>,
    ui: Res<UiKeys>,
    active: Option<Res<ActiveSpace>>,
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
    let id = active.map(|a| a.id.clone()).unwrap_or_default();
    let path = format!("curved-spaces-{}-{stamp}.png", id.replace(['/', '\\'], "_"));
    info!("saving a screenshot to {path}");
    commands.spawn(Screenshot::primary_window()).observe(
        move |captured: On<ScreenshotCaptured>| {
            // Written whole or not at all, and a failure is reported, not lost.
            match crate::plugin::screenshot::save_screenshot(
                &captured.image,
                std::path::Path::new(&path),
            ) {
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
    active: Res<ActiveSpace>,
    mut settings: ResMut<TracerSettings>,
    mut player: ResMut<PlayerSettings>,
    status: Res<TracerStatus>,
    mut stereo: ResMut<StereoSettings>,
    diagnostics: Res<DiagnosticsStore>,
    mut cameras: Query<(&mut CurvedSpaceCamera, &PlayerFrame, &Holonomy)>,
    (mut frame_rate, budget_share): (
        ResMut<FrameRateTarget>,
        Res<crate::plugin::frame_rate::BudgetShare>,
    ),
    mut picker: Local<SpacePicker>,
    entities: Res<crate::plugin::objects::EntityObjects>,
    shown_scene: Option<Res<crate::plugin::render::upload::ShownScene>>,
    (windows, look, mut commands): (
        Query<&Window, With<bevy::window::PrimaryWindow>>,
        Res<crate::plugin::components::MouseLook>,
        Commands,
    ),
) -> Result {
    let Some(space) = active.constant() else {
        return Ok(());
    };
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
            if let Some(id) = space_picker(ui, &active.id, space.description(), &mut picker)
                && id != active.id
            {
                picker.error = switch_space(&id, &mut commands).err();
                if let Some(e) = &picker.error {
                    error!("{e}");
                }
            }
            ui.separator();
            let default_fog = crate::scene::Shading::default_fog_distance(space);
            tracer_controls(ui, &mut settings, &status, default_fog);
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
            if space.geometry == crate::geometry::Geometry::Spherical {
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
            lighting_controls(
                ui,
                &mut settings,
                shown_scene.as_ref().map(|s| s.0.shading.lighting),
                true,
            );
            ui.separator();
            stereo_controls(ui, &mut stereo, active.inradius);
            colour_by_controls(ui, &mut settings, space.faces.len());
            ui.separator();
            controls::frame_rate(ui, &diagnostics);
            for (_, frame, holonomy) in &cameras {
                let chart = space.geometry.to_chart(frame.0.w_axis);
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
                space.geometry.name(),
                active.volume
            ));
            match active.injectivity_radius {
                Some(r) => ui.label(format!("injectivity radius {r:.6}")),
                None => ui.label("injectivity radius: not enumerated"),
            };
            if let Some((_, frame, _)) = cameras.iter().next()
                && !space.vertices.is_empty()
            {
                egui::CollapsingHeader::new("mini-map").default_open(true).show(ui, |ui| {
                    minimap(ui, space, active.inradius, frame, walls_shown);
                });
            }
            if let (Some(scene), Some((camera, frame, _))) =
                (shown_scene.as_deref(), cameras.iter().next())
            {
                egui::CollapsingHeader::new("inspector").default_open(true).show(ui, |ui| {
                    let window = windows.iter().next();
                    inspector(ui, space, &scene.0, camera, frame, window, look.grabbed, status.budget);
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
