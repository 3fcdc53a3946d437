//! The panel while a Nil space is shown: the picker, the tracer's knobs, the lighting, the
//! walk's feel (with `E₃` up) and the lattice's invariants.

use super::*;

#[allow(clippy::too_many_arguments)]
pub(super) fn nil_panel(
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
    mut picker: Local<SpacePicker>,
    mut commands: Commands,
) -> Result {
    let Some(space) = active.space.get::<crate::space::nil::NilSpace>() else {
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
            let scene = crate::trace::nil::default_scene(space);
            tracer_controls(ui, &mut settings, &status, scene.fog_distance);
            ui.separator();
            super::controls::lighting_controls(ui, &mut settings, Some(scene.lighting), false);
            super::controls::walk_feel(
                ui,
                &mut player,
                &mut cameras,
                &mut stereo,
                active.inradius,
                &diagnostics,
                (
                    "keep E₃ up",
                    "Walk horizontally and turn about E₃ (the centre's direction), with Space \
                     and Shift climbing along it; off, fly freely by parallel transport",
                ),
            );
            for (_, frame, holonomy) in &cameras {
                let p = frame.0.w_axis;
                ui.label(format!(
                    "position in the box: ({:+.4}, {:+.4}, {:+.5})",
                    p.x, p.y, p.z
                ));
                let last = holonomy.last_face.map_or_else(
                    || "none".to_string(),
                    |f| {
                        ["x = ½", "x = −½", "y = ½", "y = −½", "top", "bottom"]
                            .get(f)
                            .map_or_else(|| format!("face {f}"), |s| (*s).to_string())
                    },
                );
                ui.label(format!("crossings: {} (last {last})", holonomy.crossings));
            }
            ui.label(format!(
                "Nil, K = {}, volume {:.6}, H₁ = {}",
                space.k(),
                active.volume,
                space.homology()
            ));
            if let Some(r) = active.injectivity_radius {
                ui.label(format!("injectivity radius {r:.6}"));
            }
            for e in [&status.error, &status.stereo_error].into_iter().flatten() {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
            }
            ui.label(
                egui::RichText::new(
                    "click: mouse look · Esc: release · WASD, Space/Shift (along E₃), Q/E · scroll: speed · F1: panel · F3: stereo mode · F12: screenshot",
                )
                .small(),
            );
        });
    over_ui.0 = ctx.is_pointer_over_egui();
    Ok(())
}
