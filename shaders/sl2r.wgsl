// SL̃(2,R) (shader def SL2R): the GPU twin of the CPU reference in src/trace/sl2r, in f32,
// on the geometry of curved_spaces::sl2r_geometry (the flow, the sides' and tubes' crossing,
// the inverse exponential map). The sides' covectors, pairings (3×3 in a mat4, with what
// rounding left out) and partners are the face arrays; the tubes follow, then (SL2R_BALLS)
// the metric balls: safe steps by the distance and its root-free floor, Newton's steps near
// the sphere. Surfaces are lit by the lamp along the shortest geodesic to each of its images
// within reach (sl2r_gather; SL2R_SHADOWS: shadow rays by the camera's own walk, sl2r_walk).
// (SL2R_COVER) a fibre cover: the walk counts the sheet it is on as the CPU's
// space::sl2r::cover does — the fibre angle's wrapped change over pieces too short to turn
// it by π, and each side's turn (its lift at the side's midpoint beside the covector) — and a
// ball (and a lamp image) is met only on its own sheet. (WALLS) the sides drawn as walls with
// windows, met where the walk crosses them (Rust: trace::sl2r::walls).
#define_import_path curved_spaces::sl2r

#import curved_spaces::layout::{space}
#import curved_spaces::sl2r_geometry::{SL2R_NONE, SL2R_PI, Sl2rRay, sl2r_crossing, sl2r_floor, sl2r_flow, sl2r_lorentz, sl2r_on_model, sl2r_perp, sl2r_shortest}
#ifdef COLOUR_BY
#import curved_spaces::shading::{recolour_unturned}
#endif

fn sl2r_partner(face: u32) -> u32 {
    return space.partners[face / 4u][face % 4u];
}

// The frame vector v moved by side `face`'s pairing (its nearest f32 matrix and the rest).
fn sl2r_paired(face: u32, v: vec3<f32>) -> vec3<f32> {
    let x = vec4<f32>(v, 0.0);
    return (space.pairings[face] * x + space.pairings_lo[face] * x).xyz;
}

#ifdef SL2R_COVER
const SL2R_TAU: f32 = 6.28318530717959;
const SL2R_BALL_VECS: u32 = 4u;

// The fibre angle of e at p: from the radially parallel field (the boost of the origin's
// (1, 0, 0) to p), as the chart's θ.
fn sl2r_fibre_angle(e: vec3<f32>, p: vec3<f32>) -> f32 {
    let k = 1.0 / (1.0 + p.z);
    let e1 = vec3<f32>(1.0 + p.x * p.x * k, p.x * p.y * k, p.x);
    let e2 = vec3<f32>(p.x * p.y * k, 1.0 + p.y * p.y * k, p.y);
    return atan2(sl2r_lorentz(e, e2), sl2r_lorentz(e, e1));
}

// The sheets r climbs over [0, t] to the frame `end`: the angle turns by less than π over a
// piece of length 2 (|dθ/dt| ≤ √2), so each piece's wrapped change is its change.
fn sl2r_climbed(r: Sl2rRay, t: f32, end: Sl2rRay) -> f32 {
    let pieces = u32(clamp(ceil(t / 2.0), 1.0, 64.0));
    var previous = sl2r_fibre_angle(r.e, r.p);
    var climbed = 0.0;
    for (var i = 1u; i <= pieces; i += 1u) {
        var at = end;
        if i < pieces {
            at = sl2r_flow(r, t * f32(i) / f32(pieces));
        }
        let angle = sl2r_fibre_angle(at.e, at.p);
        climbed -= round((angle - previous) / SL2R_TAU);
        previous = angle;
    }
    return climbed;
}

// `sheet + by` among the cover's sheets.
fn sl2r_sheet_plus(sheet: f32, by: f32) -> f32 {
    let n = space.sl2r.z;
    let k = sheet + by;
    return k - n * floor(k / n);
}
#else
const SL2R_BALL_VECS: u32 = 3u;
#endif

#ifdef SL2R_COVER
// The sheets a crossing of side `face` climbs, from the frame `at` on the side to `moved`:
// the pairing adds its turn (the lift at the midpoint plus the wrapped change from there).
fn sl2r_sheets_through(face: u32, at: Sl2rRay, moved: Sl2rRay) -> f32 {
    let k = 1.0 / (1.0 + at.p.z);
    let e1 = vec3<f32>(1.0 + at.p.x * at.p.x * k, at.p.x * at.p.y * k, at.p.x);
    let raw = sl2r_fibre_angle(sl2r_paired(face, e1), sl2r_paired(face, at.p));
    let d = raw - space.covectors[face].w;
    let turn = space.pairings_lo[face][3][3] + d - SL2R_TAU * round(d / SL2R_TAU);
    let lifted = sl2r_fibre_angle(at.e, at.p) + turn;
    return round((lifted - sl2r_fibre_angle(moved.e, moved.p)) / SL2R_TAU);
}
#endif

