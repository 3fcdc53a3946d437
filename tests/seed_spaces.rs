use bevy_curved_spaces::prelude::*;
use bevy_curved_spaces::space::invariants::*;

#[test]
fn every_seed_space_validates() {
    for s in SEED_SPACES {
        let space = s.build().unwrap_or_else(|e| panic!("{}: {e}", s.id));
        let t = std::time::Instant::now();
        eprintln!("{}: vol {:.15} in {:.6} circ {:.6} edge {:?} hol {:?} grp {:?} inj {:?} geo {:?} ({:?})", s.id, volume(&space), inradius(&space), circumradius(&space), edge_length(&space), holonomy_order(&space), group_order(&space), injectivity_radius(&space), closed_geodesics(&space, 3.5), t.elapsed());
    }
}
