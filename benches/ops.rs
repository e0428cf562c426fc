//! Criterion benchmarks of every core operation, f32 and f64, with the nalgebra baseline
//! of the PPOE measured in the same run. `scripts/bench-report.sh` turns the results into
//! BENCHMARKS.md.

mod baseline_nalgebra;
#[path = "pinocchio/export.rs"]
mod export;
#[path = "pinocchio/robots.rs"]
mod robots;

use criterion::{criterion_group, BenchmarkId, Criterion};
use ppoe::chain::{ChainView, Convention, Joint, JointKind, UncertainPose};
use ppoe::surface::{self, Surface};
use ppoe::uncertainty::{self, IterationOptions, Order};
use ppoe::{se3, so3, Mat6, Matrix, Real, Transform, Vec3, Vector};
use ppoe_test_support::fixtures;
use serde_json::Value;
use std::hint::black_box;

fn golden_seed() -> Value {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/test_data/golden/ppoe/seed_linkmount_tcp.json"
    );
    serde_json::from_str(&std::fs::read_to_string(path).expect("golden seed file")).expect("json")
}

fn num(v: &Value) -> f64 {
    match v {
        Value::String(s) if s == "inf" => f64::INFINITY,
        Value::String(s) if s == "-inf" => f64::NEG_INFINITY,
        _ => v.as_f64().expect("number"),
    }
}

/// The seed robot's chain (from the oracle's golden file) in scalar T.
/// The seed chain in scalar T, converted from the golden f64 values the way `ppoe-build`
/// converts its tables (`Joint::from_f64`, `Transform::from_f64`: the f32 chain gets no
/// subnormal-prone `1.9e-23` entries).
fn seed_chain<T: Real>(g: &Value) -> (Vec<Joint<T>>, Transform<T>) {
    let (joints, home) = seed_chain_rounded::<f64>(g);
    let joints = joints.iter().map(Joint::from_f64).collect();
    (joints, Transform::from_f64(&home))
}

/// The seed chain with every golden value only rounded to T (no `from_f64`): in f32 it keeps
/// the `−1.9e-23` entries whose products are subnormal (the `fk_seed/rounded_only` bench).
fn seed_chain_rounded<T: Real>(g: &Value) -> (Vec<Joint<T>>, Transform<T>) {
    let joints = g["screw_axes"]
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
                std::array::from_fn(|i| T::lit(s[i])),
                T::lit(l[0]),
                T::lit(l[1]),
            )
            .prepared()
        })
        .collect();
    let h: Vec<Vec<f64>> = g["home"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r.as_array().unwrap().iter().map(num).collect())
        .collect();
    let home = Transform::from_matrix4(&std::array::from_fn(|i| {
        std::array::from_fn(|j| T::lit(h[i][j]))
    }));
    (joints, home)
}

/// The joints without their displacement constants, as `Joint::new` makes them.
fn without_constants<T: Real>(joints: &[Joint<T>]) -> Vec<Joint<T>> {
    joints
        .iter()
        .map(|j| Joint::new(j.name, j.kind, j.screw.0, j.lower, j.upper))
        .collect()
}

/// The seed example's joint covariances and initial joint values (the shared fixture).
fn seed_inputs<T: Real>() -> ([T; 6], [Mat6<T>; 6]) {
    let (thetas, covs) = fixtures::seed_state();
    (
        std::array::from_fn(|i| thetas[i]),
        std::array::from_fn(|i| covs[i]),
    )
}

/// The synthetic chain of n joints (the shared fixture: varied axes, full-rank covariances).
fn synthetic<T: Real>(n: usize) -> fixtures::Case<T> {
    fixtures::synthetic_case(n)
}

fn num_traits_abs<T: Real>(x: T) -> T {
    if x < T::ZERO {
        -x
    } else {
        x
    }
}

fn ty<T>() -> &'static str {
    if std::mem::size_of::<T>() == 4 {
        "f32"
    } else {
        "f64"
    }
}

