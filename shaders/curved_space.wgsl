// Ray tracing inside a closed 3-manifold: the GPU twin of the f64 reference in src/trace
// (same algorithm, same shading, in f32). See docs/design.md §3 and §5.
//
// Shader defs (set by src/render/gpu.rs, one pipeline per combination):
//   SPHERICAL | EUCLIDEAN | HYPERBOLIC   the geometry: only its formulas are compiled
//   CURVED                               set with SPHERICAL or HYPERBOLIC
//   GENERAL                              (benchmark) all three geometries and CURVED are set,
//                                        the geometry and counts are read at run time
//   FACE_COUNT, PARTNER_VECS             faces of the cell (partners packed 4 to a vec4<u32>)
//   FACE_SLOTS                           face array length: FACE_COUNT, at least 1 (the
//                                        3-sphere has no face; its slot is never read)
//   STEP_CAP                             a cell reaching π/2 in S³: rays step at most π/4
//                                        (chart ratio 1) without crossing (NO_FACE)
//   BALLS + BALL_COUNT, TUBES + TUBE_COUNT   the object kinds present and their numbers
//   GLOBES + GLOBE_COUNT                 textured balls (equirectangular, spinning)
//   DISCS + DISC_COUNT                   flat discs
//   INSTANCES + INSTANCE_COUNT           placed meshes (src/scene/mesh.rs)
//   COLOUR_BY (1 crossings, 2 face, 3 holonomy + COLOUR_HOLONOMY)   a teaching view's tint
//   AVATAR                               the player's avatar mesh (frames in the view)
//   MESHES                               any mesh: the scene data buffer with the
//                                        hierarchies, triangles and materials
//   TEXTURES                             textures in the scene data buffer
//   SCENE_DATA                           set with MESHES or TEXTURES: the buffer is bound
//   LIGHTS + LIGHT_COUNT, LIGHT_IMAGES   point lights, each with up to LIGHT_IMAGES copies
//   HIT_ID                               (benchmark) output what each ray met instead of a
//                                        colour: object, crossings, face path, how it ended
//   CULLING + MASK_VECS                  balls and tubes carry face masks: a segment tests
//                                        only those whose faces it comes near
//                                        (src/scene/culling.rs)
//   WALLS                                the cell's walls with windows (src/scene/walls.rs)
//   STRAIGHTFORWARD                      (benchmark) a straightforward tracer of the same
//                                        walk instead, the benchmark's comparison: balls
//                                        only, arc length and trigonometry, plain pairings
//   STEREO_SPLIT                         two eyes in two halves of the view (src/stereo.rs)
//   ANAGLYPH                             two eyes traced per pixel and mixed by two matrices
//
// Points and tangents are 4-vectors with ⟨u,v⟩ = u.xyz·v.xyz + κ u.w v.w; a ray segment in
// the cell is X(s) ∝ p + s v, a straight line of the chart, so faces are planes (N·X = 0)
// and balls and tubes are quadrics in s.

struct View {
    // The eyes' frames, left then right (both the head's in mono). Columns: right, up, back,
    // position (an isometry of the model).
    frames: array<mat4x4<f32>, 2>,
    // Frustum tangents left, right, bottom, top: image point (u, v) looks along
    // x·right + y·up − back with x = mix(left, right, u), y = mix(top, bottom, v).
    lens: vec4<f32>,
    // Viewport origin and size (pixels).
    viewport: vec4<f32>,
    // Where the second half of a split view starts (x, y in pixels; 0: no split), whether
    // the eyes are swapped (0 or 1), the scene's time in seconds (the globes' spin).
    split: vec4<f32>,
    // Anaglyph matrices (left, right; upper 3×3) acting on linear RGB.
    anaglyph: array<mat4x4<f32>, 2>,
    // The avatar's images: frame and inverse, one pair each.
    avatar: array<mat4x4<f32>, 16>,
    // Avatar images in use, the distance from the eye within which avatar hits are passed
    // through, the root node of its mesh, unused.
    avatar_info: vec4<f32>,
}

