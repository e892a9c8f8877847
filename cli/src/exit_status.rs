//! The exit status of the `dismech` command: one code per kind of outcome,
//! so that a script can tell a failed check from a locked model, a solver
//! that gave up, bad input or an output that could not be written.

use std::process::ExitCode;

use dismech::error::{DismechError, SolveError};
use dismech::explicit::ExplicitError;
use dismech::hpm::HpmError;
use dismech::implicit::ImplicitError;
use dismech::limit::{LimitError, LimitStatus};
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
        use ExplicitError as X;
        use HpmError as H;
        use ImplicitError as I;
        use LimitError as L;
        use SlopeError as S;
        match error {
            E::Output { .. } => Exit::OutputFailed,
            E::Solve(SolveError::InvalidSetting { .. }) => Exit::BadInput,
            E::Solve(_)
            | E::Explicit(
                X::NonFinite { .. } | X::ParticleLeftFrame { .. } | X::EnergyBlowUp { .. },
            )
            | E::Implicit(I::StepFailed { .. })
            | E::Hpm(H::IllConditioned { .. })
            | E::Limit(L::NoLimitLoad { .. } | L::UncertifiedOptimum { .. }) => Exit::SolverFailure,
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
            | E::Explicit(
                X::UnstableTimeStep { .. }
                | X::StartsInsideWall { .. }
                | X::InitialOverlap { .. }
                | X::LawUndefinedForShape { .. }
                | X::InvalidParticle { .. }
                | X::OutOfMemory { .. },
            )
            | E::FrameNotClosed { .. }
            | E::DegenerateWall { .. }
            | E::Limit(
                L::ContactNotTouching { .. }
                | L::PlateTouchesNothing { .. }
                | L::DrivingSupportCount(_)
                | L::NoDeadLoads
                | L::DuplicateBody { .. }
                | L::DuplicateContact { .. }
                | L::LatticeTooLarge { .. }
                | L::SelfContact { .. },
            )
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
            | E::Implicit(
                I::InvalidBlock { .. }
                | I::InvalidEdgeTraction { .. }
                | I::TimeStepTooSmall { .. }
                | I::BlocksOverlap { .. }
                | I::BlocksCross { .. },
            )
            | E::InvalidPolygon { .. }
            | E::PenaltyModel(_)
            | E::UnsupportedPair(..)
            | E::NoSuchBody { .. }
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

    /// Each error of the implicit and explicit drivers exits with the code
    /// it had as a variant of `DismechError`: a run stopped on the way
    /// (non-finite, out of the frame, energy blow-up, a step failed at its
    /// smallest size) as a solver failure, a refusal before the run as bad
    /// input.
    #[test]
    fn the_drivers_errors_exit_as_before() {
        use dismech::explicit::{GoverningMode, MemoryAdvice, MemoryUse};
        use dismech::implicit::{
            EdgeTractionProblem, Halvings, StepFailure, StepReport, StepTooSmall,
        };
        let report = StepReport {
            substeps: 0,
            reductions: 0,
            halvings: Halvings::default(),
            redetections: 0,
            smallest_dt: 1e-6,
            residuals: Vec::new(),
            step_lengths: Vec::new(),
            open_close_iterations: 0,
            iterations: 0,
        };
        let cases: Vec<(DismechError, Exit)> = vec![
            (
                ExplicitError::StartsInsideWall {
                    body: 0,
                    wall: 1,
                    penetration: 1e-3,
                    tolerance: 1e-9,
                    clockwise_frame: false,
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ExplicitError::InvalidParticle {
                    particle: 0,
                    name: "mass",
                    value: 0.0,
                    requirement: "must be > 0",
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ExplicitError::OutOfMemory {
                    what: MemoryUse::Dem { particles: 1 },
                    bytes: u128::MAX,
                    advice: MemoryAdvice::AddressSpace,
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ExplicitError::InitialOverlap {
                    a: 0,
                    b: 1,
                    overlap: 1e-3,
                    tolerance: 1e-9,
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ExplicitError::UnstableTimeStep {
                    dt: 1.0,
                    limit: 1e-3,
                    governing: GoverningMode::NoContactMode,
                    overlap: None,
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ExplicitError::LawUndefinedForShape {
                    body: 0,
                    shape: "polygon",
                    contact: "a vertex on an edge",
                    advice: "use another law",
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ExplicitError::NonFinite {
                    step: 1,
                    time: 0.0,
                    body: 0,
                    quantity: "velocity",
                }
                .into(),
                Exit::SolverFailure,
            ),
            (
                ExplicitError::ParticleLeftFrame {
                    step: 1,
                    time: 0.0,
                    body: 0,
                    x: 9.0,
                    y: 9.0,
                }
                .into(),
                Exit::SolverFailure,
            ),
            (
                ExplicitError::EnergyBlowUp {
                    step: 1,
                    kinetic: 3.0,
                    available: 1.0,
                    initial_overlap: 0.0,
                }
                .into(),
                Exit::SolverFailure,
            ),
            (
                ImplicitError::InvalidBlock {
                    block: 0,
                    name: "density",
                    value: 0.0,
                    requirement: "must be finite and > 0",
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ImplicitError::InvalidEdgeTraction {
                    body: 0,
                    edge: 9,
                    reason: EdgeTractionProblem::NoSuchEdge { edges: 4 },
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ImplicitError::TimeStepTooSmall {
                    dt: 5e-324,
                    time: 0.0,
                    reason: StepTooSmall::SubStepNotNormal { smallest: 0.0 },
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ImplicitError::BlocksOverlap {
                    vertex_block: 0,
                    vertex: 2,
                    edge_block: 1,
                    depth: 1e-3,
                    tolerance: 1e-9,
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ImplicitError::BlocksCross {
                    a: 0,
                    b: 1,
                    depth: 1e-3,
                    tolerance: 1e-9,
                }
                .into(),
                Exit::BadInput,
            ),
            (
                ImplicitError::StepFailed {
                    time: 0.5,
                    dt: 1e-6,
                    reason: StepFailure::NonFiniteResidual,
                    report: Box::new(report),
                }
                .into(),
                Exit::SolverFailure,
            ),
        ];
        for (error, exit) in &cases {
            assert_eq!(Exit::of_error(error), *exit, "{error:?}");
        }
    }

    /// The limit analysis' errors, gathered into `LimitError`, exit with the
    /// codes they had as variants of `DismechError`: a model that cannot be
    /// built or analysed is bad input, an analysis without a certified
    /// limit load a solver failure.
    #[test]
    fn the_limit_analysis_errors_exit_as_before() {
        use dismech::limit::NamedPartner;
        let cases: Vec<(LimitError, Exit)> = vec![
            (
                LimitError::ContactNotTouching {
                    contact: 0,
                    body: 1,
                    partner: NamedPartner::Element(2),
                    gap: 1e-3,
                    tolerance: 1e-9,
                },
                Exit::BadInput,
            ),
            (
                LimitError::PlateTouchesNothing {
                    support: 0,
                    name: "plate".into(),
                },
                Exit::BadInput,
            ),
            (LimitError::DrivingSupportCount(2), Exit::BadInput),
            (LimitError::NoDeadLoads, Exit::BadInput),
            (LimitError::SelfContact { body: 0 }, Exit::BadInput),
            (
                LimitError::DuplicateBody {
                    body: 1,
                    existing: 0,
                    x: 0.0,
                    y: 0.0,
                    distance: 1e-12,
                },
                Exit::BadInput,
            ),
            (
                LimitError::DuplicateContact {
                    contact: 1,
                    existing: 0,
                    body: 0,
                    partner: NamedPartner::Support {
                        support: 0,
                        name: "base".into(),
                    },
                },
                Exit::BadInput,
            ),
            (
                LimitError::LatticeTooLarge {
                    m: 1000,
                    n: 1000,
                    limit: 10,
                },
                Exit::BadInput,
            ),
            (
                LimitError::NoLimitLoad {
                    status: LimitStatus::Locked,
                    what: "the uniqueness test",
                },
                Exit::SolverFailure,
            ),
            (
                LimitError::UncertifiedOptimum {
                    solver_status: "Solved".into(),
                    primal_residual: 1e-3,
                    dual_residual: 1e-3,
                    gap: 1e-3,
                    tolerance: 1e-7,
                },
                Exit::SolverFailure,
            ),
        ];
        for (error, exit) in cases {
            let joined = DismechError::from(error.clone());
            assert_eq!(joined.to_string(), error.to_string());
            assert_eq!(Exit::of_error(&joined), exit, "{error:?}");
        }
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
