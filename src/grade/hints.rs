//! The grader's general hints: what a panic, an endless loop, a dead program or a candle
//! error usually means, whatever the exercise. Hints about an exercise's own mistakes live
//! beside its lesson, in `lessons/NN-slug/exercise.toml` ([`super::prose`]).

/// The hint for a function that never returned.
pub const TIMED_OUT: &str = "Check that every loop ends: a loop whose counter never moves, or \
    a `while` whose condition stays true, never returns.";

/// The hint for a program that died.
pub const CRASHED: &str = "The program died on this input: unbounded recursion (stack \
    overflow) or std::process::exit are the usual causes.";

/// The hint for a panic with `message`.
#[must_use]
pub fn panic(message: &str) -> String {
    let hint = if message.contains("not yet implemented") {
        "The starter's todo!() is still there: replace it with your implementation."
    } else if message.contains("out of bounds") || message.contains("range end index") {
        "An index went past the end of a slice: check the loop bounds (a single step, or the \
         first and last positions, are the usual suspects)."
    } else if message.contains("overflow") {
        "An integer went out of range, often a usize going below 0 (like i - 1 at i = 0): \
         check the bounds of your loops."
    } else {
        "Your function panicked on this input: run it by hand on the input above."
    };
    hint.to_string()
}

/// The hint for an error a candle function returned.
#[must_use]
pub fn error(message: &str) -> String {
    let hint = if message.contains("not a scalar") {
        "Each loss must be a single number: mean_all() averages every element into a scalar \
         (mean(0) leaves a shape [1])."
    } else if message.contains("shape mismatch") || message.contains("broadcast") {
        "The shapes do not line up: probs is (N, 2) and every other column (N, 1); \
         probs.gather(actions, 1) picks the action's probability as (N, 1), and the \
         operators +, -, * need equal shapes (or the broadcast_ versions)."
    } else if message.contains("dtype") {
        "Mixed dtypes: the tensors are f32 and candle does not convert implicitly; scalars \
         like 1.0 - eps go straight into clamp or affine, and Tensor::new(&[1.0], ..) makes \
         an f64 tensor."
    } else {
        "Your function returned an error on this input: read the message, then run the \
         candle operations on the input above one by one."
    };
    hint.to_string()
}
