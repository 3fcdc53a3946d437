//! Triangle meshes in the curved space and the bounding-volume hierarchy both tracers walk.
//!
//! A mesh lives in its own frame (an isometry placing it in the cell). Its triangles are
//! geodesic triangles, which are flat in the chart (`docs/design.md` §1), so they are stored as
//! chart triangles of the mesh's frame and a ray meets them exactly in all three geometries.
//!
//! **Scale rule.** A vertex at position `x` of the source model (glTF units) is put at the
//! point at geodesic distance `scale·|x|` from the frame's origin in the direction of `x`
//! (the exponential map of the frame): its chart point is `T(scale·|x|)·x/|x|` with `T` =
//! tan, identity or tanh. Distances from the origin are kept exactly; a triangle is the
//! geodesic triangle between its vertices. In E³ this is plain scaling.
//!
//! The hierarchy is built on the CPU with the surface-area heuristic over 12 bins per axis
//! and flattened depth first; the WGSL tracer traverses the same nodes and triangles from
//! a storage buffer.

use super::shading::SurfaceMaterial;
use super::texture::Texture;
use crate::geometry::Geometry;
use glam::{DVec2, DVec3};

/// Triangles per leaf at most.
pub const MAX_LEAF_TRIANGLES: usize = 4;
/// Depth of the traversal stack of both tracers: the builder keeps the tree within it.
pub const MAX_BVH_DEPTH: usize = 32;
/// Steps (nodes visited) after which a ray's walk of one mesh gives up, in both tracers:
/// far more than any ray of a sensible mesh needs, and a bound the WGSL loop needs (without
/// it llvmpipe miscompiled the walk).
pub const MAX_BVH_STEPS: usize = 4096;
/// The most triangles one mesh may have.
pub const MAX_MESH_TRIANGLES: usize = 1 << 22;

const BINS: usize = 12;

/// A mesh could not be made.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// The mesh has no triangles.
    #[error("the mesh has no triangles")]
    Empty,
    /// The mesh has more triangles than the limit (the count is attached).
    #[error("the mesh has {0} triangles; at most {MAX_MESH_TRIANGLES} are taken")]
    TooMany(usize),
    /// A vertex (its index is attached) is not a finite position.
    #[error("vertex {0} is not a finite position")]
    NotFinite(usize),
    /// Vertex `index` is `distance` from the mesh's origin after scaling.
    #[error(
        "vertex {index} is {distance:.3} from the mesh's origin after scaling; in S³ every vertex must be closer than {limit:.3} (a quarter of the way round the sphere)"
    )]
    TooFar {
        index: usize,
        distance: f64,
        limit: f64,
    },
    /// The scale must be a positive number (the value given is attached).
    #[error("the scale must be a positive number, got {0}")]
    Scale(f64),
}

/// One triangle in the mesh's chart: corners, shading normals (chart directions, for smooth
/// shading), texture coordinates and the index of its material in the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// Corners in the mesh's chart.
    pub corners: [DVec3; 3],
    /// Unit normals at the corners.
    pub normals: [DVec3; 3],
    /// Texture coordinates at the corners.
    pub uvs: [DVec2; 3],
    /// Index into the scene's materials.
    pub material: u32,
}

impl Triangle {
    fn bounds(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for c in self.corners {
            b.grow(c);
        }
        b
    }

    fn centroid(&self) -> DVec3 {
        (self.corners[0] + self.corners[1] + self.corners[2]) / 3.0
    }

    /// Möller–Trumbore: the chart parameter `t` of `o + t d` in `(0, t_max)` where the line
    /// meets the triangle, with the barycentric weights of corners 1 and 2.
    #[must_use]
    pub fn intersect(&self, o: DVec3, d: DVec3, t_max: f64) -> Option<(f64, f64, f64)> {
        let [a, b, c] = self.corners;
        let e1 = b - a;
        let e2 = c - a;
        let pv = d.cross(e2);
        let det = e1.dot(pv);
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let inv = 1.0 / det;
        let tv = o - a;
        let u = tv.dot(pv) * inv;
        if !(0.0..=1.0).contains(&u) {
            return None;
        }
        let qv = tv.cross(e1);
        let v = d.dot(qv) * inv;
        if v < 0.0 || u + v > 1.0 {
            return None;
        }
        let t = e2.dot(qv) * inv;
        (t > 0.0 && t < t_max).then_some((t, u, v))
    }
}