// Beyond this gap over the radius the distance's floor alone gives the step.
const SL2R_BALL_FAR: f32 = 0.5;

#ifdef SL2R_BALLS
// Ball j's gap d − r at `at` and the rate along at's velocity (2, no cosine, where only a
// floor is known).
fn sl2r_ball_gap(base: u32, at: Sl2rRay) -> vec2<f32> {
    let pc = space.sl2r_objects[base].xyz;
    let radius = space.sl2r_objects[base].w;
    let ec = space.sl2r_objects[base + 1u].xyz;
    let fl = sl2r_floor(ec, pc, at);
    if fl > radius + SL2R_BALL_FAR {
        return vec2<f32>(fl - radius, 2.0);
    }
    let fc = sl2r_perp(pc, ec);
    let geo = sl2r_shortest(ec, fc, pc, at, radius + SL2R_BALL_FAR);
    if geo.x < 0.0 {
        return vec2<f32>(max(fl - radius, SL2R_BALL_FAR), 2.0);
    }
    let n = sl2r_flow(Sl2rRay(ec, fc, pc, geo.yzw), geo.x).v;
    return vec2<f32>(geo.x - radius, dot(n, at.v));
}

// The first t in [start, t_max] at which r comes within ball j's radius (SL2R_NONE: never):
// safe steps by the floor's gap far away, Newton's steps near (safe by convexity).
fn sl2r_ball_hit(base: u32, r: Sl2rRay, start: f32, t_max: f32) -> f32 {
    var t = start;
    for (var i = 0u; i < 64u; i += 1u) {
        // The segment's start is the ray itself: no flow (most balls end at the first step).
        var at = r;
        if t > 0.0 {
            at = sl2r_flow(r, t);
        }
        let g = sl2r_ball_gap(base, at);
        if g.x <= 2e-5 * (1.0 + t) {
            return t;
        }
        // The distance is convex below π (the curvature is at most ¼): Newton's steps stay
        // before the root, and moving away at d < π there is no hit before another
        // (π − d) + (π − r). Where only the floor is known (g.y = 2), its gap is safe.
        var step = g.x;
        if g.y >= 0.0 && g.y <= 1.0 {
            step = 2.0 * SL2R_PI - g.x - 2.0 * space.sl2r_objects[base].w;
        } else if g.y < 0.0 {
            step = g.x / -g.y;
        }
        t += step;
        if t > t_max {
            return SL2R_NONE;
        }
    }
    return SL2R_NONE;
}

#ifdef SL2R_COVER
// Whether r (on `sheet`) at t is on the sheet of the ball at `base` (its sheet and fibre
// angle in its fourth vec4): the lifted angles within π of each other, modulo 2πN (the lifts
// of one ball are 2π apart along the fibre; the shortest geodesic from the centre to a point
// of the ball turns the angle by less than √2·r).
fn sl2r_on_ball_sheet(base: u32, r: Sl2rRay, sheet: f32, t: f32) -> bool {
    let own = space.sl2r_objects[base + 3u];
    let whole = SL2R_TAU * space.sl2r.z;
    let at = sl2r_flow(r, t);
    let on = sheet + sl2r_climbed(r, t, at);
    var apart = sl2r_fibre_angle(at.e, at.p) - own.y + SL2R_TAU * (on - own.x);
    apart -= whole * round(apart / whole);
    return abs(apart) < SL2R_PI;
}
#endif

// The outward normal of the ball at `base` at `at`, in at's body frame (the distance's
// gradient: minus the shortest geodesic's end velocity from the centre), or 0 where the
// solver finds none.
fn sl2r_ball_normal(base: u32, at: Sl2rRay) -> vec3<f32> {
    let pc = space.sl2r_objects[base].xyz;
    let radius = space.sl2r_objects[base].w;
    let ec = space.sl2r_objects[base + 1u].xyz;
    let fc = sl2r_perp(pc, ec);
    let geo = sl2r_shortest(ec, fc, pc, at, radius + SL2R_BALL_FAR);
    if geo.x < 0.0 {
        return vec3<f32>(0.0);
    }
    return sl2r_flow(Sl2rRay(ec, fc, pc, geo.yzw), geo.x).v;
}
#endif

