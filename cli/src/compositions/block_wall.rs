//! One running-bond wall of rectangular blocks at rest on a fixed base,
//! solved by two methods: the explicit polygon DEM (rigid blocks, spring–
//! dashpot–Coulomb contacts, run to rest) and the implicit DDA (deformable
//! blocks, penalty contacts with return mapping, classic static analysis).
//!
//! Both methods see the same geometry and the same contact points: each
//! block's corner that lies on a neighbour's face is a contact point — the
//! two points of the DEM's face-on-face manifold are the vertex–edge
//! contacts of the DDA. Head joints are left open (`joint` wide), so that
//! no two corners meet and the blocks of a course touch only the courses
//! above and below. The contact laws are matched point by point: the DEM's
//! constant normal stiffness `k` with `k_s = k_n` is the DDA's penalty
//! `p_c = k` (eq. 8 of paper 003 uses one penalty for both directions),
//! and both use the same friction coefficient. What differs is what the
//! methods are: DEM blocks are rigid, DDA blocks strain uniformly (Young's
//! modulus `E`); the DEM reaches rest by dashpot damping of a dynamic
//! settling, the DDA by static steps that restart from zero velocity.
//!
//! The base carries the weight in both (global equilibrium, to the
//! precision of the rest criteria). How the weight is shared among the
//! blocks of the bottom course is statically indeterminate: the share
//! follows from the compliances — of the contacts, and in the DDA also of
//! the blocks — so the two methods agree on it only as far as the DDA
//! blocks are stiff compared with the contacts. No contact slips, so both
//! rest states are linear elastic solutions and the loading path does not
//! matter. For the [`Default`] wall (`k/E = 0.067`) the largest difference
//! on a bottom-course block is 0.8 % of a block's weight; it is
//! proportional to `k/E` ([`dem_vs_dda_variants`] with
//! [`RunningBondWall::scaled`]): 100 times stiffer DDA blocks divide it by
//! 90, contacts and blocks both 10 times stiffer leave it unchanged, and
//! nearly rigid DDA blocks (`E × 10⁴`) meet the rigid DEM blocks to 1e-6
//! of a block's weight. The shear springs share the weight too: a DEM
//! with `k_s/k_n = 0.25` against the DDA's single penalty differs by
//! 1.7 % of a block's weight even with nearly rigid blocks.
//!
//! Of the DDA this uses [`DdaModel::new`], [`DdaModel::advance`],
//! [`DdaModel::blocks`], [`DdaModel::contact_force_on`] and
//! [`DdaModel::contacts`] (their vertex and edge blocks, point and force),
//! with [`Block`], [`BlockMaterial`], [`DdaSettings`] and [`Prescribed`].

use dismech::dda::{Block, BlockMaterial, DdaModel, DdaSettings, PlaneState, Prescribed};
use dismech::dem::DemSimulation;
use dismech::error::{require_positive, DismechError, Result};
use dismech::explicit::{critical_time_step, ContactTarget, DemSettings, RestCriterion, RunStatus};
use dismech::integrate::{ExplicitEuler, Newmark, Restarting};
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::law::{FrictionIntegration, PenaltyCoulomb};
use dismech::math::{Point, Vec2};
use dismech::scene::{Frame, Scene};
use dismech::shape::Segment;

/// Classic DDA's static analysis: Newmark β = ½, γ = 1 restarted from rest.
type StaticDda = DdaModel<Restarting<Newmark>>;

