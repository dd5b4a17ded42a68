//! Which entry each entry of a study is compared with: its own `baseline`,
//! else the study's. An entry that is some entry's baseline is compared
//! with none, so a baseline never has a baseline of its own (chains are
//! refused).

use crate::study::{Entry, EntryResults, Study};

/// A study's baseline that cannot be: the key at fault and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BaselineError {
    /// `baseline` or `entry[<i>].baseline`.
    pub key: String,
    /// What is wrong, and what is expected.
    pub reason: String,
}

/// One entry compared with its baseline.
#[derive(Clone, Copy, Debug)]
pub struct Pair<'a> {
    /// The entry's index among the study's entries.
    pub slot: usize,
    /// The entry.
    pub entry: &'a EntryResults,
    /// Its baseline.
    pub baseline: &'a EntryResults,
}

impl Pair<'_> {
    /// The baseline's name.
    pub fn baseline_name(&self) -> &str {
        &self.baseline.entry.name
    }
}

impl Study {
    /// Whether the entry named `name` is some entry's baseline (or the
    /// study's).
    pub fn is_baseline(&self, name: &str) -> bool {
        self.baseline.as_deref() == Some(name)
            || (self.entries.iter()).any(|e| e.baseline.as_deref() == Some(name))
    }

    /// The entry `entry` is compared with: its own baseline, else the
    /// study's; none for a baseline, or without either.
    pub fn baseline_of<'a>(&'a self, entry: &'a Entry) -> Option<&'a str> {
        if self.is_baseline(&entry.name) {
            return None;
        }
        entry.baseline.as_deref().or(self.baseline.as_deref())
    }

    /// Each entry of `entries` (the study's, in its order) that has a
    /// baseline among them, with it.
    pub fn pairs<'a>(&'a self, entries: &'a [EntryResults]) -> Vec<Pair<'a>> {
        pairs(entries, |e| self.baseline_of(e))
    }

    /// Checks that the study's baseline and every entry's name another
    /// entry, and that no baseline has one of its own.
    pub fn check_baselines(&self) -> Result<(), BaselineError> {
        let named = |name: &str| self.entries.iter().any(|e| e.name == name);
        let bad = |key: String, reason: String| Err(BaselineError { key, reason });
        if let Some(b) = self.baseline.as_deref().filter(|b| !named(b)) {
            return bad("baseline".into(), format!("no entry is named '{b}'"));
        }
        for (i, e) in self.entries.iter().enumerate() {
            let Some(b) = e.baseline.as_deref() else {
                continue;
            };
            let key = format!("entry[{i}].baseline");
            if b == e.name {
                return bad(key, format!("'{b}' is this entry: name another entry"));
            }
            if !named(b) {
                return bad(key, format!("no entry is named '{b}'"));
            }
        }
        for (i, e) in self.entries.iter().enumerate() {
            let (Some(own), true) = (&e.baseline, self.is_baseline(&e.name)) else {
                continue;
            };
            let of = (self.entries.iter())
                .find(|o| o.baseline.as_deref() == Some(&e.name))
                .map_or("the study's".to_owned(), |o| {
                    format!("that of '{}'", o.name)
                });
            return bad(
                format!("entry[{i}].baseline"),
                format!(
                    "'{}' is a baseline itself ({of}), and a baseline is compared with none: \
                     drop its baseline '{own}' or compare the others with '{own}'",
                    e.name
                ),
            );
        }
        Ok(())
    }
}

/// Each of `entries` that `baseline_of` gives a baseline found among them,
/// with it, in entry order.
pub fn pairs<'a>(
    entries: &'a [EntryResults],
    baseline_of: impl Fn(&'a Entry) -> Option<&'a str>,
) -> Vec<Pair<'a>> {
    (entries.iter().enumerate())
        .filter_map(|(slot, entry)| {
            let name = baseline_of(&entry.entry)?;
            let baseline = entries.iter().find(|b| b.entry.name == name)?;
            Some(Pair {
                slot,
                entry,
                baseline,
            })
        })
        .collect()
}

/// The pairs' baselines, each once, in the order they first appear.
pub fn baselines<'a>(pairs: &[Pair<'a>]) -> Vec<&'a EntryResults> {
    let mut found: Vec<&EntryResults> = Vec::new();
    for p in pairs {
        if !found.iter().any(|b| std::ptr::eq(*b, p.baseline)) {
            found.push(p.baseline);
        }
    }
    found
}

/// The baseline every pair shares; none without pairs or with several
/// baselines.
pub fn common_baseline<'a>(pairs: &[Pair<'a>]) -> Option<&'a str> {
    match baselines(pairs)[..] {
        [one] => Some(&one.entry.name),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn study(baseline: Option<&str>, entries: &[(&str, Option<&str>)]) -> Study {
        let entries: Vec<serde_json::Value> = (entries.iter())
            .map(|(name, b)| serde_json::json!({"name": name, "algorithm": "no-advice", "baseline": b}))
            .collect();
        serde_json::from_value(serde_json::json!({
            "name": "t", "runs": 1, "episodes": 10, "eval_every": 5, "eval_episodes": 1,
            "transport": "in-process", "baseline": baseline, "entry": entries,
        }))
        .unwrap()
    }

    #[test]
    fn each_entry_is_compared_with_its_own_else_the_studys_and_baselines_with_none() {
        let s = study(
            Some("a"),
            &[("a", None), ("b", None), ("c", None), ("d", Some("c"))],
        );
        s.check_baselines().unwrap();
        let of: Vec<Option<&str>> = s.entries.iter().map(|e| s.baseline_of(e)).collect();
        assert_eq!(of, [None, Some("a"), None, Some("c")]);
        // Without the study's, only the entries' own.
        let s = study(None, &[("a", None), ("b", Some("a")), ("c", None)]);
        let of: Vec<Option<&str>> = s.entries.iter().map(|e| s.baseline_of(e)).collect();
        assert_eq!(of, [None, Some("a"), None]);
    }

    #[test]
    fn a_bad_baseline_names_its_key() {
        let err = |s: Study| s.check_baselines().unwrap_err();
        let e = err(study(Some("z"), &[("a", None)]));
        assert_eq!(
            (e.key.as_str(), e.reason.as_str()),
            ("baseline", "no entry is named 'z'")
        );
        let e = err(study(None, &[("a", None), ("b", Some("y"))]));
        assert_eq!(e.key, "entry[1].baseline");
        assert!(e.reason.contains("no entry is named 'y'"), "{e:?}");
        let e = err(study(None, &[("a", Some("a"))]));
        assert!(e.reason.contains("'a' is this entry"), "{e:?}");
        // A chain: c is b's baseline and has one of its own.
        let e = err(study(
            None,
            &[("a", None), ("b", Some("c")), ("c", Some("a"))],
        ));
        assert_eq!(e.key, "entry[2].baseline");
        assert!(
            e.reason.contains("'c' is a baseline itself (that of 'b')"),
            "{e:?}"
        );
        // The study's baseline has none of its own either.
        let e = err(study(Some("a"), &[("a", Some("b")), ("b", None)]));
        assert!(e.reason.contains("(the study's)"), "{e:?}");
    }
}
