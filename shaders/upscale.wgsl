// Scales the tracer's reduced-resolution picture up to the view (the panel's resolution
// scale): one triangle covering the viewport, bilinear sampling.

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

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {
    return textureSample(traced, traced_sampler, in.uv);
}
