//! Recipe for notebooks/14-hyperparameters.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::PpoConfig;
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 100)?;

// %% step: Where the numbers live
// The seed's hyper-parameters are PpoConfig's defaults:
println!("{config:#?}");

// %% step: Two learning rates: actor_lr and critic_lr
println!(
    "actor_lr = {}, critic_lr = {}: the critic's steps are {} times the actor's",
    config.actor_lr,
    config.critic_lr,
    config.critic_lr / config.actor_lr
);

// %% step: How long and how wide: num_episodes and hidden_dim
// Parameters of the two networks: 4 -> hidden_dim -> 2 and 4 -> hidden_dim -> 1.
let h = config.hidden_dim;
let actor = 4 * h + h + h * 2 + 2;
let critic = 4 * h + h + h + 1;
println!("actor: {actor} parameters, critic: {critic}, trained for {} episodes", config.num_episodes);

// %% step: Looking ahead: gamma and lmbda
let gl = config.gamma * config.lmbda;
println!("γ = {}, λ = {}, γλ = {gl:.4}: a TD error k steps ahead weighs γλ^k", config.gamma, config.lmbda);
for k in [1, 10, 50, 100] {
    println!("  k = {k:3}: γλ^k = {:.4}", gl.powi(k));
}

// %% step: Reuse and restraint: epochs and eps
println!(
    "each episode is used for {} gradient steps; the ratio is clipped to [{}, {}]",
    config.epochs,
    1.0 - config.eps,
    1.0 + config.eps
);

// %% step: The task: CartPole-v1
use ppo_engine::env::EnvId;
for id in EnvId::ALL {
    println!("{}: an episode is cut at {} steps", id.as_str(), id.max_episode_steps());
}
