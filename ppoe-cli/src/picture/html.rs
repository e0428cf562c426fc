//! The interactive view: one self-contained HTML page (no network at view time) with the
//! frames' data as inline JSON and a small canvas-2D renderer (`assets/viewer.js`, inline):
//! the arm (visual geometry or skeleton), the frame axes, the semi-transparent surface and
//! the means; drag to rotate, wheel to zoom, right- or shift-drag to pan, play/pause and a
//! slider over the frames, and a legend naming the surface and its probability level.
//!
//! The surface is sent on a grid of at most [`MAX_GRID`] points per side and its
//! coordinates quantised to 16 bits over the view's cube (0.03 mm for a 2 m cube: far
//! below a pixel), which keeps a 200-frame page near 2 MB.
//!
//! The page is streamed: everything the frames share comes from the survey pass (see
//! [`super::survey`]), then each frame's data is written as it is made.

use super::geom::{finite, origin};
use super::survey::{Frames, Survey};
use super::Frame;
use anyhow::Context;
use serde_json::{json, Value};
use std::io::Write;
use std::sync::Arc;

/// Most surface grid points per side in the page.
pub const MAX_GRID: usize = 31;
/// Quantisation levels either side of the cube's centre.
const Q: f64 = 32000.0;

const VIEWER_JS: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/viewer.js"));

/// Standard base64 (RFC 4648, with padding).
fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// `m` evenly spread indices of `0..n`, both ends included.
fn spread(n: usize, m: usize) -> Vec<usize> {
    if n <= m {
        return (0..n).collect();
    }
    (0..m)
        .map(|k| ((k * (n - 1)) as f64 / (m - 1) as f64).round() as usize)
        .collect()
}

