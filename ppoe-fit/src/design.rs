//! The covariance model as a linear design: Σ(θ) = R + Σₜ Aₜ·Xₜ·Aₜᵀ, a sum of *terms*
//! (one per joint, plus the residual floor of the joint model), each a 6×m transport Aₜ
//! and a symmetric m×m coefficient matrix Xₜ. The coefficients are spanned by *units*
//! `Sₚq = eₚe_qᵀ + e_qeₚᵀ` (p < q) and `eₚeₚᵀ`, so Σ is linear in the unit coefficients
//! `x = (Xₜ)ₚq` and the Gaussian log-likelihood's gradient and Fisher information in x
//! have closed forms: with Σ = LLᵀ, Bₜ = L⁻¹Aₜ, z = L⁻¹η, yₜ = Bₜᵀz, Kₜₛ = BₜᵀBₛ and
//! w = 1 (p < q) or ½ (p = q),
//! `∂ℓ/∂x_a = w_a·(yₚ·y_q − (Kₜₜ)ₚq)` and
//! `F_ab = w_a·w_b·((Kₜₛ)_qr·(Kₜₛ)ₚₛ + (Kₜₛ)_qs·(Kₜₛ)ₚr)`.

use crate::fisher::FisherSum;
use crate::parallel::chunks;
use crate::samples::Prepared;
use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// One unit: coefficient (p, q), p ≤ q, of term `term`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Unit {
    pub term: usize,
    pub p: usize,
    pub q: usize,
}

impl Unit {
    /// 1 for p < q, ½ for p = q (the unit's two or one entries).
    pub fn weight(&self) -> f64 {
        if self.p == self.q {
            0.5
        } else {
            1.0
        }
    }
}

/// The terms' transports per sample and the units.
pub(crate) struct Design {
    /// Per sample, per term: Aₜ (6×6, only the first m columns used).
    pub a: Vec<Vec<Matrix6<f64>>>,
    /// Columns per term.
    pub m: Vec<usize>,
    /// The units, grouped by term.
    pub units: Vec<Unit>,
    /// The samples' residuals.
    pub eta: Vec<Vector6<f64>>,
    /// The known measurement covariance R (tip frame).
    pub r: Matrix6<f64>,
}

/// Log-likelihood, gradient and Fisher information in the unit coefficients, and each
/// sample's squared Mahalanobis distance.
pub(crate) struct Moments {
    pub loglik: f64,
    pub grad: DVector<f64>,
    pub fisher: DMatrix<f64>,
    pub mahalanobis: Vec<f64>,
}

const LN_2PI: f64 = 1.837_877_066_409_345_5;

/// One sample's Gaussian log-density from Σ's factor L and z = L⁻¹η.
fn gaussian_loglik(lo: &Matrix6<f64>, z: &Vector6<f64>) -> f64 {
    let logdet: f64 = 2.0 * (0..6).map(|i| lo[(i, i)].ln()).sum::<f64>();
    -0.5 * (logdet + z.norm_squared() + 6.0 * LN_2PI)
}

impl Design {
    /// The design of the joint model (one term per joint, Aᵢ = Ad(Gᵢ⁻¹)·Sᵢ, m = 1) plus a
    /// floor term (A = I, units on the diagonal only), or of the full model (Aᵢ = Ad(Gᵢ⁻¹),
    /// m = 6, all 21 units), no floor. The floor only where asked (`floor`).
    pub fn new(data: &Prepared, joint_model: bool, floor: bool, r: Matrix6<f64>) -> Self {
        let n = data.screws.len();
        let mut units = Vec::new();
        let mut m = Vec::new();
        for t in 0..n {
            let mt = if joint_model { 1 } else { 6 };
            m.push(mt);
            for p in 0..mt {
                for q in p..mt {
                    units.push(Unit { term: t, p, q });
                }
            }
        }
        let floor = joint_model && floor;
        if floor {
            m.push(6);
            units.extend((0..6).map(|p| Unit { term: n, p, q: p }));
        }
        let a = data
            .transports
            .iter()
            .map(|ads| {
                let mut terms: Vec<Matrix6<f64>> = if joint_model {
                    ads.iter()
                        .zip(&data.screws)
                        .map(|(ad, s)| {
                            let mut a = Matrix6::zeros();
                            a.set_column(0, &(ad * s));
                            a
                        })
                        .collect()
                } else {
                    ads.clone()
                };
                if floor {
                    terms.push(Matrix6::identity());
                }
                terms
            })
            .collect();
        Self {
            a,
            m,
            units,
            eta: data.eta.clone(),
            r,
        }
    }

