//! Rigid-plastic limit analysis by LP: exact small cases, static
//! admissibility of the dual forces, and bad input.

use dismech::error::DismechError;
use dismech::law::RigidPlastic;
use dismech::limit::lattice::Lattice;
use dismech::limit::LimitError;
use dismech::limit::{analyse, LimitModel, LimitResult, LimitStatus, NamedPartner, Partner};
use dismech::lp::LinearProgramSolver;
use dismech::math::{Point, Vec2};
use dismech::reference::lattice_limit_load::{eq32, eq38};
use dismech::reference::{two_elements, two_elements_limit_load};
use std::f64::consts::SQRT_2;

fn solve(model: &LimitModel) -> LimitResult {
    analyse(model, &mut LinearProgramSolver::default()).unwrap()
}

/// Every element is in equilibrium under its load and the dual contact
/// forces, and every shear force is within strength: the dual is a
/// statically admissible field, so the static load is a lower bound.
fn assert_statically_admissible(model: &LimitModel, r: &LimitResult) {
    let mut force = vec![Vec2::zeros(); model.bodies().len()];
    let mut moment = vec![0.0; model.bodies().len()];
    for (c, contact) in model.contacts().iter().enumerate() {
        let on_b = contact.normal * r.normal_force[c] - contact.tangent() * r.shear_force[c];
        let a = contact.body;
        force[a] -= on_b;
        let ra = contact.point - model.bodies()[a].centre;
        moment[a] -= ra.x * on_b.y - ra.y * on_b.x;
        if let Partner::Body(b) = contact.partner {
            force[b] += on_b;
            let rb = contact.point - model.bodies()[b].centre;
            moment[b] += rb.x * on_b.y - rb.y * on_b.x;
        }
        let strength = contact.law.cohesion() + contact.law.friction() * r.normal_force[c].max(0.0);
        assert!(
            r.shear_force[c].abs() <= strength + 1e-6,
            "contact {c}: |T| = {} > {}",
            r.shear_force[c],
            strength
        );
    }
    let (kinematic, statics) = (r.kinematic_load.unwrap(), r.static_load.unwrap());
    let scale = 1.0 + kinematic.abs();
    for (i, b) in model.bodies().iter().enumerate() {
        let net = force[i] + b.load;
        assert!(
            net.norm() <= 1e-6 * scale,
            "element {i} out of balance by {net}"
        );
        if b.rotates {
            assert!(
                moment[i].abs() <= 1e-6 * scale,
                "element {i}: moment {}",
                moment[i]
            );
        }
    }
    assert!(
        (kinematic - statics).abs() <= 1e-6 * scale,
        "primal {kinematic} != dual {statics}"
    );
}

