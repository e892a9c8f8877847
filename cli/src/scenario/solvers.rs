//! `[kinematics]`, `[integrator]`, `[linear_solver]` and `[lp_solver]`:
//! the slots of the time-stepping and limit drivers besides the law.

use serde::Deserialize;

/// Body kinematics (`kind` = `rigid` or `affine`).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum KinematicsSpec {
    /// Rigid bodies, 3 unknowns ([`dismech::kinematics::Rigid2`]).
    Rigid(Empty),
    /// DDA's affine blocks, 6 unknowns ([`dismech::kinematics::Affine2`]).
    Affine(Empty),
}

impl KinematicsSpec {
    /// The `kind` as written.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Rigid(_) => "rigid",
            Self::Affine(_) => "affine",
        }
    }
}

/// A slot's table without parameters.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Empty {}

/// The time integrator (`kind` = `explicit-euler`, `newmark` or
/// `quasi-static`).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum IntegratorSpec {
    /// Symplectic Euler ([`dismech::integrate::ExplicitEuler`]): explicit driver.
    ExplicitEuler(Empty),
    /// Newmark ([`dismech::integrate::Newmark`]): implicit driver.
    Newmark(NewmarkSpec),
    /// No inertia ([`dismech::integrate::QuasiStatic`]): implicit driver.
    QuasiStatic(Empty),
}

impl IntegratorSpec {
    /// The `kind` as written.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::ExplicitEuler(_) => "explicit-euler",
            Self::Newmark(_) => "newmark",
            Self::QuasiStatic(_) => "quasi-static",
        }
    }
}

/// Newmark's β and γ.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NewmarkSpec {
    /// β (> 0); ½ by default (paper 003).
    pub beta: Option<f64>,
    /// γ (≥ ½); 1 by default (paper 003).
    pub gamma: Option<f64>,
    /// Reset the velocities after every step: classic DDA's static
    /// analysis ([`dismech::integrate::Restarting`]); false by default.
    pub restarting: Option<bool>,
}

/// The linear solver of the implicit driver (`kind` = `sparse-lu`).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LinearSolverSpec {
    /// Sparse LU with a fill-reducing ordering ([`dismech::linsolve::SparseLu`]).
    SparseLu(Empty),
}

/// The LP solver of the limit driver (`kind` = `clarabel`).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LpSolverSpec {
    /// Clarabel ([`dismech::lp::LinearProgramSolver`]).
    Clarabel(ClarabelSpec),
}

/// Clarabel's settings.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClarabelSpec {
    /// Gap and feasibility tolerance; 1e-9 by default.
    pub tolerance: Option<f64>,
    /// Most interior-point iterations; 200 by default.
    pub max_iterations: Option<u32>,
}
