//! Steps per second of the native CartPole: one environment, and the vector env.
//!
//! Compare with `shared/peer/gym_speed.py` (Gymnasium's `gym.make`, the bare env and
//! the numpy `CartPoleVectorEnv(256)`) in the same sitting; docs/measurements.md has the table.
//! Run: `cargo bench --bench cartpole`.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use ppo_tutor::env::seeding::NumpyRng;
use ppo_tutor::env::{CartPole, CartPoleConfig, CartPoleVec, EnvId, sincos};

const STEPS: usize = 10_000;

fn single(c: &mut Criterion) {
    let mut group = c.benchmark_group("cartpole");
    group.throughput(Throughput::Elements(STEPS as u64));
    let mut rng = NumpyRng::from_seed(0);
    let actions: Vec<usize> = (0..STEPS).map(|_| (rng.next_u64() & 1) as usize).collect();
    group.bench_function("single_env_steps", |b| {
        let mut env = CartPole::new(EnvId::CartPoleV1);
        env.reset(Some(0));
        b.iter(|| {
            for &a in &actions {
                let Ok(step) = env.step(black_box(a)) else {
                    return;
                };
                if step.terminated || step.truncated {
                    env.reset(None);
                }
            }
        });
    });
    group.finish();
}

fn vector(c: &mut Criterion) {
    let n = 256;
    let iters = STEPS / n * 10;
    let mut group = c.benchmark_group("cartpole");
    group.throughput(Throughput::Elements((iters * n) as u64));
    let mut rng = NumpyRng::from_seed(1);
    let actions: Vec<Vec<usize>> = (0..iters)
        .map(|_| (0..n).map(|_| (rng.next_u64() & 1) as usize).collect())
        .collect();
    group.bench_function("vector256_env_steps", |b| {
        let mut envs = CartPoleVec::new(CartPoleConfig::new(EnvId::CartPoleV1), n, 0);
        b.iter(|| {
            for a in &actions {
                let _ = black_box(envs.step(a));
            }
        });
    });
    group.finish();
}

/// The inline copy of glibc's sin/cos against libm's, per angle and over a slice.
fn sincos(c: &mut Criterion) {
    eprintln!("sin/cos backend: {}", sincos::backend());
    let n = 1024;
    let mut rng = NumpyRng::from_seed(2);
    let angles: Vec<f64> = (0..n).map(|_| rng.uniform(-0.21, 0.21)).collect();
    let mut group = c.benchmark_group("sincos");
    group.throughput(Throughput::Elements(n as u64));
    group.bench_function("libm_per_angle", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &x in &angles {
                let (s, c) = sincos::libm_sin_cos(black_box(x));
                acc += s + c;
            }
            acc
        });
    });
    group.bench_function("inline_per_angle", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &x in &angles {
                let (s, c) = sincos::sin_cos(black_box(x));
                acc += s + c;
            }
            acc
        });
    });
    let (mut sin, mut cos) = (vec![0.0; n], vec![0.0; n]);
    group.bench_function("inline_slice", |b| {
        b.iter(|| sincos::sin_cos_slice(black_box(&angles), &mut sin, &mut cos));
    });
    group.finish();
}

criterion_group!(benches, single, vector, sincos);
criterion_main!(benches);
