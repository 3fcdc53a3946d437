//! One generic part of the plugin per geometry family, as bevy_pbr registers its systems
//! once per material: [`FamilyPlugin<F>`] adds the systems written once over the geometry
//! contract ([`FamilySpace`]) — the players' motion and wrap, the entities' motion and wrap —
//! instantiated for the family `F` and run while the [`ActiveSpace`] is of that family.
//! [`crate::CurvedSpacesPlugin`] adds one for each family.

use crate::plugin::components::{ActiveSpace, CurvedSpacesSystems};
use crate::plugin::objects::{move_objects, wrap_objects};
use crate::plugin::player::{move_players, wrap_players};
use crate::space::FamilySpace;
use bevy::prelude::*;
use std::marker::PhantomData;

/// The systems of the family `F` (its space type implements the geometry contract).
pub struct FamilyPlugin<F: FamilySpace>(PhantomData<F>);

impl<F: FamilySpace> Default for FamilyPlugin<F> {
    fn default() -> Self {
        Self(PhantomData)
    }
}

impl<F: FamilySpace> Plugin for FamilyPlugin<F> {
    fn build(&self, app: &mut App) {
        let shown = ActiveSpace::shows(F::FAMILY);
        app.add_systems(
            FixedUpdate,
            (move_objects::<F>, wrap_objects::<F>)
                .chain()
                .run_if(shown.clone()),
        )
        .add_systems(
            Update,
            (
                move_players::<F>
                    .in_set(CurvedSpacesSystems::Move)
                    .after(crate::plugin::player::reset_players_on_switch),
                (wrap_players::<F>, wrap_objects::<F>).in_set(CurvedSpacesSystems::Wrap),
            )
                .run_if(shown),
        );
    }
}
