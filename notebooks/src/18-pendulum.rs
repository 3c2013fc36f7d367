//! Recipe for notebooks/18-pendulum.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::{Session, Snapshot};
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::PpoContinuousConfig;
fn mean(r: &[f64]) -> f64 {
    r.iter().sum::<f64>() / r.len() as f64
}
// The book's PPOContinuous on Pendulum-v1 with its defaults, seed 0, one episode so far.
let config: PpoContinuousConfig = PpoContinuousConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 1)?;
println!("episode 1: return {:.1}", snap.returns[0]);

// %% step: The pendulum's physics
// The native Pendulum-v1, stepped by hand with no torque from reset(seed=0): gravity alone.
use ppo_engine::env::Pendulum;
let mut env = Pendulum::new();
let first: [f32; 3] = env.reset(Some(0));
println!("reset(seed=0): (cos θ, sin θ, θ̇) = {first:?}");
for step in 1..=5 {
    let s = env.step(0.0)?;
    println!("step {step}: obs {:?}, reward {:.4}", s.obs, s.reward);
}
println!("with no torque the rod falls away from upright: θ̇ grows and the cost with it");

// %% step: The cost, and why the rod must swing up
use ppo_engine::env::pendulum::cost;
use std::f64::consts::PI;
println!("hanging, still:   cost {:.4}", cost(PI, 0.0, 0.0));
println!("worst:            cost {:.4}", cost(PI, 8.0, 2.0));
println!("full torque: 6 rad/s² against gravity's 15·sin θ; the motor holds the rod within {:.1}° of upright", (0.4_f64).asin().to_degrees());

// %% step: The training run and its return curve
// 300 episodes here (the book trains 2000: `ppo-tutor train --env Pendulum-v1` in a terminal).
let mut session = Session::new(config.clone(), 0)?;
let mut maps: Vec<(usize, Snapshot)> = Vec::new();
for episode in 1..=300 {
    let s = session.next_episode()?.expect("300 of 2000 episodes");
    if [1, 100, 300].contains(&episode) {
        maps.push((episode, s.clone()));
    }
}
let snap: Snapshot = session.into_snapshot();
println!("mean return of episodes 1-20: {:.1}; of 281-300: {:.1}", mean(&snap.returns[..20]), mean(&snap.returns[280..]));

// %% step: The mean torque across the state space
// μ at the centre of the grid (upright, at rest) and the largest |μ| on the grid, as training goes on:
for (episode, s) in &maps {
    let map = &s.pendulum_update().expect("a Pendulum snapshot has a map").policy_map;
    let biggest = map.mu.iter().fold(0.0_f32, |m, v| m.max(v.abs()));
    println!("after episode {episode:>3}: μ(upright, at rest) = {:+.4}, max |μ| on the grid = {biggest:.4}", map.mu[40]);
}
// The map after episode 300 as a picture (the table below holds the same numbers):
ppo_engine::notebook::policy_map_svg(&snap.pendulum_update().expect("a Pendulum snapshot has a map").policy_map)

// %% step: The spread σ as training goes on
for (episode, s) in &maps {
    let map = &s.pendulum_update().expect("a Pendulum snapshot has a map").policy_map;
    let mean_std = map.std.iter().sum::<f32>() / map.std.len() as f32;
    println!("after episode {episode:>3}: mean σ over the grid = {mean_std:.4}");
}
println!("(the book's full 2000 episodes shrink it: `ppo-tutor train --env Pendulum-v1` in a terminal)");
