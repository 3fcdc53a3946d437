//! Accuracy: the GPU picture against the f64 reference, the f32 drift of long rays against
//! its conditioning bound, and the fog cut-off's error against its bound.

use super::*;
use crate::geometry::{Geometry, Vector4};
use crate::plugin::render::gpu::{GpuScene, gpu_object_indices};
use crate::scene::CurvedScene;
use crate::space::{CellWalker, Limit};
use crate::trace::{RayEnd, ShadowWalk, colour_of, first_hit_traced, sample_rays, to_byte};
use crate::view::ViewKind;
use glam::{DVec4, Vec4};
use rayon::prelude::*;

/// Per pixel: what the ray met (`[object + 1, crossings, path, end]`) and its 8-bit colour.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Reference {
    pub(super) ids: Vec<[u32; 4]>,
    pub(super) rgb: Vec<[u8; 3]>,
    /// Rays that used up the budget.
    pub(super) exhausted: usize,
}

/// How one picture differs from another.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Difference {
    pub(super) hit_differs: f64,
    pub(super) mean_levels: f64,
    pub(super) max_levels: u32,
    pub(super) over_2_levels: f64,
    pub(super) over_10_levels: f64,
}

impl Reference {
    /// The f64 reference picture with what each ray met; with `round_start`, each camera ray
    /// is first rounded to f32 (then traced in f64).
    pub(super) fn trace(
        subject: &Subject,
        scene: &CurvedScene,
        (w, h): (u32, u32),
        budget: usize,
        round_start: bool,
    ) -> Self {
        let walker = CellWalker::<DVec4>::new(&subject.space);
        let index = gpu_object_indices(scene);
        let g = subject.space.geometry;
        let layout = subject.camera.layout(w, h);
        let pixels: Vec<([u32; 4], [u8; 3], bool)> = (0..w * h)
            .into_par_iter()
            .map(|k| {
                let mut ray = layout.ray_at(g, k % w, k / w);
                if round_start {
                    ray.point = Vec4::from_f64(ray.point).to_f64();
                    ray.tangent = Vec4::from_f64(ray.tangent).to_f64();
                }
                let traced = first_hit_traced(&walker, scene, ray, budget);
                let walk = ShadowWalk::new(&walker, None, budget);
                let colour = colour_of(walk, scene, &traced.end).to_array().map(to_byte);
                let exhausted = matches!(traced.end, RayEnd::Budget(c) if c == budget);
                (traced.id(|o| index[o]), colour, exhausted)
            })
            .collect();
        Self {
            ids: pixels.iter().map(|p| p.0).collect(),
            rgb: pixels.iter().map(|p| p.1).collect(),
            exhausted: pixels.iter().filter(|p| p.2).count(),
        }
    }

