//! The first of an animation's two passes: its frames are made once to learn what the
//! whole animation shares (the view fitted to all frames, the frames the GIF palette is
//! learnt from, the visual shapes the HTML page lists once), keeping none of them but a
//! few samples; the writers then make them again, one batch at a time, and stream them
//! out. Memory stays bounded whatever the number of frames, at the price of making each
//! frame twice (the PPOE and its surface grid: a small part of drawing it).

use super::{Extent, Frame, Shape, View};
use std::collections::HashMap;
use std::sync::Arc;

/// Frames sampled for the GIF palette, at most.
const PALETTE_SAMPLES: usize = 4;

/// An animation's frames, made on demand.
#[derive(Clone, Copy)]
pub struct Frames<'a> {
    /// The number of frames.
    pub n: usize,
    /// Makes frame `i` of `0..n`; the same frame every time it is called for `i` (the
    /// writers call it twice per frame, possibly on several threads).
    pub make: &'a (dyn Fn(usize) -> anyhow::Result<Frame> + Sync),
}

/// What the whole animation shares, learnt in the first pass.
pub struct Survey {
    /// The view fitted to every frame.
    pub view: View,
    /// The frames the GIF palette is learnt from, evenly spread, the first one first.
    pub samples: Vec<Frame>,
    /// The visual shapes in the order the frames first use them.
    pub shapes: Vec<Arc<Shape>>,
    /// Each shape's position in `shapes`, by address (the shapes are shared by every
    /// frame and kept alive here, so an address names one shape).
    pub shape_index: HashMap<*const Shape, usize>,
}

impl Survey {
    /// Makes every frame once, in order.
    ///
    /// # Errors
    /// No frames, or the first frame that fails (with its error).
    pub fn of(frames: &Frames<'_>) -> anyhow::Result<Survey> {
        anyhow::ensure!(frames.n > 0, "no frames to write");
        let n_samples = PALETTE_SAMPLES.min(frames.n);
        let mut wanted = (0..n_samples).map(|k| k * frames.n / n_samples).peekable();
        let mut extent = Extent::default();
        let mut survey = Survey {
            view: extent.view(),
            samples: Vec::with_capacity(n_samples),
            shapes: Vec::new(),
            shape_index: HashMap::new(),
        };
        for i in 0..frames.n {
            let f = (frames.make)(i)?;
            extent.add(&f);
            for b in &f.bodies {
                let key = Arc::as_ptr(&b.shape);
                if let std::collections::hash_map::Entry::Vacant(e) = survey.shape_index.entry(key)
                {
                    e.insert(survey.shapes.len());
                    survey.shapes.push(b.shape.clone());
                }
            }
            if wanted.peek() == Some(&i) {
                wanted.next();
                survey.samples.push(f);
            }
        }
        survey.view = extent.view();
        Ok(survey)
    }

    /// The first frame (always the first sample).
    pub fn first(&self) -> &Frame {
        &self.samples[0]
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::synthetic_frame;
    use super::*;

    #[test]
    fn the_survey_fits_the_view_to_all_frames_and_keeps_only_samples() {
        let all: Vec<Frame> = (0..9)
            .map(|i| synthetic_frame(&format!("{i}"), 0.1 * i as f64))
            .collect();
        let make = |i: usize| Ok(all[i].clone());
        let s = Survey::of(&Frames { n: 9, make: &make }).unwrap();
        assert_eq!(s.view, View::fit(&all));
        let titles: Vec<&str> = s.samples.iter().map(|f| f.title.as_str()).collect();
        assert_eq!(titles, ["0", "2", "4", "6"]);
        let err = Survey::of(&Frames { n: 0, make: &make });
        assert!(err.is_err());
    }

    /// Frames that each hold a body of one shared shape: the shape's reference count,
    /// read whenever a frame is made, is the number of frames alive at that moment (plus
    /// the test's and the survey's own references).
    fn counted() -> (Arc<Shape>, impl Fn(usize) -> anyhow::Result<Frame> + Sync) {
        let shape = Arc::new(Shape::cuboid([0.1, 0.1, 0.1]));
        let seen = shape.clone();
        let make = move |i: usize| {
            let mut f = synthetic_frame(&format!("frame {i}"), 0.01 * (i % 7) as f64);
            f.bodies.push(super::super::Body {
                shape: seen.clone(),
                pose: f.tool,
                rgb: [51, 51, 255],
            });
            Ok(f)
        };
        (shape, make)
    }

    /// The most frames alive at once while `write` writes an animation of `n` frames,
    /// beyond the survey's samples.
    fn peak_live(n: usize, write: &dyn Fn(&Frames<'_>, &Survey)) -> usize {
        let (shape, make) = counted();
        let peak = std::sync::atomic::AtomicUsize::new(0);
        let watched = |i: usize| {
            let f = make(i)?;
            peak.fetch_max(
                Arc::strong_count(&shape),
                std::sync::atomic::Ordering::Relaxed,
            );
            Ok(f)
        };
        let frames = Frames { n, make: &watched };
        let survey = Survey::of(&frames).unwrap();
        peak.store(0, std::sync::atomic::Ordering::Relaxed);
        write(&frames, &survey);
        // The test's handle, the one in `make`, the survey's shape list and its samples.
        let fixed = 3 + survey.samples.len();
        peak.into_inner() - fixed
    }

    #[test]
    fn the_writers_keep_a_bounded_number_of_frames_whatever_their_number() {
        let threads = std::thread::available_parallelism()
            .map_or(1, |n| n.get())
            .clamp(1, 8);
        let dir = super::super::tests::temp_path("bounded");
        std::fs::create_dir_all(&dir).unwrap();
        let html = |f: &Frames<'_>, s: &Survey| {
            super::super::write_html(&dir.join("a.html"), f, s).unwrap();
        };
        let gif = |f: &Frames<'_>, s: &Survey| {
            super::super::write_gif_with_progress(&dir.join("a.gif"), f, s, &mut |_| ()).unwrap();
        };
        // Holding every frame (as the writers once did) would show n alive at the end.
        for n in [12, 60] {
            assert_eq!(peak_live(n, &html), 1, "html, {n} frames");
        }
        for n in [threads + 1, 4 * threads + 3] {
            let live = peak_live(n, &gif);
            assert!(
                live <= threads,
                "gif, {n} frames: {live} alive on {threads} threads"
            );
        }
    }

    #[test]
    fn a_frame_failing_half_way_keeps_the_previous_files() {
        let dir = super::super::tests::temp_path("half-way");
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let (html, gif) = (dir.join("a.html"), dir.join("a.gif"));
        std::fs::write(&html, b"previous page").unwrap();
        std::fs::write(&gif, b"previous gif").unwrap();
        let (_shape, make) = counted();
        let n = 12;
        let survey = Survey::of(&Frames { n, make: &make }).unwrap();
        // The survey saw every frame; the writers then meet a failure at frame 7.
        let failing = |i: usize| {
            anyhow::ensure!(i != 7, "frame 7 failed");
            make(i)
        };
        let frames = Frames { n, make: &failing };
        let e = super::super::write_html(&html, &frames, &survey).unwrap_err();
        assert!(e.to_string().contains("frame 7"), "{e}");
        let e = super::super::write_gif_with_progress(&gif, &frames, &survey, &mut |_| ());
        assert!(e.unwrap_err().to_string().contains("frame 7"));
        assert_eq!(std::fs::read(&html).unwrap(), b"previous page");
        assert_eq!(std::fs::read(&gif).unwrap(), b"previous gif");
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(names.len(), 2, "temporaries left: {names:?}");
    }
}
