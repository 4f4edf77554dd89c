//! A chart with our axes: grid, ticks, tick labels, axis names, and the
//! frame around the plot area.

use plotters::coord::Shift;
use plotters::prelude::*;

use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::layout::{fitted, Layout};
use crate::sizes::{text_width, Sizes};
use crate::ticks::Axis;
use crate::FigureError;

/// Build a chart with axes `x`, `y` (coordinates: [`Axis::coord`]) and draw
/// its grid, ticks, labels and axis names.
pub(crate) fn chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    sizes: &Sizes,
    layout: &Layout,
    x: &Axis,
    y: &Axis,
    x_desc: &str,
    y_desc: &str,
) -> Result<
    ChartContext<'a, DB, Cartesian2d<impl Ranged<ValueType = f64>, impl Ranged<ValueType = f64>>>,
    FigureError,
> {
    let mut chart = ChartBuilder::on(area)
        .margin_top(layout.top)
        .margin_right(layout.right)
        .margin_bottom(layout.bottom)
        .margin_left(layout.left)
        .x_label_area_size(layout.x_area)
        .y_label_area_size(layout.y_area)
        .build_cartesian_2d(x.coord(), y.coord())?;
    let fx = |v: &f64| x.label_at(*v);
    let fy = |v: &f64| y.label_at(*v);
    let (w, h) = area.dim_in_pixel();
    let plot = layout.plot_size((w, h));
    chart
        .configure_mesh()
        .bold_line_style(RGBColor(220, 220, 220).stroke_width(sizes.px(1.0) as u32))
        .light_line_style(RGBColor(240, 240, 240).stroke_width(sizes.px(1.0) as u32))
        .axis_style(BLACK.stroke_width(sizes.axis()))
        .set_all_tick_mark_size(sizes.px(8.0))
        .label_style(sizes.font(sizes.tick()))
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .draw()?;
    // The axis names, each centred on its side of the plot, at the outer
    // edge of its label area; a name longer than its side is set smaller.
    let label = sizes.label();
    let half = (label * 0.6) as i32;
    let x_size = fitted(label, text_width(x_desc, label), plot.0);
    let y_size = fitted(label, text_width(y_desc, label), plot.1);
    let centre = |s: f64| sizes.font(s).pos(Pos::new(HPos::Center, VPos::Center));
    let (x0, y0) = (layout.left + layout.y_area, layout.top);
    area.draw(&Text::new(
        x_desc,
        (x0 + plot.0 / 2, y0 + plot.1 + layout.x_area - half),
        centre(x_size),
    ))?;
    area.draw(&Text::new(
        y_desc,
        (layout.left + half, y0 + plot.1 / 2),
        centre(y_size).transform(FontTransform::Rotate270),
    ))?;
    Ok(chart)
}

/// Close the frame around the plot area: plotters draws the left and
/// bottom axes, this adds the top and right sides.
pub(crate) fn frame<DB: DrawingBackend, X: Ranged, Y: Ranged>(
    chart: &ChartContext<'_, DB, Cartesian2d<X, Y>>,
    sizes: &Sizes,
) -> Result<(), FigureError> {
    let pa = chart.plotting_area().strip_coord_spec();
    let (w, h) = pa.dim_in_pixel();
    let (w, h) = (w as i32 - 1, h as i32 - 1);
    pa.draw(&PathElement::new(
        vec![(0, 0), (w, 0), (w, h)],
        BLACK.stroke_width(sizes.axis()),
    ))?;
    Ok(())
}
