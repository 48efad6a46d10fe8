//! Allocation-free kernels on Bernstein coefficient slices (polynomials on [0, 1]).
//!
//! Every function takes its scratch space from the caller, so the circle/circle hot path can
//! run on stack arrays. [`crate::poly::bernstein`] wraps these kernels for owned polynomials.

/// Relative rounding-noise factor for evaluating a Bernstein polynomial of degree n: the
/// computed value differs from the exact one by at most about `2 n eps sum|b_i| B_i(t)`
/// (de Casteljau / Horner backward-error bound, Farouki & Rajan 1987); we take 4 n eps for
/// headroom. A value below this bound is indistinguishable from zero.
pub const EVAL_NOISE_PER_DEGREE: f64 = 4.0 * f64::EPSILON;

/// Safety cap on Newton/bisection steps for one isolated root (bisection alone needs at most
/// 64 steps to reach adjacent doubles on [0, 1]).
const MAX_REFINE_STEPS: usize = 100;

/// Capacity of the subdivision stack. Depth-first bisection of [0, 1] down to widths of
/// 2^-60 never holds more than 61 pending intervals.
const STACK_CAP: usize = 64;

/// Smallest interval width bisection will produce (below this, doubles are adjacent).
const MIN_WIDTH: f64 = 1e-15;

/// Rows of the binomial table used by `horner_bernstein` (degrees below this avoid a
/// division per term).
pub const BINOM_ROWS: usize = 17;

/// `BINOM[n][k]` = C(n, k) (exact in f64 for n < 17).
pub const BINOM: [[f64; BINOM_ROWS]; BINOM_ROWS] = {
    let mut t = [[0.0; BINOM_ROWS]; BINOM_ROWS];
    let mut n = 0;
    while n < BINOM_ROWS {
        t[n][0] = 1.0;
        let mut k = 1;
        while k <= n {
            t[n][k] = t[n - 1][k - 1] + if k < n { t[n - 1][k] } else { 0.0 };
            k += 1;
        }
        n += 1;
    }
    t
};

/// Evaluates the Bernstein polynomial with coefficients `c` at `t` in O(n) (Horner on
/// t/(1-t), mirrored for t > 1/2 so the ratio stays <= 1).
pub fn eval(c: &[f64], t: f64) -> f64 {
    horner_bernstein(c, t, |x| x)
}

/// `sum |b_i| B_i(t)`: the scale against which rounding in [`eval`] is measured.
pub fn eval_abs(c: &[f64], t: f64) -> f64 {
    horner_bernstein(c, t, f64::abs)
}

/// `sum map(b_i) B_i(t)` by Horner's rule in the ratio t/(1-t) (or its mirror).
#[inline]
fn horner_bernstein(c: &[f64], t: f64, map: impl Fn(f64) -> f64) -> f64 {
    let n = c.len() - 1;
    if n == 0 {
        return map(c[0]);
    }
    let (s, r, rev) = if t <= 0.5 {
        (1.0 - t, t / (1.0 - t), false)
    } else {
        (t, (1.0 - t) / t, true)
    };
    let coef = |i: usize| map(if rev { c[n - i] } else { c[i] });
    let mut acc = coef(n);
    if n < BINOM_ROWS {
        let row = &BINOM[n];
        for i in (0..n).rev() {
            acc = acc * r + row[i] * coef(i);
        }
    } else {
        let mut binom = 1.0;
        for i in (0..n).rev() {
            binom = binom * (i + 1) as f64 / (n - i) as f64;
            acc = acc * r + binom * coef(i);
        }
    }
    acc * s.powi(n as i32)
}

/// Rounding-noise bound of [`eval`] at `t`, plus `coeff_noise` (the caller's absolute
/// uncertainty of each coefficient, which propagates with weight sum B_i = 1).
pub fn zero_tolerance(c: &[f64], t: f64, coeff_noise: f64) -> f64 {
    let n = (c.len() - 1).max(1) as f64;
    coeff_noise + EVAL_NOISE_PER_DEGREE * n * eval_abs(c, t)
}

