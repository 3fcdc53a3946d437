// Face masks: a segment tests only the objects near the faces it comes near.
// The Rust twin: `scene::culling`.
#define_import_path curved_spaces::culling

#import curved_spaces::layout::{ball_count, face_count, space}
#import curved_spaces::object::{NO_HIT}
#import curved_spaces::walk::{Ray}

#ifdef CULLING
// The faces a segment comes near, and whether two of them are near at one point of it.
struct Near {
    faces: u32,
    pairs: bool,
}

// The faces (bits of faces 0–31) the segment p + s v, s in [0, s_max], comes near (Rust:
// `FaceCulling::near_faces`): −N·X is linear in s, so its least value is at an end; `scale`
// bounds |X(s)| (segment_scale). The residuals are exit_face's, of the same segment.
//
// A face is near the segment on an interval of s that holds an end (or all of it). Two faces
// are near at one point exactly when both are near at the start, or both at the end, or one
// only at the start (up to s = a) and the other only at the end (from s = b) with b ≤ a; so
// `pairs` tells, from the latest a and the earliest b, whether any pair of faces needs
// visiting. Most segments are near only the faces they enter and leave by, far apart.
fn near_faces(ray: Ray, s_max: f32, scale: f32) -> Near {
    var at_start = 0u;
    var at_end = 0u;
    var leaves = -1.0;
    var reaches = NO_HIT;
    for (var f = 0u; f < min(face_count(), 32u); f += 1u) {
        let n = space.covectors[f];
        let r0 = -dot(n, ray.point);
        let rate = dot(n, ray.tangent);
        let r1 = r0 - s_max * rate;
        let t = space.near[f / 4u][f % 4u] * scale;
        let start = r0 <= t;
        let end = r1 <= t;
        if start {
            at_start |= 1u << f;
        }
        if end {
            at_end |= 1u << f;
        }
        // Near only at the start: the residual grows (rate < 0), past t at (r0 − t)/rate.
        if start && !end {
            leaves = max(leaves, (r0 - t) / rate);
        }
        // Near only at the end: the residual falls (rate > 0), to t at (r0 − t)/rate.
        if end && !start {
            reaches = min(reaches, (r0 - t) / rate);
        }
    }
    let pairs = countOneBits(at_start) >= 2u || countOneBits(at_end) >= 2u || reaches <= leaves;
    return Near(at_start | at_end, pairs);
}

// A bound on |X(s)| over the segment: 1 in E³ and H³, √(1 + s_max²) in S³.
fn segment_scale(s_max: f32) -> f32 {
    var scale = 1.0;
#ifdef SPHERICAL
    scale = sqrt(1.0 + s_max * s_max);
#endif
    return scale;
}

// The part of `range` (of s) where the segment is near face `face`: −N·X(s) = a − s b is
// linear, so it is an interval (empty when x > y).
fn near_part(ray: Ray, face: u32, scale: f32, range: vec2<f32>) -> vec2<f32> {
    let n = space.covectors[face];
    let a = -dot(n, ray.point);
    let b = dot(n, ray.tangent);
    let t = space.near[face / 4u][face % 4u] * scale;
    if b > 0.0 {
        return vec2<f32>(max(range.x, (a - t) / b), range.y);
    }
    if b < 0.0 {
        return vec2<f32>(range.x, min(range.y, (a - t) / b));
    }
    return select(vec2<f32>(1.0, 0.0), range, a <= t);
}

// Whether a segment near the faces `near` may meet object `object` (balls, then tubes).
fn may_meet(object: u32, near: u32) -> bool {
    let mask = space.masks[object / 4u][object % 4u];
    return (mask & near) == mask;
}

fn list_word(k: u32) -> u32 {
    return space.lists[k / 4u][k % 4u];
}

// Tests the balls (kind 0) or tubes (kind 1) of bucket b that a segment near the faces
// `near` may meet.
fn cull_range(kind: u32, b: u32) -> vec2<u32> {
    let at = kind * (#{CULL_BUCKETS}u + 1u) + b;
    return vec2<u32>(list_word(at), list_word(at + 1u));
}

// How many masks come before the tubes'.
fn masked_balls() -> u32 {
    var n = 0u;
#ifdef BALLS
    n = ball_count();
#endif
    return n;
}

#endif
