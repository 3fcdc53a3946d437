// Shading: the teaching views' tints and the light at a point.
// The Rust twin: `scene::shading`.
#define_import_path curved_spaces::shading

#import curved_spaces::layout::{kappa, space}
#ifdef LIGHTS
#import curved_spaces::lighting::{light_from}
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

// `surface` recoloured by the tint after `crossings` crossings, the last through
// `last_face`, in a copy that turns nothing (Nil's left translations; SL̃(2,R), whose
// holonomy view is not written): the crossings and the face alone.
fn recolour_unturned(crossings: u32, last_face: u32, surface: vec3<f32>) -> vec3<f32> {
    let unturned = mat4x4<f32>(
        vec4<f32>(1.0, 0.0, 0.0, 0.0),
        vec4<f32>(0.0, 1.0, 0.0, 0.0),
        vec4<f32>(0.0, 0.0, 1.0, 0.0),
        vec4<f32>(0.0, 0.0, 0.0, 1.0),
    );
    return recolour(colour_by_tint(crossings, last_face, unturned), surface);
}
#endif

fn shade(point: vec4<f32>, normal: vec4<f32>, albedo: vec3<f32>, emission: vec3<f32>, d: f32) -> vec3<f32> {
    let ambient = space.shading.fog.w;
    var lit = vec3<f32>(ambient);
#ifdef LIGHTS
    for (var i = 0u; i < #{LIGHT_COUNT}u; i += 1u) {
        lit += (1.0 - ambient) * space.lights[i].colour.rgb * light_from(i, point, normal);
    }
#endif
    var surface = min(albedo * lit + emission, vec3<f32>(1.0));
#ifdef COLOUR_BY
    surface = recolour(colour_tint, surface);
#endif
    let w = exp(-d / space.shading.params.x);
    return w * surface + (1.0 - w) * space.shading.fog.rgb;
}
