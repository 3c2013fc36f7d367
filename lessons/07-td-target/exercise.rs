//! Lesson 07 exercise: the TD target and the TD error, one value per transition.
//!
//! Grade: `ppo-tutor grade td_target` and `ppo-tutor grade td_delta` (or `g` in the tutor).
//! Start over: `ppo-tutor reset td_target` (restores this whole file).

/// The TD target of each step: what state `s_i` turned out to be worth, judged one step
/// later. It combines the one reward actually received with the critic's own estimate of
/// what follows, so it is better informed than the critic's prediction `V(s_i)`. It is the
/// number the critic is trained towards (lesson 11), and the seed's `td_target`.
///
/// - `rewards[i]` is the reward received on step `i` (1.0 in CartPole; the grader also uses
///   other values, negative ones included).
/// - `next_values[i]` is the critic's estimate `V(s_{i+1})` for the state that step `i`
///   landed in.
/// - `dones[i]` is true when the episode ended on step `i`. Then nothing comes after the
///   step, whatever `next_values[i]` says. In the seed only the last step is done; the
///   grader also tries episodes where every step is done.
/// - `gamma` is the discount factor γ (0.98 in the seed).
///
/// The three slices have the same length, one row per step, at least one. Return one target
/// per row, in the same order. The grader compares in f32, to about 1e-5.
///
/// Taught in lesson 7 (td-target), step 2 "The TD target"; step 3 explains the done flag.
pub fn td_target(rewards: &[f32], next_values: &[f32], dones: &[bool], gamma: f32) -> Vec<f32> {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // What is the future worth once the pole has fallen?
    todo!()
}

/// The TD error of each step: how much better step `i` went than the critic expected from
/// state `s_i`. Positive means a pleasant surprise (a good action, or a critic that
/// undervalues `s_i`); negative means things went worse than predicted. Lesson 8 builds the
/// advantages from these numbers. It is the seed's `td_delta`.
///
/// - `td_target[i]` is the TD target of step `i`, the better-informed estimate that
///   `td_target` above computes.
/// - `values[i]` is the critic's prediction `V(s_i)` for the state step `i` started in.
///
/// Both slices have the same length, at least one. Return one error per row, in the same
/// order. Mind the sign: it must be positive when the step went better than predicted.
///
/// Taught in lesson 7 (td-target), step 4 "The TD error".
pub fn td_delta(td_target: &[f32], values: &[f32]) -> Vec<f32> {
    // TODO: your code here. Of the two numbers in a row, which one knows more?
    todo!()
}
