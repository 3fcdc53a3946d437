// What a segment meets first, and the surface there.
// The Rust twin: `scene::model`.
#define_import_path curved_spaces::scene

#import curved_spaces::layout::{ball_count, space, tube_count}
#import curved_spaces::geometry::{distance_from_ratio, form, unit_tangent}
#import curved_spaces::object::{NO_HIT, Surface, hit_ball_at, hit_disc, hit_tube, tube_foot}
#import curved_spaces::texture::{globe_uv, sample_texture}
#import curved_spaces::mesh::{MeshHit, hit_mesh, mesh_surface}
#import curved_spaces::walk::{Ray}
#import curved_spaces::culling::{cull_range, list_word, masked_balls, may_meet, near_faces, near_part, segment_scale}

// What a segment meets first (Rust: `CurvedScene::intersect`): its chart ratio s (s_max when
// nothing), the kind (0 nothing, 1 ball, 2 tube, 3 globe, 4 disc, 5 mesh instance, 6 avatar
// image) and index, and for meshes the triangle hit.
struct SceneHit {
    s: f32,
    kind: u32,
    index: u32,
#ifdef MESHES
    mesh: MeshHit,
#endif
}

#ifdef BALLS
// Ball i's hit on the segment, kept in `hit` if it is nearer.
fn nearer_ball(i: u32, p: vec4<f32>, v: vec4<f32>, hit: ptr<function, SceneHit>) {
    let s = hit_ball_at(space.balls[i].centre, space.balls[i].colour.w, p, v, (*hit).s);
    if s < (*hit).s {
        (*hit).s = s;
        (*hit).kind = 1u;
        (*hit).index = i;
    }
}
#endif

#ifdef TUBES
// Tube i's hit on the segment, kept in `hit` if it is nearer.
fn nearer_tube(i: u32, p: vec4<f32>, v: vec4<f32>, hit: ptr<function, SceneHit>) {
    let s = hit_tube(space.tubes[i], p, v, (*hit).s);
    if s < (*hit).s {
        (*hit).s = s;
        (*hit).kind = 2u;
        (*hit).index = i;
    }
}
#endif

// The nearest object along the segment p + s v, s in (0, s_max); `travelled` is the distance
// before the segment (the avatar's copy the eye sits in is passed through).
fn intersect_scene(ray: Ray, s_max: f32, travelled: f32) -> SceneHit {
    let p = ray.point;
    let v = ray.tangent;
    var hit: SceneHit;
    hit.s = s_max;
    hit.kind = 0u;
    hit.index = 0u;
#ifdef MESHES
    hit.mesh = MeshHit(NO_HIT, 0u, vec2<f32>(0.0), vec3<f32>(0.0));
#endif
#ifdef CULLING
    let scale = segment_scale(s_max);
    let near_set = near_faces(ray, s_max, scale);
    let near = near_set.faces;
    // The objects that hug fewer than two faces (all lanes the same bucket), then, where two
    // faces are near at one point, the buckets of each pair f < g of the faces the segment
    // comes near, one pair a turn (most segments visit none).
    var outer = select(0u, near, near_set.pairs);
    var f = firstTrailingBit(outer);
    outer &= outer - 1u;
    var inner = outer;
    var bucket = #{CULL_BUCKETS}u - 1u;
    // The pair of the bucket, and whether the segment is near both at once (the parts of it
    // near each overlap): objects on the pair's edge or corners need both.
    var pair = vec2<u32>(0u, 0u);
    loop {
        var both = true;
        if bucket != #{CULL_BUCKETS}u - 1u {
            let part = near_part(ray, pair.y, scale, near_part(ray, pair.x, scale, vec2<f32>(0.0, s_max)));
            both = part.x <= part.y;
        }
#ifdef BALLS
        var balls = cull_range(0u, bucket);
        if !both {
            balls.y = balls.x;
        }
        for (var k = balls.x; k < balls.y; k += 1u) {
            let i = list_word(k);
            if may_meet(i, near) {
                nearer_ball(i, p, v, &hit);
            }
        }
#endif
#ifdef TUBES
        var tubes = cull_range(1u, bucket);
        if !both {
            tubes.y = tubes.x;
        }
        for (var k = tubes.x; k < tubes.y; k += 1u) {
            let i = list_word(k);
            if may_meet(masked_balls() + i, near) {
                nearer_tube(i, p, v, &hit);
            }
        }
#endif
        if inner == 0u {
            break;
        }
        let g = firstTrailingBit(inner);
        inner &= inner - 1u;
        bucket = g * (g - 1u) / 2u + f;
        pair = vec2<u32>(f, g);
        if inner == 0u && outer != 0u {
            f = firstTrailingBit(outer);
            outer &= outer - 1u;
            inner = outer;
        }
    }
