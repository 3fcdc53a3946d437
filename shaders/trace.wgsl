// One camera ray's colour (and the benchmark's straightforward tracer).
// The Rust twin: `trace`.
#define_import_path curved_spaces::trace

#import curved_spaces::layout::{ball_count, face_count, kappa, space}
#import curved_spaces::geometry::{distance_from_ratio, form, project_point, s_of, unit_tangent}
#import curved_spaces::object::{NO_HIT, roots}
#import curved_spaces::shading::{colour_by_tint, colour_tint, shade}
#import curved_spaces::hit_id::{FNV_OFFSET, FNV_PRIME, hit_id, object_number}
#import curved_spaces::walk::{NO_FACE, Ray, cross_face, exit_face, partner, walk_faces}
#import curved_spaces::scene::{SceneHit, intersect_scene, surface_at}
#import curved_spaces::walls::{cross_wall, veil_colour, veil_through}

// C(t): cos t, 1 or cosh t.
fn c_of(t: f32) -> f32 {
#ifdef SPHERICAL
    if kappa() > 0.0 {
        return cos(t);
    }
#endif
#ifdef HYPERBOLIC
    if kappa() < 0.0 {
        return cosh(t);
    }
#endif
    return 1.0;
}

// The colour seen from the eye `p` in the direction `d` (any vector of the tangent space
// there: it is made a unit tangent), the walls crossed on the way included: the entry point
// every family's tracer module has under this name (curved_space.wgsl calls it).
fn ray_colour(p: vec4<f32>, d: vec4<f32>) -> vec3<f32> {
    let v = unit_tangent(p, d);
#ifdef WALLS
    veil_colour = vec3<f32>(0.0);
    veil_through = 1.0;
    let behind = trace(p, v);
    return veil_colour + veil_through * behind;
#else
    return trace(p, v);
#endif
}

#ifdef STRAIGHTFORWARD
// The arc length t > 0 at which C(t)·a + S(t)·b = k along γ(t) = C(t) p + S(t) v, the first
// root, or NO_HIT: a ball's boundary (a = ⟨p,c⟩, b = ⟨v,c⟩, k = C(ρ) in S³ and H³; in E³
// a = |p − c|², b = 2 (p − c)·v, k = ρ², the quadric t² + b t + a = k).
fn first_arc(a: f32, b: f32, k: f32) -> f32 {
#ifdef SPHERICAL
    if kappa() > 0.0 {
        // R cos(t − φ) = k: entering at t = φ − acos(k / R).
        let r = sqrt(a * a + b * b);
        if !(k < r) {
            return NO_HIT;
        }
        let t = atan2(b, a) - acos(k / r);
        return select(NO_HIT, t, t > 0.0);
    }
#endif
#ifdef HYPERBOLIC
    if kappa() < 0.0 {
        // −⟨γ, c⟩ = cosh ρ with −⟨p,c⟩ = A, −⟨v,c⟩ = B: (A + B) u² − 2 cosh ρ u + (A − B) = 0
        // in u = eᵗ.
        let u = roots(-(a + b), 2.0 * k, -(a - b));
        if u.x > 1.0 && u.x < NO_HIT {
            return log(u.x);
        }
        return NO_HIT;
    }
#endif
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        let t = roots(1.0, b, a - k);
        return select(NO_HIT, t.x, t.x > 0.0 && t.x < NO_HIT);
    }
#endif
    return NO_HIT;
}

