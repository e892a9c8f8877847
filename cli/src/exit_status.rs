//! The exit status of the `dismech` command: one code per kind of outcome,
//! so that a script can tell a failed check from a locked model, a solver
//! that gave up, bad input or an output that could not be written.

use std::process::ExitCode;

use dismech::error::{DismechError, SolveError};
use dismech::hpm::HpmError;
use dismech::limit::LimitStatus;
use dismech::slope::SlopeError;

/// What the command's exit code says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Exit {
    /// Every check passed; the limit load was found.
    Success,
    /// A study ran and wrote its results, but a check failed.
    CheckFailed,
    /// Bad command line or bad input: a value out of range, a malformed
    /// file, an unknown study (the code clap uses for usage errors).
    BadInput,
    /// The model cannot collapse: no finite load moves it (`Locked`).
    Locked,
    /// The model collapses under its own loads, before any plate load
    /// (`Unbounded`), or at zero load (`ZeroLoad`): no positive limit load.
    Unbounded,
    /// A solver or a simulation could not go on: an LP without a certified
    /// optimum, a failed factorization, a DDA step that failed at the
    /// smallest step, a blow-up.
    SolverFailure,
    /// An output could not be written.
    OutputFailed,
}

impl Exit {
    /// Every status, in the order of their codes.
    pub const ALL: [Exit; 7] = [
        Exit::Success,
        Exit::CheckFailed,
        Exit::BadInput,
        Exit::Locked,
        Exit::Unbounded,
        Exit::SolverFailure,
        Exit::OutputFailed,
    ];

    /// The process exit code.
    pub fn code(self) -> u8 {
        match self {
            Exit::Success => 0,
            Exit::CheckFailed => 1,
            Exit::BadInput => 2,
            Exit::Locked => 3,
            Exit::Unbounded => 4,
            Exit::SolverFailure => 5,
            Exit::OutputFailed => 6,
        }
    }

    /// What the code means, in a few words.
    pub fn meaning(self) -> &'static str {
        match self {
            Exit::Success => "success: every check passed / the limit load was found",
            Exit::CheckFailed => "a study ran and wrote its results, but a check failed",
            Exit::BadInput => "bad command line or input (value out of range, unknown study)",
            Exit::Locked => "the lattice is locked: no finite load makes it collapse",
            Exit::Unbounded => "the model collapses under its own loads or at zero load (no positive limit load)",
            Exit::SolverFailure => "a solver or simulation could not go on (no certified optimum, failed step, blow-up)",
            Exit::OutputFailed => "an output could not be written",
        }
    }

    /// The table of codes printed after `--help`.
    pub fn help() -> String {
        let mut text = String::from("Exit status:\n");
        for exit in Exit::ALL {
            text.push_str(&format!("  {}  {}\n", exit.code(), exit.meaning()));
        }
        text.push_str(
            "\n`reproduce all` exits with the code of the first study that could not run; else 1 if a \
             check failed; else 0.",
        );
        text
    }

    /// The status of a limit analysis.
    pub fn of_limit(status: &LimitStatus) -> Self {
        match status {
            LimitStatus::Collapse => Exit::Success,
            LimitStatus::Locked => Exit::Locked,
            // No positive limit load: the driver meets nothing to overcome.
            LimitStatus::Unbounded | LimitStatus::ZeroLoad => Exit::Unbounded,
            LimitStatus::SolverTrouble(_) => Exit::SolverFailure,
        }
    }

    /// The status of a run stopped by `error`.
    pub fn of_error(error: &DismechError) -> Self {
        use DismechError as E;
        use HpmError as H;
        use SlopeError as S;
        match error {
            E::Output { .. } => Exit::OutputFailed,
            E::Solve(SolveError::InvalidSetting { .. }) => Exit::BadInput,
            E::Solve(_)
            | E::NonFinite { .. }
            | E::ParticleLeftFrame { .. }
            | E::EnergyBlowUp { .. }
            | E::StepFailed { .. }
            | E::Hpm(H::IllConditioned { .. })
            | E::NoLimitLoad { .. }
            | E::UncertifiedOptimum { .. } => Exit::SolverFailure,
            // Strength reduction: no factor fails the slope (it cannot
            // collapse), or none holds it (it collapses under its weight).
            E::Hpm(H::StrengthReductionNoFailure { .. }) => Exit::Locked,
            // Nothing drives the slide: its safety factor is undefined
            // (infinite on level ground), as a slope that cannot fail.
            E::Hpm(H::NothingDrivesSliding { .. }) => Exit::Locked,
            E::Hpm(H::StrengthReductionNoEquilibrium { .. }) => Exit::Unbounded,
            // The slip surface is lifted off beyond its tensile strength:
            // the slide fails under its loads, with no factor of safety.
            E::Hpm(H::SlipSurfaceInTension { .. }) => Exit::Unbounded,
            E::InvalidParameter { .. }
            | E::UnstableTimeStep { .. }
            | E::StartsInsideWall { .. }
            | E::InitialOverlap { .. }
            | E::FrameNotClosed { .. }
            | E::DegenerateWall { .. }
            | E::ContactNotTouching { .. }
            | E::PlateTouchesNothing { .. }
            | E::DrivingSupportCount(_)
            | E::NoDeadLoads
            | E::Grid(_)
            | E::Hpm(
                H::NoValidColumn { .. }
                | H::EmptyHpmModel { .. }
                | H::HpmModelTooLarge { .. }
                | H::GridTooSmall { .. }
                | H::MapData { .. },
            )
            | E::Slope(
                S::NoGroundData { .. }
                | S::DemTooSmall { .. }
                | S::InvalidRange { .. }
                | S::InvalidLayer { .. }
                | S::PoreRatioOutOfRange { .. }
                | S::PorePressureTwice { .. }
                | S::MAlphaFloorOutOfRange { .. }
                | S::HpmGround { .. },
            )
            | E::InvalidPolygon { .. }
            | E::LawUndefinedForShape { .. }
            | E::InvalidBlock { .. }
            | E::InvalidEdgeTraction { .. }
            | E::InvalidParticle { .. }
            | E::OutOfMemory { .. }
            | E::TimeStepTooSmall { .. }
            | E::BlocksOverlap { .. }
            | E::BlocksCross { .. }
            | E::DuplicateBody { .. }
            | E::DuplicateContact { .. }
            | E::LatticeTooLarge { .. }
            | E::PenaltyModel(_)
            | E::UnsupportedPair(..)
            | E::NoSuchBody { .. }
            | E::SelfContact { .. }
            | E::UnknownStudy(..)
            | E::VtkData { .. }
            | E::Checkpoint { .. } => Exit::BadInput,
        }
    }
}

