//! revdist: minimum distance between solids of revolution.
//!
//! Implements S.-H. Son, S.-H. Yoon, M.-S. Kim, G. Elber, *Efficient Minimum Distance
//! Computation for Solids of Revolution*, Computer Graphics Forum 39(2), 2020: a planar
//! profile curve in the (rho, z) half-plane is split into spirals, each approximated by a
//! tree of G1 biarcs with a guaranteed error bound; revolving the arcs gives a bounding
//! volume hierarchy of fat toroidal patches, and the distance between two patches reduces
//! to the binormals of two circles in space.
//!
//! Data flows one way: [`nurbs`] curves form a [`profile`] (built-in profiles live in
//! [`models`]); [`biarc`] trees approximate it; [`bvh`] revolves them into the hierarchy of
//! patches a [`solid`] holds; [`query`] measures two posed solids. Every slack and tolerance
//! of the query is in [`tolerances`].

pub mod biarc;
pub mod bvh;
pub mod circle;
pub mod limits;
pub mod models;
pub mod nearest;
pub mod num;
pub mod nurbs;
pub mod poly;
pub mod profile;
pub mod profile_file;
pub mod query;
pub mod request;
pub mod rng;
pub mod solid;
pub mod svg;
pub mod tessellate;
#[cfg(test)]
pub(crate) mod test_rng;
pub mod toi;
pub mod tolerances;
