//! Which implementation computes an update, and how to force the reference one.
//!
//! Both agents' `update` is written on candle tensors with autograd: that is the code the
//! lessons show, [`UpdatePath::Candle`]. For the configurations the seed and the book run,
//! the same IEEE operations in the same order also exist on plain `f32` slices,
//! [`UpdatePath::Plain`] (the private `plain` modules of [`agent`](super::agent) and
//! [`continuous::agent`](super::continuous::agent)): bit for bit the same trace and weights,
//! ten to twenty times faster. [`choose_path`] picks one for each update, and every trace
//! records the one that ran ([`UpdateTrace::path`](super::UpdateTrace::path),
//! [`ContinuousUpdateTrace::path`](super::ContinuousUpdateTrace::path)).
//!
//! The plain path runs when every condition of [`PathConditions`] holds; otherwise candle:
//!
//! ```text
//! condition                                       why candle is needed otherwise
//! no learner's losses (Agent::update_with)        only autograd differentiates any function
//! PPO's clipped surrogate (not REINFORCE, not     the plain kernels hold that one gradient
//!   no_clip, not PPO-Penalty nor the KL line        (PPO-Penalty's exact KL term and the
//!   search) and no entropy bonus (coef = 0)           line search's step have none there)
//! 3 to 512 rows, 2 to 512 hidden units, and       gemm's summation orders change outside
//!   rows × hidden > 256                             (tiny products, sums split past 512)
//! x86-64 with AVX2 and FMA, found at run time     the candle kernels the plain path copies
//! PPO_TUTOR_UPDATE is not `candle`                the switch that forces the reference
//! ```
//!
//! The continuous agent always uses its built-in clipped losses: only the shapes, the CPU
//! and the switch decide there. This table is the one statement of the rule; the agents'
//! and the kernels' docs link here.
//!
//! ## What the plain path costs a maintainer
//!
//! - **Upgrading candle or gemm.** The plain path copies the summation orders of candle 0.11
//!   and gemm 0.19 on x86-64 (the discrete `plain` module's doc lists them kernel by kernel).
//!   An upgrade that changes one makes the bit-for-bit tests fail (`cargo test -p ppo-rl
//!   plain`, which compare both paths on batch sizes either side of every switch of
//!   gemm's path); the plain kernels must then follow the new order before the upgrade lands.
//! - **Other CPUs.** Only x86-64 with AVX2 and FMA (x86-64-v3, found at run time) runs it:
//!   on AArch64, or an x86-64 without FMA, every update runs on candle, with the same numbers
//!   and ten to twenty times slower; a CPU with AVX-512 runs the AVX2 kernels (candle's own
//!   kernels there are AVX2 too). On a CPU without AVX2 and FMA the bit-for-bit tests print
//!   `SKIPPED` instead of comparing candle with candle.
//!
//! `PPO_TUTOR_UPDATE` ([`UPDATE_VAR`]) is read once per process ([`UpdatePath::forced`]):
//!
//! - `candle` (any case, spaces around it ignored): every update of both agents runs on
//!   candle, for debugging the fast path against the reference (the numbers are the same;
//!   training is slower);
//! - unset, empty, `auto`, or any other value: automatic, as above. A value it does not know
//!   is ignored, never an error: the plain path cannot be forced where its conditions fail.
//!
//! ```
//! use ppo_rl::ppo::update_path::{PathConditions, UpdatePath, choose_path};
//!
//! let seed = PathConditions {
//!     learner_losses: false,
//!     clipped_surrogate: true,
//!     entropy_bonus: false,
//!     rows: 200,
//!     hidden: 128,
//!     avx2_fma: true,
//! };
//! assert_eq!(choose_path(&seed, None), UpdatePath::Plain);
//! assert_eq!(choose_path(&seed, Some(UpdatePath::Candle)), UpdatePath::Candle);
//! let no_fma = PathConditions { avx2_fma: false, ..seed };
//! assert_eq!(choose_path(&no_fma, None), UpdatePath::Candle);
//! assert_eq!(UpdatePath::parse_setting(Some(" Candle ")), Some(UpdatePath::Candle));
//! assert_eq!(UpdatePath::parse_setting(Some("fast")), None); // unknown: automatic
//! ```

use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

use super::kernels::{isa, shapes_fit};

/// The environment variable that forces the candle path: `PPO_TUTOR_UPDATE=candle`.
pub const UPDATE_VAR: &str = "PPO_TUTOR_UPDATE";

