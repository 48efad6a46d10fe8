//! `verify eight`: random pairs with exactly 8 binormals, printed as pinned test vectors.

use super::cases::random_case;
use crate::exact_circle::RVec;
use revdist::rng::SplitMix64;
use rug::Rational;

/// Prints random pairs (A canonical) with exactly 8 binormals whose roots are at least
/// `min_gap` apart, with the exact binormal angles on B and lengths.
pub fn print_eight(count: usize, seed: u64, min_gap: f64) {
    let mut rng = SplitMix64(seed);
    for _ in 0..count {
        let case = random_case(&mut rng);
        let pair = case.exact_pair();
        let Some(res) = pair.analyse() else { continue };
        if res.root_count != 8 || res.min_root_gap < min_gap {
            continue;
        }
        let f = |x: &Rational| format!("{:?}", x.to_f64());
        let v = |x: &RVec| format!("[{}, {}, {}]", f(&x[0]), f(&x[1]), f(&x[2]));
        println!(
            "// ra {}, B centre {}, u {}, v {}, rb {} (exact: {} / {} / {} / {})",
            f(&pair.ra),
            v(&pair.c),
            v(&pair.u),
            v(&pair.v),
            f(&pair.rb),
            pair.ra,
            pair.c
                .iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(","),
            pair.u
                .iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(","),
            pair.rb
        );
        let mut b = res.binormals.clone();
        b.sort_by(|x, y| x.0.total_cmp(&y.0));
        for (theta, len) in b {
            println!("//   theta {theta:?} length {len:?}");
        }
    }
}
