//! What the shader is specialised on ([`ShaderKey`]): its shader defs and the uniform's size,
//! and composing the WGSL with them (for the tests and the benchmark).

use crate::geometry::Geometry;
use crate::plugin::render::layout::{
    FACE_BYTES, GpuBall, GpuDisc, GpuGlobe, GpuInstance, GpuShading, GpuTube, GpuView, Vec4F,
};
use bevy::shader::ShaderDefVal;

/// What the shader is specialised on: one compiled pipeline per key.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ShaderKey {
    /// The geometry (only its formulas are compiled).
    pub geometry: Geometry,
    /// Faces of the cell.
    pub faces: u32,
    /// Plain balls.
    pub balls: u32,
    /// Geodesic tubes.
    pub tubes: u32,
    /// Textured balls.
    pub globes: u32,
    /// Discs.
    pub discs: u32,
    /// Placed meshes.
    pub instances: u32,
    /// Point lights.
    pub lights: u32,
    /// Images per light (the light and its copies through the faces, or with `light_sum` its
    /// images in the cover).
    pub light_images: u32,
    /// Whether every image within the reach is summed ([`crate::scene::LightPaths::Images`];
    /// shader def `LIGHT_IMAGES_SUM`) rather than the nearest taken.
    pub light_sum: bool,
    /// Images per light walked for shadows (shader def `SHADOWS`, where above 0).
    pub shadows: u32,
    /// Shadow rays per shadowed image of a lamp with a radius (shader def `SOFT_SHADOWS`,
    /// where above 1 and shadows are walked; [`crate::scene::Lighting::soft_samples`]).
    pub soft_samples: u32,
    /// Whether the player's avatar is drawn.
    pub avatar: bool,
    /// Whether any texture is used.
    pub textures: bool,
    /// Whether balls and tubes carry face masks ([`crate::scene::FaceCulling`]): a segment
    /// tests only those whose faces it comes near.
    pub culling: bool,
    /// A spherical cell whose chords can pass π/2 ([`crate::space::Space::walks_in_steps`]):
    /// rays step at most π/4 without crossing (shader def `STEP_CAP`).
    pub step_cap: bool,
    /// A space of several cells ([`crate::space::Space::cells`]; shader def `CELLS`): each
    /// face's cell is packed beside its partner, and a walk looks for its exit among the
    /// faces of the cell it is in.
    pub cells: bool,
    /// What surfaces are coloured by over their shading ([`crate::scene::ColourBy::index`]; 0
    /// for the plain picture): shader def `COLOUR_BY`, and `COLOUR_HOLONOMY` for 3.
    pub colour_by: u32,
    /// Whether the cell's walls with windows are drawn ([`crate::scene::walls`]; shader def
    /// `WALLS`).
    pub walls: bool,
    /// Whether any surface reflects as a mirror (shader def `MIRRORS`): the walk goes on
    /// from such a hit with the reflected tangent ([`crate::trace::colour_along`]).
    pub mirrors: bool,
    /// The unspecialised variant (the benchmark's comparison): all geometries' formulas,
    /// arrays of [`GENERAL_CAPACITY`], geometry and counts read from the uniform.
    pub general: bool,
    /// The benchmark's comparison: a straightforward tracer of the same walk instead (shader
    /// def `STRAIGHTFORWARD`; balls only). See [`super::GpuScene::straightforward`].
    pub straightforward: bool,
    /// A product space (H²×R or S²×R, the surface's geometry in `geometry`; shader def
    /// `PRODUCT`): `faces` counts the polygon's sides, and the top's and bottom's pairings
    /// follow theirs.
    pub product: bool,
    /// The objects of a product scene (shader def `PRODUCT_OBJECTS`).
    pub product_objects: u32,
    /// The lamp's images a product scene sums (shader def `PRODUCT_IMAGES`; 0: the older
    /// model, the lamp in the cell only).
    pub product_images: u32,
    /// Whether a product scene walks shadow rays (shader def `PRODUCT_SHADOWS`).
    pub product_shadows: bool,
    /// A Nil space (shader def `NIL`; `faces` 0, the geometry's formulas unused).
    pub nil: bool,
    /// The objects of a Nil scene (shader def `NIL_OBJECTS`).
    pub nil_objects: u32,
    /// The lamp's images a Nil scene sums (shader def `NIL_IMAGES`; 0: the nearest copy).
    pub nil_images: u32,
    /// Whether a Nil scene walks shadow rays (shader def `NIL_SHADOWS`).
    pub nil_shadows: bool,
    /// An SL̃(2,R) space (shader def `SL2R`; `faces` counts the polygon's sides, the
    /// geometry's formulas unused).
    pub sl2r: bool,
    /// The fibre tubes of an SL̃(2,R) scene (two vec4 each in `SL2R_OBJECT_VECS`).
    pub sl2r_tubes: u32,
    /// The metric balls of an SL̃(2,R) scene (three vec4 each in `SL2R_OBJECT_VECS`, after
    /// the tubes; shader def `SL2R_BALLS` where there are any, so that a scene without them
    /// compiles no ball search).
    pub sl2r_balls: u32,
    /// A fibre cover of a unit tangent bundle (shader def `SL2R_COVER`): the walk counts
    /// sheets, and each ball has a fourth vec4 (its sheet and fibre angle).
    pub sl2r_cover: bool,
    /// The lamp's images an SL̃(2,R) scene sums, two vec4 each (shader def
    /// `SL2R_IMAGE_VECS`; for the nearest path the lamp itself, one).
    pub sl2r_images: u32,
    /// Whether an SL̃(2,R) scene walks shadow rays (shader def `SL2R_SHADOWS`).
    pub sl2r_shadows: bool,
}

