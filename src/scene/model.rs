//! The scene: what the rays can see in the cell, and how objects are placed so that they
//! look whole through the faces.

use super::mesh::{self, Mesh, Model};
use super::object::{Ball, Hit, MeshInstance, Object, Tube};
use super::shading::{DEFAULT_CUTOFF_WEIGHT, Light, Shading, SurfaceMaterial};
use super::{FaceCulling, avatar, texture::Texture};
use crate::geometry::Geometry;
use crate::space::Space;
use glam::{DMat4, DVec2, DVec3, DVec4};
use std::sync::Arc;

mod parts;
mod traced;

pub use parts::{Centrepiece, SceneParts, clifford_parallels, gyroscope};
pub use traced::{TracedModel, avatar_size};

/// The most images of one object [`CurvedScene::place`] adds (an object far larger than the cell
/// would need more, and is refused).
pub const MAX_IMAGES: usize = 512;

/// An object could not be placed.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlaceError {
    /// The object is not inside the cell: its centre is outside a face (by the distance, through the face, attached).
    #[error("the object is not inside the cell: its centre is {0:.3} outside face {1}")]
    Outside(f64, usize),
    /// The object's centre or size is not a finite number (a position too far away for
    /// the geometry, or NaN).
    #[error("the object's centre or size is not a finite number (is it too far away?)")]
    NotFinite,
    /// The object meets more than [`MAX_IMAGES`] copies of the cell.
    #[error(
        "the object meets more than {MAX_IMAGES} copies of the cell; make it smaller than the cell"
    )]
    TooLarge,
}

/// The player's own avatar: a mesh at the player's frame, seen only where rays come back
/// round the space (hits closer than `skip` to the eye are the copy the eye sits in, and
/// are passed through).
#[derive(Clone, Debug, PartialEq)]
pub struct Avatar {
    /// Index into [`CurvedScene::meshes`].
    pub mesh: u32,
    /// The avatar at the player's frame and its images under the pairings that meet the
    /// cell ([`CurvedScene::set_avatar_frame`]).
    pub instances: Vec<MeshInstance>,
    /// Hits nearer than this to the eye are not drawn.
    pub skip: f64,
}

/// The most images of the avatar drawn (its copy and those through nearby faces, edges and
/// vertices).
pub const MAX_AVATAR_IMAGES: usize = 8;

/// The avatar (mesh `mesh` of radius `radius`) at the player's `frame` and its images under
/// the pairings that meet the cell, nearest first, at most [`MAX_AVATAR_IMAGES`].
#[must_use]
pub fn avatar_instances(space: &Space, mesh: u32, radius: f64, frame: DMat4) -> Vec<MeshInstance> {
    let g = space.geometry;
    let instance = MeshInstance::new(g, mesh, frame, radius);
    let mut scratch = CurvedScene::new(Vec::new(), Vec::new(), Shading::default());
    // The player is kept inside the cell, so placing cannot fail; keep the avatar itself
    // if it somehow does.
    if scratch.place(space, Object::Mesh(instance)).is_err() {
        scratch.objects = vec![Object::Mesh(instance)];
    }
    let origin = instance.origin(g);
    let mut instances: Vec<MeshInstance> = scratch
        .objects
        .into_iter()
        .filter_map(|o| match o {
            Object::Mesh(m) => Some(m),
            _ => None,
        })
        .collect();
    instances.sort_by(|a, b| {
        g.distance(a.origin(g), origin)
            .total_cmp(&g.distance(b.origin(g), origin))
    });
    instances.truncate(MAX_AVATAR_IMAGES);
    instances
}

/// What the rays can see: objects in the cell, lights, meshes with their materials and
/// textures, the player's avatar, the shading.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvedScene {
    /// Objects, images included.
    pub objects: Vec<Object>,
    /// Point lights.
    pub lights: Vec<Light>,
    /// The shading model: fog, ambient light, cut-off.
    pub shading: Shading,
    /// Meshes that [`MeshInstance`]s place.
    pub meshes: Vec<Arc<Mesh>>,
    /// Materials of the meshes' triangles.
    pub materials: Vec<SurfaceMaterial>,
    /// Textures of materials and globes.
    pub textures: Vec<Arc<Texture>>,
    /// Seconds since the start: turns the spinning globes.
    pub time: f64,
    /// The player's ship, if drawn.
    pub avatar: Option<Avatar>,
}

