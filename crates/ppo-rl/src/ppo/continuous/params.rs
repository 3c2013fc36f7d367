//! The Gaussian policy's parameters by PyTorch name and shape: the one table the agent,
//! its checkpoints and the replay share.

use super::{ACTION_DIM, STATE_DIM};
use crate::ppo::PpoError;
use crate::ppo::checkpoint::check_against;
use crate::ppo::model::NamedWeights;

/// Every parameter's name and shape for hidden width `hidden_dim`, in PyTorch's order.
#[must_use]
pub fn parameter_shapes(hidden_dim: usize) -> [(&'static str, Vec<usize>); 10] {
    let h = hidden_dim;
    [
        ("actor.fc1.weight", vec![h, STATE_DIM]),
        ("actor.fc1.bias", vec![h]),
        ("actor.fc_mu.weight", vec![ACTION_DIM, h]),
        ("actor.fc_mu.bias", vec![ACTION_DIM]),
        ("actor.fc_std.weight", vec![ACTION_DIM, h]),
        ("actor.fc_std.bias", vec![ACTION_DIM]),
        ("critic.fc1.weight", vec![h, STATE_DIM]),
        ("critic.fc1.bias", vec![h]),
        ("critic.fc2.weight", vec![1, h]),
        ("critic.fc2.bias", vec![1]),
    ]
}

/// The ten parameter names, in PyTorch's order.
#[must_use]
pub fn parameter_names() -> [&'static str; 10] {
    parameter_shapes(0).map(|(name, _)| name)
}

/// Checks that `weights` holds exactly the ten parameters with the shapes `hidden_dim`
/// gives, and finite values.
///
/// # Errors
/// [`PpoError::MissingKey`] or [`PpoError::WrongShape`] naming the tensor in `source`.
pub fn check_weights(
    weights: &NamedWeights,
    hidden_dim: usize,
    source: &str,
) -> Result<(), PpoError> {
    check_against(
        weights,
        &parameter_shapes(hidden_dim),
        hidden_dim,
        source,
        crate::i18n::t(
            "only the ten actor./critic. parameters of the Gaussian policy",
            "只有高斯策略的 actor./critic. 十个参数",
        ),
    )
}
