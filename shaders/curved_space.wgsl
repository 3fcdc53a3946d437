// Ray tracing inside a closed 3-manifold: the GPU twin of the f64 reference in src/trace
// (same algorithm, same shading, in f32). See DESIGN.md §1 and §3.
//
// Shader defs (set by src/render/gpu.rs, one pipeline per combination):
//   SPHERICAL | EUCLIDEAN | HYPERBOLIC   the geometry: only its formulas are compiled
//   CURVED                               set with SPHERICAL or HYPERBOLIC
//   GENERAL                              (benchmark) all three geometries and CURVED are set,
//                                        the geometry and counts are read at run time
//   FACE_COUNT, PARTNER_VECS             faces of the cell (partners packed 4 to a vec4<u32>)
//   BALLS + BALL_COUNT, TUBES + TUBE_COUNT   the object kinds present and their numbers
//   HIT_ID                               (benchmark) output what each ray met instead of a
//                                        colour: object, crossings, face path, how it ended
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
    // the eyes are swapped (0 or 1), unused.
    split: vec4<f32>,
    // Anaglyph matrices (left, right; upper 3×3) acting on linear RGB.
    anaglyph: array<mat4x4<f32>, 2>,
}

struct Shading {
    // Fog colour (rgb) and ambient fraction.
    fog: vec4<f32>,
    // Fog distance λ, cut-off distance λ ln(1/w), S(near_light), crossing budget.
    params: vec4<f32>,
}

struct Light {
    position: vec4<f32>,
    // Colour × power (rgb), unused.
    colour: vec4<f32>,
}

struct Ball {
    centre: vec4<f32>,
    // Albedo (rgb) and C(ρ) (the radius ρ itself in E³).
    colour: vec4<f32>,
}

struct Tube {
    a: vec4<f32>,
    // Unit tangent at a towards b.
    towards_b: vec4<f32>,
    // Albedo (rgb) and C(ρ)² (ρ² in E³).
    colour: vec4<f32>,
    // C(L), S(L) of the segment length L, unused, unused.
    length: vec4<f32>,
}

struct SpaceUniform {
    view: View,
    shading: Shading,
    light: Light,
    // Face covectors N_f: the cell is N_f·X ≤ 0.
    covectors: array<vec4<f32>, #{FACE_COUNT}>,
    // Face pairings g_f: a ray leaving through f comes back through partner(f).
    pairings: array<mat4x4<f32>, #{FACE_COUNT}>,
    partners: array<vec4<u32>, #{PARTNER_VECS}>,
#ifdef BALLS
    balls: array<Ball, #{BALL_COUNT}>,
#endif
#ifdef TUBES
    tubes: array<Tube, #{TUBE_COUNT}>,
#endif
#ifdef GENERAL
    // κ, face count, ball count, tube count.
    general: vec4<f32>,
#endif
}

@group(0) @binding(0) var<uniform> space: SpaceUniform;

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

