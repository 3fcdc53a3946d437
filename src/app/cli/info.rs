//! `list`, `info` and `export`: the seed spaces, a space's invariants, a space as a file.

use bevy::prelude::*;
use bevy_curved_spaces::space::file::SpaceRecord;
use bevy_curved_spaces::space::group::write_gen;
use bevy_curved_spaces::space::invariants::Invariants;
use bevy_curved_spaces::space::library::{FAMILIES, is_gen_path};
use bevy_curved_spaces::space::nil::NilSpace;
use bevy_curved_spaces::space::product::ProductSpace;
use bevy_curved_spaces::space::sl2r::UnitTangentSpace;
use bevy_curved_spaces::space::{SEED_SPACES, Space};
use std::path::Path;

pub(super) fn list() {
    say!(
        "{:<22} {:<11} {:>5} {:>14}  description",
        "id",
        "geometry",
        "faces",
        "volume"
    );
    for seed in SEED_SPACES {
        match seed.build() {
            Ok(space) => say!(
                "{:<22} {:<11} {:>5} {:>14.10}  {}",
                seed.id,
                space.geometry().name(),
                space.faces().len(),
                bevy_curved_spaces::space::invariants::volume(&space),
                seed.summary
            ),
            Err(e) => say!("{:<22} invalid: {e}", seed.id),
        }
    }
    say!("");
    say!("families built from groups (any member by its id, e.g. `curved-spaces walk lens-7-2`):");
    say!("{:<22} {:<11}  description", "id", "geometry");
    for family in FAMILIES {
        say!(
            "{:<22} {:<11}  {}",
            family.pattern,
            family.geometry.name(),
            family.summary
        );
        if family.examples.len() > 1 || family.examples[0] != family.pattern {
            say!("{:<22} {:<11}  e.g. {}", "", "", family.examples.join(", "));
        }
    }
    say!("");
    say!(
        "product spaces (H²×R, S²×R): surface-WORD-circle-L[-turn-P], e.g. \
         surface-abABcdCD-circle-2 (a flat word such as abAB gives a flat space); by name:"
    );
    say!(
        "{:<24} {:<11} {:>14}  description",
        "id",
        "geometry",
        "volume"
    );
    for alias in bevy_curved_spaces::space::product::PRODUCT_ALIASES {
        match ProductSpace::new(alias.id, alias.word, alias.length, alias.turn) {
            Ok(p) => say!(
                "{:<24} {:<11} {:>14.10}  {}",
                alias.id,
                p.geometry_name(),
                p.volume(),
                alias.summary
            ),
            Err(e) => say!("{:<24} invalid: {e}", alias.id),
        }
    }
    say!("");
    say!(
        "Nil spaces: nil-K (K = 1 … {}; heisenberg is nil-1), the Heisenberg group over the \
         lattice whose centre is 1/K: every command takes them",
        bevy_curved_spaces::space::nil::MAX_NIL_K
    );
    say!("");
    say!(
        "SL̃(2,R) spaces: unit-tangent-WORD (unit-tangent-bitorus is unit-tangent-abABcdCD), the \
         unit tangent bundle of the orientable hyperbolic surface of WORD: `info`, `trace`, \
         `render` and `walk` take them (not yet `flight`, `light` or the headset)"
    );
    say!("");
    say!(
        "SPACE may also be a space file: JSON (`curved-spaces export SPACE` writes one) or a \
         Curved Spaces generator file (.gen); scripts/snappy-export.py writes .gen files of \
         SnapPy's manifolds."
    );
}

/// A number for people: fixed point where that is readable, scientific notation for the
/// very small and very large, and words where `f64` could not hold it.
fn number(x: f64, digits: usize) -> String {
    if !x.is_finite() {
        return "larger than f64 can hold".to_string();
    }
    let a = x.abs();
    if a == 0.0 || (1e-4..1e9).contains(&a) {
        format!("{x:.digits$}")
    } else {
        format!("{x:.digits$e}")
    }
}

/// JSON has no infinity: a volume f64 cannot hold is written null, and a note says why.
fn note_volume(value: &mut serde_json::Value, volume: f64) {
    if !volume.is_finite() {
        value["volume_note"] = serde_json::json!(
            "the volume is larger than f64 can hold (1.8e308): the cell is too large"
        );
    }
}

