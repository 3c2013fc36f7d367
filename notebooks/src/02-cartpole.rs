//! Recipe for notebooks/02-cartpole.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::env::{CartPole, EnvId};
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::{cartpole_svg, snapshot};
use ppo_engine::ppo::PpoConfig;
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;

// %% step: The state: four numbers
// Gymnasium's env.reset(seed=0), reproduced bit for bit:
let mut env = CartPole::new(EnvId::CartPoleV1);
let obs: [f32; 4] = env.reset(Some(0));
println!("[x, x_dot, theta, theta_dot] = {obs:?}");

// %%
cartpole_svg(&obs.map(f64::from))

// %% step: Two actions and the physics step
// Push right (action 1) five times and watch the cart speed up and the pole tip back.
for _ in 0..5 {
    let step = env.step(1)?;
    println!("{:?} reward {}", step.obs, step.reward);
}

// %% step: Reset and seeding
// The same seed gives the same start; no seed continues the generator, as in Gymnasium.
let a = env.reset(Some(42));
let b = env.reset(None);
let c = env.reset(Some(42));
println!("seed 42: {a:?}\nnext:    {b:?}\nseed 42: {c:?}");
assert_eq!(a, c);

// %% step: One reward per step, the last one too
let mut env = CartPole::new(EnvId::CartPoleV1);
env.reset(Some(0));
let mut total = 0.0;
loop {
    let step = env.step(0)?; // always push left: the pole soon falls
    total += step.reward;
    if step.terminated || step.truncated {
        println!("terminated = {}, return = {total}", step.terminated);
        break;
    }
}

// %% step: Termination and truncation
use ppo_engine::env::cartpole::{THETA_THRESHOLD_RADIANS, X_THRESHOLD};
println!("terminated: |x| > {X_THRESHOLD} or |θ| > {THETA_THRESHOLD_RADIANS:.4} rad (12°)");
println!("truncated: the time limit, {} steps on CartPole-v1", EnvId::CartPoleV1.max_episode_steps());

// %%
// The opposite pitfall: `done = terminated` alone. This hand-made policy pushes the cart
// toward where the pole is falling, which keeps it up; a loop that waits for `terminated`
// runs past the time limit (stopped here at 2000 steps).
fn balance(obs: [f32; 4]) -> usize {
    usize::from(0.05 * obs[0] + 0.1 * obs[1] + obs[2] + 0.5 * obs[3] > 0.0)
}
let mut env = CartPole::new(EnvId::CartPoleV1);
let mut obs = env.reset(Some(0));
let mut episode_return = 0.0;
let mut truncated_at: Option<usize> = None;
for t in 1..=2000 {
    let step = env.step(balance(obs))?;
    episode_return += step.reward;
    obs = step.obs;
    if step.truncated && truncated_at.is_none() {
        truncated_at = Some(t);
    }
    if step.terminated {
        break;
    }
}
println!("truncated first at step {truncated_at:?}; the loop ran on to a return of {episode_return}");
assert!(episode_return > 500.0);

// %% step: CartPole-v0 and CartPole-v1
for id in EnvId::ALL {
    println!("{}: truncated at {} steps", id.as_str(), id.max_episode_steps());
}
