//! Numbers as C's `printf("%.Ng")` writes them, exactly: shortest digits by
//! 128-bit integer arithmetic where it fits, the standard library's exact
//! formatting elsewhere. The OBJ writer and the points files use it.

use std::fmt;

/// The most significant digits [`format_g`] produces.
const MAX_SIGNIFICANT: usize = 40;

/// Room for one formatted number (at most 48 bytes with 40 digits).
const NUMBER_CAPACITY: usize = 64;

/// A fixed-size byte buffer, so that formatting a number allocates nothing.
pub(crate) struct NumberBuf {
    bytes: [u8; NUMBER_CAPACITY],
    len: usize,
}

impl NumberBuf {
    fn new() -> Self {
        NumberBuf {
            bytes: [0; NUMBER_CAPACITY],
            len: 0,
        }
    }

    fn push(&mut self, b: u8) {
        self.bytes[self.len] = b;
        self.len += 1;
    }

    fn extend(&mut self, s: &[u8]) {
        self.bytes[self.len..self.len + s.len()].copy_from_slice(s);
        self.len += s.len();
    }

    fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
}

impl fmt::Write for NumberBuf {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        if self.len + s.len() > NUMBER_CAPACITY {
            return Err(fmt::Error);
        }
        self.extend(s.as_bytes());
        Ok(())
    }
}

/// Where [`g_format`] puts its bytes.
pub(crate) trait ByteSink {
    fn push(&mut self, b: u8);
    fn extend(&mut self, s: &[u8]);
}

impl ByteSink for NumberBuf {
    fn push(&mut self, b: u8) {
        NumberBuf::push(self, b);
    }

    fn extend(&mut self, s: &[u8]) {
        NumberBuf::extend(self, s);
    }
}

impl ByteSink for Vec<u8> {
    fn push(&mut self, b: u8) {
        Vec::push(self, b);
    }

    fn extend(&mut self, s: &[u8]) {
        self.extend_from_slice(s);
    }
}

/// `10^k` for every `k` whose power fits in 128 bits.
const POW10: [u128; 39] = {
    let mut t = [1u128; 39];
    let mut k = 1;
    while k < 39 {
        t[k] = t[k - 1] * 10;
        k += 1;
    }
    t
};

/// The `p` significant decimal digits of `x` (finite, positive) rounded to
/// nearest with ties to even, as an integer of exactly `p` digits, and the
/// decimal exponent of the first digit: `x ≈ digits × 10^(exp + 1 - p)`.
///
/// Exact integer arithmetic: with `x = m × 2^e`, the digits are
/// `m × 2^e × 10^s` rounded for the scale `s` that leaves `p` digits, computed
/// in 128 bits. `None` where that does not fit (magnitudes beyond about
/// `1e±21` for 17 digits) or for more than 19 digits: the caller then uses
/// the standard library's (slower) exact formatting.
fn exact_digits(x: f64, p: u32) -> Option<(u64, i32)> {
    if !(1..=19).contains(&p) {
        return None;
    }
    let bits = x.to_bits();
    let (biased, fraction) = ((bits >> 52) as i32 & 0x7ff, bits & ((1 << 52) - 1));
    let (m, e) = match biased {
        0 => (fraction, -1074),
        _ => (fraction | 1 << 52, biased - 1075),
    };
    if m == 0 {
        return None;
    }
    // 2^b <= x < 2^(b + 1), so the decimal exponent is floor(b log10 2) or
    // one more (78913 / 2^18 is log10 2 rounded down, exact enough here).
    let b = e + 63 - m.leading_zeros() as i32;
    let mut exp = (b * 78913) >> 18;
    let limit = POW10[p as usize] as u64;
    for _ in 0..3 {
        let n = scaled_round(m, e, p as i32 - 1 - exp)?;
        if n >= limit {
            exp += 1;
        } else if n < limit / 10 {
            exp -= 1;
        } else {
            return Some((n, exp));
        }
    }
    None
}

/// `m × 2^e × 10^s` rounded to the nearest integer, ties to even, when the
/// computation fits in 128 bits and the result in 64.
fn scaled_round(m: u64, e: i32, s: i32) -> Option<u64> {
    let ten = |k: i32| POW10.get(k.unsigned_abs() as usize).copied();
    // Numerator m × 2^max(e, 0) × 10^max(s, 0).
    let mut num = u128::from(m);
    if s > 0 {
        num = num.checked_mul(ten(s)?)?;
    }
    if e > 0 {
        if num.leading_zeros() <= e as u32 {
            return None;
        }
        num <<= e;
    }
    let (q, round_up) = if s >= 0 {
        // Denominator 2^max(-e, 0): a shift.
        let shift = (-e).max(0) as u32;
        if shift == 0 {
            (num, false)
        } else if shift >= 127 {
            return None;
        } else {
            let q = num >> shift;
            let r = num & ((1u128 << shift) - 1);
            let half = 1u128 << (shift - 1);
            (q, r > half || (r == half && q & 1 == 1))
        }
    } else {
        // Denominator 2^max(-e, 0) × 10^-s.
        let mut den = ten(s)?;
        if e < 0 {
            if den.leading_zeros() <= (-e) as u32 {
                return None;
            }
            den <<= -e;
        }
        let (q, r) = (num / den, num % den);
        let rest = den - r;
        (q, r > rest || (r == rest && q & 1 == 1))
    };
    u64::try_from(q + u128::from(round_up)).ok()
}

