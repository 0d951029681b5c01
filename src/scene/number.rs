//! Decimal numbers as scene and OBJ files write them.
//!
//! The grammar is strict: optional sign, digits with an optional fraction (at least one digit in
//! all), optional exponent (`e`/`E`, optional sign, at least one digit). [`is_decimal`] is the
//! grammar alone; [`decimal`] checks the same grammar in the same pass as it gathers the digits,
//! then takes Clinger's fast path when it is exact (at most 19 digits, a mantissa up to 2^53 and
//! a power of ten up to 1e22: one correctly rounded multiplication or division of two exact
//! f64 values) and otherwise hands the token to `str::parse::<f64>`. Either way the value is the
//! correctly rounded one, bit for bit what `str::parse::<f64>` gives (tested below).

/// The powers of ten that are exact in f64.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Decimal float syntax: optional sign, digits with an optional fraction (at least one digit
/// in all), optional exponent (`e`/`E`, optional sign, at least one digit). Unlike
/// `f64::from_str` this rejects `inf`, `nan` and `infinity`.
pub fn is_decimal(s: &str) -> bool {
    let b = s.as_bytes();
    let digits_from = |mut i: usize| {
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let mut i = usize::from(matches!(b.first(), Some(b'+' | b'-')));
    let int_end = digits_from(i);
    let mut mantissa_digits = int_end - i;
    i = int_end;
    if b.get(i) == Some(&b'.') {
        let frac_end = digits_from(i + 1);
        mantissa_digits += frac_end - (i + 1);
        i = frac_end;
    }
    if mantissa_digits == 0 {
        return false;
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        i += 1;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let exp_end = digits_from(i);
        if exp_end == i {
            return false;
        }
        i = exp_end;
    }
    i == b.len()
}

/// The value of a token that [`is_decimal`] accepts, `None` for any other token. Values beyond
/// f64 come back infinite (`1e400`), as from `str::parse`; callers reject them.
pub fn decimal(b: &[u8]) -> Option<f64> {
    scan(b).and_then(|(x, end)| (end == b.len()).then_some(x))
}

/// The number at the start of `b`, up to the first byte that cannot continue it, and that
/// byte's index: `decimal(&b[..end])`, or `None` if no number starts there.
pub fn scan(b: &[u8]) -> Option<(f64, usize)> {
    let digit = |i: usize| b.get(i).map(|c| c.wrapping_sub(b'0')).filter(|&d| d < 10);
    let mut i = 0;
    let negative = match b.first() {
        Some(b'-') => {
            i = 1;
            true
        }
        Some(b'+') => {
            i = 1;
            false
        }
        _ => false,
    };
    // mantissa digits, integer and fraction; `m` is only used when there are at most 19
    let mut m: u64 = 0;
    let int_start = i;
    while let Some(d) = digit(i) {
        m = m.wrapping_mul(10).wrapping_add(u64::from(d));
        i += 1;
    }
    let mut digits = i - int_start;
    let mut frac_digits = 0;
    if b.get(i) == Some(&b'.') {
        i += 1;
        let frac_start = i;
        while let Some(d) = digit(i) {
            m = m.wrapping_mul(10).wrapping_add(u64::from(d));
            i += 1;
        }
        frac_digits = i - frac_start;
        digits += frac_digits;
    }
    if digits == 0 {
        return None;
    }
    let mut exp: i64 = 0;
    if matches!(b.get(i), Some(b'e' | b'E')) {
        i += 1;
        let exp_negative = match b.get(i) {
            Some(b'-') => {
                i += 1;
                true
            }
            Some(b'+') => {
                i += 1;
                false
            }
            _ => false,
        };
        let exp_start = i;
        while let Some(d) = digit(i) {
            // saturates far beyond any exponent the fast path takes
            exp = (exp * 10 + i64::from(d)).min(1 << 40);
            i += 1;
        }
        if i == exp_start {
            return None;
        }
        if exp_negative {
            exp = -exp;
        }
    }
    let e10 = exp - frac_digits as i64;
    if digits <= 19 && m <= 1 << 53 && (-22..=22).contains(&e10) {
        // Clinger's fast path: m and 10^|e10| are exact, so one IEEE operation rounds correctly.
        let v = m as f64;
        let v = if e10 >= 0 {
            v * POW10[e10 as usize]
        } else {
            v / POW10[(-e10) as usize]
        };
        return Some((if negative { -v } else { v }, i));
    }
    // The grammar is checked, so the token is ASCII and `str::parse` accepts it.
    let x = std::str::from_utf8(&b[..i]).ok()?.parse().ok()?;
    Some((x, i))
}

/// The finite number at the start of `b`, ending at a space, a tab, a `#` or the end of `b`,
/// and the index of that end (how scene and OBJ lines separate their tokens).
pub fn finite_token(b: &[u8]) -> Option<(f64, usize)> {
    let (x, end) = scan(b)?;
    let ends = b.get(end).is_none_or(|&c| matches!(c, b' ' | b'\t' | b'#'));
    (ends && x.is_finite()).then_some((x, end))
}

/// A finite decimal: [`decimal`] without the infinite values.
pub fn finite(b: &[u8]) -> Option<f64> {
    decimal(b).filter(|x| x.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn decimal_syntax() {
        for ok in [
            "0", "1", "-2.5", "+1", ".5", "5.", "1e-3", "1E3", "-.5e+7", "1e-400", "007",
        ] {
            assert!(is_decimal(ok), "{ok}");
            assert!(decimal(ok.as_bytes()).is_some(), "{ok}");
        }
        let bad = [
            "", ".", "+", "-", "e5", "1e", "1e+", "inf", "nan", "infinity", "0x10", "1.2.3", "--1",
            "+-1", "1_000", "1,5", "1e5.0", " 1", "１",
        ];
        for b in bad {
            assert!(!is_decimal(b), "{b}");
            assert_eq!(decimal(b.as_bytes()), None, "{b}");
        }
    }

    #[test]
    fn tokens_end_at_blanks_and_comments() {
        assert_eq!(finite_token(b"1.5 2"), Some((1.5, 3)));
        assert_eq!(finite_token(b"-2e1\tx"), Some((-20.0, 4)));
        assert_eq!(finite_token(b"3#c"), Some((3.0, 1)));
        assert_eq!(finite_token(b"7"), Some((7.0, 1)));
        for bad in [
            &b"1e400 "[..],
            b"1x",
            b"1e ",
            b"1.2.3",
            b"",
            b" 1",
            b"nan",
            b"1\r",
        ] {
            assert_eq!(finite_token(bad), None, "{bad:?}");
        }
    }

    /// Same verdict as the grammar, and when accepted the very bits of `str::parse::<f64>`.
    fn agrees(s: &str) {
        let got = decimal(s.as_bytes());
        assert_eq!(got.is_some(), is_decimal(s), "{s:?}");
        if let Some(x) = got {
            let want: f64 = s.parse().unwrap();
            assert_eq!(x.to_bits(), want.to_bits(), "{s:?}: {x:e} vs {want:e}");
        }
    }

    #[test]
    fn values_are_bit_identical_to_std_on_edge_cases() {
        for s in [
            "-0",
            "+0.0",
            "0e999999999999999999999",
            "1e400",
            "-1e400",
            "1e-400",
            "9007199254740992",
            "9007199254740993",
            "9007199254740993e-22",
            "1234567890123456789",
            "12345678901234567890",
            "0.000000000000000000000000000001",
            "1e22",
            "1e23",
            "123456e-22",
            "123456e-23",
            "4.9e-324",
            "2.4703282292062327e-324",
            "1.7976931348623157e308",
            "1.7976931348623158e308",
            "179769313486231580793728971405303415079934132710037826936173778980444968292764750946649017977587207096330286416692887910946555547851940402630657488671505820681908902000708383676273854845817711531764475730270069855571366959622842914819860834936475292719074168444365510704342711559699508093042880177904174497791.9999999999999999999999999999999999999999999999999999999999999999999999",
            "0.1",
            "0.3",
            "-12.345678",
            "99.999999",
        ] {
            agrees(s);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]

        /// Random strings over the number alphabet: grammar and value agree with the reference.
        #[test]
        fn random_tokens_agree(s in "[-+.eE0-9]{0,12}") {
            agrees(&s);
        }

        /// Well-formed numbers of every size, including long mantissas and large exponents.
        #[test]
        fn random_numbers_agree(
            sign in "[-+]?",
            int in "[0-9]{0,25}",
            frac in "(\\.[0-9]{0,25})?",
            exp in "([eE][-+]?[0-9]{1,3})?",
        ) {
            agrees(&format!("{sign}{int}{frac}{exp}"));
        }

        /// Six-decimal coordinates, as generated scenes and meshes write them.
        #[test]
        fn printed_floats_round_trip(x in -1e6f64..1e6) {
            agrees(&format!("{x:.6}"));
            agrees(&format!("{x}"));
            agrees(&format!("{x:e}"));
        }
    }
}
