//! Known divergences, kept as data (`explanations.toml`): per job, the divergence class and
//! the reason, which the report shows beside the numbers.
//!
//! ```toml
//! [funcset8]
//! class = "SL function plots"
//! reason = "filterstep curve is empty: ..."
//! ```
use std::collections::BTreeMap;
use std::path::Path;

/// Why one job differs from its reference.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Explanation {
    /// A short divergence class shared by jobs with one cause (the report counts them).
    pub class: String,
    pub reason: String,
}

/// Job name → explanation.
pub type Explanations = BTreeMap<String, Explanation>;

/// Reads `path`; a missing file is an empty set, a malformed one an error with its position.
pub fn load(path: &Path) -> Result<Explanations, String> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Explanations::new()),
        Err(e) => return Err(format!("{}: {e}", path.display())),
    };
    parse(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses the TOML text: one table per job with string keys `class` and `reason`.
pub fn parse(text: &str) -> Result<Explanations, String> {
    let doc: toml_edit::Document<String> = text.parse().map_err(|e| format!("{e}"))?;
    let mut out = Explanations::new();
    for (job, item) in doc.as_table().iter() {
        let table = item
            .as_table_like()
            .ok_or_else(|| format!("[{job}] must be a table with `class` and `reason`"))?;
        let field = |k: &str| -> Result<String, String> {
            match table.get(k) {
                None => Ok(String::new()),
                Some(v) => v
                    .as_str()
                    .map(str::to_string)
                    .ok_or_else(|| format!("[{job}] {k} must be a string")),
            }
        };
        for (k, _) in table.iter() {
            if k != "class" && k != "reason" {
                return Err(format!("[{job}] has unknown key `{k}` (class, reason)"));
            }
        }
        out.insert(
            job.to_string(),
            Explanation {
                class: field("class")?,
                reason: field("reason")?,
            },
        );
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    #[test]
    fn tables_of_class_and_reason() {
        let e = super::parse(
            "[funcset8]\nclass = \"SL plots\"\nreason = \"empty\"\n[\"Bug1031110\"]\nreason = 'r'\n",
        )
        .unwrap();
        assert_eq!(e["funcset8"].class, "SL plots");
        assert_eq!(e["funcset8"].reason, "empty");
        assert_eq!(e["Bug1031110"].class, "");
        assert!(super::parse("[a]\nwhy = \"x\"\n")
            .unwrap_err()
            .contains("`why`"));
        assert!(super::parse("a = 1\n").unwrap_err().contains("[a]"));
        assert!(super::parse("[a\n").is_err());
    }
}
