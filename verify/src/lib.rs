//! Independent checks of revdist: exact arithmetic with rug (GMP/MPFR) and float references.

pub mod baselines;
pub mod bounds;
pub mod circles;
pub mod companion;
pub mod contact;
pub mod crosscheck;
pub mod exact_circle;
pub mod oracle;
pub mod penetration;
pub mod provenance;
pub mod queries;
pub mod random_profiles;
pub mod shard;
pub mod timing;
pub mod toi;