struct Shading {
    // Fog colour (rgb) and ambient fraction.
    fog: vec4<f32>,
    // Fog distance λ, cut-off distance λ ln(1/w), S(near_light), crossing budget.
    params: vec4<f32>,
    // (1, 0, 0, 0): a one the compiler cannot see through (transform_compensated).
    exact: vec4<f32>,
}

#ifdef LIGHTS
struct Light {
    // Colour × power (rgb), number of images in use.
    colour: vec4<f32>,
    // The light and its images under the pairings: a point is lit by the nearest.
    images: array<vec4<f32>, #{LIGHT_IMAGES}>,
}
#endif

struct Ball {
    centre: vec4<f32>,
    // Albedo (rgb) and C(ρ) (the radius ρ itself in E³).
    colour: vec4<f32>,
    // Emission (rgb), unused.
    emission: vec4<f32>,
}

struct Globe {
    centre: vec4<f32>,
    // Albedo (rgb) and C(ρ) (ρ in E³).
    colour: vec4<f32>,
    // Emission (rgb), texture index.
    emission: vec4<f32>,
    // Spin in radians per second, unused ×3.
    spin: vec4<f32>,
    // The inverse of the globe's orientation frame.
    inverse: mat4x4<f32>,
}

struct Disc {
    centre: vec4<f32>,
    // Unit tangent at the centre.
    normal: vec4<f32>,
    // The plane's covector (P·X = 0).
    covector: vec4<f32>,
    // Albedo (rgb), radius.
    colour: vec4<f32>,
    emission: vec4<f32>,
}

struct Instance {
    frame: mat4x4<f32>,
    inverse: mat4x4<f32>,
    // Root node, material override (or 0xffffffff), material base (added to the mesh's own), unused.
    info: vec4<u32>,
}

struct Tube {
    a: vec4<f32>,
    // Unit tangent at a towards b.
    towards_b: vec4<f32>,
    // Albedo (rgb) and C(ρ)² (ρ² in E³).
    colour: vec4<f32>,
    // C(L), S(L) of the segment length L, unused, unused.
    length: vec4<f32>,
    emission: vec4<f32>,
}

struct SpaceUniform {
    view: View,
    shading: Shading,
    // Where the scene data buffer's parts start (in vec4): triangles, materials, texture
    // table, texels (the hierarchies' nodes start at 0).
    data: vec4<u32>,
#ifdef LIGHTS
    lights: array<Light, #{LIGHT_COUNT}>,
#endif
    // Face covectors N_f: the cell is N_f·X ≤ 0.
    covectors: array<vec4<f32>, #{FACE_SLOTS}>,
    // Face pairings g_f: a ray leaving through f comes back through partner(f).
    pairings: array<mat4x4<f32>, #{FACE_SLOTS}>,
    // What rounding g_f to f32 left out: the pairing is applied as hi + lo, compensated.
    pairings_lo: array<mat4x4<f32>, #{FACE_SLOTS}>,
    partners: array<vec4<u32>, #{PARTNER_VECS}>,
#ifdef WALLS
    // Per face: the covector scaled to a unit normal (N̂·X̂ = S(signed distance)).
    wall_units: array<vec4<f32>, #{FACE_SLOTS}>,
    // Per face: the panel's colour (rgb) and S(w) of the margin round its window.
    wall_colours: array<vec4<f32>, #{FACE_SLOTS}>,
    // Per face: the panel's opacity, 1 for a mirror (else 0), unused ×2.
    wall_looks: array<vec4<f32>, #{FACE_SLOTS}>,
    // The share of light below which a ray stops, unused ×3.
    wall_style: vec4<f32>,
#endif
#ifdef BALLS
    balls: array<Ball, #{BALL_COUNT}>,
#endif
#ifdef TUBES
    tubes: array<Tube, #{TUBE_COUNT}>,
#endif
#ifdef GLOBES
    globes: array<Globe, #{GLOBE_COUNT}>,
#endif
#ifdef DISCS
    discs: array<Disc, #{DISC_COUNT}>,
#endif
#ifdef INSTANCES
    instances: array<Instance, #{INSTANCE_COUNT}>,
#endif
#ifdef CULLING
    // Per face (four to a vec4): the bound on −N·X of the points of the model within the
    // culling distance of its plane.
    near: array<vec4<f32>, #{PARTNER_VECS}>,
    // Per ball, then per tube (four to a vec4): the faces (bits of faces 0–31) a segment
    // must come near to meet it.
    masks: array<vec4<u32>, #{MASK_VECS}>,
    // The object lists (u32, four to a vec4): for the balls, then the tubes, where each of
    // the CULL_BUCKETS buckets starts and where the last ends; then the object indices. An
    // object whose mask names two faces or more is in the bucket of one pair f < g of them
    // (g(g−1)/2 + f), the rest in the last bucket.
    lists: array<vec4<u32>, #{LIST_VECS}>,
#endif
#ifdef GENERAL
    // κ, face count, ball count, tube count.
    general: vec4<f32>,
#endif
}