// The outward normal of tube j at `at`, in at's body frame (horizontal, away from its
// fibre), or 0 on the fibre itself.
fn sl2r_tube_normal(j: u32, at: Sl2rRay) -> vec3<f32> {
    let q = space.sl2r_objects[2u * j].xyz;
    let u = -(q + sl2r_lorentz(q, at.p) * at.p);
    let len = sqrt(max(sl2r_lorentz(u, u), 0.0));
    if len <= 0.0 {
        return vec3<f32>(0.0);
    }
    return vec3<f32>(sl2r_lorentz(u, at.e) / len, sl2r_lorentz(u, at.f) / len, 0.0);
}

// The area of the geodesic sphere of radius r per solid angle, at the end of a geodesic of
// vertical velocity c (Rust: `trace::sl2r::light::area_density`): r·S + (r·S − 2K)/ω² with
// ω² = 1 − 2c², the series in x = ω²r² near 0.
fn sl2r_area_density(r: f32, c: f32) -> f32 {
    let w2 = 1.0 - 2.0 * c * c;
    let x = w2 * r * r;
    var a = 0.0;
    if abs(x) < 0.5 {
        var s = 0.0;
        var p = 0.0;
        var term_s = 1.0;
        var term_p = 2.0 / 24.0;
        for (var k = 0u; k < 6u; k += 1u) {
            s += term_s;
            p += term_p;
            let kf = f32(k);
            term_s *= x / ((2.0 * kf + 2.0) * (2.0 * kf + 3.0));
            term_p *= x * (kf + 2.0) / ((kf + 1.0) * (2.0 * kf + 5.0) * (2.0 * kf + 6.0));
        }
        a = r * r * s + r * r * r * r * p;
    } else if w2 > 0.0 {
        let w = sqrt(w2);
        let sh = sinh(w * r) / w;
        let k = (cosh(w * r) - 1.0) / w2;
        a = r * sh + (r * sh - 2.0 * k) / w2;
    } else {
        let w = sqrt(-w2);
        let sh = sin(w * r) / w;
        let k = (1.0 - cos(w * r)) / -w2;
        a = r * sh + (r * sh - 2.0 * k) / w2;
    }
    return abs(a);
}

// The light reaching the point `at` (on `sheet`) of a surface with outward normal `normal`
// (Rust: `trace::sl2r::light::gather`): along the shortest geodesic to each image of the
// lamp within the reach that ends on the image's sheet, shadowed for the nearest ones, and
// the tail.
fn sl2r_gather(at: Sl2rRay, sheet: f32, normal: vec3<f32>) -> f32 {
    let light = space.sl2r_light;
    let lighting = space.sl2r_lighting;
    let reach = light.z;
    let cosh_reach = cosh(reach);
    var sum = 0.0;
    for (var k = 0u; k < u32(lighting.x); k += 1u) {
        let qi = space.sl2r_images[2u * k + 1u].xyz;
        // Past the reach by the base distance (one Lorentz product), then by the floor.
        if -sl2r_lorentz(qi, at.p) > cosh_reach {
            continue;
        }
        let fi = space.sl2r_images[2u * k];
        if sl2r_floor(fi.xyz, qi, at) > reach {
            continue;
        }
        let image = Sl2rRay(fi.xyz, sl2r_perp(qi, fi.xyz), qi, vec3<f32>(0.0));
        let path = sl2r_shortest(at.e, at.f, at.p, image, reach);
        if path.x < 0.0 {
            continue;
        }
        let cos_l = dot(normal, path.yzw);
        if !(cos_l > 0.0 && path.x > 0.0) {
            continue;
        }
        let ray = Sl2rRay(at.e, at.f, at.p, path.yzw);
#ifdef SL2R_COVER
        if sl2r_sheet_plus(sheet, sl2r_climbed(ray, path.x, image)) != fi.w {
            continue;
        }
#endif
#ifdef SL2R_SHADOWS
        if f32(k) < light.w && path.x > 1.0e-3 {
            let start = sl2r_on_model(sl2r_flow(ray, 1.0e-3));
            var on = 0.0;
#ifdef SL2R_COVER
            on = sl2r_sheet_plus(sheet, sl2r_climbed(ray, 1.0e-3, start));
#endif
            let budget = u32(space.shading.params.w);
            if sl2r_walk(start, on, path.x - 1.0e-3, budget, false).hit != SL2R_MISS {
                continue;
            }
        }
#endif
        sum += cos_l * exp(-path.x / space.shading.params.x) / max(sl2r_area_density(path.x, path.w), light.y);
    }
    return sum + lighting.y;
}