/// Which implementation computed an update (see the [module doc](self) for the rule).
///
/// Serialised as `"plain"` or `"candle"`. The default is `Candle`, the reference.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum UpdatePath {
    /// Candle's float operations one for one on plain `f32` slices, hand-differentiated:
    /// runs when every [`PathConditions`] holds (the seed's and the book's configurations on
    /// an x86-64 CPU with AVX2 and FMA) and `PPO_TUTOR_UPDATE` is not `candle`.
    Plain,
    /// Candle tensors with autograd, the code the lessons show: runs for everything else, and
    /// for every update with `PPO_TUTOR_UPDATE=candle`.
    #[default]
    Candle,
}

impl UpdatePath {
    /// `"plain"` or `"candle"`, as serialised and as `PPO_TUTOR_UPDATE` spells it.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Plain => "plain",
            Self::Candle => "candle",
        }
    }

    /// What a value of `PPO_TUTOR_UPDATE` asks for: `Some(Candle)` for `candle` (any case,
    /// spaces around it ignored), `None` (automatic) for no value, `auto`, or anything else.
    #[must_use]
    pub fn parse_setting(value: Option<&str>) -> Option<Self> {
        value
            .map(str::trim)
            .filter(|v| v.eq_ignore_ascii_case("candle"))
            .map(|_| Self::Candle)
    }

    /// The path `PPO_TUTOR_UPDATE` forces in this process, read once at the first update:
    /// `Some(Candle)` with `PPO_TUTOR_UPDATE=candle`, else `None` (automatic).
    #[must_use]
    pub fn forced() -> Option<Self> {
        static FORCED: OnceLock<Option<UpdatePath>> = OnceLock::new();
        *FORCED.get_or_init(|| {
            let value = std::env::var_os(UPDATE_VAR);
            Self::parse_setting(value.as_deref().and_then(std::ffi::OsStr::to_str))
        })
    }

    /// Whether this CPU can run the plain path at all: x86-64 with AVX2 and FMA
    /// (x86-64-v3), detected at run time. Without it every update runs on candle.
    #[must_use]
    pub fn plain_available() -> bool {
        isa().is_some()
    }
}

impl std::fmt::Display for UpdatePath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What decides one update's path: the plain path needs every one of these as the seed's
/// configuration has it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PathConditions {
    /// A learner's losses are plugged in ([`Agent::update_with`](super::Agent::update_with)):
    /// only autograd can differentiate them (plain needs `false`).
    pub learner_losses: bool,
    /// The actor's loss is PPO's clipped surrogate `mean(-min(surr1, surr2))`, not
    /// REINFORCE's `log π · Â`, `no_clip`'s `ratio · Â`, PPO-Penalty's
    /// `−mean(ratio · Â) + β · mean(KL)` nor the KL line search's step (plain needs `true`).
    pub clipped_surrogate: bool,
    /// An entropy bonus is on (`entropy_coef` > 0; plain needs `false`).
    pub entropy_bonus: bool,
    /// Transitions in the batch (plain needs 3 to 512, and `rows × hidden > 256`).
    pub rows: usize,
    /// Hidden units of both networks (plain needs 2 to 512).
    pub hidden: usize,
    /// The CPU is x86-64 with AVX2 and FMA ([`UpdatePath::plain_available`]; plain needs
    /// `true`).
    pub avx2_fma: bool,
}

impl PathConditions {
    /// Whether the batch and the networks have shapes the plain kernels reproduce: 3 to 512
    /// rows, 2 to 512 hidden units, and more than 256 entries in the hidden layer (gemm
    /// takes other summation orders for tiny products and splits sums longer than 512).
    #[must_use]
    pub fn shapes_fit(&self) -> bool {
        shapes_fit(self.rows, self.hidden)
    }

    /// Whether every condition of the plain path holds.
    #[must_use]
    pub fn plain_fits(&self) -> bool {
        !self.learner_losses
            && self.clipped_surrogate
            && !self.entropy_bonus
            && self.shapes_fit()
            && self.avx2_fma
    }
}

/// The path of one update: [`UpdatePath::Candle`] when `forced` is `Some(Candle)`, else
/// [`UpdatePath::Plain`] exactly when [`PathConditions::plain_fits`]. `forced` is
/// [`UpdatePath::forced`] in the agents; `Some(Plain)` is the same as `None`, since the plain
/// path cannot run where its conditions fail.
#[must_use]
pub fn choose_path(conditions: &PathConditions, forced: Option<UpdatePath>) -> UpdatePath {
    if forced == Some(UpdatePath::Candle) || !conditions.plain_fits() {
        UpdatePath::Candle
    } else {
        UpdatePath::Plain
    }
}

