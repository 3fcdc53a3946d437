// Nil (shader def NIL): the GPU twin of the CPU reference in src/trace/nil and the maths of
// src/space/nil, in f32. A ray is a chart point of the Heisenberg group and a unit body
// velocity in the frame E1 = ∂x − (y/2)∂z, E2 = ∂y + (x/2)∂z, E3 = ∂z. It flows in closed
// form, leaves the box |x|, |y| ≤ ½, |z| ≤ h at the first face solved for (the sides in
// closed form, the top and bottom bracketed between the height's turning points), comes back
// by the lattice element of that face, and meets metric balls, fibre tubes and swept discs
// by steps safe by a Lipschitz bound, refined by bisection. Light comes along the shortest
// geodesic to each image of the lamp.
#define_import_path curved_spaces::nil

#import curved_spaces::layout::{space}

const NIL_PI: f32 = 3.14159265358979;
const NIL_NONE: f32 = -1.0;
const NIL_FAR: f32 = 3.0e38;

struct NilRay {
    p: vec3<f32>,
    v: vec3<f32>,
}

// Half the box's height.
fn nil_h() -> f32 {
    return space.nil_box.x;
}

// The group product p·q (q moved by the left translation by p).
fn nil_product(p: vec3<f32>, q: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(p.x + q.x, p.y + q.y, p.z + q.z + 0.5 * (p.x * q.y - p.y * q.x));
}

// Σ (−u²)ᵏ/(n+2k)! for n = 1, 2, 3 (Rust: `flow_terms`), as polynomials in w = −u² (eight
// terms reach f32's last bit for |u| < 2; no loop, so no iteration cap of a driver binds).
fn nil_series(n: u32, u: f32) -> f32 {
    let w = -u * u;
    switch n {
        case 1u: { return (((((((7.647163732e-13) * w + 1.605904384e-10) * w + 2.505210839e-08) * w + 2.755731922e-06) * w + 1.984126984e-04) * w + 8.333333333e-03) * w + 1.666666667e-01) * w + 1.000000000e+00; }
        case 2u: { return (((((((4.779477332e-14) * w + 1.147074560e-11) * w + 2.087675699e-09) * w + 2.755731922e-07) * w + 2.480158730e-05) * w + 1.388888889e-03) * w + 4.166666667e-02) * w + 5.000000000e-01; }
        default: { return (((((((2.811457254e-15) * w + 7.647163732e-13) * w + 1.605904384e-10) * w + 2.505210839e-08) * w + 2.755731922e-06) * w + 1.984126984e-04) * w + 8.333333333e-03) * w + 1.666666667e-01; }
    }
}

// (S, C, Z) of the flow for the rate c at time t: sin(ct)/c, (1 − cos ct)/c, (ct − sin ct)/c².
fn nil_flow_terms(c: f32, t: f32) -> vec3<f32> {
    let u = c * t;
    if abs(u) < 2.0 {
        return vec3<f32>(t * nil_series(1u, u), t * u * nil_series(2u, u), t * t * u * nil_series(3u, u));
    }
    let s = sin(u);
    let sh = sin(0.5 * u);
    return vec3<f32>(s / c, 2.0 * sh * sh / c, (u - s) / (c * c));
}

fn nil_flow(r: NilRay, t: f32) -> NilRay {
    let terms = nil_flow_terms(r.v.z, t);
    let u = r.v.z * t;
    let cu = cos(u);
    let su = sin(u);
    let moved = vec3<f32>(
        r.v.x * terms.x - r.v.y * terms.y,
        r.v.y * terms.x + r.v.x * terms.y,
        r.v.z * t + 0.5 * (r.v.x * r.v.x + r.v.y * r.v.y) * terms.z,
    );
    return NilRay(nil_product(r.p, moved), vec3<f32>(r.v.x * cu - r.v.y * su, r.v.x * su + r.v.y * cu, r.v.z));
}

// ---------------------------------------------------------------------------------------
// Exits (Rust: `space::nil::exit`).

fn nil_atan_over(tau: f32) -> f32 {
    if tau == 0.0 {
        return 1.0;
    }
    return atan(tau) / tau;
}

// The first time ahead of a crossing whose half-angle tangent is tau; `direct` (where
// `has_direct`) is the near root's time without a division by c. NIL_FAR: none.
fn nil_time_of(tau: f32, direct: f32, has_direct: bool, c: f32) -> f32 {
    if c == 0.0 {
        if has_direct && direct >= 0.0 {
            return direct;
        }
        return NIL_FAR;
    }
    let psi = atan(tau);
    let behind = select((psi > 0.0), (psi < 0.0), (c > 0.0));
    if behind {
        let turn = select(-NIL_PI, NIL_PI, (c > 0.0));
        return 2.0 * (psi + turn) / c;
    }
    if has_direct {
        return direct;
    }
    return 2.0 * psi / c;
}

