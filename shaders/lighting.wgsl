// The light a surface point gets from a lamp: every image of it in the cover within its
// reach, by Lambert's cosine, the falloff and the fog's absorption, the nearest few walked
// for shadows, the rest by its mean (or the nearest copy only, the older model).
// The Rust twin: `scene::lighting`.
#define_import_path curved_spaces::lighting

#import curved_spaces::layout::{kappa, space}
#import curved_spaces::geometry::{distance, distance_from_ratio, form, project_point, project_tangent, s_of, tangent_towards, unit_tangent}
#ifdef SHADOWS
#import curved_spaces::walk::{NO_FACE, Ray, cross_face, exit_face, partner}
#import curved_spaces::scene::{intersect_scene}
#endif

const TAU: f32 = 6.2831853;

#ifdef SHADOWS
// How far a shadow ray starts from the surface it leaves (Rust: `SHADOW_OFFSET`).
const SHADOW_OFFSET: f32 = 1e-3;

// (C(t), S(t)).
fn cs_of(t: f32) -> vec2<f32> {
#ifdef SPHERICAL
    if kappa() > 0.0 {
        return vec2<f32>(cos(t), sin(t));
    }
#endif
#ifdef HYPERBOLIC
    if kappa() < 0.0 {
        return vec2<f32>(cosh(t), sinh(t));
    }
#endif
    return vec2<f32>(1.0, t);
}

// Whether an object lies on the geodesic from `point` along the unit tangent `l` within
// `length`: the camera ray's walk through the faces, ended by any hit, started
// SHADOW_OFFSET along; past the crossing budget it gives up, unshadowed (Rust:
// `ShadowWalk::occluded`).
fn occluded(point: vec4<f32>, l: vec4<f32>, length: f32) -> bool {
    if length <= SHADOW_OFFSET {
        return false;
    }
    let cs0 = cs_of(SHADOW_OFFSET);
    let p = project_point(point * cs0.x + l * cs0.y);
    var ray = Ray(p, unit_tangent(p, l * cs0.x - point * (kappa() * cs0.y)));
    let total = length - SHADOW_OFFSET;
    var travelled = 0.0;
    var skip = 0xffffffffu;
    let budget = u32(space.shading.params.w);
    for (var crossings = 0u; crossings <= budget; crossings += 1u) {
        let exit = exit_face(ray, skip);
        if exit.face == 0xffffffffu {
            return false;
        }
        let cs = cs_of(total - travelled);
        let s_exit = exit.num / exit.den;
        let s_left = select(1e30, cs.y / cs.x, cs.x > 0.0);
        let hit = intersect_scene(ray, min(s_exit, s_left), 1e30);
        if hit.kind != 0u {
            return true;
        }
        if s_left <= s_exit {
            return false;
        }
        travelled += distance_from_ratio(exit.num, exit.den);
        if travelled >= total {
            return false;
        }
        ray = cross_face(ray, exit);
        skip = select(partner(exit.face), 0xffffffffu, exit.face == NO_FACE);
    }
    return false;
}

#ifdef SOFT_SHADOWS
// Successive samples of the Fibonacci spiral turn by it (Rust: `GOLDEN_ANGLE`).
const GOLDEN_ANGLE: f32 = 2.3999632;

// The longest of the coordinate axes' tangent parts at `point` with `l` and `e` taken off,
// normalised (Rust: `tangent_frame`, first `e = 0`, then the first axis found).
fn frame_axis(point: vec4<f32>, l: vec4<f32>, e: vec4<f32>) -> vec4<f32> {
    var best = vec4<f32>(0.0);
    var best_n = -1.0;
    for (var i = 0u; i < 4u; i += 1u) {
        var a = vec4<f32>(0.0);
        a[i] = 1.0;
        var v = project_tangent(point, a);
        v -= l * form(v, l);
        v -= e * form(v, e);
        let n = form(v, v);
        if n > best_n {
            best_n = n;
            best = v;
        }
    }
    return best * inverseSqrt(best_n);
}

// The shadow rays towards a lamp of S(radius) `s_r` whose centre lies `length` along `l`
// (Rust: `shadow_directions`): the frame about `l`, found once, and `versine`, 1 − cos α,
// α the lamp disc's angular radius; then sample `j` of the Fibonacci spiral over the disc.
struct SoftFrame {
    first: vec4<f32>,
    second: vec4<f32>,
    versine: f32,
}

fn soft_frame(point: vec4<f32>, l: vec4<f32>, length: f32, s_r: f32) -> SoftFrame {
    let first = frame_axis(point, l, vec4<f32>(0.0));
    let second = frame_axis(point, l, first);
    let sin_a = min(s_r / abs(s_of(length)), 1.0);
    let sin_sq = sin_a * sin_a;
    return SoftFrame(first, second, sin_sq / (1.0 + sqrt(1.0 - sin_sq)));
}

