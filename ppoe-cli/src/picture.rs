//! Pictures of a robot and its tool-pose distribution (PNG, SVG, GIF), drawn with
//! [`plotters`] without a window system.
//!
//! Every picture is [`WIDTH`]×[`HEIGHT`] = 800×700 pixels (PNG, every GIF frame, and the
//! SVG's view box) and shows, in a 3D view like the seed's (elevation 5°, azimuth 50°):
//! * the arm as a skeleton: thick grey segments between successive joint positions (base,
//!   each joint, tool), with a dot at each joint;
//! * small RGB axes (x red, y green, z blue) at the base, at every joint and at the tool;
//! * the equiprobable surface of the tool position as semi-transparent orange shaded
//!   polygons with a darker wireframe;
//! * the mean tool position (black dot) and the second-order mean of the tool position
//!   (purple cross);
//! * axis ticks in metres, a title (with the frame number) and a legend that names the
//!   surface (`sigma_label`).
//!
//! The 3D scene is drawn back to front (painter's algorithm over the surface's polygons,
//! the skeleton's segments and the axes) so the arm shows through the translucent surface.
//! Text uses DejaVu Sans, embedded in the binary (`assets/DejaVuSans.ttf`, licence in
//! `assets/DejaVuSans-LICENSE.txt`), so no system font is needed.

use anyhow::{anyhow, Context};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::Path;

/// Width of every picture in pixels.
pub const WIDTH: u32 = 800;
/// Height of every picture in pixels.
pub const HEIGHT: u32 = 700;
/// Delay between GIF frames in milliseconds.
pub const GIF_DELAY_MS: u32 = 50;
/// Height of the title band at the top of the picture, in pixels.
const TITLE_H: u32 = 44;
/// Elevation of the view (degrees), as in the seed's `ax.view_init(elev=5, azim=50)`.
const PITCH_DEG: f64 = 5.0;
/// Azimuth of the view (degrees).
const YAW_DEG: f64 = 50.0;
/// Zoom of the 3D box inside the plotting area.
const SCALE: f64 = 0.8;

const FONT: &[u8] = include_bytes!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/assets/DejaVuSans.ttf"
));

const SKELETON: RGBColor = RGBColor(70, 70, 78);
const SURFACE: RGBColor = RGBColor(245, 130, 20);
const WIRE: RGBColor = RGBColor(190, 85, 0);
const MEAN2: RGBColor = RGBColor(150, 20, 170);
const AXIS_COLORS: [RGBColor; 3] = [
    RGBColor(220, 30, 30),
    RGBColor(20, 160, 40),
    RGBColor(30, 60, 230),
];

/// One picture: the arm, its frames, the tool, the equiprobable surface and the
/// second-order mean, all in the base frame (metres).
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The title (e.g. with the frame number).
    pub title: String,
    /// Points of the skeleton, base to tool: the base origin, each joint, the tool.
    pub joints: Vec<[f64; 3]>,
    /// Frames to draw as small RGB axes: the base, each joint, the tool (row-major 4×4).
    pub frames: Vec<[[f64; 4]; 4]>,
    /// The mean tool pose (row-major 4×4).
    pub tool: [[f64; 4]; 4],
    /// The surface: an n×n grid of points (rows = φ, columns = θ, both endpoints included,
    /// so the grid closes without wrapping).
    pub surface: Vec<Vec<[f64; 3]>>,
    /// The second-order mean of the tool position.
    pub mean2: [f64; 3],
    /// What the surface is (kind and probability level).
    pub sigma_label: String,
}

/// The fixed part of a picture: the axis ranges (metres, base frame) and the image size.
///
/// The three ranges have the same length, so the 3D box is a cube and the surface is not
/// distorted. One `View` is used for all frames of an animation, so it does not jump.
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    /// Range of the base x coordinate.
    pub x: (f64, f64),
    /// Range of the base y coordinate.
    pub y: (f64, f64),
    /// Range of the base z coordinate (drawn upwards).
    pub z: (f64, f64),
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

