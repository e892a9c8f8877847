//! The neighbour list's names for a pair and for a contact point, packed
//! small: every listed pair is read and written at every step, so the
//! fewer bytes a slot has, the less memory a step streams through (a
//! large scene's list does not fit in the caches).
//!
//! A pair is its particle A and its target B (a particle or a wall) in 8
//! bytes rather than 24; a contact point's features and its law's regime
//! are 8 bytes rather than 33. Both are exact: [`pack_limits`] refuses a
//! scene whose indices would not fit, before a run starts.

use super::driver::ContactTarget;
use crate::error::{DismechError, Result};
use crate::law::Regime;
use crate::query::{ContactFeatures, Feature};
use crate::scene::Scene;
use crate::shape::AnyShape2;

/// Particles and walls are numbered below this (31 bits; the 32nd tells
/// a wall from a particle).
const MOST_BODIES: usize = 1 << 31;

/// A polygon's vertices are numbered below this (29 bits of a feature's
/// 31; two tell a vertex from an edge and from the whole boundary).
const MOST_VERTICES: usize = 1 << 29;

/// Refuse a scene whose particles, walls or polygon vertices are too many
/// to be named by the packed keys.
///
/// # Errors
/// [`DismechError::InvalidParameter`] naming the count.
pub(super) fn pack_limits(scene: &Scene) -> Result<()> {
    let most_vertices = scene
        .particles
        .iter()
        .filter_map(|p| match &p.shape {
            AnyShape2::Polygon(polygon) => Some(polygon.vertices().len()),
            _ => None,
        })
        .max()
        .unwrap_or(0);
    check_counts(
        scene.particles.len(),
        scene.frame.walls().len(),
        most_vertices,
    )
}

/// [`pack_limits`] for `particles` particles, `walls` walls and at most
/// `most_vertices` vertices a polygon.
fn check_counts(particles: usize, walls: usize, most_vertices: usize) -> Result<()> {
    let within = |name, count: usize, most: usize, requirement| {
        if count < most {
            Ok(())
        } else {
            Err(DismechError::InvalidParameter {
                name,
                value: count as f64,
                requirement,
            })
        }
    };
    within(
        "number of particles",
        particles,
        MOST_BODIES,
        "must be below 2³¹ for the explicit driver",
    )?;
    within(
        "number of walls",
        walls,
        MOST_BODIES,
        "must be below 2³¹ for the explicit driver",
    )?;
    within(
        "number of a polygon's vertices",
        most_vertices,
        MOST_VERTICES,
        "must be below 2²⁹ for the explicit driver",
    )
}

/// A listed pair: particle A and its target B, each in 32 bits (the top
/// bit of B's says a wall). A checkpoint keeps the two words; the list
/// checks them against the scene when it is restored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub(super) struct PairKey {
    a: u32,
    target: u32,
}

const WALL_BIT: u32 = 1 << 31;

impl PairKey {
    /// The key of A `a` and B `target` (indices checked by
    /// [`pack_limits`]).
    #[inline]
    pub fn new(a: usize, target: ContactTarget) -> Self {
        debug_assert!(a < MOST_BODIES, "particle {a} beyond the packed keys");
        let target = match target {
            ContactTarget::Particle(b) => {
                debug_assert!(b < MOST_BODIES, "particle {b} beyond the packed keys");
                b as u32
            }
            ContactTarget::Wall(w) => {
                debug_assert!(w < MOST_BODIES, "wall {w} beyond the packed keys");
                w as u32 | WALL_BIT
            }
        };
        Self {
            a: a as u32,
            target,
        }
    }

    /// The particle A.
    #[inline]
    pub fn a(self) -> usize {
        self.a as usize
    }

    /// What A may touch.
    #[inline]
    pub fn target(self) -> ContactTarget {
        if self.target & WALL_BIT == 0 {
            ContactTarget::Particle(self.target as usize)
        } else {
            ContactTarget::Wall((self.target & !WALL_BIT) as usize)
        }
    }
}

/// A contact point's features and the regime of its law: A's feature in
/// bits 0–30, B's in bits 31–61, the regime in bits 62–63. A feature is
/// its kind (2 bits) above its index (29 bits). Serialized as the word; one
/// read back with a kind or a regime that none packs to is refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "u64", into = "u64")]
pub(super) struct PointKey(u64);

impl From<PointKey> for u64 {
    fn from(key: PointKey) -> u64 {
        key.0
    }
}

impl TryFrom<u64> for PointKey {
    type Error = &'static str;
    fn try_from(bits: u64) -> std::result::Result<Self, Self::Error> {
        let mask = (1 << FEATURE_BITS) - 1;
        let kinds = [bits & mask, bits >> FEATURE_BITS & mask].map(|f| f >> INDEX_BITS);
        if bits >> (2 * FEATURE_BITS) > 2 || kinds.iter().any(|&k| k > 2) {
            return Err("a contact point's key names no feature or regime");
        }
        Ok(Self(bits))
    }
}

const FEATURE_BITS: u32 = 31;
const INDEX_BITS: u32 = 29;
const FEATURES_MASK: u64 = (1 << (2 * FEATURE_BITS)) - 1;

fn pack_feature(feature: Feature) -> u64 {
    let (kind, index) = match feature {
        Feature::Whole => (0, 0),
        Feature::Vertex(k) => (1, k),
        Feature::Edge(k) => (2, k),
    };
    debug_assert!(
        index < MOST_VERTICES,
        "feature {index} beyond the packed keys"
    );
    (kind << INDEX_BITS) | index as u64
}

