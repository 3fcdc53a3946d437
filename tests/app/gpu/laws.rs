//! The GPU's laws, written once over what a geometry family's pictures need and instantiated
//! per family with one line of `gpu_laws!` (as `tests/core/laws.rs` does for the walk):
//!
//! - the GPU draws the CPU reference's picture (the default view, mono);
//! - each half of a side-by-side stereo picture is its eye's own mono picture, the eyes
//!   half the eye distance either side of the head along its right, carried along the
//!   family's geodesic and wrapped into the cell on their own.

use super::*;
use bevy_curved_spaces::plugin::components::StereoSettings;
use bevy_curved_spaces::space::product::ProductSpace;
use bevy_curved_spaces::view::StereoMode;
use glam::DMat4;

/// The pictures' size: small, the cost follows the slowest pixel of each block on lavapipe.
const W: u32 = 96;
const H: u32 = 54;
/// The crossing budget of both tracers.
const CROSSINGS: u32 = 24;

/// What the laws need of a family: its spaces, its default view, its eyes and its two
/// tracers' pictures from a frame.
trait GpuLawFamily: Sized {
    /// The spaces the laws run in, by name.
    fn cases() -> Vec<(String, Self)>;
    /// The default view: the frame and the vertical field of view.
    fn view(&self) -> (DMat4, f64);
    /// The cell's size (the eye distance is measured in it).
    fn scale(&self) -> f64;
    /// The two eyes of a head, `ipd` apart, each in the cell.
    fn eyes(&self, head: DMat4, ipd: f64) -> [DMat4; 2];
    /// The GPU tracer's picture from a frame with a vertical field of view.
    fn gpu(
        &self,
        renderer: &mut OffscreenRenderer,
        view: (DMat4, f64),
        size: (u32, u32),
        stereo: StereoSettings,
    ) -> RgbImage;
    /// The CPU reference's mono picture from `frame`.
    fn cpu(&self, frame: DMat4, fov: f64, size: (u32, u32)) -> RgbImage;
}

/// A constant-curvature space.
struct Constant(String, Space);

impl GpuLawFamily for Constant {
    fn cases() -> Vec<(String, Self)> {
        ["torus", "torus-two-cells", "poincare", "seifert-weber"]
            .into_iter()
            .map(|id| {
                let space = crate::common::library_space(id);
                (id.to_string(), Constant(id.to_string(), space))
            })
            .collect()
    }
    fn view(&self) -> (DMat4, f64) {
        let camera = TraceCamera::default_for(&self.1);
        (camera.frame, camera.fov_y_degrees)
    }
    fn scale(&self) -> f64 {
        bevy_curved_spaces::space::invariants::inradius(&self.1)
    }
    fn eyes(&self, head: DMat4, ipd: f64) -> [DMat4; 2] {
        bevy_curved_spaces::view::stereo::eye_frames(&self.1, head, ipd).map(|e| e.frame)
    }
    fn gpu(
        &self,
        renderer: &mut OffscreenRenderer,
        (frame, fov): (DMat4, f64),
        size: (u32, u32),
        stereo: StereoSettings,
    ) -> RgbImage {
        let camera = TraceCamera {
            frame,
            fov_y_degrees: fov,
        };
        renderer
            .render(&OffscreenRender {
                fog_distance: Some(Shading::default_fog_distance(&self.1)),
                stereo,
                ..OffscreenRender::new(
                    ActiveSpace::new(self.0.as_str(), self.1.clone()),
                    camera,
                    size,
                    CROSSINGS,
                )
            })
            .unwrap_or_else(|e| panic!("{}: {e}", self.0))
    }
    fn cpu(&self, frame: DMat4, fov: f64, (width, height): (u32, u32)) -> RgbImage {
        let fog = Shading::default_fog_distance(&self.1);
        let scene = CurvedScene::with_parts(&self.1, fog, SceneParts::default());
        let camera = TraceCamera {
            frame,
            fov_y_degrees: fov,
        };
        render(
            &self.1,
            &scene,
            &camera,
            &RenderSettings {
                width,
                height,
                max_crossings: CROSSINGS as usize,
            },
        )
    }
}

/// A product space (H²×R, S²×R).
struct Product(ProductSpace);

impl Product {
    fn camera(frame: DMat4, fov: f64) -> bevy_curved_spaces::trace::product::ProductCamera {
        bevy_curved_spaces::trace::product::ProductCamera {
            point: frame.w_axis,
            frame: [frame.x_axis, frame.y_axis, frame.z_axis],
            fov_y_degrees: fov,
        }
    }
}

