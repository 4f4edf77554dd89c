//! A chart with our axes: grid, ticks, tick labels, axis names, and the
//! frame around the plot area.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::layout::Layout;
use crate::sizes::Sizes;
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
    chart
        .configure_mesh()
        .bold_line_style(RGBColor(220, 220, 220).stroke_width(sizes.px(1.0) as u32))
        .light_line_style(RGBColor(240, 240, 240).stroke_width(sizes.px(1.0) as u32))
        .axis_style(BLACK.stroke_width(sizes.axis()))
        .set_all_tick_mark_size(sizes.px(8.0))
        .label_style(sizes.font(sizes.tick()))
        .axis_desc_style(sizes.font(sizes.label()))
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()?;
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