/// An axis-aligned box of the chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The lowest corner.
    pub min: DVec3,
    /// The highest corner.
    pub max: DVec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    fn grow(&mut self, p: DVec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    fn merge(&mut self, b: &Aabb) {
        self.min = self.min.min(b.min);
        self.max = self.max.max(b.max);
    }

    fn area(&self) -> f64 {
        let e = (self.max - self.min).max(DVec3::ZERO);
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// The slab test: the entry parameter of `o + t d` if the line meets the box within
    /// `(0, t_max)`. `inv_d` is `1/d` per component.
    #[must_use]
    pub fn entry(&self, o: DVec3, inv_d: DVec3, t_max: f64) -> Option<f64> {
        let t0 = (self.min - o) * inv_d;
        let t1 = (self.max - o) * inv_d;
        let near = t0.min(t1).max_element().max(0.0);
        let far = t0.max(t1).min_element().min(t_max);
        (near <= far).then_some(near)
    }
}

/// A node of the flattened hierarchy: a leaf holds `count > 0` triangles from `index`; an
/// inner node (`count == 0`) has its first child right after it and its second at `index`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BvhNode {
    /// The box around the node's triangles.
    pub bounds: Aabb,
    /// First triangle (a leaf) or first child node (an inner node).
    pub index: u32,
    /// Triangles in a leaf; 0 for an inner node.
    pub count: u32,
}

/// A mesh ready to trace: triangles in hierarchy order and the hierarchy's nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// The triangles, in hierarchy order.
    pub triangles: Vec<Triangle>,
    /// The hierarchy, root first.
    pub nodes: Vec<BvhNode>,
    /// The largest geodesic distance of a vertex from the mesh's origin.
    pub radius: f64,
}

/// A mesh's hit: the triangle, the chart parameter and the barycentric weights of its
/// corners 1 and 2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshHit {
    /// Index of the triangle hit.
    pub triangle: usize,
    /// Chart ratio along the ray.
    pub t: f64,
    /// Barycentric coordinate of the second corner.
    pub u: f64,
    /// Barycentric coordinate of the third corner.
    pub v: f64,
}

/// A model's triangles before placing: positions and normals in model units, texture
/// coordinates, a material index per triangle.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshSource {
    /// Vertex positions in the model's frame.
    pub positions: Vec<DVec3>,
    /// Vertex normals, if the model has them.
    pub normals: Option<Vec<DVec3>>,
    /// Texture coordinates, if the model has them.
    pub uvs: Option<Vec<DVec2>>,
    /// Three vertex indices per triangle.
    pub indices: Vec<[u32; 3]>,
    /// One material per triangle (indices into the scene's materials).
    pub materials: Vec<u32>,
}

/// A model's triangles with its materials and textures (indices local to the model).
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// Its triangles.
    pub source: MeshSource,
    /// Its materials (indices local to the model).
    pub materials: Vec<SurfaceMaterial>,
    /// Its textures (indices local to the model).
    pub textures: Vec<Texture>,
}

impl MeshSource {
    /// Appends another source (its indices shifted past this one's vertices); normals or
    /// texture coordinates missing on one side are filled with zeros (a zero normal means
    /// the triangle's own).
    pub fn append(&mut self, other: MeshSource) {
        let offset = self.positions.len() as u32;
        let (n0, n1) = (self.positions.len(), other.positions.len());
        if self.normals.is_some() || other.normals.is_some() {
            let mut n = self.normals.take().unwrap_or_else(|| vec![DVec3::ZERO; n0]);
            n.extend(other.normals.unwrap_or_else(|| vec![DVec3::ZERO; n1]));
            self.normals = Some(n);
        }
        if self.uvs.is_some() || other.uvs.is_some() {
            let mut u = self.uvs.take().unwrap_or_else(|| vec![DVec2::ZERO; n0]);
            u.extend(other.uvs.unwrap_or_else(|| vec![DVec2::ZERO; n1]));
            self.uvs = Some(u);
        }
        self.positions.extend(other.positions);
        self.indices
            .extend(other.indices.iter().map(|t| t.map(|i| i + offset)));
        self.materials.extend(other.materials);
    }

