//! Random URDF robots for the end-to-end table check (included by `build.rs`): serial
//! chains of 1–9 joints of every supported type, fixed joints between them, rpy
//! everywhere, unnormalised axes, hostile names (quotes, backslashes, non-ASCII, XML
//! entities) and extreme but finite numbers (subnormals, −0, 10^±300, ±1e308 limits).
//! Deterministic (a fixed-seed xorshift), so the build is reproducible.

/// xorshift64*: enough randomness for test inputs, no dependency.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed.max(1))
    }
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    pub fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len())]
    }
    /// A uniform value in [−a, a].
    pub fn uniform(&mut self, a: f64) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * a - a
    }
}

const NAMES: [&str; 10] = [
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
];

/// XML-escapes an attribute value.
fn xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('\t', "&#9;")
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
    let mut s = format!("<?xml version=\"1.0\"?>\n<robot name=\"random_{index}\">\n");
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
