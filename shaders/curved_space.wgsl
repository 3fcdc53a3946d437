// Ray tracing inside a closed 3-manifold: the GPU twin of the f64 reference in src/trace
// (same algorithm, same shading, in f32). See docs/design.md §3 and §5.
//
// Shader defs (set by src/render/gpu.rs, one pipeline per combination):
//   SPHERICAL | EUCLIDEAN | HYPERBOLIC   the geometry: only its formulas are compiled
//   CURVED                               set with SPHERICAL or HYPERBOLIC
//   GENERAL                              (benchmark) all three geometries and CURVED are set,
//                                        the geometry and counts are read at run time
//   FACE_COUNT, PARTNER_VECS             faces of the cell (partners packed 4 to a vec4<u32>)
//   FACE_SLOTS                           face array length: FACE_COUNT, at least 1 (the
//                                        3-sphere has no face; its slot is never read)
//   STEP_CAP                             a cell reaching π/2 in S³: rays step at most π/4
//                                        (chart ratio 1) without crossing (NO_FACE)
//   BALLS + BALL_COUNT, TUBES + TUBE_COUNT   the object kinds present and their numbers
//   GLOBES + GLOBE_COUNT                 textured balls (equirectangular, spinning)
//   DISCS + DISC_COUNT                   flat discs
//   INSTANCES + INSTANCE_COUNT           placed meshes (src/scene/mesh.rs)
//   COLOUR_BY (1 crossings, 2 face, 3 holonomy + COLOUR_HOLONOMY)   a teaching view's tint
//   AVATAR                               the player's avatar mesh (frames in the view)
//   MESHES                               any mesh: the scene data buffer with the
//                                        hierarchies, triangles and materials
//   TEXTURES                             textures in the scene data buffer
//   SCENE_DATA                           set with MESHES or TEXTURES: the buffer is bound
//   LIGHTS + LIGHT_COUNT, LIGHT_IMAGES   point lights, each with up to LIGHT_IMAGES copies
//   HIT_ID                               (benchmark) output what each ray met instead of a
//                                        colour: object, crossings, face path, how it ended
//   CULLING + MASK_VECS                  balls and tubes carry face masks: a segment tests
//                                        only those whose faces it comes near
//                                        (src/scene/culling.rs)
//   WALLS                                the cell's walls with windows (src/scene/walls.rs)
//   STRAIGHTFORWARD                      (benchmark) a straightforward tracer of the same
//                                        walk instead, the benchmark's comparison: balls
//                                        only, arc length and trigonometry, plain pairings
//   STEREO_SPLIT                         two eyes in two halves of the view (src/stereo.rs)
//   ANAGLYPH                             two eyes traced per pixel and mixed by two matrices
//   PRODUCT + PRODUCT_OBJECTS            a product space H²×R (with HYPERBOLIC) or S²×R (with
//                                        SPHERICAL): FACE_COUNT sides, FACE_SLOTS = sides + 2
//                                        pairings (the top's, the bottom's), the product
//                                        walk and objects (shaders/product.wgsl)
//   NIL + NIL_OBJECTS, NIL_IMAGES,       a Nil space (with EUCLIDEAN, no faces packed): the
//   NIL_SHADOWS                          box's walk, its objects, the lamp's images and
//                                        shadows (shaders/nil.wgsl)
//   SL2R + SL2R_OBJECT_VECS              an SL̃(2,R) space (with HYPERBOLIC): FACE_COUNT
//                                        sides, the walk of UT H², its fibre tubes and
//                                        (SL2R_BALLS) metric balls (shaders/sl2r.wgsl)
//
// Points and tangents are 4-vectors with ⟨u,v⟩ = u.xyz·v.xyz + κ u.w v.w; a ray segment in
// the cell is X(s) ∝ p + s v, a straight line of the chart, so faces are planes (N·X = 0)
// and balls and tubes are quadrics in s.

#import curved_spaces::layout::{space}
#import curved_spaces::hit_id::{hit_id}
// The one place a family is chosen: each family's tracer module has the camera ray's
// colour under the same name, `ray_colour`.
#ifdef SL2R
#import curved_spaces::sl2r::{sl2r_eye_colour}
#else
#ifdef NIL
#import curved_spaces::nil::{ray_colour}
#else
#ifdef PRODUCT
#import curved_spaces::product::{ray_colour}
#else
#import curved_spaces::trace::{ray_colour}
#endif
#endif
#endif

// ---------------------------------------------------------------------------------------
// Entry points: one triangle covering the viewport.

struct VertexOutput {
    @builtin(position) position: vec4<f32>,
}

@vertex
fn vertex(@builtin(vertex_index) index: u32) -> VertexOutput {
    let uv = vec2<f32>(f32(index >> 1u), f32(index & 1u)) * 2.0;
    return VertexOutput(vec4<f32>(uv * vec2<f32>(2.0, -2.0) + vec2<f32>(-1.0, 1.0), 0.0, 1.0));
}

// The stored value is the sRGB encoding of what the fragment returns: return the decoded
// colour so that the 8-bit image holds the same values as the CPU reference's PNG.
fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    let low = c / 12.92;
    let high = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, c <= vec3<f32>(0.04045));
}

// The colour seen by eye `eye` through image point `uv` of its picture (ViewLayout::ray).
fn eye_colour(eye: u32, uv: vec2<f32>) -> vec3<f32> {
    let lens = space.view.lens;
    let px = mix(lens.x, lens.y, uv.x);
    let py = mix(lens.w, lens.z, uv.y);
    let f = space.view.frames[eye];
#ifdef SL2R
    // The frame holds e beside the viewer's axes: the family reads the whole of it.
    return clamp(sl2r_eye_colour(f, px, py), vec3<f32>(0.0), vec3<f32>(1.0));
#else
    return clamp(ray_colour(f[3], px * f[0] + py * f[1] - f[2]), vec3<f32>(0.0), vec3<f32>(1.0));
#endif
}

// The linear colour seen through a fragment of the viewport (ViewLayout::eye_at and
// rays_at); the target stores its sRGB encoding, the value the CPU reference writes.
fn pixel_colour(position: vec4<f32>) -> vec3<f32> {
    let view = space.view;
    let pixel = position.xy - view.viewport.xy;
    var size = view.viewport.zw;
#ifdef STEREO_SPLIT
    let split = view.split.xy;
    let second = (split.x > 0.0 && pixel.x >= split.x) || (split.y > 0.0 && pixel.y >= split.y);
    let half = select(0u, 1u, second);
    let local = pixel - f32(half) * split;
    size = select(size, split, split > vec2<f32>(0.0));
    return srgb_to_linear(eye_colour(half ^ u32(view.split.z), local / size));
#else
#ifdef ANAGLYPH
    let uv = pixel / size;
    let left = srgb_to_linear(eye_colour(0u, uv));
    let right = srgb_to_linear(eye_colour(1u, uv));
    let mixed = (view.anaglyph[0] * vec4<f32>(left, 0.0)).rgb
        + (view.anaglyph[1] * vec4<f32>(right, 0.0)).rgb;
    return clamp(mixed, vec3<f32>(0.0), vec3<f32>(1.0));
#else
    return srgb_to_linear(eye_colour(0u, pixel / size));
#endif
#endif
}

#ifdef HIT_ID
@fragment
fn fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<u32> {
    _ = pixel_colour(position);
    return hit_id;
}
#else
@fragment
fn fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(pixel_colour(position), 1.0);
}
#endif
