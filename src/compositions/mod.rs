//! Models composed from the library's pieces that are not a paper's method:
//! each is a small driver set-up with the measurement it exists for, and a
//! check against an exact solution.
//!
//! | composition | pieces | exact solution |
//! |---|---|---|
//! | [`polygon_incline`]: a rigid rectangle on an incline | [`crate::shape::Polygon`], [`crate::contact::dispatch::contact_manifold_2d`] (polygon–wall, two points), [`crate::contact::SpringDashpotCoulomb`] with a constant `k_n`, [`crate::dem::DemSimulation`] | sliding at `g (sin β − μ cos β)`, or at rest for `tan β ≤ μ` |

pub mod polygon_incline;
