//! The inline `sin`/`cos` (a copy of glibc's computation) against libm, bit for bit.
//!
//! `ppo_rl::env::sincos::sin_cos` must return exactly libm's `sin(x)` and `cos(x)`,
//! which are what Gymnasium's CartPole gets from Python's `math.sin`/`math.cos`.

use ppo_rl::env::seeding::NumpyRng;
use ppo_rl::env::sincos::{
    Backend, LibmReason, backend, libm_sin_cos, self_check_angles, sin_cos, sin_cos_slice,
};

/// Seeded angles: most in CartPole's range, the rest across the inline range and beyond.
fn angles(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = NumpyRng::from_seed(seed);
    (0..n)
        .map(|i| {
            let span = [0.25, 0.126, 0.9, 1e-6][i % 4];
            rng.uniform(-span, span)
        })
        .collect()
}

fn assert_same(x: f64, got: (f64, f64)) {
    let want = libm_sin_cos(x);
    assert!(
        got.0.to_bits() == want.0.to_bits() && got.1.to_bits() == want.1.to_bits(),
        "x = {x:e} ({:#018x}): got ({:e}, {:e}), libm gives ({:e}, {:e})",
        x.to_bits(),
        got.0,
        got.1,
        want.0,
        want.1
    );
}

#[test]
fn the_inline_path_is_on_where_it_copies_glibc() {
    let expected_inline = cfg!(all(
        target_arch = "x86_64",
        target_os = "linux",
        target_env = "gnu"
    )) && std::env::var_os("PPO_TUTOR_LIBM_SINCOS").is_none();
    #[cfg(target_arch = "x86_64")]
    let expected_inline = expected_inline
        && std::is_x86_feature_detected!("fma")
        && std::is_x86_feature_detected!("avx2");
    match backend() {
        Backend::Inline => assert!(expected_inline, "inline chosen where it should not be"),
        Backend::Libm(LibmReason::SelfCheckFailed { angle }) => {
            panic!("the inline sin/cos differs from libm at {angle:e}")
        }
        Backend::Libm(why) => assert!(!expected_inline, "libm chosen: {why}"),
    }
}

#[test]
fn equals_libm_on_ten_million_angles() {
    for x in angles(10_000_000, 7) {
        assert_same(x, sin_cos(x));
    }
}

#[test]
fn equals_libm_on_the_self_check_angles_and_special_values() {
    let specials = [
        0.0,
        -0.0,
        f64::MIN_POSITIVE,
        1e-300,
        f64::from_bits(0x3e40_0000_0000_0000),
        f64::from_bits(0x3e3f_ffff_ffff_ffff),
        0.855_468_75,
        0.855_469,
        1.0,
        -2.5,
        1e6,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for x in self_check_angles().into_iter().chain(specials) {
        assert_same(x, sin_cos(x));
    }
    let (s, c) = sin_cos(f64::NAN);
    assert!(s.is_nan() && c.is_nan());
}

#[test]
fn the_slice_version_equals_the_scalar_one() {
    let mut x = angles(1003, 11);
    x.extend([0.0, -0.0, 1e-12, 2.0, -0.9, 0.855_469, f64::INFINITY]);
    let (mut s, mut c) = (vec![0.0; x.len()], vec![0.0; x.len()]);
    sin_cos_slice(&x, &mut s, &mut c);
    for (i, &v) in x.iter().enumerate() {
        if v.is_finite() {
            assert_same(v, (s[i], c[i]));
        } else {
            assert!(s[i].is_nan() && c[i].is_nan());
        }
    }
}
