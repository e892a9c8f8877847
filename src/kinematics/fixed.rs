//! A body with no degrees of freedom: a fixed wall or support.

use nalgebra::{Matrix3, SMatrix, SVector};

use super::{Advance, AreaMoments, Kinematics, MapVector};
use crate::error::Result;

/// No motion: `x = X`. Pairs a moving body with a fixed wall without
/// carrying unknowns for the wall.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Fixed;

impl Kinematics<0> for Fixed {
    const LINEAR: bool = true;

    fn map_parameters(&self, _d: &SVector<f64, 0>) -> MapVector {
        MapVector::zeros()
    }

    fn map_jacobian(&self, _d: &SVector<f64, 0>) -> SMatrix<f64, 6, 0> {
        SMatrix::zeros()
    }

    fn map_curvature(&self, _d: &SVector<f64, 0>, _w: &MapVector) -> SMatrix<f64, 0, 0> {
        SMatrix::zeros()
    }

    fn mass(&self, _moments: &AreaMoments, _density: f64) -> SMatrix<f64, 0, 0> {
        SMatrix::zeros()
    }

    fn stiffness(&self, _moments: &AreaMoments, _elastic: &Matrix3<f64>) -> SMatrix<f64, 0, 0> {
        SMatrix::zeros()
    }
}

/// Any geometry stays where it is.
impl<G: Clone> Advance<G, 0> for Fixed {
    fn advance(&self, geometry: &G, _d: &SVector<f64, 0>, _body: usize) -> Result<G> {
        Ok(geometry.clone())
    }
}
