//! Recipe for notebooks/10-trust-region.ipynb (see 01-what-is-ppo.rs for the format).
//! The probe plays 150 held-out episodes per step (about a second); steps 3 to 6 train three
//! short runs of 40 episodes (seconds); the last step's experiment trains 20 runs of 500
//! episodes on every core (a few minutes).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{Objective, PpoConfig, PpoError, Trainer, UpdateTrace};
const LAB_EPISODES: usize = 500;
// The seed's settings and seed 0; 40 episodes of training, as `ppo-tutor trust-region` does.
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 40)?;
let trace: UpdateTrace = snap.cartpole_update().expect("40 episodes were trained").trace.clone();
// Trains a fresh agent with `config` on seed 0 for `episodes` episodes, and keeps each
// episode's return and the trace of the update that followed it.
fn run_updates(config: &PpoConfig, episodes: usize) -> Result<Vec<(f64, UpdateTrace)>, PpoError> {
    let mut trainer = Trainer::new(PpoConfig { num_episodes: episodes, ..config.clone() }, 0)?;
    let mut runs = Vec::new();
    while let Some(report) = trainer.next_episode()? {
        runs.push((report.episode_return, report.trace));
    }
    Ok(runs)
}

// %% step: What the ratio corrects, and what it does not
// The latest update: every epoch scores the surrogate on the same rows, the states π_old
// visited. Only the ratios, the weights of the actions taken, change from epoch to epoch.
let rows = trace.len() as f32;
let mean_advantage: f32 = trace.advantage.iter().sum::<f32>() / rows;
println!("{} rows, each a state π_old visited; mean Â = {mean_advantage:.4}", trace.len());
println!("epoch  mean((r − 1)·Â)  max |r − 1|");
for (k, e) in trace.epochs.iter().enumerate() {
    let gain = e.surr1.iter().sum::<f32>() / rows - mean_advantage;
    let spread = e.ratio.iter().map(|r| (r - 1.0).abs()).fold(0.0_f32, f32::max);
    println!("{:5}  {gain:+15.5}  {spread:11.5}", k + 1);
}

// %% step: Stepping along the surrogate, measured
// The probe, as `ppo-tutor trust-region` runs it: from θ_old (the actor that played the
// latest batch) along the batch's surrogate gradient, twelve step lengths α from 0 to 3.2,
// each measured on 150 held-out episodes. The table, then the chart.
use ppo_engine::notebook::Rich as _; // shows the probe: its table, then its chart
use ppo_engine::ppo::trust_region::{ProbeSettings, TrustRegionProbe, probe_snapshot};
let probe: TrustRegionProbe = probe_snapshot(&snap, &config, &ProbeSettings::default())?;
probe

// %%
// Truth minus prediction at each step, and that gap over its standard error (the two
// errors combined as if independent: a yardstick, not a test).
println!("    α    mean KL  truth − predicted  gap / se");
for p in probe.points.iter().filter(|p| p.step > 0.0) {
    let gap = p.truth - p.predicted;
    let se = (p.truth_se.powi(2) + p.predicted_se.powi(2)).sqrt();
    println!("{:5.3}  {:9.2e}  {gap:+17.3}  {:8.1}", p.step, p.kl, gap / se);
}

// %%
// The same probe on a later batch: a run of the same seed trained to 100 episodes.
let later: Snapshot = snapshot(config.clone(), 0, 100)?;
let later_probe: TrustRegionProbe = probe_snapshot(&later, &config, &ProbeSettings::default())?;
println!("after {} episodes (last return {}):", later.episodes, later.returns[later.returns.len() - 1]);
println!("    α    mean KL   predicted ΔJ_γ        true ΔJ_γ");
for p in later_probe.points.iter().filter(|p| p.step > 0.0) {
    println!(
        "{:5.3}  {:9.2e}  {:+7.3} ± {:5.3}  {:+7.3} ± {:5.3}",
        p.step, p.kl, p.predicted, p.predicted_se, p.truth, p.truth_se
    );
}

// %% step: How far is far: the KL between two policies
// PPO-Penalty records the exact KL of every row (its loss needs it); approx_kl estimates the
// same mean from the sampled actions' ratios alone. Both for the latest update of a
// penalty run on seed 0, epoch by epoch (each before that epoch's step).
let penalty: PpoConfig = PpoConfig { objective: Objective::Penalty, ..config.clone() };
let pen: Snapshot = snapshot(penalty.clone(), 0, 40)?;
let pen_trace: UpdateTrace = pen.cartpole_update().expect("40 episodes were trained").trace.clone();
println!("epoch  exact mean KL  approx_kl  largest row KL");
for (k, e) in pen_trace.epochs.iter().enumerate() {
    let largest = e.kl.iter().copied().fold(0.0_f32, f32::max);
    let exact = e.kl_mean.unwrap_or(f32::NAN);
    println!("{:5}  {exact:13.3e}  {:9.3e}  {largest:14.3e}", k + 1, e.approx_kl);
}

