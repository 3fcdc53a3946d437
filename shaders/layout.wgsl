// The uniform and the scene data buffer as the packer writes them, and the counts and
// curvature a variant is specialised on.
// The Rust twin: `plugin::render::layout`.
#define_import_path curved_spaces::layout

struct View {
    // The eyes' frames, left then right (both the head's in mono). Columns: right, up, back,
    // position (an isometry of the model).
    frames: array<mat4x4<f32>, 2>,
    // Frustum tangents left, right, bottom, top: image point (u, v) looks along
    // x·right + y·up − back with x = mix(left, right, u), y = mix(top, bottom, v).
    lens: vec4<f32>,
    // Viewport origin and size (pixels).
    viewport: vec4<f32>,
    // Where the second half of a split view starts (x, y in pixels; 0: no split), whether
    // the eyes are swapped (0 or 1), the scene's time in seconds (the globes' spin).
    split: vec4<f32>,
    // Anaglyph matrices (left, right; upper 3×3) acting on linear RGB.
    anaglyph: array<mat4x4<f32>, 2>,
    // The avatar's images: frame and inverse, one pair each.
    avatar: array<mat4x4<f32>, 16>,
    // Avatar images in use, the distance from the eye within which avatar hits are passed
    // through, the root node of its mesh, unused.
    avatar_info: vec4<f32>,
}

struct Shading {
    // Fog colour (rgb) and ambient fraction.
    fog: vec4<f32>,
    // Fog distance λ, cut-off distance λ ln(1/w), S(near_light), crossing budget.
    params: vec4<f32>,
    // (1, 0, 0, 0): a one the compiler cannot see through (transform_compensated).
    exact: vec4<f32>,
}

#ifdef LIGHTS
struct Light {
    // Colour × power (rgb), number of images in use.
    colour: vec4<f32>,
    // The reach within which images are summed, the tail's irradiance (¼ of its mean
    // fluence), S(the lamp's radius) for soft shadows (0: a point), unused.
    info: vec4<f32>,
    // LIGHT_IMAGES_SUM: the images in the cover, nearest the origin first; otherwise the
    // light and its images under the pairings (a point is lit by the nearest).
    images: array<vec4<f32>, #{LIGHT_IMAGES}>,
}
#endif

struct Ball {
    centre: vec4<f32>,
    // Albedo (rgb) and C(ρ) (the radius ρ itself in E³).
    colour: vec4<f32>,
    // Emission (rgb), reflectance.
    emission: vec4<f32>,
}

struct Globe {
    centre: vec4<f32>,
    // Albedo (rgb) and C(ρ) (ρ in E³).
    colour: vec4<f32>,
    // Emission (rgb), texture index.
    emission: vec4<f32>,
    // Spin in radians per second, reflectance, unused ×2.
    spin: vec4<f32>,
    // The inverse of the globe's orientation frame.
    inverse: mat4x4<f32>,
}

struct Disc {
    centre: vec4<f32>,
    // Unit tangent at the centre.
    normal: vec4<f32>,
    // The plane's covector (P·X = 0).
    covector: vec4<f32>,
    // Albedo (rgb), radius.
    colour: vec4<f32>,
    // Emission (rgb), reflectance.
    emission: vec4<f32>,
}

struct Instance {
    frame: mat4x4<f32>,
    inverse: mat4x4<f32>,
    // Root node, material override (or 0xffffffff), material base (added to the mesh's own), unused.
    info: vec4<u32>,
}

struct Tube {
    a: vec4<f32>,
    // Unit tangent at a towards b.
    towards_b: vec4<f32>,
    // Albedo (rgb) and C(ρ)² (ρ² in E³).
    colour: vec4<f32>,
    // C(L), S(L) of the segment length L, unused, unused.
    length: vec4<f32>,
    emission: vec4<f32>,
}

#ifdef PRODUCT
// An object of a product space (Rust: `trace::product::ProductObject`).
struct ProductObject {
    // A ball's or a fibre tube's point, or a slice tube's line covector.
    shape: vec4<f32>,
    // Kind (0 ball, 1 fibre tube, 2 slice tube, 3 horizontal disc, 4 horizontal triangle,
    // 5 vertical triangle), radius, the slice's height (a disc's and a horizontal
    // triangle's too; a disc's centre is `shape`), unused. A vertical triangle keeps the
    // second row of its barycentric map in z and w.
    info: vec4<f32>,
    // Albedo (rgb), unused.
    colour: vec4<f32>,
    // A triangle's further data (Rust: `ProductTriangle`): a horizontal one's first edge
    // covector is `shape`, its other two these; a vertical one's plane covector is `shape`,
    // then its origin, its direction along, and (s, z) of its first corner with the first
    // row of its barycentric map.
    more: array<vec4<f32>, 3>,
}
#endif

