// The product geometries H²×R and S²×R (shader def PRODUCT with HYPERBOLIC or SPHERICAL,
// the surface's geometry): the exact walk through the product cell and the objects met by a
// bracketed search, one camera ray's colour.
// The Rust twins: `space::product::ProductWalker` and `trace::product`.
//
// A point is (x, y, z, w): (x, y, w) on the surface's model, z the height along the fibre; a
// unit tangent splits into the base part of speed λ and the fibre speed μ = v.z. The shadow
// of a geodesic on the surface is the surface geodesic at speed λ, its height z + μt.
#define_import_path curved_spaces::product

#import curved_spaces::layout::{ProductObject, face_count, kappa, space}
#import curved_spaces::geometry::distance_from_ratio
#import curved_spaces::walk::{Ray, partner, transform_compensated}
#import curved_spaces::shading::{colour_by_tint, recolour}

// A step without crossing (S²: at most π/4 of surface arc).
const CAP: u32 = 0xfffffffeu;
const NONE: u32 = 0xffffffffu;
const FAR: f32 = 3.0e38;
const QUARTER_PI: f32 = 0.7853981633974483;

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
// dividing), the top or bottom the height reaches, on S² a step of π/4 (Rust:
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
        let capped = QUARTER_PI / lambda;
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

// The distance from x to object i's shape.
fn object_distance(i: u32, x: vec4<f32>) -> f32 {
    // The two vectors it needs, not the whole object (this is the searches' inner loop).
    let shape = space.product_objects[i].shape;
    let info = space.product_objects[i].info;
    let kind = u32(info.x);
    if kind == 1u {
        return surface_distance(x, shape);
    }
    if kind == 2u {
        let db = line_offset(x, shape);
        let dz = x.z - info.z;
        return sqrt(db * db + dz * dz);
    }
    let db = surface_distance(x, shape);
    let dz = x.z - shape.z;
    return sqrt(db * db + dz * dz);
}

// A vertical triangle's arclength coordinate of x along its geodesic (Rust: `arclength`).
fn arclength(o: ProductObject, x: vec4<f32>) -> f32 {
    let xb = base_of(x);
    let s = base_form(xb, o.more[1]);
#ifdef HYPERBOLIC
    return asinh(s);
#else
    return atan2(s, base_form(xb, o.more[0]));
#endif
}

// Whether x (on the triangle's slice or plane) is in triangle object o
// (Rust: `ProductTriangle::contains`).
fn triangle_contains(o: ProductObject, x: vec4<f32>) -> bool {
    if u32(o.info.x) == 4u {
        return dot(o.shape, x) >= 0.0 && dot(o.more[0], x) >= 0.0 && dot(o.more[1], x) >= 0.0;
    }
    let ds = arclength(o, x) - o.more[2].x;
    let dz = x.z - o.more[2].y;
    let l1 = o.more[2].z * ds + o.more[2].w * dz;
    let l2 = o.info.z * ds + o.info.w * dz;
    return l1 >= 0.0 && l2 >= 0.0 && l1 + l2 <= 1.0;
}

// Where the ray meets triangle object o's slice or plane in [0, t_max], or FAR
// (Rust: `ProductTriangle::plane_meeting`).
fn triangle_plane_meeting(o: ProductObject, ray: Ray, t_max: f32) -> f32 {
    var t = FAR;
    if u32(o.info.x) == 4u {
        let mu = ray.tangent.z;
        if mu == 0.0 {
            return FAR;
        }
        t = (o.info.z - ray.point.z) / mu;
    } else {
        let vb = base_of(ray.tangent);
        let lambda = sqrt(max(speed_squared(ray.point, vb), 0.0));
        if lambda <= 0.0 {
            return FAR;
        }
        let a = dot(o.shape, base_of(ray.point));
        let b = dot(o.shape, vb) / lambda;
#ifdef HYPERBOLIC
        let r = -a / b;
        if !(r >= 0.0 && r < 1.0) {
            return FAR;
        }
        t = atanh(r) / lambda;
#else
        var u = 1.5707963267948966;
        if b != 0.0 {
            u = atan(-a / b);
        }
        if u < 0.0 {
            u += 3.141592653589793;
        }
        t = u / lambda;
#endif
    }
    if !(t >= 0.0 && t <= t_max) {
        return FAR;
    }
    return t;
}