/// The wall and the material of both methods. [`Default`]: six courses of
/// 0.4 m × 0.2 m concrete blocks (39 blocks), 1 cm head joints, contact
/// stiffness 2 GN/m per m per contact point, μ = 0.6, E = 30 GPa.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunningBondWall {
    /// Number of courses (rows of blocks).
    pub courses: usize,
    /// Full blocks in the even courses (the bottom one is course 0); the
    /// odd courses hold one full block fewer, shifted by half a block,
    /// and a shorter end block at each end so that the wall ends are
    /// (nearly) flush.
    pub blocks_per_course: usize,
    /// Block length (m).
    pub block_length: f64,
    /// Block height (m).
    pub block_height: f64,
    /// Width of the open head joints between the blocks of a course (m);
    /// the end blocks of the odd courses stop one joint short of the ends.
    pub joint: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Magnitude of gravity (m/s²).
    pub gravity: f64,
    /// Stiffness per contact point, normal and shear alike (N/m per m of
    /// thickness): the DEM's `k_n = k_s` and the DDA's penalty `p_c`.
    pub contact_stiffness: f64,
    /// `k_s / k_n` of the DEM's contacts: 1 matches the DDA, whose eq. 8
    /// uses the one penalty in both directions.
    pub dem_stiffness_ratio: f64,
    /// Friction coefficient μ of every contact.
    pub friction: f64,
    /// Young's modulus of the DDA blocks (Pa); the DEM's are rigid.
    pub youngs_modulus: f64,
    /// Poisson's ratio of the DDA blocks (plane stress).
    pub poisson_ratio: f64,
}

impl Default for RunningBondWall {
    fn default() -> Self {
        Self {
            courses: 6,
            blocks_per_course: 6,
            block_length: 0.4,
            block_height: 0.2,
            joint: 0.01,
            density: 2400.0,
            gravity: 9.81,
            contact_stiffness: 2e9,
            dem_stiffness_ratio: 1.0,
            friction: 0.6,
            youngs_modulus: 30e9,
            poisson_ratio: 0.2,
        }
    }
}

/// One block of the wall: its course and its corners, counter-clockwise
/// from the lower left.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallBlock {
    /// Course (0 at the bottom).
    pub course: usize,
    /// Corners (world, m).
    pub corners: [Point; 4],
}

impl RunningBondWall {
    fn validate(&self) -> Result<()> {
        for (name, value) in [
            ("block length", self.block_length),
            ("block height", self.block_height),
            ("head joint", self.joint),
            ("density", self.density),
            ("gravity", self.gravity),
            ("contact stiffness", self.contact_stiffness),
            ("DEM k_s/k_n", self.dem_stiffness_ratio),
            ("Young's modulus", self.youngs_modulus),
        ] {
            require_positive(name, value)?;
        }
        if !(self.friction.is_finite() && self.friction >= 0.0) {
            return Err(DismechError::InvalidParameter {
                name: "friction coefficient mu",
                value: self.friction,
                requirement: "must be finite and >= 0",
            });
        }
        for (name, value) in [
            ("courses", self.courses),
            ("blocks per course", self.blocks_per_course),
        ] {
            if value < 2 {
                return Err(DismechError::InvalidParameter {
                    name,
                    value: value as f64,
                    requirement: "must be at least 2",
                });
            }
        }
        if 3.0 * self.joint >= self.block_length {
            return Err(DismechError::InvalidParameter {
                name: "head joint",
                value: self.joint,
                requirement: "must be below a third of the block length",
            });
        }
        Ok(())
    }

    /// The same wall with its contact stiffness (in both methods)
    /// multiplied by `contact` and its DDA blocks' Young's modulus by
    /// `modulus`.
    pub fn scaled(&self, contact: f64, modulus: f64) -> Self {
        Self {
            contact_stiffness: self.contact_stiffness * contact,
            youngs_modulus: self.youngs_modulus * modulus,
            ..*self
        }
    }

    /// Length of the wall (m).
    pub fn length(&self) -> f64 {
        let n = self.blocks_per_course as f64;
        n * self.block_length + (n - 1.0) * self.joint
    }

    /// Weight of a full block (N per m).
    pub fn block_weight(&self) -> f64 {
        self.density * self.block_length * self.block_height * self.gravity
    }

