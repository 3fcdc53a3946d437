//! Cells correctly rounded: every seed space's numbers against an independent
//! double-double construction of its cell from the closed form.
//!
//! The reference here is built another way than the crate builds it: face planes from
//! closed forms written out for each space (`(0, ±1, ±φ)/√(φ + 2)`, `r² = 1 − 2/√5`, …),
//! vertices where three planes meet, and each pairing as the one linear map that sends three
//! vertices of its face and the cell's centre to their images (the partner face's vertices
//! and the centre's mirror image in the partner face), solved in double-double. The crate
//! composes rotations and translations instead, so the two agree only if both are right.

use bevy_curved_spaces::geometry::{DdMat4, DdVec4, DoubleDouble, Geometry, Real, Vector4};
use bevy_curved_spaces::space::{CellWalker, SEED_SPACES, Space};
use glam::{DVec4, Vec4};

fn dd(x: f64) -> DoubleDouble {
    DoubleDouble::new(x)
}

type Dd3 = [DoubleDouble; 3];

/// The face planes `n·x = r` of a seed cell from its closed form, in the crate's face
/// order (matched by direction), or `None` for a space this test does not know.
fn reference_planes(space: &Space) -> Option<Vec<(Dd3, DoubleDouble)>> {
    let (o, z) = (dd(1.0), dd(0.0));
    let half = dd(0.5);
    let root3_2 = dd(3.0).sqrt() / dd(2.0);
    let root2_2 = dd(2.0).sqrt() / dd(2.0);
    let root5 = dd(5.0).sqrt();
    let phi = (o + root5) * half;
    let signs = |v: Dd3| {
        let mut out = vec![];
        for s in [o, -o] {
            out.push(v.map(|x| x * s));
        }
        out
    };
    let cube = || {
        let mut d = vec![];
        for axis in 0..3 {
            let mut v = [z; 3];
            v[axis] = o;
            d.extend(signs(v));
        }
        d
    };
    let dodecahedron = |r: DoubleDouble| {
        let len = (phi + dd(2.0)).sqrt();
        let mut d = vec![];
        for (a, b) in [(o, phi), (-o, phi)] {
            for v in [[z, a, b], [a, b, z], [b, z, a]] {
                d.extend(signs(v.map(|x| x / len)));
            }
        }
        d.into_iter().map(|n| (n, r)).collect::<Vec<_>>()
    };
    let planes: Vec<(Dd3, DoubleDouble)> = match space.name() {
        "torus" | "half-turn" | "quarter-turn" | "mirrored-cube" => {
            cube().into_iter().map(|n| (n, half)).collect()
        }
        "third-turn" | "sixth-turn" => {
            let mut d = vec![];
            for v in [[o, z, z], [half, root3_2, z], [-half, root3_2, z]] {
                d.extend(signs(v));
            }
            d.extend(signs([z, z, o]));
            d.into_iter().map(|n| (n, half)).collect()
        }
        "hantzsche-wendt" => {
            let mut d = vec![];
            for (i, j) in [(0, 1), (0, 2), (1, 2)] {
                for t in [o, -o] {
                    let mut v = [z; 3];
                    v[i] = root2_2;
                    v[j] = t * root2_2;
                    d.extend(signs(v));
                }
            }
            d.into_iter().map(|n| (n, root2_2)).collect()
        }
        // cos 72° = (√5 − 1)/4: r² = (1/√5 + cos α)/(1 + cos α) in H³.
        "seifert-weber" => {
            let c = (root5 - o) / dd(4.0);
            dodecahedron(((o / root5 + c) / (o + c)).sqrt())
        }
        // cos 120° = −½: r² = 1 − 2/√5 in S³.
        "poincare" => dodecahedron((o - dd(2.0) / root5).sqrt()),
        // cos 90° = 0: r = 5^(−1/4) in H³.
        "mirrored-dodecahedron" => dodecahedron((o / root5).sqrt()),
        _ => return None,
    };
    // In the crate's face order.
    let ordered = space
        .faces()
        .iter()
        .map(|f| {
            *planes
                .iter()
                .find(|(n, _)| {
                    (0..3)
                        .map(|i| (n[i].to_f64() - f.normal[i]).abs())
                        .sum::<f64>()
                        < 1e-9
                })
                .unwrap_or_else(|| panic!("{}: no closed-form face {:?}", space.name(), f.normal))
        })
        .collect();
    Some(ordered)
}

fn det3(r: [Dd3; 3]) -> DoubleDouble {
    r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
        - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
        + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0])
}

