//! IEEE division by a divisor known in advance, without waiting for the divider.
//!
//! CartPole's step has two divisions in a row on its critical path: each step's `θ̇`
//! needs the previous step's `θ̇` through `temp = (...) / TOTAL_MASS` and then
//! `thetaacc = (...) / denominator`. A hardware division takes about 13 cycles; a multiply
//! and a fused multiply-add take 7. Python rounds every division to nearest, so a faster
//! division must give the same bits, on every input.
//!
//! [`Divisor::divide`] does it in two steps:
//! 1. **A guess.** With the reciprocal in two parts, `hi + lo ≈ 1/b` (both doubles),
//!    `q = a·hi + a·lo` (one multiply, one FMA) is the correctly rounded `a/b` except for
//!    quotients extremely close to a rounding boundary.
//! 2. **A proof, per call.** [`Divisor::proves`] proves `q == a / b` from the exact
//!    remainder `a − q·b` (one FMA). When the proof fails, the hardware division is used:
//!    for zeros, infinities, NaNs, exact powers of two and extreme magnitudes, and for
//!    quotients within about 2^-50 of their spacing from a rounding boundary (none of the
//!    ten million in `tests/quotient.rs`).
//!
//! `CartPole::step` uses it for `/ TOTAL_MASS`. The step's other division on the critical
//! path divides by a number known only about 40 cycles ahead, too late to prepare its
//! reciprocal, so it stays in hardware.
//!
//! The CPU does not wait for the proof: the next multiply starts from the guess, and the
//! proof only decides a branch that is predicted taken. So the division costs the guess's
//! 7 cycles on the critical path instead of 13.
//!
//! Correctness does not depend on `hi` and `lo` being accurate (a poor guess only fails
//! the proof more often). It does need `mul_add` to be a fused multiply-add, which Rust
//! guarantees on every platform; it is fast only where the CPU has FMA, so the portable
//! [`Math`](super::sincos::Math) divides in hardware instead.

/// A divisor with its reciprocal split in two doubles, `hi + lo ≈ 1/b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Divisor {
    value: f64,
    hi: f64,
    lo: f64,
    /// The quotient exponents (biased) for which [`Divisor::proves`] can decide:
    /// `exponent - min_exponent <= exponent_span`, as unsigned numbers.
    min_exponent: u64,
    exponent_span: u64,
}

impl Divisor {
    /// `b`, with `hi = 1/b` rounded and `lo` the rounded rest of `1/b − hi`.
    #[must_use]
    pub const fn new(b: f64) -> Self {
        let hi = 1.0 / b;
        let b_exponent = ((b.to_bits() >> 52) & 0x7ff) as i64;
        if b_exponent == 0 || b_exponent == 0x7ff {
            // Zero, subnormal, infinite or NaN: never proven (no exponent reaches 0x800).
            return Self {
                value: b,
                hi,
                lo: 0.0,
                min_exponent: 0x800,
                exponent_span: 0,
            };
        }
        // 1 − b·hi exactly: `p + e == b·hi` (Dekker's product), and `1 − p` is exact
        // because p is within a rounding of 1 (Sterbenz).
        let (p, e) = two_product(b, hi);
        let rest = (1.0 - p) - e;
        // For a quotient of biased exponent E, `h = |b|·2^(E − 1076)` (see `proves`).
        // With `|b|` in [2^eb, 2^(eb+1)), `h` is a normal double, far from both ends
        // of the range, for E in [77 − eb, 2075 − eb]; E must also be in [54, 2046].
        let eb = b_exponent - 1023;
        let (min_exponent, max_exponent) = (max(77 - eb, 54), min(2075 - eb, 0x7fe));
        Self {
            value: b,
            hi,
            lo: rest / b,
            min_exponent: min_exponent as u64,
            exponent_span: max_exponent.saturating_sub(min_exponent) as u64,
        }
    }

    /// The divisor `b`.
    #[must_use]
    pub const fn value(self) -> f64 {
        self.value
    }

    /// `a / b` when the guess `a·hi + a·lo` is proven to be it; `None` otherwise.
    #[must_use]
    #[inline(always)]
    pub fn proven_quotient(self, a: f64) -> Option<f64> {
        let q = a.mul_add(self.hi, a * self.lo);
        self.proves(a, q).then_some(q)
    }

