//! The options of `dismech slope`, each value checked as it is parsed, so
//! that a bad value is refused by the command-line parser with the option's
//! name, the value as written and what it must satisfy (exit status 2).

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use dismech::error::{require_non_negative, require_positive, DismechError};
use dismech::law::friction_from_degrees;
use dismech::slope::Steps;

/// A pore-pressure ratio as given to `--ru`: a constant or a grid file.
#[derive(Debug, Clone, PartialEq)]
pub enum RuArg {
    /// The same r_u everywhere (checked to lie in [0, 1)).
    Constant(f64),
    /// A grid of r_u on the DEM's grid.
    File(PathBuf),
}

/// A strength layer as given to `--layer NAME:BOTTOM:C:PHI:GAMMA`, the
/// numbers checked as parsed.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerArg {
    /// The layer's name.
    pub name: String,
    /// The grid of its bottom elevations.
    pub bottom: PathBuf,
    /// Cohesion c' (Pa).
    pub cohesion: f64,
    /// Friction angle φ' (degrees).
    pub friction_angle: f64,
    /// Unit weight γ (N/m³).
    pub unit_weight: f64,
}

/// The trial surfaces a search runs through.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SearchKind {
    /// Scoops3D's systematic grid of sphere centres and radii.
    Spheres,
    /// r.slope.stability's random ellipsoids along the fall line.
    Ellipsoids,
}

/// The limit-equilibrium method of `--method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Hovland's 3D column method (Hovland 1977): each column's normal
    /// force its weight's component on the base normal, force sums along
    /// the sliding direction.
    Hovland,
    /// Bishop's simplified method in 3D (Hungr 1987): each column's normal
    /// force from its vertical equilibrium, moments about the horizontal
    /// axis through the surface's centre across the sliding direction,
    /// iterated on Fs; a surface with a column of m_alpha at or below
    /// --m-alpha-floor (0.2 by default) is refused.
    Bishop,
}

impl SlopeArgs {
    /// Bishop's settings of `--m-alpha-floor` (the library's default
    /// without it).
    ///
    /// # Errors
    /// [`SlopeError::Argument`](super::SlopeError::Argument) naming
    /// `--m-alpha-floor` for a floor given with a method other than
    /// Bishop's (it would be ignored), or one the library refuses.
    pub fn bishop(&self) -> Result<dismech::slope::BishopSettings, super::SlopeError> {
        let settings = dismech::slope::BishopSettings::default();
        let Some(floor) = self.m_alpha_floor else {
            return Ok(settings);
        };
        let refused = |e| super::SlopeError::argument("--m-alpha-floor", &floor.to_string(), e);
        if self.method != MethodArg::Bishop {
            return Err(refused(DismechError::InvalidParameter {
                name: "Bishop's m_alpha floor",
                value: floor,
                requirement:
                    "is an option of --method bishop only (with another method it would be ignored)",
            }));
        }
        settings.with_m_alpha_floor(floor).map_err(refused)
    }
}

impl MethodArg {
    /// The library's method.
    pub fn method(self) -> dismech::slope::Method {
        match self {
            Self::Hovland => dismech::slope::Method::Hovland,
            Self::Bishop => dismech::slope::Method::Bishop,
        }
    }

    /// Its name as an option value.
    pub fn name(self) -> &'static str {
        match self {
            Self::Hovland => "hovland",
            Self::Bishop => "bishop",
        }
    }
}

/// A range `MIN:MAX`, with a number of values `MIN:MAX:COUNT` where the
/// option takes one (a single value `V` is `V:V`, one value).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// The first value.
    pub min: f64,
    /// The last value.
    pub max: f64,
    /// How many values, where given.
    pub count: Option<usize>,
}

impl Span {
    /// `(min, max)`.
    pub fn pair(&self) -> (f64, f64) {
        (self.min, self.max)
    }

    /// The values as a grid's [`Steps`], `default_count` of them unless
    /// the option gave a count.
    pub fn steps(&self, default_count: usize) -> Steps {
        Steps {
            min: self.min,
            max: self.max,
            count: self.count.unwrap_or(default_count),
        }
    }
}

impl std::fmt::Display for Span {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.min, self.max)?;
        if let Some(count) = self.count {
            write!(f, ":{count}")?;
        }
        Ok(())
    }
}