/// Derivative coefficients (degree n-1) written to `out[..n]`: `n (b_{i+1} - b_i)`.
pub fn derivative_into(c: &[f64], out: &mut [f64]) {
    let n = c.len() - 1;
    for i in 0..n {
        out[i] = n as f64 * (c[i + 1] - c[i]);
    }
}

/// De Casteljau split at `t`: `left` gets the piece on [0, t], `right` the piece on [t, 1]
/// (both reparametrised to [0, 1]). `left`, `right` have the length of `c`.
pub fn split(c: &[f64], t: f64, left: &mut [f64], right: &mut [f64]) {
    let n = c.len() - 1;
    right.copy_from_slice(c);
    left[0] = c[0];
    for (k, l) in left.iter_mut().enumerate().skip(1) {
        for i in 0..=(n - k) {
            right[i] = (1.0 - t) * right[i] + t * right[i + 1];
        }
        *l = right[0];
    }
}

/// In-place de Casteljau: keeps the piece on [t, 1].
fn keep_right(c: &mut [f64], t: f64) {
    let n = c.len() - 1;
    for k in 1..=n {
        for i in 0..=(n - k) {
            c[i] = (1.0 - t) * c[i] + t * c[i + 1];
        }
    }
}

/// In-place de Casteljau: keeps the piece on [0, t].
fn keep_left(c: &mut [f64], t: f64) {
    let n = c.len() - 1;
    for k in 1..=n {
        for i in (k..=n).rev() {
            c[i] = (1.0 - t) * c[i - 1] + t * c[i];
        }
    }
}

/// Writes into `out` the coefficients of `c` restricted to [a, b] (0 <= a < b <= 1) and
/// reparametrised to [0, 1].
pub fn restrict_into(c: &[f64], a: f64, b: f64, out: &mut [f64]) {
    out.copy_from_slice(c);
    if b < 1.0 {
        keep_left(out, b);
    }
    if a > 0.0 {
        keep_right(out, a / b);
    }
}

/// Number of sign changes in the coefficient sequence, exact zeros skipped (Descartes'
/// rule in Bernstein form bounds the number of roots in (0, 1) by this count, with the same
/// parity).
pub fn sign_variations(c: &[f64]) -> usize {
    let mut count = 0;
    let mut last = 0.0f64;
    for &x in c {
        if x != 0.0 {
            if last != 0.0 && (x > 0.0) != (last > 0.0) {
                count += 1;
            }
            last = x;
        }
    }
    count
}

/// Scratch length needed by [`odd_roots_into`] for `n + 1` coefficients.
pub const fn odd_scratch_len(n_coeffs: usize) -> usize {
    2 * n_coeffs
}

/// Scratch length of [`odd_roots_guarded`] with a guard of `n_guard` coefficients.
pub const fn guarded_scratch_len(n_coeffs: usize, n_guard: usize) -> usize {
    2 * n_coeffs + n_guard
}

/// Finds the roots of odd multiplicity (sign changes) of `c` in the open interval (lo, hi)
/// of [0, 1], each to within `t_tol`, and passes them in increasing order to `sink`.
/// `scratch` must hold [`odd_scratch_len`] values. A piece whose coefficients are all within
/// `noise_abs` of zero is indistinguishable from the zero polynomial: it is not subdivided
/// further (its midpoint is reported if its end values differ in sign). Without this stop,
/// rounding noise around an even root would make every sub-piece show sign changes down to
/// `t_tol`.
///
/// Subdivision with the Bernstein sign-variation test: V = 0 discards a piece, V = 1 means
/// exactly one simple crossing, which a safeguarded Newton iteration converges on. Pieces
/// narrower than `t_tol` with V >= 2 report their midpoint when the end values differ in sign.
pub fn odd_roots_into(
    c: &[f64],
    lo: f64,
    hi: f64,
    t_tol: f64,
    noise_abs: f64,
    scratch: &mut [f64],
    sink: &mut impl FnMut(f64),
) {
    odd_roots_guarded(c, None, lo, hi, t_tol, noise_abs, scratch, sink);
}