// `colour` lit at `at` (on `sheet`) with outward normal `normal` (0: none found, ambient
// only).
fn sl2r_lit(colour: vec3<f32>, at: Sl2rRay, sheet: f32, normal: vec3<f32>) -> vec3<f32> {
    let ambient = space.shading.fog.w;
    if dot(normal, normal) == 0.0 {
        return colour * ambient;
    }
    let light = sl2r_gather(at, sheet, normal);
    return min(colour * (ambient + (1.0 - ambient) * space.sl2r_light.x * light), vec3<f32>(1.0));
}

#ifdef WALLS
// What the walls crossed so far added and let through (Rust: `scene::walls::Veil`).
var<private> sl2r_veil_colour: vec3<f32>;
var<private> sl2r_veil_through: f32;

// The wall a ray meets crossing side `face` at `at`, `d` from the eye, added to the veil
// (Rust: `Sl2rWalls::cross`): on the panel where the base point is farther along the side
// from its midpoint than the window reaches (asinh ⟨p, t⟩, t the side's direction there),
// lit by the angle to the side's normal. Whether enough light still gets through.
fn sl2r_wall(face: u32, at: Sl2rRay, d: f32) -> bool {
    let along = asinh(sl2r_lorentz(at.p, space.wall_units[face].xyz));
    if abs(along) > space.wall_colours[face].w {
        let looks = space.wall_looks[face];
        let n = looks.yzw;
        let normal = vec3<f32>(sl2r_lorentz(n, at.e), sl2r_lorentz(n, at.f), 0.0);
        let facing = min(abs(dot(normal, at.v)), 1.0);
        let lit = min(space.wall_colours[face].rgb * (0.55 + 0.45 * facing), vec3<f32>(1.0));
        let w = exp(-d / space.shading.params.x);
        let seen = w * lit + (1.0 - w) * space.shading.fog.rgb;
        sl2r_veil_colour += sl2r_veil_through * looks.x * seen;
        sl2r_veil_through *= 1.0 - looks.x;
    }
    return sl2r_veil_through >= space.wall_style.x;
}
#endif

// What lies behind the walls crossed, seen through them.
fn sl2r_behind_walls(c: vec3<f32>) -> vec3<f32> {
#ifdef WALLS
    return sl2r_veil_colour + sl2r_veil_through * c;
#else
    return c;
#endif
}

// Where a walk ended: the object met (tube j, or a ball's first vec4; SL2R_MISS: none), the
// segment it is met in (its start ray, the sheet there, the distance walked to it) and the
// time along it, the crossings and the last face crossed.
const SL2R_MISS: u32 = 0xffffffffu;

struct Sl2rEnd {
    hit: u32,
    ball: bool,
    r: Sl2rRay,
    sheet: f32,
    walked: f32,
    t: f32,
    crossings: u32,
    last_face: u32,
}

