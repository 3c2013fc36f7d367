//! Recipe for notebooks/04-policy-gradient.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::{Snapshot, TensorView};
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{PpoConfig, SurrogateGradients, UpdateTrace};
// The seed's settings and seed 0, 30 episodes; the experiment at the end trains 500 per run.
const LAB_EPISODES: usize = 500;
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("30 episodes were trained").trace.clone();

// %% step: What we want: J(θ)
// log P_θ(τ) keeps only the policy's factors that θ controls: Σ_t log π(a_t|s_t).
let log_p: f32 = trace.old_log_probs.iter().sum();
println!("{} actions taken; Σ_t log π(a_t|s_t) = {log_p:.3}", trace.actions.len());

// %% step: The log-derivative trick: REINFORCE
// G_t = r_t + γ·G_{t+1}, from the last step back (0 after a done), as the library computes
// it: running that backward loop yourself is lesson 8's exercise.
use ppo_engine::lesson::live::values::return_to_go;
let g: Vec<f64> = return_to_go(&trace.rewards, &trace.dones, config.gamma);
let g32: Vec<f32> = g.iter().map(|&x| x as f32).collect();
TensorView::column("return_to_go", &g32)

// %% step: A baseline removes variance, not truth
// The weights REINFORCE puts on ∇log π, without and with the critic as baseline.
let centred: Vec<f64> = g.iter().zip(&trace.values).map(|(g, v)| g - f64::from(*v)).collect();
fn mean_abs(xs: &[f64]) -> f64 {
    xs.iter().map(|x| x.abs()).sum::<f64>() / xs.len() as f64
}
println!("mean |G_t| = {:.3}, mean |G_t − V(s_t)| = {:.3}", mean_abs(&g), mean_abs(&centred));

// %% step: The advantage, not the return
let same_sign = trace
    .advantage
    .iter()
    .zip(&centred)
    .filter(|(a, c)| (**a > 0.0) == (**c > 0.0))
    .count();
println!(
    "GAE (λ = {}) and G_t − V(s_t) have the same sign on {same_sign} of {} rows",
    config.lmbda,
    centred.len()
);

// %% step: The bridge to PPO: one gradient at θ_old
// check: grad_surrogate after 30 episodes
// The session differentiated both objectives at the actor that played episode 30.
let grads: SurrogateGradients = snap.cartpole_update().expect("computed after every episode").gradients.clone();
println!("{:<18} {:>14} {:>14}", "parameter", "∇ mean(r·Â)", "∇ mean(log π·Â)");
for i in [640, 641, 642, 896, 897] {
    let name = grads.label(i).unwrap_or_default();
    println!("{name:<18} {:>14.6e} {:>14.6e}", grads.surrogate[i], grads.log_prob[i]);
}
println!("largest difference {:.3e}; largest gradient {:.3e}", grads.max_abs_diff(), grads.max_abs());
TensorView::column("grad_surrogate", &grads.surrogate)

// %% step: REINFORCE with a baseline, one switch away
// One REINFORCE run beside PPO's, seed 0, the seed's other settings:
use ppo_engine::ppo::Algorithm;
let reinforce = PpoConfig { algorithm: Algorithm::Reinforce, ..config.clone() };
let r_snap: Snapshot = snapshot(reinforce, 0, 100)?;
let p_snap: Snapshot = snapshot(config.clone(), 0, 100)?;
fn last20(s: &Snapshot) -> f64 {
    s.returns[80..].iter().sum::<f64>() / 20.0
}
println!("after 100 episodes, mean of the last 20 returns: PPO {:.1}, REINFORCE {:.1}", last20(&p_snap), last20(&r_snap));