fn unpack_feature(bits: u64) -> Feature {
    let index = (bits & ((1 << INDEX_BITS) - 1)) as usize;
    match bits >> INDEX_BITS {
        0 => Feature::Whole,
        1 => Feature::Vertex(index),
        2 => Feature::Edge(index),
        kind => unreachable!("no feature is packed as kind {kind}"),
    }
}

fn pack_features(features: &ContactFeatures) -> u64 {
    pack_feature(features.a) | pack_feature(features.b) << FEATURE_BITS
}

impl PointKey {
    /// The key of a point of `features` in `regime`.
    #[inline]
    pub fn new(features: &ContactFeatures, regime: Regime) -> Self {
        let regime = match regime {
            Regime::Open => 0,
            Regime::Stick => 1,
            Regime::Slip => 2,
        };
        Self(pack_features(features) | regime << (2 * FEATURE_BITS))
    }

    /// Whether the point is named by `features`.
    #[inline]
    pub fn has_features(self, features: &ContactFeatures) -> bool {
        self.0 & FEATURES_MASK == pack_features(features)
    }

    /// The point's features.
    pub fn features(self) -> ContactFeatures {
        let mask = (1 << FEATURE_BITS) - 1;
        ContactFeatures {
            a: unpack_feature(self.0 & mask),
            b: unpack_feature(self.0 >> FEATURE_BITS & mask),
        }
    }

    /// The law's regime at the point.
    pub fn regime(self) -> Regime {
        match self.0 >> (2 * FEATURE_BITS) {
            0 => Regime::Open,
            1 => Regime::Stick,
            2 => Regime::Slip,
            regime => unreachable!("no regime is packed as {regime}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn feature() -> impl Strategy<Value = Feature> {
        prop_oneof![
            Just(Feature::Whole),
            (0..MOST_VERTICES).prop_map(Feature::Vertex),
            (0..MOST_VERTICES).prop_map(Feature::Edge),
        ]
    }

    fn regime() -> impl Strategy<Value = Regime> {
        prop_oneof![Just(Regime::Open), Just(Regime::Stick), Just(Regime::Slip)]
    }

    fn target() -> impl Strategy<Value = ContactTarget> {
        prop_oneof![
            (0..MOST_BODIES).prop_map(ContactTarget::Particle),
            (0..MOST_BODIES).prop_map(ContactTarget::Wall),
        ]
    }

    proptest! {
        /// A pair's key gives back its A and B, up to the largest indices.
        #[test]
        fn a_pair_key_gives_back_its_pair(a in 0..MOST_BODIES, target in target()) {
            let key = PairKey::new(a, target);
            prop_assert_eq!(key.a(), a);
            prop_assert_eq!(key.target(), target);
        }

        /// A point's key gives back its features and regime, and names
        /// those features and no others.
        #[test]
        fn a_point_key_gives_back_its_features_and_regime(
            a in feature(), b in feature(), other in feature(), regime in regime()
        ) {
            let features = ContactFeatures { a, b };
            let key = PointKey::new(&features, regime);
            prop_assert_eq!(key.features(), features);
            prop_assert_eq!(key.regime(), regime);
            prop_assert!(key.has_features(&features));
            prop_assert_eq!(key.has_features(&ContactFeatures { a: other, b }), other == a);
            prop_assert_eq!(key.has_features(&ContactFeatures { a, b: other }), other == b);
        }
    }

    /// Counts up to the largest that packs pass; one more is refused,
    /// naming what is too many.
    #[test]
    fn counts_beyond_the_packing_are_refused() {
        let most = (MOST_BODIES - 1, MOST_BODIES - 1, MOST_VERTICES - 1);
        assert!(check_counts(most.0, most.1, most.2).is_ok());
        for (counts, name) in [
            ((MOST_BODIES, 0, 3), "number of particles"),
            ((10, MOST_BODIES, 3), "number of walls"),
            ((10, 4, MOST_VERTICES), "number of a polygon's vertices"),
        ] {
            match check_counts(counts.0, counts.1, counts.2) {
                Err(DismechError::InvalidParameter { name: refused, .. }) => {
                    assert_eq!(refused, name)
                }
                other => panic!("{counts:?}: {other:?}"),
            }
        }
    }

    /// Keys read back from their words: every key packed passes, a word
    /// with a feature kind or a regime of 3 is refused.
    #[test]
    fn a_point_key_read_back_is_checked() {
        let features = ContactFeatures {
            a: Feature::Edge(MOST_VERTICES - 1),
            b: Feature::Vertex(7),
        };
        let key = PointKey::new(&features, Regime::Slip);
        assert_eq!(PointKey::try_from(u64::from(key)), Ok(key));
        for bad in [
            3 << (2 * FEATURE_BITS),
            3 << INDEX_BITS,
            3 << (FEATURE_BITS + INDEX_BITS),
        ] {
            assert!(PointKey::try_from(bad).is_err(), "{bad:#x}");
        }
    }

    /// The largest indices fit.
    #[test]
    fn the_largest_indices_fit() {
        let key = PairKey::new(MOST_BODIES - 1, ContactTarget::Wall(MOST_BODIES - 1));
        assert_eq!(key.a(), MOST_BODIES - 1);
        assert_eq!(key.target(), ContactTarget::Wall(MOST_BODIES - 1));
        let last = Feature::Edge(MOST_VERTICES - 1);
        let features = ContactFeatures { a: last, b: last };
        assert_eq!(PointKey::new(&features, Regime::Slip).features(), features);
    }
}