fn core_ops<T: Real>(c: &mut Criterion) {
    let t = ty::<T>();
    let xi = Vector([0.3, -0.2, 0.5, 0.4, 0.1, -0.3].map(T::lit));
    let tr = se3::exp(&xi);
    let tr2 = se3::exp(&Vector([-0.6, 0.1, 0.2, 0.0, 0.7, 0.2].map(T::lit)));
    let cov = Mat6::from_diagonal(&Vector([1e-3, 2e-3, 5e-4, 1e-3, 3e-3, 2e-3].map(T::lit)));
    // The input lives in memory, like every other op's: storing a fresh `xi.rotation()`
    // in every iteration made the f32 code's overlapping pair loads wait on the stores.
    let w = xi.rotation();
    c.bench_function(&format!("so3_exp/{t}"), |b| {
        b.iter(|| so3::exp(black_box(&w)))
    });
    c.bench_function(&format!("so3_log/{t}"), |b| {
        b.iter(|| so3::log(black_box(&tr.rotation)))
    });
    c.bench_function(&format!("se3_exp/{t}"), |b| {
        b.iter(|| se3::exp(black_box(&xi)))
    });
    c.bench_function(&format!("se3_log/{t}"), |b| {
        b.iter(|| se3::log(black_box(&tr)))
    });
    c.bench_function(&format!("adjoint/{t}"), |b| {
        b.iter(|| black_box(&tr).adjoint())
    });
    c.bench_function(&format!("se3_left_jacobian/{t}"), |b| {
        b.iter(|| se3::left_jacobian(black_box(&xi)))
    });
    c.bench_function(&format!("se3_left_jacobian_inv/{t}"), |b| {
        b.iter(|| se3::left_jacobian_inv(black_box(&xi)))
    });
    for (name, order) in [
        ("concat_globally_2nd", Order::Second),
        ("concat_globally_4th", Order::Fourth),
    ] {
        c.bench_function(&format!("{name}/{t}"), |b| {
            b.iter(|| uncertainty::concat_globally(black_box(&tr), &cov, &tr2, &cov, order))
        });
    }
    c.bench_function(&format!("concat_locally/{t}"), |b| {
        b.iter(|| uncertainty::concat_locally(black_box(&tr), &tr2, &cov, &cov))
    });
    c.bench_function(&format!("invert/{t}"), |b| {
        b.iter(|| uncertainty::invert(black_box(&tr), &cov))
    });
    let means = [
        tr,
        tr * se3::exp(&Vector([0.01, 0.0, -0.02, 0.01, 0.0, 0.02].map(T::lit))),
        tr2 * tr,
    ];
    let covs = [cov; 3];
    c.bench_function(&format!("pose_fusion_k3/{t}"), |b| {
        b.iter(|| uncertainty::pose_fusion(black_box(&means), &covs, &IterationOptions::default()))
    });
}

fn ppoe_ops<T: Real + nalgebra::RealField>(c: &mut Criterion) {
    let t = ty::<T>();
    let g = golden_seed();
    let (joints, home) = seed_chain::<T>(&g);
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let (thetas, covs) = seed_inputs::<T>();
    c.bench_function(&format!("ppoe_seed/ours/{t}"), |b| {
        b.iter(|| chain.ppoe(black_box(&thetas), &covs, Convention::Right))
    });
    // Joints as `Joint::new` makes them (hand-written const chains): the displacement
    // constants derived in every call.
    let bare = without_constants(&joints);
    let bare_chain = ChainView {
        joints: &bare,
        home,
    };
    c.bench_function(&format!("ppoe_seed/ours_joint_new/{t}"), |b| {
        b.iter(|| bare_chain.ppoe(black_box(&thetas), &covs, Convention::Right))
    });
    c.bench_function(&format!("ppoe_seed/ours_4th_order/{t}"), |b| {
        b.iter(|| chain.ppoe_fourth_order(black_box(&thetas), &covs, Convention::Right))
    });
    // The rigid part alone: the same clipped displacements and their serial product.
    c.bench_function(&format!("fk_seed/ours/{t}"), |b| {
        b.iter(|| chain.forward_kinematics(black_box(&thetas)))
    });
    // The same with the golden values only rounded to T (no `Joint::from_f64`).
    let (rj, rh) = seed_chain_rounded::<T>(&g);
    let rounded = ChainView {
        joints: &rj,
        home: rh,
    };
    c.bench_function(&format!("fk_seed/rounded_only/{t}"), |b| {
        b.iter(|| rounded.forward_kinematics(black_box(&thetas)))
    });
    // The nalgebra baseline, checked to give the same numbers first.
    let (na, na_covs) = baseline_nalgebra::inputs(&joints, home, &covs);
    check_nalgebra(&chain, &na, &thetas, &covs, &na_covs);
    c.bench_function(&format!("ppoe_seed/nalgebra/{t}"), |b| {
        b.iter(|| baseline_nalgebra::ppoe(&na, black_box(&thetas), &na_covs))
    });
    c.bench_function(&format!("ppoe_seed/nalgebra_closed/{t}"), |b| {
        b.iter(|| baseline_nalgebra::ppoe_closed_form(&na, black_box(&thetas), &na_covs))
    });

    arm7_ops::<T>(c);

    let mut group = c.benchmark_group(format!("ppoe_chain/{t}"));
    for n in [1usize, 2, 4, 8, 16, 32] {
        let (js, home, th, cv) = synthetic::<T>(n);
        let ch = ChainView { joints: &js, home };
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| ch.ppoe(black_box(&th), &cv, Convention::Right))
        });
    }
    group.finish();

    let tip = chain.ppoe(&thetas, &covs, Convention::Right).unwrap();
    let mut buf = vec![Vec3::<T>::zeros(); 2500];
    for n in [20usize, 50] {
        for (name, s) in [
            ("lift", Surface::Lift),
            ("pytransform3d", Surface::Pytransform3d),
        ] {
            c.bench_function(&format!("surface_{name}_n{n}/{t}"), |b| {
                b.iter(|| {
                    surface::surface_grid(s, black_box(&tip.pose), &tip.cov, T::ONE, n, &mut buf)
                })
            });
        }
    }
    let _ = Matrix::<T, 1, 1>::zeros();
}