/// The chart point where three planes meet.
fn meet(p: [(Dd3, DoubleDouble); 3]) -> Dd3 {
    let rows = p.map(|(n, _)| n);
    let d = det3(rows);
    std::array::from_fn(|k| {
        let mut m = rows;
        for i in 0..3 {
            m[i][k] = p[i].1;
        }
        det3(m) / d
    })
}

/// The model point of a chart point.
fn model(g: Geometry, x: Dd3) -> DdVec4 {
    let x2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    let w = match g {
        Geometry::Euclidean => dd(1.0),
        Geometry::Spherical => dd(1.0) / (dd(1.0) + x2).sqrt(),
        Geometry::Hyperbolic => dd(1.0) / (dd(1.0) - x2).sqrt(),
    };
    DdVec4([x[0] * w, x[1] * w, x[2] * w, w])
}

/// The inverse of a 4×4 matrix by Gauss–Jordan elimination with partial pivoting.
fn invert(m: DdMat4) -> DdMat4 {
    let mut a: [[DoubleDouble; 8]; 4] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            if j < 4 {
                m.at(i, j)
            } else {
                dd(if j - 4 == i { 1.0 } else { 0.0 })
            }
        })
    });
    for col in 0..4 {
        let pivot = (col..4)
            .max_by(|&x, &y| {
                a[x][col]
                    .abs()
                    .to_f64()
                    .total_cmp(&a[y][col].abs().to_f64())
            })
            .unwrap();
        a.swap(col, pivot);
        let p = a[col][col];
        for x in &mut a[col] {
            *x = *x / p;
        }
        let pivot_row = a[col];
        for (i, row) in a.iter_mut().enumerate() {
            if i != col {
                let f = row[col];
                for (x, y) in row.iter_mut().zip(pivot_row) {
                    *x = *x - f * y;
                }
            }
        }
    }
    DdMat4(std::array::from_fn(|j| {
        DdVec4(std::array::from_fn(|i| a[i][j + 4]))
    }))
}

/// The mirror image of the origin in the plane `n·x = r`, as a model point.
fn mirrored_origin(g: Geometry, n: Dd3, r: DoubleDouble) -> DdVec4 {
    let origin = DdVec4([dd(0.0), dd(0.0), dd(0.0), dd(1.0)]);
    let cov = DdVec4([n[0], n[1], n[2], -r]);
    let m = DdVec4([n[0], n[1], n[2], dd(g.kappa()) * -r]);
    let scale = dd(2.0) * cov.dot(origin) / cov.dot(m);
    origin - m.scale(scale)
}

/// An independent double-double cell: each face's covector and pairing.
struct Reference {
    covectors: Vec<DdVec4>,
    pairings: Vec<DdMat4>,
    vertices: Vec<Dd3>,
}

fn reference(space: &Space) -> Option<Reference> {
    let g = space.geometry();
    let planes = reference_planes(space)?;
    let vertices: Vec<Dd3> = space
        .vertices()
        .iter()
        .map(|v| {
            let on: Vec<(Dd3, DoubleDouble)> = planes
                .iter()
                .filter(|(n, r)| {
                    ((0..3).map(|i| n[i].to_f64() * v[i]).sum::<f64>() - r.to_f64()).abs() < 1e-9
                })
                .copied()
                .collect();
            // Three planes that meet squarely.
            let mut best = None;
            for a in 0..on.len() {
                for b in a + 1..on.len() {
                    for c in b + 1..on.len() {
                        let d = det3([on[a].0, on[b].0, on[c].0]).abs().to_f64();
                        if best.is_none_or(|(_, e)| d > e) {
                            best = Some(([on[a], on[b], on[c]], d));
                        }
                    }
                }
            }
            meet(best.expect("a vertex on three faces").0)
        })
        .collect();
    let points: Vec<DdVec4> = vertices.iter().map(|&v| model(g, v)).collect();
    let pairings = space
        .faces()
        .iter()
        .map(|face| {
            // Three vertices of the face spread round it, and the centre.
            let k = face.vertices.len();
            let picks = [
                face.vertices[0],
                face.vertices[k / 3],
                face.vertices[2 * k / 3],
            ];
            let image = |v: usize| {
                // Which vertex of the partner it goes to (only the index comes from the
                // crate's f64 pairing).
                let to = face.pairing * space.vertex_point(v);
                (0..space.vertices().len())
                    .min_by(|&a, &b| {
                        (space.vertex_point(a) - to)
                            .length()
                            .total_cmp(&(space.vertex_point(b) - to).length())
                    })
                    .unwrap()
            };
            let (n, r) = planes[face.partner];
            let from = DdMat4([
                points[picks[0]],
                points[picks[1]],
                points[picks[2]],
                DdVec4([dd(0.0), dd(0.0), dd(0.0), dd(1.0)]),
            ]);
            let to = DdMat4([
                points[image(picks[0])],
                points[image(picks[1])],
                points[image(picks[2])],
                mirrored_origin(g, n, r),
            ]);
            to * invert(from)
        })
        .collect();
    Some(Reference {
        covectors: planes
            .iter()
            .map(|(n, r)| DdVec4([n[0], n[1], n[2], -*r]))
            .collect(),
        pairings,
        vertices,
    })
}