impl View {
    /// A view that holds every finite point of every frame (skeleton, frame axes, tool,
    /// surface, second-order mean) with a margin: x and y symmetric about the base's z axis
    /// (with the horizontal distance of the farthest point, so a rotation about the base z
    /// axis does not change it), z from below the lowest point, all three ranges of the same
    /// length (rounded up to 0.1 m).
    pub fn fit(frames: &[Frame]) -> View {
        let mut lo = [0.0f64; 3];
        let mut hi = [0.0f64; 3];
        for f in frames {
            let al = axis_len_hint(f);
            let mut add = |p: &[f64; 3], pad: f64| {
                if finite(p) {
                    for k in 0..3 {
                        lo[k] = lo[k].min(p[k] - pad);
                        hi[k] = hi[k].max(p[k] + pad);
                    }
                }
            };
            for p in &f.joints {
                add(p, al);
            }
            for m in f.frames.iter().chain(std::iter::once(&f.tool)) {
                add(&[m[0][3], m[1][3], m[2][3]], al);
            }
            for p in f.surface.iter().flatten() {
                add(p, 0.0);
            }
            add(&f.mean2, 0.0);
        }
        let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f64, f64::max);
        // A cube 10 % larger than the largest extent, in whole decimetres (at least 0.2 m).
        let span = ((extent * 1.1 * 10.0 - 1e-9).ceil() / 10.0).max(0.2);
        let centre = |k: usize| ((lo[k] + hi[k]) / 2.0 * 20.0).round() / 20.0;
        let range = |c: f64| (c - span / 2.0, c + span / 2.0);
        let (cz0, _) = range(centre(2));
        // Keep the floor (z = 0) in view when the arm stands on it and there is room.
        let z0 = if lo[2] >= 0.0 && hi[2] <= span {
            0.0
        } else {
            cz0
        };
        View {
            x: range(centre(0)),
            y: range(centre(1)),
            z: (z0, z0 + span),
            width: WIDTH,
            height: HEIGHT,
        }
    }
}

/// A length for the small frame axes: 0.05 m, or 6 % of the arm's size for a large arm.
fn axis_len_hint(f: &Frame) -> f64 {
    let mut size: f64 = 0.0;
    for w in f.joints.windows(2) {
        if finite(&w[0]) && finite(&w[1]) {
            size += norm(sub(w[1], w[0]));
        }
    }
    (0.05f64).max(0.06 * size)
}

fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The embedded font is a valid TrueType file; a failure would only lose the text.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// Plotters' coordinates (X right, Y up, Z towards the viewer before the view's rotation):
/// X = base y, Y = base z, Z = base x, a rotation (a cyclic permutation), so the picture
/// keeps the base frame right-handed.
type Coord3 = (f64, f64, f64);

fn to_plot(p: [f64; 3]) -> Coord3 {
    (p[1], p[2], p[0])
}

type Chart3<'a, DB> = ChartContext<
    'a,
    DB,
    plotters::coord::ranged3d::Cartesian3d<
        plotters::coord::types::RangedCoordf64,
        plotters::coord::types::RangedCoordf64,
        plotters::coord::types::RangedCoordf64,
    >,
>;

/// Splits the root into the title band and the chart, and builds the 3D chart. Its layout
/// depends only on the view (not on the title's text), so [`project`] can rebuild it.
fn build_chart<'a, DB: DrawingBackend>(
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

/// Pixel coordinates (x right, y down, from the top-left corner of the image) of the 3D
/// point `p` (metres, base frame) in a picture drawn with `view`.
#[cfg_attr(not(test), allow(dead_code))] // used by the tests
pub fn project(frame_view: &View, p: [f64; 3]) -> (f64, f64) {
    register_font();
    let (w, h) = (frame_view.width, frame_view.height);
    let mut buf = vec![0u8; w as usize * h as usize * 3];
    let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
    let out = match build_chart(&root, frame_view) {
        Ok((_, chart)) => {
            let (x, y) = chart.as_coord_spec().translate(&to_plot(p));
            (x as f64, y as f64)
        }
        Err(_) => (f64::NAN, f64::NAN),
    };
    out
}

/// One 3D item of the scene, drawn back to front.
enum Item {
    /// A filled polygon (a surface patch) with its outline pieces.
    Patch { pts: Vec<Coord3>, fill: RGBAColor },
    /// A line segment.
    Segment {
        a: Coord3,
        b: Coord3,
        color: RGBAColor,
        width: u32,
    },
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}
fn finite(p: &[f64; 3]) -> bool {
    p.iter().all(|c| c.is_finite())
}