    /// Σ for sample k with coefficient matrices `x` (one per term).
    pub fn sigma(&self, k: usize, x: &[Matrix6<f64>]) -> Matrix6<f64> {
        // Column-major slices and the upper triangle only: Σ is symmetric, and only the
        // first m rows and columns of each Xₜ are coefficients (zero elsewhere).
        let mut s = [0.0f64; 36];
        for ((a, xt), &m) in self.a[k].iter().zip(x).zip(&self.m) {
            let (a, xt) = (a.as_slice(), xt.as_slice());
            // Y = Aₜ·Xₜ, column c at y[6c..6c + 6].
            let mut y = [0.0f64; 36];
            for c in 0..m {
                for j in 0..m {
                    let xjc = xt[6 * c + j];
                    for r in 0..6 {
                        y[6 * c + r] += a[6 * j + r] * xjc;
                    }
                }
            }
            // Σ += Y·Aₜᵀ (upper triangle, column r2 at s[6·r2..]).
            for c in 0..m {
                for r2 in 0..6 {
                    let a2 = a[6 * c + r2];
                    for r1 in 0..=r2 {
                        s[6 * r2 + r1] += y[6 * c + r1] * a2;
                    }
                }
            }
        }
        Matrix6::from_fn(|r, c| {
            let (lo, hi) = (r.min(c), r.max(c));
            self.r[(r, c)] + s[6 * hi + lo]
        })
    }

    /// The log-likelihood alone; `None` if some Σ is not positive definite.
    pub fn loglik(&self, x: &[Matrix6<f64>]) -> Option<f64> {
        let parts = chunks(self.eta.len(), |range| {
            let mut l = 0.0;
            for k in range {
                let (lo, z) = self.whiten(k, x)?;
                l += gaussian_loglik(&lo, &z);
            }
            Some(l)
        });
        let l = parts.into_iter().sum::<Option<f64>>()?;
        l.is_finite().then_some(l)
    }

    /// Σₖ = LLᵀ's factor and the whitened residual z = L⁻¹ηₖ.
    fn whiten(&self, k: usize, x: &[Matrix6<f64>]) -> Option<(Matrix6<f64>, Vector6<f64>)> {
        let lo = self.sigma(k, x).cholesky()?.l();
        let z = lo.solve_lower_triangular(&self.eta[k])?;
        Some((lo, z))
    }

    /// Log-likelihood, gradient and Fisher information at `x`, the Fisher information
    /// from every `stride`-th sample scaled to all of them; `None` if some Σ is not
    /// positive definite.
    pub fn moments(&self, x: &[Matrix6<f64>], stride: usize) -> Option<Moments> {
        let u = self.units.len();
        let mut out = Moments {
            loglik: 0.0,
            grad: DVector::zeros(u),
            fisher: DMatrix::zeros(u, u),
            mahalanobis: Vec::with_capacity(self.eta.len()),
        };
        let mut used = 0usize;
        let mut fisher = FisherSum::new(&self.m);
        for part in chunks(self.eta.len(), |range| self.moments_of(x, stride, range)) {
            let (part, part_fisher, part_used) = part?;
            out.loglik += part.loglik;
            out.grad += part.grad;
            out.mahalanobis.extend(part.mahalanobis);
            fisher.merge(&part_fisher);
            used += part_used;
        }
        fisher.write(&self.units, &mut out.fisher);
        out.fisher.fill_lower_triangle_with_upper_triangle();
        out.fisher *= self.eta.len() as f64 / used.max(1) as f64;
        out.loglik.is_finite().then_some(out)
    }

    /// The moments' sums over the samples `range` (Fisher information as its sum, with
    /// the number of samples in it).
    fn moments_of(
        &self,
        x: &[Matrix6<f64>],
        stride: usize,
        range: std::ops::Range<usize>,
    ) -> Option<(Moments, FisherSum, usize)> {
        let mut out = Moments {
            loglik: 0.0,
            grad: DVector::zeros(self.units.len()),
            fisher: DMatrix::zeros(0, 0),
            mahalanobis: Vec::with_capacity(range.len()),
        };
        let mut used = 0usize;
        let mut fisher = FisherSum::new(&self.m);
        for k in range {
            let (lo, z) = self.whiten(k, x)?;
            let b: Vec<Matrix6<f64>> = self.a[k]
                .iter()
                .map(|a| lo.solve_lower_triangular(a))
                .collect::<Option<_>>()?;
            out.loglik += gaussian_loglik(&lo, &z);
            out.mahalanobis.push(z.norm_squared());
            let y: Vec<Vector6<f64>> = b.iter().map(|bt| bt.transpose() * z).collect();
            self.gradient(&y, |t| b[t].transpose() * b[t], &mut out.grad);
            if k % stride == 0 {
                fisher.add(&b);
                used += 1;
            }
        }
        Some((out, fisher, used))
    }