@group(0) @binding(0) var<uniform> space: SpaceUniform;

#ifdef SCENE_DATA
// Hierarchy nodes (2 vec4 each), triangles (8), materials (2), the texture table (1 each)
// and texels (4 per vec4, RGBA8 sRGB), as written by src/render/gpu.rs.
@group(0) @binding(1) var<storage, read> scene_data: array<vec4<u32>>;
#endif

const F32_EPSILON: f32 = 1.1920929e-7;

#ifdef GENERAL
// The unspecialised variant (benchmark only): every geometry's formulas are compiled and the
// geometry and counts are read from the uniform at run time, over full-size arrays.
fn kappa() -> f32 { return space.general.x; }
fn face_count() -> u32 { return u32(space.general.y); }
fn ball_count() -> u32 { return u32(space.general.z); }
fn tube_count() -> u32 { return u32(space.general.w); }
#else
#ifdef SPHERICAL
const KAPPA: f32 = 1.0;
#endif
#ifdef EUCLIDEAN
const KAPPA: f32 = 0.0;
#endif
#ifdef HYPERBOLIC
const KAPPA: f32 = -1.0;
#endif
// Constants of the specialised shader (the branches on them fold away when compiled).
fn kappa() -> f32 { return KAPPA; }
fn face_count() -> u32 { return #{FACE_COUNT}u; }
#ifdef BALLS
fn ball_count() -> u32 { return #{BALL_COUNT}u; }
#endif
#ifdef TUBES
fn tube_count() -> u32 { return #{TUBE_COUNT}u; }
#endif
#endif

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

#ifdef SCENE_DATA
fn fdata(i: u32) -> vec4<f32> {
    return bitcast<vec4<f32>>(scene_data[i]);
}
#endif

#ifdef TEXTURES
fn srgb_channel_to_linear(c: vec3<f32>) -> vec3<f32> {
    let low = c / 12.92;
    let high = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, c <= vec3<f32>(0.04045));
}

// The linear colour of texel (x, y) of texture `tex` (Texture::texel).
fn texel(tex: u32, x: u32, y: u32) -> vec3<f32> {
    let info = scene_data[space.data.z + tex];
    let i = info.x + y * info.y + x;
    let word = scene_data[space.data.w + i / 4u][i % 4u];
    let c = vec3<f32>(f32(word & 255u), f32((word >> 8u) & 255u), f32((word >> 16u) & 255u));
    return srgb_channel_to_linear(c / 255.0);
}

// Bilinear between texel centres, u wrapping, v clamped (Texture::sample).
fn sample_texture(tex: u32, uv: vec2<f32>) -> vec3<f32> {
    let info = scene_data[space.data.z + tex];
    let w = f32(info.y);
    let h = f32(info.z);
    let x = (uv.x - floor(uv.x)) * w - 0.5;
    let y = clamp(clamp(uv.y, 0.0, 1.0) * h - 0.5, 0.0, h - 1.0);
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let xa = u32(x0 - w * floor(x0 / w));
    let xb = u32((x0 + 1.0) - w * floor((x0 + 1.0) / w));
    let ya = u32(y0);
    let yb = u32(min(y0 + 1.0, h - 1.0));
    let top = mix(texel(tex, xa, ya), texel(tex, xb, ya), fx);
    let bottom = mix(texel(tex, xa, yb), texel(tex, xb, yb), fx);
    return mix(top, bottom, fy);
}
#endif

#ifdef GLOBES
// Texture coordinates of a globe's point x (BallTexture::uv).
fn globe_uv(globe: Globe, x: vec4<f32>) -> vec2<f32> {
    let local = globe.inverse * x;
    let d = normalize(local.xyz);
    let turn = 6.283185307179586;
    let longitude = atan2(d.x, d.z) - globe.spin.x * space.view.split.w;
    let u = longitude / turn + 0.5;
    return vec2<f32>(u - floor(u), acos(clamp(d.y, -1.0, 1.0)) / 3.141592653589793);
}
#endif

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
    return Surface(normal, albedo, m1.rgb);
}
#endif

// ---------------------------------------------------------------------------------------
// Shading (trace::Shading::shade)

#ifdef COLOUR_BY
// The teaching views (Rust: `scene::ColourBy`): the tint of the surface being shaded.
var<private> colour_tint: vec3<f32>;

// Distinct colours (Rust: `scene::palette`).
fn palette(i: u32) -> vec3<f32> {
    let h = fract(f32(i) * 0.618034 + 0.08) * 6.0;
    let x = 1.0 - abs(h % 2.0 - 1.0);
    var c = vec3<f32>(1.0, 0.0, x);
    switch u32(h) {
        case 0u: { c = vec3<f32>(1.0, x, 0.0); }
        case 1u: { c = vec3<f32>(x, 1.0, 0.0); }
        case 2u: { c = vec3<f32>(0.0, 1.0, x); }
        case 3u: { c = vec3<f32>(0.0, x, 1.0); }
        case 4u: { c = vec3<f32>(x, 0.0, 1.0); }
        default: {}
    }
    return c * 0.75 + vec3<f32>(0.2);
}

// A surface's lit colour as its brightness times the tint (Rust: `ColourBy::recolour`).
fn recolour(tint: vec3<f32>, surface: vec3<f32>) -> vec3<f32> {
    let lum = min(dot(surface, vec3<f32>(0.2126, 0.7152, 0.0722)), 1.0);
    return tint * (0.25 + 0.75 * lum);
}

#ifdef COLOUR_HOLONOMY
// The 30° bin of the rotation of h about the origin once the translation to h·origin is
// taken off, plus 7 when h is mirrored (Rust: `scene::holonomy_bin`).
fn holonomy_bin(h: mat4x4<f32>) -> u32 {
    let q = h[3];
    let qs = q.xyz;
    let a3 = mat3x3<f32>(h[0].xyz, h[1].xyz, h[2].xyz);
    let b = vec3<f32>(h[0].w, h[1].w, h[2].w);
    var m = a3;
    if kappa() != 0.0 {
        let k = kappa() / (1.0 + q.w);
        let outer_qq = mat3x3<f32>(qs * qs.x, qs * qs.y, qs * qs.z);
        let outer_qb = mat3x3<f32>(qs * b.x, qs * b.y, qs * b.z);
        let i3 = mat3x3<f32>(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 0.0, 1.0));
        m = (i3 - outer_qq * k) * a3 - outer_qb;
    }
    let mirrored = determinant(m) < 0.0;
    if mirrored {
        m = m * -1.0;
    }
    let trace = m[0].x + m[1].y + m[2].z;
    let angle = acos(clamp((trace - 1.0) / 2.0, -1.0, 1.0));
    let bin = min(u32(round(angle / (3.14159265 / 6.0))), 6u);
    return bin + select(0u, 7u, mirrored);
}
#endif

