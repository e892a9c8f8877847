//! Exact reference solutions: problems whose answer is known in closed form
//! or by an independent computation, against which the methods are checked
//! (tests, examples, the reproductions of the papers).
//!
//! | reference | answer | checks |
//! |---|---|---|
//! | [`incline`] | a rigid block sliding down a frictional slope, `g (sin β − μ cos β)`, or at rest; a disc rolling, `(2/3) g sin β` | the polygon DEM and the affine DDA disc (the `polygon_incline` and `affine_disc` cross-compositions) |
//! | [`block_on_floor`] | horizontal load that rocks or slides a rigid block on a frictional floor, `W min(μ, w/2h)` | the LP limit analysis of a polygon (the `polygon_lp` cross-composition) |
//! | [`sliding_block`] | rigid block on a shaken base, Coulomb friction (Newmark 1965), and the same block on an elastic–plastic shear spring | DDA (paper 003) |
//! | [`planar_slab`] | Fs of a slab on a planar slip surface by global equilibrium, `(cA + W(cos β − k_h sin β) tan φ) / (W(sin β + k_h cos β))` | HPM and Hovland (paper 001) |
//! | [`two_elements`](mod@two_elements) | limit load `(1 + √2) C` of paper 002's two-element example | the LP limit analysis |
//! | [`lattice_limit_load`] | paper 002's eqs. (20), (32), (38) for its lattices | the LP limit analysis |
//! | [`ellipse_contact`] | ellipse–ellipse contact points by dense boundary sampling and bisection | the ellipse contact routine (paper 000) |

pub mod block_on_floor;
pub mod ellipse_contact;
pub mod incline;
pub mod lattice_limit_load;
pub mod planar_slab;
pub mod sliding_block;
pub mod two_elements;

pub use block_on_floor::{BlockMechanism, BlockOnFloor};
pub use planar_slab::PlanarSlab;
pub use sliding_block::{compliant_sliding_block, rigid_sliding_block, Shaking};
pub use two_elements::{two_elements, two_elements_limit_load};