/// The vec4s of one Nil object in the uniform (shape, info, colour, its chart box).
pub const NIL_OBJECT_VEC4S: usize = 5;

/// The vec4s of one product object in the uniform (shape, info, colour and three more).
pub const PRODUCT_OBJECT_VEC4S: usize = 6;

/// Array sizes of the unspecialised variant: faces, balls, tubes.
pub const GENERAL_CAPACITY: (u32, u32, u32) = (crate::space::MAX_FACES as u32, 256, 256);

impl ShaderKey {
    /// The vec4s of an SL̃(2,R) scene's objects: two a tube, three a ball (four in a fibre
    /// cover), at least two.
    #[must_use]
    pub fn sl2r_object_vecs(&self) -> u32 {
        (2 * self.sl2r_tubes + self.sl2r_ball_vecs() * self.sl2r_balls).max(2)
    }

    /// The vec4s of one SL̃(2,R) ball: three, and a fourth in a fibre cover.
    #[must_use]
    pub fn sl2r_ball_vecs(&self) -> u32 {
        if self.sl2r_cover { 4 } else { 3 }
    }

    /// The key of an empty scene in `geometry` (no faces, objects or lights): a start for
    /// struct-update syntax.
    #[must_use]
    pub fn empty(geometry: Geometry) -> Self {
        Self {
            geometry,
            faces: 0,
            balls: 0,
            tubes: 0,
            globes: 0,
            discs: 0,
            instances: 0,
            lights: 0,
            light_images: 0,
            light_sum: false,
            shadows: 0,
            soft_samples: 0,
            avatar: false,
            textures: false,
            culling: false,
            step_cap: false,
            cells: false,
            colour_by: 0,
            walls: false,
            mirrors: false,
            general: false,
            straightforward: false,
            product: false,
            product_objects: 0,
            product_images: 0,
            product_shadows: false,
            nil: false,
            nil_objects: 0,
            nil_images: 0,
            nil_shadows: false,
            sl2r: false,
            sl2r_tubes: 0,
            sl2r_balls: 0,
            sl2r_cover: false,
            sl2r_images: 0,
            sl2r_shadows: false,
        }
    }