pub(super) fn info(space: &Space, as_json: bool) -> Result<(), String> {
    let inv = Invariants::compute(space);
    if as_json {
        let mut value = serde_json::to_value(&inv).map_err(|e| e.to_string())?;
        note_volume(&mut value, inv.volume);
        say!(
            "{}",
            serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    let opt = |x: Option<f64>| x.map_or("–".to_string(), |x| number(x, 10));
    let opt_n = |x: Option<usize>| x.map_or("–".to_string(), |x| x.to_string());
    say!("{} ({})", inv.name, inv.geometry.name());
    say!("  {}", space.description());
    say!("  faces               {}", inv.faces.len());
    if inv.cells > 1 {
        say!("  cells               {}", inv.cells);
    }
    say!("  volume              {}", number(inv.volume, 12));
    say!("  inradius            {}", number(inv.inradius, 10));
    say!("  circumradius        {}", number(inv.circumradius, 10));
    say!("  edge length         {}", opt(inv.edge_length));
    let cycles: Vec<String> = inv
        .edge_cycles
        .iter()
        .map(|c| format!("{}×{:.1}°", c.edges, c.angle_sum.to_degrees()))
        .collect();
    say!(
        "  edge cycles         {} ({})",
        cycles.len(),
        cycles.join(", ")
    );
    say!("  vertex cycles       {}", inv.vertex_cycles);
    say!("  orientable          {}", inv.orientable);
    say!("  manifold            {}", inv.manifold);
    say!("  holonomy order      {}", opt_n(inv.holonomy_order));
    say!("  group order         {}", opt_n(inv.group_order));
    say!("  first homology      {}", inv.homology);
    say!("  injectivity radius  {}", opt(inv.injectivity_radius));
    match &inv.closed_geodesics {
        None => say!("  closed geodesics    too many group elements to enumerate"),
        Some(list) if !list.is_empty() => {
            say!("  closed geodesics    length × count");
            for g in list {
                say!(
                    "                      {} × {}",
                    number(g.length, 10),
                    g.count
                );
            }
        }
        Some(_) => {}
    }
    Ok(())
}

/// `info` for a product space: its geometry, surface, volume, circle and homology.
pub(super) fn product_info(space: &ProductSpace, as_json: bool) -> Result<(), String> {
    let word = space.word();
    let h1 = space.homology().to_string();
    if as_json {
        let mut value = serde_json::json!({
            "name": space.name(),
            "geometry": space.geometry_name(),
            "description": space.description(),
            "surface": word.word,
            "surface_name": word.common_name(),
            "euler_characteristic": word.euler_characteristic(),
            "sides": word.side_count(),
            "corners_per_vertex": word.corners_per_vertex(),
            "faces": space.face_count(),
            "base_area": space.base_area(),
            "circle_length": space.length(),
            "turn": space.turn(),
            "volume": space.volume(),
            "base_inradius": space.base_inradius(),
            "orientable": space.orientable(),
            "homology": h1,
            "injectivity_radius": space.injectivity_radius(200_000),
        });
        note_volume(&mut value, space.volume());
        say!(
            "{}",
            serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    say!("{} ({})", space.name(), space.geometry_name());
    say!("  {}", space.description());
    say!(
        "  surface             {} ({}), {} sides, {} corners per vertex",
        word.word,
        word.common_name(),
        word.side_count(),
        word.corners_per_vertex()
    );
    say!("  Euler char.         {}", word.euler_characteristic());
    say!(
        "  faces               {} (sides × the circle, top, bottom)",
        space.face_count()
    );
    say!("  base area           {}", number(space.base_area(), 12));
    say!("  circle length       {}", number(space.length(), 12));
    say!(
        "  turn                {}",
        if space.turn() > 1 {
            format!("2π/{}", space.turn())
        } else {
            "none".to_string()
        }
    );
    say!("  volume              {}", number(space.volume(), 12));
    say!(
        "  base inradius       {}",
        number(space.base_inradius(), 10)
    );
    say!("  orientable          {}", space.orientable());
    say!("  first homology      {h1}");
    say!(
        "  injectivity radius  {}",
        space
            .injectivity_radius(200_000)
            .map_or("– (too many group elements)".to_string(), |r| number(
                r, 10
            ))
    );
    Ok(())
}

/// `info` of a Nil space: its lattice and cell, and the invariants computed from them.
pub(super) fn nil_info(space: &NilSpace, as_json: bool) -> Result<(), String> {
    use bevy_curved_spaces::space::FrameSpace;
    let h1 = space.homology().to_string();
    if as_json {
        let value = serde_json::json!({
            "name": space.name(),
            "geometry": "Nil",
            "description": space.description(),
            "k": space.k(),
            "faces": space.face_count(),
            "cell": {"x": [-0.5, 0.5], "y": [-0.5, 0.5], "z": [-space.half_height(), space.half_height()]},
            "volume": space.volume(),
            "orientable": true,
            "manifold": true,
            "homology": h1,
            "injectivity_radius": space.injectivity_radius(),
        });
        say!(
            "{}",
            serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    say!("{} (Nil)", space.name());
    say!("  {}", space.description());
    say!("  K                   {}", space.k());
    say!(
        "  faces               {} (x = ±1/2, y = ±1/2, z = ±1/{})",
        space.face_count(),
        2 * space.k()
    );
    say!("  volume              {}", number(space.volume(), 12));
    say!("  orientable          true");
    say!("  manifold            true");
    say!("  first homology      {h1}");
    say!(
        "  injectivity radius  {}",
        number(space.injectivity_radius(), 10)
    );
    Ok(())
}

/// `info` of an SL̃(2,R) space: its surface and cell, and the invariants computed from them.
pub(super) fn sl2r_info(space: &UnitTangentSpace, as_json: bool) -> Result<(), String> {
    use bevy_curved_spaces::space::FrameSpace;
    let word = space.word();
    let inj = space.injectivity_radius(bevy_curved_spaces::space::family::PRODUCT_GROUP_LIMIT);
    let h1 = space.homology().to_string();
    let sheets = space.sheets();
    if as_json {
        let value = serde_json::json!({
            "name": space.name(),
            "geometry": "SL2R",
            "description": space.description(),
            "word": word.word,
            "genus": space.genus(),
            "euler_characteristic": word.euler_characteristic(),
            "faces": space.face_count(),
            "polygon_inradius": space.inradius(),
            "sheets": sheets,
            "fibre_length": std::f64::consts::TAU * f64::from(sheets),
            "volume": space.volume(),
            "orientable": true,
            "manifold": true,
            "homology": h1,
            "injectivity_radius": if sheets == 1 { inj } else { None },
            "injectivity_radius_at_least": inj,
        });
        say!(
            "{}",
            serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    say!("{} (SL̃(2,R))", space.name());
    say!("  {}", space.description());
    say!(
        "  surface             {} (genus {}, Euler characteristic {})",
        word.word,
        space.genus(),
        word.euler_characteristic()
    );
    say!(
        "  faces               {} (the polygon's sides times the fibre; inradius {})",
        space.face_count(),
        number(space.inradius(), 12)
    );
    if sheets == 1 {
        say!("  fibre length        2π");
    } else {
        say!("  fibre length        {sheets}·2π (the bundle's fibre unwound {sheets} times)");
    }
    say!("  volume              {}", number(space.volume(), 12));
    say!("  orientable          true");
    say!("  manifold            true");
    say!("  first homology      {h1}");
    match inj {
        Some(r) if sheets > 1 => say!(
            "  injectivity radius  at least {} (the bundle's: a cover's loops are no shorter)",
            number(r, 10)
        ),
        Some(r) => say!(
            "  injectivity radius  {} (half the surface's systole, at most π)",
            number(r, 10)
        ),
        None => say!("  injectivity radius  (the surface group is too large to search)"),
    }
    Ok(())
}

pub(super) fn export(space: &Space, out: Option<&Path>, gen_format: bool) -> Result<(), String> {
    let gen_format = gen_format || out.is_some_and(is_gen_path);
    let text = if gen_format {
        write_gen(space).trim_end().to_string()
    } else if space.reaches_equator() {
        return Err(format!(
            "{} reaches distance π/2 from its centre, which a JSON space file (faces as chart \
             planes) cannot hold; export it as a generator file (`--gen-format` or \
             `--out FILE.gen`)",
            space.name()
        ));
    } else {
        serde_json::to_string_pretty(&SpaceRecord::from_space(space)).map_err(|e| e.to_string())?
    };
    match out {
        Some(path) => {
            bevy_curved_spaces::files::write_atomic(path, (text + "\n").as_bytes())
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            say!("wrote {}", path.display());
        }
        None => say!("{text}"),
    }
    Ok(())
}