/// One element of radius 1 and weight `w` resting on a fixed floor (the
/// line y = 0) through a contact with `floor_law`; returns the model and
/// the element.
fn element_on_floor(rotates: bool, w: f64, floor_law: RigidPlastic) -> (LimitModel, usize) {
    let mut m = LimitModel::new(1e-9).unwrap();
    let e = m.add_body(Point::new(0.0, 1.0), 1.0, rotates).unwrap();
    m.set_load(e, Vec2::new(0.0, -w)).unwrap();
    let floor = m
        .add_support(
            "floor",
            Point::new(0.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::zeros(),
        )
        .unwrap();
    m.add_contact(e, Partner::Support(floor), floor_law)
        .unwrap();
    (m, e)
}

/// [`element_on_floor`] pushed sideways (−x) by a smooth plate at unit
/// speed.
fn pushed_element_on_floor(rotates: bool, w: f64, floor_law: RigidPlastic) -> LimitModel {
    let (mut m, e) = element_on_floor(rotates, w, floor_law);
    let plate = m
        .add_support(
            "plate",
            Point::new(1.0, 0.0),
            Vec2::new(-1.0, 0.0),
            Vec2::new(-1.0, 0.0),
        )
        .unwrap();
    m.add_contact(
        e,
        Partner::Support(plate),
        RigidPlastic::cohesive(0.0).unwrap(),
    )
    .unwrap();
    m
}

/// §2.2: two elements at α = 45°; element 1 held by two walls can only
/// rotate; element 2 is pushed by a plate; all strengths C.
#[test]
fn two_element_example_needs_one_plus_root_two_c() {
    let c = 1.0;
    let m = two_elements(c).unwrap();
    let result = solve(&m);
    assert_eq!(result.status, LimitStatus::Collapse);
    approx::assert_relative_eq!(
        result.load.unwrap(),
        two_elements_limit_load(c),
        max_relative = 1e-7
    );
    assert_statically_admissible(&m, &result);
}

#[test]
fn rolling_u_model_reproduces_eqs_26_to_28() {
    for (k, np, expected) in [
        (2, 1, 1.0 + SQRT_2),
        (4, 1, 1.0 + 3.5 * SQRT_2),
        (4, 2, 1.0 + 5.0 * SQRT_2),
    ] {
        let model = Lattice::u_model(k, k, np, true).build().unwrap();
        let r = solve(&model);
        approx::assert_relative_eq!(r.load.unwrap(), expected, max_relative = 1e-7);
        assert_statically_admissible(&model, &r);
    }
}

/// Where Table 1 and eq. (32) agree the LP gives both; at (8, 2) it gives
/// Table 1's 14.59, below eq. (32): eq. (32) is the load of one guessed
/// mechanism, an upper bound that the LP improves on.
#[test]
fn rolling_u_model_at_8_2_is_below_eq32() {
    let model = Lattice::u_model(8, 8, 2, true).build().unwrap();
    let r = solve(&model);
    assert!(
        (r.load.unwrap() - 14.59).abs() < 0.006,
        "P = {}",
        r.load.unwrap()
    );
    assert!(r.load.unwrap() < eq32(8, 2) - 0.05);
    assert_statically_admissible(&model, &r);
}

#[test]
fn non_rolling_u_model_follows_eq38() {
    for k in [2, 4, 6] {
        for np in 1..=k / 2 {
            let model = Lattice::u_model(k, k, np, false).build().unwrap();
            let r = solve(&model);
            approx::assert_relative_eq!(r.load.unwrap(), eq38(k, np), max_relative = 1e-7);
            assert_statically_admissible(&model, &r);
        }
    }
}

#[test]
fn unequal_lattices_solve_or_report_locked() {
    let r = solve(&Lattice::u_model(4, 8, 1, true).build().unwrap());
    assert_eq!(r.status, LimitStatus::Collapse);
    assert!(r.load.unwrap() > 0.0);
    let model = Lattice::u_model(8, 4, 1, true).build().unwrap();
    let locked = solve(&model);
    assert_eq!(locked.status, LimitStatus::Locked);
    assert_eq!(locked.load, None);
    // A locked analysis has no mechanism to test for uniqueness; the
    // error carries the status, to be matched on.
    match dismech::limit::mechanism_uniqueness(&model, &mut LinearProgramSolver::default(), &locked)
    {
        Err(err @ DismechError::Limit(LimitError::NoLimitLoad { .. })) => {
            assert!(
                matches!(
                    err,
                    DismechError::Limit(LimitError::NoLimitLoad {
                        status: LimitStatus::Locked,
                        ..
                    })
                ),
                "{err}"
            );
            assert!(err.to_string().contains("status Locked"), "{err}");
        }
        other => panic!("{other:?}"),
    }
}

/// A single non-rolling element of weight W on a rough floor (cohesion C,
/// friction φ, associated flow) pushed sideways by a smooth plate needs
/// P = C + W tan φ: sliding dilates by tan φ and lifts the weight. If the
/// element may roll it rolls on the floor without slipping: no slip, no
/// dilation, no dissipation, so P = 0.
#[test]
fn mohr_coulomb_block_needs_c_plus_w_tan_phi_and_rolls_for_free() {
    let (c, w, phi) = (3.0, 10.0, 30f64.to_radians());
    for rotates in [false, true] {
        let m = pushed_element_on_floor(
            rotates,
            w,
            RigidPlastic::coulomb(c, phi.tan(), true).unwrap(),
        );
        let r = solve(&m);
        let expected = if rotates { 0.0 } else { c + w * phi.tan() };
        assert!(
            (r.load.unwrap() - expected).abs() < 1e-6,
            "rolling {rotates}: P = {}",
            r.load.unwrap()
        );
        assert_statically_admissible(&m, &r);
    }
}

/// A contact that may open does so for free: an element of weight W on a
/// cohesive floor, pushed by a smooth plate inclined at 45°, either slides
/// (cost √2 C) or lifts off (cost √2 W); bilateral, it can only slide.
#[test]
fn unilateral_contact_opens_without_dissipation() {
    let (c, w) = (5.0f64, 2.0f64);
    let n_plate = Vec2::new(-1.0, 1.0) / SQRT_2;
    for (unilateral, expected) in [(true, SQRT_2 * c.min(w)), (false, SQRT_2 * c)] {
        let floor_law = RigidPlastic::coulomb(c, 0.0, unilateral).unwrap();
        let (mut m, e) = element_on_floor(false, w, floor_law);
        let contact_point = Point::new(0.0, 1.0) - n_plate;
        let plate = m
            .add_support("plate", contact_point, n_plate, n_plate)
            .unwrap();
        m.add_contact(
            e,
            Partner::Support(plate),
            RigidPlastic::cohesive(0.0).unwrap(),
        )
        .unwrap();
        let r = solve(&m);
        assert!(
            (r.load.unwrap() - expected).abs() < 1e-6,
            "unilateral {unilateral}: P = {}",
            r.load.unwrap()
        );
        if unilateral {
            approx::assert_relative_eq!(r.opening[0], SQRT_2, max_relative = 1e-6);
            assert!(
                r.normal_force[0].abs() < 1e-6,
                "an open contact carries {}",
                r.normal_force[0]
            );
        }
        assert_statically_admissible(&m, &r);
    }
}

#[test]
fn limit_model_bad_input_is_a_typed_error() {
    let mut m = LimitModel::new(1e-9).unwrap();
    let a = m.add_body(Point::new(0.0, 0.0), 1.0, true).unwrap();
    let b = m.add_body(Point::new(2.5, 0.0), 1.0, true).unwrap();
    let law = RigidPlastic::cohesive(1.0).unwrap();
    match m.add_contact(a, Partner::Body(b), law).unwrap_err() {
        DismechError::Limit(LimitError::ContactNotTouching {
            contact: 0,
            body: 0,
            gap,
            ..
        }) => approx::assert_relative_eq!(gap, 0.5),
        other => panic!("{other}"),
    }
    assert!(matches!(
        RigidPlastic::cohesive(-1.0),
        Err(DismechError::InvalidParameter { .. })
    ));
    assert!(matches!(
        RigidPlastic::from_friction_angle_deg(1.0, 90.0, false),
        Err(DismechError::InvalidParameter { .. })
    ));
    assert!(matches!(
        RigidPlastic::coulomb(1.0, -0.1, false),
        Err(DismechError::InvalidParameter { .. })
    ));
    assert!(matches!(
        RigidPlastic::coulomb(1.0, f64::INFINITY, false),
        Err(DismechError::InvalidParameter { .. })
    ));
    assert!(matches!(
        Lattice::u_model(3, 3, 1, true).build(),
        Err(DismechError::InvalidParameter {
            name: "m (columns)",
            ..
        })
    ));
    m.add_support(
        "plate",
        Point::new(10.0, 0.0),
        Vec2::new(-1.0, 0.0),
        Vec2::new(-1.0, 0.0),
    )
    .unwrap();
    let plate = m.supports().len() - 1;
    match analyse(&m, &mut LinearProgramSolver::default()) {
        Err(DismechError::Limit(LimitError::PlateTouchesNothing { support, ref name })) => {
            assert_eq!(support, plate);
            assert_eq!(name, "plate");
        }
        other => panic!("{other:?}"),
    }
}

/// DEM → LP: a disc settled by the DEM into the corner of a box under a
/// gravity with a sideways part, then pushed off the left wall (the plate,
/// smooth) across the floor (cohesion C, friction φ, associated flow): the
/// LP of the converted packing must give P = C + m|g_x| + m|g_y| tan φ with
/// the DEM's mass and positions.
#[test]
fn settled_disc_converted_from_dem_needs_the_exact_push() {
    use dismech::dem::DemSimulation;
    use dismech::explicit::{DemSettings, RestCriterion};
    use dismech::integrate::ExplicitEuler;
    use dismech::limit::{model_from_packing, PackingLimitSettings};
    use dismech::scene::{Frame, Scene};

    let g = Vec2::new(-5.0, -9.81);
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), g).unwrap();
    scene
        .add_circle(Point::new(0.2, 0.2), 0.07, 2690.0)
        .unwrap();
    // Paper 000's law with Example 1's material (E = 750 kgf/cm², ν = 0.3,
    // k_s/k_n = 0.25, μ = 0.577).
    let law = dismech::law::SpringDashpotCoulomb::katsuki(750.0 * 9.80665 / 1e-4, 0.3, 0.25, 0.577)
        .unwrap();
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, DemSettings::default()).unwrap();
    sim.run_to_rest(&RestCriterion::default(), |_, _| {})
        .unwrap();
    assert_eq!(
        sim.contacts().len(),
        2,
        "the disc should rest in the corner"
    );

    let (c, phi) = (50.0, 25f64.to_radians());
    let settings = PackingLimitSettings {
        rolling: false,
        contact_law: RigidPlastic::cohesive(1.0).unwrap(),
        wall_law: RigidPlastic::coulomb(c, phi.tan(), true).unwrap(),
        plate_law: RigidPlastic::coulomb(0.0, 0.0, true).unwrap(),
        plate_wall: "left".into(),
        self_weight: true,
    };
    let model = model_from_packing(sim.scene(), sim.contacts(), &settings).unwrap();
    let r = solve(&model);
    let m = sim.scene().particles[0].mass;
    let expected = c + m * g.x.abs() + m * g.y.abs() * phi.tan();
    approx::assert_relative_eq!(r.load.unwrap(), expected, max_relative = 1e-6);
    assert_statically_admissible(&model, &r);
}

