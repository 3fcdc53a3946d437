// Textures (GPU textures, and the scene data buffer's texels), and the globe's coordinates.
// The Rust twin: `scene::texture`.
#define_import_path curved_spaces::texture

#import curved_spaces::layout::{Globe, scene_data, space}
#ifdef TEXTURES
#import curved_spaces::layout::{texture_slot_0, texture_slot_1, texture_slot_2, texture_slot_3, texture_slot_4, texture_slot_5, texture_slot_6, texture_slot_7}
#endif

#ifdef TEXTURES
fn srgb_channel_to_linear(c: vec3<f32>) -> vec3<f32> {
    let low = c / 12.92;
    let high = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, c <= vec3<f32>(0.04045));
}

// Texel p of the texture in slot `slot`, its channels in [0, 1] (sRGB-encoded).
fn slot_texel(slot: u32, p: vec2<i32>) -> vec3<f32> {
    var c = vec4<f32>(0.0);
    switch slot {
        case 0u: { c = textureLoad(texture_slot_0, p, 0); }
        case 1u: { c = textureLoad(texture_slot_1, p, 0); }
        case 2u: { c = textureLoad(texture_slot_2, p, 0); }
        case 3u: { c = textureLoad(texture_slot_3, p, 0); }
        case 4u: { c = textureLoad(texture_slot_4, p, 0); }
        case 5u: { c = textureLoad(texture_slot_5, p, 0); }
        case 6u: { c = textureLoad(texture_slot_6, p, 0); }
        default: { c = textureLoad(texture_slot_7, p, 0); }
    }
    return c.rgb;
}

// The linear colour of texel (x, y) of texture `tex` (Texture::texel): from its GPU
// texture (the table's last word is its slot), or from the scene data's texels.
fn texel(tex: u32, x: u32, y: u32) -> vec3<f32> {
    let info = scene_data[space.data.z + tex];
    if info.w != 0xffffffffu {
        return srgb_channel_to_linear(slot_texel(info.w, vec2<i32>(i32(x), i32(y))));
    }
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
