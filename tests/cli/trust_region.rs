//! `ppo-tutor trust-region` as a user runs it: the table's shape in both languages, the
//! JSON, and bad flags refused by name.

use std::process::Output;

use serde_json::Value;

use crate::common::english;

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn ppo_tutor(args: &[&str]) -> Result<Output, std::io::Error> {
    english().args(args).output()
}

const SMALL: [&str; 8] = [
    "trust-region",
    "--train-episodes",
    "5",
    "--eval-episodes",
    "6",
    "--steps",
    "0,0.1,1.6",
    "--seed",
];

/// One row per step, each with its α, a KL and three `x ± se` cells; α = 0 is all zeros.
#[test]
fn trust_region_prints_one_row_per_step() -> TestResult {
    let out = ppo_tutor(&[&SMALL[..], &["2"]].concat())?;
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let stdout = String::from_utf8(out.stdout)?;
    assert!(stdout.contains("seed 2, 5 training episodes"), "{stdout}");
    assert!(stdout.contains("6 held-out episodes of π_old"), "{stdout}");
    let header = stdout
        .lines()
        .position(|l| l.contains("mean KL") && l.contains("true ΔJ_γ"))
        .ok_or("no header")?;
    let rows: Vec<&str> = stdout.lines().skip(header + 1).take(3).collect();
    for (row, alpha) in rows.iter().zip(["0.000", "0.100", "1.600"]) {
        let cells: Vec<&str> = row.split_whitespace().collect();
        assert_eq!(cells.first(), Some(&alpha), "{row}");
        assert_eq!(row.matches('±').count(), 3, "{row}");
    }
    assert!(
        rows[0].contains("0.00e0") && rows[0].matches("+0.000 ± 0.000").count() == 2,
        "{}",
        rows[0]
    );
    // The same run in Chinese and as JSON: the same numbers.
    let zh = english()
        .args([&SMALL[..], &["2", "--lang", "zh"]].concat())
        .output()?;
    let zh = String::from_utf8(zh.stdout)?;
    assert!(
        zh.contains("真实的 ΔJ_γ") && zh.contains("随机种子 2"),
        "{zh}"
    );
    assert!(zh.contains(rows[2].trim()), "{zh}");
    let json = ppo_tutor(&[&SMALL[..], &["2", "--json"]].concat())?;
    let probe: Value = serde_json::from_slice(&json.stdout)?;
    let points = probe["points"].as_array().ok_or("no points")?;
    assert_eq!(points.len(), 3);
    assert_eq!(probe["episodes"], 6);
    assert_eq!(points[0]["truth"], 0.0);
    let kl = |i: usize| points[i]["kl"].as_f64().unwrap_or(f64::NAN);
    assert!(kl(2) > kl(1) && kl(1) > 0.0, "{probe}");
    Ok(())
}

#[test]
fn trust_region_refuses_bad_flags_by_name() -> TestResult {
    for (flag, value, want) in [
        ("--steps", "0,x", "step 'x' is not a number"),
        ("--eval-episodes", "1", "at least 2"),
        ("--train-episodes", "0", "at least 1"),
    ] {
        let out = ppo_tutor(&["trust-region", flag, value])?;
        assert_eq!(out.status.code(), Some(2), "{flag} {value}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.contains(want) && stderr.contains(flag),
            "{flag}: {stderr}"
        );
    }
    Ok(())
}
