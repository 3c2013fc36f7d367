//! Recipe for notebooks/01-what-is-ppo.ipynb: code cells between `// %%` lines; the
//! markdown, the live-value cells and the exercise come from lessons/01-what-is-ppo.
//! Regenerate: cargo run --features notebook-runner -- dev notebooks 01

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{EpochTrace, PpoConfig, UpdateTrace};
// The seed's settings and seed 0; 100 episodes of training (about a second).
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 100)?;
let trace: UpdateTrace = snap.cartpole_update().expect("100 episodes were trained").trace.clone();
println!("episode {} lasted {} steps", snap.episodes, trace.rewards.len());

// %% step: A policy that learns from its own play
// For comparison, a policy written by hand on the native CartPole-v1:
// push the cart towards the side the pole leans to.
use ppo_engine::env::{CartPole, EnvId};
let mut env = CartPole::new(EnvId::CartPoleV1);
let mut obs: [f32; 4] = env.reset(Some(0));
let mut steps: usize = 0;
loop {
    let action = if obs[2] > 0.0 { 1 } else { 0 };
    let step = env.step(action)?;
    obs = step.obs;
    steps += 1;
    if step.terminated || step.truncated {
        break;
    }
}
println!("the hand-written policy balanced for {steps} steps");
println!("PPO's last five returns after {} episodes: {:?}", snap.episodes, &snap.returns[95..]);

// %% step: The policy gradient
// π(·|s_t) for the first steps of the latest episode, and the action that was sampled.
for (t, p) in snap.cartpole_update().expect("a trained CartPole run").probs.iter().take(5).enumerate() {
    println!("s_{t}: π(left) = {:.4}  π(right) = {:.4}  sampled: {}", p[0], p[1], trace.actions[t]);
}

// %% step: Reusing a batch: the importance ratio
fn max_distance_from_one(ratio: &[f32]) -> f32 {
    ratio.iter().map(|r| (r - 1.0).abs()).fold(0.0, f32::max)
}
let first: EpochTrace = trace.epochs[0].clone();
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();
println!("epoch 1:  max |ratio - 1| = {:.6}", max_distance_from_one(&first.ratio));
println!("epoch {}: max |ratio - 1| = {:.6}", trace.epochs.len(), max_distance_from_one(&last.ratio));

// %% step: The clipped surrogate
// %% step: Where the advantage comes from: GAE
// The library's GAE on this episode's TD errors gives the update's advantage, exactly.
let advantage: Vec<f32> = ppo_engine::ppo::compute_advantage(config.gamma, config.lmbda, &trace.td_delta);
assert_eq!(advantage, trace.advantage);
println!("{} advantages, the first {:.4}, the last {:.4}", advantage.len(), advantage[0], advantage[advantage.len() - 1]);

// %% step: The whole loop at a glance