// The first time t ≥ 0 at which the ray meets the vertical plane n·(x, y) = r; NIL_NONE.
fn nil_vertical_exit(ray: NilRay, n: vec2<f32>, r: f32) -> f32 {
    let c = ray.v.z;
    let alpha = n.x * ray.v.x + n.y * ray.v.y;
    let beta = -n.x * ray.v.y + n.y * ray.v.x;
    let d = max(r - dot(n, ray.p.xy), 0.0);
    let cd = c * d;
    let a2 = 2.0 * beta - cd;
    let disc = alpha * alpha + cd * a2;
    if !(disc >= 0.0) {
        return NIL_NONE;
    }
    let root = sqrt(disc);
    let q = select(root - alpha, -(alpha + root), (alpha >= 0.0));
    var has = false;
    var best = 0.0;
    let leaves_at_start = d == 0.0 && alpha <= 0.0;
    if q != 0.0 && !leaves_at_start {
        let tau = -cd / q;
        let t = nil_time_of(tau, -2.0 * d / q * nil_atan_over(tau), true, c);
        if t != NIL_FAR {
            has = true;
            best = t;
        }
    } else if q != 0.0 && c != 0.0 {
        let t = nil_time_of(-cd / q, 0.0, false, c);
        if t > 0.0 {
            has = true;
            best = t;
        }
    }
    if a2 != 0.0 && c != 0.0 {
        let t = nil_time_of(q / a2, 0.0, false, c);
        best = select(t, min(best, t), has);
        has = true;
    }
    if has && best >= 0.0 && best < NIL_FAR {
        return best;
    }
    return NIL_NONE;
}

// The height at time t and its rate, less h in x.
fn nil_height(ray: NilRay, t: f32, h: f32) -> vec2<f32> {
    let terms = nil_flow_terms(ray.v.z, t);
    let u = ray.v.z * t;
    let cu = cos(u);
    let su = sin(u);
    let x0 = ray.v.x * terms.x - ray.v.y * terms.y;
    let y0 = ray.v.y * terms.x + ray.v.x * terms.y;
    let vx = ray.v.x * cu - ray.v.y * su;
    let vy = ray.v.x * su + ray.v.y * cu;
    let a2 = ray.v.x * ray.v.x + ray.v.y * ray.v.y;
    let z = ray.p.z + ray.v.z * t + 0.5 * a2 * terms.z + 0.5 * (ray.p.x * y0 - ray.p.y * x0);
    let rate = ray.v.z + 0.5 * a2 * terms.y + 0.5 * (ray.p.x * vy - ray.p.y * vx);
    return vec2<f32>(z - h, rate);
}

// The root of the height less h in (lo, hi), where it changes sign once (Newton's steps
// inside the bracket, bisection otherwise).
fn nil_height_root(ray: NilRay, h: f32, lo_in: f32, hi_in: f32, rising: bool) -> f32 {
    var lo = lo_in;
    var hi = hi_in;
    var t = 0.5 * (lo + hi);
    for (var i = 0u; i < 80u; i += 1u) {
        let f = nil_height(ray, t, h);
        if f.x == 0.0 {
            return t;
        }
        if (f.x < 0.0) == rising {
            lo = t;
        } else {
            hi = t;
        }
        let newton = t - f.x / f.y;
        var next = 0.5 * (lo + hi);
        if f.y != 0.0 && newton > lo && newton < hi {
            next = newton;
        }
        if next == t || !(lo < hi) {
            break;
        }
        t = next;
    }
    return t;
}

