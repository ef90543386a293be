//! `--set KEY=VALUE`: edits the spec text with toml_edit before it is parsed, so that diagnostics
//! quote and point into the text that is actually run.
//!
//! The key is a dotted TOML key (`method.reduced`, `parameters.B0`); the value is parsed as a TOML
//! value (`false`, `1e-3`, `[0, 1]`) and taken as a string when it is not one (`left`). A value that
//! is almost a TOML boolean or number (`False`, `NaN`, `Inf`, `1.`) is refused with its TOML spelling
//! rather than taken as a string.

use toml_edit::{DocumentMut, InlineTable, Item, Key, Table, Value};

use crate::diagnostics::{CliError, SpecSource};

/// Applies `assignments` in order to the spec and returns the edited text.
///
/// The text is returned unchanged (not reformatted) when there is nothing to apply. A spec that is
/// not valid TOML is reported as such, at the span of its syntax error.
pub fn apply(source: &SpecSource, assignments: &[String]) -> Result<String, CliError> {
    let text = source.text();
    if assignments.is_empty() {
        return Ok(text.to_owned());
    }
    let mut doc: DocumentMut = text.parse().map_err(|e: toml_edit::TomlError| match crate::spec::syntax(source) {
        Err(error) => CliError::Spec(error),
        Ok(()) => CliError::Set {
            arg: assignments[0].clone(),
            why: format!("the spec uses TOML syntax that --set cannot edit: {}", e.message().trim_end()),
        },
    })?;
    for arg in assignments {
        set(&mut doc, arg).map_err(|why| CliError::Set { arg: arg.clone(), why })?;
    }
    Ok(doc.to_string())
}

fn set(doc: &mut DocumentMut, arg: &str) -> Result<(), String> {
    let (key, value) = arg.split_once('=').ok_or("there is no `=` between key and value")?;
    let key = key.trim();
    if key.is_empty() {
        return Err("the key is empty".into());
    }
    let path = Key::parse(key).map_err(|e| format!("`{key}` is not a TOML key: {}", e.message().trim_end()))?;
    let value = value.trim();
    let value: Value = match value.parse() {
        Ok(value) => value,
        Err(_) => match misspelt(key, value) {
            Some(why) => return Err(why),
            None => Value::from(value),
        },
    };

    let (last, parents) = path.split_last().ok_or("the key is empty")?;
    let mut table: &mut dyn toml_edit::TableLike = doc.as_table_mut();
    let mut walked = String::new();
    for (depth, part) in parents.iter().enumerate() {
        if !walked.is_empty() {
            walked.push('.');
        }
        walked.push_str(part.get());
        let item = table.entry(part.get()).or_insert_with(|| {
            if depth == 0 {
                Item::Table(Table::new())
            } else {
                Item::Value(Value::InlineTable(InlineTable::new()))
            }
        });
        let type_name = item.type_name();
        table = item
            .as_table_like_mut()
            .ok_or_else(|| format!("`{walked}` is a {type_name}, not a table, so it has no key `{}`", last.get()))?;
    }
    if let Some(existing) = table.get(last.get()) {
        if existing.is_table_like() || existing.is_array_of_tables() {
            return Err(format!("`{key}` is a table; --set replaces single values only"));
        }
    }
    table.insert(last.get(), Item::Value(value));
    Ok(())
}