    /// One EM step for the latent per-term noise ξₜ ~ N(0, Xₜ), η = Σₜ Aₜξₜ + ν:
    /// `Xₜ ← Xₜ + Xₜ·Gₜ·Xₜ`, `Gₜ = mean over samples of (yₜyₜᵀ − Kₜₜ)` (the posterior
    /// second moment of ξₜ averaged), which keeps every Xₜ PSD and never lowers the
    /// likelihood. Returns the new coefficients and the log-likelihood at `x`.
    pub fn em_step(&self, x: &[Matrix6<f64>]) -> Option<(Vec<Matrix6<f64>>, f64)> {
        let parts = chunks(self.eta.len(), |range| {
            let mut g = vec![Matrix6::zeros(); self.m.len()];
            let mut loglik = 0.0;
            for k in range {
                let (lo, z) = self.whiten(k, x)?;
                loglik += gaussian_loglik(&lo, &z);
                for (gt, a) in g.iter_mut().zip(&self.a[k]) {
                    let b = lo.solve_lower_triangular(a)?;
                    let y = b.transpose() * z;
                    *gt += y * y.transpose() - b.transpose() * b;
                }
            }
            Some((g, loglik))
        });
        let mut g = vec![Matrix6::zeros(); self.m.len()];
        let mut loglik = 0.0;
        for part in parts {
            let (part_g, part_l) = part?;
            g.iter_mut().zip(&part_g).for_each(|(gt, pt)| *gt += pt);
            loglik += part_l;
        }
        let n = self.eta.len() as f64;
        let next = x
            .iter()
            .zip(&g)
            .zip(&self.m)
            .map(|((xt, gt), &m)| {
                let mut u = xt + xt * (gt / n) * xt;
                u = (u + u.transpose()) * 0.5;
                // Only the first m rows and columns are coefficients.
                Matrix6::from_fn(|r, c| if r < m && c < m { u[(r, c)] } else { 0.0 })
            })
            .collect();
        loglik.is_finite().then_some((next, loglik))
    }

    /// The method-of-moments normal equations: least squares of Σ(x) against ηηᵀ in the
    /// Frobenius norm (the moments at L = I with the data term ηηᵀ − R): returns
    /// (½·Σₖ⟨Dₐ, D_b⟩, ½·Σₖ⟨Dₐ, ηηᵀ − R⟩).
    pub fn normal_equations(&self) -> (DMatrix<f64>, DVector<f64>) {
        let u = self.units.len();
        let mut out = Moments {
            loglik: 0.0,
            grad: DVector::zeros(u),
            fisher: DMatrix::zeros(u, u),
            mahalanobis: Vec::new(),
        };
        let mut fisher = FisherSum::new(&self.m);
        for (k, eta) in self.eta.iter().enumerate() {
            let b = &self.a[k];
            let y: Vec<Vector6<f64>> = b.iter().map(|bt| bt.transpose() * eta).collect();
            self.gradient(&y, |t| b[t].transpose() * self.r * b[t], &mut out.grad);
            fisher.add(b);
        }
        fisher.write(&self.units, &mut out.fisher);
        out.fisher.fill_lower_triangle_with_upper_triangle();
        (out.fisher, out.grad)
    }

