//! The skin of the neighbour list: fixed, or tuned at each build to how
//! often the list has been built.
//!
//! A wider skin builds the list less often and lists more pairs that do
//! not touch. Where the particles move fast (a collapsing column, a flow)
//! the builds dominate; where they hardly move, the listed pairs do. The
//! tuned skin aims at one build every [`TARGET_STEPS_BETWEEN_BUILDS`]
//! steps: at each build after the first it is multiplied by
//! `√(target / k)`, `k` the steps since the last build, and kept between
//! the least skin and [`CEILING`] times it. A particle reaches half the
//! skin in a time proportional to the skin, so `target / k` would aim at
//! the target in one build; the square root takes half of that step (in
//! the logarithm), so that one short or long interval does not swing the
//! skin. Only how often the list is built changes, never the forces: the
//! list holds every pair that can touch at any skin.

/// The steps between builds the tuned skin aims at. A build of the list
/// costs about 1.2 steps (99 856 disks), so one in 20 steps is about 6 %
/// of the time, about where the pairs a wider skin adds cost as much as
/// the builds it saves (a fixed skin twice the least, 0.018 m against
/// 0.009 m, made 1 024 settled disks 5 % slower, medians of three). The
/// anchor's square column of 99 856 disks (renumbered), still collapsing
/// after 20 000 steps, built its list 651 times in the next 6 000 steps
/// with the least skin and 295 times tuned, and ran 12 % faster (medians
/// of two runs); over 10 000 steps, 808 times against 452 and 3 % faster,
/// the last 4 000 steps building as often either way (every 25 steps: the
/// tuned skin is back to the least). Settled packings, built every few
/// hundred steps, keep the least skin and their speed.
pub(super) const TARGET_STEPS_BETWEEN_BUILDS: f64 = 20.0;

/// How far above the least skin the tuned skin may go.
pub(super) const CEILING: f64 = 4.0;

/// The skin of each build and the steps since the last one.
#[derive(Debug, Clone, Copy)]
pub(super) struct Skin {
    /// The skin of the last build (the least before the first).
    skin: f64,
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

    /// A skin tuned from `least` up to [`CEILING`] times it.
    pub fn tuned(least: f64) -> Self {
        Self::between(least, (CEILING * least).min(f64::MAX))
    }

    fn between(least: f64, most: f64) -> Self {
        Self {
            skin: least,
            least,
            most,
            steps: 0,
            built: false,
        }
    }

    /// The skin of the last build.
    pub fn current(&self) -> f64 {
        self.skin
    }

    /// A step was taken.
    pub fn stepped(&mut self) {
        self.steps += 1;
    }

    /// The skin of a build now, from the steps since the last one.
    pub fn at_build(&mut self) -> f64 {
        if self.built {
            let ratio = TARGET_STEPS_BETWEEN_BUILDS / self.steps.max(1) as f64;
            self.skin = (self.skin * ratio.sqrt()).clamp(self.least, self.most);
        }
        self.built = true;
        self.steps = 0;
        self.skin
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
    fn a_build_at_the_next_step_counts_as_one_step() {
        // √20 ≈ 4.47 from the least: capped at 4.
        assert_eq!(skins(Skin::tuned(1.0), &[0, 1]), vec![1.0, 4.0, 4.0]);
    }

    #[test]
    fn without_particles_the_huge_least_skin_stays_finite() {
        let s = skins(Skin::tuned(f64::MAX), &[1, 1]);
        assert!(s.iter().all(|v| *v == f64::MAX), "{s:?}");
    }
}