// The tint of a surface after `crossings` crossings, the last through `last_face`, in the
// copy `held` of the cell (Rust: `ColourBy::tint`).
fn colour_by_tint(crossings: u32, last_face: u32, held: mat4x4<f32>) -> vec3<f32> {
    let mode = #{COLOUR_BY}u;
    if mode == 1u {
        return palette(crossings);
    }
    if mode == 2u {
        if last_face == 0xffffffffu {
            return vec3<f32>(1.0);
        }
        return palette(last_face);
    }
#ifdef COLOUR_HOLONOMY
    let k = holonomy_bin(held);
    if k != 0u {
        return palette(k);
    }
#endif
    return vec3<f32>(1.0);
}
#endif

fn shade(point: vec4<f32>, normal: vec4<f32>, albedo: vec3<f32>, emission: vec3<f32>, d: f32) -> vec3<f32> {
    let ambient = space.shading.fog.w;
    var lit = vec3<f32>(ambient);
#ifdef LIGHTS
    for (var i = 0u; i < #{LIGHT_COUNT}u; i += 1u) {
        let light = space.lights[i];
        // The nearest of the light's images.
        var at = light.images[0];
        var dl = distance(point, at);
        for (var k = 1u; k < u32(light.colour.w); k += 1u) {
            let q = light.images[k];
            let dq = distance(point, q);
            if dq < dl {
                dl = dq;
                at = q;
            }
        }
        if dl > 0.0 {
            let l = tangent_towards(point, at);
            let lambert = max(form(normal, l), 0.0);
            let s = max(abs(s_of(dl)), space.shading.params.z);
            lit += (1.0 - ambient) * light.colour.rgb * (lambert / (s * s));
        }
    }
#endif
    var surface = min(albedo * lit + emission, vec3<f32>(1.0));
#ifdef COLOUR_BY
    surface = recolour(colour_tint, surface);
#endif
    let w = exp(-d / space.shading.params.x);
    return w * surface + (1.0 - w) * space.shading.fog.rgb;
}