    /// The shader defs of this key (see the header of `shaders/curved_space.wgsl`).
    #[must_use]
    pub fn shader_defs(&self) -> Vec<ShaderDefVal> {
        let (faces, balls, tubes) = self.array_sizes();
        let mut defs: Vec<ShaderDefVal> = if self.general {
            ["SPHERICAL", "EUCLIDEAN", "HYPERBOLIC", "CURVED", "GENERAL"]
                .map(ShaderDefVal::from)
                .into()
        } else {
            match self.geometry {
                Geometry::Spherical => vec!["SPHERICAL".into(), "CURVED".into()],
                Geometry::Euclidean => vec!["EUCLIDEAN".into()],
                Geometry::Hyperbolic => vec!["HYPERBOLIC".into(), "CURVED".into()],
            }
        };
        defs.push(ShaderDefVal::UInt("FACE_COUNT".into(), self.faces));
        defs.push(ShaderDefVal::UInt("FACE_SLOTS".into(), faces));
        defs.push(ShaderDefVal::UInt("PARTNER_VECS".into(), faces.div_ceil(4)));
        if self.step_cap {
            defs.push("STEP_CAP".into());
        }
        if self.cells {
            defs.push("CELLS".into());
        }
        if self.product {
            defs.push("PRODUCT".into());
            defs.push(ShaderDefVal::UInt(
                "PRODUCT_OBJECTS".into(),
                self.product_objects.max(1),
            ));
            if self.product_images > 0 {
                defs.push(ShaderDefVal::UInt(
                    "PRODUCT_IMAGES".into(),
                    self.product_images,
                ));
                if self.product_shadows {
                    defs.push("PRODUCT_SHADOWS".into());
                }
            }
        }
        if self.nil {
            defs.push("NIL".into());
            defs.push(ShaderDefVal::UInt(
                "NIL_OBJECTS".into(),
                self.nil_objects.max(1),
            ));
            if self.nil_images > 0 {
                defs.push(ShaderDefVal::UInt("NIL_IMAGES".into(), self.nil_images));
                if self.nil_shadows {
                    defs.push("NIL_SHADOWS".into());
                }
            }
        }
        if self.sl2r {
            defs.push("SL2R".into());
            defs.push(ShaderDefVal::UInt(
                "SL2R_OBJECT_VECS".into(),
                self.sl2r_object_vecs(),
            ));
            if self.sl2r_balls > 0 {
                defs.push("SL2R_BALLS".into());
            }
            if self.sl2r_cover {
                defs.push("SL2R_COVER".into());
            }
            defs.push(ShaderDefVal::UInt(
                "SL2R_IMAGE_VECS".into(),
                2 * self.sl2r_images.max(1),
            ));
            if self.sl2r_shadows {
                defs.push("SL2R_SHADOWS".into());
            }
        }
        if self.straightforward {
            defs.push("STRAIGHTFORWARD".into());
        }
        if self.colour_by > 0 {
            defs.push(ShaderDefVal::UInt("COLOUR_BY".into(), self.colour_by));
            if self.colour_by == crate::scene::ColourBy::Holonomy.index() {
                defs.push("COLOUR_HOLONOMY".into());
            }
        }
        if self.walls {
            defs.push("WALLS".into());
        }
        let mut counted = |flag: &str, count_def: &str, n: u32| {
            if n > 0 {
                defs.push(flag.into());
                defs.push(ShaderDefVal::UInt(count_def.into(), n));
            }
        };
        counted("BALLS", "BALL_COUNT", balls);
        counted("TUBES", "TUBE_COUNT", tubes);
        counted("GLOBES", "GLOBE_COUNT", self.globes);
        counted("DISCS", "DISC_COUNT", self.discs);
        counted("INSTANCES", "INSTANCE_COUNT", self.instances);
        counted("LIGHTS", "LIGHT_COUNT", self.lights);
        if self.lights > 0 {
            defs.push(ShaderDefVal::UInt(
                "LIGHT_IMAGES".into(),
                self.light_images.max(1),
            ));
            if self.light_sum {
                defs.push("LIGHT_IMAGES_SUM".into());
            }
            if self.shadows > 0 {
                defs.push(ShaderDefVal::UInt("SHADOWS".into(), self.shadows));
                if self.soft_samples > 1 {
                    defs.push(ShaderDefVal::UInt("SOFT_SHADOWS".into(), self.soft_samples));
                }
            }
        }
        if self.avatar {
            defs.push("AVATAR".into());
        }
        if self.mirrors {
            defs.push("MIRRORS".into());
        }
        if self.avatar || self.instances > 0 {
            defs.push("MESHES".into());
        }
        if self.textures {
            defs.push("TEXTURES".into());
        }
        if self.avatar || self.instances > 0 || self.textures {
            defs.push("SCENE_DATA".into());
        }
        if self.culling {
            defs.push("CULLING".into());
            defs.push(ShaderDefVal::UInt("MASK_VECS".into(), self.mask_vecs()));
            defs.push(ShaderDefVal::UInt("LIST_VECS".into(), self.list_vecs()));
            defs.push(ShaderDefVal::UInt(
                "CULL_BUCKETS".into(),
                super::cull_buckets(self.faces as usize) as u32,
            ));
        }
        defs
    }

