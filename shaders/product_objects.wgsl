// The objects of a product scene (H²×R, S²×R): distances, normals and the first meeting
// of a segment of the walk with each, found exactly: the triangles and discs in closed
// form, the balls and tubes as the first root of d² − r² (Rust: `trace::product`).
#define_import_path curved_spaces::product_objects

#import curved_spaces::layout::{ProductObject, kappa, space}
#import curved_spaces::walk::Ray
#import curved_spaces::product_walk::{FAR, QUARTER_PI, along, away_from, base_form, base_of, line_offset, moved, speed_squared, surface_distance}

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
    if kind == 3u {
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
    // on the default scene: eight lanes that part pay for both.) That search needs one
    // minimum in its interval, so it runs on pieces of at most π/4 of surface arc, each
    // after a midpoint test of its own; the walk's segments are longer (`SEGMENT_ARC`), so
    // an object far from a segment is turned away once for all its pieces.
    let lambda = sqrt(max(speed_squared(ray.point, base_of(ray.tangent)), 0.0));
    let n = u32(clamp(ceil(lambda * t_max / QUARTER_PI), 1.0, 8.0));
    let piece = t_max / f32(n);
    for (var k = 0u; k < n; k += 1u) {
        let a = piece * f32(k);
        let b = select(a + piece, t_max, k + 1u == n);
        if n > 1u && object_distance(i, along(ray, 0.5 * (a + b))) > 0.5 * (b - a) + r {
            continue;
        }
        let t = bracketed_meeting(i, ray, a, b, r2);
        if t < FAR {
            return t;
        }
    }
    return FAR;
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

// The first root of F = d² − r² in [lo, hi] where F is only unimodal: a golden-section
// search for a point inside, then a bracketed search for the root before it.
fn bracketed_meeting(i: u32, ray: Ray, lo: f32, hi: f32, r2: f32) -> f32 {
    let r = sqrt(r2);
    var start = ray.point;
    if lo > 0.0 {
        start = along(ray, lo);
    }
    let d0 = object_distance(i, start);
    if d0 * d0 <= r2 {
        return lo;
    }
    let ratio = 0.6180339887498949;
    var a = lo;
    var b = hi;
    var c = b - ratio * (b - a);
    var d = a + ratio * (b - a);
    var dc = object_distance(i, along(ray, c));
    var dd = object_distance(i, along(ray, d));
    var fc = dc * dc - r2;
    var fd = dd * dd - r2;
    for (var k = 0u; k < 48u; k += 1u) {
        if fc <= 0.0 || fd <= 0.0 || b - a <= 1e-6 * max(hi, 1.0) {
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
        let e = object_distance(i, along(ray, hi));
        if e * e <= r2 {
            inside = hi;
        } else {
            return FAR;
        }
    }
    // Bisection on [lo, inside]: F > 0 at the left end, ≤ 0 at the right.
    var left = lo;
    var right = inside;
    for (var k = 0u; k < 40u; k += 1u) {
        let mid = 0.5 * (left + right);
        if mid <= left || mid >= right {
            break;
        }
        let e = object_distance(i, along(ray, mid));
        if e * e > r2 {
            left = mid;
        } else {
            right = mid;
        }
    }
    return right;
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
