//! The 3D affine body of HPM (paper 001, eqs. 2 and 23–25): twelve
//! unknowns moving an element by a linear displacement field made of a
//! rigid translation and rotation about its centroid plus a uniform strain
//! — the 3D counterpart of [`super::Affine2`] (DDA's six unknowns), used
//! by [`crate::hpm`]'s column elements.
//!
//! Degrees of freedom, in order: `u_c = (u, v, w)` at the centroid, the
//! rotation `ω = (ω_x, ω_y, ω_z)`, and the strain
//! `ε = (ε_xx, ε_yy, ε_zz, γ_yz, γ_zx, γ_xy)` (engineering shear). With
//! `r = x − x_c`, eq. (2) reads
//! `u(x) = u_c + ω × r + E(ε) r`, `E` the symmetric strain tensor, so the
//! strain of the field is exactly `ε` and eq. (25) becomes `V Bᵀ D B` with
//! `B` picking the strain DOFs.

use nalgebra::{Point3, SMatrix, SVector, Vector3};

/// Degrees of freedom of one element.
pub const ELEMENT_DOF: usize = 12;

/// A 3 × 12 matrix `N(x)` of eq. (2).
pub type ShapeMatrix = SMatrix<f64, 3, ELEMENT_DOF>;
/// A 12 × 12 element block.
pub type Block = SMatrix<f64, ELEMENT_DOF, ELEMENT_DOF>;
/// The 12 DOFs of one element.
pub type ElementDofs = SVector<f64, ELEMENT_DOF>;

/// `N(x)` for an element with centroid `centre`: `u(x) = N(x) U` (eq. 2).
pub fn shape_matrix(centre: &Point3<f64>, x: &Point3<f64>) -> ShapeMatrix {
    let r = x - centre;
    let mut n = ShapeMatrix::zeros();
    for i in 0..3 {
        n[(i, i)] = 1.0;
    }
    // ω × r.
    n[(0, 4)] = r.z;
    n[(0, 5)] = -r.y;
    n[(1, 3)] = -r.z;
    n[(1, 5)] = r.x;
    n[(2, 3)] = r.y;
    n[(2, 4)] = -r.x;
    // E(ε) r.
    n[(0, 6)] = r.x;
    n[(1, 7)] = r.y;
    n[(2, 8)] = r.z;
    n[(1, 9)] = 0.5 * r.z; // γ_yz
    n[(2, 9)] = 0.5 * r.y;
    n[(0, 10)] = 0.5 * r.z; // γ_zx
    n[(2, 10)] = 0.5 * r.x;
    n[(0, 11)] = 0.5 * r.y; // γ_xy
    n[(1, 11)] = 0.5 * r.x;
    n
}

/// The isotropic elasticity matrix D of eq. (24), engineering shear strains.
pub fn elasticity(youngs_modulus: f64, poisson_ratio: f64) -> SMatrix<f64, 6, 6> {
    let (e, nu) = (youngs_modulus, poisson_ratio);
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let mut d = SMatrix::<f64, 6, 6>::zeros();
    for i in 0..3 {
        for j in 0..3 {
            d[(i, j)] = lambda;
        }
        d[(i, i)] = lambda + 2.0 * mu;
        d[(i + 3, i + 3)] = mu;
    }
    d
}

/// The element stiffness `∫ Bᵀ D B dΩ = V Bᵀ D B` of eq. (25).
pub fn element_stiffness(volume: f64, d: &SMatrix<f64, 6, 6>) -> Block {
    let mut k = Block::zeros();
    k.fixed_view_mut::<6, 6>(6, 6).copy_from(&(d * volume));
    k
}

/// The strain DOFs of an element as a symmetric tensor.
pub fn strain_tensor(dofs: &ElementDofs) -> nalgebra::Matrix3<f64> {
    let e = |k: usize| dofs[6 + k];
    nalgebra::Matrix3::new(
        e(0),
        0.5 * e(5),
        0.5 * e(4),
        0.5 * e(5),
        e(1),
        0.5 * e(3),
        0.5 * e(4),
        0.5 * e(3),
        e(2),
    )
}

/// Displacement of an element's field at `x`.
pub fn displacement_at(centre: &Point3<f64>, dofs: &ElementDofs, x: &Point3<f64>) -> Vector3<f64> {
    shape_matrix(centre, x) * dofs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_field_has_the_strain_of_its_strain_dofs_and_rotates_rigidly() {
        let c = Point3::new(1.0, 2.0, 3.0);
        let mut u = ElementDofs::zeros();
        for (k, v) in [
            0.1, 0.2, 0.3, 0.01, -0.02, 0.03, 1e-3, 2e-3, -3e-3, 4e-4, 5e-4, -6e-4,
        ]
        .iter()
        .enumerate()
        {
            u[k] = *v;
        }
        // The displacement gradient by finite differences.
        let x = Point3::new(1.7, 1.1, 3.9);
        let h = 1e-6;
        let mut grad = nalgebra::Matrix3::zeros();
        for j in 0..3 {
            let mut xp = x;
            xp[j] += h;
            let du = (displacement_at(&c, &u, &xp) - displacement_at(&c, &u, &x)) / h;
            grad.set_column(j, &du);
        }
        let sym = 0.5 * (grad + grad.transpose());
        let skew = 0.5 * (grad - grad.transpose());
        assert!((sym - strain_tensor(&u)).norm() < 1e-8);
        // Skew part: ω × r has gradient [ω]×, so skew[(2,1)] = ω_x.
        assert!((skew[(2, 1)] - u[3]).abs() < 1e-8);
        assert!((skew[(0, 2)] - u[4]).abs() < 1e-8);
        assert!((skew[(1, 0)] - u[5]).abs() < 1e-8);
    }
}