#ifdef NIL
// An object of a Nil scene (Rust: `trace::nil::NilObject`).
struct NilObject {
    // A ball's centre, a fibre tube's foot (xy), a swept disc's lattice image.
    shape: vec4<f32>,
    // Kind (0 ball, 1 fibre tube, 2 swept disc), radius, a disc's axis (0 x, 1 y), its other
    // horizontal coordinate.
    info: vec4<f32>,
    // Albedo (rgb), a disc's height.
    colour: vec4<f32>,
    // The chart box holding it: its lowest and highest corner.
    box_lo: vec4<f32>,
    box_hi: vec4<f32>,
}
#endif

struct SpaceUniform {
    view: View,
    shading: Shading,
    // Where the scene data buffer's parts start (in vec4): triangles, materials, texture
    // table, texels (the hierarchies' nodes start at 0).
    data: vec4<u32>,
#ifdef LIGHTS
    lights: array<Light, #{LIGHT_COUNT}>,
#endif
    // Face covectors N_f: the cell is N_f·X ≤ 0.
    covectors: array<vec4<f32>, #{FACE_SLOTS}>,
    // Face pairings g_f: a ray leaving through f comes back through partner(f).
    pairings: array<mat4x4<f32>, #{FACE_SLOTS}>,
    // What rounding g_f to f32 left out: the pairing is applied as hi + lo, compensated.
    pairings_lo: array<mat4x4<f32>, #{FACE_SLOTS}>,
    partners: array<vec4<u32>, #{PARTNER_VECS}>,
#ifdef CELLS
    // Per face (four to a vec4): the faces of its cell, the first | one past the last << 16.
    cell_ranges: array<vec4<u32>, #{PARTNER_VECS}>,
#endif
#ifdef PRODUCT
    // Half the circle's length, the number of objects, unused ×2 (the pairings above are the sides', then the
    // top's R⁻¹ and the bottom's R; the covectors of those two slots are unused).
    product: vec4<f32>,
    // The light's position.
    product_light: vec4<f32>,
    product_objects: array<ProductObject, #{PRODUCT_OBJECTS}>,
#ifdef PRODUCT_IMAGES
    // The images summed, the tail's share of light, the reach, the images shadowed (Rust:
    // `trace::product::lighting::product_gather`).
    product_lighting: vec4<f32>,
    // The lamp's images in the cover, nearest the cell's centre first.
    product_images: array<vec4<f32>, #{PRODUCT_IMAGES}>,
#endif
#endif
#ifdef NIL
    // Half the box's height, K, the number of objects, the lamp's power (Rust:
    // `trace::nil::NilScene`; the face arrays above are unused).
    nil_box: vec4<f32>,
    // The lamp's chart point, the falloff's floor (the lamp's size squared).
    nil_light: vec4<f32>,
    nil_objects: array<NilObject, #{NIL_OBJECTS}>,
#ifdef NIL_IMAGES
    // The images summed, the tail's light (¼ of its fluence; 0 without it), the reach, the
    // images shadowed (Rust: `trace::nil::light::gather`).
    nil_lighting: vec4<f32>,
    // The lamp's images in the cover, nearest the box's centre first.
    nil_images: array<vec4<f32>, #{NIL_IMAGES}>,
#endif
#endif
#ifdef SL2R
    // The number of tubes, of balls, unused ×2 (Rust: `trace::sl2r::Sl2rScene`; the face
    // arrays above are the polygon's sides: covectors, 3×3 pairings in a mat4, partners).
    sl2r: vec4<f32>,
    // Per tube: its base point q (xyz) and radius; its colour (rgb) and cosh(radius). Then
    // per ball: its centre's base point (xyz) and radius; its e (xyz) and cosh(radius); its
    // colour (rgb) and sinh(radius).
    sl2r_objects: array<vec4<f32>, #{SL2R_OBJECT_VECS}>,
    // The lamp's power, the falloff's floor (the lamp's size squared), the reach, the
    // images shadowed (Rust: `trace::sl2r::light::gather`).
    sl2r_light: vec4<f32>,
    // The images summed, the tail's light (¼ of its fluence; 0 without it), unused ×2.
    sl2r_lighting: vec4<f32>,
    // Per image of the lamp (nearest the cell's centre first; the lamp itself for the
    // nearest path): its f (xyz) and sheet; its base point q (xyz), unused.
    sl2r_images: array<vec4<f32>, #{SL2R_IMAGE_VECS}>,
#endif
#ifdef WALLS
    // Per face: the covector scaled to a unit normal (N̂·X̂ = S(signed distance)).
    wall_units: array<vec4<f32>, #{FACE_SLOTS}>,
    // Per face: the panel's colour (rgb) and S(w) of the margin round its window.
    wall_colours: array<vec4<f32>, #{FACE_SLOTS}>,
    // Per face: the panel's opacity, 1 for a mirror (else 0), unused ×2.
    wall_looks: array<vec4<f32>, #{FACE_SLOTS}>,
    // The share of light below which a ray stops, unused ×3.
    wall_style: vec4<f32>,
#endif
#ifdef BALLS
    balls: array<Ball, #{BALL_COUNT}>,
#endif
#ifdef TUBES
    tubes: array<Tube, #{TUBE_COUNT}>,
#endif
#ifdef GLOBES
    globes: array<Globe, #{GLOBE_COUNT}>,
#endif
#ifdef DISCS
    discs: array<Disc, #{DISC_COUNT}>,
#endif
#ifdef INSTANCES
    instances: array<Instance, #{INSTANCE_COUNT}>,
#endif
#ifdef CULLING
    // Per face (four to a vec4): the bound on −N·X of the points of the model within the
    // culling distance of its plane.
    near: array<vec4<f32>, #{PARTNER_VECS}>,
    // Per ball, then per tube (four to a vec4): the faces (bits of faces 0–31) a segment
    // must come near to meet it.
    masks: array<vec4<u32>, #{MASK_VECS}>,
    // The object lists (u32, four to a vec4): for the balls, then the tubes, where each of
    // the CULL_BUCKETS buckets starts and where the last ends; then the object indices. An
    // object whose mask names two faces or more is in the bucket of one pair f < g of them
    // (g(g−1)/2 + f), the rest in the last bucket.
    lists: array<vec4<u32>, #{LIST_VECS}>,
#endif
#ifdef GENERAL
    // κ, face count, ball count, tube count.
    general: vec4<f32>,
#endif
}