/// Panics unless both nalgebra ports give ppoe's pose and covariance (within 1000 ε).
fn check_nalgebra<T: Real + nalgebra::RealField>(
    chain: &ChainView<'_, T>,
    na: &baseline_nalgebra::NaChain<T>,
    thetas: &[T],
    covs: &[Mat6<T>],
    na_covs: &[nalgebra::Matrix6<T>],
) {
    check_port(
        chain,
        baseline_nalgebra::ppoe(na, thetas, na_covs),
        thetas,
        covs,
    );
    check_port(
        chain,
        baseline_nalgebra::ppoe_closed_form(na, thetas, na_covs),
        thetas,
        covs,
    );
}

/// Panics unless `(na_pose, na_cov)` is ppoe's pose and covariance (within 1000 ε).
fn check_port<T: Real + nalgebra::RealField>(
    chain: &ChainView<'_, T>,
    (na_pose, na_cov): (nalgebra::Matrix4<T>, nalgebra::Matrix6<T>),
    thetas: &[T],
    covs: &[Mat6<T>],
) {
    let ours = chain.ppoe(thetas, covs, Convention::Right).unwrap();
    // Relative to the largest entry: an absolute 1000 ε would pass any f32 covariance of
    // the 7-joint arm, whose entries are ~1e-6.
    let scale = ours.cov.0.iter().flatten().fold(T::ZERO, |a, &x| {
        let y = num_traits_abs(x);
        if y > a {
            y
        } else {
            a
        }
    });
    let tol = T::EPS * T::lit(1e3);
    let m = ours.pose.to_matrix4();
    for i in 0..6 {
        for j in 0..6 {
            assert!(
                num_traits_abs(na_cov[(i, j)] - ours.cov.0[i][j]) <= tol * scale,
                "nalgebra baseline disagrees (covariance)"
            );
        }
    }
    for i in 0..3 {
        for j in 0..4 {
            assert!(
                num_traits_abs(na_pose[(i, j)] - m[i][j]) <= tol,
                "nalgebra baseline disagrees (pose)"
            );
        }
    }
}

/// The 7-joint arm of test_data/urdf/arm7.urdf (full-rank joint covariances): ppoe, the
/// nalgebra port and the rigid forward kinematics.
fn arm7_ops<T: Real + nalgebra::RealField>(c: &mut Criterion) {
    let t = ty::<T>();
    let (joints, home) = robots::core_chain::<T>(&robots::robot_chain(&robots::ARM7));
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let thetas = robots::arm7_thetas::<T>();
    let covs = robots::arm7_covs::<T>(joints.len());
    let (na, na_covs) = baseline_nalgebra::inputs(&joints, home, &covs);
    check_nalgebra(&chain, &na, &thetas, &covs, &na_covs);
    c.bench_function(&format!("ppoe_7dof/ours/{t}"), |b| {
        b.iter(|| chain.ppoe(black_box(&thetas), &covs, Convention::Right))
    });
    c.bench_function(&format!("ppoe_7dof/nalgebra/{t}"), |b| {
        b.iter(|| baseline_nalgebra::ppoe(&na, black_box(&thetas), &na_covs))
    });
    c.bench_function(&format!("ppoe_7dof/nalgebra_closed/{t}"), |b| {
        b.iter(|| baseline_nalgebra::ppoe_closed_form(&na, black_box(&thetas), &na_covs))
    });
    c.bench_function(&format!("fk_7dof/ours/{t}"), |b| {
        b.iter(|| chain.forward_kinematics(black_box(&thetas)))
    });
}