/// Appends `x` formatted like C's `printf("%.*g", significant, x)` (glibc).
pub(crate) fn g_format(x: f64, significant: usize, out: &mut impl ByteSink) {
    use fmt::Write as _;
    let p = significant.clamp(1, MAX_SIGNIFICANT);
    if x.is_sign_negative() {
        out.push(b'-');
    }
    if x.is_nan() {
        out.extend(b"nan");
        return;
    }
    if x.is_infinite() {
        out.extend(b"inf");
        return;
    }
    if x == 0.0 {
        out.push(b'0');
        return;
    }
    // The p significant digits and the exponent X of `%.{p-1}e`: from exact
    // integer arithmetic where it fits, else from Rust's `{:.N e}`, which is
    // correctly rounded too (ties to even on exact ties, as glibc).
    let mut digits = NumberBuf::new();
    let exp = if let Some((n, exp)) = exact_digits(x.abs(), p as u32) {
        let mut text = itoa::Buffer::new();
        digits.extend(text.format(n).as_bytes());
        exp
    } else {
        let mut sci = NumberBuf::new();
        write!(sci, "{:.*e}", p - 1, x.abs()).expect("a formatted number fits in 64 bytes");
        let sci = sci.as_bytes();
        let e = sci
            .iter()
            .position(|&c| c == b'e')
            .expect("exponential format has an 'e'");
        digits.push(sci[0]);
        if e > 1 {
            digits.extend(&sci[2..e]);
        }
        let (exp_negative, exp_digits) = match sci[e + 1] {
            b'-' => (true, &sci[e + 2..]),
            _ => (false, &sci[e + 1..]),
        };
        let magnitude = exp_digits
            .iter()
            .fold(0i32, |acc, &c| acc * 10 + i32::from(c - b'0'));
        if exp_negative { -magnitude } else { magnitude }
    };
    let digits = digits.as_bytes();
    let (first, rest) = (digits[0], &digits[1..]);
    // Without '#', %g removes trailing zeros of the fraction (and a bare '.').
    let mut kept = rest.len();
    while kept > 0 && rest[kept - 1] == b'0' {
        kept -= 1;
    }
    if exp < -4 || exp >= p as i32 {
        out.push(first);
        if kept > 0 {
            out.push(b'.');
            out.extend(&rest[..kept]);
        }
        out.push(b'e');
        out.push(if exp < 0 { b'-' } else { b'+' });
        let magnitude = exp.unsigned_abs();
        if magnitude < 10 {
            out.push(b'0');
        }
        let mut buf = itoa::Buffer::new();
        out.extend(buf.format(magnitude).as_bytes());
    } else if exp >= 0 {
        // 0 <= exp < p: the integer part has exp + 1 <= p digits.
        let int_rest = exp as usize;
        out.push(first);
        out.extend(&rest[..int_rest]);
        if kept > int_rest {
            out.push(b'.');
            out.extend(&rest[int_rest..kept]);
        }
    } else {
        out.extend(b"0.");
        for _ in 0..(-exp - 1) {
            out.push(b'0');
        }
        out.push(first);
        out.extend(&rest[..kept]);
    }
}

/// Appends `x` formatted exactly like C's `printf("%.*g", significant, x)`.
///
/// `significant` is clamped to `1..=40` (C treats 0 as 1). Scientific notation
/// is used when the decimal exponent is below -4 or at least `significant`;
/// trailing zeros and a trailing `.` are removed; the exponent has a sign and at
/// least two digits; `-0.0` gives `-0`, and non-finite values give `inf`,
/// `-inf` and `nan` as glibc does.
///
/// ```
/// use subdiv::io::format_g;
/// let mut s = String::new();
/// format_g(0.1, 17, &mut s);
/// s.push(' ');
/// format_g(1e20, 17, &mut s);
/// s.push(' ');
/// format_g(0.1f32 as f64, 9, &mut s);
/// assert_eq!(s, "0.10000000000000001 1e+20 0.100000001");
/// ```
pub fn format_g(x: f64, significant: usize, out: &mut String) {
    let mut buf = NumberBuf::new();
    g_format(x, significant, &mut buf);
    out.push_str(std::str::from_utf8(buf.as_bytes()).expect("formatted numbers are ASCII"));
}