    /// The distance of the farthest vertex from the model's origin (0 for none).
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.positions
            .iter()
            .map(|p| p.length())
            .fold(0.0, f64::max)
    }

    /// The mesh placed by the scale rule (module docs) in a geometry.
    pub fn place(&self, geometry: Geometry, scale: f64) -> Result<Mesh, MeshError> {
        if !(scale > 0.0 && scale.is_finite()) {
            return Err(MeshError::Scale(scale));
        }
        let limit = std::f64::consts::FRAC_PI_2 * 0.999;
        let mut radius: f64 = 0.0;
        let mut chart = Vec::with_capacity(self.positions.len());
        for (i, x) in self.positions.iter().enumerate() {
            if !x.is_finite() {
                return Err(MeshError::NotFinite(i));
            }
            let d = scale * x.length();
            if geometry == Geometry::Spherical && d >= limit {
                return Err(MeshError::TooFar {
                    index: i,
                    distance: d,
                    limit,
                });
            }
            radius = radius.max(d);
            let ratio = match geometry {
                Geometry::Spherical => d.tan(),
                Geometry::Euclidean => d,
                Geometry::Hyperbolic => d.tanh(),
            };
            chart.push(if d > 0.0 {
                *x * (ratio / x.length())
            } else {
                DVec3::ZERO
            });
        }
        let triangles = self
            .indices
            .iter()
            .zip(&self.materials)
            .map(|(t, &material)| {
                let idx = t.map(|i| i as usize);
                let corners = idx.map(|i| chart[i]);
                let flat = (corners[1] - corners[0])
                    .cross(corners[2] - corners[0])
                    .normalize_or_zero();
                let normals = match &self.normals {
                    Some(n) => idx.map(|i| {
                        let m = n[i].normalize_or_zero();
                        if m == DVec3::ZERO { flat } else { m }
                    }),
                    None => [flat; 3],
                };
                let uvs = match &self.uvs {
                    Some(u) => idx.map(|i| u[i]),
                    None => [DVec2::ZERO; 3],
                };
                Triangle {
                    corners,
                    normals,
                    uvs,
                    material,
                }
            })
            .collect();
        let mut mesh = Mesh::new(triangles)?;
        mesh.radius = radius;
        Ok(mesh)
    }
}

impl Mesh {
    /// Builds the hierarchy over chart triangles (reordered into leaf order). Degenerate
    /// triangles (zero area) are dropped: no ray can hit them.
    pub fn new(triangles: Vec<Triangle>) -> Result<Self, MeshError> {
        if triangles.len() > MAX_MESH_TRIANGLES {
            return Err(MeshError::TooMany(triangles.len()));
        }
        let mut triangles: Vec<Triangle> = triangles
            .into_iter()
            .filter(|t| {
                let [a, b, c] = t.corners;
                (b - a).cross(c - a).length_squared() > 0.0
                    && a.is_finite()
                    && b.is_finite()
                    && c.is_finite()
            })
            .collect();
        if triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        let radius = triangles
            .iter()
            .flat_map(|t| t.corners)
            .map(DVec3::length)
            .fold(0.0, f64::max);
        let mut nodes = Vec::with_capacity(2 * triangles.len() / MAX_LEAF_TRIANGLES + 1);
        let n = triangles.len();
        build(&mut triangles, 0, n, 0, &mut nodes);
        Ok(Self {
            triangles,
            nodes,
            radius,
        })
    }

