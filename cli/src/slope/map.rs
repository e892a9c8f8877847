//! The map of a slope search as SVG: the DEM's shaded relief coloured by
//! the lowest Fs of each cell in classes (with their legend), and the
//! outline of the most critical surface with an arrow along its sliding
//! direction.
//!
//! The cells are one picture, a PNG embedded in the SVG (one block of
//! pixels a cell, drawn without smoothing), under the axes, the outline and
//! the legend that plotters draws: a 100 × 100 DEM as 10 000 SVG
//! rectangles would weigh a megabyte.

use std::path::Path;

use base64::Engine as _;
use plotters::prelude::*;

use dismech::error::{DismechError, Result};
use dismech::grid::Raster;
use dismech::io::write_atomically;

use super::hillshade::{hillshade, Sun};

/// Upper bounds of the Fs classes; the last class has none.
pub const CLASS_BOUNDS: [f64; 5] = [1.0, 1.2, 1.5, 2.0, 3.0];

/// The classes' colours, from the most critical: ColorBrewer's 6-class
/// RdYlBu (Harrower & Brewer, The Cartographic Journal 40(1), 2003), a
/// diverging scale that readers with red-green colour blindness tell apart.
pub const CLASS_COLOURS: [(u8, u8, u8); 6] = [
    (215, 48, 39),
    (252, 141, 89),
    (254, 224, 144),
    (224, 243, 248),
    (145, 191, 219),
    (69, 117, 180),
];

/// The class of a factor of safety (index into [`CLASS_COLOURS`]).
pub fn class_of(fs: f64) -> usize {
    CLASS_BOUNDS.iter().take_while(|&&b| fs >= b).count()
}

/// The legend text of class `k`.
pub fn class_label(k: usize) -> String {
    match k {
        0 => format!("Fs < {:.1}", CLASS_BOUNDS[0]),
        k if k == CLASS_BOUNDS.len() => format!("Fs ≥ {:.1}", CLASS_BOUNDS[k - 1]),
        k => format!("{:.1} ≤ Fs < {:.1}", CLASS_BOUNDS[k - 1], CLASS_BOUNDS[k]),
    }
}

/// The colour of a cell: its class's colour darkened by the relief where
/// a trial surface passed, grey relief where none did, white without
/// ground data.
fn cell_colour(shade: Option<f64>, fs: Option<f64>) -> (u8, u8, u8) {
    let Some(shade) = shade else {
        return (255, 255, 255);
    };
    let scale = |v: u8, f: f64| (v as f64 * f).round().clamp(0.0, 255.0) as u8;
    match fs {
        Some(fs) => {
            let (r, g, b) = CLASS_COLOURS[class_of(fs)];
            let f = 0.45 + 0.55 * shade;
            (scale(r, f), scale(g, f), scale(b, f))
        }
        None => {
            let v = scale(255, 0.3 + 0.65 * shade);
            (v, v, v)
        }
    }
}

/// A line segment in map units.
pub type Segment = ((f64, f64), (f64, f64));

/// What the map shows.
#[derive(Debug, Clone)]
pub struct SlopeMap<'a> {
    /// The DEM (the relief).
    pub dem: &'a Raster,
    /// The lowest Fs per cell, on the DEM's grid.
    pub safety: &'a Raster,
    /// The title.
    pub title: String,
    /// The edges of the most critical surface's footprint.
    pub outline: Vec<Segment>,
    /// Its sliding direction, from the footprint's centroid.
    pub arrow: Option<Segment>,
    /// The outline's legend text.
    pub outline_label: String,
}

/// The cells' picture: `scale × scale` pixels a cell, RGB, row by row from
/// the top (north).
fn cell_pixels(map: &SlopeMap, scale: usize) -> Vec<u8> {
    let (rows, columns) = (map.dem.rows(), map.dem.columns());
    let shades = hillshade(map.dem, Sun::default());
    let mut pixels = Vec::with_capacity(rows * columns * scale * scale * 3);
    for r in 0..rows {
        let line: Vec<u8> = (0..columns)
            .flat_map(|c| {
                let (red, green, blue) = cell_colour(shades[r * columns + c], map.safety.get(r, c));
                std::iter::repeat_n([red, green, blue], scale).flatten()
            })
            .collect();
        for _ in 0..scale {
            pixels.extend_from_slice(&line);
        }
    }
    pixels
}

/// The PNG of `width × height` RGB `pixels`.
fn png(path: &Path, width: u32, height: u32, pixels: &[u8]) -> Result<Vec<u8>> {
    let fail = |e: png::EncodingError| DismechError::Output {
        path: path.display().to_string(),
        message: format!("encoding the map's cells as PNG failed: {e}"),
    };
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::High);
    let mut writer = encoder.write_header().map_err(fail)?;
    writer.write_image_data(pixels).map_err(fail)?;
    writer.finish().map_err(fail)?;
    Ok(bytes)
}