/// [`odd_roots_into`], skipping every piece on which the optional `guard` polynomial
/// (same length as `c`, with its absolute noise) is bounded away from zero: its restricted
/// coefficients all exceed the noise with one sign. Used to look for even roots of `guard`
/// among the roots of its derivative `c` only where `guard` can vanish. `scratch` needs
/// [`odd_scratch_len`] + `guard.len()` values when a guard is given.
#[allow(clippy::too_many_arguments)]
pub fn odd_roots_guarded(
    c: &[f64],
    guard: Option<(&[f64], f64)>,
    lo: f64,
    hi: f64,
    t_tol: f64,
    noise_abs: f64,
    scratch: &mut [f64],
    sink: &mut impl FnMut(f64),
) {
    let mut roots_only = |found: Found| {
        if let Found::Root(x) = found {
            sink(x);
        }
    };
    odd_roots_flat(c, guard, lo, hi, t_tol, noise_abs, scratch, &mut roots_only);
}

/// What [`odd_roots_flat`] reports: a sign change, or a flat piece that may hide a pair.
#[derive(Debug, Clone, Copy)]
enum Found {
    Root(f64),
    Flat(f64, f64),
}

/// [`odd_roots_guarded`], also reporting ([`Found::Flat`]) every piece `[a, b]` that stopped as
/// indistinguishable from zero while its coefficients still change sign: such a piece may
/// hold a pair of roots closer than rounding can separate (the ends of one sign, the values
/// between them within the noise bound of the other), which a search for sign changes
/// alone loses.
#[allow(clippy::too_many_arguments)]
fn odd_roots_flat(
    c: &[f64],
    guard: Option<(&[f64], f64)>,
    lo: f64,
    hi: f64,
    t_tol: f64,
    noise_abs: f64,
    scratch: &mut [f64],
    report: &mut impl FnMut(Found),
) {
    let m = c.len();
    if m < 2 || hi <= lo {
        return;
    }
    let (piece, rest) = scratch.split_at_mut(m);
    let (rest, gpiece) = rest.split_at_mut(m);
    let tol = t_tol.max(MIN_WIDTH);
    let mut stack = [(0.0f64, 0.0f64); STACK_CAP];
    let mut top = 1;
    stack[0] = (lo, hi);
    while top > 0 {
        top -= 1;
        let (a, b) = stack[top];
        if let Some((g, g_noise)) = guard {
            let gp = &mut gpiece[..g.len()];
            restrict_into(g, a, b, gp);
            if gp.iter().all(|&x| x > g_noise) || gp.iter().all(|&x| x < -g_noise) {
                continue;
            }
        }
        restrict_into(c, a, b, piece);
        let (f0, f1) = (piece[0], piece[m - 1]);
        if f1 == 0.0 && b < hi {
            // A root exactly on the split point b (de Casteljau made it an exact zero):
            // the right neighbour starts with the same zero, so only this piece reports it,
            // when the sign changes across b.
            let left = piece
                .iter()
                .rev()
                .find(|&&x| x != 0.0)
                .copied()
                .unwrap_or(0.0);
            restrict_into(c, b, (2.0 * b - a).min(hi), dpiece_full(rest, m));
            let right = rest[..m]
                .iter()
                .find(|&&x| x != 0.0)
                .copied()
                .unwrap_or(0.0);
            restrict_into(c, a, b, piece);
            if left * right < 0.0 {
                report(Found::Root(b));
            }
        }
        let v = sign_variations(piece);
        if v == 0 {
            continue;
        }
        if piece.iter().all(|x| x.abs() <= noise_abs) {
            if f0 * f1 < 0.0 {
                report(Found::Root(0.5 * (a + b)));
            }
            report(Found::Flat(a, b));
            continue;
        }
        if v == 1 && f0 != 0.0 && f1 != 0.0 {
            let dpiece = &mut rest[..m - 1];
            derivative_into(piece, dpiece);
            let x = refine_bracketed(piece, dpiece, tol / (b - a));
            report(Found::Root(a + x * (b - a)));
            continue;
        }
        if b - a <= tol || top + 2 > STACK_CAP {
            if f0 * f1 < 0.0 {
                report(Found::Root(0.5 * (a + b)));
            }
            continue;
        }
        let mid = split_point(c, a, b);
        // Push right first so the left half is processed first (roots come out sorted).
        stack[top] = (mid, b);
        stack[top + 1] = (a, mid);
        top += 2;
    }
}