@group(0) @binding(0) var<uniform> space: SpaceUniform;

#ifdef SCENE_DATA
// Hierarchy nodes (2 vec4 each), triangles (8), materials (2), the texture table (1 each)
// and texels (4 per vec4, RGBA8 sRGB), as written by src/render/gpu.rs.
@group(0) @binding(1) var<storage, read> scene_data: array<vec4<u32>>;
#endif

#ifdef TEXTURES
// The scene's first eight textures, RGBA8 unorm holding sRGB values, read texel by texel
// (texture.wgsl filters them as the CPU does); further ones are in scene_data. Unused
// slots hold a 1×1 texture.
@group(0) @binding(2) var texture_slot_0: texture_2d<f32>;
@group(0) @binding(3) var texture_slot_1: texture_2d<f32>;
@group(0) @binding(4) var texture_slot_2: texture_2d<f32>;
@group(0) @binding(5) var texture_slot_3: texture_2d<f32>;
@group(0) @binding(6) var texture_slot_4: texture_2d<f32>;
@group(0) @binding(7) var texture_slot_5: texture_2d<f32>;
@group(0) @binding(8) var texture_slot_6: texture_2d<f32>;
@group(0) @binding(9) var texture_slot_7: texture_2d<f32>;
#endif

const F32_EPSILON: f32 = 1.1920929e-7;

#ifdef GENERAL
// The unspecialised variant (benchmark only): every geometry's formulas are compiled and the
// geometry and counts are read from the uniform at run time, over full-size arrays.
fn kappa() -> f32 { return space.general.x; }
fn face_count() -> u32 { return u32(space.general.y); }
fn ball_count() -> u32 { return u32(space.general.z); }
fn tube_count() -> u32 { return u32(space.general.w); }
#else
#ifdef SPHERICAL
const KAPPA: f32 = 1.0;
#endif
#ifdef EUCLIDEAN
const KAPPA: f32 = 0.0;
#endif
#ifdef HYPERBOLIC
const KAPPA: f32 = -1.0;
#endif
// Constants of the specialised shader (the branches on them fold away when compiled).
fn kappa() -> f32 { return KAPPA; }
fn face_count() -> u32 { return #{FACE_COUNT}u; }
#ifdef BALLS
fn ball_count() -> u32 { return #{BALL_COUNT}u; }
#endif
#ifdef TUBES
fn tube_count() -> u32 { return #{TUBE_COUNT}u; }
#endif
#endif

#ifdef SCENE_DATA
fn fdata(i: u32) -> vec4<f32> {
    return bitcast<vec4<f32>>(scene_data[i]);
}
#endif
