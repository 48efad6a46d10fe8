//! Scenes for revdist: bodies, their poses and the effects they take part in
//! (static, kinematic, deforming, dynamic) are declared in a TOML file ([`mod@format`]); the
//! runner ([`runner`]) builds a plan and computes only what the scene asks for, with counters
//! that show it; [`output`] writes the per-frame CSV and the summary. Dynamic bodies are
//! stepped by [`dynamics`] (mass properties from [`mass`], interlocking checked by
//! [`links`]).
//!
//! Data flows one way: the scene crate depends on the `revdist` core, never the reverse.

pub mod dynamics;
pub mod format;
pub mod links;
pub mod mass;
pub mod motion;
pub mod output;
pub mod render;
pub mod runner;
