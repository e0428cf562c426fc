//! The interactive view: one self-contained HTML page (no network at view time) with the
//! frames' data as inline JSON and a small canvas-2D renderer (`assets/viewer.js`, inline):
//! the arm (visual geometry or skeleton), the frame axes, the semi-transparent surface and
//! the means; drag to rotate, wheel to zoom, right- or shift-drag to pan, play/pause and a
//! slider over the frames, and a legend naming the surface and its probability level.
//!
//! The surface is sent on a grid of at most [`MAX_GRID`] points per side and its
//! coordinates quantised to 16 bits over the view's cube (0.03 mm for a 2 m cube: far
//! below a pixel), which keeps a 200-frame page near 2 MB.

use super::geom::{finite, origin};
use super::{Frame, View};
use serde_json::{json, Value};
use std::collections::HashMap;
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

/// The shapes used by the frames, each once, and a map from shape pointer to its index.
fn shapes(frames: &[Frame]) -> (Vec<Value>, HashMap<*const super::Shape, usize>) {
    let mut index = HashMap::new();
    let mut out = Vec::new();
    for b in frames.iter().flat_map(|f| &f.bodies) {
        let key = Arc::as_ptr(&b.shape);
        if let std::collections::hash_map::Entry::Vacant(e) = index.entry(key) {
            e.insert(out.len());
            let v: Vec<Value> = b.shape.vertices.iter().flatten().map(|&x| r(x)).collect();
            out.push(json!({"v": v, "f": b.shape.faces, "closed": b.shape.closed}));
        }
    }
    (out, index)
}

/// The page's data: the view, the shapes and every frame.
fn data(frames: &[Frame]) -> anyhow::Result<Value> {
    anyhow::ensure!(!frames.is_empty(), "no frames to show");
    let view = View::fit(frames);
    let c = [
        (view.x.0 + view.x.1) / 2.0,
        (view.y.0 + view.y.1) / 2.0,
        (view.z.0 + view.z.1) / 2.0,
    ];
    let span = view.x.1 - view.x.0;
    let unit = span / (2.0 * Q);
    let (shape_list, index) = shapes(frames);
    let frames_json: Vec<Value> = frames
        .iter()
        .map(|f| {
            let (nr, nc, s) = surface_b64(f, c, unit);
            let bodies: Vec<Value> = f
                .bodies
                .iter()
                .map(|b| {
                    json!({"s": index[&Arc::as_ptr(&b.shape)], "rgb": b.rgb, "m": pose12(&b.pose)})
                })
                .collect();
            let axes: Vec<Value> = f
                .frames
                .iter()
                .chain([&f.tool])
                .map(|m| json!(pose12(m)))
                .collect();
            let joints: Vec<Value> = f.joints.iter().map(|p| json!(p.map(r))).collect();
            json!({
                "title": f.title, "rows": nr, "cols": nc, "surface": s, "bodies": bodies,
                "axes": axes, "joints": joints, "tool": origin(&f.tool).map(r),
                "mean2": f.mean2.map(r),
            })
        })
        .collect();
    Ok(json!({
        "view": {"x": [view.x.0, view.x.1], "y": [view.y.0, view.y.1], "z": [view.z.0, view.z.1]},
        "centre": c, "unit": unit, "label": frames[0].sigma_label,
        "axisLen": super::axis_len_hint(&frames[0]),
        "colours": {"surface": rgb(super::SURFACE), "wire": rgb(super::WIRE),
                    "skeleton": rgb(super::SKELETON), "mean2": rgb(super::MEAN2)},
        "delayMs": super::GIF_DELAY_MS, "shapes": shape_list, "frames": frames_json,
    }))
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

/// The page: the frames' data as JSON inside a `<script type="application/json">` (with
/// `<` escaped so no string can end the element), the viewer's script and its controls.
///
/// # Errors
/// No frames.
pub fn page(frames: &[Frame]) -> anyhow::Result<String> {
    let data = serde_json::to_string(&data(frames)?)?.replace('<', "\\u003c");
    let title = escape(&frames[0].title);
    Ok(format!(
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
<script id="ppoe-data" type="application/json">{data}</script>
<script>
{VIEWER_JS}
</script>
</body></html>
"#
    ))
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
