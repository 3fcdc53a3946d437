//! Spaces from groups: generator files read and written, Dirichlet domains against the seed
//! cells and closed forms, the library against SnapPy's stored numbers, and every kind of
//! bad generator refused with the right error.

use bevy_curved_spaces::geometry::{Geometry, ORIGIN};
use bevy_curved_spaces::space::dirichlet::{
    DirichletOptions, dirichlet_space, space_from_matrices,
};
use bevy_curved_spaces::space::group::{Generators, GroupError, parse_gen, write_gen};
use bevy_curved_spaces::space::homology::{Homology, first_homology};
use bevy_curved_spaces::space::invariants::{circumradius, group_order, inradius, volume};
use bevy_curved_spaces::space::library::{CENSUS, library_space, quaternion_map};
use bevy_curved_spaces::space::{SEED_SPACES, Space, resolve_space, seed_space};
use glam::{DMat3, DMat4, DQuat, DVec3, DVec4};
use std::f64::consts::PI;
use std::path::Path;

mod domains;
mod files;
mod invariants;

fn library(id: &str) -> Space {
    match library_space(id) {
        Some(Ok(s)) => s,
        Some(Err(e)) => panic!("{id}: {e}"),
        None => panic!("{id} is no library id"),
    }
}

fn max_entry(m: DMat4) -> f64 {
    m.to_cols_array()
        .iter()
        .fold(0.0_f64, |a, x| a.max(x.abs()))
}

/// Whether two cells are the same up to a rotation about the centre (proper, so the
/// handedness of twists counts) and a renumbering of faces: the rotation carries each face
/// plane of `a` onto one of `b`, partners onto partners, and conjugates the pairings.
fn congruent(a: &Space, b: &Space, tol: f64) -> bool {
    if a.geometry() != b.geometry() || a.faces().len() != b.faces().len() {
        return false;
    }
    let fa = a.faces();
    let fb = b.faces();
    // Two faces of `a` with independent normals fix the rotation.
    let i0 = 0;
    let Some(i1) = (1..fa.len()).find(|&i| fa[i].normal.cross(fa[i0].normal).length() > 0.1) else {
        return false;
    };
    let frame = |x: DVec3, y: DVec3| {
        let e0 = x.normalize();
        let e1 = (y - e0 * y.dot(e0)).normalize();
        DMat3::from_cols(e0, e1, e0.cross(e1))
    };
    let from = frame(fa[i0].normal, fa[i1].normal);
    for j0 in 0..fb.len() {
        for j1 in 0..fb.len() {
            if j0 == j1
                || (fb[j0].normal.dot(fb[j1].normal) - fa[i0].normal.dot(fa[i1].normal)).abs() > tol
            {
                continue;
            }
            let r3 = frame(fb[j0].normal, fb[j1].normal) * from.transpose();
            let r = DMat4::from_mat3(r3);
            let matched: Option<Vec<usize>> = fa
                .iter()
                .map(|f| {
                    fb.iter().position(|g| {
                        (r3 * f.normal - g.normal).length() < tol
                            && (f.offset - g.offset).abs() < tol * f.offset.max(1.0)
                    })
                })
                .collect();
            let Some(m) = matched else { continue };
            let ok = fa.iter().enumerate().all(|(i, f)| {
                fb[m[i]].partner == m[f.partner]
                    && max_entry(r * f.pairing * r.transpose() - fb[m[i]].pairing)
                        < tol * max_entry(f.pairing).max(1.0)
            });
            if ok {
                return true;
            }
        }
    }
    false
}