/// Fractions of a piece tried as split points, nearest the middle first.
const SPLIT_FRACTIONS: [f64; 5] = [0.5, 0.4375, 0.5625, 0.375, 0.625];

/// A split point near the middle of [a, b] where the sign of `c` is certain: |c(mid)| above
/// the evaluation rounding bound. A root within rounding of the split point would otherwise
/// sit on the boundary of both halves, where each half's end coefficient may get either
/// sign, and both sign-variation counts can miss it. When every candidate is within the
/// bound (a flat stretch), the one with the largest |c| is used.
fn split_point(c: &[f64], a: f64, b: f64) -> f64 {
    let mut best = (0.5 * (a + b), -1.0);
    // zero_tolerance(c, t, 0) <= this bound (sum |b_i| B_i(t) <= max |b_i|): values above it
    // are certain without the second evaluation.
    let n = (c.len() - 1).max(1) as f64;
    let cheap = EVAL_NOISE_PER_DEGREE * n * c.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for frac in SPLIT_FRACTIONS {
        let mid = a + frac * (b - a);
        let v = eval(c, mid).abs();
        if v > cheap || v > zero_tolerance(c, mid, 0.0) {
            return mid;
        }
        if v > best.1 {
            best = (mid, v);
        }
    }
    best.0
}

#[inline]
fn dpiece_full(rest: &mut [f64], m: usize) -> &mut [f64] {
    &mut rest[..m]
}

/// Converges on the single sign change of `q` in (0, 1) (q(0) q(1) < 0), returning the
/// local parameter to within `x_tol`. Newton from the control-polygon crossing, falling back
/// to bisection whenever a step leaves the bracket or fails to halve the residual.
fn refine_bracketed(q: &[f64], dq: &[f64], x_tol: f64) -> f64 {
    // Below a few ulps of [0, 1] Newton steps are rounding noise.
    let x_tol = x_tol.max(4.0 * f64::EPSILON);
    let n = q.len() - 1;
    // Values below the evaluation rounding bound are zero for all purposes: stop there
    // (Newton steps computed from such values are noise).
    let f_noise = EVAL_NOISE_PER_DEGREE * n as f64 * q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let neg_at_lo = q[0] < 0.0;
    let (mut x0, mut x1) = (0.0f64, 1.0f64);
    // Start where the control polygon crosses zero.
    let mut x = 0.5;
    for i in 0..n {
        if (q[i] < 0.0) != (q[i + 1] < 0.0) && q[i] != 0.0 {
            x = (i as f64 + q[i] / (q[i] - q[i + 1])) / n as f64;
            break;
        }
    }
    let mut dx_old = 1.0f64;
    for _ in 0..MAX_REFINE_STEPS {
        let f = eval(q, x);
        if f.abs() <= f_noise {
            return x;
        }
        if (f < 0.0) == neg_at_lo {
            x0 = x;
        } else {
            x1 = x;
        }
        if x1 - x0 <= x_tol {
            return 0.5 * (x0 + x1);
        }
        let df = eval(dq, x);
        let step = if df != 0.0 { f / df } else { f64::INFINITY };
        let xn = x - step;
        if xn > x0 && xn < x1 && (2.0 * step).abs() <= dx_old.abs() {
            dx_old = step;
            x = xn;
            if step.abs() <= x_tol {
                return x;
            }
        } else {
            dx_old = x1 - x0;
            x = 0.5 * (x0 + x1);
        }
    }
    x
}

