//! The parameterisations that keep every covariance positive semi-definite: σᵢ² = exp(sᵢ)
//! for the joint model (and the floor's two variances), Cᵢ = LᵢLᵢᵀ with Lᵢ lower
//! triangular with a positive diagonal exp(φ) (the log-Cholesky parameterisation, 21
//! parameters) for the full model. Each maps its parameters θ to the unit
//! coefficients of [`Design`](crate::design::Design) with an analytic Jacobian.

use nalgebra::{DMatrix, DVector, Matrix6};

/// Which per-joint covariance the fit estimates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Model {
    /// Joint-value noise: `Cᵢ = σᵢ²·SᵢSᵢᵀ`, one variance per joint (encoder noise,
    /// backlash), as [`ppoe::chain::screw_noise`] builds it.
    Joint,
    /// Any 6×6 positive semi-definite `Cᵢ` per joint (flexible links), base-frame screw
    /// coordinates, rotation first.
    Full,
}

impl Model {
    /// `"joint"` or `"full"`.
    pub fn name(self) -> &'static str {
        match self {
            Model::Joint => "joint",
            Model::Full => "full",
        }
    }
}

/// The (row, column) of each of the 21 lower-triangle entries of L, row-major.
fn lower_index() -> impl Iterator<Item = (usize, usize)> {
    (0..6).flat_map(|a| (0..=a).map(move |b| (a, b)))
}

pub(crate) struct Param {
    pub model: Model,
    pub n: usize,
    /// Lower bounds of the floor's variances (joint model); `None`: no floor (the
    /// measurement covariance is positive definite, so Σ is too).
    pub floor_min: Option<[f64; 2]>,
}

impl Param {
    /// Number of parameters θ.
    pub fn len(&self) -> usize {
        match self.model {
            Model::Joint => self.n + if self.floor_min.is_some() { 2 } else { 0 },
            Model::Full => 21 * self.n,
        }
    }

    /// The coefficient matrix of every term of the design.
    pub fn coeffs(&self, th: &DVector<f64>) -> Vec<Matrix6<f64>> {
        match self.model {
            Model::Joint => {
                let mut x: Vec<Matrix6<f64>> = (0..self.n)
                    .map(|i| {
                        let mut m = Matrix6::zeros();
                        m[(0, 0)] = th[i].exp();
                        m
                    })
                    .collect();
                if self.floor_min.is_some() {
                    let (r, t) = (th[self.n].exp(), th[self.n + 1].exp());
                    x.push(Matrix6::from_diagonal(&nalgebra::Vector6::new(
                        r, r, r, t, t, t,
                    )));
                }
                x
            }
            Model::Full => (0..self.n)
                .map(|i| {
                    let l = self.lower(th, i);
                    l * l.transpose()
                })
                .collect(),
        }
    }

    fn lower(&self, th: &DVector<f64>, i: usize) -> Matrix6<f64> {
        let mut l = Matrix6::zeros();
        for (k, (a, b)) in lower_index().enumerate() {
            let v = th[21 * i + k];
            l[(a, b)] = if a == b { v.exp() } else { v };
        }
        l
    }

    /// ∂x/∂θ: unit coefficients (as ordered by the design) by parameters.
    pub fn jacobian(&self, th: &DVector<f64>, units: usize) -> DMatrix<f64> {
        let mut j = DMatrix::zeros(units, self.len());
        match self.model {
            Model::Joint => {
                let n = self.n;
                for i in 0..n {
                    j[(i, i)] = th[i].exp();
                }
                if self.floor_min.is_some() {
                    for p in 0..6 {
                        let c = if p < 3 { n } else { n + 1 };
                        j[(n + p, c)] = th[c].exp();
                    }
                }
            }
            Model::Full => {
                for i in 0..self.n {
                    let l = self.lower(th, i);
                    let mut row = 21 * i;
                    for p in 0..6 {
                        for q in p..6 {
                            for (k, (a, b)) in lower_index().enumerate() {
                                let mut d = 0.0;
                                if p == a {
                                    d += l[(q, b)];
                                }
                                if q == a {
                                    d += l[(p, b)];
                                }
                                // The diagonal is exp(φ): ∂L_aa/∂φ = L_aa.
                                j[(row, 21 * i + k)] = if a == b { d * l[(a, a)] } else { d };
                            }
                            row += 1;
                        }
                    }
                }
            }
        }
        j
    }