    /// The blocks, course by course from the bottom, left to right.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a size, density, stiffness or
    /// modulus that is not finite and positive, a negative friction, fewer
    /// than two courses or blocks per course, or a joint of a third of the
    /// block length or more.
    pub fn blocks(&self) -> Result<Vec<WallBlock>> {
        self.validate()?;
        let (l, h, g) = (self.block_length, self.block_height, self.joint);
        let n = self.blocks_per_course;
        let end = 0.5 * l - 1.5 * g;
        let mut out = Vec::new();
        for course in 0..self.courses {
            let y = course as f64 * h;
            let mut spans: Vec<(f64, f64)> = Vec::new();
            if course % 2 == 0 {
                spans.extend((0..n).map(|i| (i as f64 * (l + g), l)));
            } else {
                spans.push((g, end));
                spans.extend((0..n - 1).map(|i| ((i as f64 + 0.5) * (l + g), l)));
                spans.push((self.length() - g - end, end));
            }
            out.extend(spans.into_iter().map(|(x, w)| WallBlock {
                course,
                corners:
                    [(x, y), (x + w, y), (x + w, y + h), (x, y + h)].map(|(x, y)| Point::new(x, y)),
            }));
        }
        Ok(out)
    }
}

/// A contact force of a solution, for pictures: the force on one of the
/// two blocks at the contact point (N/m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallContact {
    /// The contact point.
    pub point: Point,
    /// The force on one of the two bodies.
    pub force: Vec2,
}

/// The wall at rest by one method.
#[derive(Debug, Clone, PartialEq)]
pub struct WallSolution {
    /// The base's total force on the wall (N/m).
    pub base_reaction: Vec2,
    /// Total weight of the blocks (N/m).
    pub total_weight: f64,
    /// Vertical force of the base on each block of the bottom course, left
    /// to right (N/m).
    pub bottom_course: Vec<f64>,
    /// Every contact force.
    pub contacts: Vec<WallContact>,
    /// Contacts in slip at the end.
    pub slipping: usize,
    /// Whether the rest criterion was met.
    pub at_rest: bool,
    /// Steps taken.
    pub steps: usize,
    /// Mean unbalanced force per block over the mean weight at the end.
    pub unbalanced: f64,
}

impl WallSolution {
    /// Vertical base reaction over the total weight.
    pub fn base_reaction_ratio(&self) -> f64 {
        self.base_reaction.y / self.total_weight
    }
}

/// The DEM law of `wall`: constant `k_n`, `k_s = dem_stiffness_ratio k_n`,
/// critical dashpots.
fn dem_law(wall: &RunningBondWall) -> Result<SpringDashpotCoulomb> {
    SpringDashpotCoulomb::new(
        NormalStiffness::Constant(wall.contact_stiffness),
        wall.dem_stiffness_ratio,
        wall.friction,
        Damping::Critical,
    )
}

/// Settle the wall in the explicit polygon DEM: rigid blocks placed
/// touching on a fixed base (a wall of the frame 0.5 m longer than the
/// wall at each end), a quarter of the estimated stable step, run to rest
/// (kinetic energy below 1e-10 of the released, unbalanced force below
/// 1e-7 of the weight).
///
/// # Errors
/// As [`RunningBondWall::blocks`], and the DEM's own errors.
pub fn wall_by_dem(wall: &RunningBondWall) -> Result<WallSolution> {
    let blocks = wall.blocks()?;
    let base = Segment::new(Point::new(-0.5, 0.0), Point::new(wall.length() + 0.5, 0.0));
    let frame = Frame::from_walls(vec![("base".into(), base)])?;
    let mut scene = Scene::new(frame, Vec2::new(0.0, -wall.gravity))?;
    for b in &blocks {
        scene.add_polygon(&b.corners, wall.density)?;
    }
    let law = dem_law(wall)?;
    let settings = DemSettings {
        dt: 0.25 * critical_time_step(&scene, &law).dt,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, settings)?;
    let criterion = RestCriterion {
        kinetic_to_released_ratio: 1e-10,
        unbalanced_force_ratio: 1e-7,
        min_time: 0.05,
        max_time: 5.0,
        ..RestCriterion::default()
    };
    let outcome = sim.run_to_rest(&criterion, |_, _| {})?;
    let mut bottom = vec![0.0; blocks.iter().filter(|b| b.course == 0).count()];
    let mut contacts = Vec::with_capacity(sim.contacts().len());
    let mut base_reaction = Vec2::zeros();
    for c in sim.contacts() {
        if let ContactTarget::Wall(_) = c.target {
            base_reaction -= c.force_on_target;
            if let Some(share) = bottom.get_mut(c.particle) {
                *share -= c.force_on_target.y;
            }
        }
        contacts.push(WallContact {
            point: c.point,
            force: c.force_on_target,
        });
    }
    Ok(WallSolution {
        base_reaction,
        total_weight: sim.scene().total_weight(),
        bottom_course: bottom,
        slipping: count_slipping(sim.contacts().iter().map(|c| c.regime)),
        contacts,
        at_rest: outcome.status == RunStatus::AtRest,
        steps: outcome.steps as usize,
        unbalanced: outcome.unbalanced_force_ratio,
    })
}