/// Absolute noise of the coefficients of any restriction of `c` to a sub-interval: the
/// caller's `coeff_noise` plus de Casteljau rounding (convex combinations: at most
/// [`EVAL_NOISE_PER_DEGREE`] n times the largest coefficient).
pub fn noise_of(c: &[f64], coeff_noise: f64) -> f64 {
    let n = (c.len() - 1).max(1) as f64;
    let max = c.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    coeff_noise + EVAL_NOISE_PER_DEGREE * n * max
}

/// Kind of a root candidate collected by [`roots_into`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RootKind {
    /// The polynomial changes sign here.
    #[default]
    Odd,
    /// A derivative root or endpoint where the polynomial vanishes within its noise bound
    /// (even multiplicity, or a cluster of roots closer than rounding can resolve).
    Even,
}

/// Scratch length (in f64) needed by [`roots_into`] for `n + 1` coefficients.
pub const fn roots_scratch_len(n_coeffs: usize) -> usize {
    4 * n_coeffs
}

/// Candidate-buffer length needed by [`roots_into`] for `n + 1` coefficients: the odd roots
/// and the derivative's roots (at most `n` and `n - 1`), the two ends, and room for the two
/// ends of a few flat pieces.
pub const fn roots_candidate_len(n_coeffs: usize) -> usize {
    3 * n_coeffs + 2
}

/// All distinct real roots of `c` in [0, 1], including even multiplicity, each to within
/// `t_tol`, passed in increasing order to `sink` with their [`RootKind`].
///
/// Odd roots come from [`odd_roots_into`]. Even roots are sign changes of the derivative
/// (and the endpoints) where |p| <= [`zero_tolerance`] (`coeff_noise` is the caller's
/// absolute coefficient uncertainty). Candidates closer than `t_tol`, or separated only by
/// values within the noise bound when one of them is an even candidate, are merged (the even
/// candidate is kept: a derivative root locates a double root to full precision).
/// `scratch`: [`roots_scratch_len`] values; `cand`: [`roots_candidate_len`] entries.
pub fn roots_into(
    c: &[f64],
    t_tol: f64,
    coeff_noise: f64,
    scratch: &mut [f64],
    cand: &mut [(f64, RootKind)],
    sink: &mut impl FnMut(f64, RootKind),
) {
    root_clusters_into(
        c,
        t_tol,
        coeff_noise,
        scratch,
        cand,
        &mut |r: RootCluster| sink(r.root, r.kind),
    );
}

/// Whether `c` restricted to `[a, b]` has every coefficient within its noise bound
/// ([`noise_of`]): the piece cannot be told apart from zero. `scratch` holds `c.len()` values.
fn flat_between(c: &[f64], a: f64, b: f64, coeff_noise: f64, scratch: &mut [f64]) -> bool {
    let piece = &mut scratch[..c.len()];
    restrict_into(c, a, b, piece);
    let noise = noise_of(c, coeff_noise);
    piece.iter().all(|x| x.abs() <= noise)
}

/// One root reported by [`root_clusters_into`]: the representative `root` and the span
/// `[lo, hi]` of the candidates merged into it (`lo == hi` for a well-separated root). Inside
/// a span the polynomial is within its noise bound of zero, so its roots there (and the
/// extrema between them) cannot be told apart; callers that minimise a function whose
/// critical points these are should search the whole span.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RootCluster {
    pub root: f64,
    pub lo: f64,
    pub hi: f64,
    pub kind: RootKind,
}

