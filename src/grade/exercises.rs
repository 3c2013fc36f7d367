//! The registry: every exercise of the course, in course order, each in its own module
//! (signature, reference, cases, typical mistakes; its prose is in its lesson's
//! `exercise.toml`).
//!
//! To add an exercise, add its module here and to the list below (see the README's
//! "Adding an exercise"). The list makes [`ALL`], which every face iterates, and the
//! in-place graders a notebook cell calls (`grade::in_process::<name>(<name>)`).

use super::exercise::Exercise;

/// Declares the exercise modules and the registry from one list, in course order.
macro_rules! registry {
    ($($feature:literal => $name:ident),+ $(,)?) => {
        $(
            #[cfg(any(feature = "app", feature = $feature))]
            pub mod $name;
        )+

        /// Every exercise, in course order (those of the enabled lessons).
        pub static ALL: &[&dyn Exercise] = &[$(
            #[cfg(any(feature = "app", feature = $feature))]
            &$name::EXERCISE
        ),+];

        /// Every exercise's name with the feature that compiles it without the app
        /// (`exercises-NN`, NN its lesson), in course order, enabled or not.
        pub static FEATURES: &[(&str, &str)] = &[$((stringify!($name), $feature)),+];

        /// The in-place grader of every exercise, by the exercise's name.
        pub mod in_place {
            $(
                #[cfg(any(feature = "app", feature = $feature))]
                pub use super::$name::in_place as $name;
            )+
        }
    };
}

// Each exercise with the feature of its lesson: a notebook compiles only its own lesson's
// exercises (`features = ["exercises-07"]`); the app (feature `app`) has them all.
registry! {
    "exercises-03" => sample_action,
    "exercises-07" => td_target,
    "exercises-07" => td_delta,
    "exercises-08" => compute_advantage,
    "exercises-09" => log_prob_of_actions,
    "exercises-09" => ratio,
    "exercises-10" => actor_loss,
    "exercises-10" => zero_gradient_rows,
    "exercises-11" => critic_loss,
    "exercises-11" => ppo_losses,
    "exercises-12" => approx_kl,
    "exercises-12" => clip_fraction,
    "exercises-13" => moving_average,
    "exercises-15" => td_target_truncation,
    "exercises-15" => gae_rollout,
    "exercises-15" => normalize_advantage,
    "exercises-16" => gaussian_log_prob,
}

#[cfg(test)]
mod tests {
    use super::{ALL, FEATURES};

    #[test]
    fn each_exercise_is_compiled_by_its_own_lessons_feature() -> Result<(), String> {
        assert_eq!(ALL.len(), FEATURES.len(), "the app compiles every exercise");
        let manifest: toml::Table = toml::from_str(include_str!("../../Cargo.toml"))
            .map_err(|e| format!("Cargo.toml: {e}"))?;
        let declared = manifest
            .get("features")
            .and_then(|f| f.as_table())
            .ok_or("Cargo.toml has no [features]")?;
        for (exercise, (name, feature)) in ALL.iter().zip(FEATURES) {
            let lesson = exercise.meta().lesson;
            assert_eq!(exercise.meta().name, *name);
            assert_eq!(
                *feature,
                format!("exercises-{}", &lesson[..2]),
                "{name} is taught in {lesson}"
            );
            assert!(
                declared.contains_key(*feature),
                "Cargo.toml lacks feature {feature}"
            );
        }
        Ok(())
    }
}