fn count_slipping(regimes: impl Iterator<Item = dismech::law::Regime>) -> usize {
    regimes.filter(|r| *r == dismech::law::Regime::Slip).count()
}

/// Time step of the static DDA steps (s): with β = ½ the inertia term of a
/// step is `2 m / Δt²` per unit displacement, about 0.2 % of the contact
/// stiffness of the default wall, so each step removes nearly all of the
/// remaining out-of-balance force.
const DDA_STEP: f64 = 0.01;
/// Most static DDA steps.
const DDA_MAX_STEPS: usize = 200;

/// The wall in the DDA: deformable blocks (plane stress) on a fixed base
/// block 0.5 m longer than the wall at each end and one course deep,
/// return-mapping friction, the classic static analysis (velocities reset
/// after every step) in steps of 0.01 s until the unbalanced force is below
/// 1e-7 of the weight.
///
/// # Errors
/// As [`RunningBondWall::blocks`], the DDA's own errors, and
/// [`ImplicitError::StepFailed`](dismech::implicit::ImplicitError::StepFailed)
/// if a step fails at its smallest size.
pub fn wall_by_dda(wall: &RunningBondWall) -> Result<WallSolution> {
    let layout = wall.blocks()?;
    let material = BlockMaterial {
        density: wall.density,
        youngs_modulus: wall.youngs_modulus,
        poisson_ratio: wall.poisson_ratio,
        plane: PlaneState::Stress,
    };
    let mut blocks = Vec::with_capacity(layout.len() + 1);
    for (i, b) in layout.iter().enumerate() {
        blocks.push(Block::new(&b.corners, material, i)?);
    }
    let (x0, x1, depth) = (-0.5, wall.length() + 0.5, wall.block_height);
    let base_corners = [(x0, -depth), (x1, -depth), (x1, 0.0), (x0, 0.0)];
    let mut base = Block::new(
        &base_corners.map(|(x, y)| Point::new(x, y)),
        material,
        layout.len(),
    )?;
    base.prescribed = Some(Prescribed::fixed());
    blocks.push(base);
    let law = PenaltyCoulomb::new(
        wall.contact_stiffness,
        wall.friction,
        FrictionIntegration::ReturnMapping,
    )?;
    let settings = DdaSettings {
        gravity: Vec2::new(0.0, -wall.gravity),
        search_distance: 0.5 * wall.joint,
        residual_tolerance: 1e-9,
        ..DdaSettings::default()
    };
    // The static analysis of classic DDA: Newmark restarted from rest.
    let mut model = DdaModel::with_integrator(blocks, law, Restarting(Newmark::dda()), settings)?;
    let weights: Vec<f64> = layout
        .iter()
        .enumerate()
        .map(|(i, _)| block_weight(&model, i, wall))
        .collect();
    let total_weight: f64 = weights.iter().sum();
    let mut steps = 0;
    let mut unbalanced = f64::INFINITY;
    while steps < DDA_MAX_STEPS && unbalanced > 1e-7 {
        model.advance(DDA_STEP)?;
        steps += 1;
        let net: f64 = (0..layout.len())
            .map(|i| {
                let weight = block_weight(&model, i, wall);
                (model.contact_force_on(i) - Vec2::new(0.0, weight)).norm()
            })
            .sum();
        unbalanced = net / total_weight;
    }
    let base_index = layout.len();
    let base_reaction = -model.contact_force_on(base_index);
    let (contacts, bottom, slipping) = dda_contacts(&model, base_index, &layout);
    Ok(WallSolution {
        base_reaction,
        total_weight,
        bottom_course: bottom,
        contacts,
        slipping,
        at_rest: unbalanced <= 1e-7,
        steps,
        unbalanced,
    })
}

