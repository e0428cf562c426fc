//! Instruction-count harness of the PPOE schedule (`src/ppoe/schedule.rs`), for callgrind:
//! deterministic figures on a loaded or noisy machine, where timings mean nothing.
//!
//! ```text
//! cargo build --release --example ppoe_icount
//! PPOE_ICOUNT=seed/f64/right PPOE_ICOUNT_REPS=1000 valgrind --tool=callgrind \
//!     --collect-atstart=no --toggle-collect='*icount_region*' target/release/examples/ppoe_icount
//! ```
//!
//! Instructions per call = the callgrind total / reps (the loop and the indirect call add a
//! few instructions per call: the case `empty` measures them). `PPOE_ICOUNT=list` prints
//! the cases. The cases: the seed robot (6 joints, from the golden file, with the seed
//! example's covariances: three joints have a zero covariance) and a 7-joint arm with a
//! full covariance on every joint, each in f32 and f64, tip (`right`) and base (`left`)
//! frame; and `seed_rank1/...`, the rank-one PPOE (`ChainView::ppoe_rank1`: one variance
//! per joint along its screw axis) of the seed robot in the same state, with the seed
//! example's variances (0.05 rad² on joints 1, 2, 3 and 5, none on 4 and 6), against the
//! dense `seed/...` case:
//!
//! ```text
//! for c in seed/f64/right seed_rank1/f64/right seed/f32/right seed_rank1/f32/right; do
//!   PPOE_ICOUNT=$c PPOE_ICOUNT_REPS=1000 valgrind --tool=callgrind --callgrind-out-file=/dev/null \
//!     --collect-atstart=no --toggle-collect='*icount_region*' \
//!     target/release/examples/ppoe_icount 2>&1 | grep 'Collected'
//! done
//! ```

use ppoe::chain::{ChainView, Convention, Joint};
use ppoe::{Mat6, Matrix, Real, Transform};
use ppoe_test_support::fixtures::{seed_chain, seed_state as seed_inputs, synthetic_case};
use std::hint::black_box;

/// The seed example's variances per joint value, rad² (the same joints as [`seed_inputs`]).
fn seed_variances<T: Real>() -> Vec<T> {
    [0.05, 0.05, 0.05, 0.0, 0.05, 0.0].map(T::lit).to_vec()
}

/// Joints, home pose, joint values and joint covariances of a chain.
type Inputs<T> = (Vec<Joint<T>>, Transform<T>, Vec<T>, Vec<Mat6<T>>);

/// A 7-joint arm with varied axes and a full (dense, positive definite) covariance per joint.
fn arm7<T: Real>() -> Inputs<T> {
    let n = 7;
    // The synthetic chain's joints, home and joint values; its covariances replaced by dense ones.
    let (joints, home, thetas, _) = synthetic_case(n);
    let covs = (0..n)
        .map(|k| {
            // L·Lᵀ with L lower triangular, positive diagonal: dense and positive definite.
            let l: [[f64; 6]; 6] = std::array::from_fn(|i| {
                std::array::from_fn(|j| match i.cmp(&j) {
                    std::cmp::Ordering::Less => 0.0,
                    std::cmp::Ordering::Equal => 0.01 * (1.0 + 0.1 * (i + k) as f64),
                    std::cmp::Ordering::Greater => 0.002 * ((i * 7 + j * 3 + k) % 5) as f64,
                })
            });
            let m: [[f64; 6]; 6] = std::array::from_fn(|i| {
                std::array::from_fn(|j| (0..6).map(|r| l[i][r] * l[j][r]).sum())
            });
            Matrix(m.map(|r| r.map(T::lit)))
        })
        .collect();
    (joints, home, thetas, covs)
}

type Case = (String, Box<dyn FnMut()>);

#[inline(never)]
fn icount_region(reps: usize, f: &mut dyn FnMut()) {
    for _ in 0..reps {
        f();
    }
}

fn cases<T: Real>(t: &str) -> Vec<Case> {
    let mut v: Vec<Case> = Vec::new();
    let (sj, sh) = seed_chain::<T>();
    let (sth, scov) = seed_inputs::<T>();
    let (aj, ah, ath, acov) = arm7::<T>();
    for (conv, cname) in [(Convention::Right, "right"), (Convention::Left, "left")] {
        for (name, j, h, th, cov) in [
            ("seed", &sj, sh, &sth, &scov),
            ("arm7", &aj, ah, &ath, &acov),
        ] {
            let (j, th, cov) = (j.clone(), th.clone(), cov.clone());
            v.push((
                format!("{name}/{t}/{cname}"),
                Box::new(move || {
                    let chain = ChainView {
                        joints: &j,
                        home: h,
                    };
                    black_box(chain.ppoe(black_box(&th), black_box(&cov), conv)).ok();
                }),
            ));
        }
        let (j, th, s2) = (sj.clone(), sth.clone(), seed_variances::<T>());
        v.push((
            format!("seed_rank1/{t}/{cname}"),
            Box::new(move || {
                let chain = ChainView {
                    joints: &j,
                    home: sh,
                };
                black_box(chain.ppoe_rank1(black_box(&th), black_box(&s2), conv)).ok();
            }),
        ));
    }
    v
}

fn main() {
    let which = std::env::var("PPOE_ICOUNT").unwrap_or_else(|_| "list".into());
    let reps: usize = std::env::var("PPOE_ICOUNT_REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000);
    let mut all: Vec<Case> = vec![("empty".into(), Box::new(|| ()))];
    all.extend(cases::<f64>("f64"));
    all.extend(cases::<f32>("f32"));
    if which == "list" {
        for (name, _) in &all {
            println!("{name}");
        }
        return;
    }
    let (_, f) = all
        .iter_mut()
        .find(|(name, _)| *name == which)
        .unwrap_or_else(|| panic!("no case {which}: PPOE_ICOUNT=list lists them"));
    icount_region(reps, f.as_mut());
}
