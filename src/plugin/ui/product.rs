//! The panel while a product space (H²×R, S²×R) is shown: the picker, the tracer's knobs,
//! the walk's feel and the space's invariants.

use super::*;
use crate::plugin::components::BaseProductScene;

#[allow(clippy::too_many_arguments)]
pub(super) fn product_panel(
    mut contexts: EguiContexts,
    shown: Res<PanelVisible>,
    mut over_ui: ResMut<PointerOverUi>,
    active: Res<ActiveSpace>,
    base: Option<Res<BaseProductScene>>,
    mut settings: ResMut<TracerSettings>,
    mut player: ResMut<PlayerSettings>,
    status: Res<TracerStatus>,
    mut stereo: ResMut<StereoSettings>,
    diagnostics: Res<DiagnosticsStore>,
    mut cameras: Query<(&mut CurvedSpaceCamera, &PlayerFrame, &Holonomy)>,
    mut picker: Local<SpacePicker>,
    mut defaults: Local<Option<(usize, crate::trace::product::ProductScene)>>,
    mut commands: Commands,
) -> Result {
    let Some(space) = active.product() else {
        return Ok(());
    };
    let ctx = contexts.ctx_mut()?;
    if !shown.0 {
        over_ui.0 = false;
        return Ok(());
    }
    over_ui.0 = family_window(
        ctx,
        &active,
        &mut picker,
        &mut commands,
        &status,
        "click: mouse look · Esc: release · WASD, Space/Shift (along the fibre), Q/E · scroll: speed · F1: panel · F3: stereo mode · F12: screenshot",
        |ui| {
            // The default scene, built once per space, not per frame (its lamp's images are
            // a search).
            let key = std::sync::Arc::as_ptr(space) as usize;
            if defaults.as_ref().is_none_or(|(k, _)| *k != key) {
                *defaults = Some((key, crate::trace::product::default_scene(space)));
            }
            let Some((_, default)) = defaults.as_ref() else {
                return;
            };
            let default_fog = base
                .as_ref()
                .map_or(default.fog_distance, |b| b.scene.fog_distance);
            tracer_controls(ui, &mut settings, &status, default_fog);
            wall_controls(ui, &mut settings, base.as_ref().and_then(|b| b.scene.walls));
            ui.separator();
            let shown = base.as_ref().map_or(default.lighting, |b| b.scene.lighting);
            super::controls::lighting_controls(ui, &mut settings, Some(shown), false);
            // Faces as the walk numbers them: the sides, the top, the bottom.
            colour_by_controls(ui, &mut settings, space.face_count());
            let mut scale = settings.resolution_scale;
            if ui
                .add(egui::Slider::new(&mut scale, 0.125..=1.0).text("resolution scale"))
                .changed()
            {
                settings.resolution_scale = scale;
            }
            super::controls::walk_feel(
                ui,
                &mut player,
                &mut cameras,
                &mut stereo,
                active.inradius,
                &diagnostics,
                (
                    "keep the fibre up",
                    "Walk horizontally and turn about the fibre, with Space and Shift climbing along it; off, fly freely",
                ),
            );
            for (_, frame, holonomy) in &cameras {
                let p = frame.0.w_axis;
                ui.label(format!(
                    "position in the cell: ({:+.3}, {:+.3}, {:+.3})",
                    p.x / p.w,
                    p.y / p.w,
                    p.z
                ));
                let last = holonomy.last_face.map_or_else(
                    || "none".to_string(),
                    |f| match f.checked_sub(space.polygon().sides.len()) {
                        Some(0) => "top".to_string(),
                        Some(_) => "bottom".to_string(),
                        None => format!("side {f}"),
                    },
                );
                ui.label(format!("crossings: {} (last {last})", holonomy.crossings));
            }
            ui.label(format!(
                "{} geometry, volume {:.6}, base χ = {}, {}",
                space.geometry_name(),
                active.volume,
                space.euler_characteristic(),
                if space.orientable() {
                    "orientable"
                } else {
                    "non-orientable"
                }
            ));
            match active.injectivity_radius {
                Some(r) => ui.label(format!("injectivity radius {r:.6}")),
                None => ui.label("injectivity radius: not enumerated"),
            };
        },
    );
    Ok(())
}
