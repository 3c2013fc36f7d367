//! Recorded PyTorch updates (`tests/fixtures/*_update_pytorch.json`): reading them (the
//! `Reader` both agents' replay modules use), and the weights of a file's first case
//! ([`first_weights`]), by which an agent claims a file ([`OnPolicyAgent::replays`]); the
//! course's run registry replays a file of any agent with them.

use crate::i18n::t;
use serde_json::Value;

use super::PpoError;
use super::model::{NamedWeights, WeightTensor};
#[cfg(doc)]
use super::on_policy::OnPolicyAgent;

/// The weights a replay file's first case starts from (`cases[0].weights_before`, JSON
/// null where there is none), by which an agent claims the file
/// ([`OnPolicyAgent::replays`]); `file` names it in errors.
///
/// # Errors
/// [`PpoError::File`] for a file that is not JSON.
pub fn first_weights(text: &str, file: &str) -> Result<Value, PpoError> {
    let root: Value = serde_json::from_str(text).map_err(|e| PpoError::File {
        file: file.into(),
        reason: {
            let said = crate::causes::message(&e);
            crate::tr!("not valid JSON ({said})", "{said}")
        },
    })?;
    Ok(root
        .get("cases")
        .and_then(|c| c.get(0))
        .and_then(|c| c.get("weights_before"))
        .cloned()
        .unwrap_or(Value::Null))
}

/// What a case's `hyper` holds, for errors (both agents' recordings).
pub(crate) fn hyper_expected() -> &'static str {
    t(
        "an object with actor_lr, critic_lr, gamma, lmbda, epochs, eps, hidden_dim",
        "含 actor_lr、critic_lr、gamma、lmbda、epochs、eps、hidden_dim 的对象",
    )
}

/// What a case's `batch` holds, for errors (both agents' recordings).
pub(crate) fn batch_expected() -> &'static str {
    t(
        "an object with states, actions, rewards, next_states, dones",
        "含 states、actions、rewards、next_states、dones 的对象",
    )
}

/// A weight as nested JSON lists: `(out, in)` rows for a matrix, a flat list for a bias.
pub(crate) fn nested(w: &WeightTensor) -> Value {
    let num = |x: &f32| Value::from(f64::from(*x));
    match w.shape.as_slice() {
        [_, cols] if *cols > 0 => Value::Array(
            w.data
                .chunks(*cols)
                .map(|row| Value::Array(row.iter().map(num).collect()))
                .collect(),
        ),
        _ => Value::Array(w.data.iter().map(num).collect()),
    }
}

/// Reads JSON values, naming the key path and expected shape in every error.
pub(crate) struct Reader<'a> {
    /// The file's name, for error messages.
    pub(crate) file: &'a str,
}

impl Reader<'_> {
    /// The `cases` list of a replay file's text, each case read by `case` with its key path
    /// (`cases[0]`).
    ///
    /// # Errors
    /// [`PpoError::File`] for text that is not JSON, [`PpoError::MissingKey`] /
    /// [`PpoError::WrongShape`] for a missing or malformed list, or `case`'s error.
    pub(crate) fn cases<T>(
        &self,
        text: &str,
        case: impl Fn(&Value, &str) -> Result<T, PpoError>,
    ) -> Result<Vec<T>, PpoError> {
        let root: Value = serde_json::from_str(text).map_err(|e| PpoError::File {
            file: self.file.into(),
            reason: {
                let said = crate::causes::message(&e);
                crate::tr!("not valid JSON ({said})", "{said}")
            },
        })?;
        let cases = self.array(
            self.key(&root, "", "cases", t("a list of cases", "用例列表"))?,
            "cases",
            t("a list of cases", "用例列表"),
        )?;
        cases
            .iter()
            .enumerate()
            .map(|(i, c)| case(c, &format!("cases[{i}]")))
            .collect()
    }

    fn missing(&self, key: String, expected: &str) -> PpoError {
        PpoError::MissingKey {
            file: self.file.into(),
            key,
            expected: expected.into(),
        }
    }

    pub(crate) fn wrong(&self, key: &str, expected: &str, got: &Value) -> PpoError {
        let got = match got {
            Value::Array(a) => crate::tr!("a list of {} entries", "含 {} 项的列表", a.len()),
            Value::Object(_) => t("an object", "一个对象").into(),
            Value::String(s) if s.chars().count() <= 40 => {
                crate::tr!("the string {s:?}", "字符串 {s:?}")
            }
            Value::String(_) => t("a string", "一个字符串").into(),
            Value::Null => "null".into(),
            other => format!("{other}"),
        };
        PpoError::WrongShape {
            file: self.file.into(),
            key: key.into(),
            expected: expected.into(),
            got,
        }
    }

    pub(crate) fn key<'v>(
        &self,
        v: &'v Value,
        path: &str,
        key: &str,
        expected: &str,
    ) -> Result<&'v Value, PpoError> {
        let full = if path.is_empty() {
            key.to_string()
        } else {
            format!("{path}.{key}")
        };
        v.get(key).ok_or_else(|| self.missing(full, expected))
    }

    pub(crate) fn array<'v>(
        &self,
        v: &'v Value,
        path: &str,
        expected: &str,
    ) -> Result<&'v Vec<Value>, PpoError> {
        v.as_array().ok_or_else(|| self.wrong(path, expected, v))
    }

    pub(crate) fn number(&self, v: &Value, path: &str, expected: &str) -> Result<f64, PpoError> {
        v.as_f64().ok_or_else(|| self.wrong(path, expected, v))
    }

    /// A list of `len` numbers (`len` None: any length).
    pub(crate) fn floats(
        &self,
        v: &Value,
        path: &str,
        len: Option<usize>,
        expected: &str,
    ) -> Result<Vec<f32>, PpoError> {
        let a = self.array(v, path, expected)?;
        if len.is_some_and(|n| n != a.len()) {
            return Err(self.wrong(path, expected, v));
        }
        a.iter()
            .enumerate()
            .map(|(i, x)| Ok(self.number(x, &format!("{path}[{i}]"), t("a number", "数"))? as f32))
            .collect()
    }

    /// The tensors `shapes` names, each as nested lists of its shape (`(out, in)` rows).
    pub(crate) fn named_tensors(
        &self,
        w: &Value,
        path: &str,
        shapes: impl IntoIterator<Item = (&'static str, Vec<usize>)>,
    ) -> Result<NamedWeights, PpoError> {
        let mut out = NamedWeights::new();
        for (name, shape) in shapes {
            let key = format!("{path}.{name}");
            let expected = crate::tr!("a list of shape {shape:?}", "形状 {shape:?} 的列表");
            let v = self.key(w, path, name, &expected)?;
            let data = match shape.as_slice() {
                [rows, cols] => {
                    let rows_v = self.array(v, &key, &expected)?;
                    if rows_v.len() != *rows {
                        return Err(self.wrong(&key, &expected, v));
                    }
                    let mut data = Vec::with_capacity(rows * cols);
                    for (r, row) in rows_v.iter().enumerate() {
                        data.extend(self.floats(
                            row,
                            &format!("{key}[{r}]"),
                            Some(*cols),
                            &expected,
                        )?);
                    }
                    data
                }
                _ => self.floats(v, &key, Some(shape.iter().product()), &expected)?,
            };
            out.insert(name.to_string(), WeightTensor { shape, data });
        }
        Ok(out)
    }
}
