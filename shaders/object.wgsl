// Balls, discs and tubes met by a segment, exactly, and the surface at a hit.
// The Rust twin: `scene::object`.
#define_import_path curved_spaces::object

#import curved_spaces::layout::{Disc, Tube, kappa}
#import curved_spaces::geometry::{distance, form, project_point}

// ---------------------------------------------------------------------------------------
// Objects (src/trace/scene.rs)

const NO_HIT: f32 = 3.4e38;

// The roots of a s² + b s + c = 0 in increasing order, without cancellation;
// (NO_HIT, NO_HIT) when there are none.
fn roots(a: f32, b: f32, c: f32) -> vec2<f32> {
    let disc = b * b - 4.0 * a * c;
    if !(disc >= 0.0) {
        return vec2<f32>(NO_HIT, NO_HIT);
    }
    let q = -0.5 * (b + select(-1.0, 1.0, b >= 0.0) * sqrt(disc));
    let r1 = q / a;
    let r2 = c / q;
    return vec2<f32>(min(r1, r2), max(r1, r2));
}

fn in_range(s: f32, hi: f32) -> bool {
    return s > 0.0 && s < hi && abs(s) < NO_HIT;
}

// The first s in (0, hi) where the ray enters the ball of centre c and size C(ρ) (ρ in
// E³), or NO_HIT.
fn hit_ball_at(c: vec4<f32>, size: f32, p: vec4<f32>, v: vec4<f32>, hi: f32) -> f32 {
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        let d = p.xyz - c.xyz;
        let r = size;
        let t = roots(dot(v.xyz, v.xyz), 2.0 * dot(d, v.xyz), dot(d, d) - r * r);
        if in_range(t.x, hi) { return t.x; }
        if in_range(t.y, hi) { return t.y; }
        return NO_HIT;
    }
#endif
#ifdef CURVED
    if kappa() != 0.0 {
        // (⟨p,c⟩ + s⟨v,c⟩)² = C(ρ)² (1 + κ s²), on the sheet where ⟨X,c⟩ has the sign of κ C(ρ).
        let a = form(p, c);
        let b = form(v, c);
        let cr = size;
        let sheet = kappa() * cr;
        let t = roots(b * b - kappa() * cr * cr, 2.0 * a * b, a * a - cr * cr);
        if in_range(t.x, hi) && (a + t.x * b) * sheet > 0.0 { return t.x; }
        if in_range(t.y, hi) && (a + t.y * b) * sheet > 0.0 { return t.y; }
        return NO_HIT;
    }
#endif
    return NO_HIT;
}

#ifdef DISCS
// Where the ray meets the disc's plane within its radius, or NO_HIT.
fn hit_disc(disc: Disc, p: vec4<f32>, v: vec4<f32>, hi: f32) -> f32 {
    let s = -dot(disc.covector, p) / dot(disc.covector, v);
    if !(s > 0.0 && s < hi) {
        return NO_HIT;
    }
    let x = project_point(p + s * v);
    if !(distance(x, disc.centre) <= disc.colour.w) {
        return NO_HIT;
    }
    return s;
}
#endif

#ifdef TUBES
// (σ, γ) with σ/γ = S(τ)/C(τ) for the foot of x at distance τ from a along the axis.
fn tube_foot_coordinates(tube: Tube, x: vec4<f32>) -> vec2<f32> {
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        return vec2<f32>(dot(x.xyz / x.w - tube.a.xyz, tube.towards_b.xyz), 1.0);
    }
#endif
#ifdef CURVED
    if kappa() != 0.0 {
        return vec2<f32>(form(x, tube.towards_b), kappa() * form(x, tube.a));
    }
#endif
    return vec2<f32>(0.0);
}

fn over_segment(tube: Tube, x: vec4<f32>) -> bool {
    let sg = tube_foot_coordinates(tube, x);
    return sg.x >= 0.0 && sg.y * tube.length.y - sg.x * tube.length.x >= 0.0;
}

fn tube_foot(tube: Tube, x: vec4<f32>) -> vec4<f32> {
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        return tube.a + tube_foot_coordinates(tube, x).x * tube.towards_b;
    }
#endif
#ifdef CURVED
    if kappa() != 0.0 {
        return project_point(kappa() * form(x, tube.a) * tube.a + form(x, tube.towards_b) * tube.towards_b);
    }
#endif
    return x;
}

fn hit_tube(tube: Tube, p: vec4<f32>, v: vec4<f32>, hi: f32) -> f32 {
    var t = vec2<f32>(NO_HIT, NO_HIT);
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        let u = tube.towards_b.xyz;
        let d0 = p.xyz - tube.a.xyz;
        let d = d0 - dot(d0, u) * u;
        let w = v.xyz - dot(v.xyz, u) * u;
        t = roots(dot(w, w), 2.0 * dot(d, w), dot(d, d) - tube.colour.w);
    }
#endif
#ifdef CURVED
    if kappa() != 0.0 {
        // κ⟨X,e1⟩² + ⟨X,e2⟩² = C(ρ)² ⟨X,X⟩ with ⟨X,X⟩ = κ + s², e1 = a, e2 = towards_b.
        let a0 = form(p, tube.a);
        let a1 = form(v, tube.a);
        let b0 = form(p, tube.towards_b);
        let b1 = form(v, tube.towards_b);
        let cr2 = tube.colour.w;
        t = roots(
            kappa() * a1 * a1 + b1 * b1 - cr2,
            2.0 * (kappa() * a0 * a1 + b0 * b1),
            kappa() * a0 * a0 + b0 * b0 - kappa() * cr2,
        );
    }
#endif
    if in_range(t.x, hi) && over_segment(tube, p + t.x * v) { return t.x; }
    if in_range(t.y, hi) && over_segment(tube, p + t.y * v) { return t.y; }
    return NO_HIT;
}
#endif

// A surface point's outward unit normal, albedo and emission.
struct Surface {
    normal: vec4<f32>,
    albedo: vec3<f32>,
    emission: vec3<f32>,
    // The share reflected as a mirror (0: none).
    reflectance: f32,
}