/// The rolling (2,2,1) optimum is a face, not a point: one element between
/// two cohesive contacts can share the slip between them in many ways. The
/// vertex mechanism recovered from that face dissipates exactly P. The
/// non-rolling (2,2,1) optimum is unique.
#[test]
fn non_unique_optimum_is_detected_and_a_vertex_mechanism_recovered() {
    use dismech::limit::mechanism_uniqueness;
    let mut solver = LinearProgramSolver::default();
    for (rolling, unique) in [(true, false), (false, true)] {
        let model = Lattice::u_model(2, 2, 1, rolling).build().unwrap();
        let r = analyse(&model, &mut solver).unwrap();
        let u = mechanism_uniqueness(&model, &mut solver, &r).unwrap();
        assert_eq!(u.unique, unique, "rolling {rolling}: spread {}", u.spread);
        let dissipation: f64 = model
            .contacts()
            .iter()
            .zip(&u.vertex.slip)
            .map(|(c, s)| c.law.cohesion() * s.abs())
            .sum();
        approx::assert_relative_eq!(dissipation, r.kinematic_load.unwrap(), max_relative = 1e-5);
    }
}

/// An element that touches only smooth contacts can move at no cost: the
/// optimal face is unbounded, which the uniqueness test reports as not
/// unique (infinite spread) instead of failing.
#[test]
fn free_element_makes_the_optimum_non_unique_without_failing() {
    use dismech::limit::mechanism_uniqueness;
    let mut model = two_elements(1.0).unwrap();
    // A rattler: an element resting on a smooth floor, touching nothing else.
    let rattler = model.add_body(Point::new(10.0, 1.0), 1.0, true).unwrap();
    let floor = model
        .add_support(
            "smooth floor",
            Point::new(10.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::zeros(),
        )
        .unwrap();
    model
        .add_contact(
            rattler,
            Partner::Support(floor),
            RigidPlastic::cohesive(0.0).unwrap(),
        )
        .unwrap();
    let mut solver = LinearProgramSolver::default();
    let r = analyse(&model, &mut solver).unwrap();
    approx::assert_relative_eq!(r.load.unwrap(), 1.0 + SQRT_2, max_relative = 1e-7);
    let u = mechanism_uniqueness(&model, &mut solver, &r).unwrap();
    assert!(!u.unique && u.spread.is_infinite(), "{:?}", u.spread);
}

/// The static LP (forces as unknowns) gives the same limit load as the
/// kinematic LP, and its multipliers are the same mechanism where that is
/// unique.
#[test]
fn static_lp_gives_the_kinematic_limit_load() {
    use dismech::limit::analyse_static;
    let mut solver = LinearProgramSolver::default();
    let mut models = vec![two_elements(1.0).unwrap()];
    for (k, np, rolling) in [
        (2, 1, true),
        (4, 2, true),
        (8, 2, true),
        (6, 2, false),
        (10, 2, false),
    ] {
        models.push(Lattice::u_model(k, k, np, rolling).build().unwrap());
    }
    let mc = pushed_element_on_floor(
        false,
        10.0,
        RigidPlastic::coulomb(3.0, 0.5f64.tan(), true).unwrap(),
    );
    models.push(mc);
    for (m, model) in models.iter().enumerate() {
        let kinematic = analyse(model, &mut solver).unwrap();
        let statics = analyse_static(model, &mut solver).unwrap();
        assert_eq!(statics.status, LimitStatus::Collapse);
        approx::assert_relative_eq!(
            statics.load.unwrap(),
            kinematic.load.unwrap(),
            max_relative = 1e-6
        );
        assert_statically_admissible(model, &statics);
        if m == 5 {
            // Non-rolling (10,10,2): a unique mechanism.
            for (a, b) in statics.velocities.iter().zip(&kinematic.velocities) {
                assert!((a.0 - b.0).norm() < 1e-5, "{:?} vs {:?}", a.0, b.0);
            }
        }
    }
    let locked = analyse_static(
        &Lattice::u_model(8, 4, 1, true).build().unwrap(),
        &mut solver,
    )
    .unwrap();
    assert_eq!(locked.status, LimitStatus::Locked);
}

#[test]
fn duplicate_contact_is_refused() {
    // The two-element example with every contact declared twice needed
    // twice the load: each strength counted twice.
    let mut m = two_elements(1.0).unwrap();
    let (left, e1, e2) = (Partner::Support(0), 0, 1);
    let law = RigidPlastic::cohesive(1.0).unwrap();
    match m.add_contact(e1, left, law) {
        Err(DismechError::Limit(LimitError::DuplicateContact {
            contact,
            existing,
            body,
            partner,
            ..
        })) => {
            assert_eq!((contact, existing, body), (4, 0, e1));
            assert_eq!(
                partner,
                NamedPartner::Support {
                    support: 0,
                    name: "left wall".into(),
                }
            );
            assert_eq!(partner.to_string(), "support `left wall`");
        }
        other => panic!("{other:?}"),
    }
    // The same pair named the other way round, by circle geometry or at the
    // same point.
    assert!(matches!(
        m.add_contact(e2, Partner::Body(e1), law),
        Err(DismechError::Limit(LimitError::DuplicateContact {
            existing: 2,
            ..
        }))
    ));
    assert!(matches!(
        m.add_contact(e2, Partner::Body(e1), law),
        Err(DismechError::Limit(LimitError::DuplicateContact {
            partner: NamedPartner::Element(0),
            ..
        }))
    ));
    let point = m.contacts()[2].point;
    let normal = m.contacts()[2].normal;
    assert!(matches!(
        m.add_contact_at(e2, Partner::Body(e1), law, point, -normal),
        Err(DismechError::Limit(LimitError::DuplicateContact {
            existing: 2,
            ..
        }))
    ));
    assert_eq!(m.contacts().len(), 4);
    approx::assert_relative_eq!(
        solve(&m).load.unwrap(),
        two_elements_limit_load(1.0),
        max_relative = 1e-7
    );
    // Two circles touch at one point: with a loose tolerance, the contact
    // of overlapping circles named the other way round (its point on the
    // other surface) is the same contact.
    let mut m = LimitModel::new(0.01).unwrap();
    let a = m.add_body(Point::new(0.0, 0.0), 1.0, true).unwrap();
    let b = m.add_body(Point::new(1.995, 0.0), 1.0, true).unwrap();
    m.add_contact(a, Partner::Body(b), law).unwrap();
    assert!(matches!(
        m.add_contact(b, Partner::Body(a), law),
        Err(DismechError::Limit(LimitError::DuplicateContact {
            existing: 0,
            ..
        }))
    ));
    // Two points of one pair are two contacts: a second corner on a floor.
    let (mut m, e) = element_on_floor(false, 1.0, RigidPlastic::cohesive(1.0).unwrap());
    let floor = Partner::Support(0);
    m.add_contact_at(e, floor, law, Point::new(0.5, 0.0), -Vec2::y())
        .unwrap();
    assert!(matches!(
        m.add_contact_at(e, floor, law, Point::new(0.5, 0.0), -Vec2::y()),
        Err(DismechError::Limit(LimitError::DuplicateContact { .. }))
    ));
}

#[test]
fn two_bodies_at_one_point_are_refused() {
    // A third element at the second's centre carried the load a second
    // time: the two-element example needed 2 (1 + √2) C.
    let mut m = two_elements(1.0).unwrap();
    let centre = m.bodies()[1].centre;
    match m.add_body(centre, 1.0, true) {
        Err(DismechError::Limit(LimitError::DuplicateBody {
            body,
            existing,
            x,
            y,
            ..
        })) => {
            assert_eq!((body, existing), (2, 1));
            assert_eq!((x, y), (centre.x, centre.y));
        }
        other => panic!("{other:?}"),
    }
    // Whatever the shape, and within the tolerance (1e-9 m here).
    let square = dismech::shape::Polygon::rectangle(1.0, 1.0).unwrap();
    let near = dismech::math::Pose2::new(centre.x + 0.5e-9, centre.y, 0.3);
    assert!(matches!(
        m.add_shape(square.into(), near, false),
        Err(DismechError::Limit(LimitError::DuplicateBody {
            existing: 1,
            ..
        }))
    ));
    assert_eq!(m.bodies().len(), 2);
    // A loose contact tolerance (a DEM packing's overlaps) does not make
    // near neighbours one point: within a millionth of the radius they are.
    let mut m = LimitModel::new(0.1).unwrap();
    m.add_body(Point::new(0.0, 0.0), 1.0, true).unwrap();
    m.add_body(Point::new(0.05, 0.0), 1.0, true).unwrap();
    assert!(matches!(
        m.add_body(Point::new(0.05 + 0.5e-6, 0.0), 1.0, true),
        Err(DismechError::Limit(LimitError::DuplicateBody {
            body: 2,
            existing: 1,
            ..
        }))
    ));
}

#[test]
fn huge_lattice_is_refused() {
    use dismech::limit::lattice::MAX_LATTICE_ELEMENTS;
    for (m, n) in [(2, 1_000_000), (2, usize::MAX), (usize::MAX - 1, 3)] {
        match Lattice::l_model(m, n, true).build() {
            Err(DismechError::Limit(LimitError::LatticeTooLarge {
                m: gm,
                n: gn,
                limit,
            })) => {
                assert_eq!((gm, gn, limit), (m, n, MAX_LATTICE_ELEMENTS));
            }
            other => panic!("({m}, {n}): {:?}", other.map(|_| "built")),
        }
    }
    // The cap itself is accepted.
    let model = Lattice::l_model(2, MAX_LATTICE_ELEMENTS / 2, true)
        .build()
        .unwrap();
    assert_eq!(model.bodies().len(), MAX_LATTICE_ELEMENTS);
}

#[test]
fn failed_solve_reports_no_load() {
    // Two interior-point iterations: no optimum, and no load (the kinematic
    // LP's last iterate read 11.14 as a load before).
    use dismech::limit::analyse_static;
    let model = Lattice::u_model(8, 8, 2, true).build().unwrap();
    let mut solver = LinearProgramSolver {
        max_iterations: 2,
        ..LinearProgramSolver::default()
    };
    for r in [
        analyse(&model, &mut solver).unwrap(),
        analyse_static(&model, &mut solver).unwrap(),
    ] {
        assert!(
            matches!(r.status, LimitStatus::SolverTrouble(_)),
            "{:?}",
            r.status
        );
        assert_eq!(
            (r.load, r.kinematic_load, r.static_load),
            (None, None, None)
        );
    }
    // A locked lattice has none either.
    let locked = solve(&Lattice::u_model(8, 4, 1, true).build().unwrap());
    assert_eq!(locked.status, LimitStatus::Locked);
    assert_eq!((locked.kinematic_load, locked.static_load), (None, None));
}
