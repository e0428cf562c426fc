//! The picture's frame: the title band, the 3D chart (seed's camera), its grid, ticks in
//! metres and axis names.

use super::{View, TITLE_H};
use anyhow::anyhow;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Elevation of the view (degrees), as in the seed's `ax.view_init(elev=5, azim=50)`.
pub const PITCH_DEG: f64 = 5.0;
/// Azimuth of the view (degrees).
pub const YAW_DEG: f64 = 50.0;
/// Zoom of the 3D box inside the plotting area.
const SCALE: f64 = 0.8;

/// Plotters' coordinates (X right, Y up, Z towards the viewer before the view's rotation):
/// X = base y, Y = base z, Z = base x, a rotation (a cyclic permutation), so the picture
/// keeps the base frame right-handed.
pub type Coord3 = (f64, f64, f64);

/// A base-frame point in plotters' coordinates.
pub fn to_plot(p: [f64; 3]) -> Coord3 {
    (p[1], p[2], p[0])
}

/// The unit vector from the scene towards the camera, in the base frame: matplotlib's
/// `(cos elev·cos azim, cos elev·sin azim, sin elev)`.
pub fn towards_camera() -> [f64; 3] {
    let (e, a) = (PITCH_DEG.to_radians(), YAW_DEG.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

/// The 3D chart type of every picture.
pub type Chart3<'a, DB> = ChartContext<
    'a,
    DB,
    plotters::coord::ranged3d::Cartesian3d<
        plotters::coord::types::RangedCoordf64,
        plotters::coord::types::RangedCoordf64,
        plotters::coord::types::RangedCoordf64,
    >,
>;

/// Splits the root into the title band and the chart, and builds the 3D chart. Its layout
/// depends only on the view (not on the title's text), so [`super::project`] can rebuild it.
pub fn build<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    view: &View,
) -> anyhow::Result<(DrawingArea<DB, Shift>, Chart3<'a, DB>)> {
    let (title, body) = root.split_vertically(TITLE_H);
    let mut chart = ChartBuilder::on(&body)
        .margin(4)
        .build_cartesian_3d(view.y.0..view.y.1, view.z.0..view.z.1, view.x.0..view.x.1)
        .map_err(|e| anyhow!("chart: {e}"))?;
    chart.with_projection(|mut p| {
        p.pitch = PITCH_DEG.to_radians();
        p.yaw = YAW_DEG.to_radians();
        p.scale = SCALE;
        p.into_matrix()
    });
    Ok((title, chart))
}

/// Draws the title, centred in its band.
pub fn title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (tw, th) = area.dim_in_pixel();
    let style = ("sans-serif", 22)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Center));
    area.draw(&Text::new(
        text.to_string(),
        (tw as i32 / 2, th as i32 / 2 + 4),
        style,
    ))
}

/// A tick label in metres with one decimal: never "-0.0", and empty at `skip` (a corner
/// where another axis's label already sits).
pub fn tick_label(v: f64, skip: Option<f64>) -> String {
    if skip.is_some_and(|s| (v - s).abs() < 1e-9) {
        return String::new();
    }
    let s = format!("{v:.1}");
    if s == "-0.0" {
        "0.0".to_string()
    } else {
        s
    }
}

/// Draws the grid, the ticks and the axis names.
pub fn axes<DB: DrawingBackend>(
    chart: &mut Chart3<'_, DB>,
    view: &View,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    // The x ticks run along y = y_max and the y ticks along x = x_max: both have a label at
    // the front corner (x_max, y_max), where they would overlap, so x leaves it to y.
    let x_corner = view.x.1;
    let fx = move |v: &f64| tick_label(*v, Some(x_corner));
    let f = |v: &f64| tick_label(*v, None);
    chart
        .configure_axes()
        .light_grid_style(RGBColor(225, 225, 225))
        .bold_grid_style(RGBColor(200, 200, 200))
        .axis_panel_style(RGBColor(246, 246, 250))
        .max_light_lines(1)
        .x_labels(7)
        .y_labels(7)
        .z_labels(7)
        .label_style(("sans-serif", 13).into_font().color(&RGBColor(60, 60, 60)))
        // Plotters' X is base y, Z is base x (see `to_plot`).
        .x_formatter(&f)
        .y_formatter(&f)
        .z_formatter(&fx)
        .draw()?;
    // Axis names: beside the middle of the two front floor edges and above the vertical z
    // edge (x_min, y_max).
    let name_style = ("sans-serif", 16).into_font().color(&BLACK);
    let (x0, x1) = view.x;
    let (y0, y1) = view.y;
    let (z0, z1) = view.z;
    let area = chart.plotting_area();
    let label = |p: [f64; 3], dx: i32, dy: i32, s: &'static str| {
        EmptyElement::at(to_plot(p)) + Text::new(s, (dx, dy), name_style.clone())
    };
    area.draw(&label([(x0 + x1) / 2.0, y1, z0], 34, 26, "x [m]"))?;
    area.draw(&label([x1, (y0 + y1) / 2.0, z0], -70, 26, "y [m]"))?;
    area.draw(&label([x0, y1, z1], -4, -30, "z [m]"))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_have_no_negative_zero_and_skip_the_corner() {
        assert_eq!(tick_label(-0.0, None), "0.0");
        assert_eq!(tick_label(-0.04, None), "0.0");
        assert_eq!(tick_label(-0.06, None), "-0.1");
        assert_eq!(tick_label(0.2, Some(0.2)), "");
        assert_eq!(tick_label(0.4, Some(0.2)), "0.4");
    }
}
