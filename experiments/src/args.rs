//! Value parsers of the drivers' command-line flags (clap `value_parser`s): each checks one
//! kind of value, and clap's error names the flag and the offending text beside its message.

/// A model pair `a-b`, as `--pairs` takes it.
pub type ModelPair = (String, String);

/// A positive integer (counts of poses, frames, seeds, ...).
pub fn positive_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n > 0 => Ok(n),
        _ => Err("needs a positive integer".into()),
    }
}

/// An accuracy `eps` in (0, 1).
pub fn accuracy(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 && x < 1.0 => Ok(x),
        _ => Err("needs a number in (0, 1)".into()),
    }
}

/// A model pair `a-b` (model names as [`crate::shapes::profile`] takes them; a name
/// containing `-` cannot be paired this way).
pub fn model_pair(s: &str) -> Result<ModelPair, String> {
    s.trim()
        .split_once('-')
        .filter(|(a, b)| !a.is_empty() && !b.is_empty())
        .map(|(a, b)| (a.to_owned(), b.to_owned()))
        .ok_or_else(|| "needs a model pair of the form a-b".into())
}

/// A seed: decimal, or hexadecimal after `0x` (underscores allowed, as in Rust literals).
pub fn seed(s: &str) -> Result<u64, String> {
    let digits = s.trim().replace('_', "");
    let parsed = match digits.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16),
        None => digits.parse::<u64>(),
    };
    parsed.map_err(|_| "needs an integer seed (decimal or 0x hexadecimal)".into())
}

/// A comma-separated list of model pairs (for a driver's default list).
pub fn model_pairs(list: &str) -> Vec<ModelPair> {
    list.split(',')
        .map(|p| model_pair(p).unwrap_or_else(|e| panic!("default pair '{p}': {e}")))
        .collect()
}

/// Model pairs written back as [`model_pairs`] reads them (`a-b,c-d`), for provenance.
pub fn pair_list(pairs: &[ModelPair]) -> String {
    pairs
        .iter()
        .map(|(a, b)| format!("{a}-{b}"))
        .collect::<Vec<_>>()
        .join(",")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_and_errors() {
        assert_eq!(positive_count("12"), Ok(12));
        assert!(positive_count("0").is_err());
        assert!(positive_count("x").is_err());
        assert_eq!(accuracy(" 1e-4"), Ok(1e-4));
        assert!(accuracy("2").is_err());
        assert!(accuracy("0").is_err());
        assert!(accuracy("nan").is_err());
        assert_eq!(model_pair("pawn-cup"), Ok(("pawn".into(), "cup".into())));
        assert!(model_pair("pawn").is_err());
        assert!(model_pair("pawn-").is_err());
        assert_eq!(seed("0x5eed_2020"), Ok(0x5eed_2020));
        assert_eq!(seed("42"), Ok(42));
        assert!(seed("0xzz").is_err());
        assert_eq!(
            model_pairs("pawn-cup,torus-torus"),
            vec![
                ("pawn".into(), "cup".into()),
                ("torus".into(), "torus".into())
            ]
        );
    }
}
