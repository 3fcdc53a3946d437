// The light a surface point gets from a lamp: every image of it in the cover within its
// reach, by Lambert's cosine, the falloff and the fog's absorption, the nearest few walked
// for shadows, the rest by its mean (or the nearest copy only, the older model).
// The Rust twin: `scene::lighting`.
#define_import_path curved_spaces::lighting

#import curved_spaces::layout::{kappa, space}
#import curved_spaces::geometry::{distance, distance_from_ratio, form, project_point, s_of, tangent_towards, unit_tangent}
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
#endif

// The light a surface point (unit normal `normal`) gets from lamp `i`, per unit of its
// colour × power (Rust: `scene::lighting::gather`).
fn light_from(i: u32, point: vec4<f32>, normal: vec4<f32>) -> f32 {
    let count = u32(space.lights[i].colour.w);
    let near_s = space.shading.params.z;
#ifdef LIGHT_IMAGES_SUM
    let reach = space.lights[i].info.x;
    let fog = space.shading.params.x;
    var sum = 0.0;
    for (var k = 0u; k < count; k += 1u) {
        let q = space.lights[i].images[k];
        let d = distance(point, q);
        if !(d > 0.0) || d > reach {
            continue;
        }
        let s = max(abs(s_of(d)), near_s);
        let falloff = 1.0 / (s * s);
        var walk = false;
#ifdef SHADOWS
        walk = k < #{SHADOWS}u;
#endif
#ifdef SPHERICAL
        if kappa() > 0.0 {
            // Both arcs and the whole turns (a turn passes both arcs); the lamp's antipode
            // has no direction and is left out.
            if d > 3.14059265 {
                continue;
            }
            let l = tangent_towards(point, q);
            let short = max(form(normal, l), 0.0);
            let long = max(-form(normal, l), 0.0);
            if short == 0.0 && long == 0.0 {
                continue;
            }
            var a = true;
            var b = true;
#ifdef SHADOWS
            if walk {
                a = !occluded(point, l, d);
                b = !occluded(point, -l, TAU - d);
            }
#endif
            let t = exp(-TAU / fog);
            let fs = short * exp(-d / fog);
            let fl = long * exp(-(TAU - d) / fog);
            var paths = 0.0;
            if a {
                paths += fs;
            }
            if b {
                paths += fl;
            }
            if a && b {
                paths += (fs + fl) * t / (1.0 - t);
            }
            sum += paths * falloff;
            continue;
        }
#endif
        let l = tangent_towards(point, q);
        let cos = max(form(normal, l), 0.0);
        if cos > 0.0 {
#ifdef SHADOWS
            if walk && occluded(point, l, d) {
                continue;
            }
#endif
            sum += cos * exp(-d / fog) * falloff;
        }
    }
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
    let cos = max(form(normal, l), 0.0);
#ifdef SHADOWS
    if cos > 0.0 && occluded(point, l, dl) {
        return 0.0;
    }
#endif
    let s = max(abs(s_of(dl)), near_s);
    return cos / (s * s);
#endif
}
