//! The first homology group `H₁` of a space: its fundamental (or orbifold) group made
//! abelian, read from the cell's presentation. The generators are the face pairings (one per
//! pair of faces); the relations are the edge cycles (the pairings met going once around an
//! edge, to the power of the cycle's order) and, for a mirror, its square. The Smith normal
//! form of the relation matrix gives the invariant factors.

use super::Space;
use serde::Serialize;
use std::fmt;

/// A finitely generated abelian group `Zʳ ⊕ Z/d₁ ⊕ … ⊕ Z/dₖ`, each `dᵢ > 1` dividing the next.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Homology {
    /// The rank `r` of the free part (the first Betti number).
    pub rank: usize,
    /// The torsion coefficients `dᵢ`, ascending, each dividing the next.
    pub torsion: Vec<u64>,
}

impl fmt::Display for Homology {
    /// SnapPy's notation: `0`, `Z`, `Z/5 + Z/5`, `Z/2 + Z`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts: Vec<String> = self.torsion.iter().map(|d| format!("Z/{d}")).collect();
        parts.extend(std::iter::repeat_n("Z".to_string(), self.rank));
        if parts.is_empty() {
            write!(f, "0")
        } else {
            write!(f, "{}", parts.join(" + "))
        }
    }
}

impl Homology {
    /// Parses SnapPy's notation (`Z/5 + Z/5`, `Z + Z/2`, `0`) into invariant factors
    /// (cyclic factors given in any order are combined into the canonical form).
    pub fn parse(text: &str) -> Result<Self, String> {
        let text = text.trim();
        if text == "0" {
            return Ok(Self {
                rank: 0,
                torsion: Vec::new(),
            });
        }
        let mut rank = 0;
        let mut orders = Vec::new();
        for part in text.split('+').map(str::trim) {
            if part == "Z" {
                rank += 1;
            } else if let Some(d) = part.strip_prefix("Z/") {
                orders.push(
                    d.parse::<u64>()
                        .map_err(|_| format!("`{part}` is not Z or Z/n"))?,
                );
            } else {
                return Err(format!("`{part}` is not Z or Z/n"));
            }
        }
        // The invariant factors of a diagonal matrix.
        let rows: Vec<Vec<i128>> = orders
            .iter()
            .enumerate()
            .map(|(i, &d)| {
                let mut r = vec![0; orders.len()];
                r[i] = i128::from(d);
                r
            })
            .collect();
        let mut h = from_relations(&rows, orders.len());
        h.rank += rank;
        Ok(h)
    }
}

/// `H₁` of the group with `generators` generators and these relations (rows of exponents),
/// for the other kinds of cell (the product spaces).
#[must_use]
pub(crate) fn relations_homology(relations: &[Vec<i128>], generators: usize) -> Homology {
    from_relations(relations, generators)
}

/// `H₁` of the group with `generators` generators and these relations (rows of exponents).
pub(crate) fn from_relations(relations: &[Vec<i128>], generators: usize) -> Homology {
    let diagonal = smith_diagonal(relations.to_vec(), generators);
    let nonzero = diagonal.iter().filter(|&&d| d != 0).count();
    let mut torsion: Vec<u64> = diagonal
        .iter()
        .filter(|&&d| d > 1)
        .map(|&d| u64::try_from(d).unwrap_or(u64::MAX))
        .collect();
    torsion.sort_unstable();
    Homology {
        rank: generators - nonzero,
        torsion,
    }
}

/// The diagonal of the Smith normal form of an integer matrix (absolute values).
fn smith_diagonal(mut a: Vec<Vec<i128>>, columns: usize) -> Vec<i128> {
    let rows = a.len();
    let mut diagonal = Vec::new();
    for t in 0..rows.min(columns) {
        loop {
            // The smallest non-zero entry of the rest goes to (t, t).
            let mut pivot: Option<(usize, usize)> = None;
            for (i, row) in a.iter().enumerate().skip(t) {
                for (j, &x) in row.iter().enumerate().skip(t) {
                    if x != 0 && pivot.is_none_or(|(pi, pj)| x.abs() < a[pi][pj].abs()) {
                        pivot = Some((i, j));
                    }
                }
            }
            let Some((pi, pj)) = pivot else {
                return diagonal;
            };
            a.swap(t, pi);
            for row in &mut a {
                row.swap(t, pj);
            }
            let p = a[t][t];
            let mut clean = true;
            for i in t + 1..rows {
                let q = a[i][t] / p;
                if q != 0 {
                    let pivot_row = a[t].clone();
                    for (x, y) in a[i][t..columns].iter_mut().zip(&pivot_row[t..columns]) {
                        *x -= q * y;
                    }
                }
                clean &= a[i][t] == 0;
            }
            for j in t + 1..columns {
                let q = a[t][j] / p;
                if q != 0 {
                    for row in a.iter_mut() {
                        row[j] -= q * row[t];
                    }
                }
                clean &= a[t][j] == 0;
            }
            if !clean {
                continue;
            }
            // The pivot must divide the rest; if not, fold a row that it does not divide in.
            let bad = (t + 1..rows).find(|&i| (t + 1..columns).any(|j| a[i][j] % p != 0));
            match bad {
                Some(i) => {
                    let row = a[i].clone();
                    for (x, y) in a[t][t..columns].iter_mut().zip(&row[t..columns]) {
                        *x += y;
                    }
                }
                None => break,
            }
        }
        diagonal.push(a[t][t].abs());
    }
    diagonal
}

/// `H₁` of a space, from its cell's face pairings and edge cycles.
#[must_use]
pub fn first_homology(space: &Space) -> Homology {
    let faces = space.faces();
    // Generator of each face, and the sign of its pairing in it.
    let mut generator = vec![usize::MAX; faces.len()];
    let mut count = 0;
    for (i, f) in faces.iter().enumerate() {
        if f.partner >= i {
            generator[i] = count;
            generator[f.partner] = count;
            count += 1;
        }
    }
    let sign = |f: usize| if faces[f].partner >= f { 1 } else { -1 };
    let mut relations = Vec::new();
    for (i, f) in faces.iter().enumerate() {
        if f.partner == i {
            let mut r = vec![0; count];
            r[generator[i]] = 2;
            relations.push(r);
        }
    }
    // Several cells: crossings along a tree of the cells' gluings are no loops. Every seam
    // is one (the cells it joins lie side by side in the cover, so a path through seams
    // closes there too), then gluings that join cells not yet joined.
    if space.cells().len() > 1 {
        let mut parent: Vec<usize> = (0..space.cells().len()).collect();
        let seams = (0..faces.len()).filter(|&i| space.is_seam(i));
        let others = (0..faces.len()).filter(|&i| !space.is_seam(i));
        for i in seams.chain(others) {
            let (a, b) = (
                super::validate::union_find_root(&mut parent, faces[i].cell),
                super::validate::union_find_root(&mut parent, faces[faces[i].partner].cell),
            );
            if a != b || space.is_seam(i) {
                parent[a.max(b)] = a.min(b);
                let mut r = vec![0; count];
                r[generator[i]] = 1;
                relations.push(r);
            }
        }
    }
    for cycle in space.edge_cycles() {
        let mut r = vec![0i128; count];
        for &f in &cycle.crossings {
            r[generator[f]] += sign(f) * i128::from(cycle.order);
        }
        relations.push(r);
    }
    from_relations(&relations, count)
}