impl From<Exit> for ExitCode {
    fn from(exit: Exit) -> Self {
        ExitCode::from(exit.code())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use dismech::lp::LpStatus;

    #[test]
    fn codes_are_distinct_and_listed_in_the_help() {
        let help = Exit::help();
        for (i, exit) in Exit::ALL.iter().enumerate() {
            assert_eq!(exit.code() as usize, i);
            assert!(help.contains(&format!("  {}  {}", exit.code(), exit.meaning())));
        }
    }

    #[test]
    fn a_solver_in_trouble_exits_with_the_solver_code() {
        let status = LimitStatus::SolverTrouble(LpStatus::MaxIterations);
        assert_eq!(Exit::of_limit(&status), Exit::SolverFailure);
        assert_eq!(Exit::of_limit(&LimitStatus::Locked), Exit::Locked);
        assert_eq!(Exit::of_limit(&LimitStatus::Collapse), Exit::Success);
    }

    /// Hovland's factor towards 270°, driven by `Σ T`.
    fn hovland_term() -> dismech::hpm::SafetyFactorTerm {
        dismech::hpm::SafetyFactorTerm {
            factor: dismech::hpm::SafetyFactorKind::Hovland { towards_deg: 270.0 },
            force: dismech::hpm::DrivingForce::ColumnDriving,
        }
    }

    #[test]
    fn a_slide_nothing_drives_exits_as_locked_and_a_model_too_large_as_bad_input() {
        let nothing = DismechError::Hpm(HpmError::NothingDrivesSliding {
            what: hovland_term(),
            driving: 0.0,
            weight: 1.0,
            ratio: 1e-6,
        });
        assert_eq!(Exit::of_error(&nothing), Exit::Locked);
        let large = DismechError::Hpm(HpmError::HpmModelTooLarge {
            columns: 1,
            layers: usize::MAX,
            elements: u128::from(u64::MAX),
            what: dismech::hpm::MemoryParts::Model,
            bytes: u128::MAX,
            budget: Some(1),
        });
        assert_eq!(Exit::of_error(&large), Exit::BadInput);
        let small = DismechError::Hpm(HpmError::GridTooSmall {
            file: "g.asc".into(),
            rows: 1,
            columns: 2,
        });
        assert_eq!(Exit::of_error(&small), Exit::BadInput);
    }

    #[test]
    fn a_slip_surface_in_tension_exits_as_unbounded() {
        let lifted = DismechError::Hpm(HpmError::SlipSurfaceInTension {
            what: hovland_term(),
            strength: -1.0,
            driving: 1.0,
            cells: vec![(0, 0)],
            columns: 1,
            area_share: 1.0,
        });
        assert_eq!(Exit::of_error(&lifted), Exit::Unbounded);
        let text = lifted.to_string();
        assert!(
            text.contains(
                "over 100.0 % of its area, under 1 of 1 columns (grid cells (row, column) (0, 0))"
            ),
            "{text}"
        );
    }

    #[test]
    fn a_zero_limit_load_exits_as_no_positive_limit_load() {
        assert_eq!(Exit::of_limit(&LimitStatus::ZeroLoad), Exit::Unbounded);
        assert_ne!(Exit::of_limit(&LimitStatus::ZeroLoad), Exit::Success);
    }
}
