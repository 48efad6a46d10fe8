//! `verify oracle`: one query checked against the oracle, with its shapes loaded by name or
//! from a file and B's pose parsed from JSON ([`verify::oracle`]).

use clap::Args;

#[derive(Args)]
pub struct OracleArgs {
    a: String,
    b: String,
    #[arg(long, default_value = "{}")]
    pose_b: String,
    #[arg(long, default_value_t = 1e-4)]
    eps: f64,
    /// Target width of the query's interval (default: the trees' accuracy).
    #[arg(long)]
    tolerance: Option<f64>,
    /// Refine the query's witnesses on the exact surfaces.
    #[arg(long)]
    refine: bool,
}

impl OracleArgs {
    pub fn run(self) {
        if let Err(e) = oracle_command(
            &self.a,
            &self.b,
            &self.pose_b,
            self.eps,
            self.tolerance,
            self.refine,
        ) {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    }
}

/// A shape by any name the campaigns print (see `verify::queries::pool_shape`) or a profile
/// file.
fn load(spec: &str) -> Result<revdist::profile::Profile, String> {
    if let Some(p) = verify::queries::pool_shape(spec) {
        return p.map_err(|e| format!("'{spec}': {e}"));
    }
    let path = std::path::Path::new(spec);
    let looks_like_a_file = path.exists()
        || path.components().count() > 1
        || matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("toml" | "json")
        );
    if looks_like_a_file {
        return revdist::profile_file::load_path(path).map_err(|e| format!("'{spec}': {e}"));
    }
    Err(format!(
        "unknown shape '{spec}': give a profile file (.toml or .json) or a shape name the \
         campaigns print: {}",
        verify::queries::pool_shape_names()
    ))
}

/// Parses `{"translation": [..], "rotation": [w, x, y, z]}` (both optional).
fn parse_pose(s: &str) -> Result<verify::queries::PoseSpec, String> {
    let nums = |key: &str, n: usize| -> Result<Option<Vec<f64>>, String> {
        let Some(i) = s.find(&format!("\"{key}\"")) else {
            return Ok(None);
        };
        let rest = &s[i..];
        let (open, close) = (
            rest.find('[').ok_or("missing '['")?,
            rest.find(']').ok_or("missing ']'")?,
        );
        let v: Vec<f64> = rest[open + 1..close]
            .split(',')
            .map(|x| x.trim().parse::<f64>().map_err(|e| format!("{key}: {e}")))
            .collect::<Result<_, _>>()?;
        if v.len() != n {
            return Err(format!("{key} needs {n} numbers"));
        }
        Ok(Some(v))
    };
    let t = nums("translation", 3)?.unwrap_or(vec![0.0; 3]);
    let r = nums("rotation", 4)?.unwrap_or(vec![1.0, 0.0, 0.0, 0.0]);
    Ok(verify::queries::PoseSpec {
        translation: [t[0], t[1], t[2]],
        rotation: [r[0], r[1], r[2], r[3]],
    })
}

fn oracle_command(
    a: &str,
    b: &str,
    pose: &str,
    eps: f64,
    tolerance: Option<f64>,
    refine: bool,
) -> Result<(), String> {
    let (pa, pb) = (load(a)?, load(b)?);
    let pose = parse_pose(pose)?;
    let (d, o, v, tq, to) = verify::queries::single(&pa, &pb, &pose, eps, tolerance, refine)?;
    println!(
        "query   value {:.12e} interval [{:.12e}, {:.12e}] overlap {} ({:.3} ms)",
        d.value,
        d.lower,
        d.upper,
        d.overlap,
        tq.as_secs_f64() * 1e3
    );
    println!(
        "        point_a {:?} point_b {:?}",
        d.point_a.coords.as_slice(),
        d.point_b.coords.as_slice()
    );
    println!(
        "oracle  surface distance in [{:.12e}, {:.12e}], overlap {} (a in b {}, b in a {}), min signed {:.3e}; {} cells, {} refinements{} ({:.1} ms)",
        o.lower,
        o.upper,
        o.overlap(),
        o.a_in_b,
        o.b_in_a,
        o.min_signed,
        o.cells,
        o.refinements,
        if o.budget_hit { ", budget hit" } else { "" },
        to.as_secs_f64() * 1e3
    );
    println!(
        "        point_a {:?} point_b {:?}",
        o.point_a.coords.as_slice(),
        o.point_b.coords.as_slice()
    );
    if let Some(p) = o.deep_point {
        println!(
            "        deepest boundary sample inside the other solid: {:?} (depth {:.3e})",
            p.coords.as_slice(),
            -o.min_signed
        );
    }
    if v.is_empty() {
        println!("no violations");
    }
    for x in &v {
        println!(
            "VIOLATION {}: {} (excess {:.3e})",
            x.check.name(),
            x.detail,
            x.excess
        );
    }
    Ok(())
}
