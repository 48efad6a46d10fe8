//! The pawn thrown at the cup stops at its first contact.
//!
//! The pawn flies from the left towards the cup's rim, spinning about a tilted axis; the
//! time-of-impact search (`revdist::toi`) certifies that the solids are apart for every
//! `t < t_lower` and touching at `t_upper`. The pawn is stopped at `t_lower`, the last pose
//! certified free of contact (the "stop at first contact" effect a simulation wants: no
//! tunnelling, no interpenetration), and the distance there is checked with a fresh query.
//!
//! Run: `cargo run --release --example throw_pawn`

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use revdist::models::model;
use revdist::query::{try_distance, QueryOptions};
use revdist::solid::Solid;
use revdist::toi::{time_of_impact, Motion, ToiOptions, ToiOutcome};
use std::sync::Arc;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let eps = 1e-4;
    let cup = Solid::from_profile(Arc::new(model("cup")?), eps)?;
    let pawn = Solid::from_profile(Arc::new(model("pawn")?), eps)?;
    let still = Motion::fixed(Isometry3::identity())?;
    let start = Isometry3::from_parts(
        Translation3::new(-4.0, 0.3, 1.5),
        UnitQuaternion::from_scaled_axis(Vector3::y() * 1.2),
    );
    let end = Isometry3::from_parts(
        Translation3::new(1.0, 0.0, 0.4),
        UnitQuaternion::from_scaled_axis(Vector3::new(0.3, 1.0, 0.2).normalize() * 2.8),
    );
    let throw = Motion::new(start, end)?;
    let r = time_of_impact(&cup, &still, &pawn, &throw, &ToiOptions::default())?;
    println!(
        "outcome {} after {} distance queries (speed bound {:.3} per unit time)",
        r.outcome.name(),
        r.queries,
        r.speed_bound
    );
    if r.outcome != ToiOutcome::Contact {
        println!("the pawn never certainly touches the cup on this throw");
        return Ok(());
    }
    let t_upper = r.t_upper.unwrap_or(1.0);
    println!("first contact in t = [{:.9}, {:.9}]", r.t_lower, t_upper);
    if let Some(c) = &r.contact {
        println!(
            "witness at t_upper: cup {:.6?}, pawn {:.6?}",
            c.point_a.coords.as_slice(),
            c.point_b.coords.as_slice()
        );
    }
    // Stop the pawn at t_lower: certified apart for every earlier time.
    let stopped = pawn.with_pose(throw.pose_at(r.t_lower));
    let d = try_distance(&cup, &stopped, &QueryOptions::default())?;
    println!(
        "pawn stopped at t = {:.9}: distance to the cup in [{:.3e}, {:.3e}], overlap {}",
        r.t_lower, d.lower, d.upper, d.overlap
    );
    Ok(())
}