// The unit normal of object i's surface at x (the gradient of the distance; a flat
// piece's either side).
fn object_normal(i: u32, x: vec4<f32>) -> vec4<f32> {
    let o = space.product_objects[i];
    let kind = u32(o.info.x);
    if kind == 1u {
        return away_from(x, o.shape);
    }
    if kind == 3u || kind == 4u {
        return vec4<f32>(0.0, 0.0, 1.0, 0.0);
    }
    if kind == 5u {
        let xb = base_of(x);
        let m = vec4<f32>(o.shape.x, o.shape.y, 0.0, kappa() * o.shape.w);
        let t = m - xb * (base_form(m, xb) / base_form(xb, xb));
        let len = sqrt(max(base_form(t, t), 0.0));
        return select(vec4<f32>(0.0, 0.0, 1.0, 0.0), t / len, len > 0.0);
    }
    var away = vec4<f32>(0.0);
    var db = 0.0;
    var dz = 0.0;
    if kind == 2u {
        let xb = base_of(x);
        let unit = xb / sqrt(abs(kappa() * base_form(xb, xb)));
        let m = vec4<f32>(o.shape.x, o.shape.y, 0.0, kappa() * o.shape.w);
        let t = m - unit * (base_form(m, unit) / base_form(unit, unit));
        let len = sqrt(max(base_form(t, t), 0.0));
        db = line_offset(x, o.shape);
        away = select(vec4<f32>(0.0), t * (sign(db) / len), len > 0.0);
        db = abs(db);
        dz = x.z - o.info.z;
    } else {
        away = away_from(x, o.shape);
        db = surface_distance(x, o.shape);
        dz = x.z - o.shape.z;
    }
    let n = away * db + vec4<f32>(0.0, 0.0, dz, 0.0);
    let d = sqrt(db * db + dz * dz);
    return select(vec4<f32>(0.0, 0.0, 1.0, 0.0), n / d, d > 0.0);
}

// The first t in [0, t_max] where the segment meets object i, or FAR: after cheap
// rejections, the first root of F(t) = d(t)² − r² by Newton's steps in H²×R and by a
// golden-section search and a bisection on S² (Rust: `trace::product::first_meeting`, the
// f64 reference, searches by golden section and bisection in both).
fn first_meeting(i: u32, ray: Ray, t_max: f32) -> f32 {
    return first_meeting_within(i, ray, t_max, along(ray, 0.5 * t_max), 0.5 * t_max);
}

// `first_meeting` on [0, t_max] within a segment [0, 2 half] (t_max ≤ 2 half) whose
// midpoint is `mid`: the midpoint is computed once a segment for every object.
fn first_meeting_within(i: u32, ray: Ray, t_max: f32, mid: vec4<f32>, half: f32) -> f32 {
    let r = space.product_objects[i].info.y;
    let kind = u32(space.product_objects[i].info.x);
    if kind == 4u || kind == 5u {
        let o = space.product_objects[i];
        let t = triangle_plane_meeting(o, ray, t_max);
        if t == FAR || !triangle_contains(o, along(ray, t)) {
            return FAR;
        }
        return t;
    }
    if u32(space.product_objects[i].info.x) == 3u {
        // A horizontal disc: where the height reaches its slice, if within it.
        let mu = ray.tangent.z;
        if mu == 0.0 {
            return FAR;
        }
        let t = (space.product_objects[i].info.z - ray.point.z) / mu;
        if t < 0.0 || t > t_max || surface_distance(along(ray, t), space.product_objects[i].shape) > r {
            return FAR;
        }
        return t;
    }
    if kind != 1u {
        // A ball or a horizontal tube: the height along the segment is linear, and where
        // it stays more than the radius from the object's height the product distance
        // does too (no transcendental function to tell).
        let z0 = ray.point.z;
        let z1 = z0 + ray.tangent.z * t_max;
        let zc = select(space.product_objects[i].shape.z, space.product_objects[i].info.z, kind == 2u);
        if zc - r > max(z0, z1) || zc + r < min(z0, z1) {
            return FAR;
        }
    }
    // The distance is 1-Lipschitz: a segment whose midpoint is further than half its
    // length plus the radius cannot meet it.
    if object_distance(i, mid) > half + r {
        return FAR;
    }
    let r2 = r * r;
#ifdef HYPERBOLIC
    // H²×R curves nowhere positively: F is convex along the whole segment.
    return newton_meeting(i, ray, t_max, r2);
#else
    // On S² F is convex only where the surface distance stays under π/2 (the Hessian of d²
    // there is 2 d cot d on the transverse part), and the square of a tube's offset from
    // a great circle is not convex: the bracketed search, which needs only one minimum.
    // (Newton where convexity could be shown, the bracketed search elsewhere, was slower
    // on the default scene: eight lanes that part pay for both.)
    return bracketed_meeting(i, ray, t_max, r2);
#endif
}