/// What a ray segment meets first: the object's index (`objects.len() + k` for the avatar's
/// `k`-th image) and the hit.
pub type SegmentHit = (usize, Hit);

impl CurvedScene {
    /// A scene with these objects and lights, nothing else.
    #[must_use]
    pub fn new(objects: Vec<Object>, lights: Vec<Light>, shading: Shading) -> Self {
        Self {
            objects,
            lights,
            shading,
            meshes: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            time: 0.0,
            avatar: None,
        }
    }

    /// The first hit along the segment `X(s) ∝ p + s v`, `0 < s < s_max`, of a ray that has
    /// come `travelled` from the eye.
    #[must_use]
    pub fn intersect(
        &self,
        g: Geometry,
        p: DVec4,
        v: DVec4,
        s_max: f64,
        travelled: f64,
    ) -> Option<SegmentHit> {
        self.intersect_culled(g, p, v, s_max, travelled, None)
    }

    /// [`CurvedScene::intersect`], skipping the objects that `culling` (this scene's, from
    /// [`FaceCulling::new`]) shows the segment cannot meet: the same hit, sooner.
    #[must_use]
    pub fn intersect_culled(
        &self,
        g: Geometry,
        p: DVec4,
        v: DVec4,
        s_max: f64,
        travelled: f64,
        culling: Option<&FaceCulling>,
    ) -> Option<SegmentHit> {
        let mut best: Option<SegmentHit> = None;
        let mut limit = s_max;
        let near = culling.map(|c| (c, c.near_faces(p, v, s_max)));
        for (i, o) in self.objects.iter().enumerate() {
            if let Some((c, near)) = near
                && !(c.may_meet(i, near) && c.may_meet_at_once(i, p, v, s_max))
            {
                continue;
            }
            let hit = match o {
                Object::Mesh(m) => self.intersect_mesh(g, m, p, v, limit),
                _ => o.intersect(g, p, v, limit).map(|mut h| {
                    if let Object::Ball(Ball {
                        texture: Some(t), ..
                    }) = o
                    {
                        h.colour *= self.texture_colour(t.texture, t.uv(g, h.point, self.time));
                    }
                    h
                }),
            };
            if let Some(h) = hit {
                limit = h.s;
                best = Some((i, h));
            }
        }
        if let Some(avatar) = &self.avatar {
            for (k, m) in avatar.instances.iter().enumerate() {
                if let Some(h) = self.intersect_mesh(g, m, p, v, limit)
                    && travelled + g.distance_from_ratio(h.s, 1.0) >= avatar.skip
                {
                    limit = h.s;
                    best = Some((self.objects.len() + k, h));
                }
            }
        }
        best
    }

    fn texture_colour(&self, texture: u32, uv: DVec2) -> DVec3 {
        self.textures
            .get(texture as usize)
            .map_or(DVec3::ONE, |t| t.sample(uv))
    }

    /// A mesh instance's first hit on the segment, with the material's colour and the
    /// normal of the plane through the hit whose chart normal is the interpolated vertex
    /// normal (facing the ray).
    #[must_use]
    pub fn intersect_mesh(
        &self,
        g: Geometry,
        m: &MeshInstance,
        p: DVec4,
        v: DVec4,
        s_max: f64,
    ) -> Option<Hit> {
        let mesh = self.meshes.get(m.mesh as usize)?;
        let (o, d, pw, vw) = m.local_ray(p, v)?;
        let den = pw + s_max * vw;
        let t_max = if den > 0.0 {
            s_max / den
        } else {
            f64::INFINITY
        };
        let h = mesh.intersect(o, d, t_max)?;
        let s = h.t * pw / (1.0 - h.t * vw);
        if !(s > 0.0 && s < s_max) {
            return None;
        }
        let tri = &mesh.triangles[h.triangle];
        let w = [1.0 - h.u - h.v, h.u, h.v];
        let x = o + h.t * d;
        let n = (tri.normals[0] * w[0] + tri.normals[1] * w[1] + tri.normals[2] * w[2])
            .normalize_or_zero();
        let k = g.kappa();
        let local_normal = if k == 0.0 {
            n.extend(0.0)
        } else {
            n.extend(-n.dot(x) / k)
        };
        let point = g.project_point(p + s * v);
        let mut normal = g.unit_tangent(point, m.frame * local_normal);
        if g.form(normal, v) > 0.0 {
            normal = -normal;
        }
        let material = m
            .material
            .unwrap_or(tri.material.saturating_add(m.material_base))
            .min(self.materials.len().saturating_sub(1) as u32);
        let mat = self
            .materials
            .get(material as usize)
            .copied()
            .unwrap_or_default();
        let uv = tri.uvs[0] * w[0] + tri.uvs[1] * w[1] + tri.uvs[2] * w[2];
        let colour = match mat.texture {
            Some(t) => mat.colour * self.texture_colour(t, uv),
            None => mat.colour,
        };
        Some(Hit {
            s,
            point,
            normal,
            colour,
            emission: mat.emission,
            reflectance: mat.reflectance,
        })
    }