    /// ∂x/∂(natural parameters): the natural parameters are σᵢ² and the two floor
    /// variances (joint model) or the unit coefficients themselves (full model).
    pub fn natural_jacobian(&self, units: usize) -> DMatrix<f64> {
        match self.model {
            Model::Joint => {
                let n = self.n;
                let mut j = DMatrix::zeros(units, self.len());
                for i in 0..n {
                    j[(i, i)] = 1.0;
                }
                if self.floor_min.is_some() {
                    for p in 0..6 {
                        j[(n + p, if p < 3 { n } else { n + 1 })] = 1.0;
                    }
                }
                j
            }
            Model::Full => DMatrix::identity(units, units),
        }
    }

    /// Parameters at their lower bound whose gradient points below it (held fixed in a
    /// step: the active set).
    pub fn active(&self, th: &DVector<f64>, g: &DVector<f64>) -> Vec<bool> {
        let mut out = vec![false; self.len()];
        if let (Model::Joint, Some(floor)) = (self.model, self.floor_min) {
            for (k, min) in floor.iter().enumerate() {
                let i = self.n + k;
                out[i] = th[i] <= min.ln() + 1e-9 && g[i] <= 0.0;
            }
        }
        out
    }

    /// Keeps the floor's log-variances at or above their bounds.
    pub fn clamp(&self, th: &mut DVector<f64>) {
        if let (Model::Joint, Some(floor)) = (self.model, self.floor_min) {
            for (k, min) in floor.iter().enumerate() {
                let v = &mut th[self.n + k];
                *v = v.max(min.ln());
            }
        }
    }

    /// The starting point from unconstrained natural-parameter estimates (method of
    /// moments): variances at least `1e-6` of the largest, covariances projected onto
    /// the PSD cone with eigenvalues at least `1e-6` of their largest.
    pub fn start(&self, natural: &DVector<f64>) -> DVector<f64> {
        let mut th = DVector::zeros(self.len());
        match self.model {
            Model::Joint => {
                let n = self.n;
                // Where the moments give no joint a positive variance (a floor took the
                // residuals), the joints start at 1e-6 of the floor's instead of at 1e-300,
                // from where scoring can still reach them.
                let floor_scale = match self.floor_min {
                    Some(_) => 1e-6 * natural[n].max(natural[n + 1]).max(0.0),
                    None => 0.0,
                };
                let top = (0..n)
                    .map(|i| natural[i])
                    .fold(floor_scale, f64::max)
                    .max(1e-300);
                for i in 0..n {
                    th[i] = natural[i].max(1e-6 * top).ln();
                }
                // The floor starts at 1e-4 of the residuals' variance or above: at its
                // bound (1e-12) Σ is nearly singular and scoring crawls.
                if let Some(floor) = self.floor_min {
                    th[n] = natural[n].max(1e8 * floor[0]).ln();
                    th[n + 1] = natural[n + 1].max(1e8 * floor[1]).ln();
                }
            }
            Model::Full => {
                for i in 0..self.n {
                    let c = unit_matrix(natural, 21 * i);
                    let l = psd_factor(&c);
                    for (k, (a, b)) in lower_index().enumerate() {
                        th[21 * i + k] = if a == b { l[(a, a)].ln() } else { l[(a, b)] };
                    }
                }
            }
        }
        th
    }
}

impl Param {
    /// θ for given full-model coefficient matrices (factors of their PD projections).
    pub fn theta_of(&self, x: &[Matrix6<f64>]) -> DVector<f64> {
        let mut th = DVector::zeros(self.len());
        for (i, c) in x.iter().enumerate().take(self.n) {
            let l = psd_factor(c);
            for (k, (a, b)) in lower_index().enumerate() {
                th[21 * i + k] = if a == b { l[(a, a)].ln() } else { l[(a, b)] };
            }
        }
        th
    }
}

/// The symmetric 6×6 matrix whose upper-triangle units start at `offset` of `x`.
pub(crate) fn unit_matrix(x: &DVector<f64>, offset: usize) -> Matrix6<f64> {
    let mut c = Matrix6::zeros();
    let mut k = offset;
    for p in 0..6 {
        for q in p..6 {
            c[(p, q)] = x[k];
            c[(q, p)] = x[k];
            k += 1;
        }
    }
    c
}

/// A lower-triangular factor of `c` projected onto the positive definite matrices
/// (eigenvalues at least 1e-6 of the largest, and at least 1e-300).
fn psd_factor(c: &Matrix6<f64>) -> Matrix6<f64> {
    let e = c.symmetric_eigen();
    let top = e.eigenvalues.max().max(1e-300);
    let d = e.eigenvalues.map(|v| v.max(1e-6 * top));
    let m = e.eigenvectors * Matrix6::from_diagonal(&d) * e.eigenvectors.transpose();
    let m = (m + m.transpose()) * 0.5;
    m.cholesky()
        .map(|ch| ch.l())
        .unwrap_or_else(|| Matrix6::identity() * top.sqrt() * 1e-3)
}
