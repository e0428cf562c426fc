//! Instruction-count harness of the PPOE schedule (`src/transport.rs`), for callgrind:
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

use ppoe::chain::{ChainView, Convention, Joint, JointKind};
use ppoe::{se3, Mat6, Matrix, Real, Transform, Vec3};
use serde_json::Value;
use std::hint::black_box;

fn num(v: &Value) -> f64 {
    match v {
        Value::String(s) if s == "inf" => f64::INFINITY,
        Value::String(s) if s == "-inf" => f64::NEG_INFINITY,
        _ => v.as_f64().expect("number"),
    }
}

/// The seed robot's chain from the oracle's golden file, converted as `ppoe-build` does.
fn seed_chain<T: Real>() -> (Vec<Joint<T>>, Transform<T>) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/test_data/golden/ppoe/seed_linkmount_tcp.json"
    );
    let g: Value =
        serde_json::from_str(&std::fs::read_to_string(path).expect("golden seed file")).unwrap();
    let joints: Vec<Joint<f64>> = g["screw_axes"]
        .as_array()
        .unwrap()
        .iter()
        .zip(g["limits"].as_array().unwrap())
        .map(|(s, l)| {
            let s: Vec<f64> = s.as_array().unwrap().iter().map(num).collect();
            let l: Vec<f64> = l.as_array().unwrap().iter().map(num).collect();
            Joint::new(
                "j",
                JointKind::Revolute,
                std::array::from_fn(|i| s[i]),
                l[0],
                l[1],
            )
        })
        .collect();
    let h: Vec<Vec<f64>> = g["home"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r.as_array().unwrap().iter().map(num).collect())
        .collect();
    let home = Transform::from_matrix4(&std::array::from_fn(|i| std::array::from_fn(|j| h[i][j])));
    (
        joints.iter().map(Joint::from_f64).collect(),
        Transform::from_f64(&home),
    )
}

/// The seed example's joint values and covariances (joints 4 and 6 have none).
fn seed_inputs<T: Real>() -> (Vec<T>, Vec<Mat6<T>>) {
    let mut covs = vec![Mat6::zeros(); 6];
    covs[0].0[2][2] = T::lit(0.05);
    for i in [1, 2, 4] {
        covs[i].0[1][1] = T::lit(0.05);
    }
    (
        [-0.5, -0.5, -0.5, 0.0, -0.5, 0.0].map(T::lit).to_vec(),
        covs,
    )
}

/// The seed example's variances per joint value, rad² (the same joints as [`seed_inputs`]).
fn seed_variances<T: Real>() -> Vec<T> {
    [0.05, 0.05, 0.05, 0.0, 0.05, 0.0].map(T::lit).to_vec()
}

/// Joints, home pose, joint values and joint covariances of a chain.
type Inputs<T> = (Vec<Joint<T>>, Transform<T>, Vec<T>, Vec<Mat6<T>>);

/// A 7-joint arm with varied axes and a full (dense, positive definite) covariance per joint.
fn arm7<T: Real>() -> Inputs<T> {
    let n = 7;
    let joints = (0..n)
        .map(|i| {
            let a = i as f64 * 0.7;
            let s = Vec3::<f64>::new(a.sin() * 0.3, a.cos() * 0.4, 0.866);
            let q = Vec3::new(0.1 * i as f64, 0.05, 0.2 * i as f64);
            let screw = se3::screw_axis(&q, &s, 0.0).unwrap();
            Joint::from_f64(&Joint::new("j", JointKind::Revolute, screw.0, -3.0, 3.0))
        })
        .collect();
    let home = Transform::from_parts(
        [[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]].map(|r| r.map(T::lit)),
        [0.1, 0.0, 0.2 * n as f64].map(T::lit),
    );
    let thetas = (0..n).map(|i| T::lit(0.3 + 0.1 * i as f64)).collect();
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