/// Why `text`, which is not a TOML value, is not taken as a string either: it is a boolean or a
/// number spelt as other languages spell them (`False`, `NaN`, `Inf`, `1.`, `.5`).
fn misspelt(key: &str, text: &str) -> Option<String> {
    let quote = format!("to set the text `{text}`, quote it: `--set {key}='\"{text}\"'`");
    let lower = text.to_ascii_lowercase();
    if lower == "true" || lower == "false" {
        return Some(format!("`{text}` is not a TOML value; booleans are `true`/`false` (lower case); {quote}"));
    }
    let digits = text.strip_prefix(['+', '-']).unwrap_or(text);
    if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit() || b == b'_') {
        // An integer that TOML does not take: out of its range, or with leading zeros or stray `_`.
        let plain: String = text.chars().filter(|&c| c != '_').collect();
        return Some(match plain.parse::<i64>() {
            Ok(n) => format!("`{text}` is not a TOML value; write the integer as `{n}`; {quote}"),
            Err(_) => format!(
                "`{text}` is not a TOML value: TOML integers lie in {}..={}; write an integer in that range",
                i64::MIN,
                i64::MAX
            ),
        });
    }
    let number: f64 = text.parse().ok()?;
    let toml = if number.is_nan() {
        "nan".to_owned()
    } else if number.is_infinite() {
        if number > 0.0 { "inf" } else { "-inf" }.to_owned()
    } else {
        format!("{number:?}")
    };
    let integer =
        crate::spec::integral(number).map_or(String::new(), |n| format!(" (`{n}` where the key takes an integer)"));
    Some(format!("`{text}` is not a TOML value; write the number as `{toml}`{integer}; {quote}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPEC: &str = "system = \"charged_particle\" # name\n[method]\nreduced = true\n[time]\nsteps = 100\n";

    fn with(arg: &str) -> Result<String, CliError> {
        apply(&SpecSource::new("spec.toml".into(), SPEC.into()), &[arg.to_owned()])
    }

    #[test]
    fn replaces_a_value_and_keeps_the_rest_of_the_text() {
        let text = with("method.reduced=false").unwrap();
        assert_eq!(text, SPEC.replace("reduced = true", "reduced = false"));
    }

    #[test]
    fn bare_words_become_strings_and_new_tables_are_created() {
        let text = with("method.rule=left").unwrap();
        assert!(text.contains("rule = \"left\""), "{text}");
        let text = with("output.every=10").unwrap();
        assert!(text.contains("[output]\nevery = 10"), "{text}");
        let text = with("parameters.B0 = 2.5").unwrap();
        assert!(text.contains("B0 = 2.5"), "{text}");
    }

    #[test]
    fn malformed_arguments_are_refused_with_their_reason() {
        let why = |arg: &str| match with(arg) {
            Err(CliError::Set { why, .. }) => why,
            other => panic!("{arg}: {other:?}"),
        };
        assert!(why("method.reduced").contains("no `=`"));
        assert!(why("=3").contains("empty"));
        assert!(why("system.name=x").contains("`system` is a string, not a table"));
        assert!(why("time=3").contains("is a table"));
        assert!(why("a..b=1").contains("not a TOML key"));
    }

    #[test]
    fn booleans_and_numbers_spelt_otherwise_get_their_toml_spelling() {
        let why = |arg: &str| match with(arg) {
            Err(CliError::Set { why, .. }) => why,
            other => panic!("{arg}: {other:?}"),
        };
        assert!(why("method.reduced=False").contains("booleans are `true`/`false`"));
        assert!(why("method.reduced=TRUE").contains("booleans are `true`/`false`"));
        assert!(why("parameters.m=NaN").contains("`nan`"));
        assert!(why("parameters.m=Inf").contains("`inf`"));
        assert!(why("parameters.m=-Infinity").contains("`-inf`"));
        assert!(why("parameters.m=1.").contains("`1.0`"));
        assert!(why("parameters.m=.5").contains("`0.5`"));
        assert!(with("parameters.m=inf").unwrap().contains("m = inf"));
        assert!(why("method.reduced=False").contains("--set method.reduced='\"False\"'"));
        assert!(with("method.rule=\"False\"").unwrap().contains("rule = \"False\""));
    }

    #[test]
    fn a_spec_with_a_syntax_error_is_reported_where_the_error_is() {
        let source = SpecSource::new("spec.toml".into(), "system = \"charged_particle\n".into());
        assert!(matches!(apply(&source, &["a=1".into()]), Err(CliError::Spec(_))));
    }
}
