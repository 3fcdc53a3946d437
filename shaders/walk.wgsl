// The walk through the cell: exit faces and crossings by the pairings.
// The Rust twin: `space::walk`.
#define_import_path curved_spaces::walk

#import curved_spaces::layout::{face_count, kappa, space}
#import curved_spaces::geometry::{project_point, unit_tangent}

// The exit of a step without crossing (STEP_CAP).
const NO_FACE: u32 = 0xfffffffeu;

fn partner(face: u32) -> u32 {
    return space.partners[face / 4u][face % 4u];
}


// A point of the model and a unit tangent there (Rust: `geometry::Ray`).
struct Ray {
    point: vec4<f32>,
    tangent: vec4<f32>,
}

// Where a ray leaves the cell: the face and the chart ratio T = num/den of the exit point
// (Rust: `space::walk::Exit`). face is 0xffffffff where no face is ahead.
struct Exit {
    face: u32,
    num: f32,
    den: f32,
}

// The faces a walk looks for its exit among, the first and one past the last: all of them,
// or in a space of several cells (CELLS) those of the cell it is in.
fn walk_faces(point: vec4<f32>, skip: u32) -> vec2<u32> {
#ifdef CELLS
    return walk_cell(point, skip);
#else
    return vec2<u32>(0u, face_count());
#endif
}

// The faces of face f's cell: every face in a space of one cell.
fn faces_of_cell(f: u32) -> vec2<u32> {
#ifdef CELLS
    return cell_faces(f);
#else
    return vec2<u32>(0u, face_count());
#endif
}

#ifdef CELLS
// The faces of face f's cell.
fn cell_faces(f: u32) -> vec2<u32> {
    let packed = space.cell_ranges[f / 4u][f % 4u];
    return vec2<u32>(packed & 0xffffu, packed >> 16u);
}

// The cell a walk is in: that of the face just entered (`skip`), else the first of those
// whose faces the point is least outside of (Rust: `CellWalker::cell_of`).
fn walk_cell(point: vec4<f32>, skip: u32) -> vec2<u32> {
    if skip < face_count() {
        return cell_faces(skip);
    }
    var best = cell_faces(0u);
    var least = 3.4e38;
    var first = 0u;
    loop {
        if first >= face_count() {
            break;
        }
        let range = cell_faces(first);
        var outside = -3.4e38;
        for (var f = range.x; f < range.y; f += 1u) {
            outside = max(outside, dot(space.covectors[f], point));
        }
        if outside < least {
            least = outside;
            best = range;
        }
        first = max(range.y, first + 1u);
    }
    return best;
}
#endif

// The exit face: the smallest T = −(N·p)/(N·v) among faces with N·v > 0, compared without
// dividing; the face just entered (`skip`) is passed over (Rust: `CellWalker::exit`).
fn exit_face(ray: Ray, skip: u32) -> Exit {
    var exit = Exit(0xffffffffu, 0.0, 1.0);
    let faces = walk_faces(ray.point, skip);
    for (var f = faces.x; f < faces.y; f += 1u) {
        let n = space.covectors[f];
        let dn = dot(n, ray.tangent);
        if f == skip || !(dn > 0.0) {
            continue;
        }
        let nm = max(-dot(n, ray.point), 0.0);
        if exit.face == 0xffffffffu || nm * exit.den < exit.num * dn {
            exit = Exit(f, nm, dn);
        }
    }
#ifdef STEP_CAP
    // No face within π/4: a step of π/4 without crossing (Rust: `CellWalker::step_cap`).
    if exit.face == 0xffffffffu || exit.num > exit.den {
        exit = Exit(NO_FACE, 1.0, 1.0);
    }
#endif
    return exit;
}

// s + e = a + b exactly (Knuth's two-sum: additions only). `one` is 1 at run time but not to
// the compiler: multiplying by it keeps an optimiser from rewriting (a + b) − a as b, which
// is true of real numbers and would make the error term zero.
fn two_sum(a: vec4<f32>, b: vec4<f32>, one: f32) -> array<vec4<f32>, 2> {
    let s = (a + b) * one;
    let bb = (s - a) * one;
    return array<vec4<f32>, 2>(s, (a - (s - bb)) + (b - bb));
}

// (hi + lo) x with the products and sums of hi x compensated (Ogita–Rump–Oishi Dot2, four
// rows at once): as accurate as twice the precision rounded once (Rust:
// `Vector4::transform_compensated`). A pairing's entries reach e^(2r) while the points it
// moves have size e^r, so the plain product cancels and loses a digit in H³. fma gives the
// products' rounding errors; where a driver does not fuse it, the error terms are zero and
// this is the plain product plus lo x, no worse than before.
fn transform_compensated(hi: mat4x4<f32>, lo: mat4x4<f32>, x: vec4<f32>) -> vec4<f32> {
    // Flat pairings have small entries: nothing cancels (Rust: `CellWalker::apply_pairing`).
    if kappa() == 0.0 {
        return hi * x;
    }
    let one = space.shading.exact.x;
    var p = hi[0] * x.x * one;
    var s = fma(hi[0], vec4<f32>(x.x), -p) + lo[0] * x.x;
    for (var j = 1; j < 4; j += 1) {
        let h = hi[j] * x[j] * one;
        let r = fma(hi[j], vec4<f32>(x[j]), -h);
        let sum = two_sum(p, h, one);
        p = sum[0];
        s += (sum[1] + r) + lo[j] * x[j];
    }
    return p + s;
}

// Through the exit face: exit point (N·v) p − (N·p) v, tangent κ (N·p) p + (N·v) v, then the
// face's pairing (compensated), both projected back onto the model (Rust: `CellWalker::cross`).
fn cross_face(ray: Ray, exit: Exit) -> Ray {
    let at_face = ray.point * exit.den + ray.tangent * exit.num;
    let along = ray.point * (-kappa() * exit.num) + ray.tangent * exit.den;
#ifdef STEP_CAP
    if exit.face == NO_FACE {
        let moved = onto_model(at_face);
        return Ray(moved, unit_tangent(moved, along));
    }
#endif
    let hi = space.pairings[exit.face];
    let lo = space.pairings_lo[exit.face];
    let point = onto_model(transform_compensated(hi, lo, at_face));
    return Ray(point, unit_tangent(point, transform_compensated(hi, lo, along)));
}

// A point put back onto the model (Rust: `CellWalker::onto_model`). A cell that reaches the
// equator (STEP_CAP, in S³) only scales it to unit length: turning it to its antipode in the
// hemisphere w >= 0 would move the 3-sphere's points, and in projective space turn the point
// without its tangent.
fn onto_model(p: vec4<f32>) -> vec4<f32> {
#ifdef STEP_CAP
    return p / length(p);
#else
    return project_point(p);
#endif
}