/// The options of `dismech slope`.
#[derive(Debug, Clone, Args)]
#[command(allow_negative_numbers = true)]
pub struct SlopeArgs {
    /// Digital elevation model: an ESRI ASCII grid (or a GeoTIFF, `.tif`)
    /// of ground heights (m) on square cells in metres (a projected grid).
    /// No-data cells are allowed; a trial surface over one is refused.
    #[arg(long, value_name = "FILE")]
    pub dem: PathBuf,
    /// Water table: heights of the phreatic surface (m), an ESRI ASCII
    /// grid (or GeoTIFF) on the DEM's grid. Without it the ground is dry.
    #[arg(long, value_name = "FILE")]
    pub water: Option<PathBuf>,
    /// Bedrock: elevations (m) of a surface no slip surface goes below, an
    /// ESRI ASCII grid (or GeoTIFF) on the DEM's grid. A trial surface
    /// that would go deeper follows it (Scoops3D's and r.slope.stability's
    /// truncation); no column where it lies above the ground.
    #[arg(long, value_name = "FILE")]
    pub bedrock: Option<PathBuf>,
    /// Pore-pressure ratio r_u (Bishop & Morgenstern 1960): the pore
    /// pressure on a base is u = r_u σ_v, with σ_v = Σ γ_i t_i the vertical
    /// stress of the ground above it. A constant in [0, 1) or an ESRI ASCII
    /// grid (or GeoTIFF) of r_u on the DEM's grid. Instead of --water.
    #[arg(long, value_name = "VALUE|FILE", conflicts_with = "water", value_parser = parse_ru)]
    pub ru: Option<RuArg>,
    /// A strength layer above the ground of --cohesion, --friction-angle
    /// and --unit-weight (which becomes the last layer, unbounded below):
    /// NAME:BOTTOM:C:PHI:GAMMA, with BOTTOM a grid of the layer's bottom
    /// elevations (m) on the DEM's grid, C the cohesion c' (Pa), PHI the
    /// friction angle φ' (degrees) and GAMMA the unit weight (N/m³).
    /// Repeat it for several layers, top to bottom. A bottom above the
    /// ground or above the layer above is clipped to it. A column weighs
    /// Σ γ_i t_i over the layers above its base; its base takes the
    /// strength of the layer it passes through (Scoops3D's convention).
    #[arg(long = "layer", value_name = "NAME:BOTTOM:C:PHI:GAMMA", value_parser = parse_layer)]
    pub layers: Vec<LayerArg>,
    /// Effective cohesion c' on the slip surface (Pa) (of the last layer,
    /// with --layer).
    #[arg(long, value_name = "PA", value_parser = parse_cohesion)]
    pub cohesion: f64,
    /// Effective friction angle φ' on the slip surface (degrees, in [0,
    /// 90)) (of the last layer, with --layer).
    #[arg(long, value_name = "DEG", value_parser = parse_friction_angle)]
    pub friction_angle: f64,
    /// Total unit weight γ of the ground (N/m³) (of the last layer, with
    /// --layer).
    #[arg(long, value_name = "N_PER_M3", value_parser = parse_unit_weight)]
    pub unit_weight: f64,
    /// Horizontal seismic coefficient k_h (pseudo-static force k_h W along
    /// each surface's sliding direction).
    #[arg(long, value_name = "K", default_value_t = 0.0, value_parser = parse_seismic)]
    pub kh: f64,
    /// Trial surfaces: `spheres` (Scoops3D's systematic grid of centres and
    /// radii) or `ellipsoids` (r.slope.stability's random sampling).
    #[arg(long, value_enum)]
    pub search: SearchKind,
    /// Limit-equilibrium method of each trial surface: `hovland`
    /// (Hovland 1977) or `bishop` (Bishop's simplified method in 3D,
    /// Hungr 1987).
    #[arg(long, value_enum, default_value = "hovland")]
    pub method: MethodArg,
    /// Bishop's floor of m_alpha = cos(gamma) + sin(alpha) tan(phi) / F, in
    /// (0, 1]: a surface with a column at or below it is refused, as
    /// Bishop's normal forces grow as 1/m_alpha where the base rises
    /// steeply against the sliding direction [default: 0.2, Whitman &
    /// Bailey 1967]. Only with --method bishop.
    #[arg(long, value_name = "M", value_parser = parse_m_alpha_floor)]
    pub m_alpha_floor: Option<f64>,

