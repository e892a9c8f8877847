//! Values checked where the library does not check them, and the
//! library's typed errors turned into refusals that name the key that gave
//! the offending value.

use dismech::error::DismechError;
use dismech::implicit::ImplicitError;
use dismech::slope::SlopeError;

use super::source::{KeyPath, Located, Source};

/// A refusal, boxed (the error type of the builders).
pub type Refusal = Box<Located>;

/// The library's name of a value and the key of the scenario that gives
/// it, for one call of a constructor.
pub type Names<'a> = &'a [(&'a str, &'a str)];

/// The refusal of `error`, returned by a constructor called with values
/// of the table at `table`: an [`DismechError::InvalidParameter`] whose
/// name `names` lists is placed at that key; any other error at the table.
pub fn named(
    source: &Source<'_>,
    table: &KeyPath,
    names: Names<'_>,
    error: DismechError,
) -> Refusal {
    let key = match &error {
        DismechError::InvalidParameter { name, .. }
        | DismechError::Implicit(ImplicitError::InvalidBlock { name, .. }) => {
            names.iter().find(|(n, _)| n == name).map(|(_, key)| *key)
        }
        DismechError::Slope(SlopeError::InvalidRange { name, .. }) => {
            names.iter().find(|(n, _)| n == name).map(|(_, key)| *key)
        }
        _ => None,
    };
    let path = key.map_or_else(|| table.clone(), |k| table.key(k));
    Box::new(source.at_key(&path, error.to_string()))
}

/// `Ok(value)` where `ok(value)`, else a refusal at `path` saying
/// `requirement`.
pub fn require<T: std::fmt::Display + Copy>(
    source: &Source<'_>,
    path: &KeyPath,
    value: T,
    ok: bool,
    requirement: &str,
) -> Result<T, Refusal> {
    if ok {
        Ok(value)
    } else {
        Err(Box::new(
            source.at_key(path, format!("{value} is refused: {requirement}")),
        ))
    }
}

/// A finite value > 0 at `path`.
pub fn positive(source: &Source<'_>, path: &KeyPath, value: f64) -> Result<f64, Refusal> {
    require(
        source,
        path,
        value,
        value.is_finite() && value > 0.0,
        "must be finite and > 0",
    )
}

/// A finite value ≥ 0 at `path`.
pub fn non_negative(source: &Source<'_>, path: &KeyPath, value: f64) -> Result<f64, Refusal> {
    require(
        source,
        path,
        value,
        value.is_finite() && value >= 0.0,
        "must be finite and >= 0",
    )
}

/// Finite components at `path`.
pub fn finite2(source: &Source<'_>, path: &KeyPath, value: [f64; 2]) -> Result<[f64; 2], Refusal> {
    if value.iter().all(|v| v.is_finite()) {
        Ok(value)
    } else {
        Err(Box::new(source.at_key(
            path,
            format!(
                "[{}, {}] is refused: both components must be finite",
                value[0], value[1]
            ),
        )))
    }
}

/// A moving wall's velocity at `path`: finite and not zero.
pub fn wall_velocity(
    source: &Source<'_>,
    path: &KeyPath,
    value: [f64; 2],
) -> Result<[f64; 2], Refusal> {
    let v = finite2(source, path, value)?;
    if v == [0.0, 0.0] {
        return Err(Box::new(source.at_key(
            path,
            "[0, 0] is refused: a moving wall needs a velocity other than zero (leave the key out for a fixed wall)",
        )));
    }
    Ok(v)
}

/// A refusal of a combination of keys that the library cannot compose.
pub fn combination(source: &Source<'_>, paths: &[&KeyPath], message: &str) -> Refusal {
    Box::new(source.at_keys(paths, message))
}

/// Where `present`, the refusal of the key `other` beside the chosen
/// `driver.kind`, saying `message`: a slot or load the driver does not
/// take.
pub fn refuse_beside_driver(
    source: &Source<'_>,
    present: bool,
    other: KeyPath,
    message: &str,
) -> Result<(), Refusal> {
    if present {
        let kind = KeyPath::root("driver").key("kind");
        return Err(combination(source, &[&kind, &other], message));
    }
    Ok(())
}

/// The friction coefficient of the table at `table`: its `friction` (μ),
/// or its `friction_angle` (φ in degrees, μ = tan φ), not both;
/// `default` where neither is given (none: one is required).
pub fn friction(
    source: &Source<'_>,
    table: &KeyPath,
    friction: Option<f64>,
    angle: Option<f64>,
    default: Option<f64>,
) -> Result<f64, Refusal> {
    match (friction, angle) {
        (Some(_), Some(_)) => Err(combination(
            source,
            &[&table.key("friction"), &table.key("friction_angle")],
            "give the friction coefficient `friction` (mu = tan phi) or the angle `friction_angle` (degrees), not both",
        )),
        (Some(mu), None) => non_negative(source, &table.key("friction"), mu),
        (None, Some(phi)) => dismech::law::friction_from_degrees(phi)
            .map_err(|e| Box::new(source.at_key(&table.key("friction_angle"), e.to_string()))),
        (None, None) => default.ok_or_else(|| {
            Box::new(source.at_key(
                table,
                "no friction: give `friction` (mu = tan phi) or `friction_angle` (degrees)",
            ))
        }),
    }
}

/// A count that is at least `min` and at most `max`.
pub fn count(
    source: &Source<'_>,
    path: &KeyPath,
    value: usize,
    min: usize,
    max: usize,
) -> Result<usize, Refusal> {
    require(
        source,
        path,
        value,
        (min..=max).contains(&value),
        &format!("must lie in {min}..={max}"),
    )
}
