//! Profile: a chain of NURBS pieces bounding a region of the (rho, z) half-plane. Skeleton.
use crate::nurbs::NurbsCurve;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileKind {
    Closed,
    OpenOnAxis,
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProfileError {
    #[error("placeholder")]
    Placeholder,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    name: String,
    pieces: Vec<NurbsCurve>,
    kind: ProfileKind,
}

impl Profile {
    pub fn new(name: impl Into<String>, pieces: Vec<NurbsCurve>) -> Result<Self, ProfileError> {
        let _ = (name.into(), pieces);
        todo!()
    }
    pub fn name(&self) -> &str {
        &self.name
    }
    pub fn pieces(&self) -> &[NurbsCurve] {
        &self.pieces
    }
    pub fn kind(&self) -> ProfileKind {
        self.kind
    }
}