    /// Cells between neighbouring sphere centres [default: a 25th of the
    /// DEM's shorter side, at least 1].
    #[arg(long, value_name = "CELLS", value_parser = parse_stride, help_heading = "Sphere grid (--search spheres)")]
    pub stride: Option<usize>,
    /// Sphere radii (m), COUNT of them [default: 4 cells to a third of the
    /// DEM's shorter side, 10 radii].
    #[arg(long, value_name = "MIN:MAX[:COUNT]", value_parser = parse_radii, help_heading = "Sphere grid (--search spheres)")]
    pub radii: Option<Span>,

    /// Heights of the centres above the ground under them (m); COUNT of
    /// them for spheres, a uniform range for ellipsoids [default: spheres 1
    /// cell to a quarter of the DEM's shorter side, 6 heights; ellipsoids 0
    /// to a 40th of it].
    #[arg(long, value_name = "MIN:MAX[:COUNT]", value_parser = parse_heights, help_heading = "Trial surfaces, both families")]
    pub heights: Option<Span>,

    /// Number of random ellipsoids.
    #[arg(long, value_name = "N", default_value_t = 100_000, value_parser = parse_count, help_heading = "Random ellipsoids (--search ellipsoids)")]
    pub count: u64,
    /// Seed of the random ellipsoids (the same seed, the same trials).
    #[arg(
        long,
        value_name = "S",
        default_value_t = 1,
        help_heading = "Random ellipsoids (--search ellipsoids)"
    )]
    pub seed: u64,
    /// Semi-axis along the fall line (m) [default: 4 cells to a quarter of
    /// the DEM's shorter side].
    #[arg(long, value_name = "MIN:MAX", value_parser = parse_along, help_heading = "Random ellipsoids (--search ellipsoids)")]
    pub along: Option<Span>,
    /// Ratio of the semi-axis across the fall line to the one along it.
    #[arg(long, value_name = "MIN:MAX", default_value = "0.5:1", value_parser = parse_across_ratio, help_heading = "Random ellipsoids (--search ellipsoids)")]
    pub across_ratio: Span,
    /// Vertical semi-axis (m) [default: 1 cell to a 20th of the DEM's
    /// shorter side].
    #[arg(long, value_name = "MIN:MAX", value_parser = parse_vertical, help_heading = "Random ellipsoids (--search ellipsoids)")]
    pub vertical: Option<Span>,

    /// The fewest columns (DEM cells) of a surface kept.
    #[arg(long, value_name = "N", default_value_t = 4, value_parser = parse_min_columns, help_heading = "Limits on the surfaces kept")]
    pub min_columns: usize,
    /// Range of a surface's depth, its thickest column (m; `inf` for no
    /// upper limit).
    #[arg(long, value_name = "MIN:MAX", value_parser = parse_depth, help_heading = "Limits on the surfaces kept")]
    pub depth: Option<Span>,
    /// Range of a surface's volume (m³).
    #[arg(long, value_name = "MIN:MAX", value_parser = parse_volume, help_heading = "Limits on the surfaces kept")]
    pub volume: Option<Span>,
    /// Range of a surface's plan area (m²).
    #[arg(long, value_name = "MIN:MAX", value_parser = parse_area, help_heading = "Limits on the surfaces kept")]
    pub area: Option<Span>,

    /// How many of the most critical surfaces to list in critical.csv.
    #[arg(long, value_name = "K", default_value_t = 10, value_parser = parse_keep)]
    pub keep: usize,
    /// Re-analyse the K most critical surfaces by HPM (paper 001), K at
    /// most --keep (a larger K is refused):
    /// elastic, and nonlinear with --hpm-nonlinear; their Fs go into
    /// critical.csv and summary.json, the maps of the most critical one
    /// (local Fs, displacement, strains) and its slip surface into
    /// `hpm_*.asc`/`.tif`. With --layer each HPM column takes its layers
    /// at its cell centre: its slip springs the strength of the layer
    /// the surface crosses, its elements the unit weights of the layers
    /// over their height; with --ru the pore pressure r_u σ_v pushes on
    /// the slip surface under each column. K ≥ 1; leave --hpm out for no
    /// re-analysis.
    #[arg(long, value_name = "K", value_parser = parse_hpm, help_heading = "HPM re-analysis")]
    pub hpm: Option<usize>,
    /// Also run HPM's nonlinear analysis (Mohr–Coulomb slip springs, no
    /// tension) on each surface re-analysed.
    #[arg(long, requires = "hpm", help_heading = "HPM re-analysis")]
    pub hpm_nonlinear: bool,
    /// Young's modulus E of the ground for HPM (Pa); the slip springs'
    /// modulus E_slip is taken equal (paper 001, eq. 30). Only with --hpm.
    #[arg(long, value_name = "PA", default_value_t = 1e9, value_parser = parse_modulus, requires = "hpm", help_heading = "HPM re-analysis")]
    pub youngs_modulus: f64,
    /// Poisson's ratio ν of the ground for HPM, in [0, 0.5). Only with
    /// --hpm.
    #[arg(long, value_name = "NU", default_value_t = 0.2, value_parser = parse_poisson, requires = "hpm", help_heading = "HPM re-analysis")]
    pub poisson_ratio: f64,
    /// Worker threads [default: one per core].
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,
    /// Output folder, replaced whole once every file is written (a failed
    /// run leaves the previous one as it was).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Hide the progress bar.
    #[arg(long)]
    pub quiet: bool,
}