// Walks r (on `sheet`) through the sides for `length` and at most `budget` crossings to the
// first object it meets (Rust: `trace::sl2r::walk_to_object`); through the walls where
// `veiled` (the camera's rays; a shadow ray passes them).
fn sl2r_walk(start: Sl2rRay, start_sheet: f32, length: f32, budget: u32, veiled: bool) -> Sl2rEnd {
    var r = start;
    var sheet = start_sheet;
    var walked = 0.0;
    var entered = SL2R_MISS;
    var last_face = SL2R_MISS;
    for (var crossings = 0u; crossings <= budget; crossings += 1u) {
        // The side left first.
        var exit_t = 1e30;
        var exit_face = SL2R_MISS;
        for (var i = 0u; i < #{FACE_COUNT}u; i += 1u) {
            let t = sl2r_crossing(r, space.covectors[i].xyz, 0.0);
            if t < 0.0 || (i == entered && t == 0.0) {
                continue;
            }
            if t < exit_t {
                exit_t = t;
                exit_face = i;
            }
        }
        let segment = select(length - walked, exit_t, exit_face != SL2R_MISS);
        let within = min(segment, length - walked);
        // The nearest tube within it.
        var hit_t = 1e30;
        var hit = SL2R_MISS;
        for (var j = 0u; j < u32(space.sl2r.x); j += 1u) {
            let q = space.sl2r_objects[2u * j];
            let t = sl2r_crossing(r, vec3<f32>(q.x, q.y, -q.z), space.sl2r_objects[2u * j + 1u].w);
            if t >= 0.0 && t <= within && t < hit_t {
                hit_t = t;
                hit = j;
            }
        }
        var hit_ball = false;
#ifdef SL2R_BALLS
        let balls_at = 2u * u32(space.sl2r.x);
        // The base point moves at most `reach` in H², and the distance is at least the base
        // distance: a ball whose centre's base point is farther than reach + r is passed by
        // one Lorentz product.
        let reach = min(hit_t, within);
        let cosh_reach = cosh(reach);
        let sinh_reach = sinh(reach);
        for (var j = 0u; j < u32(space.sl2r.y); j += 1u) {
            let base = balls_at + SL2R_BALL_VECS * j;
            let centre = space.sl2r_objects[base];
            // cosh(reach + r) by the sum formula (cosh r and sinh r are packed with the ball).
            let far = cosh_reach * space.sl2r_objects[base + 1u].w
                + sinh_reach * space.sl2r_objects[base + 2u].w;
            if -sl2r_lorentz(r.p, centre.xyz) > far {
                continue;
            }
#ifdef SL2R_COVER
            // A hit of another sheet's lift is passed (a chord of at most 2r) and the search
            // goes on beyond it.
            var t = SL2R_NONE;
            var past = 0.0;
            for (var k = 0u; k < 8u; k += 1u) {
                t = sl2r_ball_hit(base, r, past, reach);
                if t < 0.0 || sl2r_on_ball_sheet(base, r, sheet, t) {
                    break;
                }
                past = t + 2.0 * centre.w + 1e-4;
                t = SL2R_NONE;
            }
#else
            let t = sl2r_ball_hit(base, r, 0.0, reach);
#endif
            if t >= 0.0 && t < hit_t {
                hit_t = t;
                hit = base;
                hit_ball = true;
            }
        }
#endif
        if hit != SL2R_MISS {
            return Sl2rEnd(hit, hit_ball, r, sheet, walked, hit_t, crossings, last_face);
        }
        walked += segment;
        if exit_face == SL2R_MISS || walked >= length {
            break;
        }
        let at = sl2r_flow(r, exit_t);
#ifdef WALLS
        if veiled && !sl2r_wall(exit_face, at, walked) {
            break;
        }
#endif
        let moved = sl2r_on_model(Sl2rRay(
            sl2r_paired(exit_face, at.e),
            sl2r_paired(exit_face, at.f),
            sl2r_paired(exit_face, at.p),
            at.v,
        ));
#ifdef SL2R_COVER
        sheet = sl2r_sheet_plus(
            sheet,
            sl2r_climbed(r, exit_t, at) + sl2r_sheets_through(exit_face, at, moved),
        );
#endif
        r = moved;
        entered = sl2r_partner(exit_face);
        last_face = exit_face;
    }
    return Sl2rEnd(SL2R_MISS, false, r, sheet, walked, 0.0, 0u, last_face);
}

// The colour seen from the eye frame f (the viewer's axes as body vectors with e in their
// fourth entries, the base point in the last column) through the lens point (px, py): the
// first object met, lit by the lamp and fogged, else the fog.
fn sl2r_eye_colour(frame: mat4x4<f32>, px: f32, py: f32) -> vec3<f32> {
    let d = normalize(px * frame[0].xyz + py * frame[1].xyz - frame[2].xyz);
    let p = frame[3].xyz;
    let e = vec3<f32>(frame[0].w, frame[1].w, frame[2].w);
    let r = Sl2rRay(e, sl2r_perp(p, e), p, d);
    var sheet = 0.0;
#ifdef SL2R_COVER
    // The eye's sheet rides in the frame's last entry (1 + sheet).
    sheet = round(frame[3].w - 1.0);
#endif
    let shading = space.shading;
#ifdef WALLS
    sl2r_veil_colour = vec3<f32>(0.0);
    sl2r_veil_through = 1.0;
#endif
    let end = sl2r_walk(r, sheet, shading.params.y, u32(shading.params.w), true);
    if end.hit == SL2R_MISS {
        return sl2r_behind_walls(shading.fog.rgb);
    }
    let at = sl2r_flow(end.r, end.t);
    var on = end.sheet;
#ifdef SL2R_COVER
    on = sl2r_sheet_plus(on, sl2r_climbed(end.r, end.t, at));
#endif
    var surface = vec3<f32>(0.0);
    if end.ball {
#ifdef SL2R_BALLS
        surface = sl2r_lit(space.sl2r_objects[end.hit + 2u].rgb, at, on, sl2r_ball_normal(end.hit, at));
#endif
    } else {
        surface = sl2r_lit(space.sl2r_objects[2u * end.hit + 1u].rgb, at, on, sl2r_tube_normal(end.hit, at));
    }
#ifdef COLOUR_BY
    surface = recolour_unturned(end.crossings, end.last_face, surface);
#endif
    let w = exp(-(end.walked + end.t) / shading.params.x);
    return sl2r_behind_walls(w * surface + (1.0 - w) * shading.fog.rgb);
}