#ifdef HYPERBOLIC
// The first root of a convex F = d² − r² in [0, t_max], F(0) evaluated first: Newton's
// steps from t = 0 (where F > 0 and the tangent line lies below F) climb towards it
// without passing it. A slope turned non-negative before F reaches 0, or a step past
// t_max, says there is none. A few steps where a golden section and a bisection took
// dozens, each paid by all eight lanes of a block.
fn newton_meeting(i: u32, ray: Ray, t_max: f32, r2: f32) -> f32 {
    var t = 0.0;
    var q = squared_distance_slope(i, ray);
    for (var k = 0u; k < 48u; k += 1u) {
        let f = q.x - r2;
        if f <= 0.0 {
            return t;
        }
        if !(q.y < 0.0) {
            return FAR;
        }
        let step = -0.5 * f / q.y;
        let next = t + step;
        if !(next <= t_max) {
            return FAR;
        }
        if step <= 1e-6 * max(t_max, 1.0) {
            return next;
        }
        t = next;
        q = squared_distance_slope(i, moved(ray, t, false, 0.0, 1.0));
    }
    return FAR;
}
#endif

// The first root of F = d² − r² in [0, t_max] where F is only unimodal: a golden-section
// search for a point inside, then a bracketed search for the root before it.
fn bracketed_meeting(i: u32, ray: Ray, t_max: f32, r2: f32) -> f32 {
    let r = sqrt(r2);
    let d0 = object_distance(i, ray.point);
    if d0 * d0 <= r2 {
        return 0.0;
    }
    let ratio = 0.6180339887498949;
    var a = 0.0;
    var b = t_max;
    var c = b - ratio * (b - a);
    var d = a + ratio * (b - a);
    var dc = object_distance(i, along(ray, c));
    var dd = object_distance(i, along(ray, d));
    var fc = dc * dc - r2;
    var fd = dd * dd - r2;
    for (var k = 0u; k < 48u; k += 1u) {
        if fc <= 0.0 || fd <= 0.0 || b - a <= 1e-6 * max(t_max, 1.0) {
            break;
        }
        // The minimum lies in [a, b], where the distance is at least either probe's less
        // the bracket's length: past the radius, a miss.
        if sqrt(max(fc, fd) + r2) - (b - a) > r {
            return FAR;
        }
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            let e = object_distance(i, along(ray, c));
            fc = e * e - r2;
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            let e = object_distance(i, along(ray, d));
            fd = e * e - r2;
        }
    }
    var inside = FAR;
    if fc <= 0.0 {
        inside = c;
    } else if fd <= 0.0 {
        inside = d;
    } else {
        let e = object_distance(i, along(ray, t_max));
        if e * e <= r2 {
            inside = t_max;
        } else {
            return FAR;
        }
    }
    // Bisection on [0, inside]: F > 0 at the left end, ≤ 0 at the right.
    var lo = 0.0;
    var hi = inside;
    for (var k = 0u; k < 40u; k += 1u) {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let e = object_distance(i, along(ray, mid));
        if e * e > r2 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return hi;
}

