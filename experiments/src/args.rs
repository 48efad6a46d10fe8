//! Parsing of the drivers' command-line values, with error messages that name the flag and
//! the offending text.

/// The value after flag `args[i]`.
pub fn value(args: &[String], i: usize) -> Result<String, String> {
    args.get(i + 1)
        .cloned()
        .ok_or_else(|| format!("{} needs a value", args[i]))
}

/// A positive integer for `flag`.
pub fn count(s: &str, flag: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n > 0 => Ok(n),
        _ => Err(format!("{flag} needs a positive integer, got '{s}'")),
    }
}

/// A comma-separated list of accuracies in (0, 1) for `flag`.
pub fn eps_list(s: &str, flag: &str) -> Result<Vec<f64>, String> {
    s.split(',')
        .map(|e| match e.trim().parse::<f64>() {
            Ok(x) if x.is_finite() && x > 0.0 && x < 1.0 => Ok(x),
            _ => Err(format!("{flag} needs numbers in (0, 1), got '{e}'")),
        })
        .collect()
}

/// A comma-separated list of model pairs `a-b` (model names as [`crate::shapes::profile`]
/// takes them; a name containing `-` cannot be paired this way).
pub fn pairs(s: &str, flag: &str) -> Result<Vec<(String, String)>, String> {
    s.split(',')
        .map(|p| {
            let (a, b) = p
                .trim()
                .split_once('-')
                .filter(|(a, b)| !a.is_empty() && !b.is_empty())
                .ok_or_else(|| format!("{flag}: '{p}' is not of the form a-b"))?;
            Ok((a.to_owned(), b.to_owned()))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_and_errors() {
        assert_eq!(count("12", "--poses"), Ok(12));
        assert!(count("0", "--poses").unwrap_err().contains("--poses"));
        assert!(count("x", "--poses").is_err());
        assert_eq!(eps_list("1e-3, 1e-4", "--eps"), Ok(vec![1e-3, 1e-4]));
        assert!(eps_list("1e-3,2", "--eps").unwrap_err().contains("'2'"));
        assert_eq!(
            pairs("pawn-cup,torus-torus", "--pairs"),
            Ok(vec![
                ("pawn".into(), "cup".into()),
                ("torus".into(), "torus".into())
            ])
        );
        assert!(pairs("pawn", "--pairs").is_err());
        assert!(pairs("pawn-", "--pairs").is_err());
        let a: Vec<String> = vec!["--out".into()];
        assert!(value(&a, 0).unwrap_err().contains("--out"));
    }
}
