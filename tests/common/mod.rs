//! Helpers shared by the DEM test files.

use dismech::dem::DemSimulation;
use dismech::explicit::{DemSettings, RestCriterion, RunStatus};
use dismech::integrate::ExplicitEuler;
use dismech::law::{BoundedStiffness, ContactLaw};
use dismech::scene::Scene;

/// Run `scene` with `law` and time step `dt` until it is at rest by a
/// strict criterion (kinetic / released energy below 1e-10, unbalanced
/// force below 1e-8 of the weight); fails the test otherwise.
pub fn settle<L: ContactLaw<2> + BoundedStiffness<2>>(
    scene: Scene,
    law: L,
    dt: f64,
) -> DemSimulation<L> {
    let settings = DemSettings {
        dt,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, settings).unwrap();
    let criterion = RestCriterion {
        kinetic_to_released_ratio: 1e-10,
        unbalanced_force_ratio: 1e-8,
        ..RestCriterion::default()
    };
    let outcome = sim.run_to_rest(&criterion, |_, _| {}).unwrap();
    assert_eq!(outcome.status, RunStatus::AtRest);
    sim
}
