//! Random URDF robots for the end-to-end table check (tests-build's `build.rs` generates
//! and compiles their tables): serial chains of 1–9 joints of every supported type, fixed
//! joints between them, rpy everywhere, unnormalised axes, hostile names and extreme but
//! finite numbers (subnormals, −0, 10^±300, ±1e308 limits). Deterministic (a fixed-seed
//! xorshift), so the build is reproducible.
//!
//! The names hold quotes, backslashes, XML entities, non-ASCII letters and a character of
//! every Unicode category that could break generated source: controls (Cc, C0 and C1),
//! format characters (Cf) among them every bidirectional control rustc rejects in comments
//! and literals, line and paragraph separators (Zl, Zp), non-ASCII spaces (Zs), private use
//! (Co), unassigned code points and noncharacters (Cn), a combining mark (Mn) first, and
//! `*/`. Every one is a valid XML 1.0 character.
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod hostile;
pub mod matrix4;
pub mod skeleton;

/// xorshift64*: enough randomness for test inputs, no dependency.
pub struct Rng(u64);

impl Rng {
    /// A generator seeded with `seed` (0 is replaced by 1).
    pub fn new(seed: u64) -> Self {
        Rng(seed.max(1))
    }
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    /// A value in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
    /// A random element of `xs` (not empty).
    pub fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len())]
    }
    /// A uniform value in [−a, a].
    pub fn uniform(&mut self, a: f64) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * a - a
    }
}

/// Link and joint names (each gets its index appended).
pub const NAMES: [&str; 23] = [
    "link",
    "quote\"d",
    "back\\slash",
    "ünïcødé",
    "amp&lt;gt>",
    "with space",
    "ø_ɒ_ß",
    "x",
    "名前",
    "tab\tchar",
    "rlo\u{202e}evil\u{202c}",
    "lre\u{202a}rle\u{202b}lro\u{202d}",
    "iso\u{2066}\u{2067}\u{2068}x\u{2069}",
    "lrm\u{200e}rlm\u{200f}alm\u{61c}",
    "line\nfeed\rcr",
    "nel\u{85}c1\u{9f}",
    "zl\u{2028}zp\u{2029}",
    "zs\u{a0}\u{3000}",
    "cf\u{200b}\u{ad}\u{feff}\u{2060}\u{e0001}",
    "co\u{e000}\u{10fffd}",
    "cn\u{378}\u{fdd0}\u{1fffe}",
    "\u{301}mn_first",
    "star*/slash`tick",
];

/// Odd characters for URDF file names (valid in a file name on every system): the
/// generated table's comments name the file.
pub const FILE_SUFFIXES: [&str; 5] = [
    "",
    "_\u{202e}lfru",
    "_\u{2067}x\u{2069}",
    "_\u{200b}\u{feff}",
    "_名\u{2028}",
];

/// XML-escapes an attribute value (the line breaks and tab as character references, so
/// that attribute-value normalisation keeps them).
fn xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('\t', "&#9;")
        .replace('\n', "&#10;")
        .replace('\r', "&#13;")
}

/// A length: ordinary values mostly, sometimes extreme but finite ones.
fn length(rng: &mut Rng) -> f64 {
    const SPECIAL: [f64; 9] = [0.0, -0.0, 5e-324, 1e-300, 1e-8, 1.0, 123.456, 1e6, 1e200];
    if rng.below(4) == 0 {
        *rng.pick(&SPECIAL)
    } else {
        rng.uniform(1.0)
    }
}

fn angle(rng: &mut Rng) -> f64 {
    const SPECIAL: [f64; 7] = [
        0.0,
        core::f64::consts::PI,
        -core::f64::consts::FRAC_PI_2,
        1e-12,
        7.0,
        -0.0,
        3.0,
    ];
    if rng.below(3) == 0 {
        *rng.pick(&SPECIAL)
    } else {
        rng.uniform(4.0)
    }
}

fn axis(rng: &mut Rng) -> [f64; 3] {
    const SPECIAL: [[f64; 3]; 5] = [
        [0.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
        [0.0, -2.0, 0.0],
        [1e-3, 0.0, 1e3],
        [0.3, -0.2, 0.9],
    ];
    if rng.below(2) == 0 {
        *rng.pick(&SPECIAL)
    } else {
        loop {
            let a = [rng.uniform(1.0), rng.uniform(1.0), rng.uniform(1.0)];
            if a.iter().map(|x| x * x).sum::<f64>() > 1e-2 {
                return a;
            }
        }
    }
}

fn limits(rng: &mut Rng) -> (f64, f64) {
    match rng.below(4) {
        0 => (-1e308, 1e308),
        1 => (-0.0, 0.0),
        _ => {
            let (a, b) = (rng.uniform(4.0), rng.uniform(4.0));
            (a.min(b), a.max(b))
        }
    }
}

/// One random robot: its URDF text and the (base, tip) links of its chain.
pub fn robot(rng: &mut Rng, index: usize) -> (String, String, String) {
    let n = 2 + rng.below(12); // links
    let link = |i: usize, rng: &mut Rng| format!("{}{i}", rng.pick(&NAMES));
    let links: Vec<String> = (0..n).map(|i| link(i, rng)).collect();
    let robot = format!("random_{index}_{}", NAMES[index % NAMES.len()]);
    let mut s = format!(
        "<?xml version=\"1.0\"?>\n<robot name=\"{}\">\n",
        xml(&robot)
    );
    for l in &links {
        s += &format!("  <link name=\"{}\"/>\n", xml(l));
    }
    for i in 1..n {
        // At least one moving joint: the first one is never fixed.
        let kind = if i == 1 {
            *rng.pick(&["revolute", "continuous", "prismatic"])
        } else {
            *rng.pick(&["revolute", "continuous", "prismatic", "fixed", "fixed"])
        };
        let (x, r) = (
            [length(rng), length(rng), length(rng)],
            [angle(rng), angle(rng), angle(rng)],
        );
        s += &format!(
            "  <joint name=\"{}\" type=\"{kind}\">\n",
            xml(&link(i, rng))
        );
        s += &format!(
            "    <origin xyz=\"{:?} {:?} {:?}\" rpy=\"{:?} {:?} {:?}\"/>\n",
            x[0], x[1], x[2], r[0], r[1], r[2]
        );
        s += &format!("    <parent link=\"{}\"/>\n", xml(&links[i - 1]));
        s += &format!("    <child link=\"{}\"/>\n", xml(&links[i]));
        if kind != "fixed" {
            let a = axis(rng);
            s += &format!("    <axis xyz=\"{:?} {:?} {:?}\"/>\n", a[0], a[1], a[2]);
        }
        if kind == "revolute" || kind == "prismatic" {
            let (lo, up) = limits(rng);
            s += &format!(
                "    <limit lower=\"{lo:?}\" upper=\"{up:?}\" effort=\"1\" velocity=\"1\"/>\n"
            );
        }
        s += "  </joint>\n";
    }
    s += "</robot>\n";
    (s, links[0].clone(), links[n - 1].clone())
}
