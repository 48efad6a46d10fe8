//! Time of impact of two moving solids of revolution, certified by conservative advancement
//! over the query's certified lower bounds (Johnson and Cohen 1997; Son et al. 2020 give the
//! bounds, section 3).
//!
//! * [`motion`]: the interpolated rigid motion (constant linear and angular velocity).
//! * [`speed`]: the proved bound on how fast the distance can change along two motions.
//! * [`advance`]: the search: advancement, then a contact certified from the carried
//!   witnesses ([`contact`]), else probes and bisection with tolerance-0 queries, with an
//!   honest "undecided" when neither side can be certified.
//! * [`contact`]: the cheap contact certificate (points certified inside the true solids).
//! * [`batch`]: many searches between two solids in parallel.
//!
//! This level sits above [`crate::query`] and calls only its public facade.

pub mod advance;
pub mod batch;
pub mod contact;
pub mod motion;
pub mod speed;

#[cfg(test)]
mod tests;

pub use advance::{
    time_of_impact, TimeOfImpact, ToiError, ToiOptions, ToiOutcome, DEFAULT_MAX_QUERIES,
    DEFAULT_TIME_TOLERANCE,
};
pub use batch::{times_of_impact, BatchError};
pub use motion::{Motion, MotionError};
pub use speed::speed_bound;