fn number(text: &str) -> Result<f64, String> {
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("`{text}` is not a number"))?;
    if value.is_nan() {
        return Err("NaN is not a value".into());
    }
    Ok(value)
}

fn whole<T: std::str::FromStr>(text: &str) -> Result<T, String> {
    text.trim()
        .parse()
        .map_err(|_| format!("`{text}` is not a whole number >= 0"))
}

fn message(e: DismechError) -> String {
    e.to_string()
}

fn parse_ru(text: &str) -> Result<RuArg, String> {
    match text.trim().parse::<f64>() {
        Ok(v) => {
            dismech::slope::PoreRatio::Constant(v)
                .validate()
                .map_err(message)?;
            Ok(RuArg::Constant(v))
        }
        Err(_) if !text.trim().is_empty() => Ok(RuArg::File(PathBuf::from(text))),
        Err(_) => Err("give a number in [0, 1) or a grid file".to_string()),
    }
}

fn parse_layer(text: &str) -> Result<LayerArg, String> {
    // The name up to the first `:`, the three numbers after the last three
    // (the file between may hold `:`).
    let shape = || format!("`{text}` is not NAME:BOTTOM:C:PHI:GAMMA");
    let (name, rest) = text.split_once(':').ok_or_else(shape)?;
    let mut tail = rest.rsplitn(4, ':');
    let (Some(gamma), Some(phi), Some(c), Some(bottom)) =
        (tail.next(), tail.next(), tail.next(), tail.next())
    else {
        return Err(shape());
    };
    if name.trim().is_empty() || bottom.is_empty() {
        return Err(shape());
    }
    let within = |e: String| format!("layer `{name}`: {e}");
    Ok(LayerArg {
        name: name.to_string(),
        bottom: PathBuf::from(bottom),
        cohesion: parse_cohesion(c).map_err(within)?,
        friction_angle: parse_friction_angle(phi).map_err(within)?,
        unit_weight: parse_unit_weight(gamma).map_err(within)?,
    })
}

fn parse_cohesion(text: &str) -> Result<f64, String> {
    require_non_negative("cohesion c' (Pa)", number(text)?).map_err(message)
}

fn parse_friction_angle(text: &str) -> Result<f64, String> {
    let degrees = number(text)?;
    friction_from_degrees(degrees).map_err(message)?;
    Ok(degrees)
}

fn parse_unit_weight(text: &str) -> Result<f64, String> {
    require_positive("unit weight gamma (N/m3)", number(text)?).map_err(message)
}

fn parse_m_alpha_floor(text: &str) -> Result<f64, String> {
    let floor = number(text)?;
    dismech::slope::BishopSettings::default()
        .with_m_alpha_floor(floor)
        .map_err(message)?;
    Ok(floor)
}

fn parse_seismic(text: &str) -> Result<f64, String> {
    let kh = number(text)?;
    let loads = dismech::slope::SlopeLoads {
        seismic_coefficient: kh,
        ..Default::default()
    };
    loads.validate().map_err(message)?;
    Ok(kh)
}

