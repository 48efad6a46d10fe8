//! Mutations of valid inputs for the input fuzzers (`tests/fuzz_inputs.rs`,
//! `scene/tests/fuzz_scenes.rs`): at the byte level (flips, invalid UTF-8, truncation,
//! duplicated and deleted slices) and at the value level of TOML and JSON documents (numbers
//! to NaN, infinities, 1e300, 1e-300, -0 and huge integers; fields dropped, duplicated and
//! retyped; array elements dropped, repeated or extended). Each draws from the shared seeded
//! generator (`revdist::rng`), so a fuzz run is reproducible from its seed.

#![allow(dead_code)]

use revdist::rng::SplitMix64;

/// Numbers that break careless numerics, as TOML floats.
const HOSTILE_FLOATS: [f64; 12] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e300,
    -1e300,
    1e-300,
    -1e-300,
    -0.0,
    1e155,
    1e-200,
    5e-324,
    -1.0,
];

/// The same as JSON text (JSON has no NaN or infinities: those are written as the tokens a
/// careless writer would produce, which a parser must reject).
const HOSTILE_JSON_NUMBERS: [&str; 13] = [
    "NaN",
    "Infinity",
    "-Infinity",
    "1e999",
    "1e300",
    "-1e300",
    "1e-300",
    "-0",
    "-0.0",
    "18446744073709551616",
    "-9223372036854775809",
    "1e155",
    "5e-324",
];

/// One byte-level mutation of `input`.
pub fn mutate_bytes(rng: &mut SplitMix64, input: &[u8]) -> Vec<u8> {
    let mut out = input.to_vec();
    if out.is_empty() {
        return vec![0xFF];
    }
    let at = rng.below(out.len());
    match rng.below(7) {
        0 => out[at] ^= 1 << rng.below(8),
        1 => out.insert(at, *rng.pick(&[0xFF, 0xC0, 0x80, 0x00, 0xEF])),
        2 => out.truncate(at),
        3 => {
            let end = (at + 1 + rng.below(16)).min(out.len());
            let slice = out[at..end].to_vec();
            out.splice(at..at, slice);
        }
        4 => {
            let end = (at + 1 + rng.below(16)).min(out.len());
            out.drain(at..end);
        }
        5 => out.insert(at, *rng.pick(b"[]{}\",=.-+e0123456789 \n#")),
        _ => out[at] = *rng.pick(b"[]{}\",=.-+e0123456789"),
    }
    out
}

/// One value-level mutation of a TOML document (or a byte-level one when it does not parse).
pub fn mutate_toml(rng: &mut SplitMix64, text: &str) -> Vec<u8> {
    let Ok(mut doc) = text.parse::<toml::Table>() else {
        return mutate_bytes(rng, text.as_bytes());
    };
    if rng.below(12) == 0 {
        // A duplicated line: a duplicated key or table header.
        let lines: Vec<&str> = text.lines().collect();
        let at = rng.below(lines.len().max(1));
        let mut out: Vec<&str> = lines.clone();
        if let Some(l) = lines.get(at) {
            out.insert(at, l);
        }
        return out.join("\n").into_bytes();
    }
    let mut root = toml::Value::Table(std::mem::take(&mut doc));
    mutate_toml_value(rng, &mut root, 0);
    match root {
        toml::Value::Table(t) => toml::to_string(&t)
            .unwrap_or_else(|_| text.to_string())
            .into_bytes(),
        other => other.to_string().into_bytes(),
    }
}