/// Weight of DDA block `i` as it is now (its mass follows its area).
fn block_weight(model: &StaticDda, i: usize, wall: &RunningBondWall) -> f64 {
    model.blocks()[i].area() * wall.density * wall.gravity
}

/// The contact forces of a DDA model, the base's vertical force on each
/// bottom-course block, and the contacts in slip.
fn dda_contacts(
    model: &StaticDda,
    base: usize,
    layout: &[WallBlock],
) -> (Vec<WallContact>, Vec<f64>, usize) {
    let mut bottom = vec![0.0; layout.iter().filter(|b| b.course == 0).count()];
    let mut contacts = Vec::with_capacity(model.contacts().len());
    for c in model.contacts() {
        let (vertex_block, edge_block) = c.bodies;
        let on_block = if edge_block == base {
            Some((vertex_block, c.force_on_a))
        } else if vertex_block == base {
            Some((edge_block, -c.force_on_a))
        } else {
            None
        };
        if let Some((block, force)) = on_block {
            if let Some(share) = bottom.get_mut(block) {
                *share += force.y;
            }
        }
        contacts.push(WallContact {
            point: c.point,
            force: c.force_on_a,
        });
    }
    let slipping = count_slipping(model.contacts().iter().filter_map(|c| c.state.regime));
    (contacts, bottom, slipping)
}

/// The wall by both methods, and how they differ.
#[derive(Debug, Clone, PartialEq)]
pub struct WallComparison {
    /// The wall and material.
    pub wall: RunningBondWall,
    /// The polygon DEM's solution.
    pub dem: WallSolution,
    /// The DDA's solution.
    pub dda: WallSolution,
    /// Largest difference between the methods' vertical base forces on a
    /// block of the bottom course, over the weight of a full block.
    pub bottom_course_difference: f64,
}

/// Largest difference between the vertical base forces of `dem` and
/// `dda` on a block of the bottom course, over `block_weight`.
pub fn bottom_course_difference(dem: &WallSolution, dda: &WallSolution, block_weight: f64) -> f64 {
    dem.bottom_course
        .iter()
        .zip(&dda.bottom_course)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / block_weight
}

/// Solve `wall` by the polygon DEM and by the DDA and compare the bottom
/// course's vertical forces.
///
/// # Errors
/// As [`wall_by_dem`] and [`wall_by_dda`].
pub fn dem_vs_dda(wall: &RunningBondWall) -> Result<WallComparison> {
    let dem = wall_by_dem(wall)?;
    compare_with_dda(wall, dem)
}

fn compare_with_dda(wall: &RunningBondWall, dem: WallSolution) -> Result<WallComparison> {
    let dda = wall_by_dda(wall)?;
    Ok(WallComparison {
        wall: *wall,
        bottom_course_difference: bottom_course_difference(&dem, &dda, wall.block_weight()),
        dem,
        dda,
    })
}

/// [`dem_vs_dda`] for each of `walls` (variants of one wall, e.g. by
/// [`RunningBondWall::scaled`]), running the DEM once for variants that
/// differ only in what the DEM does not see (the DDA blocks' elasticity).
///
/// # Errors
/// As [`dem_vs_dda`].
pub fn dem_vs_dda_variants(walls: &[RunningBondWall]) -> Result<Vec<WallComparison>> {
    // The DEM's blocks are rigid: its run does not depend on E and ν.
    let dem_key = |w: &RunningBondWall| RunningBondWall {
        youngs_modulus: 1.0,
        poisson_ratio: 0.0,
        ..*w
    };
    let mut dem_runs: Vec<(RunningBondWall, WallSolution)> = Vec::new();
    let mut out = Vec::with_capacity(walls.len());
    for wall in walls {
        let key = dem_key(wall);
        let dem = match dem_runs.iter().find(|(k, _)| *k == key) {
            Some((_, run)) => run.clone(),
            None => {
                let run = wall_by_dem(wall)?;
                dem_runs.push((key, run.clone()));
                run
            }
        };
        out.push(compare_with_dda(wall, dem)?);
    }
    Ok(out)
}
