//! Plan-view maps of grid cells (SVG): a colour per cell and optional
//! arrows, as paper 001 draws its local safety factors (Fig. 11),
//! surface principal strains (Fig. 12) and displacement vectors (Fig. 13).

use std::path::Path;

use plotters::prelude::*;

use super::plot::plot_error;
use dismech::error::Result;
use dismech::io::write_atomically;

/// One coloured grid cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapCell {
    /// Lower-left corner x (m).
    pub x0: f64,
    /// Lower-left corner y (m).
    pub y0: f64,
    /// Side (m).
    pub size: f64,
    /// Fill colour (RGB).
    pub color: (u8, u8, u8),
}

/// An arrow from `(x, y)` along `(dx, dy)`, in map units.
pub type Arrow = ((f64, f64), (f64, f64));

/// Draw `cells` (filled, grey outline) and `arrows` over the box
/// `extent = (x0, x1, y0, y1)` with equal x and y scales; `legend` lines are
/// written under the title. Written atomically.
pub fn cell_map(
    path: &Path,
    title: &str,
    extent: (f64, f64, f64, f64),
    cells: &[MapCell],
    arrows: &[Arrow],
    legend: &[(String, (u8, u8, u8))],
) -> Result<()> {
    let (x0, x1, y0, y1) = extent;
    let width = 700u32;
    let height = ((width as f64) * (y1 - y0) / (x1 - x0)).clamp(200.0, 2000.0) as u32 + 110;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width + 160, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
        let (plot, side) = root.split_horizontally(width);
        let mut chart = ChartBuilder::on(&plot)
            .caption(title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(45)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| plot_error(path, e))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x (m)")
            .y_desc("y (m)")
            .draw()
            .map_err(|e| plot_error(path, e))?;
        chart
            .draw_series(cells.iter().map(|c| {
                let (r, g, b) = c.color;
                Rectangle::new(
                    [(c.x0, c.y0), (c.x0 + c.size, c.y0 + c.size)],
                    RGBColor(r, g, b).filled(),
                )
            }))
            .map_err(|e| plot_error(path, e))?;
        let grey = RGBColor(150, 150, 150);
        chart
            .draw_series(cells.iter().map(|c| {
                Rectangle::new(
                    [(c.x0, c.y0), (c.x0 + c.size, c.y0 + c.size)],
                    grey.stroke_width(1),
                )
            }))
            .map_err(|e| plot_error(path, e))?;
        chart
            .draw_series(arrows.iter().filter(|a| a.1 .0.hypot(a.1 .1) > 0.0).map(
                |&((x, y), (dx, dy))| {
                    let (tx, ty) = (x + dx, y + dy);
                    let len = dx.hypot(dy);
                    let head = 0.3 * len;
                    let (ux, uy) = (dx / len, dy / len);
                    let (bx, by) = (tx - ux * head, ty - uy * head);
                    let (px, py) = (-uy * 0.5 * head, ux * 0.5 * head);
                    PathElement::new(
                        vec![
                            (x, y),
                            (tx, ty),
                            (bx + px, by + py),
                            (tx, ty),
                            (bx - px, by - py),
                        ],
                        BLACK.stroke_width(1),
                    )
                },
            ))
            .map_err(|e| plot_error(path, e))?;
        for (k, (text, (r, g, b))) in legend.iter().enumerate() {
            let y = 40 + 24 * k as i32;
            side.draw(&Rectangle::new(
                [(5, y), (21, y + 16)],
                RGBColor(*r, *g, *b).filled(),
            ))
            .map_err(|e| plot_error(path, e))?;
            side.draw(&Text::new(
                text.clone(),
                (26, y + 2),
                ("sans-serif", 13).into_font(),
            ))
            .map_err(|e| plot_error(path, e))?;
        }
        root.present().map_err(|e| plot_error(path, e))?;
    }
    write_atomically(path, svg.as_bytes())
}