// The first time in (0, before] at which the ray meets z = h; NIL_NONE.
fn nil_horizontal_exit(ray: NilRay, h: f32, before: f32) -> f32 {
    let f0 = nil_height(ray, 0.0, h);
    let c = ray.v.z;
    if c == 0.0 {
        if f0.y == 0.0 || ((f0.x > 0.0) == (f0.y > 0.0) && f0.x != 0.0) {
            return NIL_NONE;
        }
        let t = -f0.x / f0.y;
        return select(NIL_NONE, t, (t > 0.0) && (t <= before));
    }
    if ray.v.x == 0.0 && ray.v.y == 0.0 {
        let t = -f0.x / c;
        return select(NIL_NONE, t, (t > 0.0) && (t <= before));
    }
    let a2 = ray.v.x * ray.v.x + ray.v.y * ray.v.y;
    let k0 = c + 0.5 * a2 / c;
    let k1 = -0.5 * a2 / c + 0.5 * (ray.p.x * ray.v.y - ray.p.y * ray.v.x);
    let k2 = 0.5 * (ray.p.x * ray.v.x + ray.p.y * ray.v.y);
    let rho = sqrt(k1 * k1 + k2 * k2);
    var end = before;
    if before >= NIL_FAR {
        let turn = 2.0 * NIL_PI / abs(c);
        let swing = 2.0 * rho / abs(c);
        end = select((abs(f0.x) + swing) / abs(k0) + turn, turn, k0 == 0.0);
    }
    // The turning points θ = φ ± spread (+ turns), as two sequences of times merged in order.
    let period = 2.0 * NIL_PI / abs(c);
    var next = vec2<f32>(NIL_FAR, NIL_FAR);
    if rho > 0.0 && abs(k0 / rho) <= 1.0 {
        let phi = atan2(k2, k1);
        let cos_arg = -k0 / rho;
        let spread = atan2(sqrt(max(1.0 - cos_arg * cos_arg, 0.0)), cos_arg);
        for (var j = 0u; j < 2u; j += 1u) {
            var t = select(phi - spread, phi + spread, j == 0u) / c;
            t += period * ceil(-t / period);
            for (var g = 0u; g < 4u && t <= 0.0; g += 1u) {
                t += period;
            }
            next[j] = t;
        }
    }
    var lo = 0.0;
    var f_lo = f0.x;
    for (var i = 0u; i < 130u; i += 1u) {
        var hi = end;
        var which = 2u;
        if next.x < end && next.x <= next.y {
            hi = next.x;
            which = 0u;
        } else if next.y < end {
            hi = next.y;
            which = 1u;
        }
        let f_hi = nil_height(ray, hi, h).x;
        let straddles = (f_lo <= 0.0 && f_hi >= 0.0) || (f_lo >= 0.0 && f_hi <= 0.0);
        let from_the_plane = lo == 0.0 && f_lo == 0.0;
        if straddles && !from_the_plane {
            let root = nil_height_root(ray, h, lo, hi, f_lo < 0.0);
            if root > 0.0 {
                return root;
            }
        }
        if which == 2u {
            break;
        }
        next[which] += period;
        lo = hi;
        f_lo = f_hi;
    }
    return NIL_NONE;
}

// The first exit: (face, time); face 6 for a degenerate ray. Faces x = ½, x = −½, y = ½,
// y = −½, z = h, z = −h.
fn nil_exit(ray: NilRay) -> vec2<f32> {
    var face = 6u;
    var best = NIL_FAR;
    let normals = array<vec2<f32>, 4>(
        vec2<f32>(1.0, 0.0), vec2<f32>(-1.0, 0.0), vec2<f32>(0.0, 1.0), vec2<f32>(0.0, -1.0),
    );
    for (var f = 0u; f < 4u; f += 1u) {
        let t = nil_vertical_exit(ray, normals[f], 0.5);
        if t >= 0.0 && t < best {
            best = t;
            face = f;
        }
    }
    for (var f = 4u; f < 6u; f += 1u) {
        let t = nil_horizontal_exit(ray, select(-nil_h(), nil_h(), f == 4u), best);
        if t >= 0.0 && t < best {
            best = t;
            face = f;
        }
    }
    return vec2<f32>(f32(face), best);
}

// The ray carried through `face` at time t (Rust: `NilWalker::through`).
fn nil_through(ray: NilRay, face: u32, t: f32) -> NilRay {
    let h = nil_h();
    var at = nil_flow(ray, t);
    var generator = vec3<f32>(0.0);
    switch face {
        case 0u: { at.p.x = 0.5; generator = vec3<f32>(-1.0, 0.0, 0.0); }
        case 1u: { at.p.x = -0.5; generator = vec3<f32>(1.0, 0.0, 0.0); }
        case 2u: { at.p.y = 0.5; generator = vec3<f32>(0.0, -1.0, 0.0); }
        case 3u: { at.p.y = -0.5; generator = vec3<f32>(0.0, 1.0, 0.0); }
        case 4u: { at.p.z = h; }
        default: { at.p.z = -h; }
    }
    var g = vec3<f32>(0.0, 0.0, select(2.0 * h, -2.0 * h, face == 4u));
    if face < 4u {
        let moved = nil_product(generator, at.p);
        let m = -round(moved.z / (2.0 * h));
        g = nil_product(vec3<f32>(0.0, 0.0, 2.0 * h * m), generator);
    }
    var p = nil_product(g, at.p);
    switch face {
        case 0u: { p.x = -0.5; }
        case 1u: { p.x = 0.5; }
        case 2u: { p.y = -0.5; }
        case 3u: { p.y = 0.5; }
        case 4u: { p.z = -h; }
        default: { p.z = h; }
    }
    p.z = clamp(p.z, -h, h);
    return NilRay(p, at.v);
}

