// The product geometries H²×R and S²×R (shader def PRODUCT with HYPERBOLIC or SPHERICAL,
// the surface's geometry): the exact walk through the product cell, and the surface's
// distances. The objects met along it are in product_objects.wgsl, a ray's colour in
// product.wgsl. The Rust twin: `space::product::ProductWalker`.
//
// A point is (x, y, z, w): (x, y, w) on the surface's model, z the height along the fibre; a
// unit tangent splits into the base part of speed λ and the fibre speed μ = v.z. The shadow
// of a geodesic on the surface is the surface geodesic at speed λ, its height z + μt.
#define_import_path curved_spaces::product_walk

#import curved_spaces::layout::{face_count, kappa, space}
#import curved_spaces::geometry::distance_from_ratio
#import curved_spaces::walk::{Ray, transform_compensated}

// A step without crossing (S²: at most `SEGMENT_ARC` of surface arc).
const CAP: u32 = 0xfffffffeu;
const NONE: u32 = 0xffffffffu;
const FAR: f32 = 3.0e38;
const QUARTER_PI: f32 = 0.7853981633974483;
// The longest segment of surface arc the S² walk takes between crossings: π/2, since a
// side's great circle that a ray moves away from is met again within π of arc, and the
// exit search, which looks only at the sides a ray moves towards, sees every side met
// within π/2. The object search cuts a segment into pieces of at most π/4
// (`first_meeting_within`) for the objects it comes near; the CPU reference steps π/4 at
// a time.
const SEGMENT_ARC: f32 = 1.5707963267948966;
// With no side to meet (the sphere), π: a longer segment's midpoint test turns nothing
// away (2π was slower).
const WHOLE_ARC: f32 = 3.14159265;

// Where a ray leaves the cell: the face (a side, face_count() the top, face_count() + 1 the
// bottom, CAP or NONE), the distance, and for a side the ratio num/den of its base chart point.
struct ProductExit {
    face: u32,
    distance: f32,
    num: f32,
    den: f32,
}

fn base_form(a: vec4<f32>, b: vec4<f32>) -> f32 {
    return a.x * b.x + a.y * b.y + kappa() * a.w * b.w;
}

fn base_of(v: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(v.x, v.y, 0.0, v.w);
}

// ⟨v, v⟩ of a surface tangent v at p; in H² by Lagrange's identity, a sum of squares
// (Rust: `ProductWalker::speed_squared`).
fn speed_squared(p: vec4<f32>, v: vec4<f32>) -> f32 {
#ifdef HYPERBOLIC
    let c = p.x * v.y - p.y * v.x;
    return (v.x * v.x + v.y * v.y + c * c) / (p.w * p.w);
#else
    return base_form(v, v);
#endif
}

// C and S of the surface distance t: cos and sin, or cosh and sinh.
fn cs(t: f32) -> vec2<f32> {
#ifdef HYPERBOLIC
    return vec2<f32>(cosh(t), sinh(t));
#else
    return vec2<f32>(cos(t), sin(t));
#endif
}

// The ray put back onto the model (Rust: `ProductWalker::normalized`).
fn normalized(ray: Ray) -> Ray {
    let p = ray.point;
    let norm = sqrt(abs(kappa() * base_form(p, p)));
    var q = base_of(p) / norm;
#ifdef HYPERBOLIC
    q = select(q, -q, q.w < 0.0);
#endif
    let point = vec4<f32>(q.x, q.y, p.z, q.w);
    var vb = base_of(ray.tangent);
    vb -= q * (base_form(q, vb) / base_form(q, q));
    let mu = ray.tangent.z;
    let len = sqrt(speed_squared(point, vb) + mu * mu);
    return Ray(point, vec4<f32>(vb.x, vb.y, mu, vb.w) / len);
}