/// Configurations in one batch of the batch benchmarks (`batch_*`); bench_report.py divides
/// the batch's time by it.
const BATCH: usize = 256;

/// The batch PPOE against single calls and the nalgebra ports, dense covariances on every
/// joint (`robots::arm7_covs`), on the seed and the 7-joint arm: `batch_<robot>/<impl>/<T>`,
/// `batch` timing one call on `BATCH` configurations, the others one configuration
/// (`nalgebra`: general 4×4 inverses, `nalgebra_closed`: the closed form).
fn batch_ops<T: Real + nalgebra::RealField>(c: &mut Criterion) {
    let t = ty::<T>();
    let seed = seed_chain::<T>(&golden_seed());
    let arm7 = robots::core_chain::<T>(&robots::robot_chain(&robots::ARM7));
    for (name, (joints, home)) in [("seed", seed), ("7dof", arm7)] {
        let chain = ChainView {
            joints: &joints,
            home,
        };
        let n = joints.len();
        let covs = robots::arm7_covs::<T>(n);
        let thetas = robots::batch_thetas::<T>(BATCH, n);
        let mut out = vec![UncertainPose::certain(Transform::identity()); BATCH];
        c.bench_function(&format!("batch_{name}/batch/{t}"), |b| {
            b.iter(|| chain.ppoe_batch(black_box(&thetas), &covs, Convention::Right, &mut out))
        });
        let one = &thetas[..n];
        c.bench_function(&format!("batch_{name}/single/{t}"), |b| {
            b.iter(|| chain.ppoe(black_box(one), &covs, Convention::Right))
        });
        let (na, na_covs) = baseline_nalgebra::inputs(&joints, home, &covs);
        check_nalgebra(&chain, &na, one, &covs, &na_covs);
        c.bench_function(&format!("batch_{name}/nalgebra/{t}"), |b| {
            b.iter(|| baseline_nalgebra::ppoe(&na, black_box(one), &na_covs))
        });
        c.bench_function(&format!("batch_{name}/nalgebra_closed/{t}"), |b| {
            b.iter(|| baseline_nalgebra::ppoe_closed_form(&na, black_box(one), &na_covs))
        });
    }
}

fn all(c: &mut Criterion) {
    batch_ops::<f64>(c);
    batch_ops::<f32>(c);
    core_ops::<f64>(c);
    core_ops::<f32>(c);
    ppoe_ops::<f64>(c);
    ppoe_ops::<f32>(c);
}

// ---- Deterministic instruction counts (callgrind) ------------------------------------------
//
// `PPOE_CALLGRIND=<op>/<f32|f64> PPOE_CALLGRIND_REPS=<k> valgrind --tool=callgrind
// --collect-atstart=no --toggle-collect='*callgrind_region*' <this bench binary>` runs one op
// k times inside `callgrind_region` and nothing else is counted; `PPOE_CALLGRIND=list` prints
// the op names. The calls go through a `&mut dyn FnMut()`: the op `empty` measures that
// overhead (scripts/bench-report.sh subtracts it).

type Op = (String, Box<dyn FnMut()>);

#[inline(never)]
fn callgrind_region(reps: usize, f: &mut dyn FnMut()) {
    for _ in 0..reps {
        f();
    }
}

fn op<R>(name: String, mut f: impl FnMut() -> R + 'static) -> Op {
    (
        name,
        Box::new(move || {
            black_box(f());
        }),
    )
}

