//! The legend box in the top-left corner: the arm, the frame axes, the surface (with its
//! kind and probability level) and the two means.

use super::{Frame, AXIS_COLORS, MEAN2, SKELETON, SURFACE, TITLE_H, WIRE};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Up to three distinct colours of the robot's visuals, in order of appearance.
fn body_colours(frame: &Frame) -> Vec<[u8; 3]> {
    let mut out: Vec<[u8; 3]> = Vec::new();
    for b in &frame.bodies {
        if out.len() < 3 && !out.contains(&b.rgb) {
            out.push(b.rgb);
        }
    }
    out
}

/// The arm's entry: the visuals' colours, or the stick figure's grey bar.
fn arm_entry<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
    (x0, y): (i32, i32),
) -> Result<&'static str, DrawingAreaErrorKind<DB::ErrorType>> {
    let colours = body_colours(frame);
    if colours.is_empty() {
        root.draw(&PathElement::new(
            vec![(x0, y), (x0 + 34, y)],
            SKELETON.stroke_width(6),
        ))?;
        return Ok("arm: base, joints, tool");
    }
    let w = 34 / colours.len() as i32;
    for (k, c) in colours.iter().enumerate() {
        let xa = x0 + w * k as i32;
        root.draw(&Rectangle::new(
            [(xa, y - 6), (xa + w - 1, y + 6)],
            RGBColor(c[0], c[1], c[2]).filled(),
        ))?;
    }
    Ok("arm: the robot's visual geometry (URDF)")
}

/// Draws the legend.
pub fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let style = ("sans-serif", 14).into_font().color(&BLACK);
    let x0 = 12i32;
    let line_h = 20i32;
    let entries = 4;
    let y0 = TITLE_H as i32 + 8;
    let w = 12 + 36 + 8 + 7 * frame.sigma_label.chars().count().max(38) as i32;
    let corners = [(x0 - 6, y0 - 6), (x0 + w, y0 + line_h * entries + 2)];
    root.draw(&Rectangle::new(corners, WHITE.mix(0.85).filled()))?;
    root.draw(&Rectangle::new(
        corners,
        RGBColor(180, 180, 180).stroke_width(1),
    ))?;
    let text_x = x0 + 44;
    let mut y = y0 + line_h / 2;
    let arm = arm_entry(root, frame, (x0, y))?;
    root.draw(&Text::new(arm, (text_x, y - 8), style.clone()))?;
    y += line_h;
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
    let swatch = [(x0, y - 7), (x0 + 34, y + 7)];
    root.draw(&Rectangle::new(swatch, SURFACE.mix(0.45).filled()))?;
    root.draw(&Rectangle::new(swatch, WIRE.stroke_width(1)))?;
    root.draw(&Text::new(
        frame.sigma_label.clone(),
        (text_x, y - 8),
        style.clone(),
    ))?;
    y += line_h;
    root.draw(&Circle::new((x0 + 7, y), 4, BLACK.filled()))?;
    root.draw(&Cross::new((x0 + 25, y), 6, MEAN2.stroke_width(3)))?;
    root.draw(&Text::new(
        "mean tool position · second-order mean",
        (text_x, y - 8),
        style,
    ))?;
    Ok(())
}