/// The surface on a grid of at most [`MAX_GRID`] per side, as little-endian i16 triples
/// relative to the cube's centre `c` in units of `unit`; a non-finite point is
/// `i16::MIN` (the viewer skips the patches touching it).
fn surface_b64(frame: &Frame, c: [f64; 3], unit: f64) -> (usize, usize, String) {
    let rows = spread(frame.surface.len(), MAX_GRID);
    let n_cols = frame.surface.iter().map(|r| r.len()).min().unwrap_or(0);
    let cols = spread(n_cols, MAX_GRID);
    let mut bytes = Vec::with_capacity(rows.len() * cols.len() * 6);
    for &i in &rows {
        for &j in &cols {
            let p = frame.surface[i][j];
            for k in 0..3 {
                let q = (p[k] - c[k]) / unit;
                let v = if finite(&p) && q.abs() <= Q {
                    q.round() as i16
                } else {
                    i16::MIN
                };
                bytes.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    (rows.len(), cols.len(), base64(&bytes))
}

/// Rounds to 0.1 µm for the page (well below anything visible).
fn r(x: f64) -> Value {
    if x.is_finite() {
        json!((x * 1e7).round() / 1e7)
    } else {
        Value::Null
    }
}

/// The upper 3×4 of a transform, row-major, rounded.
fn pose12(m: &[[f64; 4]; 4]) -> Vec<Value> {
    m[..3]
        .iter()
        .flat_map(|row| row.iter().map(|&x| r(x)))
        .collect()
}

/// One frame's data for the page: the surface quantised about the cube's centre `c` in
/// units of `unit`, the bodies (shapes by their index in the survey), axes, skeleton and
/// markers.
fn frame_json(f: &Frame, c: [f64; 3], unit: f64, survey: &Survey) -> anyhow::Result<Value> {
    let (nr, nc, s) = surface_b64(f, c, unit);
    let bodies = f
        .bodies
        .iter()
        .map(|b| {
            let s = survey
                .shape_index
                .get(&Arc::as_ptr(&b.shape))
                .context("a frame uses a shape the survey did not see")?;
            Ok(json!({"s": s, "rgb": b.rgb, "m": pose12(&b.pose)}))
        })
        .collect::<anyhow::Result<Vec<Value>>>()?;
    let axes: Vec<Value> = f
        .frames
        .iter()
        .chain([&f.tool])
        .map(|m| json!(pose12(m)))
        .collect();
    let joints: Vec<Value> = f.joints.iter().map(|p| json!(p.map(r))).collect();
    Ok(json!({
        "title": f.title, "rows": nr, "cols": nc, "surface": s, "bodies": bodies,
        "axes": axes, "joints": joints, "tool": origin(&f.tool).map(r),
        "mean2": f.mean2.map(r),
    }))
}

/// Stands for the frames in the page's data until they are streamed in its place.
const FRAMES_MARK: &str = "\u{1}ppoe-frames\u{1}";

/// The page's data without the frames: the view, the shapes, the colours, and
/// [`FRAMES_MARK`] where the frames go; and the cube's centre and the quantisation unit.
fn data_without_frames(survey: &Survey) -> (Value, [f64; 3], f64) {
    let view = &survey.view;
    let c = [
        (view.x.0 + view.x.1) / 2.0,
        (view.y.0 + view.y.1) / 2.0,
        (view.z.0 + view.z.1) / 2.0,
    ];
    let span = view.x.1 - view.x.0;
    let unit = span / (2.0 * Q);
    let shapes: Vec<Value> = survey
        .shapes
        .iter()
        .map(|s| {
            let v: Vec<Value> = s.vertices.iter().flatten().map(|&x| r(x)).collect();
            json!({"v": v, "f": s.faces, "closed": s.closed})
        })
        .collect();
    let first = survey.first();
    let data = json!({
        "view": {"x": [view.x.0, view.x.1], "y": [view.y.0, view.y.1], "z": [view.z.0, view.z.1]},
        "centre": c, "unit": unit, "label": first.sigma_label,
        "axisLen": super::axis_len_hint(first),
        "colours": {"surface": rgb(super::SURFACE), "wire": rgb(super::WIRE),
                    "skeleton": rgb(super::SKELETON), "mean2": rgb(super::MEAN2)},
        "delayMs": super::GIF_DELAY_MS, "shapes": shapes, "frames": FRAMES_MARK,
    });
    (data, c, unit)
}

fn rgb(c: plotters::style::RGBColor) -> [u8; 3] {
    [c.0, c.1, c.2]
}

/// Escapes text for an HTML element's content.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// JSON text safe inside a `<script>` element: `<` escaped so no string can end it.
fn script_json(v: &Value) -> anyhow::Result<String> {
    Ok(serde_json::to_string(v)?.replace('<', "\\u003c"))
}

/// The page before its data: the head, the styles and the controls.
fn head(title: &str) -> String {
    let title = escape(title);
    format!(
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>{title}</title>
<style>
body {{ margin: 0; font: 14px "DejaVu Sans", sans-serif; background: #fff; overflow: hidden; }}
#view {{ display: block; width: 100vw; height: 100vh; cursor: grab; }}
#bar {{ position: absolute; left: 0; right: 0; bottom: 0; padding: 6px 12px; background: rgba(255,255,255,.85);
        display: flex; gap: 10px; align-items: center; border-top: 1px solid #bbb; }}
#slider {{ flex: 1; }}
#legend {{ position: absolute; left: 10px; top: 40px; padding: 6px 10px; background: rgba(255,255,255,.85);
           border: 1px solid #b4b4b4; line-height: 20px; }}
#title {{ position: absolute; left: 0; right: 0; top: 6px; text-align: center; font-size: 20px; }}
.sw {{ display: inline-block; width: 34px; height: 12px; margin-right: 8px; vertical-align: middle; }}
#help {{ color: #555; font-size: 12px; }}
</style></head>
<body>
<canvas id="view"></canvas>
<div id="title"></div>
<div id="legend"></div>
<div id="bar"><button id="play">pause</button><input id="slider" type="range" min="0" value="0">
<span id="help">drag: rotate · wheel: zoom · right/shift-drag: pan · double-click: reset</span></div>
<script id="ppoe-data" type="application/json">"#
    )
}

/// Writes the page to `out`: the frames' data as JSON inside a
/// `<script type="application/json">`, each frame made and written in turn (only one in
/// memory), then the viewer's script.
///
/// # Errors
/// A frame that cannot be made, or a write error.
pub fn write_page(out: &mut dyn Write, frames: &Frames<'_>, survey: &Survey) -> anyhow::Result<()> {
    let (data, c, unit) = data_without_frames(survey);
    let data = script_json(&data)?;
    let mark = script_json(&Value::from(FRAMES_MARK))?;
    let (before, after) = data
        .split_once(&mark)
        .context("the page's data lost its frames mark")?;
    out.write_all(head(&survey.first().title).as_bytes())?;
    out.write_all(before.as_bytes())?;
    out.write_all(b"[")?;
    for i in 0..frames.n {
        if i > 0 {
            out.write_all(b",")?;
        }
        let f = (frames.make)(i)?;
        out.write_all(script_json(&frame_json(&f, c, unit, survey)?)?.as_bytes())?;
    }
    out.write_all(b"]")?;
    out.write_all(after.as_bytes())?;
    write!(
        out,
        "</script>\n<script>\n{VIEWER_JS}\n</script>\n</body></html>\n"
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        for (raw, enc) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(raw.as_bytes()), enc);
        }
    }

    #[test]
    fn spread_keeps_both_ends() {
        assert_eq!(spread(5, 31), vec![0, 1, 2, 3, 4]);
        let s = spread(40, 31);
        assert_eq!((s.len(), s[0], s[30]), (31, 0, 39));
        assert!(s.windows(2).all(|w| w[0] < w[1]));
    }
}
