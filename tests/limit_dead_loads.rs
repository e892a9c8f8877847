//! The limit analysis driven by its dead loads: Heyman's arch of polygon
//! voussoirs under self-weight only (contacts from the pair query), the
//! multiplier of the dead loads where contacts have cohesion, and the
//! load drivers replaced and cleared.

#[path = "../examples/heyman_arch.rs"]
#[allow(dead_code)]
mod heyman_arch;

use dismech::error::DismechError;
use dismech::law::RigidPlastic;
use dismech::limit::LimitError;
use dismech::limit::{
    admissibility, analyse, analyse_static, LimitModel, LimitStatus, LoadDriver, NamedPartner,
    Partner,
};
use dismech::lp::LinearProgramSolver;
use dismech::math::{Point, Pose2, Vec2};
use dismech::shape::{Ellipse, Polygon};

/// The least thickness of a semicircular arch, `t/R = 0.1075` for the
/// continuous arch (Ochsendorf 2002; Heyman's 0.106 used an approximate
/// weight distribution), with hinges at the springings, at 54.5° from the
/// crown and at the crown. With 90 voussoirs the hinges can only form at
/// joints 2° apart and the voussoirs have straight faces: the least
/// thickness comes out 0.10745 (0.10748 with 360), within 1e-4 of the
/// published four digits, and the haunch hinge at the joint of 54°.
#[test]
fn heyman_arch_of_polygon_voussoirs_has_its_least_thickness() {
    let voussoirs = 90;
    let (thin, thick) = heyman_arch::least_thickness(voussoirs).unwrap();
    let t = 0.5 * (thin + thick);
    assert!(thick - thin < 1e-5, "bracket {thin}..{thick}");
    assert!((t - 0.1075).abs() < 1e-4, "t/R = {t}");
    // Both analyses agree away from the threshold: it stands above, falls
    // below.
    assert_eq!(
        heyman_arch::stands(voussoirs, 1.01 * t).unwrap(),
        Some(true)
    );
    assert_eq!(
        heyman_arch::stands(voussoirs, 0.99 * t).unwrap(),
        Some(false)
    );
    // Five hinges: springing, haunch, crown, haunch, springing.
    let zones = heyman_arch::hinge_zones(
        &heyman_arch::hinges(voussoirs, thin * (1.0 - 1e-4)).unwrap(),
        voussoirs,
    );
    assert_eq!(zones.len(), 5, "{zones:?}");
    for (found, expected) in zones.iter().zip([90.0, 54.5, 0.0, -54.5, -90.0]) {
        assert!((found - expected).abs() <= 1.0, "{zones:?}");
    }
}

/// A square block glued by a cohesive joint (c per contact point, no
/// friction, bilateral) to a vertical wall: the only mechanism slides it
/// down the wall, dissipating `2 c v` against the weight's power `W v`, so
/// the dead loads' multiplier at collapse is `λ = 2 c / W`; the dual
/// forces carry `λ W` in equilibrium.
#[test]
fn cohesive_block_on_a_wall_has_the_dead_load_multiplier_of_its_joint() {
    // From a glue far weaker than the weight (λ = 5e-8) to one that holds
    // (λ = 1.5); before the residuals were measured at the weight's scale,
    // c up to 1e-4 was refused as uncertified.
    for cohesion in [1e-6, 1e-4, 1e-2, 30.0] {
        glued_block(cohesion);
    }
}

fn glued_block(cohesion: f64) {
    let (side, weight) = (0.5, 40.0);
    let mut model = LimitModel::new(1e-9).unwrap();
    let wall = model
        .add_support("wall", Point::origin(), Vec2::x(), Vec2::zeros())
        .unwrap();
    let block = model
        .add_shape(
            Polygon::rectangle(side, side).unwrap().into(),
            Pose2::new(0.5 * side, 1.0, 0.0),
            true,
        )
        .unwrap();
    model.set_load(block, Vec2::new(0.0, -weight)).unwrap();
    let glue = RigidPlastic::cohesive(cohesion).unwrap();
    let contacts = model
        .add_contacts(block, Partner::Support(wall), glue)
        .unwrap();
    assert_eq!(contacts.len(), 2, "both corners on the wall");
    model.multiply_dead_loads();
    let mut solver = LinearProgramSolver::default();
    let exact = 2.0 * cohesion / weight;
    for result in [
        analyse(&model, &mut solver).unwrap(),
        analyse_static(&model, &mut solver).unwrap(),
    ] {
        assert_eq!(result.status, LimitStatus::Collapse);
        let lambda = result.load.unwrap();
        // Certified at the scale of the real weight (λ = 1): a small λ is
        // known to 1e-7 of that, not of itself.
        assert!(
            (lambda - exact).abs() < 1e-7 * exact.max(1.0),
            "c = {cohesion}: λ = {lambda}"
        );
    }
    let result = analyse(&model, &mut solver).unwrap();
    let check = admissibility(&model, &result);
    assert!(check.equilibrium < 1e-7, "{check:?}");
    assert!(check.strength_excess < 1e-7, "{check:?}");
    // The block slides straight down.
    let (v, omega) = result.velocities[block];
    assert!(v.x.abs() < 1e-7 * v.norm() && v.y < 0.0 && omega.abs() < 1e-7 * v.norm());
}

