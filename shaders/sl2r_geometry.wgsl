// SL̃(2,R)'s geometry in f32 (the twin of src/space/sl2r): a point of UT H² is the Lorentz
// frame (e, e⊥, p); a geodesic is F·exp(tW)·exp(2ct R) with exp(tW) = I + S W + K W², S and
// K entire in ω²t² (one formula for hypercycles, horocycles and circles). A side n·p ≤ 0 and
// a fibre tube ⟨p, q⟩ ≥ −cosh r are both met where n·p(t) + c crosses 0, a quadratic in
// τ = tanh(ωt/2)/(ω/2), polished by Newton's method (sl2r_crossing). The distance by the
// inverse exponential map (one unknown γ, the logarithm of SO(2,1) in closed form, the
// secant method from the principal guess, else scanned and refined by the Illinois method:
// sl2r_shortest) and its root-free floor (sl2r_floor). Nothing here reads the scene.
#define_import_path curved_spaces::sl2r_geometry
const SL2R_PI: f32 = 3.14159265358979;
const SL2R_NONE: f32 = -1.0;

struct Sl2rRay {
    e: vec3<f32>,
    f: vec3<f32>,
    p: vec3<f32>,
    // The body velocity (a, b, c) in (X, Y, V).
    v: vec3<f32>,
}

fn sl2r_lorentz(u: vec3<f32>, w: vec3<f32>) -> f32 {
    return u.x * w.x + u.y * w.y - u.z * w.z;
}

// e turned by +90° at p: J(p × e).
fn sl2r_perp(p: vec3<f32>, e: vec3<f32>) -> vec3<f32> {
    let c = cross(p, e);
    return vec3<f32>(c.x, c.y, -c.z);
}

// (S, K) of the flow for ω² = w2 at time t: series while |ω²t²| < 4, closed forms beyond.
fn sl2r_terms(w2: f32, t: f32) -> vec2<f32> {
    let x = w2 * t * t;
    if abs(x) < 4.0 {
        // Σ xᵏ/(2k+1)! and Σ xᵏ/(2k+2)!, k ≤ 7: the next terms are below f32's last bit.
        var s = 1.0 / 1307674368000.0;
        s = s * x + 1.0 / 6227020800.0;
        s = s * x + 1.0 / 39916800.0;
        s = s * x + 1.0 / 362880.0;
        s = s * x + 1.0 / 5040.0;
        s = s * x + 1.0 / 120.0;
        s = s * x + 1.0 / 6.0;
        s = s * x + 1.0;
        var k = 1.0 / 20922789888000.0;
        k = k * x + 1.0 / 87178291200.0;
        k = k * x + 1.0 / 479001600.0;
        k = k * x + 1.0 / 3628800.0;
        k = k * x + 1.0 / 40320.0;
        k = k * x + 1.0 / 720.0;
        k = k * x + 1.0 / 24.0;
        k = k * x + 0.5;
        return vec2<f32>(t * s, t * t * k);
    }
    if w2 > 0.0 {
        let om = sqrt(w2);
        let h = sinh(0.5 * om * t);
        return vec2<f32>(sinh(om * t) / om, 2.0 * h * h / w2);
    }
    let om = sqrt(-w2);
    let h = sin(0.5 * om * t);
    return vec2<f32>(sin(om * t) / om, 2.0 * h * h / (-w2));
}

// The ray moved by t along its geodesic.
fn sl2r_flow(r: Sl2rRay, t: f32) -> Sl2rRay {
    let a = r.v.x;
    let b = r.v.y;
    let c = r.v.z;
    let sk = sl2r_terms(a * a + b * b - c * c, t);
    let s = sk.x;
    let k = sk.y;
    // exp(tW) = I + S W + K W² (rows), W = a B₁ + b B₂ − c R.
    let m0 = vec3<f32>(1.0 + k * (a * a - c * c), s * c + k * a * b, s * a + k * b * c);
    let m1 = vec3<f32>(-s * c + k * a * b, 1.0 + k * (b * b - c * c), s * b - k * a * c);
    let m2 = vec3<f32>(s * a - k * b * c, s * b + k * a * c, 1.0 + k * (a * a + b * b));
    // Column j of F·exp(tW) is e·m0[j] + f·m1[j] + p·m2[j].
    let e = r.e * m0.x + r.f * m1.x + r.p * m2.x;
    let f = r.e * m0.y + r.f * m1.y + r.p * m2.y;
    let p = r.e * m0.z + r.f * m1.z + r.p * m2.z;
    let phi = 2.0 * c * t;
    let co = cos(phi);
    let si = sin(phi);
    return Sl2rRay(e * co + f * si, f * co - e * si, p, vec3<f32>(a * co + b * si, b * co - a * si, c));
}