// The exit of a step without crossing (STEP_CAP).
const NO_FACE: u32 = 0xfffffffeu;

fn partner(face: u32) -> u32 {
    return space.partners[face / 4u][face % 4u];
}

#ifdef HIT_ID
// What the ray met (trace::TracedRay::id): object index + 1 (balls, then tubes; 0 for
// none), crossings, a hash of the faces crossed, and how it ended (1 hit, 2 fog, 3 budget).
var<private> hit_id: vec4<u32>;
const FNV_OFFSET: u32 = 2166136261u;

// The object's place in the GPU's lists (gpu::gpu_object_indices): balls, tubes, globes,
// discs, mesh instances, then the avatar's images.
fn object_number(kind: u32, index: u32) -> u32 {
    var base = 0u;
    var counts = array<u32, 5>(0u, 0u, 0u, 0u, 0u);
#ifdef BALLS
    counts[0] = ball_count();
#endif
#ifdef TUBES
    counts[1] = tube_count();
#endif
#ifdef GLOBES
    counts[2] = #{GLOBE_COUNT}u;
#endif
#ifdef DISCS
    counts[3] = #{DISC_COUNT}u;
#endif
#ifdef INSTANCES
    counts[4] = #{INSTANCE_COUNT}u;
#endif
    for (var k = 1u; k < kind; k += 1u) {
        base += counts[k - 1u];
    }
    return base + index;
}
const FNV_PRIME: u32 = 16777619u;
#endif

// A surface point's outward unit normal, albedo and emission.
struct Surface {
    normal: vec4<f32>,
    albedo: vec3<f32>,
    emission: vec3<f32>,
}

// A point of the model and a unit tangent there (Rust: `geometry::Ray`).
struct Ray {
    point: vec4<f32>,
    tangent: vec4<f32>,
}

// Where a ray leaves the cell: the face and the chart ratio T = num/den of the exit point
// (Rust: `space::walk::Exit`). face is 0xffffffff where no face is ahead.
struct Exit {
    face: u32,
    num: f32,
    den: f32,
}

#ifdef CULLING
// Per face, the residual −N·p at the segment's start and its rate N·v along it (−N·X(s) =
// start − s·rate), kept by exit_face so that the culling reads them instead of forming the
// dot products again.
var<private> face_start: array<f32, #{FACE_SLOTS}>;
var<private> face_rate: array<f32, #{FACE_SLOTS}>;
#endif

