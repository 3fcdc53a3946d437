// The cell's walls with windows, met where a ray crosses a face.
// The Rust twin: `scene::walls`.
#define_import_path curved_spaces::walls

#import curved_spaces::layout::{kappa, space}
#import curved_spaces::geometry::{form}
#import curved_spaces::walk::{Exit, Ray, faces_of_cell}

#ifdef WALLS
// What the walls crossed so far added and let through (Rust: `scene::Veil`).
var<private> veil_colour: vec3<f32>;
var<private> veil_through: f32;

// The wall a ray meets leaving through `exit` at distance `d` from the eye, added to the veil
// (Rust: `WallPanels::cross`): on the panel where some other face g is nearer than
// S(w)·sin θ_fg, lit by the angle of incidence, fogged, blended by its opacity.
fn cross_wall(ray: Ray, exit: Exit, d: f32) {
    let f = exit.face;
    let at_face = ray.point * exit.den + ray.tangent * exit.num;
    var x = at_face / length(at_face);
#ifdef EUCLIDEAN
    x = at_face / at_face.w;
#endif
#ifdef HYPERBOLIC
    x = at_face / sqrt(-form(at_face, at_face));
#endif
    let unit = space.wall_units[f];
    let margin = space.wall_colours[f].w;
    var on_panel = false;
    let faces = faces_of_cell(f);
    for (var g = faces.x; g < faces.y; g += 1u) {
        let other = space.wall_units[g];
        let c = form(unit, other);
        let sine = sqrt(max(1.0 - c * c, 0.0));
        if g != f && -dot(other, x) < margin * sine {
            on_panel = true;
        }
    }
    if !on_panel {
        return;
    }
    let along = ray.point * (-kappa() * exit.num) + ray.tangent * exit.den;
    let facing = min(abs(dot(unit, along)) / sqrt(form(along, along)), 1.0);
    let look = space.wall_looks[f];
    let light = select(0.55 + 0.45 * facing, 0.55 + 0.45 * (1.0 - facing), look.y > 0.5);
    let lit = min(space.wall_colours[f].rgb * light, vec3<f32>(1.0));
    let w = exp(-d / space.shading.params.x);
    let seen = w * lit + (1.0 - w) * space.shading.fog.rgb;
    veil_colour += veil_through * look.x * seen;
    veil_through *= 1.0 - look.x;
}
#endif
