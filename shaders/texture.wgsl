// Textures in the scene data buffer, and the globe's coordinates.
// The Rust twin: `scene::texture`.
#define_import_path curved_spaces::texture

#import curved_spaces::layout::{Globe, scene_data, space}

#ifdef TEXTURES
fn srgb_channel_to_linear(c: vec3<f32>) -> vec3<f32> {
    let low = c / 12.92;
    let high = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, c <= vec3<f32>(0.04045));
}

// The linear colour of texel (x, y) of texture `tex` (Texture::texel).
fn texel(tex: u32, x: u32, y: u32) -> vec3<f32> {
    let info = scene_data[space.data.z + tex];
    let i = info.x + y * info.y + x;
    let word = scene_data[space.data.w + i / 4u][i % 4u];
    let c = vec3<f32>(f32(word & 255u), f32((word >> 8u) & 255u), f32((word >> 16u) & 255u));
    return srgb_channel_to_linear(c / 255.0);
}

// Bilinear between texel centres, u wrapping, v clamped (Texture::sample).
fn sample_texture(tex: u32, uv: vec2<f32>) -> vec3<f32> {
    let info = scene_data[space.data.z + tex];
    let w = f32(info.y);
    let h = f32(info.z);
    let x = (uv.x - floor(uv.x)) * w - 0.5;
    let y = clamp(clamp(uv.y, 0.0, 1.0) * h - 0.5, 0.0, h - 1.0);
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let xa = u32(x0 - w * floor(x0 / w));
    let xb = u32((x0 + 1.0) - w * floor((x0 + 1.0) / w));
    let ya = u32(y0);
    let yb = u32(min(y0 + 1.0, h - 1.0));
    let top = mix(texel(tex, xa, ya), texel(tex, xb, ya), fx);
    let bottom = mix(texel(tex, xa, yb), texel(tex, xb, yb), fx);
    return mix(top, bottom, fy);
}
#endif

#ifdef GLOBES
// Texture coordinates of a globe's point x (BallTexture::uv).
fn globe_uv(globe: Globe, x: vec4<f32>) -> vec2<f32> {
    let local = globe.inverse * x;
    let d = normalize(local.xyz);
    let turn = 6.283185307179586;
    let longitude = atan2(d.x, d.z) - globe.spin.x * space.view.split.w;
    let u = longitude / turn + 0.5;
    return vec2<f32>(u - floor(u), acos(clamp(d.y, -1.0, 1.0)) / 3.141592653589793);
}
#endif