// The exit face: the smallest T = −(N·p)/(N·v) among faces with N·v > 0, compared without
// dividing; the face just entered (`skip`) is passed over (Rust: `CellWalker::exit`).
fn exit_face(ray: Ray, skip: u32) -> Exit {
    var exit = Exit(0xffffffffu, 0.0, 1.0);
    for (var f = 0u; f < face_count(); f += 1u) {
        let n = space.covectors[f];
        let dn = dot(n, ray.tangent);
        if f == skip || !(dn > 0.0) {
            continue;
        }
        let nm = max(-dot(n, ray.point), 0.0);
        if exit.face == 0xffffffffu || nm * exit.den < exit.num * dn {
            exit = Exit(f, nm, dn);
        }
    }
#ifdef STEP_CAP
    // No face within π/4: a step of π/4 without crossing (Rust: `CellWalker::step_cap`).
    if exit.face == 0xffffffffu || exit.num > exit.den {
        exit = Exit(NO_FACE, 1.0, 1.0);
    }
#endif
    return exit;
}

// s + e = a + b exactly (Knuth's two-sum: additions only). `one` is 1 at run time but not to
// the compiler: multiplying by it keeps an optimiser from rewriting (a + b) − a as b, which
// is true of real numbers and would make the error term zero.
fn two_sum(a: vec4<f32>, b: vec4<f32>, one: f32) -> array<vec4<f32>, 2> {
    let s = (a + b) * one;
    let bb = (s - a) * one;
    return array<vec4<f32>, 2>(s, (a - (s - bb)) + (b - bb));
}

// (hi + lo) x with the products and sums of hi x compensated (Ogita–Rump–Oishi Dot2, four
// rows at once): as accurate as twice the precision rounded once (Rust:
// `Vector4::transform_compensated`). A pairing's entries reach e^(2r) while the points it
// moves have size e^r, so the plain product cancels and loses a digit in H³. fma gives the
// products' rounding errors; where a driver does not fuse it, the error terms are zero and
// this is the plain product plus lo x, no worse than before.
fn transform_compensated(hi: mat4x4<f32>, lo: mat4x4<f32>, x: vec4<f32>) -> vec4<f32> {
    // Flat pairings have small entries: nothing cancels (Rust: `CellWalker::apply_pairing`).
    if kappa() == 0.0 {
        return hi * x;
    }
    let one = space.shading.exact.x;
    var p = hi[0] * x.x * one;
    var s = fma(hi[0], vec4<f32>(x.x), -p) + lo[0] * x.x;
    for (var j = 1; j < 4; j += 1) {
        let h = hi[j] * x[j] * one;
        let r = fma(hi[j], vec4<f32>(x[j]), -h);
        let sum = two_sum(p, h, one);
        p = sum[0];
        s += (sum[1] + r) + lo[j] * x[j];
    }
    return p + s;
}

