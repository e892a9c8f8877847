//! Cross-compositions: models that combine the slots in ways the four
//! papers do not, each a short constructor over the library's drivers and a
//! function that measures what an exact solution or a second method
//! predicts. The `compositions` study and the tests call the same
//! functions.
//!
//! | composition | drivers and pieces | checked against |
//! |---|---|---|
//! | [`packing_lp`] | explicit DEM of ellipses → limit analysis ([`crate::limit::model_from_packing`], Clarabel) | equilibrium of the dual, primal = dual |

pub mod packing_lp;