/// [`roots_into`] reporting each merged cluster of candidates with its span.
pub fn root_clusters_into(
    c: &[f64],
    t_tol: f64,
    coeff_noise: f64,
    scratch: &mut [f64],
    cand: &mut [(f64, RootKind)],
    sink: &mut impl FnMut(RootCluster),
) {
    let m = c.len();
    if m < 2 {
        return;
    }
    let (dc, rest) = scratch.split_at_mut(m - 1);
    derivative_into(c, dc);
    let cap = cand.len();
    let mut count = 0usize;
    let mut push = |x: f64, k: RootKind, count: &mut usize| {
        if *count < cap {
            cand[*count] = (x, k);
            *count += 1;
        }
    };
    if c[0].abs() <= zero_tolerance(c, 0.0, coeff_noise) {
        push(0.0, RootKind::Even, &mut count);
    }
    {
        // A flat piece (within the noise, coefficients changing sign) becomes a cluster:
        // both its ends as even candidates, merged below because the piece between them is
        // flat. Without it two roots closer than the noise can resolve, whose piece has ends
        // of one sign, were lost (a nearly cylindrical cone's squared critical-angle
        // equation, `query::angles::meridian_line`).
        let mut found = |f: Found| match f {
            Found::Root(x) => push(x, RootKind::Odd, &mut count),
            Found::Flat(a, b) => {
                push(a, RootKind::Even, &mut count);
                push(b, RootKind::Even, &mut count);
            }
        };
        let noise = noise_of(c, coeff_noise);
        odd_roots_flat(c, None, 0.0, 1.0, t_tol, noise, rest, &mut found);
    }
    if m > 2 {
        let mut crit = |x: f64| {
            if eval(c, x).abs() <= zero_tolerance(c, x, coeff_noise) {
                push(x, RootKind::Even, &mut count);
            }
        };
        // Derivative coefficients n (b_{i+1} - b_i) carry 2 n times the coefficient noise.
        let d_noise = 2.0 * (m - 1) as f64 * coeff_noise;
        let guard = Some((c, noise_of(c, coeff_noise)));
        let dn = noise_of(dc, d_noise);
        odd_roots_guarded(dc, guard, 0.0, 1.0, t_tol, dn, rest, &mut crit);
    }
    if c[m - 1].abs() <= zero_tolerance(c, 1.0, coeff_noise) {
        push(1.0, RootKind::Even, &mut count);
    }
    let list = &mut cand[..count];
    // Insertion sort: the list is short and already made of two sorted runs.
    for i in 1..list.len() {
        let mut j = i;
        while j > 0 && list[j - 1].0 > list[j].0 {
            list.swap(j - 1, j);
            j -= 1;
        }
    }
    // Merge clusters.
    let mut i = 0;
    while i < list.len() {
        let mut best = list[i];
        let mut j = i + 1;
        while j < list.len() {
            let prev = list[j - 1].0;
            let next = list[j];
            let close = next.0 - prev <= t_tol;
            let has_even = best.1 == RootKind::Even || next.1 == RootKind::Even;
            let mid = 0.5 * (prev + next.0);
            let flat = has_even
                && (eval(c, mid).abs() <= zero_tolerance(c, mid, coeff_noise)
                    || flat_between(c, prev, next.0, coeff_noise, rest));
            if !(close || flat) {
                break;
            }
            let prefer_even = best.1 == RootKind::Odd && next.1 == RootKind::Even;
            let smaller = best.1 == next.1 && eval(c, next.0).abs() < eval(c, best.0).abs();
            if prefer_even || smaller {
                best = next;
            }
            j += 1;
        }
        sink(RootCluster {
            root: best.0,
            lo: list[i].0,
            hi: list[j - 1].0,
            kind: best.1,
        });
        i = j;
    }
}
