//! The accuracy modes compared (a curve of the figures each) and their CSV names.

use crate::shard::{Field, Scalar};
use revdist::query::{QueryOptions, Tolerance};

/// A curve of the figures: one accuracy mode of one method.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Method {
    Rev,
    RevTol0,
    RevRefined,
    FclObbrss,
    FclRss,
}

pub(super) const METHODS: [Method; 5] = [
    Method::Rev,
    Method::RevTol0,
    Method::RevRefined,
    Method::FclObbrss,
    Method::FclRss,
];

impl Method {
    /// Name in the CSV.
    pub(super) fn key(self) -> &'static str {
        match self {
            Method::Rev => "revdist",
            Method::RevTol0 => "revdist_tol0",
            Method::RevRefined => "revdist_refined",
            Method::FclObbrss => "fcl_obbrss",
            Method::FclRss => "fcl_rss",
        }
    }

    /// Name in the tables and legends.
    pub(super) fn label(self) -> &'static str {
        match self {
            Method::Rev => "revdist, default tolerance",
            Method::RevTol0 => "revdist, tolerance 0",
            Method::RevRefined => "revdist, refined",
            Method::FclObbrss => "FCL OBBRSS",
            Method::FclRss => "FCL RSS",
        }
    }

    pub(super) fn is_fcl(self) -> bool {
        matches!(self, Method::FclObbrss | Method::FclRss)
    }

    pub(super) fn options(self) -> QueryOptions {
        QueryOptions {
            tolerance: if self == Method::RevTol0 {
                Tolerance::Absolute(0.0)
            } else {
                Tolerance::Trees
            },
            refine: self == Method::RevRefined,
            ..QueryOptions::default()
        }
    }
}

impl Field for Method {
    fn text(&self) -> String {
        self.key().to_owned()
    }
    fn parse(cell: &str) -> Result<Self, String> {
        METHODS
            .into_iter()
            .find(|m| m.key() == cell)
            .ok_or_else(|| format!("'{cell}' is not a method"))
    }
}
impl Scalar for Method {}