#ifdef BALLS
// The first s in (0, hi) where the ray enters the ball, or NO_HIT.
fn hit_ball(ball: Ball, p: vec4<f32>, v: vec4<f32>, hi: f32) -> f32 {
    let c = ball.centre;
#ifdef EUCLIDEAN
    if kappa() == 0.0 {
        let d = p.xyz - c.xyz;
        let r = ball.colour.w;
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
        let cr = ball.colour.w;
        let sheet = kappa() * cr;
        let t = roots(b * b - kappa() * cr * cr, 2.0 * a * b, a * a - cr * cr);
        if in_range(t.x, hi) && (a + t.x * b) * sheet > 0.0 { return t.x; }
        if in_range(t.y, hi) && (a + t.y * b) * sheet > 0.0 { return t.y; }
        return NO_HIT;
    }
#endif
    return NO_HIT;
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

// ---------------------------------------------------------------------------------------
// Shading (trace::Shading::shade)

fn shade(point: vec4<f32>, normal: vec4<f32>, albedo: vec3<f32>, d: f32) -> vec3<f32> {
    let ambient = space.shading.fog.w;
    var lit = vec3<f32>(ambient);
    let light = space.light;
    let dl = distance(point, light.position);
    if dl > 0.0 {
        let l = tangent_towards(point, light.position);
        let lambert = max(form(normal, l), 0.0);
        let s = max(abs(s_of(dl)), space.shading.params.z);
        lit += (1.0 - ambient) * light.colour.rgb * (lambert / (s * s));
    }
    let surface = min(albedo * lit, vec3<f32>(1.0));
    let w = exp(-d / space.shading.params.x);
    return w * surface + (1.0 - w) * space.shading.fog.rgb;
}

fn partner(face: u32) -> u32 {
    return space.partners[face / 4u][face % 4u];
}

#ifdef HIT_ID
// What the ray met (trace::TracedRay::id): object index + 1 (balls, then tubes; 0 for
// none), crossings, a hash of the faces crossed, and how it ended (1 hit, 2 fog, 3 budget).
var<private> hit_id: vec4<u32>;
const FNV_OFFSET: u32 = 2166136261u;
const FNV_PRIME: u32 = 16777619u;
#endif

// The colour seen along one camera ray (trace::first_hit and trace::trace_pixel).
fn trace(start_point: vec4<f32>, start_tangent: vec4<f32>) -> vec3<f32> {
    let fog = space.shading.fog.rgb;
    let cutoff = space.shading.params.y;
    let budget = u32(space.shading.params.w);
    var p = start_point;
    var v = start_tangent;
    var travelled = 0.0;
    var skip = 0xffffffffu;
#ifdef HIT_ID
    var path = FNV_OFFSET;
    hit_id = vec4<u32>(0u, 0u, path, 3u);
#endif
    for (var crossings = 0u; crossings <= budget; crossings += 1u) {
        // The exit face: the smallest T = −(N·p)/(N·v) among faces with N·v > 0,
        // compared without dividing; the face just entered is skipped.
        var face = 0xffffffffu;
        var num = 0.0;
        var den = 1.0;
        for (var f = 0u; f < face_count(); f += 1u) {
            let n = space.covectors[f];
            let dn = dot(n, v);
            if f == skip || !(dn > 0.0) {
                continue;
            }
            let nm = max(-dot(n, p), 0.0);
            if face == 0xffffffffu || nm * den < num * dn {
                face = f;
                num = nm;
                den = dn;
            }
        }
        if face == 0xffffffffu {
            break;
        }
        // The nearest object before the exit face.
        var s_hit = num / den;
        var albedo = vec3<f32>(0.0);
        var foot = vec4<f32>(0.0);
        var hit = false;
#ifdef HIT_ID
        var object = 0u;
#endif
#ifdef BALLS
        for (var i = 0u; i < ball_count(); i += 1u) {
            let s = hit_ball(space.balls[i], p, v, s_hit);
            if s < s_hit {
                s_hit = s;
                albedo = space.balls[i].colour.rgb;
                foot = space.balls[i].centre;
                hit = true;
#ifdef HIT_ID
                object = i + 1u;
#endif
            }
        }
#endif
#ifdef TUBES
        var tube_hit = 0xffffffffu;
        for (var i = 0u; i < tube_count(); i += 1u) {
            let s = hit_tube(space.tubes[i], p, v, s_hit);
            if s < s_hit {
                s_hit = s;
                tube_hit = i;
                hit = true;
#ifdef HIT_ID
#ifdef BALLS
                object = ball_count() + i + 1u;
#else
                object = i + 1u;
#endif
#endif
            }
        }
#endif
        if hit {
            let point = project_point(p + s_hit * v);
#ifdef TUBES
            if tube_hit != 0xffffffffu {
                albedo = space.tubes[tube_hit].colour.rgb;
                foot = tube_foot(space.tubes[tube_hit], point);
            }
#endif
            let d = travelled + distance_from_ratio(s_hit, 1.0);
            if d >= cutoff {
#ifdef HIT_ID
                hit_id = vec4<u32>(0u, crossings, path, 2u);
#endif
                return fog;
            }
#ifdef HIT_ID
            hit_id = vec4<u32>(object, crossings, path, 1u);
#endif
            // Outward normal: away from the ball's centre or the tube's axis.
            let normal = unit_tangent(point, point - foot);
            return shade(point, normal, albedo, d);
        }
        if crossings == budget {
#ifdef HIT_ID
            hit_id = vec4<u32>(0u, crossings, path, 3u);
#endif
            break;
        }
        // Cross: exit point (N·v) p − (N·p) v, tangent κ (N·p) p + (N·v) v, then the pairing.
        let at_face = p * den + v * num;
        let along = p * (-kappa() * num) + v * den;
        let m = space.pairings[face];
        p = project_point(m * at_face);
        v = unit_tangent(p, m * along);
        travelled += distance_from_ratio(num, den);
#ifdef HIT_ID
        path = (path ^ (face + 1u)) * FNV_PRIME;
        hit_id = vec4<u32>(0u, crossings + 1u, path, 3u);
#endif
        if travelled >= cutoff {
#ifdef HIT_ID
            hit_id.w = 2u;
#endif
            return fog;
        }
        skip = partner(face);
    }
    return fog;
}

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
    return clamp(trace(p, v), vec3<f32>(0.0), vec3<f32>(1.0));
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
