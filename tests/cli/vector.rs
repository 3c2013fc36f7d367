//! `ppo-tutor cartpole --envs N`: Gymnasium's `SyncVectorEnv` traces reproduced through the
//! command line in both autoreset modes (`tests/fixtures/cartpole_vector_*_gymnasium.json`,
//! the fixtures' key names and shapes), and bad input refused with exit 2, naming the step
//! and the env.

use serde_json::Value;

use crate::common::english;

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn fixture(mode: &str) -> Result<Value, Box<dyn std::error::Error>> {
    let path = format!(
        "{}/tests/fixtures/cartpole_vector_{mode}_gymnasium.json",
        env!("CARGO_MANIFEST_DIR")
    );
    Ok(serde_json::from_str(&std::fs::read_to_string(path)?)?)
}

/// Every number under `v`, in order, as f32 bits (observations are float32 in both).
fn f32_bits(v: &Value) -> Vec<u32> {
    match v {
        Value::Number(n) => n
            .as_f64()
            .map(|x| (x as f32).to_bits())
            .into_iter()
            .collect(),
        Value::Array(a) => a.iter().flat_map(f32_bits).collect(),
        _ => Vec::new(),
    }
}

#[test]
fn cli_json_reproduces_both_autoreset_modes() -> TestResult {
    let dir = tempfile::tempdir()?;
    for mode in ["same_step", "next_step"] {
        let fx = fixture(mode)?;
        let traces = fx["traces"].as_array().ok_or("no traces")?;
        for want in traces {
            let file = dir.path().join(format!("{mode}-{}.json", want["seed"]));
            std::fs::write(&file, want["actions"].to_string())?;
            let out = english()
                .args(["cartpole", "--envs", &want["num_envs"].to_string()])
                .args(["--seed", &want["seed"].to_string()])
                .args(["--autoreset", want["autoreset"].as_str().ok_or("no mode")?])
                .arg("--actions-file")
                .arg(&file)
                .arg("--json")
                .output()?;
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(out.status.success(), "{mode}: {stderr}");
            let got: Value = serde_json::from_slice(&out.stdout)?;
            let name = format!("{mode} seed {}", want["seed"]);
            for key in [
                "seed",
                "num_envs",
                "autoreset",
                "actions",
                "terminated",
                "truncated",
            ] {
                assert_eq!(got[key], want[key], "{name}: {key}");
            }
            for key in ["reset_obs", "obs"] {
                assert_eq!(f32_bits(&got[key]), f32_bits(&want[key]), "{name}: {key}");
            }
            assert_eq!(got["rewards"], want["rewards"], "{name}: rewards");
            let (g, w) = (&got["final_obs"], &want["final_obs"]);
            assert_eq!(
                g.as_array().map(Vec::len),
                w.as_array().map(Vec::len),
                "{name}"
            );
            for (g, w) in g
                .as_array()
                .into_iter()
                .flatten()
                .zip(w.as_array().into_iter().flatten())
            {
                assert_eq!((&g["step"], &g["env"]), (&w["step"], &w["env"]), "{name}");
                assert_eq!(
                    f32_bits(&g["obs"]),
                    f32_bits(&w["obs"]),
                    "{name}: final_obs"
                );
            }
        }
    }
    Ok(())
}

#[test]
fn bad_vector_input_is_one_clear_error_with_exit_2() -> TestResult {
    let dir = tempfile::tempdir()?;
    let run =
        |envs: &str, text: Option<&str>| -> Result<(i32, String), Box<dyn std::error::Error>> {
            let file = dir.path().join("steps.json");
            match text {
                Some(t) => std::fs::write(&file, t)?,
                None => {
                    let _ = std::fs::remove_file(&file);
                }
            }
            let out = english()
                .args(["cartpole", "--envs", envs, "--actions-file"])
                .arg(&file)
                .output()?;
            Ok((
                out.status.code().unwrap_or(-1),
                String::from_utf8_lossy(&out.stderr).into_owned(),
            ))
        };
    let (code, err) = run("2", Some("[[0, 1], [1]]"))?;
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("step 1") && err.contains("1 actions") && err.contains("--envs 2"),
        "{err}"
    );
    let (code, err) = run("2", Some("[[0, 1], [1, 2]]"))?;
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("step 1, env 1: action 2"), "{err}");
    let (code, err) = run("2", Some("[[0, 1], [1, \"left\"]]"))?;
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("step 1, env 1"), "{err}");
    let (code, err) = run("0", Some("[]"))?;
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("1 or more, got '0'"), "{err}");
    let (code, err) = run("2", None)?;
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("cannot read --actions-file") && err.contains("steps.json"),
        "{err}"
    );
    let (code, err) = run("2", Some("{\"steps\": 1}"))?;
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("no array of steps"), "{err}");
    // --envs without a file, and a mode that does not exist, are usage errors too.
    let out = english().args(["cartpole", "--envs", "2"]).output()?;
    assert_eq!(out.status.code(), Some(2));
    let out = english()
        .args([
            "cartpole",
            "--envs",
            "2",
            "--autoreset",
            "later",
            "--actions-file",
            "x",
        ])
        .output()?;
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        err.contains("same-step") && err.contains("next-step"),
        "{err}"
    );
    Ok(())
}
