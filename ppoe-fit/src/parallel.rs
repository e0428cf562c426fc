//! The per-sample sums of the likelihood, its moments and the EM step split into a fixed
//! number of chunks of samples, each summed on its own scoped thread where the machine
//! has more than one core. The chunks are fixed (not the core count), so every sum, and
//! the fit, is the same on any machine.

use std::ops::Range;

/// Chunks of samples: the fit's machine has two cores.
const CHUNKS: usize = 2;
/// Below this many samples a thread costs more than it saves (the result is the same).
const MIN_THREADED: usize = 256;

/// `f` over `CHUNKS` consecutive ranges covering `0..n`, results in the ranges' order.
pub(crate) fn chunks<T: Send>(n: usize, f: impl Fn(Range<usize>) -> T + Sync) -> Vec<T> {
    let size = n.div_ceil(CHUNKS).max(1);
    let ranges: Vec<Range<usize>> = (0..CHUNKS)
        .map(|c| (c * size).min(n)..((c + 1) * size).min(n))
        .collect();
    let cores = std::thread::available_parallelism().map_or(1, |p| p.get());
    if cores < 2 || n < MIN_THREADED {
        return ranges.into_iter().map(&f).collect();
    }
    let f = &f;
    std::thread::scope(|s| {
        let handles: Vec<_> = ranges[1..]
            .iter()
            .cloned()
            .map(|r| s.spawn(move || f(r)))
            .collect();
        let mut out = vec![f(ranges[0].clone())];
        // A panicking chunk re-raises its panic here (the sums themselves do not panic).
        out.extend(
            handles
                .into_iter()
                .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e))),
        );
        out
    })
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