pub(crate) fn push_u64(n: u64, out: &mut Vec<u8>) {
    let mut buf = itoa::Buffer::new();
    out.extend_from_slice(buf.format(n).as_bytes());
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g(x: f64, p: usize) -> String {
        let mut s = String::new();
        format_g(x, p, &mut s);
        s
    }

    #[test]
    fn format_g_matches_printf() {
        // Expectations from C/Python `'%.17g' % x` and `'%.9g' % x`.
        let cases: &[(f64, usize, &str)] = &[
            (0.1, 17, "0.10000000000000001"),
            (1.0, 17, "1"),
            (1e-5, 17, "1.0000000000000001e-05"),
            (123456.789, 17, "123456.789"),
            (1e20, 17, "1e+20"),
            (-0.0, 17, "-0"),
            (0.0, 17, "0"),
            (0.5, 17, "0.5"),
            (2.0 / 3.0, 17, "0.66666666666666663"),
            (1e16, 17, "10000000000000000"),
            (1e17, 17, "1e+17"),
            (100.0, 17, "100"),
            (1e-4, 17, "0.0001"),
            (9.999_999_999_999_999e-5, 17, "9.9999999999999991e-05"),
            (9.999_999_999_999_999e-5, 3, "0.0001"),
            (-1.5e-300, 17, "-1.5000000000000001e-300"),
            (5e-324, 17, "4.9406564584124654e-324"),
            (f64::MAX, 17, "1.7976931348623157e+308"),
            (123456789.0, 3, "1.23e+08"),
            (100.0, 1, "1e+02"),
            (0.125, 2, "0.12"),
            (2.5, 1, "2"),
            (0.3125, 3, "0.312"),
            (f64::INFINITY, 17, "inf"),
            (f64::NEG_INFINITY, 17, "-inf"),
            (f64::NAN, 17, "nan"),
            (0.1f32 as f64, 9, "0.100000001"),
            (1e-5f32 as f64, 9, "9.99999975e-06"),
            (123456789.0f32 as f64, 9, "123456792"),
            (f32::MAX as f64, 9, "3.40282347e+38"),
        ];
        for &(x, p, want) in cases {
            assert_eq!(g(x, p), want, "{x:e} with {p} digits");
        }
        assert_eq!(g(0.5, 0), "0.5", "0 digits behaves as 1");
    }

    /// The digits and exponent of `{:.(p-1)e}`, the standard library's
    /// correctly rounded formatting (the fallback of `exact_digits`).
    fn std_digits(x: f64, p: u32) -> (u64, i32) {
        let s = format!("{:.*e}", p as usize - 1, x);
        let (mantissa, exp) = s.split_once('e').unwrap();
        (
            mantissa.replace('.', "").parse().unwrap(),
            exp.parse().unwrap(),
        )
    }

    #[test]
    fn exact_digits_equal_the_standard_library() {
        // A xorshift stream of bit patterns: every exponent, and values in
        // the ranges coordinates take.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let (mut fast, mut total) = (0, 0);
        let mut check = |x: f64, p: u32| {
            if !x.is_finite() || x <= 0.0 {
                return;
            }
            total += 1;
            if let Some(got) = exact_digits(x, p) {
                fast += 1;
                assert_eq!(got, std_digits(x, p), "{x:e} with {p} digits");
            }
        };
        for _ in 0..200_000 {
            let bits = next();
            let p = (bits % 19) as u32 + 1;
            check(f64::from_bits(bits >> 1), p);
            let unit = (bits >> 11) as f64 / (1u64 << 53) as f64;
            check(unit * 200.0, 17);
            check(unit * 1e-3, 17);
            check(f64::from(unit as f32 * 50.0), 9);
        }
        // Exact ties at every precision: (2n + 1) / 2 × 10^t, rounded to
        // even by both.
        for p in 1..=17u32 {
            for t in -3..=3 {
                for n in [1u64, 2, 12, 125, 9, 99_999, 1 << 40] {
                    let n = n % 10u64.pow(p).max(1);
                    let x = (2 * n + 1) as f64 / 2.0 * 10f64.powi(t);
                    check(x, p);
                    check(x.next_up(), p);
                    check(x.next_down(), p);
                }
            }
        }
        // Powers of ten and their neighbours (the exponent's estimate).
        for k in -30..=30 {
            let x = 10f64.powi(k);
            for p in [1, 9, 15, 16, 17] {
                check(x, p);
                check(x.next_up(), p);
                check(x.next_down(), p);
                check(x * 9.999_999_999_999_999, p);
            }
        }
        assert!(fast * 2 > total, "the fast path took {fast} of {total}");
    }

    #[test]
    fn format_g_round_trips_every_f64_it_writes() {
        let mut x = 1.0e-310_f64;
        while x < 1.0e300 {
            for v in [x, -x, x * 1.000_000_1, x / 3.0] {
                let s = g(v, 17);
                assert_eq!(s.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{s}");
            }
            x *= 7.3;
        }
    }
}
