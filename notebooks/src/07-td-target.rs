//! Recipe for notebooks/07-td-target.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("30 episodes were trained").trace.clone();
println!("episode {} lasted {} steps", snap.episodes, trace.rewards.len());

// %% step: What the critic is for
// %% step: The TD target
// %% step: Why multiply by (1 − done)
let last = trace.rewards.len() - 1;
println!(
    "last step: done = {}, V(s') = {:.4}, td_target = {:.4} = the reward alone",
    trace.dones[last], trace.next_values[last], trace.td_target[last]
);

// %% step: The TD error
// A positive TD error: the step went better than the critic expected from s_t.
let positive = trace.td_delta.iter().filter(|d| **d > 0.0).count();
println!(
    "{positive} of {} TD errors are positive; the last is {:.4}, with V(s_T−1) = {:.4}",
    trace.td_delta.len(),
    trace.td_delta[last],
    trace.values[last]
);

// %% step: Computed once per update
// %% exercise
