//! `proptest` strategies for a law's inputs and histories (the `proptest`
//! feature), so that a law of one's own runs the checks of
//! [`super`](crate::law::conformance) over random loading paths without
//! knowing how to build its history state by hand.
//!
//! A history is what a law makes of a loading path: [`loading_path`]
//! draws a start overlap and a sequence of relative-displacement
//! increments whose normal components move the overlap (`overlap_k =
//! overlap_{k−1} + Δu_n,k`, so a law that follows its own displacement
//! history, such as HPM's slip spring, sees a consistent one), and
//! [`history_then_input`] runs all but the last input through the law
//! from its default state and yields the state reached with the last
//! input:
//!
//! ```
//! use dismech::law::conformance::{self, strategies::{history_then_input, Scales}};
//! use dismech::law::{FrictionIntegration, PairProperties, PenaltyCoulomb};
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//! let law = PenaltyCoulomb::new(1e8, 0.5, FrictionIntegration::ReturnMapping).unwrap();
//! let scales = Scales::new(1e-4, 1e-4, PairProperties::rigid());
//! TestRunner::default()
//!     .run(&history_then_input::<_, 2>(law, scales, 1..8), |(state, input)| {
//!         let violations = conformance::check_all(&law, &input, &state);
//!         prop_assert!(violations.is_empty(), "{:?}", violations);
//!         Ok(())
//!     })
//!     .unwrap();
//! ```

use std::ops::Range;

use nalgebra::SVector;
use proptest::prelude::*;

use crate::law::{ContactInput, ContactLaw, PairProperties};

/// The sizes of the random inputs: overlaps are drawn in
/// `[−overlap/2, overlap]`, each component of an increment in
/// `[−increment, increment]` (the normal one scaled by `normal_ratio`),
/// and the relative rotation in `[−rotation, rotation]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// Largest overlap at the start of a path (m).
    pub overlap: f64,
    /// Largest component of a relative-displacement increment (m).
    pub increment: f64,
    /// The normal increment's share of `increment` (1 by default; smaller
    /// keeps a path's overlap near its start while it slides).
    pub normal_ratio: f64,
    /// Time step (s) of every input.
    pub dt: f64,
    /// The pair's geometry and masses, the same for every input.
    pub pair: PairProperties,
    /// Largest relative rotation of a step (rad;
    /// [`ContactInput::rotation`]), 0 by default: for a law with rolling
    /// resistance. (At 0 no rotation is drawn, and the paths are those
    /// drawn before the field existed.)
    pub rotation: f64,
}

impl Scales {
    /// Scales with `normal_ratio = 1`, `dt = 1e-4` s and no rotation.
    pub fn new(overlap: f64, increment: f64, pair: PairProperties) -> Self {
        Self {
            overlap,
            increment,
            normal_ratio: 1.0,
            dt: 1e-4,
            pair,
            rotation: 0.0,
        }
    }
}

/// A loading path of `steps` inputs (a range of lengths, at least one): a
/// start overlap, then increments whose normal components move the
/// overlap. The first input is new (`is_new`), the others are not.
pub fn loading_path<const D: usize>(
    scales: Scales,
    steps: Range<usize>,
) -> impl Strategy<Value = Vec<ContactInput<D>>> {
    let steps = steps.start.max(1)..steps.end.max(steps.start.max(1) + 1);
    // A rotation, when drawn, is one more component of each step's draw.
    let width = if scales.rotation > 0.0 { D + 1 } else { D };
    let unit = prop::collection::vec(-1.0f64..1.0, width);
    (-0.5f64..1.0, prop::collection::vec(unit, steps)).prop_map(move |(start, increments)| {
        let mut overlap = start * scales.overlap;
        increments
            .into_iter()
            .enumerate()
            .map(|(k, unit)| {
                let rotation = unit.get(D).map_or(0.0, |u| u * scales.rotation);
                let mut increment = SVector::<f64, D>::from_iterator(
                    unit.into_iter().take(D).map(|u| u * scales.increment),
                );
                increment[0] *= scales.normal_ratio;
                if k > 0 {
                    overlap += increment[0];
                }
                ContactInput {
                    overlap,
                    increment,
                    dt: scales.dt,
                    is_new: k == 0,
                    pair: scales.pair,
                    rotation,
                }
            })
            .collect()
    })
}

/// The state `law` reaches over a random [`loading_path`] (all its inputs
/// but the last, from the default state, each step's state kept), with the
/// path's last input: a case for any check of
/// [`super`](crate::law::conformance).
pub fn history_then_input<L, const D: usize>(
    law: L,
    scales: Scales,
    steps: Range<usize>,
) -> impl Strategy<Value = (L::State, ContactInput<D>)>
where
    L: ContactLaw<D> + std::fmt::Debug + 'static,
{
    loading_path::<D>(scales, steps).prop_map(move |mut path| {
        let last = path.pop().expect("a loading path has at least one input");
        let state = path.iter().fold(L::State::default(), |state, input| {
            law.evaluate(input, &state).state
        });
        (state, last)
    })
}
