// The product geometries' tracer (shader def PRODUCT with HYPERBOLIC or SPHERICAL): the
// walls, the lamp's light along every geodesic to its images, one camera ray's colour.
// The walk is in product_walk.wgsl, the objects in product_objects.wgsl; the Rust twin is
// `trace::product`.
#define_import_path curved_spaces::product

#import curved_spaces::layout::{face_count, kappa, space}
#import curved_spaces::walk::{Ray, partner}
#import curved_spaces::shading::{colour_by_tint, recolour}
#import curved_spaces::product_walk::{CAP, FAR, NONE, along, away_from, base_form, base_of, cs, line_offset, moved, normalized, product_cross, product_exit, surface_distance}
#import curved_spaces::product_objects::{first_meeting, first_meeting_within, object_normal}

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

// The colour seen from the eye `p` in the direction `d`: the entry point every family's
// tracer module has under this name (curved_space.wgsl calls it).
fn ray_colour(p: vec4<f32>, d: vec4<f32>) -> vec3<f32> {
    return trace_product(product_ray(p, d));
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
