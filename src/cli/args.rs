//! Value parsers shared by the subcommands: each error names what was expected.

use crate::env::EnvId;
use crate::tr;

/// Parses a seed: a non-negative integer that fits in 64 bits.
///
/// # Errors
/// A message naming the accepted range.
pub fn parse_seed(s: &str) -> Result<u64, String> {
    s.trim().parse::<u64>().map_err(|_| {
        let max = u64::MAX;
        tr!(
            "expected a non-negative integer up to {max}, got '{s}'",
            "应为不超过 {max} 的非负整数，实际是 '{s}'"
        )
    })
}

/// Parses a count of episodes: a whole number of at least 1 (`-5` and `0` are refused by
/// name, not taken for a flag).
///
/// # Errors
/// A message naming what was expected and what was given.
pub fn parse_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(tr!(
            "expected a whole number of at least 1, got '{s}'",
            "应为不小于 1 的整数，实际是 '{s}'"
        )),
    }
}

/// Parses a whole number, 0 or more (`-1` is refused by name, not taken for a flag); the
/// command checks its range.
///
/// # Errors
/// A message naming what was expected and what was given.
pub fn parse_whole(s: &str) -> Result<usize, String> {
    s.trim().parse::<usize>().map_err(|_| {
        tr!(
            "expected a whole number, 0 or more, got '{s}'",
            "应为不小于 0 的整数，实际是 '{s}'"
        )
    })
}

/// Checks an output path given as `flag` before any work is done (a bad path was once
/// found only after training): its folder must exist and take a new file (`/proc` does
/// not), the path must not be a folder, a device or anything else that is not a regular
/// file (`--save /dev/full` once replaced the device node), and with `extensions` its
/// extension must be one of them.
///
/// # Errors
/// One sentence naming the flag, the path and the fix.
pub fn check_output(
    flag: &str,
    path: &std::path::Path,
    extensions: Option<&[&str]>,
) -> Result<(), String> {
    let shown = path.display();
    if let Ok(meta) = std::fs::symlink_metadata(path)
        && !meta.is_file()
    {
        return Err(tr!(
            "{flag} {shown}: not a regular file; give the path of a file to write",
            "{flag} {shown}：不是普通文件；请给出要写入的文件路径"
        ));
    }
    if let Some(exts) = extensions {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        if !ext.is_some_and(|e| exts.contains(&e.as_str())) {
            let list = exts.iter().map(|e| format!("FILE.{e}")).collect::<Vec<_>>();
            let list = list.join(" / ");
            return Err(tr!(
                "{flag} {shown}: cannot tell the format from the extension; use {list}",
                "{flag} {shown}：无法从扩展名判断格式；请使用 {list}"
            ));
        }
    }
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => std::path::Path::new("."),
    };
    if !folder.is_dir() {
        let folder = folder.display();
        return Err(tr!(
            "{flag} {shown}: the folder {folder} does not exist; create it first",
            "{flag} {shown}：文件夹 {folder} 不存在；请先创建它"
        ));
    }
    if let Err(e) = try_a_file_in(folder) {
        let (folder, cause) = (folder.display(), ppo_engine::causes::message(&e));
        return Err(tr!(
            "{flag} {shown}: cannot write a file in {folder} ({cause}); choose a folder you can write",
            "{flag} {shown}：无法在 {folder} 中写入文件（{cause}）；请换一个可写的文件夹"
        ));
    }
    Ok(())
}

/// Creates and removes an empty hidden file in `folder`: whether a new file can be written
/// there (what a written output needs: it is renamed into place).
fn try_a_file_in(folder: &std::path::Path) -> std::io::Result<()> {
    let probe = ppo_engine::files::temporary_sibling(&folder.join("probe"));
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)?;
    std::fs::remove_file(&probe)
}

/// The most seeds one `--seeds` list may hold.
pub const MAX_SEEDS: usize = 256;

/// Seeds given on the command line as one list (`0-4`, `1,3,8`), in the order given.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SeedList(pub Vec<u64>);

/// Parses a list of seeds: numbers and inclusive ranges separated by commas, `0-4`,
/// `1,3,8`, `0-2,10`. Each seed at most once.
///
/// # Errors
/// A message naming the part that is not a seed or a range, a range that runs backwards,
/// a seed given twice, or a list longer than [`MAX_SEEDS`].
pub fn parse_seeds(s: &str) -> Result<SeedList, String> {
    let mut seeds: Vec<u64> = Vec::new();
    for part in s.split(',').map(str::trim) {
        let (from, to) = match part.split_once('-') {
            Some((a, b)) => (parse_seed(a)?, parse_seed(b)?),
            None if part.is_empty() => {
                return Err(tr!(
                    "expected seeds like 0-4 or 1,3,8, got an empty item in '{s}'",
                    "随机种子应写成 0-4 或 1,3,8 这样，'{s}' 中有一项是空的"
                ));
            }
            None => {
                let seed = parse_seed(part)?;
                (seed, seed)
            }
        };
        if from > to {
            return Err(tr!(
                "the range '{part}' runs backwards; write {to}-{from}",
                "范围 '{part}' 写反了，应写成 {to}-{from}"
            ));
        }
        if to - from >= MAX_SEEDS as u64 || seeds.len() + (to - from) as usize >= MAX_SEEDS {
            return Err(tr!(
                "'{s}' lists more than {MAX_SEEDS} seeds",
                "'{s}' 列出的随机种子超过 {MAX_SEEDS} 个"
            ));
        }
        for seed in from..=to {
            if seeds.contains(&seed) {
                return Err(tr!(
                    "seed {seed} is listed twice in '{s}'",
                    "随机种子 {seed} 在 '{s}' 中出现了两次"
                ));
            }
            seeds.push(seed);
        }
    }
    Ok(SeedList(seeds))
}