#[test]
fn load_drivers_are_replaced_and_cleared() {
    let mut model = LimitModel::new(1e-9).unwrap();
    let floor = model
        .add_support("floor", Point::origin(), Vec2::y(), Vec2::zeros())
        .unwrap();
    let block = model
        .add_shape(
            Polygon::rectangle(1.0, 1.0).unwrap().into(),
            Pose2::new(0.0, 0.5, 0.0),
            true,
        )
        .unwrap();
    let joint = RigidPlastic::coulomb(0.0, 0.5, true).unwrap();
    assert_eq!(
        model
            .add_contacts(block, Partner::Support(floor), joint)
            .unwrap()
            .len(),
        2
    );
    let mut solver = LinearProgramSolver::default();
    // Without weights there is nothing to multiply.
    model.multiply_dead_loads();
    assert!(matches!(
        analyse(&model, &mut solver),
        Err(DismechError::Limit(LimitError::NoDeadLoads))
    ));
    model.set_load(block, Vec2::new(0.0, -10.0)).unwrap();
    // A block on a floor stands under any multiple of its weight.
    assert_eq!(
        analyse(&model, &mut solver).unwrap().status,
        LimitStatus::Locked
    );
    // A live load replaces the dead loads' multiplier: pushed at its
    // centre, the block slides at λ = μ W = 5 before it would tip (at
    // W w / (2 h) = 10).
    model
        .set_live_load(block, Vec2::x(), Point::new(0.0, 0.5))
        .unwrap();
    assert!(matches!(model.load_driver(), Some(LoadDriver::Live(_))));
    let lambda = analyse(&model, &mut solver).unwrap().load.unwrap();
    assert!((lambda - 5.0).abs() < 1e-7, "λ = {lambda}");
    // Cleared, the model has no driver until a support moves.
    model.clear_load_driver();
    assert!(model.load_driver().is_none() && model.live_load().is_none());
    assert!(matches!(
        analyse(&model, &mut solver),
        Err(DismechError::Limit(LimitError::DrivingSupportCount(0)))
    ));
}

#[test]
fn outlines_apart_are_refused_with_their_gap() {
    let mut model = LimitModel::new(1e-6).unwrap();
    let floor = model
        .add_support("floor", Point::origin(), Vec2::y(), Vec2::zeros())
        .unwrap();
    let square = || Polygon::rectangle(1.0, 1.0).unwrap().into();
    let low = model
        .add_shape(square(), Pose2::new(0.0, 0.5 + 1e-3, 0.0), true)
        .unwrap();
    let high = model
        .add_shape(square(), Pose2::new(0.0, 2.0, 0.0), true)
        .unwrap();
    let joint = RigidPlastic::coulomb(0.0, 0.5, true).unwrap();
    match model.add_contacts(low, Partner::Support(floor), joint) {
        Err(DismechError::Limit(LimitError::ContactNotTouching { gap, partner, .. })) => {
            assert!((gap - 1e-3).abs() < 1e-12, "gap {gap}");
            assert!(
                matches!(partner, NamedPartner::Support { support, .. } if support == floor),
                "{partner:?}"
            );
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        model.add_contacts(low, Partner::Body(high), joint),
        Err(DismechError::Limit(LimitError::ContactNotTouching { .. }))
    ));
    assert!(matches!(
        model.add_contacts(low, Partner::Body(high), joint),
        Err(DismechError::Limit(LimitError::ContactNotTouching {
            partner: NamedPartner::Element(j),
            ..
        })) if j == high
    ));
    assert!(matches!(
        model.add_contacts(low, Partner::Body(low), joint),
        Err(DismechError::Limit(LimitError::SelfContact { .. }))
    ));
    // Stacked within the tolerance, a face on a face gives its two ends.
    let top = model
        .add_shape(square(), Pose2::new(0.0, 1.5 + 1e-3 + 5e-7, 0.0), true)
        .unwrap();
    let joints = model.add_contacts(low, Partner::Body(top), joint).unwrap();
    assert_eq!(joints.len(), 2);
    for c in joints {
        let contact = &model.contacts()[c];
        assert!((contact.normal - Vec2::y()).norm() < 1e-12);
        assert!((contact.point.x.abs() - 0.5).abs() < 1e-9);
    }
}

