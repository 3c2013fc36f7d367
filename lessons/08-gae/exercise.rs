//! Lesson 08 exercise: generalised advantage estimation.
//!
//! Grade: `ppo-tutor grade compute_advantage` (or `g` in the tutor).
//! Start over: `ppo-tutor reset compute_advantage`.

/// The advantage of every step of an episode, by generalised advantage estimation (GAE).
///
/// A step's advantage says how much better its action turned out than the critic expected.
/// A single TD error looks one step ahead and then trusts the critic; GAE also listens to the
/// surprises of all the later steps of the episode, with each one counting less the further
/// away it is. γ and λ set how fast they fade. This is the seed's
/// `rl_utils.compute_advantage(gamma, lmbda, td_delta)`.
///
/// - `gamma` is the discount factor γ (0.98 in the seed).
/// - `lmbda` is GAE's λ (0.95 in the seed), the dial between trusting the critic after one
///   step (λ = 0) and using the real rewards to the end of the episode (λ = 1).
/// - `td_delta[t]` is the TD error δ_t of step t (lesson 7), in the episode's order. The slice
///   is one whole episode: its last entry is the episode's final step, and nothing comes after
///   it.
///
/// Return one advantage per step, as many as `td_delta` holds, in the episode's order: index
/// t holds the advantage of step t. The grader tries single-step episodes, λ = 0 and λ = 1, and
/// compares to 1e-5 absolute and 1e-4 relative. The seed does this arithmetic in float32; to
/// match it to the last digit, do yours in f32 too (step 4 of the lesson says how).
///
/// Taught in lesson 8 (gae), step 3 "Why the loop runs backwards"; step 4 "The numpy detour,
/// in float32" explains the arithmetic.
pub fn compute_advantage(gamma: f32, lmbda: f32, td_delta: &[f32]) -> Vec<f32> {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // Which step's advantage can you compute without knowing any other?
    todo!()
}