/// Draws one picture on `root` (already cleared by the caller or not: this fills it white).
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
    view: &View,
) -> anyhow::Result<()> {
    register_font();
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("drawing: {e}");
    root.fill(&WHITE).map_err(e)?;
    let (title_area, mut chart) = build_chart(root, view)?;

    // Title.
    let (tw, th) = title_area.dim_in_pixel();
    title_area
        .draw(&Text::new(
            frame.title.clone(),
            (tw as i32 / 2, th as i32 / 2 + 4),
            ("sans-serif", 22).into_font().color(&BLACK).pos(
                plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Center,
                    plotters::style::text_anchor::VPos::Center,
                ),
            ),
        ))
        .map_err(e)?;

    // Axes, ticks in metres.
    let fmt = |v: &f64| format!("{:.1}", v);
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
        .x_formatter(&fmt)
        .y_formatter(&fmt)
        .z_formatter(&fmt)
        .draw()
        .map_err(e)?;
    // Axis names: beside the middle of the two front floor edges (the y ticks run along
    // x = x_max, the x ticks along y = y_max) and above the vertical z edge (x_min, y_max).
    {
        let name_style = ("sans-serif", 16).into_font().color(&BLACK);
        let (x0, x1) = view.x;
        let (y0, y1) = view.y;
        let (z0, z1) = view.z;
        let area = chart.plotting_area();
        let label = |p: [f64; 3], dx: i32, dy: i32, s: &'static str| {
            EmptyElement::at(to_plot(p)) + Text::new(s, (dx, dy), name_style.clone())
        };
        area.draw(&label([(x0 + x1) / 2.0, y1, z0], 34, 26, "x [m]"))
            .map_err(e)?;
        area.draw(&label([x1, (y0 + y1) / 2.0, z0], -70, 26, "y [m]"))
            .map_err(e)?;
        area.draw(&label([x0, y1, z1], -4, -30, "z [m]"))
            .map_err(e)?;
    }

    // The scene.
    let mut items: Vec<Item> = Vec::new();
    let rows = &frame.surface;
    let n_rows = rows.len();
    if n_rows >= 2 {
        let light = {
            let l = [0.4, -0.3, 0.85];
            let n = norm(l);
            [l[0] / n, l[1] / n, l[2] / n]
        };
        let centre = surface_centre(frame);
        for i in 0..n_rows - 1 {
            let m = rows[i].len().min(rows[i + 1].len());
            for j in 0..m.saturating_sub(1) {
                let q = [
                    rows[i][j],
                    rows[i + 1][j],
                    rows[i + 1][j + 1],
                    rows[i][j + 1],
                ];
                if !q.iter().all(finite) {
                    continue;
                }
                let mut nrm = cross(sub(q[2], q[0]), sub(q[3], q[1]));
                let len = norm(nrm);
                if len < 1e-300 {
                    continue;
                }
                for c in &mut nrm {
                    *c /= len;
                }
                // Point the normal outwards so the shading is consistent.
                let mid = [
                    (q[0][0] + q[2][0]) / 2.0,
                    (q[0][1] + q[2][1]) / 2.0,
                    (q[0][2] + q[2][2]) / 2.0,
                ];
                let out = sub(mid, centre);
                if out[0] * nrm[0] + out[1] * nrm[1] + out[2] * nrm[2] < 0.0 {
                    for c in &mut nrm {
                        *c = -*c;
                    }
                }
                let lambert = (nrm[0] * light[0] + nrm[1] * light[1] + nrm[2] * light[2]).abs();
                let k = 0.55 + 0.45 * lambert;
                let fill = RGBColor(
                    (SURFACE.0 as f64 * k) as u8,
                    (SURFACE.1 as f64 * k) as u8,
                    (SURFACE.2 as f64 * k) as u8,
                )
                .mix(0.30);
                items.push(Item::Patch {
                    pts: q.iter().map(|p| to_plot(*p)).collect(),
                    fill,
                });
            }
        }
        // Wireframe: about 16 lines each way.
        let n_cols = rows.iter().map(|r| r.len()).min().unwrap_or(0);
        let stride_i = ((n_rows - 1) / 12).max(1);
        let stride_j = ((n_cols.max(2) - 1) / 18).max(1);
        let wire = WIRE.mix(0.55);
        let mut wire_line = |a: [f64; 3], b: [f64; 3]| {
            if finite(&a) && finite(&b) && norm(sub(a, b)) > 0.0 {
                items.push(Item::Segment {
                    a: to_plot(a),
                    b: to_plot(b),
                    color: wire,
                    width: 1,
                });
            }
        };
        for i in (0..n_rows).step_by(stride_i) {
            for j in 0..n_cols.saturating_sub(1) {
                wire_line(rows[i][j], rows[i][j + 1]);
            }
        }
        for j in (0..n_cols).step_by(stride_j) {
            for i in 0..n_rows - 1 {
                wire_line(rows[i][j], rows[i + 1][j]);
            }
        }
    }
    // Skeleton.
    for w in frame.joints.windows(2) {
        if finite(&w[0]) && finite(&w[1]) {
            items.push(Item::Segment {
                a: to_plot(w[0]),
                b: to_plot(w[1]),
                color: SKELETON.to_rgba(),
                width: 6,
            });
        }
    }
    // Frame axes.
    let al = axis_len_hint(frame);
    for m in frame.frames.iter().chain(std::iter::once(&frame.tool)) {
        let o = [m[0][3], m[1][3], m[2][3]];
        for (a, color) in AXIS_COLORS.iter().enumerate() {
            let tip = [
                o[0] + al * m[0][a],
                o[1] + al * m[1][a],
                o[2] + al * m[2][a],
            ];
            if finite(&o) && finite(&tip) {
                items.push(Item::Segment {
                    a: to_plot(o),
                    b: to_plot(tip),
                    color: color.to_rgba(),
                    width: 3,
                });
            }
        }
    }

    // Back to front: a larger projected depth is farther from the viewer.
    let coord = chart.as_coord_spec().clone();
    let depth = |p: &Coord3| coord.projected_depth(&p.0, &p.1, &p.2) as f64;
    let mut keyed: Vec<(f64, Item)> = items
        .into_iter()
        .map(|it| {
            let d = match &it {
                Item::Patch { pts, .. } => pts.iter().map(&depth).sum::<f64>() / pts.len() as f64,
                Item::Segment { a, b, .. } => (depth(a) + depth(b)) / 2.0,
            };
            (d, it)
        })
        .collect();
    keyed.sort_by(|a, b| b.0.total_cmp(&a.0));
    let area = chart.plotting_area();
    for (_, it) in keyed {
        match it {
            Item::Patch { pts, fill } => {
                area.draw(&Polygon::new(pts, fill.filled())).map_err(e)?;
            }
            Item::Segment { a, b, color, width } => {
                area.draw(&PathElement::new(vec![a, b], color.stroke_width(width)))
                    .map_err(e)?;
            }
        }
    }
    // Joint dots, tool dot and second-order mean on top.
    for p in frame.joints.iter().filter(|p| finite(p)) {
        area.draw(&Circle::new(to_plot(*p), 4, SKELETON.filled()))
            .map_err(e)?;
    }
    let tool = [frame.tool[0][3], frame.tool[1][3], frame.tool[2][3]];
    if finite(&tool) {
        area.draw(&Circle::new(to_plot(tool), 4, BLACK.filled()))
            .map_err(e)?;
    }
    if finite(&frame.mean2) {
        area.draw(&Cross::new(to_plot(frame.mean2), 6, MEAN2.stroke_width(3)))
            .map_err(e)?;
    }

    draw_legend(root, frame).map_err(e)?;
    Ok(())
}