/// Whether `x` is the `f64` nearest `exact`: within half a unit in the last place (a
/// value that is exactly zero must be zero).
fn correctly_rounded_f64(x: f64, exact: DoubleDouble) -> bool {
    if exact.abs().to_f64() < 1e-25 {
        return x == 0.0;
    }
    let ulp = (x.abs().next_up() - x.abs()).min(x.abs() - x.abs().next_down());
    ((dd(x) - exact).abs().to_f64()) <= 0.5 * ulp * (1.0 + 1e-9)
}

/// The same for `f32`.
fn correctly_rounded_f32(x: f32, exact: DoubleDouble) -> bool {
    if exact.abs().to_f64() < 1e-25 {
        return x == 0.0;
    }
    let a = x.abs();
    let ulp = f64::from((a.next_up() - a).min(a - a.next_down()));
    ((dd(f64::from(x)) - exact).abs().to_f64()) <= 0.5 * ulp * (1.0 + 1e-9)
}

/// Every seed space with its independent reference.
fn seeds() -> Vec<(Space, Reference)> {
    SEED_SPACES
        .iter()
        // A space of several cells is not built from a closed form: `torus-two-cells` is
        // given by halves and units, exact in binary (`several_cells.rs` checks them).
        .filter(|s| s.build().unwrap().cells().len() == 1)
        .map(|s| {
            let space = s.build().unwrap();
            let r = reference(&space).unwrap_or_else(|| panic!("no reference for {}", s.id));
            (space, r)
        })
        .collect()
}

#[test]
fn the_independent_reference_is_a_valid_cell_of_each_seed_space() {
    // The reference itself: each pairing is an isometry that maps its face's covector to
    // the partner's (turned inside out) and is the inverse of the partner's, to 30 digits.
    for (space, r) in seeds() {
        let g = space.geometry();
        let k = dd(g.kappa());
        for (f, face) in space.faces().iter().enumerate() {
            let m = r.pairings[f];
            let back = r.pairings[face.partner];
            let product = back * m;
            let defect = (product - DdMat4::IDENTITY).max_abs();
            assert!(
                defect < 1e-28,
                "{} face {f}: pairings not inverse by {defect:e}",
                space.name()
            );
            if g != Geometry::Euclidean {
                // mᵀ G m = G.
                let gm = |i: usize| if i == 3 { k } else { dd(1.0) };
                for a in 0..4 {
                    for b in 0..4 {
                        let s = (0..4).fold(dd(0.0), |s, i| s + m.at(i, a) * gm(i) * m.at(i, b));
                        let want = if a == b { gm(a) } else { dd(0.0) };
                        assert!(
                            (s - want).abs().to_f64() < 1e-28,
                            "{} face {f}: not an isometry",
                            space.name()
                        );
                    }
                }
            }
            // The cell's vertices on this face go to vertices on the partner face.
            for &v in &face.vertices {
                let p = m * model(g, r.vertices[v]);
                let on = r.covectors[face.partner].dot(p).abs().to_f64();
                assert!(
                    on < 1e-28,
                    "{} face {f}: vertex {v} off the partner by {on:e}",
                    space.name()
                );
            }
        }
    }
}

#[test]
fn every_seed_cell_agrees_with_the_independent_reference_to_28_digits() {
    for (space, r) in seeds() {
        let cell = space
            .exact()
            .unwrap_or_else(|| panic!("{}: no exact cell", space.name()));
        for (f, face) in cell.faces.iter().enumerate() {
            let dc = (face.covector() - r.covectors[f])
                .0
                .map(|x| x.abs().to_f64());
            assert!(
                dc.iter().all(|&d| d < 1e-28),
                "{} face {f} covector: {dc:?}",
                space.name()
            );
            let dm = (face.pairing - r.pairings[f]).max_abs();
            assert!(
                dm < 1e-28,
                "{} face {f} pairing off by {dm:e}",
                space.name()
            );
        }
    }
}

