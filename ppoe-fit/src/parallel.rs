//! The per-sample sums of the likelihood, its moments and the EM step split into a fixed
//! number of chunks of samples, summed on up to as many scoped threads as the machine
//! has cores. The chunks are fixed (not the core count) and merged in their order, so
//! every sum, and the fit, is the same on any machine; only the speed depends on the
//! cores.

use std::ops::Range;

/// Chunks of samples: enough to keep eight cores busy, few enough that a chunk of a
/// 2000-sample fit still pays for its thread.
const CHUNKS: usize = 8;
/// Below this many samples a thread costs more than it saves (the result is the same).
const MIN_THREADED: usize = 256;

/// `f` over `CHUNKS` consecutive ranges covering `0..n`, results in the ranges' order.
pub(crate) fn chunks<T: Send>(n: usize, f: impl Fn(Range<usize>) -> T + Sync) -> Vec<T> {
    chunks_from(n, MIN_THREADED, f)
}

/// [`chunks`] for items that each cost as much as a thread or more (threaded from
/// `min_threaded` items on).
pub(crate) fn chunks_from<T: Send>(
    n: usize,
    min_threaded: usize,
    f: impl Fn(Range<usize>) -> T + Sync,
) -> Vec<T> {
    let size = n.div_ceil(CHUNKS).max(1);
    let ranges: Vec<Range<usize>> = (0..CHUNKS)
        .map(|c| (c * size).min(n)..((c + 1) * size).min(n))
        .collect();
    let cores = std::thread::available_parallelism().map_or(1, |p| p.get());
    if cores < 2 || n < min_threaded {
        return ranges.into_iter().map(&f).collect();
    }
    // Thread t sums chunks t, t + threads, …; the results go back in chunk order.
    let threads = cores.min(CHUNKS);
    let f = &f;
    let ranges = &ranges;
    let per_thread = |t: usize| -> Vec<(usize, T)> {
        (t..CHUNKS)
            .step_by(threads)
            .map(|c| (c, f(ranges[c].clone())))
            .collect()
    };
    let mut out: Vec<(usize, T)> = std::thread::scope(|s| {
        let handles: Vec<_> = (1..threads)
            .map(|t| s.spawn(move || per_thread(t)))
            .collect();
        let mut out = per_thread(0);
        // A panicking chunk re-raises its panic here (the sums themselves do not panic).
        for h in handles {
            out.extend(h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)));
        }
        out
    });
    out.sort_by_key(|(c, _)| *c);
    out.into_iter().map(|(_, x)| x).collect()
}

#[cfg(test)]
mod tests {
    use super::chunks;

    /// The ranges cover every index once, in order, for sizes around the chunk bounds.
    #[test]
    fn ranges_cover_every_sample_once() {
        for n in [0, 1, 2, 3, 255, 256, 257, 2000, 2001] {
            let got: Vec<usize> = chunks(n, |r| r.collect::<Vec<_>>())
                .into_iter()
                .flatten()
                .collect();
            assert_eq!(got, (0..n).collect::<Vec<_>>(), "n = {n}");
        }
    }
}
