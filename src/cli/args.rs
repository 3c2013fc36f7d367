//! Value parsers shared by the subcommands: each error names what was expected.

use crate::env::EnvId;

/// Parses a seed: a non-negative integer that fits in 64 bits.
///
/// # Errors
/// A message naming the accepted range.
pub fn parse_seed(s: &str) -> Result<u64, String> {
    s.trim().parse::<u64>().map_err(|_| {
        format!(
            "expected a non-negative integer up to {}, got '{s}'",
            u64::MAX
        )
    })
}

/// Parses a Gymnasium environment id.
///
/// # Errors
/// A message listing the supported ids.
pub fn parse_env(s: &str) -> Result<EnvId, String> {
    s.parse::<EnvId>().map_err(|_| {
        let ids: Vec<_> = EnvId::ALL.iter().map(|id| id.as_str()).collect();
        format!(
            "unknown environment '{s}': expected one of {}",
            ids.join(", ")
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
            other => Err(format!(
                "action {} is '{other}': CartPole's actions are 0 (left) and 1 (right), comma-separated like 0,1,1,0",
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
