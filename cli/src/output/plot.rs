//! SVG plots (plotters): line charts and pictures of a particle assembly
//! with its contact forces.

use std::path::Path;

use plotters::prelude::*;

use dismech::error::{DismechError, Result};
use dismech::io::write_atomically;
use dismech::math::{Point, Vec2};
use dismech::shape::Segment;

/// One named series of a line chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// Points `(x, y)`.
    pub points: Vec<(f64, f64)>,
    /// Draw markers at the points as well as the line.
    pub markers: bool,
}

const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
];

pub(super) fn plot_error(path: &Path, e: impl std::fmt::Display) -> DismechError {
    DismechError::Output {
        path: path.display().to_string(),
        message: format!("plotting failed: {e}"),
    }
}

fn padded_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        0.5 * lo.abs().max(1.0)
    };
    (lo - pad, hi + pad)
}

/// A line chart of `series`, written atomically to `path`.
pub fn line_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<()> {
    chart(path, title, (x_label, y_label), series, true)
}

/// A scatter chart of `series` (markers only, no lines), written
/// atomically to `path`.
pub fn scatter_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<()> {
    chart(path, title, (x_label, y_label), series, false)
}

fn chart(
    path: &Path,
    title: &str,
    (x_label, y_label): (&str, &str),
    series: &[Series],
    lines: bool,
) -> Result<()> {
    let (x0, x1) = padded_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.0)));
    let (y0, y1) = padded_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 600)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| plot_error(path, e))?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .draw()
            .map_err(|e| plot_error(path, e))?;
        for (i, s) in series.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            let line = if lines { &s.points[..] } else { &[] };
            chart
                .draw_series(LineSeries::new(line.iter().copied(), color.stroke_width(2)))
                .map_err(|e| plot_error(path, e))?
                .label(s.name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            if s.markers || !lines {
                chart
                    .draw_series(s.points.iter().map(|&p| Circle::new(p, 3, color.filled())))
                    .map_err(|e| plot_error(path, e))?;
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| plot_error(path, e))?;
        root.present().map_err(|e| plot_error(path, e))?;
    }
    write_atomically(path, svg.as_bytes())
}

/// A force to draw: a segment through `point` along `force`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceMark {
    /// Where the force acts.
    pub point: Point,
    /// The force (N/m).
    pub force: Vec2,
}

/// What a picture of an assembly shows on top of its circles and lines.
#[derive(Debug, Default)]
struct Overlay<'a> {
    /// Segments centred on a point (contact forces), already scaled.
    centred: Vec<(Point, Vec2)>,
    /// Arrows from a point (velocities), already scaled.
    arrows: Vec<(Point, Vec2)>,
    /// Crosses (slipping contacts).
    crosses: &'a [Point],
    /// Head length of the arrows.
    head: f64,
}

/// The outline of a circle as a closed polyline of 33 points.
fn circle_outline(centre: &Point, radius: f64) -> Vec<Point> {
    (0..=32)
        .map(|k| {
            let t = k as f64 / 32.0 * std::f64::consts::TAU;
            Point::new(centre.x + radius * t.cos(), centre.y + radius * t.sin())
        })
        .collect()
}

