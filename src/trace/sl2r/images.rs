//! The surface group's elements that bring a tube, a ball or a lamp's image near the cell,
//! each with what it adds to the lifted fibre angle in a fibre cover.

use crate::space::sl2r::UnitTangentSpace;

/// The 3×3 identity.
const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The sides' pairings in `f64`, rows.
fn pairings(space: &UnitTangentSpace) -> Vec<[[f64; 3]; 3]> {
    space
        .sides()
        .iter()
        .map(|s| s.pairing.map(|r| r.map(|x| x.hi)))
        .collect()
}

/// The product `a b` of 3×3 matrices of rows.
fn times(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum::<f64>()))
}

/// `m v` for a 3×3 matrix of rows.
pub(super) fn apply(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

/// The elements of the surface group that are words of up to four pairings, one for each
/// image of the base point `q` (enough for every polygon that shares a vertex with the
/// cell; the group is torsion-free, so distinct elements move `q` apart).
pub(super) fn group_elements(space: &UnitTangentSpace, q: [f64; 3]) -> Vec<[[f64; 3]; 3]> {
    group_elements_turning(space, q)
        .into_iter()
        .map(|(m, _)| m)
        .collect()
}

/// [`group_elements`] with what each adds to the lifted fibre angle of a point over `q`
/// (the sum of its pairings' turns along the word, [`UnitTangentSpace::side_turn`]; 0 in
/// `UT Σ`, whose sheet is always the first).
pub(super) fn group_elements_turning(
    space: &UnitTangentSpace,
    q: [f64; 3],
) -> Vec<([[f64; 3]; 3], f64)> {
    let covering = space.sheets() > 1;
    let pairings = pairings(space);
    let identity = IDENTITY;
    let mut seen = vec![(identity, q, 0.0)];
    let mut frontier = vec![(identity, q, 0.0)];
    for _ in 0..4 {
        let mut next = Vec::new();
        for &(g, at, turned) in &frontier {
            for (face, m) in pairings.iter().enumerate() {
                let element = times(m, &g);
                let image = apply(&element, q);
                let new = seen.iter().all(|(_, s, _)| {
                    (0..3).map(|i| (s[i] - image[i]).abs()).fold(0.0, f64::max) > 1e-9 * image[2]
                });
                if new {
                    let turn = if covering {
                        turned + space.side_turn(face, at)
                    } else {
                        0.0
                    };
                    seen.push((element, image, turn));
                    next.push((element, image, turn));
                }
            }
        }
        frontier = next;
    }
    seen.into_iter().map(|(m, _, turn)| (m, turn)).collect()
}

/// The elements `γ` of the surface group whose tile `γ·P` may hold a point within `radius`
/// of the polygon's centre, with what each adds to the lifted fibre angle of a point over
/// `q` (as [`group_elements_turning`]): a search over the tiles through their sides (right
/// multiplication by the pairings), keeping each tile whose centre is within
/// `radius + ρ` (`ρ` the circumradius): every tile that meets the disc, and the tiles that
/// meet it are joined through their sides.
pub(super) fn elements_within(
    space: &UnitTangentSpace,
    q: [f64; 3],
    radius: f64,
) -> Vec<([[f64; 3]; 3], f64)> {
    let covering = space.sheets() > 1;
    let pairings = pairings(space);
    // The turn of the word m_{w₀}·…·m_{wₖ₋₁} at q: each pairing's at the point the pairings
    // after it have moved q to.
    let word_turn = |word: &[usize]| {
        let mut at = q;
        let mut turn = 0.0;
        for &face in word.iter().rev() {
            turn += space.side_turn(face, at);
            at = apply(&pairings[face], at);
        }
        turn
    };
    let bound = (radius + space.circumradius()).cosh() * (1.0 + 1e-12);
    let identity = IDENTITY;
    let mut centres = vec![[0.0, 0.0, 1.0]];
    let mut out = vec![(identity, 0.0)];
    let mut frontier: Vec<([[f64; 3]; 3], Vec<usize>)> = vec![(identity, Vec::new())];
    while !frontier.is_empty() {
        let mut next = Vec::new();
        for (g, word) in &frontier {
            for (face, m) in pairings.iter().enumerate() {
                let element = times(g, m);
                let centre = [element[0][2], element[1][2], element[2][2]];
                let new = centre[2] <= bound
                    && centres.iter().all(|c: &[f64; 3]| {
                        (0..3).map(|i| (c[i] - centre[i]).abs()).fold(0.0, f64::max)
                            > 1e-9 * centre[2]
                    });
                if new {
                    centres.push(centre);
                    let mut word = word.clone();
                    word.push(face);
                    let turn = if covering { word_turn(&word) } else { 0.0 };
                    out.push((element, turn));
                    next.push((element, word));
                }
            }
        }
        frontier = next;
    }
    out
}
