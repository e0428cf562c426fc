//! The Fisher information of the design accumulated over samples in a cache- and
//! SIMD-friendly form. Per sample and pair of terms t ≤ s, the entries
//! `F_ab = w_a·w_b·((Kₜₛ)_qr·(Kₜₛ)ₚᵤ + (Kₜₛ)_qu·(Kₜₛ)ₚr)` (a = (t, p, q), b = (s, r, u))
//! are all products of two entries of the same Kₜₛ = BₜᵀBₛ: the sum over samples of
//! `vec(Kₜₛ)·vec(Kₜₛ)ᵀ` holds every such sum. That outer product is a contiguous
//! rank-one update (which vectorises) instead of scattered writes into the units' matrix;
//! the units' Fisher information is read out of it once, after the last sample.

use crate::design::Unit;
use nalgebra::{DMatrix, Matrix6};

/// Σₖ vec(Kₜₛ)·vec(Kₜₛ)ᵀ per pair of terms t ≤ s, upper triangles, row-major; vec index
/// of (Kₜₛ)ᵢⱼ is `i·mₛ + j`.
pub(crate) struct FisherSum {
    m: Vec<usize>,
    /// Start of each pair's block in `sums` (index t·terms + s, t ≤ s).
    offset: Vec<usize>,
    sums: Vec<f64>,
}

impl FisherSum {
    /// An empty sum for terms with `m` columns each.
    pub fn new(m: &[usize]) -> Self {
        let terms = m.len();
        let mut offset = vec![0; terms * terms];
        let mut len = 0;
        for t in 0..terms {
            for s in t..terms {
                offset[t * terms + s] = len;
                let d = m[t] * m[s];
                len += d * d;
            }
        }
        Self {
            m: m.to_vec(),
            offset,
            sums: vec![0.0; len],
        }
    }

    /// Adds one sample: `b[t]` = Bₜ (only the first mₜ columns are used).
    pub fn add(&mut self, b: &[Matrix6<f64>]) {
        let terms = self.m.len();
        let mut v = [0.0f64; 36];
        for t in 0..terms {
            for s in t..terms {
                let (mt, ms) = (self.m[t], self.m[s]);
                for i in 0..mt {
                    for j in 0..ms {
                        v[i * ms + j] = b[t].column(i).dot(&b[s].column(j));
                    }
                }
                let d = mt * ms;
                let block = &mut self.sums[self.offset[t * terms + s]..][..d * d];
                for (r, row) in block.chunks_exact_mut(d).enumerate() {
                    let vr = v[r];
                    // Upper triangle only: the block is symmetric.
                    for (o, vc) in row[r..].iter_mut().zip(&v[r..d]) {
                        *o += vr * vc;
                    }
                }
            }
        }
    }

    /// Adds another sum over other samples (same terms).
    pub fn merge(&mut self, other: &FisherSum) {
        self.sums
            .iter_mut()
            .zip(&other.sums)
            .for_each(|(s, o)| *s += o);
    }

    /// Σₖ (Kₜₛ)ᵢⱼ·(Kₜₛ)ₖₗ from pair (t, s)'s upper triangle.
    fn get(&self, t: usize, s: usize, (i, j): (usize, usize), (k, l): (usize, usize)) -> f64 {
        let terms = self.m.len();
        let ms = self.m[s];
        let d = self.m[t] * ms;
        let (x, y) = (i * ms + j, k * ms + l);
        let (x, y) = (x.min(y), x.max(y));
        self.sums[self.offset[t * terms + s] + x * d + y]
    }

    /// Adds the units' Fisher information (upper triangle) to `fisher`.
    pub fn write(&self, units: &[Unit], fisher: &mut DMatrix<f64>) {
        for (ia, a) in units.iter().enumerate() {
            for (ib, b) in units.iter().enumerate().skip(ia) {
                let (t, s) = (a.term, b.term);
                let v =
                    self.get(t, s, (a.q, b.p), (a.p, b.q)) + self.get(t, s, (a.q, b.q), (a.p, b.p));
                fisher[(ia, ib)] += a.weight() * b.weight() * v;
            }
        }
    }
}
