//! Cross-compositions: models that combine the slots in ways the four
//! papers do not, each a short constructor over the library's drivers and a
//! function that measures what an exact solution or a second method
//! predicts. The `compositions` study and the tests call the same
//! functions.
//!
//! | composition | drivers and pieces | checked against |
//! |---|---|---|
//! | [`polygon_incline`]: a rigid rectangle on an incline | [`crate::shape::Polygon`], [`crate::contact::dispatch::contact_manifold_2d`] (polygon–wall, two points), [`crate::law::SpringDashpotCoulomb`] with a constant `k_n`, [`crate::dem::DemSimulation`] | sliding at `g (sin β − μ cos β)`, or at rest for `tan β ≤ μ` |
//! | [`packing_lp`]: a DEM-settled packing of ellipses | explicit DEM of ellipses → limit analysis ([`crate::limit::model_from_packing`], Clarabel) | equilibrium of the dual, primal = dual |

pub mod packing_lp;
pub mod polygon_incline;
