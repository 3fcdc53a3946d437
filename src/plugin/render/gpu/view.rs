//! The per-view words of the uniform (the eyes' frames, the lens, the viewport, stereo and
//! the avatar) and the view's shader defs.

use super::*;

/// What a view's uniform holds besides the eyes: the scene's time (the globes' spin) and
/// the avatar's images at the player's frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ViewExtras {
    /// The scene's clock in seconds.
    pub time: f64,
    /// At most [`crate::scene::MAX_AVATAR_IMAGES`] are drawn.
    pub avatar: Vec<crate::scene::MeshInstance>,
    /// Avatar hits nearer than this to the eye are passed through.
    pub avatar_skip: f64,
    /// The root node of the avatar's mesh.
    pub avatar_root: u32,
}

impl ViewExtras {
    /// The extras of a scene's view at `time` with the avatar (if the scene has one) at the
    /// player's `frame`.
    #[must_use]
    pub fn new(space: &Space, gpu: &GpuScene, frame: DMat4, time: f64) -> Self {
        let Some(a) = gpu.avatar else {
            return Self {
                time,
                ..Self::default()
            };
        };
        Self {
            time,
            avatar: crate::scene::avatar_instances(space, a.mesh, a.radius, frame),
            avatar_skip: a.skip,
            avatar_root: a.root,
        }
    }
}

/// The per-view part of the uniform (`View` in the shader): the eyes' frames (columns
/// right, up, back, position), the frustum tangents, the viewport (origin and size in
/// pixels), the stereo split, eye swap and time, the anaglyph matrices and the avatar.
#[must_use]
pub fn view_words(layout: &ViewLayout, origin: [u32; 2], extras: &ViewExtras) -> [u32; VIEW_WORDS] {
    let lens = layout.lens;
    let images = extras.avatar.len().min(crate::scene::MAX_AVATAR_IMAGES);
    let mut avatar = [mat4(DMat4::IDENTITY); 2 * AVATAR_SLOTS];
    for (k, m) in extras.avatar.iter().take(images).enumerate() {
        avatar[2 * k] = mat4(m.frame);
        avatar[2 * k + 1] = mat4(m.inverse);
    }
    let view = GpuView {
        frames: layout.frames.map(mat4),
        lens: vec4(DVec4::new(lens.left, lens.right, lens.bottom, lens.top)),
        viewport: vec4(DVec4::new(
            f64::from(origin[0]),
            f64::from(origin[1]),
            layout.size[0],
            layout.size[1],
        )),
        split: vec4(DVec4::new(
            layout.split[0],
            layout.split[1],
            f64::from(u8::from(layout.swap_eyes)),
            extras.time,
        )),
        anaglyph: [layout.anaglyph.0, layout.anaglyph.1].map(|m| mat4(DMat4::from_mat3(m))),
        avatar,
        avatar_info: vec4(DVec4::new(
            images as f64,
            extras.avatar_skip,
            f64::from(extras.avatar_root),
            0.0,
        )),
    };
    bytemuck::cast(view)
}

/// The shader defs of a view kind (added to the scene's, [`ShaderKey::shader_defs`]).
#[must_use]
pub fn view_shader_defs(kind: ViewKind) -> Vec<ShaderDefVal> {
    match kind {
        ViewKind::Mono => vec![],
        ViewKind::Split => vec!["STEREO_SPLIT".into()],
        ViewKind::Anaglyph => vec!["ANAGLYPH".into()],
    }
}
