//! The panel while an SL̃(2,R) space is shown: the picker, the tracer's knobs, the lighting,
//! the walk's feel (with the fibre up, and what climbing it does) and the bundle's
//! invariants.

use super::*;

#[allow(clippy::too_many_arguments)]
pub(super) fn sl2r_panel(
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
    base: Option<Res<crate::plugin::sl2r::BaseSl2rScene>>,
    mut commands: Commands,
) -> Result {
    let Some(space) = active.space.get::<crate::space::sl2r::UnitTangentSpace>() else {
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
        "click: mouse look · Esc: release · WASD on the surface, Space/Shift along the fibre, Q/E · scroll: speed · F1: panel · F3: stereo mode · F12: screenshot",
        |ui| {
            // The default fog (not the whole default scene, whose tubes' images a frame need
            // not find again).
            let fog = crate::trace::sl2r::default_fog_distance(space);
            tracer_controls(ui, &mut settings, &status, fog);
            ui.separator();
            // The lamp is a point: no radius (soft shadows) to set.
            let shown = base
                .as_ref()
                .map_or_else(crate::scene::lighting::Lighting::default, |b| {
                    b.scene.lighting
                });
            super::controls::lighting_controls(ui, &mut settings, Some(shown), false);
            super::controls::walk_feel(
                ui,
                &mut player,
                &mut cameras,
                &mut stereo,
                active.inradius,
                &diagnostics,
                (
                    "keep the fibre up",
                    "Walk on the surface with the fibre up; Space and Shift climb along the \
                     fibre, which turns e (half of where you are): the world turns round you, \
                     as turning on the spot and climbing are one motion here; off, fly along \
                     your own axes",
                ),
            );
            for (_, frame, holonomy) in &cameras {
                // The chart point [x, y, θ] that `--eye`, scene files and flights take.
                let f = frame.0;
                let p = [f.w_axis.x, f.w_axis.y, f.w_axis.z];
                let e = [f.x_axis.w, f.y_axis.w, f.z_axis.w];
                let at =
                    crate::space::sl2r::chart_point(&[e, crate::space::sl2r::flow::perp(p, e), p]);
                // In a fibre cover the angle is lifted by the sheet (2π a sheet).
                let sheet = crate::trace::sl2r::camera_sheet(&f);
                let theta = at.z + std::f64::consts::TAU * f64::from(sheet);
                ui.label(format!(
                    "at [x, y, θ] = [{:+.4}, {:+.4}, {theta:+.4}] (as --eye and flights take it)",
                    at.x, at.y
                ));
                if space.sheets() > 1 {
                    ui.label(format!(
                        "sheet {} of {} (the fibre closes after {}·2π)",
                        sheet + 1,
                        space.sheets(),
                        space.sheets()
                    ));
                }
                let last = holonomy
                    .last_face
                    .map_or_else(|| "none".to_string(), |f| format!("side {f}"));
                ui.label(format!("crossings: {} (last {last})", holonomy.crossings));
            }
            ui.label(format!(
                "SL̃(2,R), genus {}, volume {:.6}, H₁ = {}",
                space.genus(),
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
