//! The 3D scene of a picture: the surface's shaded patches and wireframe, the robot's
//! solid visuals (or, without visuals, the skeleton), the frame axes, drawn back to front
//! (painter's algorithm), then the markers on top.

use super::chart::{to_plot, towards_camera, Chart3, Coord3};
use super::geom::{apply, dot, finite, norm, origin, rotate, sub, unit};
use super::solid::{polygon_normal, Body};
use super::{axis_len_hint, surface_centre, Frame, AXIS_COLORS, MEAN2, SKELETON, SURFACE, WIRE};
use plotters::prelude::*;

/// Opacity of the surface's patches: the arm stays visible through the surface.
const SURFACE_ALPHA: f64 = 0.30;

/// One 3D item of the scene, drawn back to front.
pub enum Item {
    /// A filled polygon (a surface patch or a face of a solid).
    Patch {
        /// The corners, in plotters' coordinates.
        pts: Vec<Coord3>,
        /// The fill.
        fill: RGBAColor,
        /// Also stroke the outline in the fill's colour (closes hairline seams between
        /// opaque faces).
        seal: bool,
    },
    /// A line segment.
    Segment {
        a: Coord3,
        b: Coord3,
        color: RGBAColor,
        width: u32,
    },
}

/// The direction of the light for the surface (from above, in front).
fn surface_light() -> [f64; 3] {
    unit([0.4, -0.3, 0.85]).unwrap_or([0.0, 0.0, 1.0])
}

/// The direction of the light for solids: from above the camera, a little to its left, so
/// faces turned to the viewer are lit and the tops brightest.
fn solid_light() -> [f64; 3] {
    let c = towards_camera();
    unit([c[0] + 0.3, c[1] - 0.2, c[2] + 0.9]).unwrap_or([0.0, 0.0, 1.0])
}

/// A solid's colour under Lambert shading with a soft highlight, so black parts keep a
/// visible shape.
pub fn shade(rgb: [u8; 3], lambert: f64) -> [u8; 3] {
    let l = lambert.clamp(0.0, 1.0);
    let k = 0.45 + 0.55 * l;
    rgb.map(|c| (c as f64 * k + 70.0 * l.powi(4)).min(255.0) as u8)
}

/// The surface's quadrilateral patches, Lambert-shaded about its centre.
pub fn surface_items(frame: &Frame, items: &mut Vec<Item>) {
    let rows = &frame.surface;
    let light = surface_light();
    let centre = surface_centre(frame);
    for pair in rows.windows(2) {
        let m = pair[0].len().min(pair[1].len());
        for j in 0..m.saturating_sub(1) {
            let q = [pair[0][j], pair[1][j], pair[1][j + 1], pair[0][j + 1]];
            if !q.iter().all(finite) {
                continue;
            }
            let Some(nrm) = unit(super::geom::cross(sub(q[2], q[0]), sub(q[3], q[1]))) else {
                continue;
            };
            // Whatever the winding, the outward side is the one away from the centre.
            let mid = [0, 1, 2].map(|k| (q[0][k] + q[2][k]) / 2.0);
            let side = dot(sub(mid, centre), nrm).signum();
            let lambert = (side * dot(nrm, light)).abs();
            let k = 0.55 + 0.45 * lambert;
            let fill = RGBColor(
                (SURFACE.0 as f64 * k) as u8,
                (SURFACE.1 as f64 * k) as u8,
                (SURFACE.2 as f64 * k) as u8,
            )
            .mix(SURFACE_ALPHA);
            items.push(Item::Patch {
                pts: q.iter().map(|p| to_plot(*p)).collect(),
                fill,
                seal: false,
            });
        }
    }
    wireframe_items(frame, items);
}

/// About 13 × 19 lines of the surface's grid.
fn wireframe_items(frame: &Frame, items: &mut Vec<Item>) {
    let rows = &frame.surface;
    let n_rows = rows.len();
    if n_rows < 2 {
        return;
    }
    let n_cols = rows.iter().map(|r| r.len()).min().unwrap_or(0);
    let stride_i = ((n_rows - 1) / 12).max(1);
    let stride_j = ((n_cols.max(2) - 1) / 18).max(1);
    let wire = WIRE.mix(0.55);
    let mut line = |a: [f64; 3], b: [f64; 3]| {
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
            line(rows[i][j], rows[i][j + 1]);
        }
    }
    for j in (0..n_cols).step_by(stride_j) {
        for i in 0..n_rows - 1 {
            line(rows[i][j], rows[i + 1][j]);
        }
    }
}