fn callgrind_ops<T: Real + nalgebra::RealField>() -> Vec<Op> {
    let t = ty::<T>();
    let xi = Vector([0.3, -0.2, 0.5, 0.4, 0.1, -0.3].map(T::lit));
    let tr = se3::exp(&xi);
    let tr2 = se3::exp(&Vector([-0.6, 0.1, 0.2, 0.0, 0.7, 0.2].map(T::lit)));
    let cov = Mat6::from_diagonal(&Vector([1e-3, 2e-3, 5e-4, 1e-3, 3e-3, 2e-3].map(T::lit)));
    let g = golden_seed();
    let (joints, home) = seed_chain::<T>(&g);
    let (thetas, covs) = seed_inputs::<T>();
    let (na, na_covs) = baseline_nalgebra::inputs(&joints, home, &covs);
    let tip = ChainView {
        joints: &joints,
        home,
    }
    .ppoe(&thetas, &covs, Convention::Right)
    .unwrap();
    let mut v: Vec<Op> = vec![
        op(format!("empty/{t}"), || ()),
        op(format!("so3_exp/{t}"), move || {
            let w = xi.rotation();
            so3::exp(black_box(&w))
        }),
        op(format!("so3_log/{t}"), move || {
            so3::log(black_box(&tr.rotation))
        }),
        op(format!("se3_exp/{t}"), move || se3::exp(black_box(&xi))),
        op(format!("se3_log/{t}"), move || se3::log(black_box(&tr))),
        op(format!("adjoint/{t}"), move || black_box(&tr).adjoint()),
        op(format!("se3_left_jacobian/{t}"), move || {
            se3::left_jacobian(black_box(&xi))
        }),
        op(format!("se3_left_jacobian_inv/{t}"), move || {
            se3::left_jacobian_inv(black_box(&xi))
        }),
        op(format!("concat_globally_2nd/{t}"), move || {
            uncertainty::concat_globally(black_box(&tr), &cov, &tr2, &cov, Order::Second)
        }),
        op(format!("concat_globally_4th/{t}"), move || {
            uncertainty::concat_globally(black_box(&tr), &cov, &tr2, &cov, Order::Fourth)
        }),
        op(format!("concat_locally/{t}"), move || {
            uncertainty::concat_locally(black_box(&tr), &tr2, &cov, &cov)
        }),
        op(format!("invert/{t}"), move || {
            uncertainty::invert(black_box(&tr), &cov)
        }),
    ];
    let means = [
        tr,
        tr * se3::exp(&Vector([0.01, 0.0, -0.02, 0.01, 0.0, 0.02].map(T::lit))),
        tr2 * tr,
    ];
    v.push(op(format!("pose_fusion_k3/{t}"), move || {
        uncertainty::pose_fusion(black_box(&means), &[cov; 3], &IterationOptions::default())
    }));
    let (j1, j2) = (joints.clone(), joints.clone());
    v.push(op(format!("ppoe_seed/ours/{t}"), move || {
        let chain = ChainView { joints: &j1, home };
        chain.ppoe(black_box(&thetas), &covs, Convention::Right)
    }));
    let bare = without_constants(&joints);
    v.push(op(format!("ppoe_seed/ours_joint_new/{t}"), move || {
        let chain = ChainView {
            joints: &bare,
            home,
        };
        chain.ppoe(black_box(&thetas), &covs, Convention::Right)
    }));
    v.push(op(format!("ppoe_seed/ours_4th_order/{t}"), move || {
        let chain = ChainView { joints: &j2, home };
        chain.ppoe_fourth_order(black_box(&thetas), &covs, Convention::Right)
    }));
    let j3 = joints.clone();
    v.push(op(format!("fk_seed/ours/{t}"), move || {
        let chain = ChainView { joints: &j3, home };
        chain.forward_kinematics(black_box(&thetas))
    }));
    let (rj, rh) = seed_chain_rounded::<T>(&g);
    v.push(op(format!("fk_seed/rounded_only/{t}"), move || {
        let chain = ChainView {
            joints: &rj,
            home: rh,
        };
        chain.forward_kinematics(black_box(&thetas))
    }));
    let (na2, thetas2, na_covs2) = (na.clone(), thetas, na_covs.clone());
    v.push(op(format!("ppoe_seed/nalgebra/{t}"), move || {
        baseline_nalgebra::ppoe(&na, black_box(&thetas), &na_covs)
    }));
    v.push(op(format!("ppoe_seed/nalgebra_closed/{t}"), move || {
        baseline_nalgebra::ppoe_closed_form(&na2, black_box(&thetas2), &na_covs2)
    }));
    v.extend(arm7_callgrind_ops::<T>());
    v.extend(chain_callgrind_ops::<T>());
    v.extend(surface_callgrind_ops(tip));
    v
}