// Through the exit face: exit point (N·v) p − (N·p) v, tangent κ (N·p) p + (N·v) v, then the
// face's pairing (compensated), both projected back onto the model (Rust: `CellWalker::cross`).
fn cross_face(ray: Ray, exit: Exit) -> Ray {
    let at_face = ray.point * exit.den + ray.tangent * exit.num;
    let along = ray.point * (-kappa() * exit.num) + ray.tangent * exit.den;
#ifdef STEP_CAP
    if exit.face == NO_FACE {
        let moved = project_point(at_face);
        return Ray(moved, unit_tangent(moved, along));
    }
#endif
    let hi = space.pairings[exit.face];
    let lo = space.pairings_lo[exit.face];
    let point = project_point(transform_compensated(hi, lo, at_face));
    return Ray(point, unit_tangent(point, transform_compensated(hi, lo, along)));
}

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
    var surface = Surface(vec4<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
#ifdef BALLS
    if hit.kind == 1u {
        let ball = space.balls[hit.index];
        surface = Surface(unit_tangent(point, point - ball.centre), ball.colour.rgb, ball.emission.rgb);
    }
#endif
#ifdef TUBES
    if hit.kind == 2u {
        let tube = space.tubes[hit.index];
        surface = Surface(unit_tangent(point, point - tube_foot(tube, point)), tube.colour.rgb, tube.emission.rgb);
    }
#endif
#ifdef GLOBES
    if hit.kind == 3u {
        let globe = space.globes[hit.index];
        var albedo = globe.colour.rgb;
#ifdef TEXTURES
        albedo *= sample_texture(u32(globe.emission.w), globe_uv(globe, point));
#endif
        surface = Surface(unit_tangent(point, point - globe.centre), albedo, globe.emission.rgb);
    }
#endif
#ifdef DISCS
    if hit.kind == 4u {
        let disc = space.discs[hit.index];
        var normal = unit_tangent(point, disc.normal);
        if form(normal, v) > 0.0 {
            normal = -normal;
        }
        surface = Surface(normal, disc.colour.rgb, disc.emission.rgb);
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

#ifdef WALLS
// What the walls crossed so far added and let through (Rust: `scene::Veil`).
var<private> veil_colour: vec3<f32>;
var<private> veil_through: f32;

// The wall a ray meets leaving through `exit` at distance `d` from the eye, added to the veil
// (Rust: `WallPanels::cross`): on the panel where some other face g is nearer than
// S(w)·sin θ_fg, lit by the angle of incidence, fogged, blended by its opacity.
fn cross_wall(ray: Ray, exit: Exit, d: f32) {
    let f = exit.face;
    let at_face = ray.point * exit.den + ray.tangent * exit.num;
    var x = at_face / length(at_face);
#ifdef EUCLIDEAN
    x = at_face / at_face.w;
#endif
#ifdef HYPERBOLIC
    x = at_face / sqrt(-form(at_face, at_face));
#endif
    let unit = space.wall_units[f];
    let margin = space.wall_colours[f].w;
    var on_panel = false;
    for (var g = 0u; g < face_count(); g += 1u) {
        let other = space.wall_units[g];
        let c = form(unit, other);
        let sine = sqrt(max(1.0 - c * c, 0.0));
        if g != f && -dot(other, x) < margin * sine {
            on_panel = true;
        }
    }
    if !on_panel {
        return;
    }
    let along = ray.point * (-kappa() * exit.num) + ray.tangent * exit.den;
    let facing = min(abs(dot(unit, along)) / sqrt(form(along, along)), 1.0);
    let look = space.wall_looks[f];
    let light = select(0.55 + 0.45 * facing, 0.55 + 0.45 * (1.0 - facing), look.y > 0.5);
    let lit = min(space.wall_colours[f].rgb * light, vec3<f32>(1.0));
    let w = exp(-d / space.shading.params.x);
    let seen = w * lit + (1.0 - w) * space.shading.fog.rgb;
    veil_colour += veil_through * look.x * seen;
    veil_through *= 1.0 - look.x;
}
#endif

#ifdef STRAIGHTFORWARD
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
        for (var f = 0u; f < face_count(); f += 1u) {
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
// One camera ray's colour: walk the cell, nearest object hit against exit face, cross by
// pairings until the fog cut-off or the crossing budget (Rust: `trace::first_hit` and
// `colour_of`).
fn trace(start_point: vec4<f32>, start_tangent: vec4<f32>) -> vec3<f32> {
    let fog = space.shading.fog.rgb;
    let cutoff = space.shading.params.y;
    let budget = u32(space.shading.params.w);
    var ray = Ray(start_point, start_tangent);
    var travelled = 0.0;
    var skip = 0xffffffffu;
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
    for (var crossings = 0u; crossings <= budget; crossings += 1u) {
        let exit = exit_face(ray, skip);
        if exit.face == 0xffffffffu {
            break;
        }
        let hit = intersect_scene(ray, exit.num / exit.den, travelled);
        if hit.kind != 0u {
            let point = project_point(ray.point + hit.s * ray.tangent);
            let d = travelled + distance_from_ratio(hit.s, 1.0);
            if d >= cutoff {
#ifdef HIT_ID
                hit_id = vec4<u32>(0u, crossings, path, 2u);
#endif
                return fog;
            }
#ifdef HIT_ID
            hit_id = vec4<u32>(object_number(hit.kind, hit.index) + 1u, crossings, path, 1u);
#endif
            let surface = surface_at(hit, point, ray.tangent);
#ifdef COLOUR_BY
            colour_tint = colour_by_tint(crossings, last_face, held);
#endif
            return shade(point, surface.normal, surface.albedo, surface.emission, d);
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
                return fog;
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
        if travelled >= cutoff {
#ifdef HIT_ID
            hit_id.w = 2u;
#endif
            return fog;
        }
        skip = select(partner(exit.face), 0xffffffffu, exit.face == NO_FACE);
    }
    return fog;
}
#endif

// ---------------------------------------------------------------------------------------
// Entry points: one triangle covering the viewport.

struct VertexOutput {
    @builtin(position) position: vec4<f32>,
}

@vertex
fn vertex(@builtin(vertex_index) index: u32) -> VertexOutput {
    let uv = vec2<f32>(f32(index >> 1u), f32(index & 1u)) * 2.0;
    return VertexOutput(vec4<f32>(uv * vec2<f32>(2.0, -2.0) + vec2<f32>(-1.0, 1.0), 0.0, 1.0));
}

// The stored value is the sRGB encoding of what the fragment returns: return the decoded
// colour so that the 8-bit image holds the same values as the CPU reference's PNG.
fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    let low = c / 12.92;
    let high = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, c <= vec3<f32>(0.04045));
}

// The colour seen by eye `eye` through image point `uv` of its picture (ViewLayout::ray).
fn eye_colour(eye: u32, uv: vec2<f32>) -> vec3<f32> {
    let lens = space.view.lens;
    let px = mix(lens.x, lens.y, uv.x);
    let py = mix(lens.w, lens.z, uv.y);
    let f = space.view.frames[eye];
    let p = f[3];
    let v = unit_tangent(p, px * f[0] + py * f[1] - f[2]);
#ifdef WALLS
    veil_colour = vec3<f32>(0.0);
    veil_through = 1.0;
    let behind = trace(p, v);
    return clamp(veil_colour + veil_through * behind, vec3<f32>(0.0), vec3<f32>(1.0));
#else
    return clamp(trace(p, v), vec3<f32>(0.0), vec3<f32>(1.0));
#endif
}

// The linear colour seen through a fragment of the viewport (ViewLayout::eye_at and
// rays_at); the target stores its sRGB encoding, the value the CPU reference writes.
fn pixel_colour(position: vec4<f32>) -> vec3<f32> {
    let view = space.view;
    let pixel = position.xy - view.viewport.xy;
    var size = view.viewport.zw;
#ifdef STEREO_SPLIT
    let split = view.split.xy;
    let second = (split.x > 0.0 && pixel.x >= split.x) || (split.y > 0.0 && pixel.y >= split.y);
    let half = select(0u, 1u, second);
    let local = pixel - f32(half) * split;
    size = select(size, split, split > vec2<f32>(0.0));
    return srgb_to_linear(eye_colour(half ^ u32(view.split.z), local / size));
#else
#ifdef ANAGLYPH
    let uv = pixel / size;
    let left = srgb_to_linear(eye_colour(0u, uv));
    let right = srgb_to_linear(eye_colour(1u, uv));
    let mixed = (view.anaglyph[0] * vec4<f32>(left, 0.0)).rgb
        + (view.anaglyph[1] * vec4<f32>(right, 0.0)).rgb;
    return clamp(mixed, vec3<f32>(0.0), vec3<f32>(1.0));
#else
    return srgb_to_linear(eye_colour(0u, pixel / size));
#endif
#endif
}

#ifdef HIT_ID
@fragment
fn fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<u32> {
    _ = pixel_colour(position);
    return hit_id;
}
#else
@fragment
fn fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(pixel_colour(position), 1.0);
}
#endif
