// The model of the three geometries: the form, projections, S(t), distances.
// The Rust twin: `geometry`.
#define_import_path curved_spaces::geometry

#import curved_spaces::layout::{F32_EPSILON, kappa}

// ---------------------------------------------------------------------------------------
// Geometry (src/geometry/mod.rs)

fn form(a: vec4<f32>, b: vec4<f32>) -> f32 {
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        return dot(a.xyz, b.xyz);
    }
#endif
#ifdef CURVED
    if kappa() != 0.0 {
        return dot(a.xyz, b.xyz) + kappa() * a.w * b.w;
    }
#endif
    return 0.0;
}

// Back onto the model along the ray through the origin of R⁴ (the chart point is kept).
fn project_point(p: vec4<f32>) -> vec4<f32> {
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        return p / p.w;
    }
#endif
#ifdef SPHERICAL
    if kappa() > 0.0 {
        return p * (select(1.0, -1.0, p.w < 0.0) / length(p));
    }
#endif
#ifdef HYPERBOLIC
    if kappa() < 0.0 {
        let s = select(1.0, -1.0, p.w < 0.0);
        let q = -form(p, p);
        if q > 16.0 * F32_EPSILON * p.w * p.w {
            return p * (s / sqrt(q));
        }
        // Rounding pushed the point onto or past the sphere at infinity: pull its chart point
        // inside, keeping its direction from the origin.
        let w = abs(p.w);
        let f = sqrt(1.0 - 8.0 * F32_EPSILON) * w / length(p.xyz);
        let x = vec4<f32>(p.xyz * f, w);
        return x / sqrt(-form(x, x));
    }
#endif
    return p;
}

fn project_tangent(p: vec4<f32>, v: vec4<f32>) -> vec4<f32> {
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        return v - p * (v.w / p.w);
    }
#endif
#ifdef CURVED
    if kappa() != 0.0 {
        return v - p * (form(p, v) / form(p, p));
    }
#endif
    return v;
}

fn unit_tangent(p: vec4<f32>, v: vec4<f32>) -> vec4<f32> {
    let t = project_tangent(p, v);
    return t * inverseSqrt(form(t, t));
}

// S(t): sin t, t or sinh t.
fn s_of(t: f32) -> f32 {
#ifdef SPHERICAL
    if kappa() > 0.0 {
        return sin(t);
    }
#endif
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        return t;
    }
#endif
#ifdef HYPERBOLIC
    if kappa() < 0.0 {
        return sinh(t);
    }
#endif
    return 0.0;
}

// Length of the segment from p to p + T v with T = num/den: atan T, T, atanh T.
fn distance_from_ratio(num: f32, den: f32) -> f32 {
#ifdef SPHERICAL
    if kappa() > 0.0 {
        return atan2(num, den);
    }
#endif
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        return num / den;
    }
#endif
#ifdef HYPERBOLIC
    if kappa() < 0.0 {
        return 0.5 * log((den + num) / max(den - num, F32_EPSILON * den));
    }
#endif
    return 0.0;
}

// Geodesic distance in forms that stay accurate for near and far points.
fn distance(p: vec4<f32>, q: vec4<f32>) -> f32 {
#ifdef SPHERICAL
    if kappa() > 0.0 {
        return 2.0 * atan2(length(p - q), length(p + q));
    }
#endif
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        return length(p.xyz / p.w - q.xyz / q.w);
    }
#endif
#ifdef HYPERBOLIC
    if kappa() < 0.0 {
        let d = p - q;
        return 2.0 * asinh(sqrt(max(form(d, d), 0.0)) * 0.5);
    }
#endif
    return 0.0;
}

fn tangent_towards(p: vec4<f32>, q: vec4<f32>) -> vec4<f32> {
    let d = project_tangent(p, q - p);
    return d * inverseSqrt(form(d, d));
}