// The ray back on the model: p on the hyperboloid, e a unit tangent there, e⊥ completing
// the frame, the velocity unit.
fn sl2r_on_model(r: Sl2rRay) -> Sl2rRay {
    let p = r.p / sqrt(max(-sl2r_lorentz(r.p, r.p), 1e-30));
    let t = r.e + sl2r_lorentz(r.e, p) * p;
    let e = t / sqrt(max(sl2r_lorentz(t, t), 1e-30));
    return Sl2rRay(e, sl2r_perp(p, e), p, normalize(r.v));
}

// atanh(√y)/√y (atan(√−y)/√−y for y < 0).
fn sl2r_atanhc(y: f32) -> f32 {
    if abs(y) < 0.01 {
        return 1.0 + y * (1.0 / 3.0 + y * (0.2 + y * (1.0 / 7.0)));
    }
    if y > 0.0 {
        let s = sqrt(y);
        return 0.5 * log((1.0 + s) / (1.0 - s)) / s;
    }
    let s = sqrt(-y);
    return atan(s) / s;
}

// The time at which τ(t) first equals tau (SL2R_NONE where it never does); an infinite
// root (a circle's half period) is asked with `infinite`.
fn sl2r_time_of(tau: f32, w2: f32, infinite: bool) -> f32 {
    if w2 >= 0.0 {
        let y = 0.25 * w2 * tau * tau;
        if infinite || tau < 0.0 || y >= 1.0 {
            return SL2R_NONE;
        }
        return tau * sl2r_atanhc(y);
    }
    let om = sqrt(-w2);
    if infinite {
        return SL2R_PI / om;
    }
    let y = 0.25 * w2 * tau * tau;
    if tau >= 0.0 {
        if y > -0.01 {
            return tau * sl2r_atanhc(y);
        }
        return 2.0 * atan(0.5 * om * tau) / om;
    }
    return 2.0 * (SL2R_PI + atan(0.5 * om * tau)) / om;
}

// The first t ≥ 0 at which n·p(t) + offset goes from ≤ 0 to > 0 (SL2R_NONE: never).
fn sl2r_crossing(r: Sl2rRay, n: vec3<f32>, offset: f32) -> f32 {
    let u = vec3<f32>(dot(n, r.e), dot(n, r.f), dot(n, r.p));
    let a = r.v.x;
    let b = r.v.y;
    let c = r.v.z;
    let alpha = u.z + offset;
    let beta = a * u.x + b * u.y;
    let gamma = c * (b * u.x - a * u.y) + (a * a + b * b) * u.z;
    let w2 = a * a + b * b - c * c;
    if alpha >= 0.0 && beta > 0.0 {
        return 0.0;
    }
    let qa = 0.5 * gamma - 0.25 * alpha * w2;
    let disc = beta * beta - 4.0 * qa * alpha;
    if disc < 0.0 {
        return SL2R_NONE;
    }
    let q = -0.5 * (beta + select(1.0, -1.0, beta < 0.0) * sqrt(disc));
    var best = 1e30;
    // The root q/A (at infinity where A = 0), then α/q.
    if qa != 0.0 {
        let tau = q / qa;
        if 2.0 * qa * tau + beta > 0.0 {
            let t = sl2r_time_of(tau, w2, false);
            if t >= 0.0 {
                best = min(best, t);
            }
        }
    } else if beta < 0.0 {
        let t = sl2r_time_of(0.0, w2, true);
        if t >= 0.0 {
            best = min(best, t);
        }
    }
    if q != 0.0 {
        let tau = alpha / q;
        if 2.0 * qa * tau + beta > 0.0 {
            let t = sl2r_time_of(tau, w2, false);
            if t >= 0.0 {
                best = min(best, t);
            }
        }
    }
    if best >= 1e30 {
        return SL2R_NONE;
    }
    // Newton's steps on f itself, each kept where it makes |f| smaller.
    var t = best;
    var sk = sl2r_terms(w2, t);
    var f = alpha + beta * sk.x + gamma * sk.y;
    for (var i = 0u; i < 2u; i += 1u) {
        let df = beta * (1.0 + w2 * sk.y) + gamma * sk.x;
        if f == 0.0 || df == 0.0 {
            break;
        }
        let next = max(t - f / df, 0.0);
        let nsk = sl2r_terms(w2, next);
        let nf = alpha + beta * nsk.x + gamma * nsk.y;
        if !(abs(nf) < abs(f)) {
            break;
        }
        t = next;
        sk = nsk;
        f = nf;
    }
    return t;
}