impl GpuLawFamily for Product {
    fn cases() -> Vec<(String, Self)> {
        [
            "bitorus-circle",
            "sphere-circle-turn",
            "projective-plane-circle",
        ]
        .into_iter()
        .map(|id| (id.to_string(), Product(crate::common::product(id))))
        .collect()
    }
    fn view(&self) -> (DMat4, f64) {
        let c = bevy_curved_spaces::trace::product::default_camera(&self.0);
        (
            bevy_curved_spaces::space::product::motion::camera_frame(c.point, c.frame),
            c.fov_y_degrees,
        )
    }
    fn scale(&self) -> f64 {
        self.0.scale()
    }
    fn eyes(&self, head: DMat4, ipd: f64) -> [DMat4; 2] {
        bevy_curved_spaces::space::product::motion::product_eye_frames(&self.0, head, ipd)
    }
    fn gpu(
        &self,
        renderer: &mut OffscreenRenderer,
        (frame, fov): (DMat4, f64),
        size: (u32, u32),
        stereo: StereoSettings,
    ) -> RgbImage {
        let scene = bevy_curved_spaces::trace::product::default_scene(&self.0);
        renderer
            .render_product_stereo(
                &self.0,
                &scene,
                &Self::camera(frame, fov),
                size,
                CROSSINGS,
                stereo,
            )
            .unwrap_or_else(|e| panic!("{}: {e}", self.0.name()))
    }
    fn cpu(&self, frame: DMat4, fov: f64, (width, height): (u32, u32)) -> RgbImage {
        let scene = bevy_curved_spaces::trace::product::default_scene(&self.0);
        bevy_curved_spaces::trace::product::render_product(
            &self.0,
            &scene,
            &Self::camera(frame, fov),
            width,
            height,
            CROSSINGS as usize,
        )
    }
}

/// The GPU draws the CPU reference's picture of the default view.
fn the_gpu_draws_the_cpu_picture<F: GpuLawFamily>() {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-laws");
    let mut failures = Vec::new();
    for (id, family) in F::cases() {
        let (frame, fov) = family.view();
        let gpu = family.gpu(
            &mut renderer,
            (frame, fov),
            (W, H),
            StereoSettings::default(),
        );
        let cpu = family.cpu(frame, fov, (W, H));
        judge(&id, &gpu, &cpu, &out, &mut failures);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Each half of the GPU's side-by-side picture is its eye's own mono picture at half the
/// width: the eyes are the family's, and the stereo layout adds nothing of its own.
fn stereo_halves_are_the_eyes_pictures<F: GpuLawFamily>() {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for (id, family) in F::cases() {
        let (head, fov) = family.view();
        let ipd = 0.12 * family.scale();
        let stereo = StereoSettings {
            mode: StereoMode::SideBySide,
            ipd: Some(ipd),
            swap_eyes: false,
        };
        let both = family.gpu(&mut renderer, (head, fov), (2 * W, H), stereo);
        let eyes = family.eyes(head, ipd);
        let mut halves = Vec::new();
        for (k, eye) in eyes.iter().enumerate() {
            let mono = family.gpu(
                &mut renderer,
                (*eye, fov),
                (W, H),
                StereoSettings::default(),
            );
            let half = image::imageops::crop_imm(&both, k as u32 * W, 0, W, H).to_image();
            let (c, _) = compare(&half, &mono, TOLERANCE);
            println!(
                "{id:<24} eye {k}: its half of the stereo picture against its mono picture: {:.3} % differ, max {}",
                100.0 * c.differing,
                c.max_error
            );
            assert!(
                c.differing <= MAX_DIFFERING,
                "{id}: eye {k}'s half differs from its mono picture in {:.2} % of pixels",
                100.0 * c.differing
            );
            halves.push(half);
        }
        // The eyes see different pictures: the law sees two eyes, not one twice.
        assert!(
            compare(&halves[0], &halves[1], TOLERANCE).0.differing > 0.01,
            "{id}: both halves are one picture"
        );
    }
}

/// Every GPU law, as tests of a family: `gpu_laws!(module, Family);`.
macro_rules! gpu_laws {
    ($module:ident, $family:ty) => {
        mod $module {
            use super::*;

            #[test]
            fn the_gpu_draws_the_cpu_picture() {
                super::the_gpu_draws_the_cpu_picture::<$family>();
            }

            #[test]
            fn stereo_halves_are_the_eyes_pictures() {
                super::stereo_halves_are_the_eyes_pictures::<$family>();
            }
        }
    };
}

gpu_laws!(constant_curvature, Constant);
gpu_laws!(products, Product);