    /// The first hit of the chart line `o + t d` with `0 < t < t_max`, walking the hierarchy
    /// nearest child first (the WGSL `hit_mesh` walks it the same way).
    #[must_use]
    pub fn intersect(&self, o: DVec3, d: DVec3, t_max: f64) -> Option<MeshHit> {
        let inv_d = d.recip();
        let mut best: Option<MeshHit> = None;
        let mut t_best = t_max;
        let mut stack = [0u32; MAX_BVH_DEPTH];
        let mut top = 0;
        let mut node = 0u32;
        for _ in 0..MAX_BVH_STEPS {
            let n = &self.nodes[node as usize];
            if n.count > 0 {
                for i in n.index..n.index + n.count {
                    if let Some((t, u, v)) = self.triangles[i as usize].intersect(o, d, t_best) {
                        t_best = t;
                        best = Some(MeshHit {
                            triangle: i as usize,
                            t,
                            u,
                            v,
                        });
                    }
                }
            } else {
                let (a, b) = (node + 1, n.index);
                let ta = self.nodes[a as usize].bounds.entry(o, inv_d, t_best);
                let tb = self.nodes[b as usize].bounds.entry(o, inv_d, t_best);
                match (ta, tb) {
                    (Some(x), Some(y)) => {
                        let (near, far) = if x <= y { (a, b) } else { (b, a) };
                        stack[top] = far;
                        top += 1;
                        node = near;
                        continue;
                    }
                    (Some(_), None) => {
                        node = a;
                        continue;
                    }
                    (None, Some(_)) => {
                        node = b;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Next subtree from the stack, skipping any now farther than the best hit.
            loop {
                if top == 0 {
                    return best;
                }
                top -= 1;
                let candidate = stack[top];
                if self.nodes[candidate as usize]
                    .bounds
                    .entry(o, inv_d, t_best)
                    .is_some()
                {
                    node = candidate;
                    break;
                }
            }
        }
        best
    }

    /// Every triangle tested: the reference for the hierarchy.
    #[must_use]
    pub fn intersect_brute_force(&self, o: DVec3, d: DVec3, t_max: f64) -> Option<MeshHit> {
        let mut best: Option<MeshHit> = None;
        let mut t_best = t_max;
        for (i, tri) in self.triangles.iter().enumerate() {
            if let Some((t, u, v)) = tri.intersect(o, d, t_best) {
                t_best = t;
                best = Some(MeshHit {
                    triangle: i,
                    t,
                    u,
                    v,
                });
            }
        }
        best
    }

    /// The depth of the hierarchy (1 for a single leaf).
    #[must_use]
    pub fn depth(&self) -> usize {
        fn walk(nodes: &[BvhNode], i: usize) -> usize {
            let n = &nodes[i];
            if n.count > 0 {
                1
            } else {
                1 + walk(nodes, i + 1).max(walk(nodes, n.index as usize))
            }
        }
        walk(&self.nodes, 0)
    }
}

/// Builds the subtree of `triangles[start..end]` at `depth`, pushing its nodes.
fn build(
    triangles: &mut [Triangle],
    start: usize,
    end: usize,
    depth: usize,
    nodes: &mut Vec<BvhNode>,
) {
    let mut bounds = Aabb::EMPTY;
    let mut centroids = Aabb::EMPTY;
    for t in &triangles[start..end] {
        bounds.merge(&t.bounds());
        centroids.grow(t.centroid());
    }
    let at = nodes.len();
    nodes.push(BvhNode {
        bounds,
        index: start as u32,
        count: (end - start) as u32,
    });
    let count = end - start;
    // The stack holds one entry per level below the root: keep the depth within it.
    if count <= MAX_LEAF_TRIANGLES || depth + 2 >= MAX_BVH_DEPTH {
        return;
    }
    let mid = split(&mut triangles[start..end], &bounds, &centroids).map(|m| start + m);
    let Some(mid) = mid else {
        return;
    };
    nodes[at].count = 0;
    build(triangles, start, mid, depth + 1, nodes);
    nodes[at].index = nodes.len() as u32;
    build(triangles, mid, end, depth + 1, nodes);
}

/// The binned-SAH split of `triangles` (reordered): the size of the first part, or `None`
/// when a leaf is cheaper (for more than twice the leaf size, the median split instead).
fn split(triangles: &mut [Triangle], bounds: &Aabb, centroids: &Aabb) -> Option<usize> {
    let n = triangles.len();
    let extent = centroids.max - centroids.min;
    let mut best: Option<(f64, usize, f64)> = None;
    for axis in 0..3 {
        if !(extent[axis] > 0.0) {
            continue;
        }
        let bin_of = |t: &Triangle| {
            let f = (t.centroid()[axis] - centroids.min[axis]) / extent[axis];
            ((f * BINS as f64) as usize).min(BINS - 1)
        };
        let mut bins = [(Aabb::EMPTY, 0usize); BINS];
        for t in triangles.iter() {
            let b = &mut bins[bin_of(t)];
            b.0.merge(&t.bounds());
            b.1 += 1;
        }
        // Sweep from the right, then from the left.
        let mut right = [(0.0, 0usize); BINS];
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for i in (1..BINS).rev() {
            acc.merge(&bins[i].0);
            cnt += bins[i].1;
            right[i] = (acc.area(), cnt);
        }
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for i in 0..BINS - 1 {
            acc.merge(&bins[i].0);
            cnt += bins[i].1;
            let (ra, rc) = right[i + 1];
            if cnt == 0 || rc == 0 {
                continue;
            }
            let cost = acc.area() * cnt as f64 + ra * rc as f64;
            if best.is_none_or(|b| cost < b.0) {
                let plane = centroids.min[axis] + extent[axis] * (i + 1) as f64 / BINS as f64;
                best = Some((cost, axis, plane));
            }
        }
    }
    let leaf_cost = bounds.area() * n as f64;
    match best {
        Some((cost, axis, plane)) if cost < leaf_cost || n > 2 * MAX_LEAF_TRIANGLES => {
            let mid = partition(triangles, |t| t.centroid()[axis] < plane);
            (mid > 0 && mid < n)
                .then_some(mid)
                .or_else(|| median(triangles))
        }
        None if n > 2 * MAX_LEAF_TRIANGLES => median(triangles),
        _ => None,
    }
}

/// Splits at the median centroid along the longest axis (all centroids may coincide).
fn median(triangles: &mut [Triangle]) -> Option<usize> {
    let n = triangles.len();
    if n < 2 {
        return None;
    }
    let mut b = Aabb::EMPTY;
    for t in triangles.iter() {
        b.grow(t.centroid());
    }
    let e = b.max - b.min;
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    triangles.sort_by(|a, b| a.centroid()[axis].total_cmp(&b.centroid()[axis]));
    Some(n / 2)
}

fn partition(triangles: &mut [Triangle], left: impl Fn(&Triangle) -> bool) -> usize {
    let mut i = 0;
    for j in 0..triangles.len() {
        if left(&triangles[j]) {
            triangles.swap(i, j);
            i += 1;
        }
    }
    i
}

/// A box mesh of half-size `h` centred on the origin, 12 triangles with flat normals and
/// per-face texture coordinates, all of `material`.
#[must_use]
pub fn cube_source(h: f64, material: u32) -> MeshSource {
    let mut s = MeshSource::default();
    let (mut normals, mut uvs) = (Vec::new(), Vec::new());
    for axis in 0..3 {
        for sign in [-1.0, 1.0] {
            let n = DVec3::from_array({
                let mut a = [0.0; 3];
                a[axis] = sign;
                a
            });
            let u = DVec3::from_array({
                let mut a = [0.0; 3];
                a[(axis + 1) % 3] = 1.0;
                a
            });
            let v = n.cross(u);
            let base = s.positions.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                s.positions.push((n + a * u + b * v) * h);
                normals.push(n);
                uvs.push(DVec2::new(0.5 + 0.5 * a, 0.5 - 0.5 * b));
            }
            s.indices.push([base, base + 1, base + 2]);
            s.indices.push([base, base + 2, base + 3]);
            s.materials.extend([material; 2]);
        }
    }
    s.normals = Some(normals);
    s.uvs = Some(uvs);
    s
}