    /// Whether any surface reflects as a mirror (a ball, disc or material with a
    /// reflectance above 0).
    #[must_use]
    pub fn has_mirrors(&self) -> bool {
        self.objects.iter().any(|o| match o {
            Object::Ball(b) => b.reflectance > 0.0,
            Object::Disc(d) => d.reflectance > 0.0,
            Object::Tube(_) | Object::Mesh(_) => false,
        }) || self.materials.iter().any(|m| m.reflectance > 0.0)
    }

    /// Gathers the lamps' light as `lighting` says ([`crate::scene::lighting`]): sets it in
    /// the shading and finds each lamp's images in the cover within its reach. The message
    /// names a setting out of range.
    pub fn set_lighting(&mut self, space: &Space, lighting: super::Lighting) -> Result<(), String> {
        lighting.check()?;
        let reach = lighting.reach(space);
        let radius = lighting.lamp_radius(space);
        for light in &mut self.lights {
            *light = light.with_reach(space, reach).with_radius(radius);
        }
        self.shading.lighting = lighting;
        Ok(())
    }

    /// Puts the avatar at the player's `frame`, with its images under the pairings where it
    /// sticks out of the cell ([`avatar_instances`]).
    pub fn set_avatar_frame(&mut self, space: &Space, frame: DMat4) {
        let Some(avatar) = self.avatar.as_mut() else {
            return;
        };
        let radius = self
            .meshes
            .get(avatar.mesh as usize)
            .map_or(0.0, |m| m.radius);
        avatar.instances = avatar_instances(space, avatar.mesh, radius, frame);
    }
}

/// Distinct colours for edge cycles (a golden-angle walk around the hue circle).
#[must_use]
pub fn palette(i: usize) -> DVec3 {
    let h = (i as f64 * 0.618_033_988_75 + 0.08).fract() * 6.0;
    let x = 1.0 - (h % 2.0 - 1.0).abs();
    let (r, g, b) = match h as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    DVec3::new(r, g, b) * 0.75 + DVec3::splat(0.2)
}

impl CurvedScene {
    /// Adds `object` (its centre inside the cell) and, where it sticks out through faces,
    /// its images under the pairings that meet the cell, so that it is seen whole from
    /// every side and in every copy of the cell. Images equal to an object already in the
    /// scene are not added twice. Returns how many objects were added.
    ///
    /// A ray that leaves through face `f` continues from `g_f` of its exit point, so the
    /// part of an object outside `f` is seen inside the cell as `g_f(object)`: that image
    /// is added when the object reaches past `f` and the image comes within reach of the
    /// cell (tested at points along a tube's axis); images of images are followed the same way (edges, vertices).
    /// The test is conservative: a tube whose flat end only touches the cell at a vertex
    /// (an edge of a neighbouring cell) is kept too; it costs time, never a wrong pixel.
    pub fn place(&mut self, space: &Space, object: Object) -> Result<usize, PlaceError> {
        let g = space.geometry;
        let (centre, radius) = object.bounding_ball(g);
        if !(centre.is_finite() && radius.is_finite()) {
            return Err(PlaceError::NotFinite);
        }
        let (f, d) = space.past_face(centre);
        if d > 1e-9 || d.is_nan() {
            return Err(PlaceError::Outside(d, f));
        }
        const SAME: f64 = 1e-9;
        // Points along the object's core (a ball's centre, a tube's axis at spacing ≤ its
        // radius) and the slack they need: every point of the object is within `reach` of one.
        let cores = |o: &Object| -> (Vec<DVec4>, f64) {
            match o {
                Object::Ball(b) => (vec![b.centre], b.radius),
                Object::Disc(d) => (vec![d.centre], d.radius),
                Object::Mesh(m) => (vec![m.origin(g)], m.radius),
                Object::Tube(t) => {
                    let length = g.distance(t.a, t.b);
                    let steps = ((length / t.radius.max(1e-9)).ceil() as usize).clamp(1, 256);
                    let step = length / steps as f64;
                    let points = (0..=steps)
                        .map(|i| g.project_point(g.geodesic(t.a, t.towards_b, i as f64 * step).0))
                        .collect();
                    (points, t.radius + 0.5 * step)
                }
            }
        };
        // Conservative: a point whose largest face distance is under `reach` may be within
        // `reach` of the cell (the face distances underestimate near edges and vertices).
        let meets_cell = |o: &Object| {
            let (points, reach) = cores(o);
            points.iter().any(|p| space.past_face(*p).1 < reach)
        };
        let mut found: Vec<Object> = Vec::new();
        let mut queue = vec![object];
        while let Some(o) = queue.pop() {
            if found.iter().any(|x| x.same_as(&o, g, SAME)) {
                continue;
            }
            if found.len() >= MAX_IMAGES {
                return Err(PlaceError::TooLarge);
            }
            let (points, reach) = cores(&o);
            for (f, face) in space.faces.iter().enumerate() {
                // A seam's image is the object itself.
                if space.is_seam(f) {
                    continue;
                }
                if points.iter().any(|p| space.face_distance(f, *p) > -reach) {
                    let image = o.transformed(g, face.pairing);
                    if meets_cell(&image) && !found.iter().any(|x| x.same_as(&image, g, SAME)) {
                        queue.push(image);
                    }
                }
            }
            found.push(o);
        }
        let before = self.objects.len();
        for o in found {
            if !self.objects.iter().any(|x| x.same_as(&o, g, SAME)) {
                self.objects.push(o);
            }
        }
        Ok(self.objects.len() - before)
    }

