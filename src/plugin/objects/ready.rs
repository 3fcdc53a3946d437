//! The entities' objects gathered for the scene, with their meshes and textures ready.

use super::*;

/// A drawn object's shape with its mesh or texture ready.
// Gathered anew each frame objects change: no box per object.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum ReadyShape {
    /// A ball.
    Ball(f64),
    /// A globe: radius, texture, spin.
    Globe(f64, Arc<Texture>, f64),
    /// A tube: length, radius.
    Tube(f64, f64),
    /// A disc: radius.
    Disc(f64),
    /// A mesh.
    Mesh(Arc<TracedModel>),
    /// A base scene's object at a start frame.
    Carried(Object, DMat4),
}

/// One object to draw: what it is and where.
#[derive(Clone, Debug)]
pub struct ReadyObject {
    /// Its entity.
    pub entity: Entity,
    /// Its shape.
    pub shape: ReadyShape,
    /// Its frame in the cell.
    pub frame: DMat4,
    /// Albedo (`None`: a mesh's own materials).
    pub colour: Option<DVec3>,
    /// Emission.
    pub emission: DVec3,
    /// The share reflected as a mirror.
    pub reflectance: f64,
}

/// The entities' objects as the tracer will draw them, gathered when any changed; objects
/// whose mesh is not ready (still loading or building) are counted in `pending`, and
/// objects that cannot be drawn are described in `problems`.
#[derive(Resource, Clone, Debug, Default)]
pub struct EntityObjects {
    /// The objects, in entity order.
    pub objects: Vec<ReadyObject>,
    /// Objects whose mesh is still loading or being built.
    pub pending: usize,
    /// What is wrong with objects left out.
    pub problems: Vec<String>,
}

impl ReadyObject {
    /// The scene object: the shape placed at the frame, its mesh and texture added to
    /// `scene` (once each: `added` remembers them by identity).
    fn object(
        &self,
        geometry: Geometry,
        scene: &mut CurvedScene,
        added: &mut HashMap<usize, (u32, u32)>,
    ) -> Object {
        let g = geometry;
        let f = self.frame;
        let centre = g.project_point(f.w_axis);
        let colour = self.colour.unwrap_or(DVec3::ONE);
        match &self.shape {
            ReadyShape::Ball(r) => Object::Ball(
                Ball::new(g, centre, *r, colour)
                    .with_emission(self.emission)
                    .with_reflectance(self.reflectance),
            ),
            ReadyShape::Globe(r, texture, spin) => {
                let key = Arc::as_ptr(texture) as usize;
                let index = added
                    .entry(key)
                    .or_insert_with(|| {
                        scene.textures.push(texture.clone());
                        (scene.textures.len() as u32 - 1, 0)
                    })
                    .0;
                Object::Ball(
                    Ball::new(g, centre, *r, colour)
                        .with_emission(self.emission)
                        .with_reflectance(self.reflectance)
                        .with_texture(BallTexture {
                            texture: index,
                            frame: f,
                            spin: *spin,
                        }),
                )
            }
            ReadyShape::Tube(length, radius) => {
                let end = |t: f64| {
                    g.project_point(f * g.translation(DVec3::Y, t) * crate::geometry::ORIGIN)
                };
                Object::Tube(
                    Tube::new(g, end(-0.5 * length), end(0.5 * length), *radius, colour)
                        .with_emission(self.emission),
                )
            }
            ReadyShape::Disc(r) => Object::Disc(
                Disc::new(g, centre, g.unit_tangent(centre, f.z_axis), *r, colour)
                    .with_emission(self.emission)
                    .with_reflectance(self.reflectance),
            ),
            ReadyShape::Carried(object, start) => object.transformed(g, f * g.inverse(*start)),
            ReadyShape::Mesh(model) => {
                let key = Arc::as_ptr(&model.mesh) as usize;
                let (mesh, base) = *added.entry(key).or_insert_with(|| scene.add_traced(model));
                let mut instance = MeshInstance::new(g, mesh, f, model.mesh.radius);
                instance.material_base = base;
                if self.colour.is_some() || self.emission != DVec3::ZERO || self.reflectance > 0.0 {
                    scene.materials.push(SurfaceMaterial {
                        colour,
                        texture: None,
                        emission: self.emission,
                        reflectance: self.reflectance,
                    });
                    instance.material = Some(scene.materials.len() as u32 - 1);
                }
                Object::Mesh(instance)
            }
        }
    }
}

/// Adds the entities' objects to `scene` with their images through the faces
/// ([`CurvedScene::place`]); returns what could not be placed.
pub fn add_entity_objects(
    scene: &mut CurvedScene,
    space: &Space,
    objects: &[ReadyObject],
) -> Vec<String> {
    let mut added = HashMap::new();
    let mut problems = Vec::new();
    for o in objects {
        let object = o.object(space.geometry, scene, &mut added);
        if let Err(e) = scene.place(space, object) {
            problems.push(format!("object {}: {e}", o.entity));
        }
    }
    problems
}