/// Parses a Gymnasium environment id.
///
/// # Errors
/// A message listing the supported ids.
pub fn parse_env(s: &str) -> Result<EnvId, String> {
    s.parse::<EnvId>().map_err(|_| {
        let ids: Vec<_> = EnvId::ALL.iter().map(|id| id.as_str()).collect();
        let ids = ids.join(", ");
        tr!(
            "unknown environment '{s}': expected one of {ids}",
            "未知的环境 '{s}'：应为 {ids} 之一"
        )
    })
}

/// A list of CartPole actions given on the command line (one clap value, not many).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ActionList(pub Vec<usize>);

/// Parses a comma-separated action list such as `0,1,1,0`; the empty string is no actions.
///
/// # Errors
/// A message naming the first entry that is not 0 or 1, and its position.
pub fn parse_actions(s: &str) -> Result<ActionList, String> {
    if s.trim().is_empty() {
        return Ok(ActionList(Vec::new()));
    }
    s.split(',')
        .enumerate()
        .map(|(i, part)| match part.trim() {
            "0" => Ok(0),
            "1" => Ok(1),
            other => Err(tr!(
                "action {} is '{other}': CartPole's actions are 0 (left) and 1 (right), comma-separated like 0,1,1,0",
                "第 {} 个动作是 '{other}'：CartPole 的动作是 0（左）和 1（右），用逗号分隔，如 0,1,1,0",
                i + 1
            )),
        })
        .collect::<Result<_, _>>()
        .map(ActionList)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_paths_are_checked_before_any_work() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let ok = dir.path().join("out.svg");
        assert_eq!(check_output("--plot", &ok, Some(&["png", "svg"])), Ok(()));
        let exts: Option<&[&str]> = Some(&["png", "svg"]);
        for (path, want) in [
            (dir.path().join("out.xyz"), "FILE.png / FILE.svg"),
            (dir.path().join("out"), "FILE.png / FILE.svg"),
            (dir.path().join("missing/out.png"), "does not exist"),
            (dir.path().to_path_buf(), "not a regular file"),
        ] {
            let e = check_output("--plot", &path, exts)
                .err()
                .unwrap_or_default();
            assert!(
                e.contains(want) && e.starts_with("--plot "),
                "{}: {e}",
                path.display()
            );
        }
        #[cfg(unix)]
        {
            let e = check_output("--save", std::path::Path::new("/dev/null"), None);
            assert!(e.err().unwrap_or_default().contains("not a regular file"));
        }
        // The probe leaves nothing behind.
        assert_eq!(std::fs::read_dir(dir.path())?.count(), 0);
        Ok(())
    }

    /// A folder that takes no new file (`/proc`, which even root cannot write a file in) is
    /// refused by name before any work.
    #[cfg(target_os = "linux")]
    #[test]
    fn a_folder_that_takes_no_file_is_refused() {
        let e = check_output(
            "--save",
            std::path::Path::new("/proc/x.safetensors"),
            Some(&["safetensors"]),
        )
        .err()
        .unwrap_or_default();
        assert!(
            e.starts_with("--save /proc/x.safetensors: cannot write a file in /proc"),
            "{e}"
        );
    }

    #[test]
    fn a_count_is_a_whole_number_of_at_least_one() {
        assert_eq!(parse_count("12"), Ok(12));
        assert_eq!(parse_count(" 1 "), Ok(1));
        for bad in ["0", "-5", "1.5", "", "many"] {
            let e = parse_count(bad).err().unwrap_or_default();
            assert!(
                e.contains("at least 1") && e.contains(&format!("'{bad}'")),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn a_whole_number_is_0_or_more() {
        assert_eq!(parse_whole("0"), Ok(0));
        assert_eq!(parse_whole(" 12 "), Ok(12));
        for bad in ["-1", "1.5", "", "x"] {
            let e = parse_whole(bad).err().unwrap_or_default();
            assert!(
                e.contains("0 or more") && e.contains(&format!("'{bad}'")),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn seed_lists_parse_and_reject() {
        assert_eq!(parse_seeds("0-4"), Ok(SeedList(vec![0, 1, 2, 3, 4])));
        assert_eq!(parse_seeds("3"), Ok(SeedList(vec![3])));
        assert_eq!(parse_seeds(" 1, 3 ,8-9"), Ok(SeedList(vec![1, 3, 8, 9])));
        for (bad, says) in [
            ("", "empty item"),
            ("1,,2", "empty item"),
            ("4-1", "runs backwards; write 1-4"),
            ("0-3,2", "seed 2 is listed twice"),
            ("x", "non-negative integer"),
            ("1-y", "non-negative integer"),
            ("0-256", "more than 256 seeds"),
            ("0-18446744073709551615", "more than 256 seeds"),
        ] {
            let err = parse_seeds(bad).err().unwrap_or_default();
            assert!(err.contains(says), "{bad:?}: {err}");
        }
        assert_eq!(parse_seeds("0-255").map(|s| s.0.len()), Ok(256));
    }

    #[test]
    fn actions_parse_and_reject() {
        assert_eq!(parse_actions("0, 1,1"), Ok(ActionList(vec![0, 1, 1])));
        assert_eq!(parse_actions(""), Ok(ActionList(vec![])));
        assert!(parse_actions("0,2").is_err_and(|e| e.contains("action 2 is '2'")));
        assert!(parse_actions("0,,1").is_err());
    }

    #[test]
    fn seeds_parse_and_reject() {
        assert_eq!(parse_seed("18446744073709551615"), Ok(u64::MAX));
        assert!(parse_seed("-1").is_err());
        assert!(parse_seed("abc").is_err());
    }
}