/// Draw particle outlines (closed polylines), thick lines and an overlay,
/// scaled equally in x and y, and write the SVG atomically.
fn draw_picture(
    path: &Path,
    title: &str,
    outlines: &[Vec<Point>],
    lines: &[(Point, Point)],
    overlay: &Overlay,
) -> Result<()> {
    let xs = outlines
        .iter()
        .flatten()
        .map(|p| p.x)
        .chain(lines.iter().flat_map(|(a, b)| [a.x, b.x]));
    let ys = outlines
        .iter()
        .flatten()
        .map(|p| p.y)
        .chain(lines.iter().flat_map(|(a, b)| [a.y, b.y]));
    let (x0, x1) = padded_range(xs);
    let (y0, y1) = padded_range(ys);
    let width_px = 800u32;
    let height_px = ((width_px as f64) * (y1 - y0) / (x1 - x0)).clamp(200.0, 2400.0) as u32 + 60;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width_px, height_px)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(10)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| plot_error(path, e))?;
        let grey = RGBColor(160, 160, 160);
        chart
            .draw_series(outlines.iter().map(|outline| {
                let pts: Vec<(f64, f64)> = outline.iter().map(|p| (p.x, p.y)).collect();
                PathElement::new(pts, grey.stroke_width(1))
            }))
            .map_err(|e| plot_error(path, e))?;
        chart
            .draw_series(lines.iter().map(|(a, b)| {
                PathElement::new(vec![(a.x, a.y), (b.x, b.y)], BLACK.stroke_width(3))
            }))
            .map_err(|e| plot_error(path, e))?;
        chart
            .draw_series(overlay.centred.iter().map(|(p, v)| {
                let half = v * 0.5;
                PathElement::new(
                    vec![(p.x - half.x, p.y - half.y), (p.x + half.x, p.y + half.y)],
                    PALETTE[1].stroke_width(2),
                )
            }))
            .map_err(|e| plot_error(path, e))?;
        chart
            .draw_series(
                overlay
                    .arrows
                    .iter()
                    .filter(|a| a.1.norm() > 0.0)
                    .map(|(p, v)| {
                        let tip = *p + v;
                        let back = -v.normalize() * overlay.head.min(0.4 * v.norm());
                        let side = dismech::math::perp(&back) * 0.5;
                        PathElement::new(
                            vec![
                                (p.x, p.y),
                                (tip.x, tip.y),
                                (tip.x + back.x + side.x, tip.y + back.y + side.y),
                                (tip.x, tip.y),
                                (tip.x + back.x - side.x, tip.y + back.y - side.y),
                            ],
                            PALETTE[0].stroke_width(2),
                        )
                    }),
            )
            .map_err(|e| plot_error(path, e))?;
        chart
            .draw_series(
                overlay
                    .crosses
                    .iter()
                    .map(|p| Cross::new((p.x, p.y), 5, PALETTE[1].stroke_width(2))),
            )
            .map_err(|e| plot_error(path, e))?;
        root.present().map_err(|e| plot_error(path, e))?;
    }
    write_atomically(path, svg.as_bytes())
}

/// The factor that makes the longest of `vectors` `max_length` long.
fn scale_to(vectors: impl Iterator<Item = Vec2>, max_length: f64) -> f64 {
    let longest = vectors.map(|v| v.norm()).fold(0.0, f64::max);
    if longest > 0.0 {
        max_length / longest
    } else {
        0.0
    }
}

/// A picture of an assembly: circles (outline), walls, and contact forces
/// drawn as segments centred on the contact point, with length proportional
/// to the force (the largest is `max_length` long), like paper 000 Fig. 5(b).
pub fn assembly_picture(
    path: &Path,
    title: &str,
    circles: &[(Point, f64)],
    walls: &[Segment],
    forces: &[ForceMark],
    max_length: f64,
) -> Result<()> {
    let outlines: Vec<Vec<Point>> = circles.iter().map(|(c, r)| circle_outline(c, *r)).collect();
    outline_picture(path, title, &outlines, walls, forces, max_length)
}

/// [`assembly_picture`] for particles of any shape, given by their outlines
/// (closed polylines).
pub fn outline_picture(
    path: &Path,
    title: &str,
    outlines: &[Vec<Point>],
    walls: &[Segment],
    forces: &[ForceMark],
    max_length: f64,
) -> Result<()> {
    let scale = scale_to(forces.iter().map(|f| f.force), max_length);
    let lines: Vec<(Point, Point)> = walls.iter().map(|w| (w.start, w.end)).collect();
    let overlay = Overlay {
        centred: forces.iter().map(|f| (f.point, f.force * scale)).collect(),
        ..Overlay::default()
    };
    draw_picture(path, title, outlines, &lines, &overlay)
}

/// A picture of a collapse mechanism: elements (outline), supports (thick
/// lines), velocity arrows from each element centre, and crosses on
/// slipping contacts, like paper 002's Figs. 4–9 and 11–16. The longest
/// arrow is `max_arrow` long.
pub fn mechanism_picture(
    path: &Path,
    title: &str,
    circles: &[(Point, f64)],
    lines: &[(Point, Point)],
    arrows: &[(Point, Vec2)],
    marks: &[Point],
    max_arrow: f64,
) -> Result<()> {
    let scale = scale_to(arrows.iter().map(|a| a.1), max_arrow);
    let overlay = Overlay {
        arrows: arrows.iter().map(|(p, v)| (*p, v * scale)).collect(),
        crosses: marks,
        head: 0.25 * max_arrow,
        ..Overlay::default()
    };
    let outlines: Vec<Vec<Point>> = circles.iter().map(|(c, r)| circle_outline(c, *r)).collect();
    draw_picture(path, title, &outlines, lines, &overlay)
}
