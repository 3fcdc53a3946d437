//! The panel's teaching views: the mini-map of the cell and the ray inspector.

use super::*;

/// The cell seen from outside: its edges in the chart (coloured by edge cycle, as the
/// default scene draws them), each face's number at its nearest point to the centre in
/// that face's colour (the colours of `--colour-by face`, or of the walls when they are
/// shown), and the player: a white dot and
/// the direction it looks in. An oblique view of the chart, fixed so that it reads the
/// same as you move.
pub(super) fn minimap(
    ui: &mut egui::Ui,
    space: &crate::space::Space,
    inradius: f64,
    frame: &PlayerFrame,
    walls: bool,
) {
    use crate::scene::palette;
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
    let ahead = g.to_chart((frame.0 * g.translation(glam::DVec3::NEG_Z, 0.3 * inradius)).w_axis);
    let (p, q) = (to_screen(here), to_screen(ahead));
    painter.line_segment([p, q], egui::Stroke::new(2.0, egui::Color32::WHITE));
    painter.circle_filled(p, 4.0, egui::Color32::WHITE);
}

/// The story of the ray through the pointer (or the screen centre while the mouse looks
/// round): the faces it crossed with the distance at each, the word of pairings, and what
/// it met. Traced on the CPU in f64, the reference the GPU is tested against.
#[allow(clippy::too_many_arguments)]
pub(super) fn inspector(
    ui: &mut egui::Ui,
    space: &crate::space::Space,
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