fn at_least_one<T: std::str::FromStr + Into<u64> + Copy>(
    text: &str,
    what: &str,
) -> Result<T, String> {
    let value: T = whole(text)?;
    if value.into() == 0 {
        return Err(format!("{what} must be at least 1"));
    }
    Ok(value)
}

fn parse_stride(text: &str) -> Result<usize, String> {
    at_least_one::<u32>(text, "the stride (cells)").map(|v| v as usize)
}

fn parse_count(text: &str) -> Result<u64, String> {
    at_least_one::<u64>(text, "the number of trials")
}

fn parse_min_columns(text: &str) -> Result<usize, String> {
    at_least_one::<u32>(text, "the fewest columns").map(|v| v as usize)
}

fn parse_threads(text: &str) -> Result<usize, String> {
    at_least_one::<u16>(text, "the number of threads").map(usize::from)
}

fn parse_modulus(text: &str) -> Result<f64, String> {
    require_positive("Young's modulus E (Pa)", number(text)?).map_err(message)
}

fn parse_poisson(text: &str) -> Result<f64, String> {
    let nu = number(text)?;
    if !(0.0..0.5).contains(&nu) {
        return Err(format!("Poisson's ratio {nu} must lie in [0, 0.5)"));
    }
    Ok(nu)
}

fn parse_keep(text: &str) -> Result<usize, String> {
    whole::<u32>(text).map(|v| v as usize)
}

/// `--hpm K`, K ≥ 1: `--hpm 0` would re-analyse nothing and leave the HPM
/// options beside it (`--hpm-nonlinear`, `--youngs-modulus`,
/// `--poisson-ratio`) unused, so it is refused naming them.
fn parse_hpm(text: &str) -> Result<usize, String> {
    match parse_keep(text)? {
        0 => Err(format!(
            "`{text}` re-analyses no surface, so --hpm-nonlinear, --youngs-modulus and --poisson-ratio would be ignored: give K >= 1, or leave --hpm out (and those options with it) for no re-analysis"
        )),
        k => Ok(k),
    }
}

/// `MIN:MAX`, `MIN:MAX:COUNT` (where `counted`) or `V`, min ≤ max.
fn span(text: &str, counted: bool) -> Result<Span, String> {
    let parts: Vec<&str> = text.split(':').collect();
    let (min, max, count) = match parts.as_slice() {
        [v] => {
            let v = number(v)?;
            (v, v, None)
        }
        [a, b] => (number(a)?, number(b)?, None),
        [a, b, n] if counted => {
            let n: usize = whole(n)?;
            if n == 0 {
                return Err("COUNT must be at least 1".into());
            }
            (number(a)?, number(b)?, Some(n))
        }
        _ if counted => return Err(format!("`{text}` is not MIN:MAX or MIN:MAX:COUNT")),
        _ => return Err(format!("`{text}` is not MIN:MAX")),
    };
    if min > max {
        return Err(format!("MIN {min} lies above MAX {max}"));
    }
    Ok(Span { min, max, count })
}

/// A span whose bounds are finite and, where `positive`, > 0, checked by
/// the library's [`Steps`] (the check its families make).
fn checked_span(
    text: &str,
    counted: bool,
    name: &'static str,
    positive: bool,
) -> Result<Span, String> {
    let s = span(text, counted)?;
    Steps::checked(name, s.min, s.max, s.count.unwrap_or(1), positive).map_err(message)?;
    Ok(s)
}

fn parse_radii(text: &str) -> Result<Span, String> {
    checked_span(text, true, "sphere radius (m)", true)
}

fn parse_heights(text: &str) -> Result<Span, String> {
    checked_span(text, true, "height above the ground (m)", false)
}

fn parse_along(text: &str) -> Result<Span, String> {
    checked_span(text, false, "semi-axis along (m)", true)
}

fn parse_across_ratio(text: &str) -> Result<Span, String> {
    checked_span(text, false, "ratio across/along", true)
}

fn parse_vertical(text: &str) -> Result<Span, String> {
    checked_span(text, false, "vertical semi-axis (m)", true)
}

/// A limit: `MIN:MAX` with MIN ≥ 0 finite and MAX ≥ MIN (`inf` allowed).
fn limit(text: &str, name: &'static str) -> Result<Span, String> {
    let s = span(text, false)?;
    require_non_negative(name, s.min).map_err(message)?;
    Ok(s)
}