/// An ellipse on a support touches it at its lowest point towards it;
/// declaring a pair again is refused and leaves the model as it was.
#[test]
fn ellipse_on_a_floor_touches_at_its_lowest_point_and_pairs_are_all_or_none() {
    let mut model = LimitModel::new(1e-9).unwrap();
    let floor = model
        .add_support("floor", Point::origin(), Vec2::y(), Vec2::zeros())
        .unwrap();
    let (a, b, angle) = (0.2f64, 0.1f64, 0.4f64);
    let height = ((a * angle.sin()).powi(2) + (b * angle.cos()).powi(2)).sqrt();
    let ellipse = model
        .add_shape(
            Ellipse::new(a, b).unwrap().into(),
            Pose2::new(0.3, height, angle),
            true,
        )
        .unwrap();
    let joint = RigidPlastic::coulomb(0.0, 0.5, true).unwrap();
    let found = model
        .add_contacts(ellipse, Partner::Support(floor), joint)
        .unwrap();
    assert_eq!(found.len(), 1);
    let contact = model.contacts()[found[0]];
    assert!(contact.point.y.abs() < 1e-12, "{:?}", contact.point);
    assert!((contact.normal + Vec2::y()).norm() < 1e-12);
    // The lowest point of the tilted ellipse lies off its centre's
    // vertical: found here by sampling its boundary.
    let (sin, cos) = angle.sin_cos();
    let lowest = (0..200_000)
        .map(|k| k as f64 * std::f64::consts::TAU / 200_000.0)
        .map(|t| {
            let (x, y) = (a * t.cos(), b * t.sin());
            (0.3 + x * cos - y * sin, height + x * sin + y * cos)
        })
        .fold((0.0, f64::INFINITY), |m, p| if p.1 < m.1 { p } else { m });
    assert!(lowest.1.abs() < 1e-9, "{lowest:?}");
    assert!(
        (contact.point.x - lowest.0).abs() < 1e-4,
        "{} vs {}",
        contact.point.x,
        lowest.0
    );
    assert!((contact.point.x - 0.3).abs() > 0.05);
    // A block with two corners on the floor, declared twice: the second
    // declaration is refused and adds nothing.
    let block = model
        .add_shape(
            Polygon::rectangle(1.0, 1.0).unwrap().into(),
            Pose2::new(3.0, 0.5, 0.0),
            true,
        )
        .unwrap();
    assert_eq!(
        model
            .add_contacts(block, Partner::Support(floor), joint)
            .unwrap()
            .len(),
        2
    );
    let before = model.contacts().len();
    assert!(matches!(
        model.add_contacts(block, Partner::Support(floor), joint),
        Err(DismechError::Limit(LimitError::DuplicateContact { .. }))
    ));
    assert_eq!(model.contacts().len(), before);
}

/// Blocks of a stack bond meet corner to corner: A and B side by side on
/// the ground, D on B, so D's bottom-left corner meets A's top-right
/// corner at a point. That point has no contact normal and makes no
/// contact; pushed to the left at its centre, D slides over B at
/// λ = μ W = 5 (a contact with a normal between the two faces would lock
/// the slide and give 10).
#[test]
fn corners_meeting_at_a_point_make_no_contact() {
    let mut model = LimitModel::new(1e-9).unwrap();
    let ground = model
        .add_support("ground", Point::origin(), Vec2::y(), Vec2::zeros())
        .unwrap();
    let square = || Polygon::rectangle(1.0, 1.0).unwrap().into();
    let a = model
        .add_shape(square(), Pose2::new(0.5, 0.5, 0.0), true)
        .unwrap();
    let b = model
        .add_shape(square(), Pose2::new(1.5, 0.5, 0.0), true)
        .unwrap();
    let d = model
        .add_shape(square(), Pose2::new(1.5, 1.5, 0.0), true)
        .unwrap();
    for body in [a, b, d] {
        model.set_load(body, Vec2::new(0.0, -10.0)).unwrap();
    }
    let joint = RigidPlastic::coulomb(0.0, 0.5, true).unwrap();
    for (body, partner) in [
        (a, Partner::Support(ground)),
        (b, Partner::Support(ground)),
        (a, Partner::Body(b)),
        (b, Partner::Body(d)),
    ] {
        assert_eq!(model.add_contacts(body, partner, joint).unwrap().len(), 2);
    }
    assert!(model
        .add_contacts(a, Partner::Body(d), joint)
        .unwrap()
        .is_empty());
    model
        .set_live_load(d, Vec2::new(-1.0, 0.0), Point::new(1.5, 1.5))
        .unwrap();
    let mut solver = LinearProgramSolver::default();
    for result in [
        analyse(&model, &mut solver).unwrap(),
        analyse_static(&model, &mut solver).unwrap(),
    ] {
        assert_eq!(result.status, LimitStatus::Collapse);
        let lambda = result.load.unwrap();
        assert!((lambda - 5.0).abs() < 1e-6, "λ = {lambda}");
    }
}
