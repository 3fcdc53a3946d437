// The benchmark's baseline: the cheapest fullscreen material (one uniform read and a colour
// from the pixel position), drawn like the tracer (one triangle over the viewport) so that
// the tracer's frame time can be reported as a ratio to it.

@group(0) @binding(0) var<uniform> tint: vec4<f32>;

struct VertexOutput {
    @builtin(position) position: vec4<f32>,
}

@vertex
fn vertex(@builtin(vertex_index) index: u32) -> VertexOutput {
    let uv = vec2<f32>(f32(index >> 1u), f32(index & 1u)) * 2.0;
    return VertexOutput(vec4<f32>(uv * vec2<f32>(2.0, -2.0) + vec2<f32>(-1.0, 1.0), 0.0, 1.0));
}

@fragment
fn fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(fract(position.xy / 256.0), tint.z, 1.0);
}
