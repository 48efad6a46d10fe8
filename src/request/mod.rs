//! What a caller asks for, checked once for every front end: the profile a name or a path
//! stands for ([`spec`]), the accuracy and budget of a query ([`options`]) and a pose given
//! as a translation and a unit quaternion or as a homogeneous matrix ([`pose`]).
//!
//! The command line (`revdist distance`, its batch mode, every subcommand that takes a
//! profile) and the Python package map their inputs through these functions, so that the
//! same input gives the same query, bit for bit, and the same error message.

pub mod options;
pub mod pose;
pub mod spec;

pub use options::{check_eps, check_tolerance, max_time, query_options, OptionError, DEFAULT_EPS};
pub use pose::{
    pose_from_matrix, pose_from_quaternion, unit_quaternion, PoseError, UNIT_QUATERNION_SLACK,
};
pub use spec::{build_solid, load_profile, read_profile_file, SpecError};
