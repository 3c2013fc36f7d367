//! The app's custom drawings: live tensors, the return plot, the cart and pole, the
//! pendulum, the clip chart.

pub mod cartpole;
pub mod clip;
pub mod lab;
pub mod pendulum;
pub mod plot;
pub mod tensors;
pub mod text;

/// Whether plots use Braille dots (default) or plain dots (`PPO_TUTOR_ASCII=1`, for fonts
/// without Braille glyphs).
#[must_use]
pub fn marker() -> ratatui::symbols::Marker {
    if std::env::var_os("PPO_TUTOR_ASCII").is_some_and(|v| !v.is_empty() && v != "0") {
        ratatui::symbols::Marker::Dot
    } else {
        ratatui::symbols::Marker::Braille
    }
}
