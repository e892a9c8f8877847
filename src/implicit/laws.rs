//! Which contact law each pair of bodies follows: one law for every
//! contact, or a law per pair of body groups (e.g. a soil–soil strength and
//! a stronger soil–wall one).

/// The contact law of each pair of body groups ([`super::Body::group`]): a
/// default law, and laws for given pairs of groups (in either order).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ContactLaws<L> {
    default: L,
    pairs: Vec<((usize, usize), L)>,
}

impl<L> ContactLaws<L> {
    /// Every contact follows `law`.
    pub fn uniform(law: L) -> Self {
        Self {
            default: law,
            pairs: Vec::new(),
        }
    }

    /// Contacts between groups `a` and `b` (either way round) follow `law`.
    pub fn with_pair(mut self, a: usize, b: usize, law: L) -> Self {
        let key = (a.min(b), a.max(b));
        self.pairs.retain(|(k, _)| *k != key);
        self.pairs.push((key, law));
        self
    }

    /// The law of a contact between groups `a` and `b`.
    pub fn law(&self, a: usize, b: usize) -> &L {
        let key = (a.min(b), a.max(b));
        self.pairs
            .iter()
            .find(|(k, _)| *k == key)
            .map_or(&self.default, |(_, law)| law)
    }

    /// The law of contacts between groups no pair names.
    pub fn default_law(&self) -> &L {
        &self.default
    }
}

impl<L> From<L> for ContactLaws<L> {
    fn from(law: L) -> Self {
        Self::uniform(law)
    }
}
