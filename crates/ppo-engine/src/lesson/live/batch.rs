//! What every agent's latest update has in common, borrowed from its own trace: the batch's
//! columns and each epoch's ratio and losses. The live values that mean the same in every
//! run (`td_target`, `ratio`, `actor_loss`, ...) and the quiz's measures read this view, so
//! they are written once, whatever the agent.

/// The latest batch's columns and its update's epochs, borrowed from an agent's trace.
#[derive(Debug, Clone, PartialEq)]
pub struct Batch<'a> {
    /// The states acted in, one row per step.
    pub states: Rows<'a>,
    /// The states each step led to.
    pub next_states: Rows<'a>,
    /// The actions taken.
    pub actions: Actions<'a>,
    /// The environment's rewards.
    pub rewards: &'a [f32],
    /// `done_t`, where the TD target drops `V(s')`.
    pub dones: &'a [bool],
    /// `V(s_t)` before the update.
    pub values: &'a [f32],
    /// `V(s_{t+1})` before the update.
    pub next_values: &'a [f32],
    /// `r_t + γ·V(s_{t+1})·(1 − done_t)`.
    pub td_target: &'a [f32],
    /// `td_target − V(s_t)`.
    pub td_delta: &'a [f32],
    /// The GAE advantage.
    pub advantage: &'a [f32],
    /// `log π_old(a_t|s_t)`, the policy that played.
    pub old_log_probs: &'a [f32],
    /// Each epoch of the update, in order.
    pub epochs: Vec<EpochView<'a>>,
}

/// One epoch of a [`Batch`]'s update.
#[derive(Debug, Clone, PartialEq)]
pub struct EpochView<'a> {
    /// `log π_θ(a_t|s_t)` at the epoch's start.
    pub log_probs: &'a [f32],
    /// `π_θ / π_old`.
    pub ratio: &'a [f32],
    /// `ratio · Â`.
    pub surr1: &'a [f32],
    /// `clip(ratio, 1 − ε, 1 + ε) · Â`.
    pub surr2: &'a [f32],
    /// Where the clip was active, when the agent records it; `None` marks ratios outside
    /// `[1 − ε, 1 + ε]` instead.
    pub clipped: Option<&'a [bool]>,
    /// The actor's loss of the epoch.
    pub actor_loss: f32,
    /// The critic's loss of the epoch.
    pub critic_loss: f32,
}

/// States as rows of equal width, flattened.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rows<'a> {
    /// The values, row after row.
    pub values: &'a [f32],
    /// The width of a row (the observation's size).
    pub width: usize,
}

impl<'a> Rows<'a> {
    /// Rows of fixed width `N`.
    #[must_use]
    pub fn of<const N: usize>(rows: &'a [[f32; N]]) -> Self {
        Self {
            values: rows.as_flattened(),
            width: N,
        }
    }

    /// The number of rows.
    #[must_use]
    pub fn len(&self) -> usize {
        self.values.len().checked_div(self.width).unwrap_or(0)
    }

    /// Whether there is no row.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Row `i`, `None` past the end.
    #[must_use]
    pub fn row(&self, i: usize) -> Option<&'a [f32]> {
        self.values.get(i * self.width..(i + 1) * self.width)
    }
}

/// The actions of a batch, in the space the agent acts in (Gymnasium's `Discrete` or `Box`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Actions<'a> {
    /// Indices of a discrete action space (CartPole's 0 and 1).
    Discrete(&'a [usize]),
    /// One real number per step (Pendulum's torque).
    Continuous(&'a [f32]),
}

impl Actions<'_> {
    /// Action `i` as a number, `None` past the end.
    #[must_use]
    pub fn get(&self, i: usize) -> Option<f64> {
        match self {
            Self::Discrete(a) => a.get(i).map(|&a| a as f64),
            Self::Continuous(a) => a.get(i).map(|&a| f64::from(a)),
        }
    }
}

impl Batch<'_> {
    /// How many observations the episode went through: each state it acted in, then the
    /// one it ended in (the frames of an animation).
    #[must_use]
    pub fn observation_count(&self) -> usize {
        self.states.len() + usize::from(!self.next_states.is_empty())
    }

    /// Observation `i` of the episode (0 is the reset, [`Self::observation_count`] − 1
    /// where it ended), `None` past the end.
    #[must_use]
    pub fn observation(&self, i: usize) -> Option<&[f32]> {
        match self.states.row(i) {
            Some(state) => Some(state),
            None if i == self.states.len() => {
                let last = self.next_states.len().checked_sub(1)?;
                self.next_states.row(last)
            }
            None => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_and_observations_follow_the_episode() {
        let states = [[0.0, 1.0], [2.0, 3.0]];
        let next = [[2.0, 3.0], [4.0, 5.0]];
        let rows = Rows::of(&states);
        assert_eq!((rows.len(), rows.row(1)), (2, Some(&[2.0, 3.0][..])));
        assert_eq!(rows.row(2), None);
        let batch = Batch {
            states: rows,
            next_states: Rows::of(&next),
            actions: Actions::Discrete(&[1, 0]),
            rewards: &[],
            dones: &[],
            values: &[],
            next_values: &[],
            td_target: &[],
            td_delta: &[],
            advantage: &[],
            old_log_probs: &[],
            epochs: Vec::new(),
        };
        assert_eq!(batch.observation_count(), 3);
        assert_eq!(batch.observation(2), Some(&[4.0, 5.0][..]));
        assert_eq!(batch.observation(3), None);
        assert_eq!(batch.actions.get(0), Some(1.0));
        let empty = Rows::of::<2>(&[]);
        assert!(empty.is_empty() && empty.row(0).is_none());
    }
}