fn plot_error(path: &Path, e: impl std::fmt::Display) -> DismechError {
    DismechError::Output {
        path: path.display().to_string(),
        message: format!("plotting failed: {e}"),
    }
}

/// Pixels across the map's cells.
const MAP_WIDTH: u32 = 640;
/// Pixels across the legend.
const LEGEND_WIDTH: u32 = 230;

/// The SVG text of `map` (`path` names it in errors).
pub fn slope_map_svg(path: &Path, map: &SlopeMap) -> Result<String> {
    let dem = map.dem;
    let (x0, y0) = dem.lower_left();
    let d = dem.cell_size();
    let (x1, y1) = (x0 + dem.columns() as f64 * d, y0 + dem.rows() as f64 * d);
    // Margins of the chart around its cells: caption, tick labels.
    let (left, right, top, bottom) = (80u32, 15u32, 40u32, 50u32);
    let cells_high = ((MAP_WIDTH as f64) * (y1 - y0) / (x1 - x0))
        .round()
        .clamp(100.0, 1600.0) as u32;
    let size = (
        left + MAP_WIDTH + right + LEGEND_WIDTH,
        top + cells_high + bottom,
    );
    let mut svg = String::new();
    let picture_at;
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        let (plot, side) = root.split_horizontally(left + MAP_WIDTH + right);
        let mut chart = ChartBuilder::on(&plot)
            .caption(&map.title, ("sans-serif", 17))
            .margin_top(8)
            .margin_right(right)
            .x_label_area_size(bottom - 8)
            .y_label_area_size(left)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| plot_error(path, e))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("easting (m)")
            .y_desc("northing (m)")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .x_labels(6)
            .y_labels(6)
            .draw()
            .map_err(|e| plot_error(path, e))?;
        picture_at = (
            chart.backend_coord(&(x0, y1)),
            chart.backend_coord(&(x1, y0)),
        );
        // The outline: white under black, to be seen on dark and light cells.
        for (colour, width) in [(WHITE, 4), (BLACK, 2)] {
            chart
                .draw_series(
                    map.outline
                        .iter()
                        .map(|&(a, b)| PathElement::new(vec![a, b], colour.stroke_width(width))),
                )
                .map_err(|e| plot_error(path, e))?;
        }
        if let Some(((x, y), (tx, ty))) = map.arrow {
            let (dx, dy) = (tx - x, ty - y);
            let (bx, by) = (tx - 0.3 * dx, ty - 0.3 * dy);
            let (px, py) = (-0.15 * dy, 0.15 * dx);
            let head = vec![(bx + px, by + py), (tx, ty), (bx - px, by - py)];
            for (colour, width) in [(WHITE, 4), (BLACK, 2)] {
                chart
                    .draw_series([
                        PathElement::new(vec![(x, y), (tx, ty)], colour.stroke_width(width)),
                        PathElement::new(head.clone(), colour.stroke_width(width)),
                    ])
                    .map_err(|e| plot_error(path, e))?;
            }
        }
        draw_legend(path, &side, map)?;
        root.present().map_err(|e| plot_error(path, e))?;
    }
    // The cells go under everything plotters drew: right after the <svg>
    // tag, on a white ground.
    let ((px0, py0), (px1, py1)) = picture_at;
    let (w, h) = ((px1 - px0).max(1) as u32, (py1 - py0).max(1) as u32);
    let scale = ((w as usize).div_ceil(dem.columns()))
        .max((h as usize).div_ceil(dem.rows()))
        .clamp(1, 16);
    let pixels = cell_pixels(map, scale);
    let png = png(
        path,
        (dem.columns() * scale) as u32,
        (dem.rows() * scale) as u32,
        &pixels,
    )?;
    let image = format!(
        "<rect x=\"0\" y=\"0\" width=\"{}\" height=\"{}\" fill=\"#FFFFFF\"/>\n<image x=\"{px0}\" y=\"{py0}\" width=\"{w}\" height=\"{h}\" preserveAspectRatio=\"none\" style=\"image-rendering:pixelated\" href=\"data:image/png;base64,{}\"/>\n",
        size.0,
        size.1,
        base64::engine::general_purpose::STANDARD.encode(png)
    );
    let at = svg
        .find("<svg")
        .and_then(|start| svg[start..].find('>').map(|end| start + end + 1))
        .ok_or_else(|| plot_error(path, "plotters wrote no <svg> tag"))?;
    let at = if svg[at..].starts_with('\n') {
        at + 1
    } else {
        at
    };
    svg.insert_str(at, &image);
    Ok(svg)
}

