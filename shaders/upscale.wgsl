// Scales the tracer's reduced-resolution picture up to the view (the panel's resolution
// scale): one triangle covering the viewport, bilinear sampling.
//
// Shader defs: SPLIT_X | SPLIT_Y   the picture holds two eyes side by side (top and bottom):
//                                  samples stay in the half of the output pixel's eye.

@group(0) @binding(0) var traced: texture_2d<f32>;
@group(0) @binding(1) var traced_sampler: sampler;

struct VertexOutput {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn vertex(@builtin(vertex_index) index: u32) -> VertexOutput {
    let uv = vec2<f32>(f32(index >> 1u), f32(index & 1u)) * 2.0;
    let clip = vec4<f32>(uv * vec2<f32>(2.0, -2.0) + vec2<f32>(-1.0, 1.0), 0.0, 1.0);
    return VertexOutput(clip, uv);
}

// A texture coordinate kept within the half of `n` texels it lies in, so that bilinear
// sampling never mixes the two eyes. The second eye starts at texel floor(n/2) (its centre
// at floor(n/2) + 0.5 is where ViewLayout::eye_at switches eyes).
fn keep_in_half(u: f32, n: u32) -> f32 {
    let m = f32(n / 2u);
    let size = f32(n);
    if u < 0.5 {
        return min(u, (m - 0.5) / size);
    }
    return max(u, (m + 0.5) / size);
}

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {
    var uv = in.uv;
#ifdef SPLIT_X
    uv.x = keep_in_half(uv.x, textureDimensions(traced).x);
#endif
#ifdef SPLIT_Y
    uv.y = keep_in_half(uv.y, textureDimensions(traced).y);
#endif
    return textureSample(traced, traced_sampler, uv);
}
