//! Exaggerating the equiprobable surface so that a real robot's noise can be seen.
//!
//! A robot with 2–5 mrad of joint noise has a surface of a few millimetres around a tool a
//! metre away: a pixel or two in a picture of the whole arm. `--exaggerate K` scales the
//! surface by K about the mean tool position (nothing else: the arm, the frames and the
//! second-order mean stay at true scale), and the legend says so ("surface drawn ×K").
//! The default for pictures is automatic: when the surface's diameter is under 1/40 of
//! the arm's extent (about 10 pixels where the arm spans 400), it is scaled by the
//! smallest of 1, 2, 5 × 10ⁿ that makes it at least 1/10 of the arm's extent; otherwise
//! it is drawn at true scale. Mesh files keep true scale unless `--exaggerate` is given.

use crate::picture::Frame;

/// How much to scale the surface about the tool position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Exaggeration {
    /// Scale a surface too small to see (see the module docs); true scale otherwise.
    Auto,
    /// Scale by this positive finite factor (1: true scale).
    Factor(f64),
}

/// `--exaggerate`: `auto` or a positive finite factor (a usage error otherwise).
///
/// # Errors
/// A message for clap when the value is neither.
pub fn parse(s: &str) -> Result<Exaggeration, String> {
    if s == "auto" {
        return Ok(Exaggeration::Auto);
    }
    match s.parse::<f64>() {
        Ok(k) if k.is_finite() && k > 0.0 => Ok(Exaggeration::Factor(k)),
        _ => Err("expected `auto` or a positive finite factor (1: true scale)".into()),
    }
}

/// The largest distance of the surface from the tool position, and the extent of the
/// arm (the largest side of the skeleton's bounding box).
fn sizes(frame: &Frame) -> (f64, f64) {
    let t = [frame.tool[0][3], frame.tool[1][3], frame.tool[2][3]];
    let radius = frame
        .surface
        .iter()
        .flatten()
        .map(|p| (0..3).map(|k| (p[k] - t[k]).powi(2)).sum::<f64>().sqrt())
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max);
    let extent = (0..3)
        .map(|k| {
            let (lo, hi) = frame
                .joints
                .iter()
                .fold((t[k], t[k]), |(lo, hi), p| (lo.min(p[k]), hi.max(p[k])));
            hi - lo
        })
        .fold(0.0, f64::max);
    (radius, extent)
}

/// The automatic factor of a frame: 1 unless its surface is too small to see.
pub fn auto_factor(frame: &Frame) -> f64 {
    let (radius, extent) = sizes(frame);
    if radius <= 0.0 || !extent.is_finite() || 2.0 * radius >= extent / 40.0 {
        return 1.0; // nothing to show, or already visible
    }
    let need = extent / 10.0 / (2.0 * radius);
    let mut decade = 10f64.powi(need.log10().floor() as i32);
    loop {
        for m in [1.0, 2.0, 5.0] {
            if m * decade >= need {
                return m * decade;
            }
        }
        decade *= 10.0;
    }
}

/// The factor for `e` and this frame.
pub fn factor(e: Exaggeration, frame: &Frame) -> f64 {
    match e {
        Exaggeration::Auto => auto_factor(frame),
        Exaggeration::Factor(k) => k,
    }
}

/// The factor as the legend writes it: an integer without decimals, else 3 significant
/// digits.
pub fn shown(k: f64) -> String {
    if k >= 1.0 && k.fract() == 0.0 && k < 1e15 {
        format!("{k:.0}")
    } else {
        format!("{}", format!("{k:.2e}").parse::<f64>().unwrap_or(k))
    }
}

/// Scales the frame's surface by `k` about the tool position and says so in its label;
/// `k = 1` leaves the frame as it is.
pub fn apply(frame: &mut Frame, k: f64) {
    if k == 1.0 {
        return;
    }
    let t = [frame.tool[0][3], frame.tool[1][3], frame.tool[2][3]];
    for p in frame.surface.iter_mut().flatten() {
        *p = [0, 1, 2].map(|i| t[i] + k * (p[i] - t[i]));
    }
    frame.sigma_label = format!(
        "{}; surface drawn ×{} about the tool (not to scale)",
        frame.sigma_label,
        shown(k)
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame whose arm spans 1 m (base to tool along x) and whose surface is a ring of
    /// radius `r` around the tool.
    fn frame(r: f64) -> Frame {
        let mut tool = crate::picture::geom::IDENTITY;
        tool[0][3] = 1.0;
        let ring = (0..8)
            .map(|i| {
                let a = i as f64 * std::f64::consts::FRAC_PI_4;
                [1.0 + r * a.cos(), r * a.sin(), 0.0]
            })
            .collect();
        Frame {
            title: String::new(),
            joints: vec![[0.0; 3], [1.0, 0.0, 0.0]],
            frames: Vec::new(),
            tool,
            surface: vec![ring],
            mean2: [1.0, 0.0, 0.0],
            sigma_label: "lift surface".into(),
            bodies: Vec::new(),
        }
    }

    #[test]
    fn the_automatic_factor_is_the_smallest_round_one_that_shows_the_surface() {
        // Diameter 2r against 1 m: visible from 1/40 m (r = 0.0125) on.
        assert_eq!(auto_factor(&frame(0.0125)), 1.0);
        assert_eq!(auto_factor(&frame(0.3)), 1.0);
        // r = 3 mm: diameter 6 mm, 1/10 m needs ×16.7: ×20.
        assert_eq!(auto_factor(&frame(0.003)), 20.0);
        // r = 0.04 mm: needs ×1250: ×2000.
        assert_eq!(auto_factor(&frame(4e-5)), 2000.0);
        // r = 11 mm: diameter 2.2 cm < 2.5 cm, needs ×4.5 for 10 cm: ×5.
        assert_eq!(auto_factor(&frame(0.011)), 5.0);
        assert_eq!(auto_factor(&frame(0.0)), 1.0);
    }

    #[test]
    fn scaling_multiplies_the_distances_from_the_tool_and_labels_it() {
        let plain = frame(0.003);
        let mut f = plain.clone();
        apply(&mut f, 1.0);
        assert_eq!(f, plain);
        apply(&mut f, 20.0);
        assert_eq!(
            f.sigma_label,
            "lift surface; surface drawn ×20 about the tool (not to scale)"
        );
        for (p, q) in f.surface[0].iter().zip(&plain.surface[0]) {
            for k in 0..3 {
                let (dp, dq) = (p[k] - [1.0, 0.0, 0.0][k], q[k] - [1.0, 0.0, 0.0][k]);
                assert!((dp - 20.0 * dq).abs() < 1e-15, "{p:?} {q:?}");
            }
        }
        assert_eq!((f.joints, f.mean2), (plain.joints, plain.mean2));
        assert_eq!(shown(2.5), "2.5");
        assert_eq!(shown(1.0 / 3.0), "0.333");
        assert!(parse("0").is_err() && parse("inf").is_err() && parse("x").is_err());
        assert_eq!(parse("auto"), Ok(Exaggeration::Auto));
    }
}
