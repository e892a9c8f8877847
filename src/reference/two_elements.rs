//! The two-element example of paper 002 (Yamada & Tamura 2000, §2.2,
//! Fig. 3), whose limit load `(1 + √2) C` is known in closed form.

use crate::error::Result;
use crate::law::RigidPlastic;
use crate::limit::{LimitModel, Partner};
use crate::math::{Point, Vec2};

/// The two-element example of §2.2 (Fig. 3): element 1 at the origin held
/// by a left wall and a floor (so that it can only rotate), element 2 at
/// α = 45° pushed in −x by a plate; every contact, plate included, has
/// strength `cohesion`; R = 1. The paper's limit load is (1 + √2)C.
///
/// # Errors
/// [`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter)
/// naming `contact cohesion C` when `cohesion` is negative or not finite
/// ([`RigidPlastic::cohesive`]); the fixed geometry itself is valid.
pub fn two_elements(cohesion: f64) -> Result<LimitModel> {
    let law = RigidPlastic::cohesive(cohesion)?;
    let d = std::f64::consts::SQRT_2;
    let mut m = LimitModel::new(1e-9)?;
    let e1 = m.add_body(Point::new(0.0, 0.0), 1.0, true)?;
    let e2 = m.add_body(Point::new(d, d), 1.0, true)?;
    let left = m.add_support(
        "left wall",
        Point::new(-1.0, 0.0),
        Vec2::new(1.0, 0.0),
        Vec2::zeros(),
    )?;
    let floor = m.add_support(
        "floor",
        Point::new(0.0, -1.0),
        Vec2::new(0.0, 1.0),
        Vec2::zeros(),
    )?;
    let plate = m.add_support(
        "loading plate",
        Point::new(d + 1.0, 0.0),
        Vec2::new(-1.0, 0.0),
        Vec2::new(-1.0, 0.0),
    )?;
    m.add_contact(e1, Partner::Support(left), law)?;
    m.add_contact(e1, Partner::Support(floor), law)?;
    m.add_contact(e1, Partner::Body(e2), law)?;
    m.add_contact(e2, Partner::Support(plate), law)?;
    Ok(m)
}

/// The limit load of [`two_elements`]: `P = (1 + √2) C`.
pub fn two_elements_limit_load(cohesion: f64) -> f64 {
    (1.0 + std::f64::consts::SQRT_2) * cohesion
}
