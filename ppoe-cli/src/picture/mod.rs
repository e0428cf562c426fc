//! Pictures of a robot and its tool-pose distribution (PNG, SVG, GIF, and an interactive
//! HTML view), drawn without a window system.
//!
//! Every picture is [`WIDTH`]×[`HEIGHT`] = 800×700 pixels (PNG, every GIF frame, and the
//! SVG's view box) and shows, in a 3D view like the seed's (elevation 5°, azimuth 50°):
//! * the arm: its URDF visual geometry (cylinders, boxes, spheres, meshes) in the
//!   material colours, Lambert-shaded, each link at its pose; or, for a robot without
//!   visuals, a skeleton of thick grey segments between successive joint positions (base,
//!   each joint, tool) with a dot at each joint;
//! * small RGB axes (x red, y green, z blue) at the base, at every joint and at the tool;
//! * the equiprobable surface of the tool position as semi-transparent teal shaded
//!   polygons with a darker wireframe;
//! * the mean tool position (black dot) and the second-order mean of the tool position
//!   (purple cross);
//! * axis ticks in metres, a title (with the frame number) and a legend that names the
//!   surface (`sigma_label`).
//!
//! The 3D scene is drawn back to front (painter's algorithm over the surface's polygons,
//! the solids' faces, the skeleton's segments and the axes) so the arm shows through the
//! translucent surface. Text uses DejaVu Sans, embedded in the binary
//! (`assets/DejaVuSans.ttf`, licence in `assets/DejaVuSans-LICENSE.txt`), so no system font
//! is needed. Files are written atomically (temporary file, then rename).

mod anim;
mod chart;
pub mod geom;
pub mod html;
mod legend;
mod scene;
pub mod solid;
mod survey;

use anyhow::anyhow;
use geom::{finite, norm, origin, sub};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
pub use solid::{Body, Shape};
use std::path::Path;
pub use survey::{Frames, Survey};

/// Width of every picture in pixels.
pub const WIDTH: u32 = 800;
/// Height of every picture in pixels.
pub const HEIGHT: u32 = 700;
/// Delay between GIF frames in milliseconds.
pub const GIF_DELAY_MS: u32 = 50;
/// Height of the title band at the top of the picture, in pixels.
const TITLE_H: u32 = 44;

const FONT: &[u8] = include_bytes!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/assets/DejaVuSans.ttf"
));

const SKELETON: RGBColor = RGBColor(70, 70, 78);
/// Teal: apart from the usual robot colours (blue, orange, black, grey) and the axes.
const SURFACE: RGBColor = RGBColor(0, 170, 160);
const WIRE: RGBColor = RGBColor(0, 105, 100);
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
    /// The robot's visual geometry placed at this state; empty for a robot without
    /// visuals (the skeleton is drawn instead).
    pub bodies: Vec<Body>,
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

/// Every finite point a frame draws, with the margin each needs: the skeleton and frame
/// origins padded by the axis length, the surface, the second-order mean and the solids'
/// vertices as they are.
fn extent_points(f: &Frame, add: &mut dyn FnMut(&[f64; 3], f64)) {
    let al = axis_len_hint(f);
    for p in &f.joints {
        add(p, al);
    }
    for m in f.frames.iter().chain(std::iter::once(&f.tool)) {
        add(&origin(m), al);
    }
    for p in f.surface.iter().flatten() {
        add(p, 0.0);
    }
    add(&f.mean2, 0.0);
    for b in &f.bodies {
        for v in &b.shape.vertices {
            add(&geom::apply(&b.pose, *v), 0.0);
        }
    }
}

/// The running bounds of every frame seen so far, so an animation's [`View`] can be
/// fitted while its frames stream past (none of them kept).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Extent {
    lo: [f64; 3],
    hi: [f64; 3],
}

