//! Each agent's live view, one file per agent: its [`super::session::LiveAgent`] impl,
//! what it shows of its latest episode and update ([`super::session::LiveAgent::Latest`],
//! a [`super::LatestView`]) and the live values only it has.

pub mod cartpole;
pub mod pendulum;