#ifdef HYPERBOLIC
// The squared distance from object i's shape (a ball, a fibre's tube or a horizontal
// geodesic's tube) at the ray's point, and half its rate of change along the ray's unit
// tangent: (d², d·d').
fn squared_distance_slope(i: u32, at: Ray) -> vec2<f32> {
    let shape = space.product_objects[i].shape;
    let info = space.product_objects[i].info;
    let kind = u32(info.x);
    let x = at.point;
    let vb = base_of(at.tangent);
    var db = 0.0;
    var slope = 0.0;
    var dz = 0.0;
    if kind == 2u {
        // The signed offset from the line: asinh s, s = ⟨m, x⟩ on the model, whose rate
        // is ⟨m, v⟩.
        let xb = base_of(x);
        let s = dot(shape, xb / sqrt(abs(kappa() * base_form(xb, xb))));
        db = asinh(s);
        slope = dot(shape, vb) / sqrt(1.0 + s * s);
        dz = x.z - info.z;
    } else {
        db = surface_distance(x, shape);
        slope = base_form(away_from(x, shape), vb);
        dz = select(x.z - shape.z, 0.0, kind == 1u);
    }
    return vec2<f32>(db * db + dz * dz, db * slope + dz * at.tangent.z);
}
#endif

// The unit tangent at p towards q (surface part along the surface geodesic, height part
// the difference in height, in proportion).
fn tangent_towards(p: vec4<f32>, q: vec4<f32>) -> vec4<f32> {
    let db = surface_distance(p, q);
    let v = -away_from(p, q) * db + vec4<f32>(0.0, 0.0, q.z - p.z, 0.0);
    let len = sqrt(base_form(v, v) + v.z * v.z);
    return select(vec4<f32>(0.0, 0.0, 1.0, 0.0), v / len, len > 0.0);
}

// A camera ray: the start put on the model, the direction made a unit tangent there.
fn product_ray(point: vec4<f32>, direction: vec4<f32>) -> Ray {
    return normalized(Ray(point, direction));
}

#ifdef WALLS
// What the walls crossed so far added and let through (Rust: `scene::walls::Veil`).
var<private> veil_colour: vec3<f32>;
var<private> veil_through: f32;

// The wall a ray meets entering the cell through `face` (the sides, then the top and the
// bottom), at distance d from the eye, added to the veil (Rust:
// `trace::product::walls::ProductWalls::cross`).
fn product_wall(face: u32, ray: Ray, d: f32) {
    let x = ray.point;
    let margin = space.wall_colours[face].w;
    let look = space.wall_looks[face];
    var on_panel = false;
    var facing = abs(ray.tangent.z);
    if face < face_count() {
        let along = look.z - surface_distance(x, space.wall_units[face]);
        let up = space.product.x - abs(x.z);
        on_panel = min(along, up) < margin;
        let c = space.covectors[face];
        let unit = c / sqrt(abs(c.x * c.x + c.y * c.y + kappa() * c.w * c.w));
        facing = abs(dot(unit, ray.tangent));
    } else if face_count() == 0u {
        on_panel = surface_distance(x, vec4<f32>(0.0, 0.0, 0.0, 1.0)) > margin;
    } else {
        for (var k = 0u; k < face_count(); k += 1u) {
            let c = space.covectors[k];
            let unit = c / sqrt(abs(c.x * c.x + c.y * c.y + kappa() * c.w * c.w));
            if line_offset(x, -unit) < margin {
                on_panel = true;
            }
        }
    }
    if !on_panel {
        return;
    }
    let lit = min(space.wall_colours[face].rgb * (0.55 + 0.45 * min(facing, 1.0)), vec3<f32>(1.0));
    let w = exp(-d / space.shading.params.x);
    let seen = w * lit + (1.0 - w) * space.shading.fog.rgb;
    veil_colour += veil_through * look.x * seen;
    veil_through *= 1.0 - look.x;
}
#endif

// What lies behind the walls, seen through them.
fn behind_walls(c: vec3<f32>) -> vec3<f32> {
#ifdef WALLS
    return veil_colour + veil_through * c;
#else
    return c;
#endif
}

// The product's falloff: the geodesic sphere's area per solid angle at the light, r² S(ρ)/ρ
// for a point ρ away on the surface (Rust: `light_spread`).
fn light_spread(db: f32, dz: f32) -> f32 {
    var ratio = 1.0 - kappa() * db * db / 6.0;
    if db >= 1.0e-2 {
        ratio = cs(db).y / db;
    }
    return (db * db + dz * dz) * max(ratio, 0.0);
}