/// The mean of the surface's finite points (the tool position for a centred surface).
fn surface_centre(frame: &Frame) -> [f64; 3] {
    let mut s = [0.0; 3];
    let mut n = 0usize;
    for p in frame.surface.iter().flatten().filter(|p| finite(p)) {
        for k in 0..3 {
            s[k] += p[k];
        }
        n += 1;
    }
    if n == 0 {
        return [frame.tool[0][3], frame.tool[1][3], frame.tool[2][3]];
    }
    [s[0] / n as f64, s[1] / n as f64, s[2] / n as f64]
}

fn draw_legend<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let style = ("sans-serif", 14).into_font().color(&BLACK);
    let x0 = 12i32;
    let line_h = 20i32;
    let entries = 4;
    let y0 = TITLE_H as i32 + 8;
    let w = 12 + 36 + 8 + 7 * frame.sigma_label.chars().count().max(34) as i32;
    root.draw(&Rectangle::new(
        [(x0 - 6, y0 - 6), (x0 + w, y0 + line_h * entries + 2)],
        WHITE.mix(0.85).filled(),
    ))?;
    root.draw(&Rectangle::new(
        [(x0 - 6, y0 - 6), (x0 + w, y0 + line_h * entries + 2)],
        RGBColor(180, 180, 180).stroke_width(1),
    ))?;
    let text_x = x0 + 44;
    let mut y = y0 + line_h / 2;
    // Arm.
    root.draw(&PathElement::new(
        vec![(x0, y), (x0 + 34, y)],
        SKELETON.stroke_width(6),
    ))?;
    root.draw(&Text::new(
        "arm: base, joints, tool",
        (text_x, y - 8),
        style.clone(),
    ))?;
    y += line_h;
    // Frame axes.
    for (k, c) in AXIS_COLORS.iter().enumerate() {
        let xa = x0 + 12 * k as i32;
        root.draw(&PathElement::new(
            vec![(xa, y), (xa + 10, y)],
            c.stroke_width(3),
        ))?;
    }
    root.draw(&Text::new(
        "frame axes x, y, z (base, joints, tool)",
        (text_x, y - 8),
        style.clone(),
    ))?;
    y += line_h;
    // Surface.
    root.draw(&Rectangle::new(
        [(x0, y - 7), (x0 + 34, y + 7)],
        SURFACE.mix(0.45).filled(),
    ))?;
    root.draw(&Rectangle::new(
        [(x0, y - 7), (x0 + 34, y + 7)],
        WIRE.stroke_width(1),
    ))?;
    root.draw(&Text::new(
        frame.sigma_label.clone(),
        (text_x, y - 8),
        style.clone(),
    ))?;
    y += line_h;
    // Means.
    root.draw(&Circle::new((x0 + 7, y), 4, BLACK.filled()))?;
    root.draw(&Cross::new((x0 + 25, y), 6, MEAN2.stroke_width(3)))?;
    root.draw(&Text::new(
        "mean tool position · second-order mean",
        (text_x, y - 8),
        style,
    ))?;
    Ok(())
}