// %% step: Answer 1: a hard limit on the KL (TRPO)
// The KL line search on seed 0 for 40 episodes. Per update: the KL of the first try, how
// many halvings, the accepted α, its KL on the batch (at most δ) and its surrogate gain;
// "-" where no length passed and the actor kept θ_old. The first ten updates, then all 40.
use ppo_engine::ppo::trace::LineSearchTrace;
let line_search: PpoConfig = PpoConfig { objective: Objective::LineSearch, ..config.clone() };
let searched: Vec<(f64, UpdateTrace)> = run_updates(&line_search, 40)?;
println!(
    "first try α = {}, at most {} halvings, δ = {}",
    line_search.ls_max_step, line_search.ls_backtracks, line_search.kl_delta
);
// A number with `digits` decimals, or "-" for none.
fn dash(v: Option<f64>, digits: usize) -> String {
    v.map_or("-".to_string(), |v| format!("{v:.digits$}"))
}
println!("episode  return  first KL  halvings       α        KL       gain");
for (i, (ret, t)) in searched.iter().enumerate().take(10) {
    let Some(s) = t.line_search else { continue };
    println!(
        "{:7}  {ret:6}  {:>8}  {:8}  {:>6}  {:>8}  {:>9}",
        i + 1,
        dash(s.first_kl.map(f64::from), 4),
        s.halvings,
        dash(s.step, 4),
        dash(s.kl.map(f64::from), 5),
        dash(s.gain.map(f64::from), 5)
    );
}
let searches: Vec<LineSearchTrace> = searched.iter().filter_map(|(_, t)| t.line_search).collect();
let accepted = searches.iter().filter(|s| s.step.is_some()).count();
let halvings = searches.iter().map(|s| s.halvings).sum::<usize>() as f64 / searches.len() as f64;
println!("all {} updates: {accepted} took a step, {halvings:.2} halvings on average", searches.len());

// %% step: Answer 2: a KL penalty with an adaptive β (PPO-Penalty)
// PPO-Penalty on seed 0 for 40 episodes: β during each update, d (the KL after its last
// epoch) and β for the next update.
let penalised: Vec<(f64, UpdateTrace)> = run_updates(&penalty, 40)?;
let delta = penalty.kl_delta;
println!(
    "β₀ = {}, δ = {delta}: β halves when d < {:.4} and doubles when d > {:.4}",
    penalty.beta_init,
    delta / 1.5,
    delta * 1.5
);
println!("episode  return   β before  KL after d    β after");
for (i, (ret, t)) in penalised.iter().enumerate() {
    let Some(p) = t.penalty else { continue };
    println!("{:7}  {ret:6}  {:9.5}  {:10.5}  {:9.5}", i + 1, p.beta_before, p.kl_after, p.beta_after);
}

// The live values below are this penalty run's latest update (seed 0, 40 episodes, the run
// of step 3); `clip_snap` keeps the seed's clip run for the next step.
let clip_snap: Snapshot = snap.clone();
let snap: Snapshot = pen.clone();

// %% step: Answer 3: the clip (PPO-Clip)
// The live values below are the seed's clip run's again.
let snap: Snapshot = clip_snap.clone();
// The seed's clip on the same seed and episodes, beside the other two answers: the exact KL
// each update moved the policy by (kl_after, the same measure for every objective).
use ppo_engine::i18n::pad_right;
let clipped: Vec<(f64, UpdateTrace)> = run_updates(&config, 40)?;
println!("objective     mean KL  largest KL  updates above 1.5δ  mean of the last 10 returns");
for (name, runs) in [("clip", &clipped), ("penalty", &penalised), ("line search", &searched)] {
    let kls: Vec<f32> = runs.iter().filter_map(|(_, t)| t.kl_after).collect();
    let mean = kls.iter().sum::<f32>() / kls.len() as f32;
    let largest = kls.iter().copied().fold(0.0_f32, f32::max);
    let above = kls.iter().filter(|&&kl| f64::from(kl) > 1.5 * config.kl_delta).count();
    let last: f64 = runs[runs.len() - 10..].iter().map(|(r, _)| r).sum::<f64>() / 10.0;
    println!("{}  {mean:7.4}  {largest:10.4}  {above:12} of {:2}  {last:27.1}", pad_right(name, 12), kls.len());
}

// %% step: Four ways over five seeds
// %% exercise
