//! The panel's space picker: the seed spaces, the library's families and files.

use super::*;

/// The space picker's fields: the family parameters and the file path being typed, and the
/// last error.
#[derive(Debug)]
pub struct SpacePicker {
    lens_p: u32,
    lens_q: u32,
    prism_n: u32,
    census: usize,
    nil_k: u32,
    path: String,
    pub(super) error: Option<String>,
}

impl Default for SpacePicker {
    fn default() -> Self {
        Self {
            lens_p: 7,
            lens_q: 2,
            prism_n: 3,
            census: 1,
            nil_k: 3,
            path: String::new(),
            error: None,
        }
    }
}

/// The library members without parameters, as the picker lists them.
pub(super) const LIBRARY_FIXED: &[&str] = &[
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
/// `active_id` is the space shown and `description` a line about it.
pub(super) fn space_picker(
    ui: &mut egui::Ui,
    active_id: &str,
    description: &str,
    picker: &mut SpacePicker,
) -> Option<String> {
    let mut chosen = None;
    egui::ComboBox::from_label("space")
        .selected_text(active_id)
        .show_ui(ui, |ui| {
            let mut item = |ui: &mut egui::Ui, id: &str, summary: &str| {
                if ui
                    .selectable_label(active_id == id, id)
                    .on_hover_text(summary)
                    .clicked()
                {
                    chosen = Some(id.to_string());
                }
            };
            for seed in SEED_SPACES {
                item(ui, seed.id, seed.summary);
            }
            ui.separator();
            for &id in LIBRARY_FIXED {
                let summary = crate::space::library::FAMILIES
                    .iter()
                    .find(|f| f.pattern == id)
                    .map_or("", |f| f.summary);
                item(ui, id, summary);
            }
            ui.separator();
            for alias in crate::space::product::PRODUCT_ALIASES {
                item(ui, alias.id, alias.summary);
            }
        });
    if let Some(summary) = SEED_SPACES.iter().find(|s| s.id == active_id) {
        ui.label(egui::RichText::new(summary.summary).small());
    } else if !description.is_empty() {
        ui.label(egui::RichText::new(description).small());
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
            ui.label("Nil");
            ui.add(
                egui::DragValue::new(&mut picker.nil_k)
                    .range(1..=crate::space::nil::MAX_NIL_K)
                    .prefix("K "),
            );
            if ui.button("go").clicked() {
                chosen = Some(format!("nil-{}", picker.nil_k));
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

/// Shows the space an id names, of any family, as the [`ActiveSpace`]; players go to its
/// start view. An error names what is wrong with the id.
pub(super) fn switch_space(id: &str, commands: &mut Commands) -> Result<(), String> {
    commands.insert_resource(ActiveSpace::named(id)?);
    Ok(())
}

/// The panel's window in a family of its own section (products, Nil, SL̃(2,R)): the space
/// picker at the top (a pick switches the space), the family's `body`, then the tracer's
/// errors and the `keys` hint. Marks whether the pointer is over it.
pub(super) fn family_window(
    ctx: &egui::Context,
    active: &ActiveSpace,
    picker: &mut SpacePicker,
    commands: &mut Commands,
    status: &TracerStatus,
    keys: &str,
    body: impl FnOnce(&mut egui::Ui),
) -> bool {
    egui::Window::new("Curved spaces")
        .default_pos((12.0, 12.0))
        .default_width(300.0)
        .vscroll(true)
        .show(ctx, |ui| {
            if let Some(id) = space_picker(ui, &active.id, active.space.description(), picker)
                && id != active.id
            {
                picker.error = switch_space(&id, commands).err();
                if let Some(e) = &picker.error {
                    error!("{e}");
                }
            }
            ui.separator();
            body(ui);
            for e in [&status.error, &status.stereo_error].into_iter().flatten() {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
            }
            ui.label(egui::RichText::new(keys).small());
        });
    ctx.is_pointer_over_egui()
}