/// Writes one frame as an 800×700 PNG image (axis ranges fitted to this frame).
pub fn write_png(path: &Path, frame: &Frame) -> anyhow::Result<()> {
    write_png_with_view(path, frame, &View::fit(std::slice::from_ref(frame)))
}

/// Writes one frame as an 800×700 PNG image with the given view.
pub fn write_png_with_view(path: &Path, frame: &Frame, view: &View) -> anyhow::Result<()> {
    let root = BitMapBackend::new(path, (view.width, view.height)).into_drawing_area();
    draw(&root, frame, view)?;
    root.present()
        .map_err(|e| anyhow!("{e}"))
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Writes one frame as an SVG image (800×700 view box, axis ranges fitted to this frame).
pub fn write_svg(path: &Path, frame: &Frame) -> anyhow::Result<()> {
    let view = View::fit(std::slice::from_ref(frame));
    let root = SVGBackend::new(path, (view.width, view.height)).into_drawing_area();
    draw(&root, frame, &view)?;
    root.present()
        .map_err(|e| anyhow!("{e}"))
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Writes the frames as an animated GIF: every frame 800×700, [`GIF_DELAY_MS`] ms apart,
/// one fixed view fitted to all frames (so the axes do not jump), looping.
pub fn write_gif(path: &Path, frames: &[Frame]) -> anyhow::Result<()> {
    write_gif_with_progress(path, frames, &mut |_| {})
}

/// The colours the pictures draw with, kept exactly in the GIF palette (small items such
/// as the RGB frame axes would otherwise lose their colour to the quantiser).
fn key_colours() -> Vec<[u8; 3]> {
    let mut c: Vec<[u8; 3]> = vec![
        [255, 255, 255],
        [0, 0, 0],
        [246, 246, 250],
        [225, 225, 225],
        [200, 200, 200],
        [180, 180, 180],
        [60, 60, 60],
    ];
    for k in [SKELETON, SURFACE, WIRE, MEAN2]
        .iter()
        .chain(AXIS_COLORS.iter())
    {
        c.push([k.0, k.1, k.2]);
    }
    c
}

/// Bits per channel of the colour look-up table that maps RGB to the palette.
const LUT_BITS: u32 = 6;

/// One palette for the whole animation: the [`key_colours`], then colours learnt by
/// NeuQuant from sample frames; and a look-up table from RGB (top [`LUT_BITS`] bits of each
/// channel) to the nearest palette entry.
struct Palette {
    rgb: Vec<u8>,
    lut: Vec<u8>,
}

impl Palette {
    fn learn(samples: &[Vec<u8>]) -> Palette {
        let keys = key_colours();
        let mut rgba = Vec::new();
        for buf in samples {
            for px in buf.chunks_exact(3).step_by(3) {
                rgba.extend_from_slice(&[px[0], px[1], px[2], 255]);
            }
        }
        let mut rgb: Vec<u8> = keys.iter().flatten().copied().collect();
        if !rgba.is_empty() {
            let nq = color_quant::NeuQuant::new(3, 256 - keys.len(), &rgba);
            rgb.extend(nq.color_map_rgb());
        }
        let colours: Vec<[i32; 3]> = rgb
            .chunks_exact(3)
            .map(|c| [c[0] as i32, c[1] as i32, c[2] as i32])
            .collect();
        let levels = 1usize << LUT_BITS;
        let shift = 8 - LUT_BITS;
        let mut lut = vec![0u8; levels * levels * levels];
        for (cell, slot) in lut.iter_mut().enumerate() {
            let ch = |k: usize| {
                (((cell >> (k * LUT_BITS as usize)) & (levels - 1)) << shift) as i32
                    + (1 << shift) / 2
            };
            let (r, g, b) = (ch(2), ch(1), ch(0));
            let mut best = (i32::MAX, 0usize);
            for (i, c) in colours.iter().enumerate() {
                let d = (c[0] - r).pow(2) * 3 + (c[1] - g).pow(2) * 4 + (c[2] - b).pow(2) * 2;
                if d < best.0 {
                    best = (d, i);
                }
            }
            *slot = best.1 as u8;
        }
        Palette { rgb, lut }
    }

    fn index(&self, r: u8, g: u8, b: u8) -> u8 {
        let shift = 8 - LUT_BITS;
        let cell = ((r as usize >> shift) << (2 * LUT_BITS))
            | ((g as usize >> shift) << LUT_BITS)
            | (b as usize >> shift);
        self.lut[cell]
    }
}

/// Draws one frame into an RGB buffer.
fn rgb_buffer(frame: &Frame, view: &View) -> anyhow::Result<Vec<u8>> {
    let (w, h) = (view.width, view.height);
    let mut buf = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        draw(&root, frame, view)?;
        root.present().map_err(|e| anyhow!("{e}"))?;
    }
    Ok(buf)
}

/// Draws one frame and maps it to the palette: a GIF frame.
fn gif_frame(frame: &Frame, view: &View, palette: &Palette) -> anyhow::Result<gif::Frame<'static>> {
    let buf = rgb_buffer(frame, view)?;
    let indices: Vec<u8> = buf
        .chunks_exact(3)
        .map(|p| palette.index(p[0], p[1], p[2]))
        .collect();
    Ok(gif::Frame {
        width: view.width as u16,
        height: view.height as u16,
        delay: (GIF_DELAY_MS / 10) as u16,
        buffer: std::borrow::Cow::Owned(indices),
        ..gif::Frame::default()
    })
}

