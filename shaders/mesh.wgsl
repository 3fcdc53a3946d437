// Meshes: their bounding hierarchies, triangles and materials.
// The Rust twin: `scene::mesh`.
#define_import_path curved_spaces::mesh

#import curved_spaces::layout::{fdata, kappa, scene_data, space}
#import curved_spaces::geometry::{form, unit_tangent}
#import curved_spaces::object::{NO_HIT, Surface}
#import curved_spaces::texture::{sample_texture}

#ifdef MESHES
// A mesh hit: s along the segment, the triangle, the barycentric weights of corners 1
// and 2, and the chart point in the mesh's frame.
struct MeshHit {
    s: f32,
    triangle: u32,
    uv: vec2<f32>,
    local: vec3<f32>,
}

// The slab test of node n: entry parameter or NO_HIT.
fn node_entry(n: u32, o: vec3<f32>, inv_d: vec3<f32>, hi: f32) -> f32 {
    let lo = fdata(2u * n).xyz;
    let up = fdata(2u * n + 1u).xyz;
    let t0 = (lo - o) * inv_d;
    let t1 = (up - o) * inv_d;
    let tmin = min(t0, t1);
    let tmax = max(t0, t1);
    let near = max(max(max(tmin.x, tmin.y), tmin.z), 0.0);
    let far = min(min(min(tmax.x, tmax.y), tmax.z), hi);
    return select(NO_HIT, near, near <= far);
}

const BVH_STACK: u32 = 32u;

// The traversal stack of hit_mesh (one per invocation).
var<private> bvh_stack: array<u32, BVH_STACK>;

// The first hit of the mesh with root node `root` placed by `inverse` (cell → mesh chart)
// on the segment p + s v, s in (0, hi) (CurvedScene::intersect_mesh, Mesh::intersect).
fn hit_mesh(root: u32, inverse: mat4x4<f32>, p: vec4<f32>, v: vec4<f32>, hi: f32) -> MeshHit {
    var best = MeshHit(NO_HIT, 0u, vec2<f32>(0.0), vec3<f32>(0.0));
    let lp = inverse * p;
    let lv = inverse * v;
    if !(lp.w > 0.0) {
        return best;
    }
    let o = lp.xyz / lp.w;
    let d = lv.xyz - o * lv.w;
    let den = lp.w + hi * lv.w;
    var t_best = select(NO_HIT, hi / den, den > 0.0);
    let inv_d = 1.0 / d;
    var top = 0u;
    var node = root;
    var found = false;
    var hit_t = 0.0;
    // Depth first, each node at most once; a walk that needs more than 4096 steps gives up
    // (Mesh::intersect does the same; no ray of our meshes comes near, and without this
    // bound llvmpipe miscompiled the walk).
    for (var steps = 0u; steps < 4096u; steps += 1u) {
        let info = scene_data[2u * node + 1u].w;
        let index = scene_data[2u * node].w;
        var descend = false;
        if info > 0u {
            let tri_base = space.data.x;
            for (var i = index; i < index + info; i += 1u) {
                let b = tri_base + 8u * i;
                let a = fdata(b).xyz;
                let e1 = fdata(b + 1u).xyz;
                let e2 = fdata(b + 2u).xyz;
                let pv = cross(d, e2);
                let det = dot(e1, pv);
                if det == 0.0 {
                    continue;
                }
                let inv = 1.0 / det;
                let tv = o - a;
                let u = dot(tv, pv) * inv;
                if u < 0.0 || u > 1.0 {
                    continue;
                }
                let qv = cross(tv, e1);
                let w = dot(d, qv) * inv;
                if w < 0.0 || u + w > 1.0 {
                    continue;
                }
                let t = dot(e2, qv) * inv;
                if t > 0.0 && t < t_best {
                    t_best = t;
                    hit_t = t;
                    found = true;
                    best.triangle = i;
                    best.uv = vec2<f32>(u, w);
                }
            }
        } else {
            let a = node + 1u;
            let b = index;
            let ta = node_entry(a, o, inv_d, t_best);
            let tb = node_entry(b, o, inv_d, t_best);
            if ta < NO_HIT && tb < NO_HIT {
                if top < BVH_STACK {
                    bvh_stack[top] = select(a, b, ta <= tb);
                    top += 1u;
                }
                node = select(b, a, ta <= tb);
                descend = true;
            } else if ta < NO_HIT {
                node = a;
                descend = true;
            } else if tb < NO_HIT {
                node = b;
                descend = true;
            }
        }
        if descend {
            continue;
        }
        // The next subtree from the stack that is still nearer than the best hit.
        var next = false;
        while top > 0u {
            top -= 1u;
            let candidate = bvh_stack[top];
            if node_entry(candidate, o, inv_d, t_best) < NO_HIT {
                node = candidate;
                next = true;
                break;
            }
        }
        if !next {
            break;
        }
    }
    if found {
        let s = hit_t * lp.w / (1.0 - hit_t * lv.w);
        if s > 0.0 && s < hi {
            best.s = s;
            best.local = o + hit_t * d;
        }
    }
    return best;
}

// The normal and the material's colour and emission of a mesh hit (CurvedScene::intersect_mesh).
fn mesh_surface(hit: MeshHit, frame: mat4x4<f32>, material_override: u32, material_base: u32, point: vec4<f32>, v: vec4<f32>) -> Surface {
    let b = space.data.x + 8u * hit.triangle;
    let w = vec3<f32>(1.0 - hit.uv.x - hit.uv.y, hit.uv.x, hit.uv.y);
    let n = normalize(fdata(b + 3u).xyz * w.x + fdata(b + 4u).xyz * w.y + fdata(b + 5u).xyz * w.z);
    var local_normal = vec4<f32>(n, 0.0);
    if kappa() != 0.0 {
        local_normal.w = -dot(n, hit.local) / kappa();
    }
    var normal = unit_tangent(point, frame * local_normal);
    if form(normal, v) > 0.0 {
        normal = -normal;
    }
    var material = scene_data[b].w + material_base;
    if material_override != 0xffffffffu {
        material = material_override;
    }
    let m0 = fdata(space.data.y + 2u * material);
    let m1 = fdata(space.data.y + 2u * material + 1u);
    var albedo = m0.rgb;
#ifdef TEXTURES
    let tex = scene_data[space.data.y + 2u * material].w;
    if tex != 0xffffffffu {
        let uv01 = fdata(b + 6u);
        let uv2 = fdata(b + 7u).xy;
        let uv = uv01.xy * w.x + uv01.zw * w.y + uv2 * w.z;
        albedo *= sample_texture(tex, uv);
    }
#endif
    return Surface(normal, albedo, m1.rgb, m1.w);
}
#endif