    /// The sizes of the uniform's face, ball and tube arrays.
    #[must_use]
    pub fn array_sizes(&self) -> (u32, u32, u32) {
        if self.general {
            GENERAL_CAPACITY
        } else if self.product {
            // The sides, then the top's and the bottom's pairings.
            (self.faces + 2, 0, 0)
        } else {
            // WGSL has no empty arrays: the 3-sphere's face slot is unused.
            (self.faces.max(1), self.balls, self.tubes)
        }
    }

    /// `vec4`s of the face masks (a `u32` per ball and tube, four to a `vec4`); 0 without
    /// culling.
    #[must_use]
    pub fn mask_vecs(&self) -> u32 {
        if self.culling {
            (self.balls + self.tubes).div_ceil(4)
        } else {
            0
        }
    }

    /// `vec4`s of the culling's object lists (`u32`s four to a `vec4`): for the balls, then
    /// the tubes, where each of [`super::cull_buckets`] buckets starts (and the end), then
    /// the object indices.
    #[must_use]
    pub fn list_vecs(&self) -> u32 {
        if self.culling {
            let buckets = super::cull_buckets(self.faces as usize) as u32;
            (2 * (buckets + 1) + self.balls + self.tubes).div_ceil(4)
        } else {
            0
        }
    }

    /// `vec4`s at the end of the uniform that only culling uses: the per-face thresholds
    /// (four to a `vec4`), the masks and the object lists.
    #[must_use]
    pub fn culling_vecs(&self) -> usize {
        if self.culling {
            self.faces.div_ceil(4) as usize + self.mask_vecs() as usize + self.list_vecs() as usize
        } else {
            0
        }
    }

    /// Size in bytes of `SpaceUniform` for this key, from the sizes of its typed parts.
    #[must_use]
    pub fn uniform_bytes(&self) -> usize {
        let vec4 = size_of::<Vec4F>();
        let (faces, balls, tubes) = self.array_sizes();
        let (faces, balls, tubes) = (faces as usize, balls as usize, tubes as usize);
        let count = |n: u32| n as usize;
        size_of::<GpuView>()
            + size_of::<GpuShading>()
            + vec4 // scene data offsets
            + count(self.lights) * (2 + count(self.light_images.max(1))) * vec4
            + faces * FACE_BYTES
            + faces.div_ceil(4) * vec4 // partners, four to a vec4
            + if self.cells { faces.div_ceil(4) * vec4 } else { 0 } // the faces' cells
            + if self.walls { (3 * faces + 1) * vec4 } else { 0 }
            + balls * size_of::<GpuBall>()
            + tubes * size_of::<GpuTube>()
            + count(self.globes) * size_of::<GpuGlobe>()
            + count(self.discs) * size_of::<GpuDisc>()
            + count(self.instances) * size_of::<GpuInstance>()
            + self.culling_vecs() * vec4
            + if self.general { vec4 } else { 0 }
            + if self.product {
                (2 + PRODUCT_OBJECT_VEC4S * count(self.product_objects.max(1))) * vec4
                    + if self.product_images > 0 {
                        (1 + count(self.product_images)) * vec4
                    } else {
                        0
                    }
            } else {
                0
            }
            + if self.nil {
                (2 + NIL_OBJECT_VEC4S * count(self.nil_objects.max(1))) * vec4
                    + if self.nil_images > 0 {
                        (1 + count(self.nil_images)) * vec4
                    } else {
                        0
                    }
            } else {
                0
            }
            + if self.sl2r {
                (3 + count(self.sl2r_object_vecs()) + 2 * count(self.sl2r_images.max(1))) * vec4
            } else {
                0
            }
    }
}

