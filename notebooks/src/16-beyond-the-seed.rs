//! Recipe for notebooks/16-beyond-the-seed.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::PpoConfig;
fn mean_last(returns: &[f64], k: usize) -> f64 {
    returns[returns.len() - k..].iter().sum::<f64>() / k as f64
}
// The seed as written: 300 episodes, seed 0.
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 300)?;
println!("the seed: mean of the last 50 returns = {:.1}", mean_last(&snap.returns, 50));

// %% step: Truncation is not termination
// The fix, one switch away: bootstrap V(s') when the time limit cut the episode.
let fixed: Snapshot = snapshot(PpoConfig { bootstrap_on_truncation: true, ..config.clone() }, 0, 300)?;
println!("bootstrap_on_truncation: mean of the last 50 returns = {:.1}", mean_last(&fixed.returns, 50));

// %% step: Advantages are not normalised
let normalised: Snapshot = snapshot(PpoConfig { normalize_advantage: true, ..config.clone() }, 0, 300)?;
println!("normalize_advantage: mean of the last 50 returns = {:.1}", mean_last(&normalised.returns, 50));

// %% step: CartPole-v0 or CartPole-v1
use ppo_engine::env::EnvId;
let v0: Snapshot = snapshot(PpoConfig { env_id: EnvId::CartPoleV0, ..config.clone() }, 0, 300)?;
let best = v0.returns.iter().copied().fold(0.0, f64::max);
println!("CartPole-v0: no return above {best} (the 200-step limit)");

// %% step: Rollouts, vector environments and minibatches
// %% step: Entropy bonus and gradient-norm clipping
// %% step: Value clipping, orthogonal init, learning-rate annealing

// %% exercise