#ifdef PRODUCT_SHADOWS
// Whether an object lies on the geodesic from the ray's start within `length`: a shadow ray
// walked through the faces as a camera ray is; one that runs out of crossings is clear
// (Rust: `product_occluded`).
fn product_occluded(start: Ray, length: f32) -> bool {
    let budget = u32(space.shading.params.w);
    var ray = start;
    var travelled = 0.0;
    var skip = NONE;
    var crossings = 0u;
    var steps = 0u;
    for (var guard = 0u; guard < 4u * budget + 256u; guard += 1u) {
        if travelled >= length {
            return false;
        }
        let exit = product_exit(ray, skip);
        if exit.face == NONE {
            return false;
        }
        let t_max = min(exit.distance, length - travelled);
        let mid = along(ray, 0.5 * t_max);
        for (var i = 0u; i < min(u32(space.product.y), #{PRODUCT_OBJECTS}u); i += 1u) {
            if first_meeting_within(i, ray, t_max, mid, 0.5 * t_max) < FAR {
                return true;
            }
        }
        if exit.distance >= length - travelled {
            return false;
        }
        travelled += exit.distance;
        ray = product_cross(ray, exit);
        skip = select(NONE, partner(exit.face), exit.face < face_count());
        if exit.face == CAP {
            steps += 1u;
            if steps > 64u {
                return false;
            }
            continue;
        }
        steps = 0u;
        crossings += 1u;
        if crossings > budget {
            return false;
        }
    }
    return false;
}
#endif

#ifdef PRODUCT_IMAGES
// One geodesic's light at x from an image: h along the surface in the unit direction u, dz
// up; Lambert's cosine, the fog's absorption, the falloff r² |S(h)|/h held at 1 or more,
// unless the k-th image is shadowed (Rust: `trace::product::lighting::paths_to` and
// `product_gather`).
fn path_light(x: vec4<f32>, normal: vec4<f32>, h: f32, u: vec4<f32>, dz: f32, k: u32) -> f32 {
    let info = space.product_lighting;
    let r = sqrt(h * h + dz * dz);
    if !(r > 0.0) || r > info.z {
        return 0.0;
    }
    let l = (u * h + vec4<f32>(0.0, 0.0, dz, 0.0)) / r;
    let cosine = base_form(normal, l) + normal.z * l.z;
    if cosine <= 0.0 {
        return 0.0;
    }
    var spread = r * r;
    if h >= 1.0e-4 {
        spread = r * r * abs(cs(h).y) / h;
    }
#ifdef PRODUCT_SHADOWS
    let offset = 1.0e-3;
    if k < u32(info.w) && r > offset {
        let start = moved(Ray(x, l), offset, false, 0.0, 1.0);
        if product_occluded(normalized(start), r - offset) {
            return 0.0;
        }
    }
#endif
    return cosine * exp(-r / space.shading.params.x) / max(spread, 1.0);
}

// The light at x (unit normal `normal`) along every geodesic to each image of the lamp
// within the reach, and the images beyond by their mean (Rust: `product_gather`).
fn product_gather(x: vec4<f32>, normal: vec4<f32>) -> f32 {
    let info = space.product_lighting;
    var sum = info.y;
    for (var k = 0u; k < min(u32(info.x), #{PRODUCT_IMAGES}u); k += 1u) {
        let q = space.product_images[k];
        let rho = surface_distance(x, q);
        let away = away_from(x, q);
        let dz = q.z - x.z;
#ifdef SPHERICAL
        // On the antipodal fibre every way round has a whole cone of directions.
        if rho > 3.14159265 - 1.0e-3 {
            continue;
        }
        sum += path_light(x, normal, rho, -away, dz, k);
        if rho < 1.0e-3 {
            continue;
        }
        // Each way round the great circle, until past the reach.
        for (var n = 1.0; n < 64.0; n += 1.0) {
            let back = 6.28318531 * n - rho;
            if back * back + dz * dz > info.z * info.z {
                break;
            }
            sum += path_light(x, normal, back, away, dz, k);
            sum += path_light(x, normal, back + 2.0 * rho, -away, dz, k);
        }
#else
        sum += path_light(x, normal, rho, -away, dz, k);
#endif
    }
    return sum;
}
#endif

// One camera ray's colour: the nearest object in each segment of the walk, shaded with the
// light (Lambert, the product's falloff, never more than at distance 1) and fog; the
// fog colour past the cut-off or the crossing budget (Rust: `trace_product_pixel`).
fn trace_product(start: Ray) -> vec3<f32> {
    let fog = space.shading.fog.rgb;
    let ambient = space.shading.fog.w;
    let lambda_fog = space.shading.params.x;
    let cutoff = space.shading.params.y;
    let budget = u32(space.shading.params.w);
    var ray = start;
    var travelled = 0.0;
    var skip = NONE;
    var crossings = 0u;
    var steps = 0u;
#ifdef COLOUR_BY
    var last_face = NONE;
    var held = mat4x4<f32>(
        vec4<f32>(1.0, 0.0, 0.0, 0.0),
        vec4<f32>(0.0, 1.0, 0.0, 0.0),
        vec4<f32>(0.0, 0.0, 1.0, 0.0),
        vec4<f32>(0.0, 0.0, 0.0, 1.0),
    );
#endif
#ifdef WALLS
    veil_colour = vec3<f32>(0.0);
    veil_through = 1.0;
#endif
    // The object met and where along the last segment; shaded after the walk, once (a SIMD
    // rasteriser such as llvmpipe runs an `if`'s body whenever any lane reaches it, so
    // shading inside the walk's loop was paid at every crossing).
    var met = NONE;
    var met_at = 0.0;
    for (var guard = 0u; guard < 4u * budget + 256u; guard += 1u) {
        if travelled >= cutoff {
            break;
        }
        let exit = product_exit(ray, skip);
        if exit.face == NONE {
            break;
        }
        let t_max = min(exit.distance, cutoff - travelled);
        var nearest = FAR;
        var object = NONE;
        let half = 0.5 * t_max;
        let mid = along(ray, half);
        for (var i = 0u; i < min(u32(space.product.y), #{PRODUCT_OBJECTS}u); i += 1u) {
            // Only a meeting before the nearest so far matters.
            let t = first_meeting_within(i, ray, min(t_max, nearest), mid, half);
            if t < nearest {
                nearest = t;
                object = i;
            }
        }
        if object != NONE {
            met = object;
            met_at = nearest;
            break;
        }
        if exit.distance >= cutoff - travelled {
            break;
        }
        travelled += exit.distance;
        ray = product_cross(ray, exit);
        skip = select(NONE, partner(exit.face), exit.face < face_count());
        if exit.face == CAP {
            steps += 1u;
            if steps > 64u {
                break;
            }
            continue;
        }
        steps = 0u;
        crossings += 1u;
        if crossings > budget {
            break;
        }
#ifdef COLOUR_BY
        last_face = exit.face;
        held = space.pairings[exit.face] * held;
#endif
#ifdef WALLS
        var entered = skip;
        if skip == NONE {
            entered = select(face_count(), face_count() + 1u, exit.face == face_count());
        }
        product_wall(entered, ray, travelled);
        if veil_through < space.wall_style.x {
            break;
        }
#endif
    }
    if met != NONE {
        let hit = moved(ray, met_at, false, 0.0, 1.0);
        let at = hit.point;
        var normal = object_normal(met, at);
        if u32(space.product_objects[met].info.x) >= 3u
            && base_form(normal, hit.tangent) + normal.z * hit.tangent.z > 0.0 {
            // A flat piece is lit on the side the ray comes from.
            normal = -normal;
        }
#ifdef PRODUCT_IMAGES
        let light = product_gather(at, normal);
#else
        // The older model: the lamp in the cell only, unabsorbed.
        let to_light = tangent_towards(at, space.product_light);
        let spread = light_spread(
            surface_distance(at, space.product_light),
            at.z - space.product_light.z,
        );
        let light = max(base_form(normal, to_light) + normal.z * to_light.z, 0.0)
            / max(spread, 1.0);
#endif
        let lit = ambient + (1.0 - ambient) * light;
        var surface = min(space.product_objects[met].colour.rgb * lit, vec3<f32>(1.0));
#ifdef COLOUR_BY
        surface = recolour(colour_by_tint(crossings, last_face, held), surface);
#endif
        let w = exp(-(travelled + met_at) / lambda_fog);
        return behind_walls(w * surface + (1.0 - w) * fog);
    }
    return behind_walls(fog);
}
