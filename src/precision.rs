//! [`Precision`]: how the product decides a hit (`--precision`), one value for every renderer
//! (the per-eye kernels, `--accel world`, the fronts).

/// How hits are decided (`--precision`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Precision {
    /// f32, and f64 where the f32 answer is not trusted to 1e-5 (`--precision auto`, the
    /// default): f32x8 packets, each untrusted hit decided again in f64.
    #[default]
    Auto,
    /// f32 alone: f32x8 packets (or the f32 scalar kernel).
    F32,
    /// f64 everywhere: f64x4 packets (or the scalar kernel), equal to the oracle.
    F64,
}

impl Precision {
    /// Every precision, the default first.
    pub const ALL: [Precision; 3] = [Precision::Auto, Precision::F32, Precision::F64];

    /// The name `--precision` takes (also the one `-time` and `--stats` report).
    pub fn name(self) -> &'static str {
        match self {
            Precision::Auto => "auto",
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }

    /// The precision whose [`Precision::name`] is `s`, or `None`.
    pub fn parse(s: &str) -> Option<Precision> {
        Precision::ALL.into_iter().find(|p| p.name() == s)
    }
}