// The benchmark's comparison, never drawn by the plugin: a straightforward tracer of the
// same walk and shading, as one would first write it. The geodesic is followed by arc
// length, γ(t) = C(t) p + S(t) v: each face's crossing is solved for t with an inverse
// trigonometric (hyperbolic) function, a division a face, and the ball's with its own
// trigonometric solution; the point and tangent are moved along γ, the face's pairing is
// applied as a plain f32 product and both are put back on the model every step. The
// tracer above compares chart ratios without dividing, moves along chart lines, and
// applies the pairings compensated. Balls only, no step cap.
fn trace(start_point: vec4<f32>, start_tangent: vec4<f32>) -> vec3<f32> {
    let fog = space.shading.fog.rgb;
    let cutoff = space.shading.params.y;
    let budget = u32(space.shading.params.w);
    var p = start_point;
    var v = start_tangent;
    var travelled = 0.0;
    var skip = 0xffffffffu;
    for (var crossings = 0u; crossings <= budget; crossings += 1u) {
        // N·γ(t) = C(t) N·p + S(t) N·v = 0 at T(t) = S/C = −N·p / N·v.
        var t_exit = NO_HIT;
        var face = 0xffffffffu;
        let faces = walk_faces(p, skip);
        for (var f = faces.x; f < faces.y; f += 1u) {
            let n = space.covectors[f];
            let b = dot(n, v);
            if f != skip && b > 0.0 {
                let t = distance_from_ratio(max(-dot(n, p), 0.0) / b, 1.0);
                if t < t_exit {
                    t_exit = t;
                    face = f;
                }
            }
        }
        if face == 0xffffffffu {
            break;
        }
        var t_hit = t_exit;
        var ball = 0xffffffffu;
#ifdef BALLS
        for (var i = 0u; i < ball_count(); i += 1u) {
            let c = space.balls[i].centre;
            let size = space.balls[i].colour.w;
            var t = NO_HIT;
            if kappa() == 0.0 {
                let d = p.xyz - c.xyz;
                t = first_arc(dot(d, d), 2.0 * dot(d, v.xyz), size * size);
            } else {
                t = first_arc(form(p, c) * kappa(), form(v, c) * kappa(), size);
            }
            if t < t_hit {
                t_hit = t;
                ball = i;
            }
        }
#endif
        if ball != 0xffffffffu {
            let d = travelled + t_hit;
            if d >= cutoff {
                return fog;
            }
            let point = project_point(c_of(t_hit) * p + s_of(t_hit) * v);
            let centre = space.balls[ball].centre;
            return shade(point, unit_tangent(point, point - centre), space.balls[ball].colour.rgb, space.balls[ball].emission.rgb, d);
        }
        if crossings == budget {
            break;
        }
        travelled += t_exit;
        if travelled >= cutoff {
            return fog;
        }
        let at = c_of(t_exit) * p + s_of(t_exit) * v;
        let along = -kappa() * s_of(t_exit) * p + c_of(t_exit) * v;
        let g = space.pairings[face];
        p = project_point(g * at);
        v = unit_tangent(p, g * along);
        skip = partner(face);
    }
    return fog;
}
#else
#ifdef MIRRORS
// Most mirror bounces (Rust: `trace::MAX_BOUNCES`), and how far along the reflected geodesic
// the ray starts again (`trace::MIRROR_OFFSET`).
const MAX_BOUNCES: u32 = 8u;
const MIRROR_OFFSET: f32 = 1e-3;
// What the mirrors met so far let through of what the ray sees next, and what they added.
var<private> mirror_sum: vec3<f32>;
var<private> mirror_weight: f32;
#endif

// The colour at the end of the ray's path: `c` seen through the mirrors met on the way (and
// the walls crossed since the last one, which the caller would add otherwise).
fn path_end(c: vec3<f32>) -> vec3<f32> {
#ifdef MIRRORS
#ifdef WALLS
    let seen = veil_colour + veil_through * c;
    veil_colour = vec3<f32>(0.0);
    veil_through = 1.0;
    return mirror_sum + mirror_weight * seen;
#else
    return mirror_sum + mirror_weight * c;
#endif
#else
    return c;
#endif
}