// ---------------------------------------------------------------------------------------
// The shortest geodesic (Rust: `space::nil::distance::shortest`): (length, start velocity).

// h(v) of the winding's equation and its rate, in θ itself or its complement δ = 2π − θ.
fn nil_winding(v: f32, complement: bool, rho2: f32, height: f32) -> vec2<f32> {
    let sh = sin(0.5 * v);
    let s2 = sh * sh;
    let sv = sin(v);
    var theta = v;
    var theta_minus_sin = nil_flow_terms(1.0, v).z;
    var sin_theta = sv;
    if complement {
        theta = 2.0 * NIL_PI - v;
        theta_minus_sin = theta + sv;
        sin_theta = -sv;
    }
    let value = theta + rho2 * theta_minus_sin / (8.0 * s2) - height;
    let rate = 1.0 + (2.0 - theta_minus_sin * sin_theta / (2.0 * s2 * s2)) * rho2 / 8.0;
    return vec2<f32>(value, select(rate, -rate, complement));
}

fn nil_shortest(p: vec3<f32>, q: vec3<f32>) -> vec4<f32> {
    let d = nil_product(-p, q);
    let rho2 = d.x * d.x + d.y * d.y;
    let height = abs(d.z);
    let up = select(1.0, -1.0, (d.z < 0.0));
    if rho2 == 0.0 {
        if height == 0.0 {
            return vec4<f32>(0.0, 0.0, 0.0, 1.0);
        }
        if height <= 2.0 * NIL_PI {
            return vec4<f32>(height, 0.0, 0.0, up);
        }
        let length = 2.0 * NIL_PI * sqrt(height / NIL_PI - 1.0);
        let c = 2.0 * NIL_PI / length;
        return vec4<f32>(length, sqrt(max(1.0 - c * c, 0.0)), 0.0, up * c);
    }
    let rho = sqrt(rho2);
    if height == 0.0 {
        return vec4<f32>(rho, d.x / rho, d.y / rho, 0.0);
    }
    let complement = nil_winding(NIL_PI, false, rho2, height).x < 0.0;
    var lo = 0.0;
    var hi = NIL_PI;
    var v = 0.5 * NIL_PI;
    if !complement {
        v = min(height / (1.0 + rho2 / 12.0), NIL_PI);
    }
    for (var i = 0u; i < 80u; i += 1u) {
        let f = nil_winding(v, complement, rho2, height);
        if f.x == 0.0 {
            break;
        }
        if (f.x > 0.0) == complement {
            lo = v;
        } else {
            hi = v;
        }
        let newton = v - f.x / f.y;
        var next = 0.5 * (lo + hi);
        if f.y != 0.0 && newton > lo && newton < hi {
            next = newton;
        }
        if next == v || !(lo < hi) {
            break;
        }
        v = next;
    }
    let t = select(v, 2.0 * NIL_PI - v, complement);
    let sh = sin(0.5 * v);
    let chord = sqrt(rho2 + 4.0 * sh * sh);
    let length = t / (2.0 * sh) * chord;
    let c = 2.0 * sh / chord;
    let a = rho / chord;
    let angle = atan2(d.y, d.x) - up * t * 0.5;
    return vec4<f32>(length, a * cos(angle), a * sin(angle), up * c);
}

// ---------------------------------------------------------------------------------------
// Objects (Rust: `trace::nil::objects`).

// The object's gap at p (negative inside) and its unit normal; the rate bound in w of the
// second vector.
struct NilGap {
    gap: f32,
    normal: vec3<f32>,
    rate: f32,
}

