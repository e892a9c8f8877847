//! The skin of the neighbour list: fixed, or tuned at each build to how
//! often the list has been built.
//!
//! A wider skin builds the list less often and lists more pairs that do
//! not touch. Where the particles move fast (a collapsing column, a flow)
//! the builds dominate; where they hardly move, the listed pairs do. The
//! tuned skin aims at one build every [`TARGET_STEPS_BETWEEN_BUILDS`]
//! steps: at each build after the first it is multiplied by
//! `√(target / k)`, `k` the steps since the last build, and kept between
//! the least skin and [`CEILING_OVER_LEAST`] times it. A particle reaches
//! half the skin in a time proportional to the skin, so `target / k`
//! would aim at the target in one build; the square root takes half of
//! that step in the logarithm, so the skin settles towards the target
//! without overshooting it when the particles keep their pace (a single
//! build one step after the last still multiplies it by √20, to the
//! ceiling). Only the work changes (how often the list is built, how many
//! pairs it holds), never the results: the list holds every pair that
//! can touch at any skin.

/// The steps between builds the tuned skin aims at. A build of the list
/// costs about 1.2 steps (99 856 disks), so one in 20 steps is about 6 %
/// of the time, about where the pairs a wider skin adds cost as much as
/// the builds it saves (a fixed skin twice the least made 1 024 settled
/// disks about 5 % slower). The value was chosen on the anchor's square
/// column of 99 856 disks, still collapsing after 20 000 steps, not swept:
/// the README's throughput section gives the measurements.
pub(super) const TARGET_STEPS_BETWEEN_BUILDS: f64 = 20.0;

/// The widest tuned skin, over the least. With the least skin 0.15 of the
/// smallest radius, two such disks are listed at four times it out to 2.6
/// radii between centres against 2.15: 1.46 times the area in which a
/// neighbour's centre is listed.
pub(super) const CEILING_OVER_LEAST: f64 = 4.0;

/// The skin of each build and the steps since the last one (a checkpoint
/// keeps it whole: the next skin is tuned from it).
#[derive(Debug, Clone, Copy, serde::Serialize, serde::Deserialize)]
pub(super) struct Skin {
    /// The skin of the last build (the least before the first).
    current: f64,
    least: f64,
    most: f64,
    /// Steps since the last build.
    steps: u64,
    /// Whether the list has been built.
    built: bool,
}

impl Skin {
    /// A skin that does not change.
    pub fn fixed(skin: f64) -> Self {
        Self::between(skin, skin)
    }

    /// A skin tuned from `least` (finite, not negative) up to
    /// [`CEILING_OVER_LEAST`] times it.
    pub fn tuned(least: f64) -> Self {
        debug_assert!(least.is_finite() && least >= 0.0, "least skin {least}");
        Self::between(least, (CEILING_OVER_LEAST * least).min(f64::MAX))
    }

    fn between(least: f64, most: f64) -> Self {
        Self {
            current: least,
            least,
            most,
            steps: 0,
            built: false,
        }
    }

    /// Whether the skins are finite, not negative and in order (a skin
    /// read from a checkpoint is checked so).
    pub fn is_valid(&self) -> bool {
        let ordered = 0.0 <= self.least && self.least <= self.current && self.current <= self.most;
        ordered && self.most.is_finite()
    }

    /// The skin of the last build.
    pub fn current(&self) -> f64 {
        self.current
    }

    /// A step was taken.
    pub fn stepped(&mut self) {
        self.steps += 1;
    }

    /// The skin of a build now, from the steps since the last one.
    pub fn at_build(&mut self) -> f64 {
        if self.built {
            let ratio = TARGET_STEPS_BETWEEN_BUILDS / self.steps.max(1) as f64;
            self.current = (self.current * ratio.sqrt()).clamp(self.least, self.most);
        }
        self.built = true;
        self.steps = 0;
        self.current
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Builds `intervals` steps apart: the skins of the builds.
    fn skins(mut skin: Skin, intervals: &[u64]) -> Vec<f64> {
        let mut out = vec![skin.at_build()];
        for &k in intervals {
            for _ in 0..k {
                skin.stepped();
            }
            out.push(skin.at_build());
        }
        out
    }

    #[test]
    fn a_fixed_skin_stays() {
        assert_eq!(skins(Skin::fixed(0.01), &[1, 5, 400]), vec![0.01; 4]);
        assert_eq!(skins(Skin::fixed(0.0), &[1, 1]), vec![0.0; 3]);
    }

    #[test]
    fn builds_every_five_steps_double_the_skin_then_reach_the_ceiling() {
        // √(20 / 5) = 2 a build, up to 4 times the least.
        let s = skins(Skin::tuned(0.01), &[5, 5, 5]);
        assert_eq!(s, vec![0.01, 0.02, 0.04, 0.04]);
    }

    #[test]
    fn builds_at_the_target_keep_the_skin_and_rare_builds_bring_it_down() {
        let s = skins(Skin::tuned(0.01), &[5, 20, 20, 80, 80, 500]);
        assert_eq!(s, vec![0.01, 0.02, 0.02, 0.02, 0.01, 0.01, 0.01]);
    }

    #[test]
    fn a_build_with_no_step_between_is_taken_as_one_step_apart() {
        // √20 ≈ 4.47 from the least: capped at 4.
        assert_eq!(skins(Skin::tuned(1.0), &[0, 1]), vec![1.0, 4.0, 4.0]);
        // A skin of 0 stays 0 (without the step, 0 · ∞ would be NaN).
        assert_eq!(skins(Skin::tuned(0.0), &[0]), vec![0.0, 0.0]);
    }

    #[test]
    fn without_particles_the_huge_least_skin_stays_finite() {
        let s = skins(Skin::tuned(f64::MAX), &[1, 1]);
        assert!(s.iter().all(|v| *v == f64::MAX), "{s:?}");
    }
}
