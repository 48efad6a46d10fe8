//! The B-spline basis (de Boor, Cox recurrences): the knot span of a parameter, the basis
//! functions and their derivatives, as NURBS evaluation and fitting need them.

pub(super) fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Index `i` of the knot span `[k_i, k_{i+1})` holding `t`, with `degree <= i < n`; the
/// domain's end belongs to the last non-empty span.
pub fn find_span(degree: usize, knots: &[f64], t: f64) -> usize {
    let n = knots.len() - degree - 1; // number of control points
    if t >= knots[n] {
        let mut i = n - 1;
        while knots[i] == knots[i + 1] {
            i -= 1;
        }
        return i;
    }
    if t <= knots[degree] {
        return degree;
    }
    let (mut lo, mut hi) = (degree, n);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if t < knots[mid] {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}

/// The `degree + 1` non-zero B-spline basis functions at `t` and the span index they start
/// after: `N_{span-degree+j}(t)` is `values[j]`. For least-squares fitting.
pub fn basis_functions(degree: usize, knots: &[f64], t: f64) -> (usize, Vec<f64>) {
    let span = find_span(degree, knots, t);
    let d = basis_derivatives(degree, knots, span, t, 0);
    (span, d[0].clone())
}

/// Basis functions and their derivatives up to `order` on `span` (Cox-de Boor recurrence
/// with the divided-difference form of the derivatives).
pub(super) fn basis_derivatives(
    p: usize,
    knots: &[f64],
    span: usize,
    t: f64,
    order: usize,
) -> Vec<Vec<f64>> {
    // ndu[j][r]: basis of degree j (upper triangle) and knot differences (lower triangle).
    let mut ndu = vec![vec![0.0; p + 1]; p + 1];
    let mut left = vec![0.0; p + 1];
    let mut right = vec![0.0; p + 1];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    let order = order.min(p);
    let mut ders = vec![vec![0.0; p + 1]; order + 1];
    for j in 0..=p {
        ders[0][j] = ndu[j][p];
    }
    let mut a = vec![vec![0.0; p + 1]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=order {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk as usize];
                d = a[s2][0] * ndu[rk as usize][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if (r as isize - 1) <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                d += a[s2][j] * ndu[idx][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for (k, row) in ders.iter_mut().enumerate().skip(1) {
        for v in row.iter_mut() {
            *v *= factor;
        }
        factor *= (p - k) as f64;
    }
    ders
}