/// The surface ops for the callgrind mode (the same inputs as the `surface_*` benches).
fn surface_callgrind_ops<T: Real>(tip: UncertainPose<T>) -> Vec<Op> {
    let t = ty::<T>();
    let mut v = Vec::new();
    for n in [20usize, 50] {
        for (name, s) in [
            ("lift", Surface::Lift),
            ("pytransform3d", Surface::Pytransform3d),
        ] {
            let mut buf = vec![Vec3::<T>::zeros(); 2500];
            v.push(op(format!("surface_{name}_n{n}/{t}"), move || {
                surface::surface_grid(s, black_box(&tip.pose), &tip.cov, T::ONE, n, &mut buf)
                    .is_ok()
            }));
        }
    }
    v
}

/// The synthetic chains' ops for the callgrind mode (the same inputs as `ppoe_chain`).
fn chain_callgrind_ops<T: Real>() -> Vec<Op> {
    let t = ty::<T>();
    let mut v = Vec::new();
    for n in [1usize, 2, 4, 8, 16, 32] {
        let (js, home, th, cv) = synthetic::<T>(n);
        v.push(op(format!("ppoe_chain/{t}/{n}"), move || {
            let ch = ChainView { joints: &js, home };
            ch.ppoe(black_box(&th), &cv, Convention::Right)
        }));
    }
    v
}

/// The 7-joint arm's ops for the callgrind mode (the same inputs as `arm7_ops`).
fn arm7_callgrind_ops<T: Real + nalgebra::RealField>() -> Vec<Op> {
    let t = ty::<T>();
    let mut v = Vec::new();
    let (aj, ah) = robots::core_chain::<T>(&robots::robot_chain(&robots::ARM7));
    let (ath, acov) = (robots::arm7_thetas::<T>(), robots::arm7_covs::<T>(aj.len()));
    let (ana, ana_covs) = baseline_nalgebra::inputs(&aj, ah, &acov);
    let (aj1, ath1, acov1) = (aj.clone(), ath.clone(), acov.clone());
    v.push(op(format!("ppoe_7dof/ours/{t}"), move || {
        let chain = ChainView {
            joints: &aj1,
            home: ah,
        };
        chain.ppoe(black_box(&ath1), &acov1, Convention::Right)
    }));
    let (ath2, ath3) = (ath.clone(), ath.clone());
    let (ana3, ana_covs3) = (ana.clone(), ana_covs.clone());
    v.push(op(format!("ppoe_7dof/nalgebra/{t}"), move || {
        baseline_nalgebra::ppoe(&ana, black_box(&ath2), &ana_covs)
    }));
    v.push(op(format!("ppoe_7dof/nalgebra_closed/{t}"), move || {
        baseline_nalgebra::ppoe_closed_form(&ana3, black_box(&ath3), &ana_covs3)
    }));
    v.push(op(format!("fk_7dof/ours/{t}"), move || {
        let chain = ChainView {
            joints: &aj,
            home: ah,
        };
        chain.forward_kinematics(black_box(&ath))
    }));
    v
}

/// The callgrind mode (see above); `false` if `PPOE_CALLGRIND` is not set.
fn callgrind_mode() -> bool {
    let Ok(which) = std::env::var("PPOE_CALLGRIND") else {
        return false;
    };
    let reps: usize = std::env::var("PPOE_CALLGRIND_REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000);
    let mut ops = callgrind_ops::<f64>();
    ops.extend(callgrind_ops::<f32>());
    if which == "list" {
        for (name, _) in &ops {
            println!("{name}");
        }
        return true;
    }
    let Some((_, f)) = ops.iter_mut().find(|(n, _)| *n == which) else {
        eprintln!("PPOE_CALLGRIND: unknown op {which} (PPOE_CALLGRIND=list lists them)");
        std::process::exit(2);
    };
    f(); // warm (lazy statics, first-touch): not counted
    callgrind_region(reps, f.as_mut());
    true
}

criterion_group!(benches, all);

fn main() {
    // `PPOE_PINOCCHIO_EXPORT=DIR`: write DIR/robots.hpp for benches/pinocchio/fk_bench.cpp.
    if let Ok(dir) = std::env::var("PPOE_PINOCCHIO_EXPORT") {
        export::write_header(&dir);
        return;
    }
    if callgrind_mode() {
        return;
    }
    benches();
    Criterion::default().configure_from_args().final_summary();
}
