// Nil's geometry on the GPU (shader def NIL): the GPU twin of src/space/nil in f32 — the
// geodesic flow in closed form, the exits from the box of nil-K (the sides in closed form,
// the top and bottom bracketed between the height's turning points), the crossing by the
// lattice element of the face, and the shortest geodesic to a point (the inverse of the
// exponential map). The tracer (`curved_spaces::nil`) builds on it.
#define_import_path curved_spaces::nil_geometry

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
fn nil_height_root(ray: NilRay, h: f32, lo_in: f32, hi_in: f32, rising: bool, start: f32) -> f32 {
    var lo = lo_in;
    var hi = hi_in;
    var t = start;
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
    // Out of reach before `before` (Rust: `horizontal_exit`): the height moves at most
    // |c| T + a r0 T / 2 + a^2 T^2 / 4 by the time T.
    if before < NIL_FAR {
        let a = length(ray.v.xy);
        let reach = (abs(c) + 0.5 * a * (length(ray.p.xy) + 0.5 * a * before)) * before;
        if abs(f0.x) > reach * (1.0 + 1.0e-5) + 1.0e-7 * abs(h) {
            return NIL_NONE;
        }
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
    var rate_lo = f0.y;
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
        let at_hi = nil_height(ray, hi, h);
        let f_hi = at_hi.x;
        let straddles = (f_lo <= 0.0 && f_hi >= 0.0) || (f_lo >= 0.0 && f_hi <= 0.0);
        let from_the_plane = lo == 0.0 && f_lo == 0.0;
        if straddles && !from_the_plane {
            // Newton's step from the bracket's start, else the middle.
            let newton = lo - f_lo / rate_lo;
            var start = 0.5 * (lo + hi);
            if rate_lo != 0.0 && newton > lo && newton < hi {
                start = newton;
            }
            let root = nil_height_root(ray, h, lo, hi, f_lo < 0.0, start);
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
        rate_lo = at_hi.y;
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