/// For the tests that compare the plain path with candle: `true` where this CPU runs the
/// plain path; elsewhere it prints `SKIPPED: test: ...` and returns `false`, so that the
/// test returns instead of comparing candle with candle.
#[cfg(test)]
pub(crate) fn plain_runs_here(test: &str) -> bool {
    if UpdatePath::plain_available() {
        return true;
    }
    eprintln!(
        "SKIPPED: {test}: this CPU lacks AVX2+FMA (x86-64-v3), so the plain update cannot run \
         and there is nothing to compare candle with"
    );
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The seed's update on CartPole: every condition of the plain path holds.
    const SEED: PathConditions = PathConditions {
        learner_losses: false,
        clipped_surrogate: true,
        entropy_bonus: false,
        rows: 200,
        hidden: 128,
        avx2_fma: true,
    };

    #[test]
    fn the_seed_runs_plain_unless_candle_is_forced() {
        assert_eq!(choose_path(&SEED, None), UpdatePath::Plain);
        assert_eq!(
            choose_path(&SEED, Some(UpdatePath::Plain)),
            UpdatePath::Plain
        );
        assert_eq!(
            choose_path(&SEED, Some(UpdatePath::Candle)),
            UpdatePath::Candle
        );
    }

    /// Each condition alone sends the update to candle, and forcing plain does not help.
    #[test]
    fn each_condition_alone_sends_the_update_to_candle() {
        let cases = [
            (
                "learner losses",
                PathConditions {
                    learner_losses: true,
                    ..SEED
                },
            ),
            (
                "no clip or REINFORCE",
                PathConditions {
                    clipped_surrogate: false,
                    ..SEED
                },
            ),
            (
                "entropy bonus",
                PathConditions {
                    entropy_bonus: true,
                    ..SEED
                },
            ),
            ("2 rows", PathConditions { rows: 2, ..SEED }),
            ("513 rows", PathConditions { rows: 513, ..SEED }),
            ("1 hidden unit", PathConditions { hidden: 1, ..SEED }),
            (
                "513 hidden units",
                PathConditions {
                    hidden: 513,
                    ..SEED
                },
            ),
            (
                "rows × hidden = 256",
                PathConditions {
                    rows: 4,
                    hidden: 64,
                    ..SEED
                },
            ),
            (
                "no AVX2+FMA",
                PathConditions {
                    avx2_fma: false,
                    ..SEED
                },
            ),
        ];
        for (what, conditions) in cases {
            assert!(!conditions.plain_fits(), "{what}");
            for forced in [None, Some(UpdatePath::Plain), Some(UpdatePath::Candle)] {
                assert_eq!(
                    choose_path(&conditions, forced),
                    UpdatePath::Candle,
                    "{what}, forced {forced:?}"
                );
            }
        }
    }

    /// The ends of the shapes the plain kernels take.
    #[test]
    fn the_shape_limits_are_inclusive() {
        for (rows, hidden) in [(3, 128), (512, 128), (200, 2), (200, 512), (5, 52)] {
            let conditions = PathConditions {
                rows,
                hidden,
                ..SEED
            };
            assert_eq!(
                choose_path(&conditions, None),
                UpdatePath::Plain,
                "{rows} rows, {hidden} hidden"
            );
        }
    }

    #[test]
    fn only_candle_is_a_setting_and_nothing_else_fails() {
        for value in ["candle", "CANDLE", " Candle\n"] {
            assert_eq!(
                UpdatePath::parse_setting(Some(value)),
                Some(UpdatePath::Candle),
                "{value:?}"
            );
        }
        for value in [
            None,
            Some(""),
            Some("auto"),
            Some("plain"),
            Some("gpu"),
            Some("1"),
        ] {
            assert_eq!(UpdatePath::parse_setting(value), None, "{value:?}");
        }
    }

    #[test]
    fn paths_serialise_as_their_names() -> Result<(), serde_json::Error> {
        for path in [UpdatePath::Plain, UpdatePath::Candle] {
            let text = serde_json::to_string(&path)?;
            assert_eq!(text, format!("\"{path}\""));
            assert_eq!(serde_json::from_str::<UpdatePath>(&text)?, path);
        }
        Ok(())
    }
}
