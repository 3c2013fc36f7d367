//! The registry: every exercise of the course, in course order, each in its own module
//! (signature, reference, cases, typical mistakes; its prose is in its lesson's
//! `exercise.toml`).
//!
//! To add an exercise, add its module here and to the list below (see CONTRIBUTING.md,
//! "Adding an exercise"). The list makes [`ALL`], which every face iterates, and the
//! in-place graders a notebook cell calls (`grade::in_process::<name>(<name>)`).

use super::exercise::Exercise;

/// Declares the exercise modules and the registry from one list, in course order.
macro_rules! registry {
    ($($name:ident),+ $(,)?) => {
        $(
            pub mod $name;
        )+

        /// Every exercise, in course order.
        pub static ALL: &[&dyn Exercise] = &[$(&$name::EXERCISE),+];

        /// The in-place grader of every exercise, by the exercise's name.
        pub mod in_place {
            $(
                pub use super::$name::in_place as $name;
            )+
        }
    };
}

// Grading (feature `exercises`) compiles every exercise: a notebook whose lesson has
// exercises depends on the crate with `features = ["exercises"]`, and the app has them all.
registry! {
    sample_action,
    n_step_target,
    compute_advantage,
    importance_weighted_mean,
    categorical_kl,
    zero_gradient_rows,
    clipped_value_loss,
    ppo_losses,
    reverse_kl,
    kl_early_stop,
    td_target_truncation,
    gae_rollout,
    diag_gaussian_log_prob,
}