/// The legend: the Fs classes, the cells no surface reached, the critical
/// surface's outline and the sun.
fn draw_legend<DB: DrawingBackend>(
    path: &Path,
    side: &DrawingArea<DB, plotters::coord::Shift>,
    map: &SlopeMap,
) -> Result<()> {
    let font = ("sans-serif", 13).into_font();
    let text = |s: String, x: i32, y: i32| Text::new(s, (x, y), font.clone());
    side.draw(&Text::new(
        "lowest Fs per cell".to_string(),
        (8, 44),
        ("sans-serif", 14).into_font(),
    ))
    .map_err(|e| plot_error(path, e))?;
    let mut y = 66;
    // Swatches as the cells of level ground show them.
    let level = Some(Sun::default().altitude_deg.to_radians().sin());
    let mut swatches: Vec<((u8, u8, u8), String)> = (0..CLASS_COLOURS.len())
        .rev()
        .map(|k| {
            let fs = if k == 0 { 0.0 } else { CLASS_BOUNDS[k - 1] };
            (cell_colour(level, Some(fs)), class_label(k))
        })
        .collect();
    swatches.push((cell_colour(level, None), "no trial surface".to_string()));
    for ((r, g, b), label) in swatches {
        side.draw(&Rectangle::new(
            [(8, y), (26, y + 16)],
            RGBColor(r, g, b).filled(),
        ))
        .map_err(|e| plot_error(path, e))?;
        side.draw(&text(label, 34, y + 2))
            .map_err(|e| plot_error(path, e))?;
        y += 22;
    }
    y += 10;
    for (colour, width) in [(WHITE, 4), (BLACK, 2)] {
        side.draw(&PathElement::new(
            vec![(8, y + 8), (26, y + 8)],
            colour.stroke_width(width),
        ))
        .map_err(|e| plot_error(path, e))?;
    }
    side.draw(&text(map.outline_label.clone(), 34, y + 2))
        .map_err(|e| plot_error(path, e))?;
    y += 22;
    side.draw(&text("arrow: its sliding direction".into(), 34, y + 2))
        .map_err(|e| plot_error(path, e))?;
    y += 30;
    let sun = Sun::default();
    side.draw(&text(
        format!(
            "relief: sun at {}°, {}° high",
            sun.azimuth_deg, sun.altitude_deg
        ),
        8,
        y,
    ))
    .map_err(|e| plot_error(path, e))?;
    Ok(())
}

/// Write the map of `map` to `path` (SVG), atomically.
///
/// # Errors
/// [`DismechError::Output`] naming the path when the map cannot be drawn
/// or written (it is then not there).
pub fn write_slope_map(path: &Path, map: &SlopeMap) -> Result<()> {
    write_atomically(path, slope_map_svg(path, map)?.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_split_at_their_bounds() {
        assert_eq!(class_of(0.7), 0);
        assert_eq!(class_of(1.0), 1);
        assert_eq!(class_of(1.1999), 1);
        assert_eq!(class_of(2.5), 4);
        assert_eq!(class_of(3.0), 5);
        assert_eq!(class_of(f64::INFINITY), 5);
        assert_eq!(class_label(0), "Fs < 1.0");
        assert_eq!(class_label(2), "1.2 ≤ Fs < 1.5");
        assert_eq!(class_label(5), "Fs ≥ 3.0");
    }

    #[test]
    fn the_cells_lie_under_the_drawing_and_each_cell_is_one_colour() {
        let dem = Raster::from_fn(8, 6, 100.0, 200.0, 5.0, |x, y| Some(0.3 * x + 0.1 * y)).unwrap();
        let safety = Raster::from_fn(8, 6, 100.0, 200.0, 5.0, |x, _| {
            (x > 120.0).then_some(0.8 + (x - 120.0) / 10.0)
        })
        .unwrap();
        let map = SlopeMap {
            dem: &dem,
            safety: &safety,
            title: "test".into(),
            outline: vec![((120.0, 210.0), (130.0, 210.0))],
            arrow: Some(((125.0, 215.0), (130.0, 212.0))),
            outline_label: "critical surface".into(),
        };
        let svg = slope_map_svg(Path::new("map.svg"), &map).unwrap();
        let image = svg.find("<image").unwrap();
        assert!(image < svg.find("<text").unwrap());
        assert!(image < svg.find("<polyline").unwrap());
        assert!(svg.contains("href=\"data:image/png;base64,"));
        for k in 0..6 {
            assert!(svg.contains(&class_label(k).replace('<', "&lt;")), "{k}");
        }
        // A plane shades every cell alike: the cells with an Fs of one
        // class share one colour, and each cell is a block of one colour.
        let scale = 3;
        let pixels = cell_pixels(&map, scale);
        let width = 8 * scale;
        let at = |row: usize, col: usize| {
            let k = 3 * (row * width + col);
            [pixels[k], pixels[k + 1], pixels[k + 2]]
        };
        for r in 0..6 * scale {
            for c in 0..width {
                assert_eq!(at(r, c), at(r / scale * scale, c / scale * scale));
            }
        }
        // Column 4 (x = 122.5, Fs 1.05) and column 5 (x = 127.5, Fs 1.55).
        assert_ne!(at(0, 4 * scale), at(0, 5 * scale));
        // Column 0 has no Fs: grey.
        let [r, g, b] = at(0, 0);
        assert!(r == g && g == b);
    }
}