/// As [`write_gif`], calling `progress(i)` after frame `i` (0-based) is written, in order.
///
/// Frames are drawn with plotters on all available cores (a few frames per core at a
/// time, so memory stays small) and written in order by the `gif` encoder with one global
/// palette (the drawing colours exactly, plus colours learnt from a few sample frames).
pub fn write_gif_with_progress(
    path: &Path,
    frames: &[Frame],
    progress: &mut dyn FnMut(usize),
) -> anyhow::Result<()> {
    anyhow::ensure!(
        !frames.is_empty(),
        "no frames to write to {}",
        path.display()
    );
    let view = View::fit(frames);
    let (w, h) = (view.width, view.height);
    anyhow::ensure!(
        w <= u16::MAX as u32 && h <= u16::MAX as u32,
        "image too large for a GIF"
    );
    let n_samples = 4.min(frames.len());
    let samples = (0..n_samples)
        .map(|k| rgb_buffer(&frames[k * frames.len() / n_samples], &view))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let palette = Palette::learn(&samples);
    drop(samples);
    let file =
        std::fs::File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    let mut enc = gif::Encoder::new(
        std::io::BufWriter::new(file),
        w as u16,
        h as u16,
        &palette.rgb,
    )
    .with_context(|| format!("cannot write {}", path.display()))?;
    enc.set_repeat(gif::Repeat::Infinite)?;
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, 8);
    let batch = threads * 4;
    for (b, chunk) in frames.chunks(batch).enumerate() {
        let mut done: Vec<(usize, anyhow::Result<gif::Frame<'static>>)> = std::thread::scope(|s| {
            let (view, palette) = (&view, &palette);
            let handles: Vec<_> = (0..threads)
                .map(|t| {
                    s.spawn(move || {
                        chunk
                            .iter()
                            .enumerate()
                            .skip(t)
                            .step_by(threads)
                            .map(|(i, f)| (i, gif_frame(f, view, palette)))
                            .collect::<Vec<_>>()
                    })
                })
                .collect();
            handles
                .into_iter()
                .flat_map(|h| {
                    h.join().unwrap_or_else(|_| {
                        vec![(usize::MAX, Err(anyhow!("a drawing thread panicked")))]
                    })
                })
                .collect()
        });
        done.sort_by_key(|(i, _)| *i);
        for (i, fr) in done {
            enc.write_frame(&fr?)
                .with_context(|| format!("cannot write {}", path.display()))?;
            progress(b * batch + i);
        }
    }
    enc.into_inner()
        .with_context(|| format!("cannot write {}", path.display()))?
        .into_inner()
        .map_err(|e| anyhow!("cannot write {}: {}", path.display(), e.error()))?;
    Ok(())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A 3-segment arm (base, two joints, tool) with a small ellipsoid grid around the tool.
    pub(crate) fn synthetic_frame(title: &str, lift: f64) -> Frame {
        let joints = vec![
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 0.4],
            [0.3, 0.0, 0.7 + lift],
            [0.6, 0.1, 0.7 + lift],
        ];
        let pose = |p: [f64; 3]| {
            [
                [1.0, 0.0, 0.0, p[0]],
                [0.0, 1.0, 0.0, p[1]],
                [0.0, 0.0, 1.0, p[2]],
                [0.0, 0.0, 0.0, 1.0],
            ]
        };
        let tool_p = joints[3];
        let n = 20;
        let surface = (0..n)
            .map(|i| {
                let phi = std::f64::consts::PI * i as f64 / (n - 1) as f64;
                (0..n)
                    .map(|j| {
                        let th = 2.0 * std::f64::consts::PI * j as f64 / (n - 1) as f64;
                        [
                            tool_p[0] + 0.08 * phi.sin() * th.cos(),
                            tool_p[1] + 0.05 * phi.sin() * th.sin(),
                            tool_p[2] + 0.12 * phi.cos(),
                        ]
                    })
                    .collect()
            })
            .collect();
        Frame {
            title: title.to_string(),
            frames: joints.iter().map(|p| pose(*p)).collect(),
            joints,
            tool: pose(tool_p),
            surface,
            mean2: [tool_p[0] - 0.02, tool_p[1], tool_p[2] - 0.01],
            sigma_label: "2σ (74 %) test surface".to_string(),
        }
    }

    pub(crate) fn temp_path(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("ppoe-cli-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    fn decode_png(path: &Path) -> (u32, u32, Vec<u8>) {
        let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!(info.color_type, png::ColorType::Rgb);
        assert_eq!(info.bit_depth, png::BitDepth::Eight);
        buf.truncate(info.buffer_size());
        (info.width, info.height, buf)
    }

    #[test]
    fn png_has_the_stated_size_and_is_not_blank() {
        let frame = synthetic_frame("PPOE test robot — frame 1/3", 0.0);
        let path = temp_path("picture.png");
        write_png(&path, &frame).unwrap();
        let (w, h, px) = decode_png(&path);
        assert_eq!((w, h), (WIDTH, HEIGHT));
        assert_eq!(px.len(), (w * h * 3) as usize);
        let non_white = px.chunks(3).filter(|c| c != &[255, 255, 255]).count();
        assert!(
            non_white > (w * h / 20) as usize,
            "only {non_white} non-white pixels"
        );
        let distinct: std::collections::HashSet<&[u8]> = px.chunks(3).collect();
        assert!(distinct.len() > 100, "only {} colours", distinct.len());
    }

    #[test]
    fn surface_centre_lands_on_the_drawn_tool() {
        let frame = synthetic_frame("centre", 0.0);
        let view = View::fit(std::slice::from_ref(&frame));
        let path = temp_path("centre.png");
        write_png_with_view(&path, &frame, &view).unwrap();
        let (w, _, px) = decode_png(&path);
        let tool = [frame.tool[0][3], frame.tool[1][3], frame.tool[2][3]];
        let (tx, ty) = project(&view, tool);
        let (cx, cy) = project(&view, surface_centre(&frame));
        assert!(
            (tx - cx).hypot(ty - cy) <= 2.0,
            "tool ({tx}, {ty}) vs centre ({cx}, {cy})"
        );
        // The tool's markers are drawn there: the black dot of the mean tool position and the
        // purple cross of the second-order mean (the surface around them is light orange).
        let at = |x: f64, y: f64| {
            let i = ((y as u32 * w + x as u32) * 3) as usize;
            [px[i], px[i + 1], px[i + 2]]
        };
        let c = at(cx, cy);
        let dark = |c: [u8; 3]| c.iter().map(|&v| v as u32).sum::<u32>() < 400;
        assert!(dark(c), "pixel at the surface centre is {c:?}");
        // A pixel on the surface's rim but away from the skeleton is surface-coloured.
        let top = frame.surface[0][0];
        let (sx, sy) = project(&view, [top[0], top[1], top[2] - 0.02]);
        let s = at(sx, sy);
        assert!(
            s != [255, 255, 255] && s[0] > s[2],
            "pixel inside the surface is {s:?}"
        );
        // Far from the scene (the top right corner of the box) is background.
        // Far from the scene (high on the back wall x = x_min) is background or grid.
        let span = view.x.1 - view.x.0;
        let (fx, fy) = project(
            &view,
            [view.x.0, view.y.0 + 0.7 * span, view.z.0 + 0.85 * span],
        );
        let f = at(fx, fy);
        assert!(f.iter().all(|&v| v > 180), "background pixel is {f:?}");
    }

    #[test]
    fn view_is_right_handed_like_the_seed() {
        // Elevation 5°, azimuth 50° (matplotlib's view_init): the camera looks from the
        // direction (cos 50°, sin 50°, sin 5°); base x points left, base y right, z up.
        let view = View {
            x: (-1.0, 1.0),
            y: (-1.0, 1.0),
            z: (0.0, 2.0),
            width: WIDTH,
            height: HEIGHT,
        };
        let o = project(&view, [0.0, 0.0, 0.5]);
        let x = project(&view, [0.5, 0.0, 0.5]);
        let y = project(&view, [0.0, 0.5, 0.5]);
        let z = project(&view, [0.0, 0.0, 1.0]);
        assert!(x.0 < o.0 - 50.0, "x {x:?} o {o:?}");
        assert!(y.0 > o.0 + 50.0, "y {y:?} o {o:?}");
        assert!(z.1 < o.1 - 100.0, "z {z:?} o {o:?}");
        // Seen from 5° above: +x and +y both point towards the camera (cos 50°, sin 50°), so
        // their ends appear a little lower, y's a bit more.
        assert!(x.1 > o.1 && y.1 >= x.1, "x {x:?} y {y:?} o {o:?}");
        // x is more foreshortened sideways than y (azimuth 50° > 45°).
        assert!((x.0 - o.0).abs() > (y.0 - o.0).abs());
    }

    #[test]
    fn view_is_a_cube_holding_every_frame() {
        let frames = [synthetic_frame("a", 0.0), synthetic_frame("b", 0.3)];
        let v = View::fit(&frames);
        let spans = [v.x.1 - v.x.0, v.y.1 - v.y.0, v.z.1 - v.z.0];
        assert!((spans[0] - spans[1]).abs() < 1e-12 && (spans[0] - spans[2]).abs() < 1e-12);
        for f in &frames {
            for p in f.joints.iter().chain(f.surface.iter().flatten()) {
                assert!(v.x.0 <= p[0] && p[0] <= v.x.1, "{p:?} {v:?}");
                assert!(v.y.0 <= p[1] && p[1] <= v.y.1, "{p:?} {v:?}");
                assert!(v.z.0 <= p[2] && p[2] <= v.z.1, "{p:?} {v:?}");
            }
        }
    }

    #[test]
    fn svg_has_the_title() {
        let frame = synthetic_frame("PPOE test robot frame 7/9", 0.0);
        let path = temp_path("picture.svg");
        write_svg(&path, &frame).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.trim_start().starts_with("<svg") || text.contains("<svg"));
        assert!(text.trim_end().ends_with("</svg>"));
        assert!(text.contains("PPOE test robot frame 7/9"));
        assert!(text.contains("test surface"));
        assert!(text.contains(r#"width="800""#) && text.contains(r#"height="700""#));
    }

    #[test]
    fn gif_has_every_frame_at_the_same_size() {
        let frames: Vec<Frame> = (0..3)
            .map(|i| synthetic_frame(&format!("frame {i}/3"), 0.1 * i as f64))
            .collect();
        let path = temp_path("anim.gif");
        let mut seen = Vec::new();
        write_gif_with_progress(&path, &frames, &mut |i| seen.push(i)).unwrap();
        assert_eq!(seen, vec![0, 1, 2]);
        let mut opts = gif::DecodeOptions::new();
        opts.set_color_output(gif::ColorOutput::RGBA);
        let mut dec = opts.read_info(std::fs::File::open(&path).unwrap()).unwrap();
        assert_eq!((dec.width() as u32, dec.height() as u32), (WIDTH, HEIGHT));
        let mut n = 0;
        while let Some(f) = dec.read_next_frame().unwrap() {
            assert_eq!((f.width as u32, f.height as u32), (WIDTH, HEIGHT));
            assert_eq!(f.delay, (GIF_DELAY_MS / 10) as u16);
            n += 1;
        }
        assert_eq!(n, 3);
    }
}

#[cfg(test)]
mod timing {
    use super::tests::{synthetic_frame, temp_path};
    use super::*;

    /// `cargo test --release -p ppoe-cli --bin ppoe -- --ignored --nocapture gif_200`:
    /// the time to write a 200-frame GIF with a 50×50 surface grid.
    #[test]
    #[ignore]
    fn gif_200_frames_timing() {
        let frames: Vec<Frame> = (0..200)
            .map(|i| {
                let mut f = synthetic_frame(&format!("frame {i}/200"), 0.002 * i as f64);
                let c = [f.tool[0][3], f.tool[1][3], f.tool[2][3]];
                let n = 50;
                f.surface = (0..n)
                    .map(|a| {
                        let phi = std::f64::consts::PI * a as f64 / (n - 1) as f64;
                        (0..n)
                            .map(|b| {
                                let th = 2.0 * std::f64::consts::PI * b as f64 / (n - 1) as f64;
                                [
                                    c[0] + 0.3 * phi.sin() * th.cos(),
                                    c[1] + 0.1 * phi.sin() * th.sin(),
                                    c[2] + 0.2 * phi.cos(),
                                ]
                            })
                            .collect()
                    })
                    .collect();
                f
            })
            .collect();
        let t = std::time::Instant::now();
        let path = temp_path("timing.gif");
        write_gif(&path, &frames).unwrap();
        let _ = std::fs::remove_file(&path);
        eprintln!("200 GIF frames in {:.2} s", t.elapsed().as_secs_f64());
        let t = std::time::Instant::now();
        let view = View::fit(&frames);
        let mut buf = vec![0u8; (WIDTH * HEIGHT * 3) as usize];
        for f in &frames {
            let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
            draw(&root, f, &view).unwrap();
            root.present().unwrap();
        }
        eprintln!("of which drawing {:.2} s", t.elapsed().as_secs_f64());
    }
}