    /// `a / b`, bit for bit: the proven guess, or the hardware division.
    #[must_use]
    #[inline(always)]
    pub fn divide(self, a: f64) -> f64 {
        match self.proven_quotient(a) {
            Some(q) => q,
            None => divide_in_hardware(a, self.value),
        }
    }

    /// Whether `q` is provably `a / b` rounded to nearest (`false` means "not proven").
    ///
    /// Let `x = a/b` exactly and `u` the spacing of doubles at `q`. When `q` is normal and
    /// not a power of two, its neighbours are `q ± u`, so `q` is the rounding of `x` when
    /// `|x − q| < u/2`. (`x` is never exactly halfway: a midpoint has p+1 significant
    /// bits, and a midpoint times `b` has more than p.) That is `|a − q·b| < h` with
    /// `h = |b|·u/2`.
    /// - `h` is exact: `u/2` is a power of two, and the exponent window set in
    ///   [`Divisor::new`] keeps `h` a normal double between `2^-999` and `2^1000`.
    /// - `r = fma(−q, b, a)` is `a − q·b` rounded once. If that is normal,
    ///   `|a − q·b| <= |r|·(1 + 2^-52)`, which the rounded `|r|·(1 + 2^-50)` exceeds, so
    ///   `|r|·(1 + 2^-50) < h` proves the bound. If `a − q·b` is subnormal or zero it is
    ///   below `2^-1022`, far below `h`.
    ///
    /// NaNs, infinities, zeros, subnormals and powers of two fail one of the conditions.
    #[must_use]
    #[inline(always)]
    pub fn proves(self, a: f64, q: f64) -> bool {
        const MANTISSA: u64 = (1 << 52) - 1;
        let bits = q.to_bits();
        let exponent = (bits >> 52) & 0x7ff;
        // u/2 = 2^(exponent − 1023 − 53).
        let half_spacing = f64::from_bits(exponent.wrapping_sub(53) << 52);
        let h = self.value.abs() * half_spacing;
        let r = (-q).mul_add(self.value, a);
        (exponent.wrapping_sub(self.min_exponent) <= self.exponent_span)
            & (bits & MANTISSA != 0)
            & (r.abs() * (1.0 + pow2(-50)) < h)
    }
}

/// The rare case, kept out of line so that the common one is a predicted branch and not
/// a select (which would wait for the division anyway).
#[cold]
#[inline(never)]
fn divide_in_hardware(a: f64, b: f64) -> f64 {
    a / b
}

/// `2^k` for `-1022 <= k <= 1023`.
const fn pow2(k: i64) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

const fn max(a: i64, b: i64) -> i64 {
    if a > b { a } else { b }
}

const fn min(a: i64, b: i64) -> i64 {
    if a < b { a } else { b }
}

/// `(p, e)` with `p = a·b` rounded and `p + e == a·b` exactly (Dekker, no FMA needed, so
/// it runs in a `const fn`). Assumes no overflow or underflow.
const fn two_product(a: f64, b: f64) -> (f64, f64) {
    let (a1, a2) = split(a);
    let (b1, b2) = split(b);
    let p = a * b;
    let e = ((a1 * b1 - p) + a1 * b2 + a2 * b1) + a2 * b2;
    (p, e)
}

/// Veltkamp's split of `x` into two halves of 26 bits each, `x == hi + lo`.
const fn split(x: f64) -> (f64, f64) {
    let c = 134_217_729.0 * x; // 2^27 + 1
    let hi = c - (c - x);
    (hi, x - hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reciprocal_parts_are_hi_rounded_and_a_small_rest() {
        let d = Divisor::new(1.1);
        assert_eq!(d.hi, 1.0 / 1.1);
        // hi + lo is 1/1.1 to well beyond double precision: b·(hi + lo) − 1 ≈ 0.
        let residual = 1.1f64.mul_add(d.hi, -1.0) + 1.1 * d.lo;
        assert!(residual.abs() < pow2(-100), "{residual:e}");
        assert!(d.lo != 0.0 && d.lo.abs() < pow2(-53));
    }

    #[test]
    fn two_product_is_exact() {
        let (p, e) = two_product(1.1, 1.0 / 1.1);
        assert_eq!(e, 1.1f64.mul_add(1.0 / 1.1, -p));
    }
}