const SL2R_SCAN_STEP: f32 = 0.125;

// A logarithm (x, y, z) of exp(xB₁ + yB₂ + zR), φ = z + γ there, and whether it exists.
struct Sl2rLog {
    u: vec3<f32>,
    f: f32,
    ok: bool,
}

// log(G·exp(−2γR)) on the principal branch (G by its rows) and φ(γ).
fn sl2r_phi(g0: vec3<f32>, g1: vec3<f32>, g2: vec3<f32>, gamma: f32) -> Sl2rLog {
    let co = cos(2.0 * gamma);
    let si = sin(2.0 * gamma);
    let h0 = vec3<f32>(g0.x * co - g0.y * si, g0.x * si + g0.y * co, g0.z);
    let h1 = vec3<f32>(g1.x * co - g1.y * si, g1.x * si + g1.y * co, g1.z);
    let h2 = vec3<f32>(g2.x * co - g2.y * si, g2.x * si + g2.y * co, g2.z);
    // (H − H⁻¹)/2 = S·U with H⁻¹ = J Hᵀ J; N = S²ω², C = (tr H − 1)/2.
    let x = 0.5 * (h0.z + h2.x);
    let y = 0.5 * (h1.z + h2.y);
    let z = 0.5 * (h1.x - h0.y);
    let n = x * x + y * y - z * z;
    let c = 0.5 * (h0.x + h1.y + h2.z - 1.0);
    var s = 1.0;
    if abs(n) < 1e-2 && c > 0.0 {
        s = 1.0 / (1.0 + n * (-1.0 / 6.0 + n * (3.0 / 40.0 + n * (-5.0 / 112.0 + n * (35.0 / 1152.0)))));
    } else if n > 0.0 {
        if c < 0.999 {
            return Sl2rLog(vec3<f32>(0.0), 0.0, false);
        }
        let u = sqrt(n);
        s = u / asinh(u);
    } else {
        let u = sqrt(-n);
        if u < 1e-20 {
            return Sl2rLog(vec3<f32>(0.0), 0.0, false);
        }
        s = u / atan2(u, c);
    }
    let l = vec3<f32>(x, y, z) / s;
    return Sl2rLog(l, l.z + gamma, true);
}