    /// The default scene of a space: the cell's edges as thin tubes coloured by edge cycle,
    /// a small ball at each vertex, a ball at the centre and one light, with fog at `fog`.
    #[must_use]
    pub fn default_for(space: &Space, fog_distance: f64) -> Self {
        Self::with_parts(space, fog_distance, SceneParts::default())
    }

    /// The default scene with only the chosen parts (the light and shading are the same).
    #[must_use]
    pub fn with_parts(space: &Space, fog_distance: f64, parts: SceneParts) -> Self {
        let g = space.geometry;
        let inradius = crate::space::invariants::inradius(space);
        let light_at = g.translation(DVec3::new(0.45, 0.8, 0.4), 0.65 * inradius) * space.centre();
        let light = Light::new(space, light_at, DVec3::ONE, g.s(0.7 * inradius).powi(2));
        CurvedScene::new(
            Vec::new(),
            vec![light],
            Shading {
                ambient: 0.3,
                fog_colour: DVec3::new(0.04, 0.05, 0.08),
                fog_distance,
                near_light: 0.05 * inradius,
                cutoff_weight: DEFAULT_CUTOFF_WEIGHT,
                colour_by: super::ColourBy::Shading,
                walls: None,
                lighting: super::Lighting::default(),
            },
        )
        .adding_parts(space, parts)
    }

    /// This scene with the default scene's parts added: the part objects before its own,
    /// and the avatar given or taken away as `parts.avatar` says. A scene file's scene and
    /// the plugin's base scene are made whole this way.
    #[must_use]
    pub fn adding_parts(&self, space: &Space, parts: SceneParts) -> CurvedScene {
        let mut scene = self.clone();
        scene.objects.splice(0..0, Self::part_objects(space, parts));
        if parts.clifford {
            for tube in clifford_parallels(space) {
                // A segment too large to place is left out (it never is for these sizes).
                let _ = scene.place(space, tube);
            }
        }
        scene.add_centrepiece(space, parts.centrepiece);
        if !parts.avatar {
            scene.avatar = None;
        } else if scene.avatar.is_none() {
            let size = crate::scene::avatar_size(crate::space::invariants::inradius(space));
            // The ship is a fixed small model: placing it cannot fail.
            let _ = scene.add_avatar(space.geometry, size);
        }
        scene
    }

