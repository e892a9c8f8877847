//! `--hpm K`: the K most critical surfaces of the search re-analysed by
//! paper 001's HPM ([`dismech::slope::hpm_reanalysis`]), what each gives
//! (Fs, displacement, share of the slip surface yielded) for critical.csv
//! and summary.json, and the maps of the most critical one.

use dismech::hpm::{HpmResult, HpmSettings, NonlinearSettings};
use dismech::slope::{
    hpm_reanalysis, CriticalSurface, HpmReanalysis, HpmStiffness, SearchResult, TrialSurface,
};

use super::args::SlopeArgs;
use super::error::SlopeError;
use super::Problem;

/// What one HPM analysis (elastic or nonlinear) gives.
#[derive(Debug, Clone, PartialEq)]
pub struct HpmNumbers {
    /// Fs along the sliding direction (Hovland's assumption,
    /// [`HpmResult::sliding_safety_factor`]), or why there is none.
    pub sliding_fs: Result<f64, String>,
    /// The stress ratio `Σ (c + σ tan φ) A / Σ |τ| A`
    /// ([`HpmResult::safety_factor`]), or why there is none.
    pub stress_ratio_fs: Result<f64, String>,
    /// Whether equilibrium was found.
    pub converged: bool,
    /// The relative out-of-balance force.
    pub residual: f64,
    /// Iterations (0 for the elastic solve).
    pub iterations: usize,
    /// The largest displacement at the top of a column (m).
    pub max_displacement: f64,
    /// Share of the slip surface's area slipping or open.
    pub yielded_fraction: f64,
}

impl HpmNumbers {
    fn of(analysis: &HpmReanalysis, result: &HpmResult) -> Self {
        let model = &analysis.model;
        let (iterations, residual) = match result.convergence {
            dismech::hpm::Convergence::Converged {
                iterations,
                residual,
            }
            | dismech::hpm::Convergence::NotConverged {
                iterations,
                residual,
            } => (iterations, residual),
        };
        Self {
            sliding_fs: result
                .sliding_safety_factor(model)
                .map_err(|e| e.to_string()),
            stress_ratio_fs: result.safety_factor(model).map_err(|e| e.to_string()),
            converged: result.convergence.converged(),
            residual,
            iterations,
            max_displacement: result
                .surface(model)
                .iter()
                .map(|p| p.displacement.norm())
                .fold(0.0, f64::max),
            yielded_fraction: result.yielded_area_fraction(model),
        }
    }

    /// As JSON: `fs` and `stress_ratio_fs` (null with `fs_refused` or
    /// `stress_ratio_refused` naming why), convergence, displacement.
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "fs": self.sliding_fs.as_ref().ok(),
            "fs_refused": self.sliding_fs.as_ref().err(),
            "stress_ratio_fs": self.stress_ratio_fs.as_ref().ok(),
            "stress_ratio_refused": self.stress_ratio_fs.as_ref().err(),
            "converged": self.converged,
            "residual": self.residual,
            "iterations": self.iterations,
            "max_displacement_m": self.max_displacement,
            "yielded_area_fraction": self.yielded_fraction,
        })
    }
}

/// One surface re-analysed.
#[derive(Debug, Clone, PartialEq)]
pub struct HpmSurface {
    /// Its rank among the critical surfaces (1 the most critical).
    pub rank: usize,
    /// Its trial index in the family.
    pub trial: u64,
    /// The Fs of the search (Hovland's, or Bishop's with `--method
    /// bishop`).
    pub hovland_fs: f64,
    /// The search's method (`hovland` or `bishop`): the JSON key of the
    /// Fs is `<method>_fs`.
    pub method: &'static str,
    /// HPM's columns, elastic and nonlinear numbers, or why the model
    /// could not be built or solved.
    pub outcome: Result<(usize, HpmNumbers, Option<HpmNumbers>), String>,
}

impl HpmSurface {
    /// As JSON.
    pub fn json(&self) -> serde_json::Value {
        let fs_key = format!("{}_fs", self.method);
        let mut value = match &self.outcome {
            Ok((columns, elastic, nonlinear)) => serde_json::json!({
                "rank": self.rank,
                "trial": self.trial,
                "columns": columns,
                "elastic": elastic.json(),
                "nonlinear": nonlinear.as_ref().map(HpmNumbers::json),
            }),
            Err(reason) => serde_json::json!({
                "rank": self.rank,
                "trial": self.trial,
                "refused": reason,
            }),
        };
        value[fs_key] = self.hovland_fs.into();
        value
    }
}

/// The re-analyses of a run: each surface's numbers, and the whole
/// analysis of the most critical one (for its maps), where it could be
/// made.
#[derive(Debug, Clone, Default)]
pub struct HpmRuns {
    /// Surface by surface, most critical first.
    pub surfaces: Vec<HpmSurface>,
    /// The most critical surface's analysis.
    pub worst: Option<HpmReanalysis>,
}

/// Refuse `--hpm` above `--keep` (checked before the search). Layers of
/// any unit weights, a water table and a pore-pressure ratio are taken
/// ([`dismech::slope::hpm_reanalysis`]).
///
/// # Errors
/// [`SlopeError::HpmAboveKeep`] for `--hpm K` above `--keep`.
pub fn check(args: &SlopeArgs) -> Result<(), SlopeError> {
    let Some(hpm) = args.hpm else {
        return Ok(());
    };
    if hpm > args.keep {
        return Err(SlopeError::HpmAboveKeep {
            hpm,
            keep: args.keep,
        });
    }
    Ok(())
}

/// Re-analyse the `args.hpm` most critical surfaces of `result`.
pub fn reanalyse<S: TrialSurface + Copy>(
    args: &SlopeArgs,
    problem: &Problem,
    result: &SearchResult<S>,
) -> HpmRuns {
    let stiffness = HpmStiffness {
        youngs_modulus: args.youngs_modulus,
        poisson_ratio: args.poisson_ratio,
        slip_modulus: args.youngs_modulus,
        ..HpmStiffness::default()
    };
    let nonlinear = NonlinearSettings::default();
    let mut runs = HpmRuns::default();
    for (k, c) in result
        .critical
        .iter()
        .take(args.hpm.unwrap_or(0))
        .enumerate()
    {
        let CriticalSurface {
            trial,
            surface,
            result: fs,
        } = c;
        let analysis = hpm_reanalysis(
            &problem.terrain,
            &problem.ground,
            &problem.loads,
            surface,
            fs,
            &stiffness,
            &HpmSettings::default(),
            args.hpm_nonlinear.then_some(&nonlinear),
        );
        let outcome = analysis.as_ref().map_err(|e| e.to_string()).map(|a| {
            (
                a.model.columns.len(),
                HpmNumbers::of(a, &a.elastic),
                a.nonlinear.as_ref().map(|r| HpmNumbers::of(a, r)),
            )
        });
        runs.surfaces.push(HpmSurface {
            rank: k + 1,
            trial: *trial,
            hovland_fs: fs.safety_factor,
            method: args.method.name(),
            outcome,
        });
        if k == 0 {
            runs.worst = analysis.ok();
        }
    }
    runs
}