// The shortest geodesic from the frame (ec, fc, pc) to the frame of `at` shorter than
// `bound`: (its length, its unit start velocity), or a length below 0 where there is none.
fn sl2r_shortest(ec: vec3<f32>, fc: vec3<f32>, pc: vec3<f32>, at: Sl2rRay, bound: f32) -> vec4<f32> {
    // G = F₀⁻¹F₁: G[i][j] = sᵢ⟨F₀ᵢ, F₁ⱼ⟩, s = (1, 1, −1).
    let g0 = vec3<f32>(sl2r_lorentz(ec, at.e), sl2r_lorentz(ec, at.f), sl2r_lorentz(ec, at.p));
    let g1 = vec3<f32>(sl2r_lorentz(fc, at.e), sl2r_lorentz(fc, at.f), sl2r_lorentz(fc, at.p));
    let g2 = -vec3<f32>(sl2r_lorentz(pc, at.e), sl2r_lorentz(pc, at.f), sl2r_lorentz(pc, at.p));
    var best = vec4<f32>(-1.0, 0.0, 0.0, 0.0);
    // No geodesic is shorter than the base distance ρ, and one shorter than L has |γ| below
    // √(L² − ρ²) (its base point's path, √(α² + β²) long, covers ρ).
    let chord = at.p - pc;
    let rho = 2.0 * asinh(0.5 * sqrt(max(sl2r_lorentz(chord, chord), 0.0)));
    if rho >= bound {
        return best;
    }
    // The secant method from the principal guess first: a geodesic shorter than the
    // injectivity radius π is the only one that short, so a root it finds below 3 is the
    // answer.
    let principal = sl2r_phi(g0, g1, g2, 0.0);
    if principal.ok {
        var ga = principal.u.z;
        var a0 = sl2r_phi(g0, g1, g2, ga);
        var gb = ga + a0.f;
        var b0 = sl2r_phi(g0, g1, g2, gb);
        var settled = false;
        for (var i = 0u; i < 10u; i += 1u) {
            if !(a0.ok && b0.ok) {
                break;
            }
            if b0.f == 0.0 || abs(gb - ga) <= 1e-6 * (1.0 + abs(gb)) {
                settled = true;
                break;
            }
            if b0.f == a0.f {
                break;
            }
            let gc = gb - b0.f * (gb - ga) / (b0.f - a0.f);
            ga = gb;
            a0 = b0;
            gb = gc;
            b0 = sl2r_phi(g0, g1, g2, gb);
        }
        if settled && b0.ok && abs(b0.f) < 1e-4 {
            let len = length(vec3<f32>(b0.u.x, b0.u.y, gb));
            if len < 3.0 {
                if len < bound {
                    best = vec4<f32>(len, vec3<f32>(b0.u.x, b0.u.y, gb) / max(len, 1e-30));
                }
                return best;
            }
        }
    }
    var reach = bound;
    let zero = principal;
    for (var side = 0u; side < 2u; side += 1u) {
        let sign = select(1.0, -1.0, side == 1u);
        var a = 0.0;
        var fa = zero.f;
        var last_ok = zero.ok;
        for (var k = 1u; k < 26u; k += 1u) {
            let gamma = sign * f32(k) * SL2R_SCAN_STEP;
            if abs(gamma) - SL2R_SCAN_STEP >= sqrt(max(reach * reach - rho * rho, 0.0)) {
                break;
            }
            let here = sl2r_phi(g0, g1, g2, gamma);
            if last_ok && here.ok && (fa < 0.0) != (here.f < 0.0) && abs(fa - here.f) < SL2R_PI {
                // The Illinois method on [a, b].
                var lo = a;
                var flo = fa;
                var b = gamma;
                var fb = here.f;
                var u = here.u;
                for (var i = 0u; i < 24u; i += 1u) {
                    if fb == 0.0 || abs(b - lo) <= 1e-6 * (1.0 + abs(b)) {
                        break;
                    }
                    var m = (lo * fb - b * flo) / (fb - flo);
                    if !(m > min(lo, b) && m < max(lo, b)) {
                        m = 0.5 * (lo + b);
                    }
                    let r = sl2r_phi(g0, g1, g2, m);
                    if !r.ok {
                        break;
                    }
                    if (r.f < 0.0) != (fb < 0.0) {
                        lo = b;
                        flo = fb;
                    } else {
                        flo = 0.5 * flo;
                    }
                    b = m;
                    fb = r.f;
                    u = r.u;
                }
                let len = length(vec3<f32>(u.x, u.y, b));
                if len < reach {
                    reach = len;
                    best = vec4<f32>(len, vec3<f32>(u.x, u.y, b) / max(len, 1e-30));
                }
            }
            a = gamma;
            fa = here.f;
            last_ok = here.ok;
        }
    }
    return best;
}

// A floor of the distance from the frame (ec, fc, pc) to `at`: the base distance, and the
// turn of e against fc carried along the base geodesic (|ψ| ≤ L + L²/π).
fn sl2r_floor(ec: vec3<f32>, pc: vec3<f32>, at: Sl2rRay) -> f32 {
    let d = at.p - pc;
    let rho = 2.0 * asinh(0.5 * sqrt(max(sl2r_lorentz(d, d), 0.0)));
    let k = sl2r_lorentz(at.p, ec) / (1.0 - sl2r_lorentz(pc, at.p));
    let g = ec + k * (pc + at.p);
    let psi = atan2(abs(sl2r_lorentz(g, at.f)), sl2r_lorentz(g, at.e));
    return max(rho, 2.0 * psi / (1.0 + sqrt(1.0 + 4.0 * psi / SL2R_PI)));
}
