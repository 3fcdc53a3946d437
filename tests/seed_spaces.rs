use bevy_curved_spaces::prelude::*;

#[test]
fn every_seed_space_validates() {
    for s in SEED_SPACES {
        let space = s.build().unwrap_or_else(|e| panic!("{}: {e}", s.id));
        eprintln!("{}: V{} E{} cycles {:?} vcycles {} orientable {} manifold {}", s.id, space.vertices.len(), space.edges.len(),
          space.edge_cycles.iter().map(|c| (c.edges.len(), c.angle_sum.to_degrees(), c.order)).collect::<Vec<_>>(), space.vertex_cycles.len(), space.orientable, space.manifold);
    }
}