    /// Adds the centrepieces that need a texture or a mesh (the globe, the galaxy) at the
    /// cell's centre; the ball and the gyroscope are plain objects ([`Self::part_objects`]).
    fn add_centrepiece(&mut self, space: &Space, centrepiece: Centrepiece) {
        use crate::scene::centrepiece::{
            GLOBE_SPIN, centrepiece_tilt, galaxy_model, galaxy_radius, globe_texture,
        };
        let g = space.geometry;
        // Centrepieces stay well inside the chart's hemisphere in S³.
        let inradius =
            crate::space::invariants::inradius_at_most(space, std::f64::consts::FRAC_PI_4);
        let frame = g.translation_to(space.centre()) * centrepiece_tilt(g);
        let object = match centrepiece {
            Centrepiece::Globe => {
                self.textures.push(globe_texture());
                Object::Ball(
                    Ball::new(g, space.centre(), 0.3 * inradius, DVec3::ONE).with_texture(
                        crate::scene::BallTexture {
                            texture: self.textures.len() as u32 - 1,
                            frame,
                            spin: GLOBE_SPIN,
                        },
                    ),
                )
            }
            Centrepiece::Galaxy => {
                let radius = galaxy_radius(inradius);
                // A fixed small model, well inside π/2: placing it cannot fail.
                let Ok(mesh) = self.add_model(g, &galaxy_model(), radius) else {
                    return;
                };
                let r = self.meshes[mesh as usize].radius;
                Object::Mesh(MeshInstance::new(g, mesh, frame, r))
            }
            Centrepiece::None | Centrepiece::Ball | Centrepiece::Gyroscope => return,
        };
        // Well inside the cell (a third of the inradius or less): no images, cannot fail.
        let _ = self.place(space, object);
    }

    /// The objects of the default scene's parts: the cell's edges as thin tubes coloured by
    /// edge cycle with a small ball at each vertex, and the centre ball (the avatar is not
    /// an object: see [`CurvedScene::add_avatar`]).
    #[must_use]
    pub fn part_objects(space: &Space, parts: SceneParts) -> Vec<Object> {
        let g = space.geometry;
        let inradius = crate::space::invariants::inradius(space);
        let tube = 0.05 * inradius;
        let edges = if parts.edges {
            space.edges.as_slice()
        } else {
            &[]
        };
        let vertices = if parts.edges { space.vertices.len() } else { 0 };
        // In a space of several cells, the seams between them are inside the fundamental
        // domain: their edges and vertices are none of the domain's.
        let on_seam = |v: usize| {
            space
                .faces
                .iter()
                .enumerate()
                .any(|(i, f)| f.vertices.contains(&v) && space.is_seam(i))
        };
        let mut objects: Vec<Object> = edges
            .iter()
            .filter(|e| !e.faces.iter().any(|&f| space.is_seam(f)))
            .map(|e| {
                Object::Tube(Tube::new(
                    g,
                    space.vertex_point(e.vertices[0]),
                    space.vertex_point(e.vertices[1]),
                    tube,
                    palette(e.cycle),
                ))
            })
            .collect();
        // A lens beyond the chart (L(P, 1)): its one edge is the great circle where its two
        // faces meet, at π/2 from the centre and without vertices, drawn as four quarters.
        if parts.edges && space.reaches_equator() && space.faces.len() == 2 {
            // Gram–Schmidt: the two covectors first, then the plane orthogonal to both.
            let mut basis: Vec<DVec4> = Vec::new();
            let candidates = [space.faces[0].covector, space.faces[1].covector];
            for e in candidates
                .into_iter()
                .chain([DVec4::X, DVec4::Y, DVec4::Z, DVec4::W])
            {
                let mut v = e;
                for b in &basis {
                    v -= *b * v.dot(*b);
                }
                if v.length() > 1e-6 && basis.len() < 4 {
                    basis.push(v.normalize());
                }
            }
            if let [_, _, e1, e2] = basis[..] {
                let at = |k: f64| {
                    let t = k * std::f64::consts::FRAC_PI_2;
                    e1 * t.cos() + e2 * t.sin()
                };
                objects.extend((0..4).map(|k| {
                    Object::Tube(Tube::new(
                        g,
                        at(f64::from(k)),
                        at(f64::from(k + 1)),
                        tube,
                        palette(0),
                    ))
                }));
            }
        }
        objects.extend((0..vertices).filter(|&v| !on_seam(v)).map(|v| {
            Object::Ball(Ball::new(
                g,
                space.vertex_point(v),
                1.6 * tube,
                DVec3::splat(0.9),
            ))
        }));
        if parts.centrepiece == Centrepiece::Gyroscope {
            objects.extend(gyroscope(space));
        }
        if parts.centrepiece == Centrepiece::Ball {
            objects.push(Object::Ball(Ball::new(
                g,
                space.centre(),
                0.25 * inradius,
                DVec3::new(1.0, 0.78, 0.45),
            )));
        }
        objects
    }
}
