use super::*;
use clap::Parser;

#[derive(Debug, Clone, PartialEq)]
struct Demo {
    pair: String,
    eps: f64,
    times: Vec<f64>,
    best: Option<&'static str>,
}
crate::shard_record!(Demo {
    pair,
    eps,
    times,
    best
});

#[derive(Parser)]
struct Cli {
    #[command(flatten)]
    flags: Flags,
}

fn flags(args: &[&str]) -> Result<Flags, clap::Error> {
    Cli::try_parse_from(std::iter::once("demo").chain(args.iter().copied())).map(|c| c.flags)
}

fn temp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("verify-shard-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Unit `u` of the demo campaign: a seeded row (NaN and a long float included).
fn unit(u: usize) -> Result<Demo, String> {
    Ok(Demo {
        pair: format!("pawn-cup{u}"),
        eps: 10f64.powi(-(u as i32 % 3) - 3),
        times: vec![1.0 / (u + 3) as f64, f64::NAN, u as f64],
        best: u.is_multiple_of(2).then_some("OBBRSS"),
    })
}

fn same(a: &[Demo], b: &[Demo]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| {
            x.pair == y.pair
                && x.eps.to_bits() == y.eps.to_bits()
                && x.best == y.best
                && x.times
                    .iter()
                    .map(|t| t.to_bits())
                    .eq(y.times.iter().map(|t| t.to_bits()))
        })
}

const UNITS: usize = 7;

fn settings(poses: usize) -> Vec<(&'static str, String)> {
    vec![("poses", poses.to_string()), ("eps", "[0.001]".into())]
}

#[test]
fn every_unit_in_one_shard_balanced_and_not_periodic() {
    for units in [0, 1, 7, 33, 100] {
        for count in 1..6 {
            let mut all: Vec<usize> = (0..count)
                .flat_map(|index| Shard { index, count }.units(units))
                .collect();
            let sizes: Vec<usize> = (0..count)
                .map(|index| Shard { index, count }.units(units).len())
                .collect();
            assert!(sizes.iter().max().unwrap() - sizes.iter().min().unwrap() <= 1);
            all.sort_unstable();
            assert_eq!(all, (0..units).collect::<Vec<_>>(), "{units} / {count}");
        }
    }
    // 11 pairs x 3 eps: no shard of 3 gets only one eps (unit mod 3 would).
    for index in 0..3 {
        let eps: Vec<usize> = Shard { index, count: 3 }
            .units(33)
            .iter()
            .map(|u| u % 3)
            .collect();
        assert!(eps.iter().any(|&e| e != eps[0]), "shard {index}: {eps:?}");
    }
}

#[test]
fn bad_shards_are_clear_errors() {
    for (bad, says) in [
        ("3/2", "need 0 <= I < N"),
        ("2/2", "need 0 <= I < N"),
        ("0/0", "need 0 <= I < N"),
        ("a/b", "'a' is not a whole number"),
        ("1", "not of the form I/N"),
        ("-1/2", "is not a whole number"),
    ] {
        let e = bad.parse::<Shard>().unwrap_err();
        assert!(e.contains(says), "{bad}: {e}");
        let e = flags(&["--shard", bad]).expect_err("an error").to_string();
        assert!(e.contains("--shard") && e.contains(says), "{bad}: {e}");
    }
    assert_eq!("1/3".parse::<Shard>(), Ok(Shard { index: 1, count: 3 }));
    assert!(flags(&["--shard", "0/2", "--merge", "x"]).is_err());
}

#[test]
fn two_shards_merge_to_the_unsharded_rows() {
    let whole = Flags::default()
        .run((Path::new("unused"), "demo"), &settings(5), UNITS, unit)
        .unwrap()
        .unwrap();
    let dirs = [temp("s0"), temp("s1")];
    for (i, d) in dirs.iter().enumerate() {
        let f = flags(&["--shard", &format!("{i}/2")]).unwrap();
        assert_eq!(f.units(UNITS).len(), if i == 0 { 4 } else { 3 });
        assert_eq!(f.units(UNITS), f.shard.unwrap().units(UNITS));
        let none = f.run((d, "demo"), &settings(5), UNITS, unit).unwrap();
        assert!(none.is_none(), "a shard writes rows, no tables");
    }
    // The shards in any order.
    let list = format!("{},{}", dirs[1].display(), dirs[0].display());
    let merge = flags(&["--merge", &list]).unwrap();
    assert!(merge.units(UNITS).is_empty());
    let never = |_: usize| -> Result<Demo, String> { panic!("a merge computes nothing") };
    let merged = merge
        .run((Path::new("out"), "demo"), &settings(5), UNITS, never)
        .unwrap()
        .unwrap();
    assert!(same(&merged, &whole), "{merged:?}\n{whole:?}");

    // Inconsistent merges are errors that say why.
    let err = |f: &Flags, s: &[(&str, String)]| {
        f.run((Path::new("out"), "demo"), s, UNITS, never)
            .unwrap_err()
    };
    let e = err(&merge, &settings(6));
    assert!(e.contains("`poses` is '5' there, '6' in this merge"), "{e}");
    let one = flags(&["--merge", &dirs[0].display().to_string()]).unwrap();
    assert!(err(&one, &settings(5)).contains("shards [1] of 2 are missing"));
    let twice = flags(&[
        "--merge",
        &format!("{},{}", dirs[0].display(), dirs[0].display()),
    ]);
    assert!(err(&twice.unwrap(), &settings(5)).contains("shard 0/2 is given twice"));
    // A shard whose file lost a row.
    let path = rows::rows_path(&dirs[1], "demo");
    let text = std::fs::read_to_string(&path).unwrap();
    let lost = Shard { index: 1, count: 2 }.units(UNITS)[0];
    let cut: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with(&format!("{lost},")))
        .collect();
    std::fs::write(&path, cut.join("\n")).unwrap();
    let e = err(&merge, &settings(5));
    assert!(
        e.contains(&format!("units [{lost}] of 7 are in no shard's rows")),
        "{e}"
    );
    let e = err(
        &flags(&["--merge", "/nonexistent-shard"]).unwrap(),
        &settings(5),
    );
    assert!(e.contains("cannot read"), "{e}");
    for d in dirs {
        std::fs::remove_dir_all(d).unwrap();
    }
}
