// Nil (shader def NIL): the GPU twin of the CPU reference in src/trace/nil, in f32, on
// Nil's geometry (`curved_spaces::nil_geometry`, the twin of src/space/nil). A ray walks the
// box by exits solved in closed form or bracketed, comes back by the lattice element of the
// face it left, and meets metric balls, fibre tubes and swept discs by steps safe by a
// Lipschitz bound, refined by bisection (a fibre tube in closed form, where the ray's shadow
// comes within its radius). Light comes along the shortest geodesic to each image of the
// lamp; walls with windows and the teaching views as in the other families.
#define_import_path curved_spaces::nil

#import curved_spaces::layout::{space}
#import curved_spaces::nil_geometry::{NIL_FAR, NIL_NONE, NIL_PI, NilRay, nil_atan_over, nil_exit, nil_flow, nil_h, nil_product, nil_shortest, nil_through, nil_vertical_exit}
#ifdef COLOUR_BY
#import curved_spaces::shading::{recolour_unturned}
#endif

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

// The chart box of the segment of length t_max (Rust: `segment_box`): its lowest and
// highest corner, widened by a hair for f32's rounding.
struct NilBox {
    lo: vec3<f32>,
    hi: vec3<f32>,
}

fn nil_segment_box(ray: NilRay, t_max: f32) -> NilBox {
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
    return NilBox(lo, hi);
}

// Whether the segment's chart box meets object i's.
fn nil_box_meets(i: u32, segment: NilBox) -> bool {
    let o = space.nil_objects[i];
    return all((segment.lo <= o.box_hi.xyz)) && all((o.box_lo.xyz <= segment.hi));
}

// The nearest object met within t_max: (index, t); index NIL_OBJECTS for none. Where not
// `exact` (a shadow ray), the first found.
fn nil_nearest(ray: NilRay, t_max: f32, exact: bool) -> vec2<f32> {
    var best = t_max;
    var index = #{NIL_OBJECTS}u;
    // The segment's chart box, made once and again only where a hit shortens the segment.
    var segment = nil_segment_box(ray, best);
    for (var i = 0u; i < u32(space.nil_box.z); i += 1u) {
        if !nil_box_meets(i, segment) || nil_clearance(i, ray.p) > best {
            continue;
        }
        let t = nil_meeting(i, ray, best, exact);
        if (t >= 0.0) && ((index == #{NIL_OBJECTS}u) || (t < best)) {
            best = t;
            index = i;
            if !exact {
                break;
            }
            segment = nil_segment_box(ray, best);
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
    // The object met (NIL_OBJECTS: none), the distance, the ray there, the crossings and the
    // face crossed last (0xffffffff: none).
    index: u32,
    distance: f32,
    at: NilRay,
    crossings: u32,
    last_face: u32,
}

// Walks the ray to its first object within `length`, through at most `budget` faces; where
// not `exact` (a shadow ray), only whether it meets one is sure.
fn nil_walk(start: NilRay, length: f32, budget: u32, exact: bool) -> NilEnd {
    var ray = start;
    var distance = 0.0;
    var crossings = 0u;
    var last_face = 0xffffffffu;
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
            return NilEnd(u32(hit.x), distance + hit.y, nil_flow(ray, hit.y), crossings, last_face);
        }
        if exit.y >= length - distance {
            break;
        }
        let here = ray;
        ray = nil_through(ray, face, exit.y);
        distance += exit.y;
        crossings += 1u;
        last_face = face;
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
    return NilEnd(#{NIL_OBJECTS}u, distance, ray, crossings, last_face);
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
        // Past the reach by the root-free floor of the distance: no root to find.
        if nil_distance_floor(space.nil_images[k].xyz, x) > lighting.z {
            continue;
        }
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
    var surface = min(o.colour.rgb * lit, vec3<f32>(1.0));
#ifdef COLOUR_BY
    // A left translation turns nothing: the copy's rotation is always none.
    surface = recolour_unturned(end.crossings, end.last_face, surface);
#endif
    let w = exp(-end.distance / shading.params.x);
    return nil_behind_walls(w * surface + (1.0 - w) * shading.fog.rgb);
}
