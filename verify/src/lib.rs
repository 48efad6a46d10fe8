//! Independent checks of revdist: exact arithmetic with rug (GMP/MPFR) and float references.

pub mod circles;
pub mod companion;
pub mod exact_circle;
