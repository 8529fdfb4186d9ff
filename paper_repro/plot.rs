//! SVG and PNG plots with plotters: line/marker series and bands, in the paper's grey scale.

use plotters::prelude::*;
use std::path::Path;

/// What a series draws.
pub enum Series {
    /// A polyline.
    Line {
        label: String,
        grey: u8,
        dashed: bool,
        points: Vec<(f64, f64)>,
    },
    /// Filled or hollow circles.
    Marks {
        label: String,
        grey: u8,
        filled: bool,
        points: Vec<(f64, f64)>,
    },
    /// Filled rectangles (x0, y0, x1, y1), e.g. the boxes of a paving.
    Rects {
        label: String,
        grey: u8,
        rects: Vec<(f64, f64, f64, f64)>,
    },
    /// A band between lo(x) and hi(x), drawn as a filled polygon and its two edges.
    Band {
        label: String,
        grey: u8,
        points: Vec<(f64, f64, f64)>,
    },
}

/// One chart.
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_range: (f64, f64),
    pub y_range: (f64, f64),
    pub series: Vec<Series>,
    /// Legend in the upper left (else upper right).
    pub legend_left: bool,
}

fn grey(g: u8) -> RGBColor {
    RGBColor(g, g, g)
}

fn draw<DB: DrawingBackend>(
    area: DrawingArea<DB, plotters::coord::Shift>,
    c: &Chart,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| format!("plot '{}': {x:?}", c.title);
    area.fill(&WHITE).map_err(e)?;
    let mut chart = ChartBuilder::on(&area)
        .caption(&c.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(48)
        .y_label_area_size(64)
        .build_cartesian_2d(c.x_range.0..c.x_range.1, c.y_range.0..c.y_range.1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(&c.x_label)
        .y_desc(&c.y_label)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(e)?;
    for s in &c.series {
        match s {
            Series::Line {
                label,
                grey: g,
                dashed,
                points,
            } => {
                let style = grey(*g).stroke_width(2);
                let anno = if *dashed {
                    chart
                        .draw_series(DashedLineSeries::new(points.iter().copied(), 6, 4, style))
                        .map_err(e)?
                } else {
                    chart
                        .draw_series(LineSeries::new(points.iter().copied(), style))
                        .map_err(e)?
                };
                let col = grey(*g);
                anno.label(label).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], col.stroke_width(2))
                });
            }
            Series::Marks {
                label,
                grey: g,
                filled,
                points,
            } => {
                let col = grey(*g);
                let style = if *filled {
                    col.filled()
                } else {
                    col.stroke_width(2)
                };
                let r = if *filled { 3 } else { 6 };
                chart
                    .draw_series(points.iter().map(|&(x, y)| Circle::new((x, y), r, style)))
                    .map_err(e)?
                    .label(label)
                    .legend(move |(x, y)| Circle::new((x + 10, y), r, style));
            }
            Series::Rects {
                label,
                grey: g,
                rects,
            } => {
                let col = grey(*g);
                chart
                    .draw_series(rects.iter().map(|&(x0, y0, x1, y1)| {
                        Rectangle::new([(x0, y0), (x1, y1)], col.filled())
                    }))
                    .map_err(e)?
                    .label(label)
                    .legend(move |(x, y)| {
                        Rectangle::new([(x, y - 5), (x + 20, y + 5)], col.filled())
                    });
            }
            Series::Band {
                label,
                grey: g,
                points,
            } => {
                let col = grey(*g);
                let mut poly: Vec<(f64, f64)> = points.iter().map(|&(x, lo, _)| (x, lo)).collect();
                poly.extend(points.iter().rev().map(|&(x, _, hi)| (x, hi)));
                chart
                    .draw_series(std::iter::once(Polygon::new(poly, col.mix(0.35).filled())))
                    .map_err(e)?
                    .label(label)
                    .legend(move |(x, y)| {
                        Rectangle::new([(x, y - 5), (x + 20, y + 5)], col.mix(0.35).filled())
                    });
                for edge in [0, 1] {
                    chart
                        .draw_series(LineSeries::new(
                            points
                                .iter()
                                .map(|&(x, lo, hi)| (x, if edge == 0 { lo } else { hi })),
                            col.stroke_width(1),
                        ))
                        .map_err(e)?;
                }
            }
        }
    }
    chart
        .configure_series_labels()
        .position(if c.legend_left {
            SeriesLabelPosition::UpperLeft
        } else {
            SeriesLabelPosition::UpperRight
        })
        .label_font(("sans-serif", 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    area.present().map_err(e)?;
    Ok(())
}

/// Writes `stem.svg` and `stem.png`: the charts in a grid of `cols` columns, 800×600 each.
pub fn save_grid(charts: &[Chart], cols: usize, stem: &Path) -> Result<Vec<String>, String> {
    let cols = cols.max(1);
    let rows = charts.len().div_ceil(cols).max(1);
    let size = (800 * cols as u32, 600 * rows as u32);
    let svg = stem.with_extension("svg");
    let png = stem.with_extension("png");
    fn all<DB: DrawingBackend>(
        area: DrawingArea<DB, plotters::coord::Shift>,
        charts: &[Chart],
        grid: (usize, usize),
    ) -> Result<(), String>
    where
        DB::ErrorType: 'static,
    {
        for (a, c) in area.split_evenly(grid).into_iter().zip(charts) {
            draw(a, c)?;
        }
        Ok(())
    }
    all(
        SVGBackend::new(&svg, size).into_drawing_area(),
        charts,
        (rows, cols),
    )?;
    all(
        BitMapBackend::new(&png, size).into_drawing_area(),
        charts,
        (rows, cols),
    )?;
    Ok(vec![svg.display().to_string(), png.display().to_string()])
}

/// Writes `stem.svg` and `stem.png` (800×600).
pub fn save(chart: &Chart, stem: &Path) -> Result<Vec<String>, String> {
    let svg = stem.with_extension("svg");
    let png = stem.with_extension("png");
    draw(SVGBackend::new(&svg, (800, 600)).into_drawing_area(), chart)?;
    draw(
        BitMapBackend::new(&png, (800, 600)).into_drawing_area(),
        chart,
    )?;
    Ok(vec![svg.display().to_string(), png.display().to_string()])
}
