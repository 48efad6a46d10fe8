//! Scenes for revdist (issue 14): bodies, their poses and the effects they take part in
//! (static, kinematic, deforming, dynamic) are declared in a TOML file; the runner builds a
//! plan and computes only what the scene asks for, with counters that show it.
//!
//! Data flows one way: the scene crate depends on the `revdist` core, never the reverse.

pub mod dynamics;