fn nil_gap(i: u32, p: vec3<f32>) -> NilGap {
    let o = space.nil_objects[i];
    let kind = u32(o.info.x);
    let radius = o.info.y;
    if kind == 0u {
        let s = nil_shortest(o.shape.xyz, p);
        let n = nil_flow(NilRay(o.shape.xyz, s.yzw), s.x).v;
        return NilGap(s.x - radius, n, 1.0);
    }
    if kind == 1u {
        let d = p.xy - o.shape.xy;
        let r = length(d);
        var n = vec3<f32>(1.0, 0.0, 0.0);
        if r > 0.0 {
            n = vec3<f32>(d / r, 0.0);
        }
        return NilGap(r - radius, n, 1.0);
    }
    // A swept disc.
    let along = u32(o.info.z);
    let offset = o.info.w;
    let q = nil_product(-o.shape.xyz, p);
    let s = select(q.y, q.x, along == 0u);
    let e = select(vec3<f32>(offset, s, o.colour.w), vec3<f32>(s, offset, o.colour.w), along == 0u);
    let local = nil_product(-e, q);
    let a = select(local.x, local.y, along == 0u);
    let b = local.z;
    let across = select(q.x, q.y, along == 0u);
    let twist = across - 0.5 * offset;
    var grad_a = vec3<f32>(1.0, 0.0, 0.0);
    var grad_b = vec3<f32>(0.0, twist, 1.0);
    if along == 0u {
        grad_a = vec3<f32>(0.0, 1.0, 0.0);
        grad_b = vec3<f32>(-twist, 0.0, 1.0);
    }
    let rho = sqrt(a * a + b * b);
    let end = abs(s) - 0.5;
    // The shear's bound over a step no longer than the gap (Rust: `NilObject::gap`).
    let reach = abs(twist) + max(max(rho - radius, end), 0.0);
    let rate = sqrt(1.0 + reach * reach);
    if end > rho - radius {
        var n = vec3<f32>(0.0);
        n[along] = sign(s);
        return NilGap(end, n, rate);
    }
    var n = vec3<f32>(0.0, 0.0, 1.0);
    if rho > 0.0 {
        n = normalize(a * grad_a + b * grad_b);
    }
    return NilGap(rho - radius, n, rate);
}

// A lower bound on the distance from the ball's centre c to p that needs no root (Rust:
// `distance_floor`).
fn nil_distance_floor(c: vec3<f32>, p: vec3<f32>) -> f32 {
    let d = nil_product(-c, p);
    return max(length(d.xy), 2.0 * (sqrt(1.0 + abs(d.z)) - 1.0));
}

// A lower bound on the distance from p to object i (0 inside).
fn nil_clearance(i: u32, p: vec3<f32>) -> f32 {
    let o = space.nil_objects[i];
    if u32(o.info.x) == 0u {
        return max(nil_distance_floor(o.shape.xyz, p) - o.info.y, 0.0);
    }
    let g = nil_gap(i, p);
    return max(g.gap / g.rate, 0.0);
}

// The gap along the ray at t and its rate.
fn nil_gap_along(i: u32, ray: NilRay, t: f32) -> vec3<f32> {
    let at = nil_flow(ray, t);
    let g = nil_gap(i, at.p);
    return vec3<f32>(g.gap, dot(g.normal, at.v), g.rate);
}