impl Extent {
    /// Widens the bounds to hold every finite point of `f` with its margin (see
    /// [`View::fit`]).
    pub fn add(&mut self, f: &Frame) {
        let (lo, hi) = (&mut self.lo, &mut self.hi);
        extent_points(f, &mut |p, pad| {
            if finite(p) {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k] - pad);
                    hi[k] = hi[k].max(p[k] + pad);
                }
            }
        });
    }

    /// The view of the frames added so far (see [`View::fit`]).
    pub fn view(&self) -> View {
        let (lo, hi) = (self.lo, self.hi);
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

impl View {
    /// A view that holds every finite point of every frame (skeleton, frame axes, tool,
    /// surface, second-order mean, visuals) with a margin: all three ranges of the same
    /// length (10 % more than the largest extent, rounded up to 0.1 m), centred on the
    /// points, z starting at the floor (z = 0) when the arm stands on it and fits.
    pub fn fit(frames: &[Frame]) -> View {
        let mut e = Extent::default();
        for f in frames {
            e.add(f);
        }
        e.view()
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

/// Pixel coordinates (x right, y down, from the top-left corner of the image) of the 3D
/// point `p` (metres, base frame) in a picture drawn with `view`.
#[cfg_attr(not(test), allow(dead_code))] // used by the tests
pub fn project(frame_view: &View, p: [f64; 3]) -> (f64, f64) {
    register_font();
    let (w, h) = (frame_view.width, frame_view.height);
    let mut buf = vec![0u8; w as usize * h as usize * 3];
    let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
    let out = match chart::build(&root, frame_view) {
        Ok((_, chart)) => {
            let (x, y) = chart.as_coord_spec().translate(&chart::to_plot(p));
            (x as f64, y as f64)
        }
        Err(_) => (f64::NAN, f64::NAN),
    };
    out
}

/// Draws one picture on `root`: white background, title, axes, the 3D scene back to
/// front, the markers, the legend.
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
    view: &View,
) -> anyhow::Result<()> {
    register_font();
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("drawing: {e}");
    root.fill(&WHITE).map_err(e)?;
    let (title_area, mut chart) = chart::build(root, view)?;
    chart::title(&title_area, &frame.title).map_err(e)?;
    chart::axes(&mut chart, view).map_err(e)?;
    let mut items = Vec::new();
    scene::surface_items(frame, &mut items);
    if frame.bodies.is_empty() {
        scene::skeleton_items(frame, &mut items);
    } else {
        scene::body_items(&frame.bodies, &mut items);
    }
    scene::axis_items(frame, &mut items);
    scene::paint(&chart, items).map_err(e)?;
    scene::markers(&chart, frame).map_err(e)?;
    legend::draw(root, frame).map_err(e)?;
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
        return origin(&frame.tool);
    }
    [s[0] / n as f64, s[1] / n as f64, s[2] / n as f64]
}

/// Writes one frame as an 800×700 PNG image (axis ranges fitted to this frame).
///
/// # Errors
/// A drawing failure, or the file cannot be written (an earlier file at `path` is kept).
pub fn write_png(path: &Path, frame: &Frame) -> anyhow::Result<()> {
    write_png_with_view(path, frame, &View::fit(std::slice::from_ref(frame)))
}

/// Writes one frame as an 800×700 PNG image with the given view.
///
/// # Errors
/// A drawing failure, or the file cannot be written (an earlier file at `path` is kept).
pub fn write_png_with_view(path: &Path, frame: &Frame, view: &View) -> anyhow::Result<()> {
    crate::output::write_atomic_path(path, |tmp| {
        let root = BitMapBackend::new(tmp, (view.width, view.height)).into_drawing_area();
        draw(&root, frame, view)?;
        root.present().map_err(|e| anyhow!("{e}"))
    })
}

/// Writes one frame as an SVG image (800×700 view box, axis ranges fitted to this frame).
///
/// # Errors
/// A drawing failure, or the file cannot be written (an earlier file at `path` is kept).
pub fn write_svg(path: &Path, frame: &Frame) -> anyhow::Result<()> {
    let view = View::fit(std::slice::from_ref(frame));
    let mut text = String::new();
    {
        let root =
            SVGBackend::with_string(&mut text, (view.width, view.height)).into_drawing_area();
        draw(&root, frame, &view)?;
        root.present().map_err(|e| anyhow!("{e}"))?;
    }
    crate::output::write_atomic(path, |w| w.write_all(text.as_bytes()))
}

/// Writes the frames as an animated GIF: 800×700, [`GIF_DELAY_MS`] ms apart, one fixed
/// view fitted to all frames (`survey.view`, so the axes do not jump), looping; calls
/// `progress(i)` after frame `i` (0-based) is written, in order.
///
/// Frames are made again and drawn on all available cores, a few at a time, and each is
/// written to the (temporary) file as soon as the frames before it are: memory does not
/// grow with the number of frames. One palette serves the whole animation (the drawing
/// colours exactly, plus colours learnt from the survey's sample frames); after the first
/// frame each frame holds only the rectangle that changed.
///
/// # Errors
/// A frame that cannot be made, a drawing failure, or the file cannot be written (an
/// earlier file at `path` is kept).
pub fn write_gif_with_progress(
    path: &Path,
    frames: &Frames<'_>,
    survey: &Survey,
    progress: &mut dyn FnMut(usize),
) -> anyhow::Result<()> {
    anim::write(path, frames, survey, progress)
}

/// Writes the frames as one self-contained interactive HTML page (see [`html`]), each
/// frame made again and written as it comes (memory does not grow with their number).
///
/// # Errors
/// A frame that cannot be made, or the file cannot be written (an earlier file at `path`
/// is kept).
pub fn write_html(path: &Path, frames: &Frames<'_>, survey: &Survey) -> anyhow::Result<()> {
    crate::output::write_atomic_with(path, |w| html::write_page(w, frames, survey))
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
            bodies: Vec::new(),
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
        // Teal: green and blue well above red.
        assert!(
            s[1] > s[0] + 30 && s[2] > s[0] + 30,
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

    /// Decodes a GIF and composes its frames on the canvas (frames keep what they do not
    /// cover, transparent pixels keep the previous image): the picture shown after each frame.
    pub(crate) fn composed_gif_frames(path: &Path) -> (u32, u32, Vec<Vec<u8>>) {
        let mut opts = gif::DecodeOptions::new();
        opts.set_color_output(gif::ColorOutput::RGBA);
        let mut dec = opts.read_info(std::fs::File::open(path).unwrap()).unwrap();
        let (w, h) = (dec.width() as usize, dec.height() as usize);
        let mut canvas = vec![255u8; w * h * 3];
        let mut out = Vec::new();
        while let Some(f) = dec.read_next_frame().unwrap() {
            assert_eq!(f.delay, (GIF_DELAY_MS / 10) as u16);
            let (l, t, fw, fh) = (
                f.left as usize,
                f.top as usize,
                f.width as usize,
                f.height as usize,
            );
            assert!(l + fw <= w && t + fh <= h, "frame outside the canvas");
            for y in 0..fh {
                for x in 0..fw {
                    let s = &f.buffer[(y * fw + x) * 4..][..4];
                    if s[3] != 0 {
                        let d = ((t + y) * w + l + x) * 3;
                        canvas[d..d + 3].copy_from_slice(&s[..3]);
                    }
                }
            }
            out.push(canvas.clone());
        }
        (w as u32, h as u32, out)
    }

    #[test]
    fn gif_frames_compose_to_the_drawn_pictures() {
        let frames: Vec<Frame> = (0..3)
            .map(|i| synthetic_frame(&format!("frame {i}/3"), 0.1 * i as f64))
            .collect();
        let path = temp_path("anim.gif");
        let mut seen = Vec::new();
        let make = |i: usize| Ok(frames[i].clone());
        let source = Frames { n: 3, make: &make };
        let survey = Survey::of(&source).unwrap();
        write_gif_with_progress(&path, &source, &survey, &mut |i| seen.push(i)).unwrap();
        assert_eq!(seen, vec![0, 1, 2]);
        let (w, h, shown) = composed_gif_frames(&path);
        assert_eq!((w, h), (WIDTH, HEIGHT));
        assert_eq!(shown.len(), 3);
        // Each composed frame is its own drawing up to the palette's rounding: a wrong
        // rectangle or transparency would leave the previous arm or surface visible.
        let view = View::fit(&frames);
        for (f, img) in frames.iter().zip(&shown) {
            let want = rgb_buffer(f, &view).unwrap();
            let far = want
                .chunks(3)
                .zip(img.chunks(3))
                .filter(|(a, b)| a.iter().zip(*b).any(|(x, y)| x.abs_diff(*y) > 40))
                .count();
            assert!(
                far < (w * h / 500) as usize,
                "{far} pixels differ in {}",
                f.title
            );
        }
    }
}
