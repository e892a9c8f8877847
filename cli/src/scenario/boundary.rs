//! `[boundary]`: the rigid frame of the explicit driver.

use serde::Deserialize;

/// The frame (`kind` = `open-box` or `walls`).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BoundarySpec {
    /// An open box with its bottom-left corner at the origin
    /// ([`dismech::scene::Frame::open_box`]): walls `left`, `bottom`,
    /// `right`.
    OpenBox(OpenBoxSpec),
    /// A chain of walls through the given points, counter-clockwise around
    /// what it holds ([`dismech::scene::Frame::from_walls`]).
    Walls(WallsSpec),
}

impl BoundarySpec {
    /// The `kind` as written.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::OpenBox(_) => "open-box",
            Self::Walls(_) => "walls",
        }
    }
}

/// An open box.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OpenBoxSpec {
    /// Inner width (m).
    pub width: f64,
    /// Height of the walls (m).
    pub height: f64,
}

/// A chain of walls.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallsSpec {
    /// The points the walls join, in order (m); wall k runs from point k
    /// to point k + 1.
    #[serde(deserialize_with = "super::exact::each")]
    pub points: Vec<[f64; 2]>,
    /// A name per wall (`wall0`, `wall1`, … by default).
    pub names: Option<Vec<String>>,
}
