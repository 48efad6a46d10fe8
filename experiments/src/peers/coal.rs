//! coal 3 through its own process (`coal_peer`, cpp/coal/coal_peer.cc, built by
//! experiments/build.rs): never in this process, which links Debian's FCL (the two abort with a
//! double free). The program reads shapes and poses on stdin and answers with distances and
//! per-query times; see the protocol at the top of the C++ file.

use super::convex::Primitive;
use nalgebra::Isometry3;
use revdist::tessellate::CertifiedMesh;
use std::fmt::Write as _;
use std::io::{BufRead, BufReader, Write};
use std::path::PathBuf;
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

/// Environment variable that overrides, at run time, the path of the `coal_peer` program
/// built into the binary (a path that does not exist makes coal "missing": the tests use it).
pub const PROGRAM_ENV: &str = "REVDIST_COAL_PEER";

/// What the coal columns say when the program is not there.
pub const MISSING_HINT: &str = "coal missing: run scripts/deps.sh";

/// Why coal cannot be used: the message a table prints in its columns.
#[derive(Debug, Clone)]
pub struct Missing(pub String);

impl std::fmt::Display for Missing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Missing {}

/// The `coal_peer` program: the run-time override, else the one the build compiled.
fn program() -> Result<PathBuf, Missing> {
    let path = match std::env::var_os(PROGRAM_ENV) {
        Some(p) => PathBuf::from(p),
        None => match option_env!("REVDIST_COAL_PEER") {
            Some(p) => PathBuf::from(p),
            None => {
                let why = option_env!("REVDIST_COAL_PEER_MISSING").unwrap_or(MISSING_HINT);
                return Err(Missing(why.to_owned()));
            }
        },
    };
    if path.is_file() {
        Ok(path)
    } else {
        Err(Missing(format!(
            "{MISSING_HINT} (no program at {})",
            path.display()
        )))
    }
}

/// A shape coal built: its build time and memory as coal reports them.
#[derive(Debug, Clone, Copy, Default)]
pub struct Built {
    pub build_ms: f64,
    pub bytes: usize,
}

/// One query's answer: coal's distance and the time it took.
#[derive(Debug, Clone, Copy)]
pub struct Answer {
    pub distance: f64,
    pub us: f64,
    /// Signed queries: coal's unit normal from A to B (world frame); B moved by
    /// `-distance` along it touches A.
    pub normal: Option<[f64; 3]>,
}

/// A running `coal_peer` process.
pub struct CoalPeer {
    child: Child,
    input: ChildStdin,
    output: BufReader<ChildStdout>,
    /// coal's version string (`COAL_VERSION`).
    pub version: String,
    /// coal's default GJK tolerance (`GJK_DEFAULT_TOLERANCE`), as the program reports it.
    pub gjk_tolerance: f64,
}

type Res<T> = Result<T, Box<dyn std::error::Error>>;

impl CoalPeer {
    /// Starts the program; [`Missing`] when it is not built or not found.
    pub fn start() -> Res<CoalPeer> {
        let path = program()?;
        let mut child = Command::new(&path)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .map_err(|e| {
                Missing(format!(
                    "{MISSING_HINT} ({} did not start: {e})",
                    path.display()
                ))
            })?;
        let input = child.stdin.take().ok_or("coal_peer: no stdin")?;
        let output = BufReader::new(child.stdout.take().ok_or("coal_peer: no stdout")?);
        let mut peer = CoalPeer {
            child,
            input,
            output,
            version: String::new(),
            gjk_tolerance: f64::NAN,
        };
        peer.send("version\n")?;
        let line = peer.line()?;
        let f: Vec<&str> = line.split_whitespace().collect();
        match f.as_slice() {
            ["version", v, tol] => {
                peer.version = (*v).to_owned();
                peer.gjk_tolerance = tol.parse()?;
            }
            _ => return Err(format!("coal_peer: unexpected reply '{line}'").into()),
        }
        Ok(peer)
    }

    fn send(&mut self, text: &str) -> Res<()> {
        self.input
            .write_all(text.as_bytes())
            .and_then(|()| self.input.flush())
            .map_err(|e| format!("coal_peer stopped reading its input: {e}").into())
    }

    fn line(&mut self) -> Res<String> {
        let mut s = String::new();
        if self.output.read_line(&mut s)? == 0 {
            return Err("coal_peer ended without an answer (see its error above)".into());
        }
        Ok(s.trim_end().to_owned())
    }