// The exit: the side the shadow meets first (the smallest ratio, compared without
// dividing), the top or bottom the height reaches, on S² a step of `SEGMENT_ARC` (Rust:
// `ProductWalker::exit`). `skip` is the side just entered.
fn product_exit(ray: Ray, skip: u32) -> ProductExit {
    let p = ray.point;
    let v = ray.tangent;
    let lambda = sqrt(max(speed_squared(p, base_of(v)), 0.0));
    let mu = v.z;
    var best = ProductExit(NONE, FAR, 0.0, 1.0);
    if lambda > 0.0 {
        var side = NONE;
        var num = 0.0;
        var den = 1.0;
        for (var f = 0u; f < face_count(); f += 1u) {
            let n = space.covectors[f];
            let dn = dot(n, v);
            if f == skip || !(dn > 0.0) {
                continue;
            }
            let nm = max(-dot(n, p), 0.0);
            if side == NONE || nm * den < num * dn {
                side = f;
                num = nm;
                den = dn;
            }
        }
        if side != NONE {
            let scaled = lambda * num;
#ifdef HYPERBOLIC
            // A shadow whose ratio reaches 1 never meets the side's line.
            let reaches = scaled < den;
#else
            let reaches = true;
#endif
            if reaches {
                best = ProductExit(side, distance_from_ratio(scaled, den) / lambda, scaled, den);
            }
        }
#ifdef SPHERICAL
        let capped = select(SEGMENT_ARC, WHOLE_ARC, face_count() == 0u) / lambda;
        if capped < best.distance {
            best = ProductExit(CAP, capped, 0.0, 1.0);
        }
#endif
    }
    let half = space.product.x;
    if mu > 0.0 {
        let t = max((half - p.z) / mu, 0.0);
        if t < best.distance {
            best = ProductExit(face_count(), t, 0.0, 1.0);
        }
    } else if mu < 0.0 {
        let t = max((-half - p.z) / mu, 0.0);
        if t < best.distance {
            best = ProductExit(face_count() + 1u, t, 0.0, 1.0);
        }
    }
    return best;
}

// The point and tangent at distance t along the ray; at a side's exit (`ratio`) C and S
// come from the ratio itself, so the point lands on the side's line (Rust:
// `ProductWalker::moved`).
fn moved(ray: Ray, t: f32, ratio: bool, num: f32, den: f32) -> Ray {
    let p = ray.point;
    let v = ray.tangent;
    let pb = base_of(p);
    let vb = base_of(v);
    let lambda = sqrt(max(speed_squared(p, vb), 0.0));
    let mu = v.z;
    var c_s = cs(lambda * t);
    if ratio {
#ifdef HYPERBOLIC
        let f = sqrt(max((den - num) * (den + num), 0.0));
#else
        let f = sqrt(den * den + num * num);
#endif
        c_s = vec2<f32>(den / f, num / f);
    }
    var pb2 = pb;
    var vb2 = vb;
    if lambda > 0.0 {
        pb2 = pb * c_s.x + vb * (c_s.y / lambda);
        vb2 = pb * (-kappa() * lambda * c_s.y) + vb * c_s.x;
    }
    return Ray(vec4<f32>(pb2.x, pb2.y, p.z + mu * t, pb2.w), vec4<f32>(vb2.x, vb2.y, mu, vb2.w));
}

// Through the exit face: moved there, the face's pairing applied (compensated), the top and
// bottom setting the height to the opposite slice (Rust: `ProductWalker::cross`).
fn product_cross(ray: Ray, exit: ProductExit) -> Ray {
    let sides = face_count();
    let at = moved(ray, exit.distance, exit.face < sides, exit.num, exit.den);
    if exit.face == CAP {
        return normalized(at);
    }
    let hi = space.pairings[exit.face];
    let lo = space.pairings_lo[exit.face];
    var point = transform_compensated(hi, lo, at.point);
    let tangent = transform_compensated(hi, lo, at.tangent);
    if exit.face == sides {
        point.z = -space.product.x;
    } else if exit.face == sides + 1u {
        point.z = space.product.x;
    }
    return normalized(Ray(point, tangent));
}

// The point at distance t along a ray (the exact geodesic).
fn along(ray: Ray, t: f32) -> vec4<f32> {
    return moved(ray, t, false, 0.0, 1.0).point;
}

// The surface distance between the base points of p and q, from their chord.
fn surface_distance(p: vec4<f32>, q: vec4<f32>) -> f32 {
    let d = base_of(p) - base_of(q);
    let chord = sqrt(max(base_form(d, d), 0.0));
#ifdef HYPERBOLIC
    return 2.0 * asinh(0.5 * chord);
#else
    return 2.0 * asin(min(0.5 * chord, 1.0));
#endif
}

// The unit surface tangent at p pointing away from the base point q (zero at q).
fn away_from(p: vec4<f32>, q: vec4<f32>) -> vec4<f32> {
    let pb = base_of(p);
    let qb = base_of(q);
    let toward = qb - pb * (base_form(qb, pb) / base_form(pb, pb));
    let len = sqrt(max(base_form(toward, toward), 0.0));
    return select(vec4<f32>(0.0), -toward / len, len > 0.0);
}

// The surface distance from a base point x to the line of unit covector m, signed.
fn line_offset(x: vec4<f32>, m: vec4<f32>) -> f32 {
    let xb = base_of(x);
    let s = dot(m, xb / sqrt(abs(kappa() * base_form(xb, xb))));
#ifdef HYPERBOLIC
    return asinh(s);
#else
    return asin(clamp(s, -1.0, 1.0));
#endif
}