// The root of the gap between lo (outside) and hi (inside), by bisection.
fn nil_refine(i: u32, ray: NilRay, lo_in: f32, hi_in: f32) -> f32 {
    var lo = lo_in;
    var hi = hi_in;
    for (var k = 0u; k < 40u; k += 1u) {
        let mid = 0.5 * (lo + hi);
        if !(mid > lo && mid < hi) {
            break;
        }
        if nil_gap(i, nil_flow(ray, mid).p).gap > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return hi;
}

// Where the ray first comes into the vertical slab holding swept disc i (Rust:
// `NilObject::slab_entry`); 0 inside it and for the other shapes, NIL_NONE never.
fn nil_slab_entry(i: u32, ray: NilRay) -> f32 {
    let o = space.nil_objects[i];
    if u32(o.info.x) != 2u {
        return 0.0;
    }
    let across = 1u - u32(o.info.z);
    let centre = o.shape[across] + o.info.w;
    let lo = centre - o.info.y;
    let hi = centre + o.info.y;
    let x = ray.p[across];
    var n = vec2<f32>(0.0);
    if x < lo {
        n[across] = 1.0;
        return nil_vertical_exit(ray, n, lo);
    }
    if x > hi {
        n[across] = -1.0;
        return nil_vertical_exit(ray, n, -hi);
    }
    return 0.0;
}

// asin(z)/z for 0 <= z <= 1.
fn nil_asin_over(z: f32) -> f32 {
    if z < 1.0e-2 {
        return 1.0 + z * z / 6.0;
    }
    return asin(min(z, 1.0)) / z;
}

// When the ray's shadow in the plane is within r of the point b (Rust:
// `space::nil::shadow_within`): (t_in, t_out, period) for its first visit, t_in NIL_NONE
// where it never is, t_out and the period NIL_FAR where it never leaves or never comes back.
fn nil_shadow_within(ray: NilRay, b: vec2<f32>, r: f32) -> vec3<f32> {
    let never = vec3<f32>(NIL_NONE, 0.0, 0.0);
    let q = b - ray.p.xy;
    let big_a = dot(q, q) - r * r;
    let a = length(ray.v.xy);
    if !(a > 1.0e-30) {
        return select(never, vec3<f32>(0.0, NIL_FAR, NIL_FAR), (big_a <= 0.0));
    }
    let h = ray.v.xy / a;
    let x = dot(q, h);
    var y = q.y * h.x - q.x * h.y;
    var k = ray.v.z / a;
    if k < 0.0 {
        k = -k;
        y = -y;
    }
    let p = 1.0 - k * y;
    let big_r = length(vec2<f32>(k * x, p));
    var e = x * x / (big_r + p) - 0.5 * big_a;
    if !(p > 0.0) {
        e = (big_r - p) / (k * k) - 0.5 * big_a;
    }
    if !(e >= 0.0) {
        return never;
    }
    let w = sqrt(e / (2.0 * big_r));
    var period = NIL_FAR;
    if k > 0.0 {
        period = 2.0 * NIL_PI / abs(ray.v.z);
    }
    if k * w >= 1.0 {
        return vec3<f32>(0.0, NIL_FAR, period);
    }
    let half = 2.0 * w * nil_asin_over(k * w);
    var middle = atan2(k * x, p) / max(k, 1.0e-30);
    if p > 0.0 {
        middle = (x / p) * nil_atan_over(k * x / p);
    }
    var t_in = (middle - half) / a;
    var t_out = (middle + half) / a;
    if t_in < 0.0 {
        if t_out >= 0.0 || big_a <= 0.0 {
            t_in = 0.0;
            t_out = max(t_out, 0.0);
        } else if k > 0.0 {
            t_in += period;
            t_out += period;
        } else {
            return never;
        }
    }
    return vec3<f32>(t_in, t_out, period);
}

// The first t in [0, t_max] at which the ray meets object i; NIL_NONE for a miss. Where not
// `exact` (a shadow ray), any t found in the object.
fn nil_meeting(i: u32, ray: NilRay, t_max: f32, exact: bool) -> f32 {
    let kind = u32(space.nil_objects[i].info.x);
    if kind == 1u {
        // A fibre tube: exactly where the shadow first comes within its radius.
        let o = space.nil_objects[i];
        let t = nil_shadow_within(ray, o.shape.xy, o.info.y).x;
        return select(NIL_NONE, t, (t >= 0.0) && (t <= t_max));
    }
    // A ball is stepped from the start: on lavapipe the shadow's visits (as the CPU takes
    // them) cost more than they save.
    let start = nil_slab_entry(i, ray);
    if start < 0.0 || start > t_max {
        return NIL_NONE;
    }
    return nil_step_meeting(i, ray, start, t_max, exact);
}

// The first t in [first, to] at which the ray meets object i, by safe steps from `first`
// (no meeting lies before it); NIL_NONE for a miss.
fn nil_step_meeting(i: u32, ray: NilRay, first: f32, t_max: f32, exact: bool) -> f32 {
    var t = first;
    var g = nil_gap_along(i, ray, first);
    if g.x <= 0.0 {
        if first > 0.0 && exact {
            return nil_refine(i, ray, 0.0, first);
        }
        return first;
    }
    let o = space.nil_objects[i];
    let is_ball = u32(o.info.x) == 0u;
    let floor = 64.0 * 1.1920929e-7 * (1.0 + o.info.y + t_max);
    for (var k = 0u; k < 4000u; k += 1u) {
        if g.y < 0.0 {
            let guess = t - g.x / g.y;
            if guess <= t_max && nil_gap_along(i, ray, guess).x <= 0.0 {
                if !exact {
                    return guess;
                }
                return nil_refine(i, ray, t, guess);
            }
        }
        if g.x < floor {
            return select(NIL_NONE, t, (g.y < -sqrt(floor)));
        }
        var before = t;
        t += g.x / g.z;
        if is_ball {
            // Root-free safe steps while the floor keeps the ball more than a radius away.
            for (var j = 0u; j < 64u; j += 1u) {
                if t > t_max {
                    break;
                }
                let far = nil_distance_floor(o.shape.xyz, nil_flow(ray, t).p) - o.info.y;
                if !(far > o.info.y) {
                    break;
                }
                before = t;
                t += far;
            }
        }
        if t > t_max {
            return NIL_NONE;
        }
        g = nil_gap_along(i, ray, t);
        if g.x <= 0.0 {
            if !exact {
                return t;
            }
            return nil_refine(i, ray, before, t);
        }
    }
    return NIL_NONE;
}

// Whether the chart box of the segment (Rust: `segment_box`) meets object i's.
fn nil_segment_meets(i: u32, ray: NilRay, t_max: f32) -> bool {
    let a = length(ray.v.xy);
    var centre = ray.p.xy;
    var reach = vec2<f32>(a * t_max);
    let c = ray.v.z;
    if abs(c) * t_max > 1.0e-6 {
        let radius = a / abs(c);
        let circle = vec2<f32>(ray.p.x - ray.v.y / c, ray.p.y + ray.v.x / c);
        let lo = max(centre - reach, circle - vec2<f32>(radius));
        let hi = min(centre + reach, circle + vec2<f32>(radius));
        centre = 0.5 * (lo + hi);
        reach = 0.5 * (hi - lo);
    }
    let far = length(abs(centre) + reach);
    let slack = 0.5 * a * far;
    let lo = vec3<f32>(centre - reach, ray.p.z + min(t_max * (c - slack), 0.0)) - vec3<f32>(1.0e-5);
    let hi = vec3<f32>(centre + reach, ray.p.z + max(t_max * (c + slack), 0.0)) + vec3<f32>(1.0e-5);
    let o = space.nil_objects[i];
    return all((lo <= o.box_hi.xyz)) && all((o.box_lo.xyz <= hi));
}

// The nearest object met within t_max: (index, t); index NIL_OBJECTS for none. Where not
// `exact` (a shadow ray), the first found.
fn nil_nearest(ray: NilRay, t_max: f32, exact: bool) -> vec2<f32> {
    var best = t_max;
    var index = #{NIL_OBJECTS}u;
    for (var i = 0u; i < u32(space.nil_box.z); i += 1u) {
        if !nil_segment_meets(i, ray, best) || nil_clearance(i, ray.p) > best {
            continue;
        }
        let t = nil_meeting(i, ray, best, exact);
        if (t >= 0.0) && ((index == #{NIL_OBJECTS}u) || (t < best)) {
            best = t;
            index = i;
            if !exact {
                break;
            }
        }
    }
    return vec2<f32>(f32(index), best);
}

#ifdef WALLS
// What the walls crossed so far added and let through (Rust: `scene::walls::Veil`).
var<private> nil_veil_colour: vec3<f32>;
var<private> nil_veil_through: f32;

// Whether the point p of the pair's face at -1/2 (or the bottom) is on the panel of face's
// pair rather than in its window (Rust: `trace::nil::walls::NilWalls::on_panel`).
fn nil_on_panel(face: u32, p: vec3<f32>) -> bool {
    let margin = space.wall_colours[face].w;
    let pair = face / 2u;
    if pair == 0u {
        return min(0.5 - abs(p.y), nil_h() - abs(p.z)) < margin;
    }
    if pair == 1u {
        return min(0.5 - abs(p.x), nil_h() - abs(p.z)) < margin;
    }
    return min(0.5 - abs(p.x), 0.5 - abs(p.y)) < margin;
}

// The wall a ray meets crossing `face`, judged at `on_face` and lit where it left (`left`),
// at distance d from the eye, added to the veil (Rust: `NilWalls::cross`).
fn nil_wall(face: u32, on_face: vec3<f32>, left: NilRay, d: f32) {
    if !nil_on_panel(face, on_face) {
        return;
    }
    let pair = face / 2u;
    var normal = normalize(vec3<f32>(-0.5 * left.p.y, 0.5 * left.p.x, 1.0));
    if pair == 0u {
        normal = vec3<f32>(1.0, 0.0, 0.0);
    } else if pair == 1u {
        normal = vec3<f32>(0.0, 1.0, 0.0);
    }
    let facing = min(abs(dot(normal, left.v)), 1.0);
    let lit = min(space.wall_colours[face].rgb * (0.55 + 0.45 * facing), vec3<f32>(1.0));
    let w = exp(-d / space.shading.params.x);
    let seen = w * lit + (1.0 - w) * space.shading.fog.rgb;
    let opacity = space.wall_looks[face].x;
    nil_veil_colour += nil_veil_through * opacity * seen;
    nil_veil_through *= 1.0 - opacity;
}
#endif

// What lies behind the walls, seen through them.
fn nil_behind_walls(c: vec3<f32>) -> vec3<f32> {
#ifdef WALLS
    return nil_veil_colour + nil_veil_through * c;
#else
    return c;
#endif
}

struct NilEnd {
    // The object met (NIL_OBJECTS: none), the crossings, the distance.
    index: u32,
    distance: f32,
    at: NilRay,
}

// Walks the ray to its first object within `length`, through at most `budget` faces; where
// not `exact` (a shadow ray), only whether it meets one is sure.
fn nil_walk(start: NilRay, length: f32, budget: u32, exact: bool) -> NilEnd {
    var ray = start;
    var distance = 0.0;
    var crossings = 0u;
    loop {
        if distance >= length {
            break;
        }
        let exit = nil_exit(ray);
        let face = u32(exit.x);
        if face > 5u {
            break;
        }
        let t_max = min(exit.y, length - distance);
        let hit = nil_nearest(ray, t_max, exact);
        if u32(hit.x) < #{NIL_OBJECTS}u {
            return NilEnd(u32(hit.x), distance + hit.y, nil_flow(ray, hit.y));
        }
        if exit.y >= length - distance {
            break;
        }
        let here = ray;
        ray = nil_through(ray, face, exit.y);
        distance += exit.y;
        crossings += 1u;
#ifdef WALLS
        if exact {
            // The panel is judged on the pair's face at -1/2 (or the bottom): where the ray
            // leaves through it, or where it comes in after leaving through its partner.
            let left = nil_flow(here, exit.y);
            var on_face = ray.p;
            if (face & 1u) == 1u {
                on_face = left.p;
            }
            nil_wall(face, on_face, left, distance);
            if nil_veil_through < space.wall_style.x {
                break;
            }
        }
#endif
        if crossings > budget {
            break;
        }
    }
    return NilEnd(#{NIL_OBJECTS}u, distance, ray);
}

// ---------------------------------------------------------------------------------------
// Light (Rust: `trace::nil::light`).

// The geodesic sphere's area per solid angle (Rust: `area_density`).
fn nil_area_density(r: f32, c: f32) -> f32 {
    let s = c * r;
    var sinc = 1.0 - s * s / 6.0;
    if abs(s) >= 1.0e-2 {
        sinc = sin(s) / s;
    }
    let s2 = s * s;
    var p = 1.0 / 12.0 - s2 / 180.0 + s2 * s2 / 6720.0;
    if abs(s) >= 0.3 {
        p = (2.0 * (1.0 - cos(s)) - s * sin(s)) / (s2 * s2);
    }
    return abs(r * r * sinc + r * r * r * r * p);
}

// The light along the shortest geodesic (length, start) from x, walked for a shadow where
// `shadowed`.
fn nil_light_along(x: vec3<f32>, normal: vec3<f32>, path: vec4<f32>, shadowed: bool) -> f32 {
    let cos_l = dot(normal, path.yzw);
    if !(cos_l > 0.0 && path.x > 0.0) {
        return 0.0;
    }
#ifdef NIL_SHADOWS
    if shadowed && path.x > 1.0e-3 {
        let start = nil_flow(NilRay(x, path.yzw), 1.0e-3);
        if nil_walk(start, path.x - 1.0e-3, u32(space.shading.params.w), false).index < #{NIL_OBJECTS}u {
            return 0.0;
        }
    }
#endif
    let floor = space.nil_light.w;
    return cos_l * exp(-path.x / space.shading.params.x) / max(nil_area_density(path.x, path.w), floor);
}

fn nil_gather(x: vec3<f32>, normal: vec3<f32>) -> f32 {
#ifdef NIL_IMAGES
    var sum = 0.0;
    let lighting = space.nil_lighting;
    for (var k = 0u; k < u32(lighting.x); k += 1u) {
        let path = nil_shortest(x, space.nil_images[k].xyz);
        if path.x <= lighting.z {
            sum += nil_light_along(x, normal, path, f32(k) < lighting.w);
        }
    }
    return sum + lighting.y;
#else
    return nil_light_along(x, normal, nil_shortest(x, space.nil_light.xyz), false);
#endif
}

// The colour seen along a camera ray (chart point, body direction): its first object lit
// and fogged, else the fog.
fn ray_colour(point: vec4<f32>, tangent: vec4<f32>) -> vec3<f32> {
    let start = NilRay(point.xyz, normalize(tangent.xyz));
    let shading = space.shading;
#ifdef WALLS
    nil_veil_colour = vec3<f32>(0.0);
    nil_veil_through = 1.0;
#endif
    let end = nil_walk(start, shading.params.y, u32(shading.params.w), true);
    if end.index >= #{NIL_OBJECTS}u {
        return nil_behind_walls(shading.fog.rgb);
    }
    let o = space.nil_objects[end.index];
    let normal = nil_gap(end.index, end.at.p).normal;
    let light = nil_gather(end.at.p, normal);
    let ambient = shading.fog.w;
    let lit = ambient + (1.0 - ambient) * space.nil_box.w * light;
    let surface = min(o.colour.rgb * lit, vec3<f32>(1.0));
    let w = exp(-end.distance / shading.params.x);
    return nil_behind_walls(w * surface + (1.0 - w) * shading.fog.rgb);
}
