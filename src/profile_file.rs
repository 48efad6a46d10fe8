//! The TOML profile format, so that profiles are portable between tools.
//!
//! ```toml
//! name = "quarter-disk"
//!
//! [[piece]]                       # one table per NURBS piece, joined end to start
//! degree = 2
//! knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]
//! points = [[0.0, -1.0], [1.0, -1.0], [1.0, 0.0]]   # [rho, z] control points, rho >= 0
//! weights = [1.0, 0.7071067811865476, 1.0]         # optional: rational when present
//!
//! [[piece]]
//! degree = 1
//! knots = [0.0, 0.0, 1.0, 1.0]
//! points = [[1.0, 0.0], [0.0, 0.0]]
//! ```
//!
//! Exactly these names are accepted: top-level `name` and `piece`; per piece `degree`,
//! `knots`, `points` and the optional `weights`. Anything else is an error, as is every
//! invalid curve ([`CurveError`]) or profile ([`ProfileError`]). [`to_toml_string`] writes
//! numbers in Rust's shortest round-trip form, so reading back gives bit-identical data.

use crate::nurbs::{CurveError, NurbsCurve};
use crate::profile::{Profile, ProfileError};
use nalgebra::Point2;
use serde::Deserialize;
use std::fmt::Write as _;

/// Why a profile file could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProfileFileError {
    /// Not TOML, an unknown field, a missing field or a value of the wrong type; `line` is
    /// where the parser stopped (1-based), when it says.
    #[error("malformed profile file{}: {message}", line.map(|l| format!(" (line {l})")).unwrap_or_default())]
    Syntax {
        message: String,
        line: Option<usize>,
    },
    /// A piece is not a valid NURBS curve; `line` is where its table starts.
    #[error("piece {piece} (line {line}): {source}")]
    Piece {
        piece: usize,
        line: usize,
        #[source]
        source: CurveError,
    },
    /// A control point does not have exactly two coordinates `[rho, z]`.
    #[error("piece {piece} (line {line}), control point {index}: expected 2 coordinates [rho, z], got {found}")]
    PointArity {
        piece: usize,
        line: usize,
        index: usize,
        found: usize,
    },
    /// The pieces do not form a valid profile.
    #[error("invalid profile: {0}")]
    Profile(#[from] ProfileError),
    /// The file could not be read.
    #[error("cannot read {path}: {message}")]
    Io { path: String, message: String },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileRepr {
    name: String,
    piece: Vec<toml::Spanned<PieceRepr>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PieceRepr {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<Vec<f64>>,
    weights: Option<Vec<f64>>,
}

/// 1-based line of byte offset `at` in `text`.
fn line_of(text: &str, at: usize) -> usize {
    1 + text.as_bytes()[..at.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
}

/// Parses and validates a profile from TOML text.
pub fn from_toml_str(text: &str) -> Result<Profile, ProfileFileError> {
    let (name, pieces) = pieces_from_toml_str(text)?;
    Ok(Profile::new(name, pieces)?)
}

/// [`from_toml_str`] for a degenerate chain ([`Profile::allowing_self_contact`]): a
/// regression profile whose chain touches or folds back onto itself, kept for robustness
/// tests of the trees and queries.
pub fn from_toml_str_allowing_self_contact(text: &str) -> Result<Profile, ProfileFileError> {
    let (name, pieces) = pieces_from_toml_str(text)?;
    Ok(Profile::allowing_self_contact(name, pieces)?)
}

/// The name and the validated pieces of a profile file, without the checks of the chain
/// ([`Profile::new`] or, for robustness tests on degenerate chains,
/// [`Profile::allowing_self_contact`]).
pub fn pieces_from_toml_str(text: &str) -> Result<(String, Vec<NurbsCurve>), ProfileFileError> {
    let repr: FileRepr = toml::from_str(text).map_err(|e| ProfileFileError::Syntax {
        message: e.message().trim_end().to_string(),
        line: e.span().map(|s| line_of(text, s.start)),
    })?;
    let pieces = repr
        .piece
        .into_iter()
        .enumerate()
        .map(|(piece, spanned)| {
            let line = line_of(text, spanned.span().start);
            let p = spanned.into_inner();
            let points = p
                .points
                .iter()
                .enumerate()
                .map(|(index, q)| match q[..] {
                    [r, z] => Ok(Point2::new(r, z)),
                    _ => Err(ProfileFileError::PointArity {
                        piece,
                        line,
                        index,
                        found: q.len(),
                    }),
                })
                .collect::<Result<Vec<_>, _>>()?;
            NurbsCurve::new(p.degree, p.knots, points, p.weights).map_err(|source| {
                ProfileFileError::Piece {
                    piece,
                    line,
                    source,
                }
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok((repr.name, pieces))
}

/// Reads and validates a profile file.
pub fn load_path(path: &std::path::Path) -> Result<Profile, ProfileFileError> {
    let text = std::fs::read_to_string(path).map_err(|e| ProfileFileError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })?;
    from_toml_str(&text)
}

/// Writes a profile as TOML that [`from_toml_str`] reads back bit-identically.
pub fn to_toml_string(profile: &Profile) -> String {
    let mut out = String::new();
    let name = toml::Value::String(profile.name().to_string());
    writeln!(out, "name = {name}").unwrap();
    for c in profile.pieces() {
        out.push_str("\n[[piece]]\n");
        writeln!(out, "degree = {}", c.degree()).unwrap();
        writeln!(out, "knots = [{}]", join(c.knots().iter().map(num))).unwrap();
        let pts = c
            .points()
            .iter()
            .map(|q| format!("[{}, {}]", num(&q.x), num(&q.y)));
        writeln!(out, "points = [{}]", join(pts)).unwrap();
        if let Some(w) = c.weights() {
            writeln!(out, "weights = [{}]", join(w.iter().map(num))).unwrap();
        }
    }
    out
}

/// Shortest representation that parses back to the same f64 (always with a `.` or exponent,
/// so TOML reads it as a float).
fn num(v: &f64) -> String {
    format!("{v:?}")
}

fn join(items: impl Iterator<Item = String>) -> String {
    items.collect::<Vec<_>>().join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::ProfileKind;

    const QUARTER_DISK: &str = r#"
name = "quarter-disk"

[[piece]]
degree = 2
knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]
points = [[0.0, -1.0], [1.0, -1.0], [1.0, 0.0]]
weights = [1.0, 0.7071067811865476, 1.0]

[[piece]]
degree = 1
knots = [0.0, 0.0, 1.0, 1.0]
points = [[1.0, 0.0], [0.0, 0.0]]
"#;

    #[test]
    fn reads_the_documented_example_and_round_trips() {
        let p = from_toml_str(QUARTER_DISK).unwrap();
        assert_eq!(p.name(), "quarter-disk");
        assert_eq!(p.kind(), ProfileKind::OpenOnAxis);
        assert_eq!(p.pieces().len(), 2);
        let text = to_toml_string(&p);
        assert_eq!(from_toml_str(&text).unwrap(), p);
    }

    #[test]
    fn round_trip_is_bit_exact_for_awkward_numbers() {
        let pts = vec![
            Point2::new(0.0, 1e-300),
            Point2::new(std::f64::consts::PI, -0.1 - 0.2),
            Point2::new(1e100, 1.0 / 3.0),
            Point2::new(0.0, 7.0),
        ];
        let c = NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 1., 1., 1., 1.],
            pts,
            Some(vec![1.0, 1.0 / 7.0, 3e-5, 1.0]),
        )
        .unwrap();
        // At a size of 1e100 the loop out and back is a fold-back within the tolerance:
        // only the chain is checked.
        let p = Profile::allowing_self_contact("awkward \"name\"", vec![c]).unwrap();
        let (name, pieces) = pieces_from_toml_str(&to_toml_string(&p)).unwrap();
        assert_eq!(Profile::allowing_self_contact(name, pieces).unwrap(), p);
    }

    fn err(text: &str) -> ProfileFileError {
        from_toml_str(text).unwrap_err()
    }

    fn with(piece: &str) -> String {
        format!("name = \"x\"\n[[piece]]\n{piece}")
    }

    #[test]
    fn every_bad_input_names_its_problem() {
        let e = err("name = \"x\"\ncolour = 3\n");
        assert!(
            matches!(&e, ProfileFileError::Syntax { message: m, .. } if m.contains("colour")),
            "{e}"
        );
        let e = err(&with("degree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[0.0, 0.0], [1.0, 1.0]]\ncolor = 1\n"));
        assert!(
            matches!(&e, ProfileFileError::Syntax { message: m, .. } if m.contains("color")),
            "{e}"
        );
        let e = err("name = \"x\"\n");
        assert!(
            matches!(&e, ProfileFileError::Syntax { message: m, .. } if m.contains("piece")),
            "{e}"
        );
        let e = err("this is not toml");
        assert!(matches!(e, ProfileFileError::Syntax { .. }));
        let e = err(&with(
            "degree = 1\nknots = [0.0, 1.0, 1.0]\npoints = [[0.0, 0.0], [1.0, 1.0]]\n",
        ));
        assert!(
            matches!(
                e,
                ProfileFileError::Piece {
                    piece: 0,
                    line: 2,
                    source: CurveError::WrongKnotCount { .. }
                }
            ),
            "{e}"
        );
        let e = err(&with("degree = 1\nknots = [0.0, 0.0, 1.0, 0.5, 1.0]\npoints = [[0.0, 0.0], [1.0, 1.0], [0.0, 2.0]]\n"));
        assert!(
            matches!(
                e,
                ProfileFileError::Piece {
                    source: CurveError::DecreasingKnots { .. },
                    ..
                }
            ),
            "{e}"
        );
        let e = err(&with("degree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[0.0, 0.0], [0.0, 1.0]]\nweights = [1.0, -2.0]\n"));
        assert!(
            matches!(
                e,
                ProfileFileError::Piece {
                    source: CurveError::NonPositiveWeight { index: 1, .. },
                    ..
                }
            ),
            "{e}"
        );
        let e = err(&with(
            "degree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[0.0, 0.0], [nan, 1.0]]\n",
        ));
        assert!(
            matches!(
                e,
                ProfileFileError::Piece {
                    source: CurveError::NonFinite { .. },
                    ..
                }
            ),
            "{e}"
        );
        let e = err(&with(
            "degree = 1\nknots = [0.0, 0.0, inf, inf]\npoints = [[0.0, 0.0], [0.0, 1.0]]\n",
        ));
        assert!(
            matches!(
                e,
                ProfileFileError::Piece {
                    source: CurveError::NonFinite { what: "knot", .. },
                    ..
                }
            ),
            "{e}"
        );
        let e = err(&with(
            "degree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[0.0, 0.0], [-1.0, 1.0]]\n",
        ));
        assert!(
            matches!(
                e,
                ProfileFileError::Profile(ProfileError::NegativeRho { .. })
            ),
            "{e}"
        );
        let gap = "degree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[0.0, 0.0], [1.0, 1.0]]\n[[piece]]\ndegree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[1.0, 1.5], [0.0, 2.0]]\n";
        assert!(matches!(
            err(&with(gap)),
            ProfileFileError::Profile(ProfileError::Gap { .. })
        ));
        let e = err(&with(
            "degree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[0.5, 0.0], [1.0, 1.0]]\n",
        ));
        assert!(
            matches!(
                e,
                ProfileFileError::Profile(ProfileError::NotClosedNorOnAxis { .. })
            ),
            "{e}"
        );
        let e = err(&with(
            "degree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[0.0, 1.0], [0.0, 1.0]]\n",
        ));
        assert!(
            matches!(e, ProfileFileError::Profile(ProfileError::TooSmall { .. })),
            "{e}"
        );
        let e = err(&with("degree = -1\nknots = []\npoints = []\n"));
        assert!(matches!(e, ProfileFileError::Syntax { .. }), "{e}");
        assert!(err(&with(
            "degree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[0.0, 0.0], [1.0, 1.0]]\n"
        ))
        .to_string()
        .contains("neither closed"));
    }

    proptest::proptest! {
        #[test]
        fn any_valid_profile_round_trips(
            inner in proptest::collection::vec((0.0f64..10.0, -10.0f64..10.0, 0.01f64..100.0), 1..8),
            z0 in -5.0f64..5.0,
            z1 in -5.0f64..5.0,
        ) {
            let degree = inner.len().min(3);
            let mut pts = vec![Point2::new(0.0, z0)];
            pts.extend(inner.iter().map(|&(r, z, _)| Point2::new(r, z)));
            pts.push(Point2::new(0.0, z1));
            let mut w = vec![1.0];
            w.extend(inner.iter().map(|&(_, _, w)| w));
            w.push(1.0);
            let n = pts.len();
            let mut knots = vec![0.0; degree + 1];
            knots.extend((1..n - degree).map(|i| i as f64 / (n - degree) as f64));
            knots.extend(vec![1.0; degree + 1]);
            let c = NurbsCurve::new(degree, knots, pts, Some(w)).unwrap();
            if let Ok(p) = Profile::new("random", vec![c]) {
                proptest::prop_assert_eq!(from_toml_str(&to_toml_string(&p)).unwrap(), p);
            }
        }
    }

    #[test]
    fn missing_file_is_an_io_error() {
        let e = load_path(std::path::Path::new("/nonexistent/revdist.toml")).unwrap_err();
        assert!(matches!(e, ProfileFileError::Io { .. }));
    }
}
