//! The panel's controls for walls, colours and stereo.

use super::*;

/// The cell's walls: on or off, how far their windows are open, how much light they stop.
/// `shown` is the walls of the scene on screen (the settings' or the base scene's own).
pub(super) fn wall_controls(
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

/// How the lamps light the scene: every image in the cover or the nearest copy, how far the
/// images are summed, the tail beyond, how many are shadowed. `shown` is the lighting of
/// the scene on screen (the settings' or the base scene's own). `soft`: the lamps can have
/// a radius for soft shadows (not in the product spaces, whose lamp is a point).
pub(super) fn lighting_controls(
    ui: &mut egui::Ui,
    settings: &mut ResMut<TracerSettings>,
    shown: Option<crate::scene::lighting::Lighting>,
    soft: bool,
) {
    use crate::scene::lighting::{LightPaths, Lighting};
    let current = settings.lighting.or(shown).unwrap_or_default();
    let mut wanted = current;
    egui::ComboBox::from_label("light paths")
        .selected_text(wanted.paths.name())
        .show_ui(ui, |ui| {
            for p in [LightPaths::Images, LightPaths::Nearest] {
                ui.selectable_value(&mut wanted.paths, p, p.name());
            }
        });
    if wanted.paths == LightPaths::Images {
        ui.add(
            egui::Slider::new(&mut wanted.reach_inradii, 0.5..=12.0).text("light reach (inradii)"),
        );
        ui.checkbox(&mut wanted.tail, "the images beyond, by their mean");
    }
    ui.add(egui::Slider::new(&mut wanted.shadows, 0..=16).text("shadowed images"));
    let cap = settings.quality.max_shadows();
    if wanted.shadows > cap {
        ui.weak(format!(
            "capped at {cap} by the {:?} quality",
            settings.quality
        ));
    }
    if soft && wanted.shadows > 0 {
        ui.add(
            egui::Slider::new(
                &mut wanted.lamp_radius_inradii,
                0.0..=Lighting::MAX_LAMP_RADIUS_INRADII,
            )
            .text("lamp radius (inradii)"),
        );
        if wanted.lamp_radius_inradii > 0.0 {
            ui.add(egui::Slider::new(&mut wanted.soft_samples, 1..=32).text("soft shadow rays"));
        }
    }
    if wanted != current && wanted.check().is_ok() {
        settings.lighting = Some(wanted);
    }
    if ui
        .add_enabled(
            current != Lighting::default(),
            egui::Button::new("default lighting"),
        )
        .clicked()
    {
        settings.lighting = Some(Lighting::default());
    }
}

/// The teaching view and its legend: what each tint means.
pub(super) fn colour_by_controls(
    ui: &mut egui::Ui,
    settings: &mut ResMut<TracerSettings>,
    faces: usize,
) {
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
pub(super) fn stereo_controls(
    ui: &mut egui::Ui,
    stereo: &mut ResMut<StereoSettings>,
    inradius: f64,
) {
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

/// The fog, the quality and the crossing budget (automatic or fixed); `default_fog` is the
/// space's own fog distance.
pub(super) fn tracer_controls(
    ui: &mut egui::Ui,
    settings: &mut ResMut<TracerSettings>,
    status: &TracerStatus,
    default_fog: f64,
) {
    let in_use = if status.fog_distance > 0.0 {
        status.fog_distance
    } else {
        default_fog
    };
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
}

/// The walk's feel and the view, as the panels of the families with a preferred up share
/// them: speed, keeping `up` (the checkbox's label and hover text), the field of view, the
/// stereo settings and the frame rate.
pub(super) fn walk_feel(
    ui: &mut egui::Ui,
    player: &mut PlayerSettings,
    cameras: &mut Query<(&mut CurvedSpaceCamera, &PlayerFrame, &Holonomy)>,
    stereo: &mut ResMut<StereoSettings>,
    inradius: f64,
    diagnostics: &DiagnosticsStore,
    (up_label, up_hover): (&str, &str),
) {
    ui.add(
        egui::Slider::new(&mut player.speed, 0.01..=20.0)
            .logarithmic(true)
            .text("speed (inradii/s)"),
    );
    ui.checkbox(&mut player.fibre_up, up_label)
        .on_hover_text(up_hover);
    for (mut camera, _, _) in cameras.iter_mut() {
        let mut fov = camera.fov_y_degrees;
        if ui
            .add(egui::Slider::new(&mut fov, 20.0..=120.0).text("field of view (°)"))
            .changed()
        {
            camera.fov_y_degrees = fov;
        }
    }
    ui.separator();
    stereo_controls(ui, stereo, inradius);
    ui.separator();
    frame_rate(ui, diagnostics);
}

/// The frame rate and a frame's time, smoothed, where the diagnostics have them.
pub(super) fn frame_rate(ui: &mut egui::Ui, diagnostics: &DiagnosticsStore) {
    let fps = diagnostics
        .get(&FrameTimeDiagnosticsPlugin::FPS)
        .and_then(|d| d.smoothed());
    let ms = diagnostics
        .get(&FrameTimeDiagnosticsPlugin::FRAME_TIME)
        .and_then(|d| d.smoothed());
    if let (Some(fps), Some(ms)) = (fps, ms) {
        ui.label(format!("{fps:.0} fps, {ms:.1} ms per frame"));
    }
}
