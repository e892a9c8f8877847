//! Typed errors for misuse and for runs that cannot go on.
//!
//! One error per module for the grid files ([`crate::grid::GridError`]),
//! HPM ([`crate::hpm::HpmError`]), the slope search
//! ([`crate::slope::SlopeError`]), the implicit driver
//! ([`crate::implicit::ImplicitError`]), the explicit driver
//! ([`crate::explicit::ExplicitError`]) and the limit analysis
//! ([`crate::limit::LimitError`]), joined into [`DismechError`] by its
//! variants [`DismechError::Grid`], [`DismechError::Hpm`],
//! [`DismechError::Slope`], [`DismechError::Implicit`],
//! [`DismechError::Explicit`] and [`DismechError::Limit`] (transparent: the same message, and `From`,
//! so that `?` turns one into a [`DismechError`]); the rest, shared by
//! several modules or of the other methods, are variants of
//! [`DismechError`] itself.

/// Every error dismech returns to a caller.
///
/// Each variant names the offending value, so that a message read on its own
/// says what to change. The errors of the grid files, HPM, the slope
/// search, the implicit and explicit drivers and the limit analysis are
/// their modules' own, joined here ([`DismechError::Grid`],
/// [`DismechError::Hpm`], [`DismechError::Slope`],
/// [`DismechError::Implicit`], [`DismechError::Explicit`],
/// [`DismechError::Limit`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DismechError {
    /// A parameter is outside its admissible range (non-finite, negative, zero…).
    #[error("invalid {name} = {}: {requirement}", Number(*value))]
    InvalidParameter {
        /// The parameter's name as the user wrote it (e.g. `radius`, `density`).
        name: &'static str,
        /// The value given.
        value: f64,
        /// What it must satisfy (e.g. `must be finite and > 0`).
        requirement: &'static str,
    },
    /// The walls of a frame leave a gap.
    #[error("frame does not close: wall {wall} ends at ({end_x}, {end_y}) but wall {next} starts at ({start_x}, {start_y}), a gap of {gap:.3e} m")]
    FrameNotClosed {
        /// Wall whose end is open.
        wall: usize,
        /// The wall that should start there.
        next: usize,
        /// End point of `wall`.
        end_x: f64,
        /// End point of `wall`.
        end_y: f64,
        /// Start point of `next`.
        start_x: f64,
        /// Start point of `next`.
        start_y: f64,
        /// Distance between the two.
        gap: f64,
    },
    /// A wall segment has zero length or non-finite end points.
    #[error("wall {wall} is degenerate: {reason}")]
    DegenerateWall {
        /// Index of the wall.
        wall: usize,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A grid file (ESRI ASCII or GeoTIFF) that cannot be read or used
    /// ([`crate::grid::GridError`]).
    #[error(transparent)]
    Grid(#[from] crate::grid::GridError),
    /// An HPM model or analysis that cannot be built or run, or whose
    /// safety factor is undefined ([`crate::hpm::HpmError`]).
    #[error(transparent)]
    Hpm(#[from] crate::hpm::HpmError),
    /// A slope search whose terrain, ground or trial surfaces cannot be
    /// used, or ground an HPM re-analysis of its surfaces cannot take
    /// ([`crate::slope::SlopeError`]).
    #[error(transparent)]
    Slope(#[from] crate::slope::SlopeError),
    /// An implicit model (DDA's among them) whose bodies cannot be used or
    /// overlap at the start, or a step of it that cannot be taken
    /// ([`crate::implicit::ImplicitError`]).
    #[error(transparent)]
    Implicit(#[from] crate::implicit::ImplicitError),
    /// An explicit run (the DEM's among them) refused before it starts or
    /// stopped on the way ([`crate::explicit::ExplicitError`]).
    #[error(transparent)]
    Explicit(#[from] crate::explicit::ExplicitError),
    /// A limit analysis whose model cannot be built or analysed, or whose
    /// optimum is not certified ([`crate::limit::LimitError`]).
    #[error(transparent)]
    Limit(#[from] crate::limit::LimitError),
    /// A polygon block is not a valid simple polygon.
    #[error("block {block} is not a valid polygon: {reason}")]
    InvalidPolygon {
        /// Index of the block.
        block: usize,
        /// What is wrong.
        reason: &'static str,
    },
    /// A limit-analysis model that has no penalty counterpart.
    #[error("the limit model cannot be turned into a penalty model: {0}")]
    PenaltyModel(PenaltyRefusal),
    /// A shape pair has no contact routine.
    #[error("unsupported contact pair: {0} against {1}")]
    UnsupportedPair(&'static str, &'static str),
    /// A body index does not exist.
    #[error("no body with index {index} (the scene has {count})")]
    NoSuchBody {
        /// Index asked for.
        index: usize,
        /// Number of bodies.
        count: usize,
    },
    /// A global solve failed.
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// A VTK dataset or frame cannot be made: an array that does not fit
    /// its dataset, a result of another model, a limit result without a
    /// mechanism ([`crate::vtk`]).
    #[error("VTK output: {reason}")]
    VtkData {
        /// What does not fit.
        reason: crate::vtk::VtkProblem,
    },
    /// Writing an output failed.
    #[error("cannot write {path}: {message}")]
    Output {
        /// The file.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// A reproduction name that does not exist.
    #[error("unknown study `{0}`; known studies: {1}")]
    UnknownStudy(String, String),
    /// A checkpoint that cannot be saved, read or restored into this
    /// model (see [`crate::checkpoint`]).
    #[error("checkpoint {origin}: {problem}")]
    Checkpoint {
        /// Where it comes from: its path, or `bytes` for one in memory.
        origin: String,
        /// What is wrong.
        problem: crate::checkpoint::CheckpointProblem,
    },
}

/// Why a limit-analysis model has no penalty counterpart
/// ([`DismechError::PenaltyModel`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PenaltyRefusal {
    /// A contact that may open has cohesion; the penalty law has none.
    #[error("a contact that may open has cohesion {cohesion}; the penalty law has none")]
    CohesiveOpening {
        /// The contact's cohesion.
        cohesion: f64,
    },
    /// A support that no contact touches.
    #[error("support {support} ({name}) has no contact")]
    SupportWithoutContact {
        /// Index of the support.
        support: usize,
        /// Its name.
        name: String,
    },
    /// An element that is not a circle.
    #[error("element {element} is not a circle")]
    NotACircle {
        /// Index of the element.
        element: usize,
    },
    /// Not exactly one moving support (plate).
    #[error("{count} supports move; a pushover needs exactly one plate")]
    MovingSupports {
        /// Number of moving supports.
        count: usize,
    },
    /// Two contacts of one pair of groups with different strengths.
    #[error("contact {contact} has strength c = {cohesion}, tan phi = {friction}, unlike another contact of the same kind (c = {other_cohesion}, tan phi = {other_friction})")]
    UnlikeStrengths {
        /// Index of the contact.
        contact: usize,
        /// Its cohesion.
        cohesion: f64,
        /// Its friction coefficient tan φ.
        friction: f64,
        /// The cohesion of the contact of the same kind met first.
        other_cohesion: f64,
        /// Its friction coefficient tan φ.
        other_friction: f64,
    },
    /// A limit model without contacts.
    #[error("the limit model has no contact")]
    NoContact,
    /// The limit analysis found no collapse to compare with.
    #[error("the LP found no collapse ({status:?})")]
    NoCollapse {
        /// The analysis' status.
        status: crate::limit::LimitStatus,
    },
}

/// A number in a message: as Rust writes it where that is short, in
/// scientific notation where it is very small or very large (a subnormal
/// written out in full takes 300 digits).
pub(crate) struct Number(pub(crate) f64);

impl std::fmt::Display for Number {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = self.0;
        if v == 0.0 || !v.is_finite() || (1e-6..1e15).contains(&v.abs()) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

/// A byte count in binary units.
pub(crate) struct Bytes(pub(crate) u128);

impl std::fmt::Display for Bytes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let b = self.0 as f64;
        let gib = 1024.0 * 1024.0 * 1024.0;
        if b >= gib {
            write!(f, "{:.1} GiB", b / gib)
        } else {
            write!(f, "{:.1} MiB", b / (1024.0 * 1024.0))
        }
    }
}

/// Shorthand for results with [`DismechError`].
pub type Result<T> = std::result::Result<T, DismechError>;

/// Check that `value` is finite and strictly positive.
///
/// # Errors
/// [`DismechError::InvalidParameter`] naming `name` and `value` (requirement
/// "must be finite and > 0") when `value` is zero, negative, NaN or infinite.
pub fn require_positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(DismechError::InvalidParameter {
            name,
            value,
            requirement: "must be finite and > 0",
        })
    }
}

/// Check that `value` is finite and not negative.
///
/// # Errors
/// [`DismechError::InvalidParameter`] naming `name` and `value` (requirement
/// "must be finite and >= 0") when `value` is negative, NaN or infinite.
pub fn require_non_negative(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(DismechError::InvalidParameter {
            name,
            value,
            requirement: "must be finite and >= 0",
        })
    }
}

/// Check that `value` is finite.
///
/// # Errors
/// [`DismechError::InvalidParameter`] naming `name` and `value` (requirement
/// "must be finite") when `value` is NaN or infinite.
pub fn require_finite(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(DismechError::InvalidParameter {
            name,
            value,
            requirement: "must be finite",
        })
    }
}

/// Why a linear solve, a factorization or a linear program failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// The system's parts have inconsistent sizes.
    #[error("dimension mismatch in {what}: expected {expected}, found {found}")]
    DimensionMismatch {
        /// Which part of the system.
        what: &'static str,
        /// The size implied by the rest of the system.
        expected: usize,
        /// The size given.
        found: usize,
    },
    /// An entry of the system is NaN or infinite.
    #[error("non-finite value {value} in {what} at index {index}")]
    NonFinite {
        /// Which part of the system.
        what: &'static str,
        /// Position of the entry.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A diagonal mass or pivot is not positive.
    #[error("non-positive {what} {value} at index {index}")]
    NonPositive {
        /// Which part of the system.
        what: &'static str,
        /// Position of the entry.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The matrix could not be factorized (singular or, for Cholesky, not
    /// positive definite).
    #[error("factorization failed: {0}")]
    Factorization(FactorizationFailure),
    /// A solver setting is out of its range.
    #[error("invalid {name} = {value}: {requirement}")]
    InvalidSetting {
        /// The setting.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What it must satisfy.
        requirement: &'static str,
    },
    /// An entry was added at a position the sparsity pattern does not hold.
    #[error("entry ({row}, {col}) is not in the sparsity pattern")]
    OutsidePattern {
        /// Row of the entry.
        row: usize,
        /// Column of the entry.
        col: usize,
    },
    /// The underlying LP solver refused the problem.
    #[error("linear program solver error: {0}")]
    LinearProgram(LpFailure),
}

/// Why a matrix could not be factorized or a factor used
/// ([`SolveError::Factorization`]); where the linear-algebra library
/// (faer) refused, its message is kept.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FactorizationFailure {
    /// A solve asked of a solver that holds no factor.
    #[error("solve before a factorization")]
    NotFactored,
    /// The symbolic analysis of the sparsity pattern failed.
    #[error("{stage}: {message}")]
    Analysis {
        /// The step of the analysis (e.g. `symbolic Cholesky analysis`).
        stage: &'static str,
        /// The library's message.
        message: String,
    },
    /// A workspace could not be allocated.
    #[error("allocating the {workspace} workspace: {message}")]
    Workspace {
        /// Which workspace (`LU`, `solve`, `Cholesky`).
        workspace: &'static str,
        /// The library's message.
        message: String,
    },
    /// The sparse Cholesky factorization met a pivot that is not positive.
    #[error("sparse Cholesky (matrix not positive definite) failed: {message}")]
    NotPositiveDefinite {
        /// The library's message.
        message: String,
    },
    /// The sparse LU factorization met a zero column.
    #[error("sparse LU (matrix structurally singular): {message}")]
    StructurallySingular {
        /// The library's message.
        message: String,
    },
    /// The factor gave a solution that is not finite.
    #[error("matrix is numerically singular: solution entry {index} is {value}")]
    NumericallySingular {
        /// The entry of the solution.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A diagonal block of a block-Jacobi preconditioner is not positive
    /// definite.
    #[error("block-Jacobi block {block} is not positive definite")]
    BlockNotPositiveDefinite {
        /// Index of the block.
        block: usize,
    },
    /// A diagonal block of a multigrid level is not positive definite.
    #[error("diagonal block {block} of a multigrid level is not positive definite")]
    LevelBlockNotPositiveDefinite {
        /// Index of the block.
        block: usize,
    },
    /// A line of a multigrid level with lines (a grid column of HPM's
    /// column multigrid), its diagonal blocks taken together, is not
    /// positive definite.
    #[error(
        "line {line} of a multigrid level (its diagonal blocks together) is not positive definite"
    )]
    LineNotPositiveDefinite {
        /// Index of the line, in the order given.
        line: usize,
    },
    /// A block row of a multigrid level has no diagonal block.
    #[error("block {block} has no diagonal block")]
    NoDiagonalBlock {
        /// Index of the block row.
        block: usize,
    },
    /// A multigrid aggregate too small for the near-null vectors.
    #[error(
        "aggregate {aggregate} has {unknowns} unknowns, fewer than the {vectors} near-null vectors"
    )]
    SmallAggregate {
        /// Index of the aggregate.
        aggregate: usize,
        /// Its unknowns.
        unknowns: usize,
        /// The near-null vectors.
        vectors: usize,
    },
}

/// Why the LP solver gave no usable answer ([`SolveError::LinearProgram`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LpFailure {
    /// The solver (Clarabel) refused to set the problem up.
    #[error("{message}")]
    Setup {
        /// The solver's message.
        message: String,
    },
    /// The solver panicked inside (on degenerate input); the panic was
    /// caught.
    #[error("{message}")]
    Panicked {
        /// The panic's message, or `internal solver panic`.
        message: String,
    },
    /// The LP of a mechanism-uniqueness test did not reach an optimum.
    #[error("the uniqueness test LP ended with status {status:?}")]
    UniquenessTest {
        /// The status it ended with.
        status: crate::lp::LpStatus,
    },
}