#[test]
fn every_seed_cell_is_correctly_rounded_in_f64_and_f32() {
    for (space, r) in seeds() {
        let name = space.name().to_string();
        let mut checked = 0;
        for (f, face) in space.faces().iter().enumerate() {
            for i in 0..4 {
                assert!(
                    correctly_rounded_f64(face.covector[i], r.covectors[f].0[i]),
                    "{name} face {f} covector[{i}] = {:e}, exact {:?}",
                    face.covector[i],
                    r.covectors[f].0[i]
                );
                for j in 0..4 {
                    let x = face.pairing.col(j)[i];
                    let exact = r.pairings[f].at(i, j);
                    assert!(
                        correctly_rounded_f64(x, exact),
                        "{name} face {f} pairing ({i}, {j}) = {x:e}, exact {exact:?}"
                    );
                    checked += 1;
                }
            }
        }
        for (v, x) in space.vertices().iter().enumerate() {
            for i in 0..3 {
                assert!(
                    correctly_rounded_f64(x[i], r.vertices[v][i]),
                    "{name} vertex {v}[{i}] = {:e}, exact {:?}",
                    x[i],
                    r.vertices[v][i]
                );
            }
        }
        // What the f64 walker and the GPU's f32 copies hold: each rounded once, and the low
        // parts what that rounding left out.
        let w64 = CellWalker::<DVec4>::new(&space);
        let w32 = CellWalker::<Vec4>::new(&space);
        for f in 0..space.faces().len() {
            for i in 0..4 {
                assert!(correctly_rounded_f32(
                    w32.covectors[f][i],
                    r.covectors[f].0[i]
                ));
                assert_eq!(w64.covectors[f][i], space.faces()[f].covector[i]);
                for j in 0..4 {
                    let exact = r.pairings[f].at(i, j);
                    let (hi, lo) = (w32.pairings[f].col(j)[i], w32.pairings_lo[f].col(j)[i]);
                    assert!(
                        correctly_rounded_f32(hi, exact),
                        "{name} face {f} f32 pairing ({i}, {j}) = {hi:e}, exact {exact:?}"
                    );
                    let rest = exact - dd(f64::from(hi));
                    // A rest below double-double's resolution of the entry is zero.
                    let resolution = 1e-28 * exact.abs().to_f64().max(1.0);
                    assert!(
                        if rest.abs().to_f64() < resolution {
                            f64::from(lo.abs()) < resolution
                        } else {
                            correctly_rounded_f32(lo, rest)
                        },
                        "{name} face {f} f32 low part ({i}, {j}) = {lo:e}, exact {rest:?}"
                    );
                    // In f64 the low part carries the value to double-double's own
                    // accuracy (its rounding is below what the reference resolves).
                    let pair = dd(w64.pairings[f].col(j)[i]) + dd(w64.pairings_lo[f].col(j)[i]);
                    let off = (pair - exact).abs().to_f64();
                    assert!(off < 1e-30, "{name} face {f} f64 hi + lo off by {off:e}");
                }
            }
        }
        assert!(checked > 0);
    }
}

#[test]
fn rounding_a_double_double_to_f32_is_correct_at_half_way_points() {
    // 1 + 2⁻²⁴ is half-way between two f32s: ties to even (1), but a hair above goes up.
    let half_way = dd(1.0) + dd(2f64.powi(-24));
    assert_eq!(half_way.round_f32(), 1.0);
    let above = half_way + dd(1e-30);
    assert_eq!(above.round_f32(), 1.0 + f32::EPSILON);
    let below = half_way - dd(1e-30);
    assert_eq!(below.round_f32(), 1.0);
    // Rounding to f64 first would land on the half-way point and go to even: wrong.
    assert_eq!((above.hi as f32), 1.0);
    // Odd neighbour: ties go up to even.
    let odd = dd(f64::from(1.0 + f32::EPSILON)) + dd(2f64.powi(-24));
    assert_eq!(odd.round_f32(), 1.0 + 2.0 * f32::EPSILON);
    // Negative values mirror.
    assert_eq!((-above).round_f32(), -(1.0 + f32::EPSILON));
    // Vector4's rounding of a pair is the same.
    let v = <Vec4 as Vector4>::from_f64_pair(DVec4::splat(above.hi), DVec4::splat(above.lo));
    assert_eq!(v.x, 1.0 + f32::EPSILON);
}