#[cfg(feature = "bench")]
/// Composes WGSL with shader defs through naga_oil (as Bevy does) into a naga module, with
/// the tracer's modules ([`super::SHADER_MODULES`]) available to `#import`; the error names
/// the file and what went wrong.
///
/// With the environment variable `CURVED_SPACES_SHADER_DIR` set to a folder, the modules and
/// the tracer's entry points are read from the files of that folder with the same names
/// instead of the copies built in (the benchmark then times shader edits without a rebuild);
/// a file it lacks is an error.
pub fn compose_wgsl(
    source: &str,
    file_path: &str,
    defs: &[ShaderDefVal],
) -> Result<naga::Module, String> {
    use naga_oil::compose::{
        ComposableModuleDescriptor, Composer, NagaModuleDescriptor, ShaderDefValue, ShaderLanguage,
        ShaderType,
    };
    let shader_defs: std::collections::HashMap<String, ShaderDefValue> = defs
        .iter()
        .map(|d| match d {
            ShaderDefVal::Bool(k, v) => (k.clone(), ShaderDefValue::Bool(*v)),
            ShaderDefVal::Int(k, v) => (k.clone(), ShaderDefValue::Int(*v)),
            ShaderDefVal::UInt(k, v) => (k.clone(), ShaderDefValue::UInt(*v)),
        })
        .collect();
    let dir = std::env::var_os("CURVED_SPACES_SHADER_DIR").map(std::path::PathBuf::from);
    let read = |path: &str, built_in: &str| -> Result<String, String> {
        let Some(dir) = &dir else {
            return Ok(built_in.to_owned());
        };
        let name = std::path::Path::new(path)
            .file_name()
            .unwrap_or(path.as_ref());
        let file = dir.join(name);
        std::fs::read_to_string(&file).map_err(|e| {
            format!(
                "{}: {e} (CURVED_SPACES_SHADER_DIR names the folder to read the shaders from)",
                file.display()
            )
        })
    };
    let source = read(file_path, source)?;
    let mut composer = Composer::default();
    for (path, module) in super::SHADER_MODULES {
        let module = read(path, module)?;
        let added = composer.add_composable_module(ComposableModuleDescriptor {
            source: &module,
            file_path: path,
            language: ShaderLanguage::Wgsl,
            shader_defs: shader_defs.clone(),
            ..Default::default()
        });
        if let Err(e) = added {
            return Err(format!("{path}: {}", e.emit_to_string(&composer)));
        }
    }
    let made = composer.make_naga_module(NagaModuleDescriptor {
        source: &source,
        file_path,
        shader_type: ShaderType::Wgsl,
        shader_defs,
        additional_imports: &[],
    });
    made.map_err(|e| format!("{file_path}: {}", e.emit_to_string(&composer)))
}

/// A name in a composed module without naga_oil's decoration of its module
/// (`SpaceUniformX_naga_oil_mod_X…X` → `SpaceUniform`).
#[cfg(feature = "bench")]
#[must_use]
pub fn undecorated(name: &str) -> &str {
    name.find("X_naga_oil_mod_X").map_or(name, |i| &name[..i])
}