    fn built(&mut self, id: &str) -> Res<Built> {
        let line = self.line()?;
        let f: Vec<&str> = line.split_whitespace().collect();
        match f.as_slice() {
            ["shape", i, ms, bytes] if *i == id => Ok(Built {
                build_ms: ms.parse()?,
                bytes: bytes.parse()?,
            }),
            _ => Err(format!("coal_peer: unexpected reply '{line}' to shape {id}").into()),
        }
    }

    /// Builds coal's `BVHModel<OBBRSS>` of a certified mesh under the name `id`.
    pub fn mesh(&mut self, id: &str, cm: &CertifiedMesh) -> Res<Built> {
        check_id(id)?;
        let m = &cm.mesh;
        let mut s = String::with_capacity(64 * (m.vertices.len() + m.triangles.len()));
        let _ = writeln!(s, "mesh {id} {} {}", m.vertices.len(), m.triangles.len());
        for v in &m.vertices {
            let _ = writeln!(s, "{:e} {:e} {:e}", v.x, v.y, v.z);
        }
        for t in &m.triangles {
            let _ = writeln!(s, "{} {} {}", t[0], t[1], t[2]);
        }
        self.send(&s)?;
        self.built(id)
    }

    /// Creates coal's exact primitive `p` under the name `id`.
    pub fn primitive(&mut self, id: &str, p: &Primitive) -> Res<Built> {
        check_id(id)?;
        let s = match *p {
            Primitive::Sphere { r, zc } => format!("sphere {id} {r:e} {zc:e}\n"),
            Primitive::Capsule { r, lz, zc } => format!("capsule {id} {r:e} {lz:e} {zc:e}\n"),
            Primitive::Cylinder { r, lz, zc } => format!("cylinder {id} {r:e} {lz:e} {zc:e}\n"),
            Primitive::Cone { r, lz, zc } => format!("cone {id} {r:e} {lz:e} {zc:e}\n"),
        };
        self.send(&s)?;
        self.built(id)
    }

    /// coal's distance from shape `a` (at the identity) to shape `b` at each pose, each query
    /// timed by the program (one after the other: blocked).
    pub fn query(&mut self, a: &str, b: &str, poses: &[Isometry3<f64>]) -> Res<Vec<Answer>> {
        self.queries("query", a, b, poses)
    }

    /// coal's *signed* distance (its default request: EPA's penetration depth, negated, where
    /// the shapes overlap) from shape `a` (at the identity) to shape `b` at each pose, timed
    /// as [`CoalPeer::query`].
    pub fn signed_query(&mut self, a: &str, b: &str, poses: &[Isometry3<f64>]) -> Res<Vec<Answer>> {
        self.queries("signed", a, b, poses)
    }

    fn queries(
        &mut self,
        command: &str,
        a: &str,
        b: &str,
        poses: &[Isometry3<f64>],
    ) -> Res<Vec<Answer>> {
        let mut s = format!("{command} {a} {b} {}\n", poses.len());
        for p in poses {
            let (q, t) = (p.rotation.quaternion(), p.translation.vector);
            let _ = writeln!(
                s,
                "{:e} {:e} {:e} {:e} {:e} {:e} {:e}",
                q.w, q.i, q.j, q.k, t.x, t.y, t.z
            );
        }
        self.send(&s)?;
        let mut answers = Vec::with_capacity(poses.len());
        for _ in poses {
            let line = self.line()?;
            let f: Vec<&str> = line.split_whitespace().collect();
            match f.as_slice() {
                ["d", d, ns] => answers.push(Answer {
                    distance: d.parse()?,
                    us: ns.parse::<f64>()? * 1e-3,
                    normal: None,
                }),
                ["d", d, ns, x, y, z] => answers.push(Answer {
                    distance: d.parse()?,
                    us: ns.parse::<f64>()? * 1e-3,
                    normal: Some([x.parse()?, y.parse()?, z.parse()?]),
                }),
                _ => return Err(format!("coal_peer: unexpected reply '{line}'").into()),
            }
        }
        match self.line()?.as_str() {
            "end" => Ok(answers),
            other => Err(format!("coal_peer: expected 'end', got '{other}'").into()),
        }
    }
}

/// Shape names go into a whitespace-separated protocol: no blanks.
fn check_id(id: &str) -> Res<()> {
    if id.is_empty() || id.contains(char::is_whitespace) {
        return Err(format!("coal shape name '{id}' must be one word").into());
    }
    Ok(())
}

impl Drop for CoalPeer {
    fn drop(&mut self) {
        let _ = self.input.write_all(b"quit\n");
        let _ = self.input.flush();
        let _ = self.child.wait();
    }
}