fn parse_depth(text: &str) -> Result<Span, String> {
    limit(text, "depth (m)")
}

fn parse_volume(text: &str) -> Result<Span, String> {
    limit(text, "volume (m3)")
}

fn parse_area(text: &str) -> Result<Span, String> {
    limit(text, "area (m2)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_are_read_with_and_without_a_count() {
        assert_eq!(
            span("2:8:4", true).unwrap(),
            Span {
                min: 2.0,
                max: 8.0,
                count: Some(4)
            }
        );
        assert_eq!(span("5", false).unwrap().pair(), (5.0, 5.0));
        assert_eq!(span("0:inf", false).unwrap().max, f64::INFINITY);
        assert_eq!(span("-1.5:2", true).unwrap().steps(6).count, 6);
        assert_eq!(span("2:8:4", true).unwrap().to_string(), "2:8:4");
    }

    #[test]
    fn bad_spans_say_what_is_wrong() {
        assert_eq!(span("8:2", false).unwrap_err(), "MIN 8 lies above MAX 2");
        assert_eq!(span("1:2:3", false).unwrap_err(), "`1:2:3` is not MIN:MAX");
        assert_eq!(span("1:2:0", true).unwrap_err(), "COUNT must be at least 1");
        assert_eq!(span("a:2", true).unwrap_err(), "`a` is not a number");
        assert_eq!(span("nan:2", true).unwrap_err(), "NaN is not a value");
        let e = parse_radii("-5:10").unwrap_err();
        assert!(e.contains("sphere radius (m) = -5"), "{e}");
        let e = parse_along("1:inf").unwrap_err();
        assert!(e.contains("semi-axis along (m) = inf"), "{e}");
        let e = parse_depth("-1:5").unwrap_err();
        assert!(e.contains("depth (m) = -1"), "{e}");
    }

    #[test]
    fn material_values_are_checked_by_the_library_rules() {
        assert_eq!(parse_cohesion("5e3").unwrap(), 5e3);
        assert!(parse_cohesion("-1")
            .unwrap_err()
            .contains("cohesion c' (Pa) = -1"));
        assert!(parse_friction_angle("90")
            .unwrap_err()
            .contains("must lie in [0, 90)"));
        assert_eq!(parse_friction_angle("0").unwrap(), 0.0);
        assert!(parse_unit_weight("0")
            .unwrap_err()
            .contains("must be finite and > 0"));
        assert!(parse_seismic("11").unwrap_err().contains("at most 10"));
        assert_eq!(parse_m_alpha_floor("0.05").unwrap(), 0.05);
        assert_eq!(parse_m_alpha_floor("1").unwrap(), 1.0);
        for bad in ["0", "-0.1", "1.5", "inf"] {
            let e = parse_m_alpha_floor(bad).unwrap_err();
            assert!(e.contains("m_alpha floor") && e.contains("(0, 1]"), "{e}");
        }
        assert_eq!(
            parse_stride("0").unwrap_err(),
            "the stride (cells) must be at least 1"
        );
        assert_eq!(
            parse_threads("x").unwrap_err(),
            "`x` is not a whole number >= 0"
        );
    }

    #[test]
    fn layers_and_ru_are_read_and_checked() {
        let l = parse_layer("till:C:/data/till.asc:5e3:22:18e3").unwrap();
        assert_eq!(l.name, "till");
        assert_eq!(l.bottom, PathBuf::from("C:/data/till.asc"));
        assert_eq!(
            (l.cohesion, l.friction_angle, l.unit_weight),
            (5e3, 22.0, 18e3)
        );
        let e = parse_layer("till:b.asc:5e3:22:-1").unwrap_err();
        assert!(e.contains("layer `till`") && e.contains("-1"), "{e}");
        assert!(parse_layer("till:5e3:22").is_err());
        assert!(parse_layer(":b.asc:5e3:22:18e3").is_err());
        assert_eq!(parse_ru("0.3").unwrap(), RuArg::Constant(0.3));
        assert_eq!(
            parse_ru("ru.asc").unwrap(),
            RuArg::File(PathBuf::from("ru.asc"))
        );
        let e = parse_ru("1").unwrap_err();
        assert!(e.contains("r_u = 1"), "{e}");
        assert!(parse_ru("-0.1").is_err());
    }
}
