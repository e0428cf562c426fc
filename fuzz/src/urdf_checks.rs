//! The `urdf` oracle: parse, extract chains, generate tables, evaluate the PPOE.

use ppoe::chain::{ChainView, Convention, Joint};
use ppoe::linalg::Mat6;
use ppoe_build::codegen::{self, Scalar, Source};
use ppoe_build::literal::{needs_escape, str_lit};
use ppoe_build::{RobotChain, Urdf};

/// Maximum number of (base, tip) pairs tried per input.
pub const MAX_PAIRS: usize = 8;
/// Inputs with more links than this are parsed but no chain is extracted (bounds the
/// work per input: chain extraction is O(path²)).
pub const MAX_LINKS: usize = 2000;

/// The body of the `urdf` target.
pub fn run(data: &[u8]) {
    let Ok(urdf) = Urdf::parse_bytes(data) else {
        return;
    };
    if urdf.links.len() > MAX_LINKS || urdf.links.is_empty() {
        return;
    }
    let source = Source {
        file_name: "fuzz.urdf".into(),
        sha256: codegen::sha256_hex(data),
    };
    for (b, t) in pairs(urdf.links.len(), data.len()) {
        let (base, tip) = (urdf.links[b].name.as_str(), urdf.links[t].name.as_str());
        let Ok(chain) = urdf.chain::<&str>(base, tip, None) else {
            continue;
        };
        assert!(!chain.joints.is_empty(), "chain with no joints: {chain:?}");
        // The same chain with the joints listed explicitly.
        let names = chain.joint_names();
        let again = urdf.chain(base, tip, Some(&names));
        assert_eq!(
            again.as_ref(),
            Ok(&chain),
            "explicit joint list gives another chain"
        );
        check_codegen(&chain, &source);
        check_runtime(&chain);
    }
}

/// The (base, tip) link pairs tried for `n` links: (first link, every other link) and
/// (every link, last link), bounded; a deterministic spread over the rest from the
/// input's length.
fn pairs(n: usize, len: usize) -> Vec<(usize, usize)> {
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for i in 1..n.min(MAX_PAIRS / 2 + 1) {
        pairs.push((0, i));
    }
    pairs.push((0, n - 1));
    pairs.push((n / 2, n - 1));
    pairs.push((n - 1, 0));
    pairs.push((len % n, (len / 7) % n));
    pairs.truncate(MAX_PAIRS + 2);
    pairs
}

/// Codegen: f64 always works; the f32 table iff the geometry fits in f32.
fn check_codegen(chain: &RobotChain, source: &Source) {
    let text = codegen::generate(chain, "FUZZ", Scalar::F64, source)
        .unwrap_or_else(|e| panic!("codegen::generate (f64) failed on an Ok chain: {e}"));
    // Names are escaped: nothing a reader cannot see (bidirectional controls, other
    // format and control characters) reaches the source raw; lines end in '\n' only.
    if let Some(c) = text.chars().find(|&c| c != '\n' && needs_escape(c)) {
        panic!("generated text holds raw {:?}:\n{text}", c);
    }
    for j in &chain.joints {
        let lit = str_lit(&j.name);
        assert!(
            text.contains(&lit),
            "generated text lacks joint name {lit}:\n{text}"
        );
    }
    assert!(text.contains(&format!("ppoe::chain::Chain<f64, {}>", chain.joints.len())));
    let ctors = text.matches("ppoe::chain::Joint::new(").count()
        + text.matches("ppoe::chain::Joint::with_constants(").count();
    assert_eq!(ctors, chain.joints.len());
    let geometry_fits = chain
        .joints
        .iter()
        .flat_map(|j| j.screw.iter())
        .chain(chain.home.iter().flatten())
        .all(|&x| (x as f32).is_finite());
    // A range admits a finite f32 position unless rounding to f32 moves its lower end
    // above f32::MAX or its upper end below −f32::MAX (both ends are ordered and not NaN
    // in an Ok chain, and rounding keeps the order).
    let limits_fit = chain
        .joints
        .iter()
        .all(|j| (j.lower as f32) <= f32::MAX && (j.upper as f32) >= -f32::MAX);
    let fits = geometry_fits && limits_fit;
    let both = codegen::generate(chain, "FUZZ", Scalar::Both, source);
    assert_eq!(both.is_ok(), fits, "Scalar::Both: {both:?}");
}

/// The runtime chain (names not leaked: the core does not need them): the PPOE and
/// forward kinematics at zero joint values.
fn check_runtime(chain: &RobotChain) {
    let joints: Vec<Joint<f64>> = chain
        .joints
        .iter()
        .map(|j| Joint::new("", j.kind, j.screw, j.lower, j.upper))
        .collect();
    let home = chain.home_transform();
    assert!(
        home.translation.is_finite() && home.rotation.is_finite(),
        "home pose not finite: {home:?}"
    );
    let rchain = ChainView {
        joints: &joints,
        home,
    };
    let zeros = vec![0.0; joints.len()];
    let covs = vec![Mat6::<f64>::identity() * 1e-4; joints.len()];
    // "Finite geometry": every screw and home value within 1e100 (larger ones may
    // overflow the covariance transport, which squares the translations).
    let moderate = chain
        .joints
        .iter()
        .flat_map(|j| j.screw.iter())
        .chain(chain.home.iter().flatten())
        .all(|x| x.abs() <= 1e100);
    for conv in [Convention::Right, Convention::Left] {
        let out = rchain
            .ppoe_checked(&zeros, &covs, conv)
            .unwrap_or_else(|e| panic!("ppoe_checked on zero joint values: {e}"));
        if moderate {
            assert!(
                out.pose.translation.is_finite() && out.pose.rotation.is_finite(),
                "PPOE pose not finite: {out:?}"
            );
            assert!(out.cov.is_finite(), "PPOE covariance not finite: {out:?}");
        }
    }
    // Forward kinematics at 0 is the home pose when 0 is within every joint's limits
    // (Exp(0) = I exactly).
    let fk = rchain.forward_kinematics(&zeros).expect("lengths match");
    if joints.iter().all(|j| j.lower <= 0.0 && 0.0 <= j.upper) {
        assert_eq!(fk, home, "FK(0) != M");
    }
}
