//! The animated GIF: one shared palette for the whole animation (learnt from a few sample
//! frames in the survey pass), and after the first frame only the rectangle that changed,
//! with unchanged pixels inside it transparent (they compress to almost nothing), so a
//! 200-frame animation stays small. Each frame is written to the file as soon as it and
//! the frames before it are drawn.

use super::survey::{Frames, Survey};
use super::{key_colours, rgb_buffer, Frame, View, GIF_DELAY_MS};
use anyhow::{anyhow, Context};
use std::borrow::Cow;
use std::path::Path;

/// Bits per channel of the colour look-up table that maps RGB to the palette.
const LUT_BITS: u32 = 6;
/// The palette index left unused by the drawing: "unchanged since the previous frame".
const TRANSPARENT: u8 = 255;

/// One palette for the whole animation: the [`key_colours`], then colours learnt by
/// NeuQuant from sample frames (255 colours in all: index [`TRANSPARENT`] is kept free); and
/// a look-up table from RGB (top [`LUT_BITS`] bits of each channel) to the nearest entry.
pub struct Palette {
    rgb: Vec<u8>,
    lut: Vec<u8>,
}

impl Palette {
    /// Learns the palette from sample RGB frames; `extra` colours are kept exactly.
    pub fn learn(samples: &[Vec<u8>], extra: &[[u8; 3]]) -> Palette {
        let mut keys = key_colours();
        for c in extra {
            if keys.len() < 64 && !keys.contains(c) {
                keys.push(*c);
            }
        }
        let mut rgba = Vec::new();
        for buf in samples {
            for px in buf.chunks_exact(3).step_by(3) {
                rgba.extend_from_slice(&[px[0], px[1], px[2], 255]);
            }
        }
        let mut rgb: Vec<u8> = keys.iter().flatten().copied().collect();
        if !rgba.is_empty() {
            let nq = color_quant::NeuQuant::new(3, 255 - keys.len(), &rgba);
            rgb.extend(nq.color_map_rgb());
        }
        let colours: Vec<[i32; 3]> = rgb
            .chunks_exact(3)
            .map(|c| [c[0] as i32, c[1] as i32, c[2] as i32])
            .collect();
        rgb.resize(256 * 3, 0);
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

    /// The palette index of an RGB colour.
    pub fn index(&self, r: u8, g: u8, b: u8) -> u8 {
        let shift = 8 - LUT_BITS;
        let cell = ((r as usize >> shift) << (2 * LUT_BITS))
            | ((g as usize >> shift) << LUT_BITS)
            | (b as usize >> shift);
        self.lut[cell]
    }
}

/// Draws one frame and maps it to palette indices.
fn indexed(frame: &Frame, view: &View, palette: &Palette) -> anyhow::Result<Vec<u8>> {
    let buf = rgb_buffer(frame, view)?;
    Ok(buf
        .chunks_exact(3)
        .map(|p| palette.index(p[0], p[1], p[2]))
        .collect())
}

/// The GIF frame that turns the displayed image `shown` into `next`: the bounding box of
/// the changed pixels, unchanged ones transparent; `shown` is updated.
fn delta(shown: &mut [u8], next: &[u8], width: usize) -> gif::Frame<'static> {
    let height = next.len() / width;
    let (mut x0, mut y0, mut x1, mut y1) = (width, height, 0, 0);
    for (i, (a, b)) in shown.iter().zip(next).enumerate() {
        if a != b {
            let (x, y) = (i % width, i / width);
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x + 1), y1.max(y + 1));
        }
    }
    if x0 >= x1 {
        // Nothing changed: one transparent pixel keeps the frame's delay.
        (x0, y0, x1, y1) = (0, 0, 1, 1);
    }
    let mut buffer = Vec::with_capacity((x1 - x0) * (y1 - y0));
    for y in y0..y1 {
        for x in x0..x1 {
            let i = y * width + x;
            buffer.push(if shown[i] == next[i] {
                TRANSPARENT
            } else {
                next[i]
            });
            shown[i] = next[i];
        }
    }
    gif::Frame {
        left: x0 as u16,
        top: y0 as u16,
        width: (x1 - x0) as u16,
        height: (y1 - y0) as u16,
        delay: (GIF_DELAY_MS / 10) as u16,
        dispose: gif::DisposalMethod::Keep,
        transparent: Some(TRANSPARENT),
        buffer: Cow::Owned(buffer),
        ..gif::Frame::default()
    }
}

