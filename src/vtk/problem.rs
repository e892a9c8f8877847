//! Why a VTK dataset or frame cannot be made ([`DismechError::VtkData`]),
//! one variant a cause; each one's Display is the message's text.
//!
//! [`DismechError::VtkData`]: crate::error::DismechError::VtkData

use crate::kinematics::affine3::ELEMENT_DOF;

/// Which data of a dataset an array belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum DataKind {
    /// Point data, one tuple a point.
    #[error("point")]
    Point,
    /// Cell data, one tuple a cell.
    #[error("cell")]
    Cell,
}

/// Why a VTK dataset or frame cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VtkProblem {
    /// A piece name that cannot name a file.
    #[error("the piece name `{name}` must be letters, digits, `_` and `-` (it names files)")]
    PieceName {
        /// The name given.
        name: String,
    },
    /// A piece name already in the frame.
    #[error("the frame already has a piece `{name}`")]
    DuplicatePiece {
        /// The name given.
        name: String,
    },
    /// An unstructured grid with another number of cell types than cells.
    #[error("{types} cell types for {cells} cells")]
    CellTypeCount {
        /// Cell types given.
        types: usize,
        /// Cells given.
        cells: usize,
    },
    /// A cell naming a point the dataset does not have.
    #[error("a cell names point {point}, of {points} points")]
    NoSuchPoint {
        /// The point named.
        point: i64,
        /// Points of the dataset.
        points: usize,
    },
    /// An array of no component.
    #[error("{kind} data `{name}` has no component")]
    NoComponent {
        /// Point or cell data.
        kind: DataKind,
        /// The array's name.
        name: String,
    },
    /// An array whose length is not its components times the tuples.
    #[error(
        "{kind} data `{name}` has {values} values, not {components} components × {tuples} {kind}s"
    )]
    ValueCount {
        /// Point or cell data.
        kind: DataKind,
        /// The array's name.
        name: String,
        /// Values given.
        values: usize,
        /// Components of the array.
        components: usize,
        /// Points or cells of the dataset.
        tuples: usize,
    },
    /// Two arrays of one name.
    #[error("{kind} data `{name}` is named twice")]
    NamedTwice {
        /// Point or cell data.
        kind: DataKind,
        /// The name.
        name: String,
    },
    /// An HPM result of another model.
    #[error("the HPM result has {displacements} displacements and {tractions} slip tractions, the model {elements} elements ({} displacements) and {springs} slip springs: it is not a result of this model", ELEMENT_DOF * elements)]
    NotThisHpmResult {
        /// Displacements of the result.
        displacements: usize,
        /// Slip tractions of the result.
        tractions: usize,
        /// Elements of the model.
        elements: usize,
        /// Slip springs of the model.
        springs: usize,
    },
    /// A limit result without a mechanism, or of another model.
    #[error("the limit result (status {status:?}) has {velocities} body velocities for the model's {bodies} bodies: only a result of this model with a mechanism (Collapse or ZeroLoad) has a frame")]
    NoMechanism {
        /// The result's status.
        status: crate::limit::LimitStatus,
        /// Body velocities of the result.
        velocities: usize,
        /// Bodies of the model.
        bodies: usize,
    },
    /// A limit result of another model (another number of contacts).
    #[error("the limit result has {forces} contact forces for the model's {contacts} contacts: it is not a result of this model")]
    NotThisLimitResult {
        /// Contact forces of the result.
        forces: usize,
        /// Contacts of the model.
        contacts: usize,
    },
}
