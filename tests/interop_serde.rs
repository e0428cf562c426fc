//! serde (feature `serde`): JSON round trips are bit-exact, and deserialisation rejects
//! what the types' own checks reject.
#![cfg(feature = "serde")]

use ppoe::chain::{screw_noise, Chain, Convention, Joint, JointKind, UncertainPose};
use ppoe::{Error, Mat3, Mat6, Matrix, Transform, Vector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const INF: f64 = f64::INFINITY;

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

fn arm() -> Chain<f64, 3> {
    Chain::new(
        "base",
        "tool",
        [
            Joint::new(
                "shoulder",
                JointKind::Revolute,
                [0., 0., 1., 0., 0., 0.],
                -3.0,
                3.0,
            ),
            Joint::new(
                "elbow",
                JointKind::Continuous,
                [0., 1., 0., -0.5, 0., 0.],
                -INF,
                INF,
            ),
            Joint::new(
                "slide",
                JointKind::Prismatic,
                [0., 0., 0., 1., 0., 0.],
                0.0,
                0.25,
            ),
        ]
        .map(Joint::prepared),
        Transform::from_rpy(&[0.1, 0.2, 0.3], [1.0, 0.0, 0.5]).unwrap(),
    )
}

#[test]
fn vectors_and_matrices_round_trip_bit_exact() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..200 {
        // Random bit patterns of finite numbers, including subnormals and extremes.
        let v = Vector([0; 6].map(|_| loop {
            let x = f64::from_bits(rng.gen());
            if x.is_finite() {
                break x;
            }
        }));
        let back: Vector<f64, 6> =
            serde_json::from_str(&serde_json::to_string(&v).unwrap()).unwrap();
        assert!(back
            .0
            .iter()
            .zip(&v.0)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        let m = Matrix([[0; 4]; 2].map(|r| r.map(|_| rng.gen::<f32>() * 1e3 - 5e2)));
        let back: Matrix<f32, 2, 4> =
            serde_json::from_str(&serde_json::to_string(&m).unwrap()).unwrap();
        assert_eq!(back, m);
    }
    assert_eq!(
        serde_json::to_string(&Vector([1.5f64, -2.0])).unwrap(),
        "[1.5,-2.0]"
    );
    assert_eq!(
        serde_json::to_string(&Mat3::<f32>::identity()).unwrap(),
        "[[1.0,0.0,0.0],[0.0,1.0,0.0],[0.0,0.0,1.0]]"
    );
    // Wrong lengths are errors.
    assert!(serde_json::from_str::<Vector<f64, 3>>("[1,2]").is_err());
    assert!(serde_json::from_str::<Vector<f64, 3>>("[1,2,3,4]").is_err());
    assert!(serde_json::from_str::<Matrix<f64, 2, 2>>("[[1,2],[3]]").is_err());
}

#[test]
fn transform_round_trips_and_is_validated() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    for _ in 0..200 {
        let rpy = [0; 3].map(|_| rng.gen_range(-3.0..3.0));
        let t = Transform::<f64>::from_rpy(&rpy, [0; 3].map(|_| rng.gen_range(-9.0..9.0))).unwrap();
        let back: Transform<f64> =
            serde_json::from_str(&serde_json::to_string(&t).unwrap()).unwrap();
        assert_eq!(back, t);
        let t32 = Transform::<f32>::from_f64(&t);
        let back: Transform<f32> =
            serde_json::from_str(&serde_json::to_string(&t32).unwrap()).unwrap();
        assert_eq!(back, t32);
    }
    // The 4×4 homogeneous matrix, row-major: written by hand, not by the code under test.
    let ok = "[[1,0,0,1],[0,1,0,2],[0,0,1,3],[0,0,0,1]]";
    let t = serde_json::from_str::<Transform<f64>>(ok).unwrap();
    assert_eq!(t.translation.0, [1.0, 2.0, 3.0]);
    assert_eq!(t.rotation, Mat3::identity());
    // A quarter turn about z: column 0 of R is the image of x, (0, 1, 0).
    let quarter = "[[0,-1,0,0],[1,0,0,0],[0,0,1,0],[0,0,0,1]]";
    let q = serde_json::from_str::<Transform<f64>>(quarter).unwrap();
    assert_eq!(
        q.rotation.0,
        [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    );
    assert_eq!(
        serde_json::to_string(&Transform::<f64>::identity()).unwrap(),
        "[[1.0,0.0,0.0,0.0],[0.0,1.0,0.0,0.0],[0.0,0.0,1.0,0.0],[0.0,0.0,0.0,1.0]]"
    );
    let bad = [
        "[[1,0,0,1],[0,1,0,2],[0,0,-1,3],[0,0,0,1]]", // reflection
        "[[1,0.01,0,1],[0,1,0,2],[0,0,1,3],[0,0,0,1]]", // not orthonormal
        "[[1,0,0,1],[0,1,0,2],[0,0,1,3],[0,0,0,2]]",  // not homogeneous
        "[[1,0,0,1],[0,1,0,2],[0,0,1,3],[0.1,0,0,1]]", // a projective row
        "[[1,0,0,1],[0,1,0,2],[0,0,1,3]]",            // 3 rows
        "[[1,0,0],[0,1,0],[0,0,1],[0,0,0]]",          // rows of 3
        "[[1,0,0,1],[0,1,0,2],[0,0,1,3],[0,0,0,1],[0,0,0,1]]",
        "[[1,0,0,1e999],[0,1,0,2],[0,0,1,3],[0,0,0,1]]",
        r#"{"rotation":[[1,0,0],[0,1,0],[0,0,1]],"translation":[1,2,3]}"#, // the old shape
    ];
    for b in bad {
        assert!(serde_json::from_str::<Transform<f64>>(b).is_err(), "{b}");
    }
    let e = serde_json::from_str::<Transform<f64>>(bad[2])
        .unwrap_err()
        .to_string();
    assert!(e.contains("bottom row"), "{e}");
    let e = serde_json::from_str::<Transform<f64>>(bad[1])
        .unwrap_err()
        .to_string();
    assert!(e.contains("not orthonormal"), "{e}");
}

#[test]
fn chain_round_trips_bit_exact_with_unbounded_limits() {
    let chain = arm();
    let json = leak(serde_json::to_string(&chain).unwrap());
    assert!(
        json.contains(r#""kind":"continuous""#) && json.contains(r#""lower":null"#),
        "{json}"
    );
    let back: Chain<f64, 3> = serde_json::from_str(json).unwrap();
    assert_eq!(back, chain); // names, kinds, screws, limits, displacement constants, home
                             // Joints written with Joint::new (no constants) come back prepared.
    let raw = Joint::new(
        "j",
        JointKind::Revolute,
        [1.0f32, 0., 0., 0., 0., 0.],
        -1.0,
        1.0,
    );
    let back: Joint<f32> =
        serde_json::from_str(leak(serde_json::to_string(&raw).unwrap())).unwrap();
    assert_eq!(back, raw.prepared());
    // A chain of another length, and a joint axis of length 2, are errors.
    assert!(serde_json::from_str::<Chain<f64, 2>>(json).is_err());
    let bad_axis = json.replacen("[0.0,0.0,1.0,0.0,0.0,0.0]", "[0.0,0.0,2.0,0.0,0.0,0.0]", 1);
    assert_ne!(bad_axis, json);
    let e = serde_json::from_str::<Chain<f64, 3>>(leak(bad_axis))
        .unwrap_err()
        .to_string();
    assert!(e.contains("zero length") || e.contains("axis"), "{e}");
    // An infinite limit on the wrong side cannot be written as null: an error.
    let wrong = Joint::new(
        "w",
        JointKind::Revolute,
        [1.0, 0., 0., 0., 0., 0.],
        INF,
        INF,
    );
    assert!(serde_json::to_string(&wrong).is_err());
    // Names with escapes cannot be borrowed: an error, not a changed name.
    let esc = leak(
        serde_json::to_string(&Joint::new(
            "a\"b",
            JointKind::Revolute,
            [1.0, 0., 0., 0., 0., 0.],
            -1.0,
            1.0,
        ))
        .unwrap(),
    );
    assert!(serde_json::from_str::<Joint<f64>>(esc).is_err());
}

#[test]
fn uncertain_pose_round_trips_and_cov_is_validated() {
    let chain = arm();
    let covs = chain.joints.map(|j| screw_noise(&j.screw, 1e-4));
    let tip = chain
        .ppoe_checked(&[0.3, -0.2, 0.1], &covs, Convention::Right)
        .unwrap();
    let json = serde_json::to_string(&tip).unwrap();
    let back: UncertainPose<f64> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, tip);
    let mut asym = tip;
    asym.cov.0[0][1] += 1.0;
    let e = serde_json::from_str::<UncertainPose<f64>>(&serde_json::to_string(&asym).unwrap())
        .unwrap_err();
    assert!(e.to_string().contains("symmetric"), "{e}");
    // Fields it does not know are ignored (an `eval` result's `thetas_clipped`); a
    // missing one is an error.
    let mut extra = serde_json::to_value(tip).unwrap();
    extra["thetas_clipped"] = serde_json::json!([0.3, -0.2, 0.1]);
    let back: UncertainPose<f64> = serde_json::from_value(extra).unwrap();
    assert_eq!(back, tip);
    let mut missing = serde_json::to_value(tip).unwrap();
    let cov = missing.as_object_mut().unwrap().remove("cov").unwrap();
    missing["covv"] = cov;
    assert!(serde_json::from_value::<UncertainPose<f64>>(missing).is_err());
    let mut neg = tip;
    neg.cov = Mat6::identity().scale(-1.0);
    assert!(
        serde_json::from_str::<UncertainPose<f64>>(&serde_json::to_string(&neg).unwrap()).is_err()
    );
}

#[test]
fn enums_round_trip() {
    for k in [
        JointKind::Revolute,
        JointKind::Continuous,
        JointKind::Prismatic,
    ] {
        let s = serde_json::to_string(&k).unwrap();
        assert_eq!(serde_json::from_str::<JointKind>(&s).unwrap(), k);
    }
    assert_eq!(
        serde_json::to_string(&JointKind::Prismatic).unwrap(),
        "\"prismatic\""
    );
    for c in [
        Convention::Right,
        Convention::Left,
        Convention::Pytransform3d,
    ] {
        assert_eq!(
            serde_json::from_str::<Convention>(&serde_json::to_string(&c).unwrap()).unwrap(),
            c
        );
    }
    assert_eq!(
        serde_json::to_string(&Error::NotARotation).unwrap(),
        "\"NotARotation\""
    );
    assert_eq!(
        serde_json::from_str::<Error>("\"GridSize\"").unwrap(),
        Error::GridSize
    );
    assert!(serde_json::from_str::<JointKind>("\"fixed\"").is_err());
}

#[test]
fn chain_view_is_written_like_its_chain() {
    let chain = arm();
    let view = serde_json::to_value(chain.as_ref()).unwrap();
    let full = serde_json::to_value(chain).unwrap();
    assert_eq!(view["joints"], full["joints"]);
    assert_eq!(view["home"], full["home"]);
    assert_eq!(view.as_object().unwrap().len(), 2);
}
