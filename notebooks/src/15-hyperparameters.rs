//! Recipe for notebooks/15-hyperparameters.ipynb (see 01-what-is-ppo.rs for the format).
//! Each knob's experiment trains 5 to 15 runs of 500 episodes on every core (a minute or more).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::PpoConfig;
const LAB_EPISODES: usize = 500;
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 100)?;

// %% step: Where the numbers live
// The seed's hyper-parameters are PpoConfig's defaults:
println!("{config:#?}");

// %% step: critic_lr: a ten times smaller critic step
println!(
    "critic_lr = {} (the seed's) against {}, the actor's own rate {}",
    config.critic_lr,
    config.critic_lr / 10.0,
    config.actor_lr
);

// %% step: hidden_dim: 16 units instead of 128
// Parameters of the two networks: 4 -> hidden_dim -> 2 and 4 -> hidden_dim -> 1.
for h in [config.hidden_dim, 16] {
    let actor = 4 * h + h + h * 2 + 2;
    let critic = 4 * h + h + h + 1;
    println!("hidden_dim = {h:3}: actor {actor} parameters, critic {critic}");
}

// %% step: gamma: a horizon of 10, 50 or 1000 steps
for gamma in [0.9, config.gamma, 0.999] {
    println!("γ = {gamma}: horizon 1/(1 − γ) = {:.0} steps", 1.0 / (1.0 - gamma));
}

// %% step: lmbda: how far GAE trusts the critic
// A TD error l steps ahead weighs (γλ)^l: the weight halves every ln 0.5 / ln(γλ) steps.
for lmbda in [0.5, config.lmbda, 1.0] {
    let gl = config.gamma * lmbda;
    println!("λ = {lmbda}: γλ = {gl:.3}, the weight halves every {:.1} steps", 0.5f64.ln() / gl.ln());
}

// %% step: The rest: what lesson 13 measured, and the task
use ppo_engine::env::EnvId;
for id in EnvId::ALL {
    println!("{}: an episode is cut at {} steps", id.as_str(), id.max_episode_steps());
}