// Sample `j`, spread evenly by solid angle: 1 − cos θ = u (1 − cos α).
fn soft_direction(point: vec4<f32>, l: vec4<f32>, f: SoftFrame, j: u32) -> vec4<f32> {
    let u = (f32(j) + 0.5) / f32(#{SOFT_SHADOWS}u);
    let theta = 2.0 * asin(sqrt(0.5 * u * f.versine));
    let phi = f32(j) * GOLDEN_ANGLE;
    let v = l * cos(theta) + (f.first * cos(phi) + f.second * sin(phi)) * sin(theta);
    return unit_tangent(point, v);
}
#endif

// The share of lamp `i` seen from `point` along `l`, its centre `length` away: the shadow
// rays over its disc that reach it (one, to its centre, for a point lamp).
fn seen(i: u32, point: vec4<f32>, l: vec4<f32>, length: f32) -> f32 {
#ifdef SOFT_SHADOWS
    let s_r = space.lights[i].info.z;
    if s_r > 0.0 {
        let f = soft_frame(point, l, length, s_r);
        var open = 0.0;
        for (var j = 0u; j < #{SOFT_SHADOWS}u; j += 1u) {
            if !occluded(point, soft_direction(point, l, f, j), length) {
                open += 1.0;
            }
        }
        return open / f32(#{SOFT_SHADOWS}u);
    }
#endif
    return select(1.0, 0.0, occluded(point, l, length));
}

#ifdef SPHERICAL
// Whether the short arc along `v` (`length`) and the long one the other way round the same
// great circle are open: (short, long, both) as 0 or 1.
fn arcs_open(point: vec4<f32>, v: vec4<f32>, length: f32) -> vec3<f32> {
    let a = !occluded(point, v, length);
    let b = !occluded(point, -v, TAU - length);
    return vec3<f32>(select(0.0, 1.0, a), select(0.0, 1.0, b), select(0.0, 1.0, a && b));
}

// In S³, the shares of lamp `i` seen along the short arcs (`length` along `l`), along the
// long ones and along both (a whole turn passes both).
fn seen_arcs(i: u32, point: vec4<f32>, l: vec4<f32>, length: f32) -> vec3<f32> {
#ifdef SOFT_SHADOWS
    let s_r = space.lights[i].info.z;
    if s_r > 0.0 {
        let f = soft_frame(point, l, length, s_r);
        var open = vec3<f32>(0.0);
        for (var j = 0u; j < #{SOFT_SHADOWS}u; j += 1u) {
            open += arcs_open(point, soft_direction(point, l, f, j), length);
        }
        return open / f32(#{SOFT_SHADOWS}u);
    }
#endif
    return arcs_open(point, l, length);
}
#endif
#endif

#ifdef LIGHT_IMAGES_SUM
// What image `k` of lamp `i` within its reach gives a surface point (unit normal `normal`),
// walked for shadows if `walk` (Rust: one term of `scene::lighting::gather`).
fn image_light(i: u32, k: u32, point: vec4<f32>, normal: vec4<f32>, walk: bool) -> f32 {
    let near_s = space.shading.params.z;
    let reach = space.lights[i].info.x;
    let fog = space.shading.params.x;
    let q = space.lights[i].images[k];
#ifdef HYPERBOLIC
#ifndef STRAIGHTFORWARD
    if kappa() < 0.0 && !walk {
        // With the chord u = |point − q|/2 = sinh(d/2): sinh d = 2u√(1 + u²),
        // e^(−d) = (√(1 + u²) + u)^(−2), and ⟨normal, l⟩ = ⟨normal, q⟩ / sinh d because the
        // normal is orthogonal to the point (q = cosh d·point + sinh d·l). One square root,
        // one log and one exp an image instead of asinh, sinh, exp and a normalisation: the
        // image sum is most of a frame's shading.
        let chord = point - q;
        let u = 0.5 * sqrt(max(form(chord, chord), 0.0));
        let c = sqrt(1.0 + u * u);
        let d = 2.0 * log(c + u);
        if !(u > 0.0) || d > reach {
            return 0.0;
        }
        let sinh_d = 2.0 * u * c;
        let cos = max(form(normal, q) / sinh_d, 0.0);
        let s = max(sinh_d, near_s);
        return cos * exp(-d / fog) / (s * s);
    }
#endif
#endif
    let d = distance(point, q);
    if !(d > 0.0) || d > reach {
        return 0.0;
    }
    let s = max(abs(s_of(d)), near_s);
    let falloff = 1.0 / (s * s);
#ifdef SPHERICAL
    if kappa() > 0.0 {
        // Both arcs and the whole turns (a turn passes both arcs); the lamp's antipode
        // has no direction and is left out.
        if d > 3.14059265 {
            return 0.0;
        }
        let l = tangent_towards(point, q);
        let short = max(form(normal, l), 0.0);
        let long = max(-form(normal, l), 0.0);
        if short == 0.0 && long == 0.0 {
            return 0.0;
        }
        // The shares seen along the short arcs, the long ones and both.
        var open = vec3<f32>(1.0);
#ifdef SHADOWS
        if walk {
            open = seen_arcs(i, point, l, d);
        }
#endif
        let t = exp(-TAU / fog);
        let fs = short * exp(-d / fog);
        let fl = long * exp(-(TAU - d) / fog);
        let paths = fs * open.x + fl * open.y + (fs + fl) * open.z * t / (1.0 - t);
        return paths * falloff;
    }
#endif
    let l = tangent_towards(point, q);
    let cos = max(form(normal, l), 0.0);
    if cos > 0.0 {
        var open = 1.0;
#ifdef SHADOWS
        if walk {
            open = seen(i, point, l, d);
        }
#endif
        return cos * open * exp(-d / fog) * falloff;
    }
    return 0.0;
}
#endif

// The light a surface point (unit normal `normal`) gets from lamp `i`, per unit of its
// colour × power (Rust: `scene::lighting::gather`).
fn light_from(i: u32, point: vec4<f32>, normal: vec4<f32>) -> f32 {
    let count = u32(space.lights[i].colour.w);
    let near_s = space.shading.params.z;
#ifdef LIGHT_IMAGES_SUM
    var sum = 0.0;
    // The nearest images, walked for shadows, in a loop of their own: a SIMD rasteriser
    // such as llvmpipe runs an `if`'s body whenever any lane reaches it, so a shadow walk
    // under `if k < SHADOWS` in one loop over every image was paid at every image.
    var first = 0u;
#ifdef SHADOWS
    first = min(count, #{SHADOWS}u);
    for (var k = 0u; k < first; k += 1u) {
        sum += image_light(i, k, point, normal, true);
    }
#endif
#ifdef STRAIGHTFORWARD
    // The benchmark's straightforward tracer sums every image, as one would first write it.
    for (var k = first; k < count; k += 1u) {
        sum += image_light(i, k, point, normal, false);
    }
#else
    // Only the images within the reach give light, a few of the hundreds a hyperbolic
    // lamp may have. They come nearest the origin first, so none past |point| + reach
    // from the origin is within the reach of the point (the triangle inequality) and the
    // loop ends there: a loop stops when every lane of a SIMD rasteriser has left it,
    // where an `if` that skips an image for some lanes would save nothing. Both bounds
    // compare chords, one dot product an image (|x − y|² = 4 S(d/2)²), with a margin for
    // f32 rounding, so that every image the exact test in `image_light` keeps is summed
    // (the cut ends at the antipode in S³, where every image may reach).
    let reach = space.lights[i].info.x;
    let origin = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    let half_out = s_of(min(0.5 * (distance(origin, point) + reach) + 1e-3, 1.5707));
    let out_limit = 4.0 * half_out * half_out * 1.0001 + 1e-5;
    let half_reach = s_of(min(0.5 * reach + 1e-3, 1.5707));
    let reach_limit = 4.0 * half_reach * half_reach * 1.0001 + 1e-5;
    for (var k = first; k < count; k += 1u) {
        let q = space.lights[i].images[k];
        let from_origin = origin - q;
        if form(from_origin, from_origin) > out_limit {
            break;
        }
        let chord = point - q;
        if form(chord, chord) <= reach_limit {
            sum += image_light(i, k, point, normal, false);
        }
    }
#endif
    return sum + space.lights[i].info.y;
#else
    // The nearest of the light's images through the faces.
    var at = space.lights[i].images[0];
    var dl = distance(point, at);
    for (var k = 1u; k < count; k += 1u) {
        let q = space.lights[i].images[k];
        let dq = distance(point, q);
        if dq < dl {
            dl = dq;
            at = q;
        }
    }
    if !(dl > 0.0) {
        return 0.0;
    }
    let l = tangent_towards(point, at);
    var cos = max(form(normal, l), 0.0);
#ifdef SHADOWS
    if cos > 0.0 {
        cos *= seen(i, point, l, dl);
    }
#endif
    let s = max(abs(s_of(dl)), near_s);
    return cos / (s * s);
#endif
}