// One camera ray's colour: walk the cell, nearest object hit against exit face, cross by
// pairings until the fog cut-off or the crossing budget (Rust: `trace::first_hit` and
// `colour_of`).
//
// The walk's loop holds only the walk and the intersections; the surface, its shading and a
// mirror's bounce come after it, once per ray (once per bounce). A SIMD rasteriser such as
// llvmpipe runs the body of every `if` that any lane reaches, whatever the condition, so
// shading inside the loop was paid at every crossing of every pixel.
fn trace(start_point: vec4<f32>, start_tangent: vec4<f32>) -> vec3<f32> {
    let fog = space.shading.fog.rgb;
    let cutoff = space.shading.params.y;
    let budget = u32(space.shading.params.w);
    var ray = Ray(start_point, start_tangent);
    var travelled = 0.0;
    var skip = 0xffffffffu;
    var crossings = 0u;
#ifdef MIRRORS
    mirror_sum = vec3<f32>(0.0);
    mirror_weight = 1.0;
    var bounces = 0u;
#endif
#ifdef HIT_ID
    var path = FNV_OFFSET;
    hit_id = vec4<u32>(0u, 0u, path, 3u);
#endif
#ifdef COLOUR_BY
    var last_face = 0xffffffffu;
    var held = mat4x4<f32>(
        vec4<f32>(1.0, 0.0, 0.0, 0.0),
        vec4<f32>(0.0, 1.0, 0.0, 0.0),
        vec4<f32>(0.0, 0.0, 1.0, 0.0),
        vec4<f32>(0.0, 0.0, 0.0, 1.0),
    );
#endif
    // One pass a bounce (one pass without mirrors).
    loop {
        // The walk, up to the first object, the fog cut-off, the budget or a wall that stops
        // the ray (hit.kind stays 0 for all but the first).
        var hit: SceneHit;
        loop {
            let exit = exit_face(ray, skip);
            if exit.face == 0xffffffffu {
                break;
            }
            hit = intersect_scene(ray, exit.num / exit.den, travelled);
            if hit.kind != 0u {
                break;
            }
            if crossings == budget {
#ifdef HIT_ID
                hit_id = vec4<u32>(0u, crossings, path, 3u);
#endif
                break;
            }
            travelled += distance_from_ratio(exit.num, exit.den);
#ifdef WALLS
            if exit.face != NO_FACE {
                cross_wall(ray, exit, travelled);
                if veil_through < space.wall_style.x {
#ifdef HIT_ID
                    hit_id = vec4<u32>(0u, crossings + 1u, (path ^ (exit.face + 1u)) * FNV_PRIME, 2u);
#endif
                    break;
                }
            }
#endif
            ray = cross_face(ray, exit);
#ifdef COLOUR_BY
            if exit.face != NO_FACE {
                last_face = exit.face;
#ifdef COLOUR_HOLONOMY
                held = space.pairings[exit.face] * held;
#endif
            }
#endif
#ifdef HIT_ID
            if exit.face != NO_FACE {
                path = (path ^ (exit.face + 1u)) * FNV_PRIME;
            }
            hit_id = vec4<u32>(0u, crossings + 1u, path, 3u);
#endif
            crossings += 1u;
            if travelled >= cutoff {
#ifdef HIT_ID
                hit_id.w = 2u;
#endif
                break;
            }
            skip = select(partner(exit.face), 0xffffffffu, exit.face == NO_FACE);
        }
        if hit.kind == 0u {
            return path_end(fog);
        }
        let point = project_point(ray.point + hit.s * ray.tangent);
        let d = travelled + distance_from_ratio(hit.s, 1.0);
        if d >= cutoff {
#ifdef HIT_ID
            hit_id = vec4<u32>(0u, crossings, path, 2u);
#endif
            return path_end(fog);
        }
#ifdef HIT_ID
        hit_id = vec4<u32>(object_number(hit.kind, hit.index) + 1u, crossings, path, 1u);
#endif
        let surface = surface_at(hit, point, ray.tangent);
#ifdef COLOUR_BY
        colour_tint = colour_by_tint(crossings, last_face, held);
#endif
        let shaded = shade(point, surface.normal, surface.albedo, surface.emission, d);
#ifdef MIRRORS
        // A mirror: 1 − r of the lit surface, r of what the reflected ray sees, the walk
        // going on from the hit (Rust: `trace::colour_along`); the bounce counts as a
        // crossing.
        let r = surface.reflectance;
        if r > 0.0 && bounces < MAX_BOUNCES && crossings < budget {
            bounces += 1u;
#ifdef WALLS
            mirror_sum += mirror_weight * (veil_colour + veil_through * (1.0 - r) * shaded);
            mirror_weight *= veil_through * r;
            veil_colour = vec3<f32>(0.0);
            veil_through = 1.0;
#else
            mirror_sum += mirror_weight * (1.0 - r) * shaded;
            mirror_weight *= r;
#endif
            let v = unit_tangent(point, ray.tangent);
            let n = surface.normal;
            let reflected = v - 2.0 * form(v, n) * n;
            let restart = project_point(c_of(MIRROR_OFFSET) * point + s_of(MIRROR_OFFSET) * reflected);
            let along = -kappa() * s_of(MIRROR_OFFSET) * point + c_of(MIRROR_OFFSET) * reflected;
            ray = Ray(restart, unit_tangent(restart, along));
            travelled = d + MIRROR_OFFSET;
            skip = 0xffffffffu;
            crossings += 1u;
            continue;
        }
#endif
        return path_end(shaded);
    }
    // Not reached (every pass returns or goes on to the next bounce); naga asks for it.
    return path_end(fog);
}
#endif