fn mutate_toml_value(rng: &mut SplitMix64, v: &mut toml::Value, depth: usize) {
    use toml::Value;
    // Descend into a random child most of the time, else mutate this node.
    let descend = depth < 6 && rng.below(10) != 0;
    match v {
        Value::Table(t) if descend && !t.is_empty() => {
            let keys: Vec<String> = t.keys().cloned().collect();
            let key = rng.pick(&keys).clone();
            match rng.below(8) {
                0 => {
                    t.remove(&key);
                }
                1 => {
                    let copy = t[&key].clone();
                    t.insert(format!("{key}_"), copy);
                }
                _ => mutate_toml_value(rng, t.get_mut(&key).unwrap(), depth + 1),
            }
        }
        Value::Array(a) if descend && !a.is_empty() => {
            let at = rng.below(a.len());
            match rng.below(8) {
                0 => {
                    a.remove(at);
                }
                1 => {
                    let copy = a[at].clone();
                    a.insert(at, copy);
                }
                2 => a.push(Value::Float(*rng.pick(&HOSTILE_FLOATS))),
                _ => mutate_toml_value(rng, &mut a[at], depth + 1),
            }
        }
        Value::Float(x) if rng.below(2) == 0 => {
            // A plausible edit: the same number moved a little or a lot.
            *x *= 1.0 + *rng.pick(&[1e-15, 1e-9, -1e-6, 1e-3, 0.1, -0.5, 3.0, -2.0]);
        }
        _ => {
            *v = match rng.below(12) {
                0 => Value::String("junk".into()),
                1 => Value::Integer(*rng.pick(&[i64::MAX, i64::MIN, 0, -1, 1 << 53])),
                2 => Value::Array(vec![]),
                3 => Value::Boolean(true),
                _ => Value::Float(*rng.pick(&HOSTILE_FLOATS)),
            }
        }
    }
}

/// One value-level mutation of a JSON line (or a byte-level one when it does not parse).
pub fn mutate_json(rng: &mut SplitMix64, line: &str) -> Vec<u8> {
    let Ok(mut v) = serde_json::from_str::<serde_json::Value>(line) else {
        return mutate_bytes(rng, line.as_bytes());
    };
    if rng.below(3) == 0 {
        // Replace one number token in the text by a hostile one.
        let text = line.as_bytes();
        let starts: Vec<usize> = (0..text.len())
            .filter(|&i| {
                (text[i].is_ascii_digit() || text[i] == b'-')
                    && (i == 0 || !(text[i - 1].is_ascii_alphanumeric() || text[i - 1] == b'.'))
            })
            .collect();
        if !starts.is_empty() {
            let s = *rng.pick(&starts);
            let mut e = s + 1;
            while e < text.len() && (text[e].is_ascii_digit() || b".eE+-".contains(&text[e])) {
                e += 1;
            }
            let mut out = text[..s].to_vec();
            out.extend_from_slice(rng.pick(&HOSTILE_JSON_NUMBERS).as_bytes());
            out.extend_from_slice(&text[e..]);
            return out;
        }
    }
    mutate_json_value(rng, &mut v, 0);
    v.to_string().into_bytes()
}

fn mutate_json_value(rng: &mut SplitMix64, v: &mut serde_json::Value, depth: usize) {
    use serde_json::{json, Value};
    let descend = depth < 6 && rng.below(5) != 0;
    match v {
        Value::Object(m) if descend && !m.is_empty() => {
            let keys: Vec<String> = m.keys().cloned().collect();
            let key = rng.pick(&keys).clone();
            match rng.below(8) {
                0 => {
                    m.remove(&key);
                }
                1 => {
                    let copy = m[&key].clone();
                    m.insert(format!("{key}_"), copy);
                }
                _ => mutate_json_value(rng, m.get_mut(&key).unwrap(), depth + 1),
            }
        }
        Value::Array(a) if descend && !a.is_empty() => {
            let at = rng.below(a.len());
            match rng.below(8) {
                0 => {
                    a.remove(at);
                }
                1 => {
                    let copy = a[at].clone();
                    a.insert(at, copy);
                }
                2 => a.push(json!(1e300)),
                _ => mutate_json_value(rng, &mut a[at], depth + 1),
            }
        }
        _ => {
            *v = match rng.below(7) {
                0 => json!("junk"),
                1 => json!(u64::MAX),
                2 => json!([]),
                3 => json!(null),
                4 => json!({}),
                _ => json!(*rng.pick(&[1e300, -1e300, 1e-300, -0.0, 1e155, -1.0, 0.0])),
            }
        }
    }
}