    /// Adds one sample's gradient, `kdiag(t)` the matrix subtracted from yyᵀ for term t.
    fn gradient(
        &self,
        y: &[Vector6<f64>],
        kdiag: impl Fn(usize) -> Matrix6<f64>,
        grad: &mut DVector<f64>,
    ) {
        let mut current = usize::MAX;
        let mut kd = Matrix6::zeros();
        for (ia, a) in self.units.iter().enumerate() {
            if a.term != current {
                current = a.term;
                kd = kdiag(current);
            }
            grad[ia] += a.weight() * (y[a.term][a.p] * y[a.term][a.q] - kd[(a.p, a.q)]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::samples::Prepared;

    /// Twenty made-up samples of a two-joint design.
    fn prepared() -> Prepared {
        let mut prepared = Prepared {
            eta: Vec::new(),
            transports: Vec::new(),
            screws: vec![
                Vector6::new(0., 0., 1., 0., 0.3, 0.),
                Vector6::new(1., 0., 0., 0., 0., 0.2),
            ],
            clipped: 0,
        };
        for k in 0..20 {
            let f = k as f64;
            prepared.eta.push(Vector6::from_fn(|i, _| {
                ((i as f64 + 1.0) * (f + 0.3)).sin() * 0.01
            }));
            prepared.transports.push(
                (0..2)
                    .map(|j| {
                        Matrix6::from_fn(|r, c| {
                            ((r * 7 + c * 3 + j * 5) as f64 + f).cos()
                                + if r == c { 2.0 } else { 0.0 }
                        })
                    })
                    .collect(),
            );
        }
        prepared
    }

    /// Positive definite coefficient matrices for every term of `d`.
    fn coefficients(d: &Design) -> Vec<Matrix6<f64>> {
        d.m.iter()
            .enumerate()
            .map(|(t, &m)| {
                let mut a = Matrix6::from_fn(|r, c| {
                    if r < m && c < m {
                        ((r + 2 * c + t) as f64).sin() * 0.1
                    } else {
                        0.0
                    }
                });
                a = a * a.transpose() * 1e-3;
                for i in 0..m {
                    a[(i, i)] += 1e-4;
                }
                a
            })
            .collect()
    }

    /// The closed-form gradient against central differences of the log-likelihood.
    #[test]
    fn gradient_matches_differences() {
        let prepared = prepared();
        for joint_model in [true, false] {
            let d = Design::new(&prepared, joint_model, true, Matrix6::identity() * 1e-6);
            let x = coefficients(&d);
            let mo = d.moments(&x, 1).unwrap();
            for (ia, u) in d.units.iter().enumerate() {
                let h = 1e-7;
                let mut xp = x.clone();
                let mut xm = x.clone();
                xp[u.term][(u.p, u.q)] += h;
                xm[u.term][(u.p, u.q)] -= h;
                if u.p != u.q {
                    xp[u.term][(u.q, u.p)] += h;
                    xm[u.term][(u.q, u.p)] -= h;
                }
                let num = (d.loglik(&xp).unwrap() - d.loglik(&xm).unwrap()) / (2.0 * h);
                let rel = (num - mo.grad[ia]).abs() / num.abs().max(1.0);
                assert!(
                    rel < 1e-4,
                    "{joint_model} unit {u:?}: {num} vs {}",
                    mo.grad[ia]
                );
            }
        }
    }

    /// The Fisher information against its definition for a Gaussian of covariance
    /// Σ(x): `F_ab = ½·Σₖ tr(Σₖ⁻¹·∂Σₖ/∂x_a·Σₖ⁻¹·∂Σₖ/∂x_b)`, with dense inverses.
    #[test]
    fn fisher_matches_definition() {
        let prepared = prepared();
        for joint_model in [true, false] {
            let d = Design::new(&prepared, joint_model, true, Matrix6::identity() * 1e-6);
            let x = coefficients(&d);
            let fisher = d.moments(&x, 1).unwrap().fisher;
            let derivative = |k: usize, u: &Unit| {
                let mut e = Matrix6::zeros();
                e[(u.p, u.q)] = 1.0;
                e[(u.q, u.p)] = 1.0;
                d.a[k][u.term] * e * d.a[k][u.term].transpose()
            };
            for (ia, ua) in d.units.iter().enumerate() {
                for (ib, ub) in d.units.iter().enumerate() {
                    let mut want = 0.0;
                    for k in 0..d.eta.len() {
                        let sigma = d.a[k]
                            .iter()
                            .zip(&x)
                            .fold(d.r, |s, (a, xt)| s + a * xt * a.transpose());
                        let inv = sigma.try_inverse().unwrap();
                        let m = inv * derivative(k, ua) * inv * derivative(k, ub);
                        want += 0.5 * m.trace();
                    }
                    let got = fisher[(ia, ib)];
                    assert!(
                        (got - want).abs() <= 1e-9 * want.abs().max(1.0),
                        "{joint_model} ({ia}, {ib}): {got} vs {want}"
                    );
                }
            }
        }
    }
}