/// The faces of the robot's solids, shaded; faces of closed solids turned away from the
/// camera are skipped (they are hidden by the front faces).
pub fn body_items(bodies: &[Body], items: &mut Vec<Item>) {
    let eye = towards_camera();
    let light = solid_light();
    for body in bodies {
        let world: Vec<[f64; 3]> = body
            .shape
            .vertices
            .iter()
            .map(|v| apply(&body.pose, *v))
            .collect();
        if !world.iter().all(finite) {
            continue;
        }
        for face in &body.shape.faces {
            let pts: Vec<[f64; 3]> = face.iter().map(|&i| world[i as usize]).collect();
            let Some(n) = unit(polygon_normal(&pts)) else {
                continue;
            };
            let facing = dot(n, eye);
            if body.shape.closed && facing <= 0.0 {
                continue;
            }
            // An open mesh shows whichever side faces the camera.
            let n = if facing < 0.0 { n.map(|c| -c) } else { n };
            let [r, g, b] = shade(body.rgb, dot(n, light));
            items.push(Item::Patch {
                pts: pts.into_iter().map(to_plot).collect(),
                fill: RGBColor(r, g, b).to_rgba(),
                seal: true,
            });
        }
    }
}

/// The stick figure: thick segments between successive joint positions.
pub fn skeleton_items(frame: &Frame, items: &mut Vec<Item>) {
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
}

/// Small RGB axes at the base, every joint and the tool.
pub fn axis_items(frame: &Frame, items: &mut Vec<Item>) {
    let al = axis_len_hint(frame);
    for m in frame.frames.iter().chain(std::iter::once(&frame.tool)) {
        let o = origin(m);
        for (a, color) in AXIS_COLORS.iter().enumerate() {
            let mut e = [0.0; 3];
            e[a] = al;
            let d = rotate(m, e);
            let tip = [o[0] + d[0], o[1] + d[1], o[2] + d[2]];
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
}

/// Draws the items back to front: a larger projected depth is farther from the viewer.
pub fn paint<DB: DrawingBackend>(
    chart: &Chart3<'_, DB>,
    items: Vec<Item>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let coord = chart.as_coord_spec().clone();
    let depth = |p: &Coord3| coord.projected_depth(&p.0, &p.1, &p.2) as f64;
    let mut keyed: Vec<(f64, Item)> = items
        .into_iter()
        .map(|it| {
            let d = match &it {
                Item::Patch { pts, .. } => pts.iter().map(depth).sum::<f64>() / pts.len() as f64,
                Item::Segment { a, b, .. } => (depth(a) + depth(b)) / 2.0,
            };
            (d, it)
        })
        .collect();
    keyed.sort_by(|a, b| b.0.total_cmp(&a.0));
    let area = chart.plotting_area();
    for (_, it) in keyed {
        match it {
            Item::Patch { pts, fill, seal } => {
                if seal {
                    let mut ring = pts.clone();
                    ring.push(pts[0]);
                    area.draw(&PathElement::new(ring, fill.stroke_width(1)))?;
                }
                area.draw(&Polygon::new(pts, fill.filled()))?;
            }
            Item::Segment { a, b, color, width } => {
                area.draw(&PathElement::new(vec![a, b], color.stroke_width(width)))?;
            }
        }
    }
    Ok(())
}

/// The joint dots (stick figure only), the tool dot and the second-order mean, on top.
pub fn markers<DB: DrawingBackend>(
    chart: &Chart3<'_, DB>,
    frame: &Frame,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let area = chart.plotting_area();
    if frame.bodies.is_empty() {
        for p in frame.joints.iter().filter(|p| finite(p)) {
            area.draw(&Circle::new(to_plot(*p), 4, SKELETON.filled()))?;
        }
    }
    let tool = origin(&frame.tool);
    if finite(&tool) {
        area.draw(&Circle::new(to_plot(tool), 4, BLACK.filled()))?;
    }
    if finite(&frame.mean2) {
        area.draw(&Cross::new(to_plot(frame.mean2), 6, MEAN2.stroke_width(3)))?;
    }
    Ok(())
}