#else
#ifdef BALLS
    for (var i = 0u; i < ball_count(); i += 1u) {
        nearer_ball(i, p, v, &hit);
    }
#endif
#ifdef TUBES
    for (var i = 0u; i < tube_count(); i += 1u) {
        nearer_tube(i, p, v, &hit);
    }
#endif
#endif
#ifdef GLOBES
    for (var i = 0u; i < #{GLOBE_COUNT}u; i += 1u) {
        let s = hit_ball_at(space.globes[i].centre, space.globes[i].colour.w, p, v, hit.s);
        if s < hit.s {
            hit.s = s;
            hit.kind = 3u;
            hit.index = i;
        }
    }
#endif
#ifdef DISCS
    for (var i = 0u; i < #{DISC_COUNT}u; i += 1u) {
        let s = hit_disc(space.discs[i], p, v, hit.s);
        if s < hit.s {
            hit.s = s;
            hit.kind = 4u;
            hit.index = i;
        }
    }
#endif
#ifdef MESHES
    // The placed meshes, then the avatar's images, through one call of hit_mesh (two calls
    // made llvmpipe miscompile the walk).
    var mesh_slots = 0u;
#ifdef INSTANCES
    mesh_slots += #{INSTANCE_COUNT}u;
#endif
    let instance_slots = mesh_slots;
#ifdef AVATAR
    mesh_slots += u32(space.view.avatar_info.x);
#endif
    for (var i = 0u; i < mesh_slots; i += 1u) {
        let is_avatar = i >= instance_slots;
        var root = 0u;
        var inverse = mat4x4<f32>();
#ifdef INSTANCES
        if !is_avatar {
            root = space.instances[i].info.x;
            inverse = space.instances[i].inverse;
        }
#endif
#ifdef AVATAR
        if is_avatar {
            root = u32(space.view.avatar_info.z);
            inverse = space.view.avatar[2u * (i - instance_slots) + 1u];
        }
#endif
        let h = hit_mesh(root, inverse, p, v, hit.s);
        // The avatar's copy the eye sits in is passed through.
        if h.s < hit.s
            && (!is_avatar || travelled + distance_from_ratio(h.s, 1.0) >= space.view.avatar_info.y) {
            hit.s = h.s;
            hit.kind = select(5u, 6u, is_avatar);
            hit.index = select(i, i - instance_slots, is_avatar);
            hit.mesh = h;
        }
    }
#endif
    return hit;
}

// The surface at a hit point: outward normal (towards the viewer for discs), albedo and
// emission (Rust: `Hit`'s normal and material).
fn surface_at(hit: SceneHit, point: vec4<f32>, v: vec4<f32>) -> Surface {
    var surface = Surface(vec4<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0), 0.0);
#ifdef BALLS
    if hit.kind == 1u {
        let ball = space.balls[hit.index];
        surface = Surface(unit_tangent(point, point - ball.centre), ball.colour.rgb, ball.emission.rgb, ball.emission.w);
    }
#endif
#ifdef TUBES
    if hit.kind == 2u {
        let tube = space.tubes[hit.index];
        surface = Surface(unit_tangent(point, point - tube_foot(tube, point)), tube.colour.rgb, tube.emission.rgb, 0.0);
    }
#endif
#ifdef GLOBES
    if hit.kind == 3u {
        let globe = space.globes[hit.index];
        var albedo = globe.colour.rgb;
#ifdef TEXTURES
        albedo *= sample_texture(u32(globe.emission.w), globe_uv(globe, point));
#endif
        surface = Surface(unit_tangent(point, point - globe.centre), albedo, globe.emission.rgb, globe.spin.y);
    }
#endif
#ifdef DISCS
    if hit.kind == 4u {
        let disc = space.discs[hit.index];
        var normal = unit_tangent(point, disc.normal);
        if form(normal, v) > 0.0 {
            normal = -normal;
        }
        surface = Surface(normal, disc.colour.rgb, disc.emission.rgb, disc.emission.w);
    }
#endif
#ifdef INSTANCES
    if hit.kind == 5u {
        let instance = space.instances[hit.index];
        surface = mesh_surface(hit.mesh, instance.frame, instance.info.y, instance.info.z, point, v);
    }
#endif
#ifdef AVATAR
    if hit.kind == 6u {
        surface = mesh_surface(hit.mesh, space.view.avatar[2u * hit.index], 0xffffffffu, 0u, point, v);
    }
#endif
    return surface;
}
