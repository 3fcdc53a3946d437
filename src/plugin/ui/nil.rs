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
    mut defaults: Local<Option<(usize, crate::trace::nil::NilScene)>>,
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
    over_ui.0 = family_window(
        ctx,
        &active,
        &mut picker,
        &mut commands,
        &status,
        "click: mouse look · Esc: release · WASD, Space/Shift (along E₃), Q/E · scroll: speed · F1: panel · F3: stereo mode · F12: screenshot",
        |ui| {
            // The default scene (its fog and lighting), built once per space, not per frame:
            // its lamp's images are a search.
            let key = std::sync::Arc::as_ptr(space) as usize;
            if defaults.as_ref().is_none_or(|(k, _)| *k != key) {
                *defaults = Some((key, crate::trace::nil::default_scene(space)));
            }
            let Some((_, scene)) = defaults.as_ref() else {
                return;
            };
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
        },
    );
    Ok(())
}
