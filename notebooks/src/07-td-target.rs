//! Recipe for notebooks/07-td-target.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_tutor::lesson::{Snapshot, TensorView};
use ppo_tutor::notebook::snapshot;
use ppo_tutor::ppo::{PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.trace.clone().expect("30 episodes were trained");
println!("episode {} lasted {} steps", snap.episodes, trace.rewards.len());

// %% step: What the critic is for
// %% step: The TD target
// check: td_target after 30 episodes
// td_target = rewards + gamma * V(s') * (1 - dones), computed here from the batch.
let gamma = config.gamma as f32;
let targets: Vec<f32> = (0..trace.rewards.len())
    .map(|t| {
        let not_done = if trace.dones[t] { 0.0 } else { 1.0 };
        trace.rewards[t] + gamma * trace.next_values[t] * not_done
    })
    .collect();
TensorView::column("td_target", &targets)

// %% step: Why multiply by (1 − done)
let last = trace.rewards.len() - 1;
println!(
    "last step: done = {}, V(s') = {:.4}, td_target = {:.4} = the reward alone",
    trace.dones[last], trace.next_values[last], targets[last]
);

// %% step: The TD error
// check: td_delta after 30 episodes
let deltas: Vec<f32> = targets.iter().zip(&trace.values).map(|(y, v)| y - v).collect();
TensorView::column("td_delta", &deltas)

// %% step: Computed once per update
// %% exercise
