//! The fast division (`env::quotient`) against the hardware division, bit for bit.
//!
//! `CartPole::step` divides by `TOTAL_MASS` with `Divisor::divide`: a guess proven per
//! call, or the hardware division when the proof fails. It must equal `a / b` always.

use ppo_rl::env::cartpole::TOTAL_MASS;
use ppo_rl::env::quotient::Divisor;
use ppo_rl::env::seeding::NumpyRng;

fn assert_same(a: f64, b: f64, got: f64) {
    let want = a / b;
    assert!(
        got.to_bits() == want.to_bits(),
        "{a:e} / {b:e}: got {got:e} ({:#018x}), IEEE gives {want:e} ({:#018x})",
        got.to_bits(),
        want.to_bits()
    );
}

/// Asserts `by.divide(a)` is `a / b`; returns whether the guess went unproven.
fn divides_exactly(by: Divisor, a: f64) -> bool {
    assert_same(a, by.value(), by.divide(a));
    by.proven_quotient(a).is_none()
}

/// A double with a random sign, a random 52-bit mantissa and an exponent in `-e..=e`.
fn any_magnitude(rng: &mut NumpyRng, e: i32) -> f64 {
    let exponent = (rng.next_u64() % (2 * e as u64 + 1)) as i32 - e;
    let mantissa = 1.0 + rng.next_f64();
    let sign = if rng.next_u64() & 1 == 0 { 1.0 } else { -1.0 };
    sign * mantissa * 2f64.powi(exponent)
}

#[test]
fn dividing_by_the_total_mass_equals_ieee_division_on_ten_million_numerators() {
    let by = Divisor::new(TOTAL_MASS);
    let mut rng = NumpyRng::from_seed(11);
    let mut unproven = 0;
    for _ in 0..5_000_000 {
        // In the range of CartPole's numerators: the fast path must be the one taken
        // (a failed proof costs a misprediction).
        unproven += usize::from(divides_exactly(by, rng.uniform(-40.0, 40.0)));
        // Of any size, extremes included (those go to the hardware division).
        divides_exactly(by, any_magnitude(&mut rng, 1023));
    }
    assert!(unproven <= 10, "{unproven} of 5,000,000 guesses unproven");
}

#[test]
fn any_divisor_gives_ieee_division() {
    let mut rng = NumpyRng::from_seed(12);
    let mut unproven = 0;
    for _ in 0..1_000_000 {
        let by = Divisor::new(any_magnitude(&mut rng, 400));
        unproven += usize::from(divides_exactly(by, any_magnitude(&mut rng, 400)));
    }
    assert!(unproven <= 10, "{unproven} of 1,000,000 guesses unproven");
}

#[test]
fn the_proof_never_accepts_a_neighbour_of_the_quotient() {
    let mut rng = NumpyRng::from_seed(13);
    let mut accepted = 0;
    for _ in 0..1_000_000 {
        let (a, b) = (any_magnitude(&mut rng, 300), any_magnitude(&mut rng, 300));
        let (q, by) = (a / b, Divisor::new(b));
        assert!(
            !by.proves(a, q.next_up()) && !by.proves(a, q.next_down()),
            "accepted a neighbour of {a:e} / {b:e} = {q:e}"
        );
        accepted += usize::from(by.proves(a, q));
    }
    assert!(accepted >= 999_990, "only {accepted} true quotients proven");
}

#[test]
fn special_values_go_to_the_hardware_division() {
    let by = Divisor::new(TOTAL_MASS);
    let specials = [
        0.0,
        -0.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        f64::MIN_POSITIVE,
        5e-324,
        -1e-310,
        2.0 * TOTAL_MASS, // the quotient 2 is a power of two
        -0.5 * TOTAL_MASS,
    ];
    for a in specials {
        let got = by.divide(a);
        if a.is_nan() {
            assert!(got.is_nan());
        } else {
            assert_same(a, TOTAL_MASS, got);
        }
        assert_eq!(by.proven_quotient(a), None, "{a:e} should not be proven");
    }
    for q in [f64::NAN, f64::INFINITY, 0.0] {
        assert!(!by.proves(1.0, q));
    }
    // The largest doubles are proven where the proof's bounds allow, and exact either way.
    for a in [f64::MAX, -f64::MAX] {
        assert_same(a, TOTAL_MASS, by.divide(a));
    }
}

#[test]
fn special_divisors_go_to_the_hardware_division() {
    for b in [
        0.0,
        -0.0,
        1e-310,
        f64::INFINITY,
        f64::NAN,
        f64::MAX,
        f64::MIN_POSITIVE,
    ] {
        let by = Divisor::new(b);
        for a in [1.0, -3.5, 1e300, 1e-300, 0.0] {
            let (got, want) = (by.divide(a), a / b);
            assert!(
                got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                "{a:e} / {b:e}: got {got:e}, IEEE gives {want:e}"
            );
        }
    }
    for b in [0.0, 1e-310, f64::INFINITY, f64::NAN] {
        assert_eq!(Divisor::new(b).proven_quotient(1.0), None, "b = {b:e}");
    }
}
