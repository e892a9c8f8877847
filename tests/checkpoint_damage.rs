//! Checkpoints damaged behind their checksum (bits flipped in the payload
//! and the checksum written again, as a tool that rewrites files might):
//! each is refused with a typed error or restored, never a panic, and a
//! restored one steps (or stops with an error) without a panic either.
//! The header's layout is the documented one (`dismech::checkpoint`).

use dismech::dda::{Block, BlockMaterial, DdaModel, DdaSettings, PlaneState, Prescribed};
use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::DemSettings;
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::law::{Damping, FrictionIntegration, NormalStiffness, PenaltyCoulomb};
use dismech::math::{Point, SplitMix64, Vec2};
use dismech::scene::{Frame, Scene};

/// Where the payload starts, and where its checksum is kept.
const PAYLOAD: usize = 29;
const CHECKSUM: std::ops::Range<usize> = 21..29;

/// FNV-1a, 64 bits: the checksum of the format.
fn fnv(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// `bytes` with `flips` random bits of the payload flipped and the
/// checksum written again.
fn damaged(bytes: &[u8], flips: usize, random: &mut SplitMix64) -> Vec<u8> {
    let mut b = bytes.to_vec();
    for _ in 0..flips {
        let at = PAYLOAD + (random.next_uniform() * (b.len() - PAYLOAD) as f64) as usize;
        b[at] ^= 1 << ((random.next_uniform() * 8.0) as u32);
    }
    let sum = fnv(&b[PAYLOAD..]);
    b[CHECKSUM].copy_from_slice(&sum.to_le_bytes());
    b
}

/// A DEM of a disc, an ellipse and a square on a floor, 300 steps in: 3 000
/// damaged copies of its checkpoint, each refused as a checkpoint error or
/// restored and stepped three times.
#[test]
fn a_damaged_dem_checkpoint_never_panics() {
    let law =
        SpringDashpotCoulomb::new(NormalStiffness::Constant(1e6), 0.5, 0.3, Damping::Critical)
            .unwrap();
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    scene
        .add_circle(Point::new(0.3, 0.05), 0.05, 2600.0)
        .unwrap();
    scene
        .add_ellipse(Point::new(0.5, 0.0301), 0.06, 0.03, 0.0, 2600.0)
        .unwrap();
    scene
        .add_rectangle(Point::new(0.7, 0.0401), 0.08, 0.08, 0.0, 2600.0)
        .unwrap();
    let settings = DemSettings {
        dt: 1e-4,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, settings).unwrap();
    for _ in 0..300 {
        sim.step().unwrap();
    }
    let bytes = sim.checkpoint().unwrap();
    let mut random = SplitMix64(3);
    let (mut restored, mut refused) = (0, 0);
    for case in 0..3000 {
        let b = damaged(&bytes, 1 + case % 3, &mut random);
        match DemSimulation::<SpringDashpotCoulomb>::restore(law, ExplicitEuler, &b) {
            Ok(mut s) => {
                restored += 1;
                for _ in 0..3 {
                    if s.step().is_err() {
                        break;
                    }
                }
                let _ = s.contacts();
            }
            Err(DismechError::Checkpoint { .. }) => refused += 1,
            Err(other) => panic!("case {case}: {other:?}"),
        }
    }
    println!("restored {restored}, refused {refused}");
    assert!(restored > 0 && refused > 0, "{restored} {refused}");
}

/// A DDA block and a disc on a fixed base, five steps in: 1 500 damaged
/// copies of its checkpoint, each refused as a checkpoint error or
/// restored and advanced one step.
#[test]
fn a_damaged_dda_checkpoint_never_panics() {
    let model = || {
        let rock = BlockMaterial {
            density: 2200.0,
            youngs_modulus: 1e9,
            poisson_ratio: 0.25,
            plane: PlaneState::Stress,
        };
        let square = |x0: f64, y0: f64, x1: f64, y1: f64| {
            [(x0, y0), (x1, y0), (x1, y1), (x0, y1)].map(|(x, y)| Point::new(x, y))
        };
        let mut base = Block::new(&square(-2.0, -0.5, 2.0, 0.0), rock, 0).unwrap();
        base.prescribed = Some(Prescribed::fixed());
        let block = Block::new(&square(-0.5, 0.0, 0.5, 0.5), rock, 1).unwrap();
        let disc = Block::circle(Point::new(1.2, 0.2), 0.2, rock, 2).unwrap();
        let law = PenaltyCoulomb::new(1e9, 0.5, FrictionIntegration::ReturnMapping).unwrap();
        let settings = DdaSettings {
            overlap_tolerance: 1e-4,
            ..DdaSettings::default()
        };
        DdaModel::new(vec![base, block, disc], law, settings).unwrap()
    };
    let mut run = model();
    for _ in 0..5 {
        run.advance(1e-3).unwrap();
    }
    let bytes = run.checkpoint().unwrap();
    let mut random = SplitMix64(5);
    let (mut restored, mut refused) = (0, 0);
    for case in 0..1500 {
        let b = damaged(&bytes, 1 + case % 2, &mut random);
        let mut target = model();
        match target.restore(&b) {
            Ok(()) => {
                restored += 1;
                let _ = target.advance(1e-3);
            }
            Err(DismechError::Checkpoint { .. }) => refused += 1,
            Err(other) => panic!("case {case}: {other:?}"),
        }
    }
    println!("restored {restored}, refused {refused}");
    assert!(restored > 0 && refused > 0, "{restored} {refused}");
}