/// Makes and draws frames `first..first + count` on `threads` threads, each frame made,
/// drawn and dropped by one thread; their palette indices in order.
fn draw_batch(
    frames: &Frames<'_>,
    (first, count): (usize, usize),
    threads: usize,
    view: &View,
    palette: &Palette,
) -> anyhow::Result<Vec<Vec<u8>>> {
    let mut done: Vec<(usize, anyhow::Result<Vec<u8>>)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                s.spawn(move || {
                    (first + t..first + count)
                        .step_by(threads)
                        .map(|i| (i, (frames.make)(i).and_then(|f| indexed(&f, view, palette))))
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
    done.into_iter().map(|(_, px)| px).collect()
}

/// Makes and draws the frames on all available cores, a few per core at a time (so
/// memory does not grow with the number of frames), and hands each frame's palette
/// indices to `sink` in order.
fn draw_in_order(
    frames: &Frames<'_>,
    view: &View,
    palette: &Palette,
    sink: &mut dyn FnMut(usize, Vec<u8>) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, 8);
    let batch = threads * 4;
    for first in (0..frames.n).step_by(batch) {
        let count = batch.min(frames.n - first);
        let drawn = draw_batch(frames, (first, count), threads.min(count), view, palette)?;
        for (i, px) in (first..).zip(drawn) {
            sink(i, px)?;
        }
    }
    Ok(())
}

/// The palette of the animation (see [`Palette`]) from the survey's sample frames.
fn palette(survey: &Survey) -> anyhow::Result<Palette> {
    let samples = survey
        .samples
        .iter()
        .map(|f| rgb_buffer(f, &survey.view))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let body_rgb: Vec<[u8; 3]> = survey.first().bodies.iter().map(|b| b.rgb).collect();
    Ok(Palette::learn(&samples, &body_rgb))
}

/// Writes the animation (see [`super::write_gif_with_progress`]): the header and the
/// palette from `survey`, then each frame as it is drawn.
pub fn write(
    path: &Path,
    frames: &Frames<'_>,
    survey: &Survey,
    progress: &mut dyn FnMut(usize),
) -> anyhow::Result<()> {
    let view = &survey.view;
    let (w, h) = (view.width, view.height);
    anyhow::ensure!(
        w <= u16::MAX as u32 && h <= u16::MAX as u32,
        "image too large for a GIF"
    );
    let palette = palette(survey)?;
    crate::output::write_atomic_path(path, |tmp| {
        let file = std::fs::File::create(tmp)
            .with_context(|| format!("cannot create {}", tmp.display()))?;
        let mut enc = gif::Encoder::new(
            std::io::BufWriter::new(file),
            w as u16,
            h as u16,
            &palette.rgb,
        )?;
        enc.set_repeat(gif::Repeat::Infinite)?;
        let mut shown: Option<Vec<u8>> = None;
        draw_in_order(frames, view, &palette, &mut |i, px| {
            let frame = match shown.as_mut() {
                None => {
                    let f = gif::Frame {
                        width: w as u16,
                        height: h as u16,
                        delay: (GIF_DELAY_MS / 10) as u16,
                        dispose: gif::DisposalMethod::Keep,
                        buffer: Cow::Borrowed(&px),
                        ..gif::Frame::default()
                    };
                    enc.write_frame(&f)?;
                    shown = Some(px);
                    progress(i);
                    return Ok(());
                }
                Some(s) => delta(s, &px, w as usize),
            };
            enc.write_frame(&frame)?;
            progress(i);
            Ok(())
        })?;
        enc.into_inner()?
            .into_inner()
            .map_err(|e| anyhow!("{}", e.error()))?
            .sync_all()?;
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delta_holds_exactly_the_changed_pixels() {
        let width = 5;
        let mut shown = vec![1u8; 20];
        let mut next = shown.clone();
        next[7] = 3; // (2, 1)
        next[13] = 4; // (3, 2)
        let f = delta(&mut shown, &next, width);
        assert_eq!((f.left, f.top, f.width, f.height), (2, 1, 2, 2));
        assert_eq!(f.buffer.as_ref(), &[3, TRANSPARENT, TRANSPARENT, 4]);
        assert_eq!(shown, next);
        let f = delta(&mut shown, &next, width);
        assert_eq!((f.width, f.height), (1, 1));
        assert_eq!(f.buffer.as_ref(), &[TRANSPARENT]);
    }
}