    pub(super) fn compare(&self, reference: &Reference) -> Difference {
        // A hit is the object and the faces crossed to it; fog and budget both show fog.
        let key = |id: &[u32; 4]| if id[3] == 1 { (id[0], id[2]) } else { (0, 0) };
        let n = self.ids.len().max(1) as f64;
        let hit_differs = self
            .ids
            .iter()
            .zip(&reference.ids)
            .filter(|(a, b)| key(a) != key(b))
            .count() as f64
            / n;
        let levels: Vec<u32> = self
            .rgb
            .iter()
            .zip(&reference.rgb)
            .map(|(a, b)| {
                (0..3)
                    .map(|c| u32::from(a[c].abs_diff(b[c])))
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        Difference {
            hit_differs,
            mean_levels: levels.iter().map(|&l| f64::from(l)).sum::<f64>() / n,
            max_levels: levels.iter().copied().max().unwrap_or(0),
            over_2_levels: levels.iter().filter(|&&l| l > 2).count() as f64 / n,
            over_10_levels: levels.iter().filter(|&&l| l > 10).count() as f64 / n,
        }
    }
}

/// The GPU's picture and hit ids of a setting.
pub(super) fn gpu_pixels(
    harness: &mut Harness,
    subject: &Subject,
    gpu: &GpuScene,
    budget: u32,
    size: (u32, u32),
) -> Result<Reference, BenchError> {
    let words = uniform_words(&subject.camera.layout(size.0, size.1), gpu);
    let colour = harness.frame(size.0, size.1, Output::Colour, &words, Some(gpu));
    harness.draw(
        &Program::Tracer(gpu.key, ViewKind::Mono, Output::Colour),
        &colour,
    )?;
    let rgba = harness.read_pixels(&colour)?;
    let ids_frame = harness.frame(size.0, size.1, Output::HitId, &words, Some(gpu));
    harness.draw(
        &Program::Tracer(gpu.key, ViewKind::Mono, Output::HitId),
        &ids_frame,
    )?;
    let id_bytes = harness.read_pixels(&ids_frame)?;
    let ids: Vec<[u32; 4]> = bytemuck::cast_slice::<u8, u32>(&id_bytes)
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect();
    Ok(Reference {
        exhausted: ids
            .iter()
            .filter(|id| id[3] == 3 && id[1] == budget)
            .count(),
        ids,
        rgb: rgba.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect(),
    })
}

/// The conditioning factor `G(d)` of docs/design.md §3.
#[must_use]
pub fn growth(geometry: Geometry, d: f64) -> f64 {
    match geometry {
        Geometry::Spherical => 1.0,
        Geometry::Euclidean => 1.0 + d,
        Geometry::Hyperbolic => d.exp(),
    }
}

pub(super) fn median(mut v: Vec<f64>) -> Option<f64> {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied()
}

/// f32 against f64 along `drift_rays` random rays, at each of `drift_crossings`.
pub(super) fn drift(subject: &Subject, config: &BenchConfig) -> Vec<DriftRow> {
    let space = &subject.space;
    let g = space.geometry;
    let Some(&most) = config.drift_crossings.iter().max() else {
        return Vec::new();
    };
    let w64 = CellWalker::<DVec4>::new(space);
    let w32 = CellWalker::<Vec4>::new(space);
    let rays = sample_rays(space, config.drift_rays, 0xd71f7);
    let traces: Vec<_> = rays
        .par_iter()
        .map(|ray| {
            let exact = w64.trace(*ray, Limit::Crossings(most));
            let single = w32.trace(
                crate::geometry::Ray {
                    point: Vec4::from_f64(ray.point),
                    tangent: Vec4::from_f64(ray.tangent),
                },
                Limit::Crossings(most),
            );
            (exact, single)
        })
        .collect();
    config
        .drift_crossings
        .iter()
        .map(|&n| {
            let mut agree = 0;
            let (mut positions, mut directions, mut distances) = (vec![], vec![], vec![]);
            let mut ratios: Vec<f64> = Vec::new();
            for (exact, single) in &traces {
                let (Some(a), Some(b)) = (exact.crossings.get(n - 1), single.crossings.get(n - 1))
                else {
                    continue;
                };
                distances.push(a.distance);
                let same = exact.crossings[..n]
                    .iter()
                    .zip(&single.crossings[..n])
                    .all(|(x, y)| x.face == y.face);
                if !same {
                    continue;
                }
                agree += 1;
                let p32 = g.project_point(b.ray.point.to_f64());
                let error = g.distance(a.ray.point, p32);
                positions.push(error);
                ratios.push(
                    error / (DRIFT_BOUND_FACTOR * F32_EPSILON * n as f64 * growth(g, a.distance)),
                );
                let v32 = g.unit_tangent(a.ray.point, b.ray.tangent.to_f64());
                let d = v32 - a.ray.tangent;
                let chord = g.form(d, d).max(0.0).sqrt();
                directions.push(2.0 * (0.5 * chord).min(1.0).asin());
            }
            let d = median(distances).unwrap_or(0.0);
            DriftRow {
                space: subject.id.clone(),
                geometry: subject.geometry(),
                crossings: n,
                rays: traces.len(),
                same_faces: agree as f64 / traces.len().max(1) as f64,
                median_distance: d,
                max_position_error: positions.iter().copied().reduce(f64::max),
                median_position_error: median(positions),
                median_direction_error: median(directions),
                bound: Some(DRIFT_BOUND_FACTOR * F32_EPSILON * n as f64 * growth(g, d))
                    .filter(|b| b.is_finite()),
                worst_bound_ratio: ratios.into_iter().reduce(f64::max),
            }
        })
        .collect()
}

/// Width of the distance bins of the digits-lost curve.
const CURVE_BIN: f64 = 2.0;

/// Walks of [`BenchConfig::conditioning_rays`] rays of 100 crossings in f64 and f32, with the
/// pairing compensated and plain, against the double-double reference: the statistics over
/// crossings 1–30 and 1–100, and the digits lost beyond conditioning against distance.
pub(super) fn conditioning(
    subject: &Subject,
    config: &BenchConfig,
) -> (Vec<ConditioningRow>, Vec<ConditioningPoint>) {
    use crate::space::accuracy::{CrossingAccuracy, ReferenceWalk, SATURATED, summarize};
    const CROSSINGS: usize = 100;
    let space = &subject.space;
    let rays = sample_rays(space, config.conditioning_rays, 0xc0d1);
    let walkers = |compensated| {
        let mut w64 = CellWalker::<DVec4>::new(space);
        let mut w32 = CellWalker::<Vec4>::new(space);
        w64.compensated = compensated;
        w32.compensated = compensated;
        (w64, w32)
    };
    let variants = [("compensated", walkers(true)), ("plain", walkers(false))];
    // Per ray: for each (precision, pairing) the accuracy at every crossing.
    let per_ray: Vec<Vec<(&str, &str, Vec<CrossingAccuracy>)>> = rays
        .par_iter()
        .map(|ray| {
            let reference = ReferenceWalk::new(space, *ray, CROSSINGS);
            let limits64 = reference.conditioning(f64::EPSILON);
            let limits32 = reference.conditioning(F32_EPSILON);
            variants
                .iter()
                .flat_map(|(pairing, (w64, w32))| {
                    [
                        ("f64", *pairing, reference.accuracy_of(w64, &limits64)),
                        ("f32", *pairing, reference.accuracy_of(w32, &limits32)),
                    ]
                })
                .collect()
        })
        .collect();
    let mut rows = Vec::new();
    let mut curve = Vec::new();
    for precision in ["f64", "f32"] {
        for (pairing, _) in &variants {
            let all: Vec<&CrossingAccuracy> = per_ray
                .iter()
                .flatten()
                .filter(|(p, q, _)| *p == precision && q == pairing)
                .flat_map(|(_, _, rows)| rows)
                .collect();
            for n in [30, CROSSINGS] {
                let Some(s) = summarize(all.iter().copied().filter(|c| c.crossing <= n)) else {
                    continue;
                };
                rows.push(ConditioningRow {
                    space: subject.id.clone(),
                    geometry: subject.geometry(),
                    precision: precision.into(),
                    pairing: pairing.to_string(),
                    crossings: n,
                    median: s.median,
                    worst: s.worst,
                    counted: s.counted,
                    left_out: s.left_out,
                });
            }
            let mut bins: Vec<(usize, Vec<f64>)> = Vec::new();
            for c in &all {
                let Some(r) = c.ratio().filter(|_| c.conditioning <= SATURATED) else {
                    continue;
                };
                let bin = (c.distance / CURVE_BIN) as usize;
                match bins.iter_mut().find(|(b, _)| *b == bin) {
                    Some((_, v)) => v.push(r.max(1e-6).log10()),
                    None => bins.push((bin, vec![r.max(1e-6).log10()])),
                }
            }
            bins.sort_by_key(|(b, _)| *b);
            for (bin, digits) in bins {
                let count = digits.len();
                curve.push(ConditioningPoint {
                    space: subject.id.clone(),
                    precision: precision.into(),
                    pairing: pairing.to_string(),
                    distance: (bin as f64 + 0.5) * CURVE_BIN,
                    median_digits: median(digits).unwrap_or(0.0),
                    count,
                });
            }
        }
    }
    (rows, curve)
}

/// The error of the fog cut-off: the f64 picture with it against one traced without it.
pub(super) fn cutoff(subject: &Subject, fog_factor: f64, (w, h): (u32, u32)) -> CutoffRow {
    let scene = subject.scene(fog_factor);
    let mut uncut = scene.clone();
    // A weight of 1e-15 puts the cut-off ~34.5 λ away: nothing is cut off that f64 can see.
    uncut.shading.cutoff_weight = 1e-15;
    let walker = CellWalker::<DVec4>::new(&subject.space);
    let g = subject.space.geometry;
    let layout = subject.camera.layout(w, h);
    let errors: Vec<(f64, bool)> = (0..w * h)
        .into_par_iter()
        .map(|k| {
            let ray = layout.ray_at(g, k % w, k / w);
            let cut = first_hit_traced(&walker, &scene, ray, EXACT_BUDGET).end;
            let full = first_hit_traced(&walker, &uncut, ray, EXACT_BUDGET).end;
            let walk = ShadowWalk::new(&walker, None, EXACT_BUDGET);
            let error = (colour_of(walk, &scene, &cut) - colour_of(walk, &uncut, &full))
                .abs()
                .max_element();
            (error, matches!(full, RayEnd::Budget(_)))
        })
        .collect();
    let n = errors.len().max(1) as f64;
    let max_error = errors.iter().map(|e| e.0).fold(0.0, f64::max);
    let bound = scene.shading.cutoff_weight;
    CutoffRow {
        space: subject.id.clone(),
        geometry: subject.geometry(),
        fog_factor,
        fog_distance: scene.shading.fog_distance,
        cutoff_distance: scene.shading.cutoff_distance(),
        bound,
        max_error,
        mean_error: errors.iter().map(|e| e.0).sum::<f64>() / n,
        within_bound: max_error <= bound,
        reference_budget_exhausted: errors.iter().filter(|e| e.1).count() as f64 / n,
    }
}
