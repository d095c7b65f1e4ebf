//! Reading input files with errors that name the file, the line, the column, the field and what
//! is allowed.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

/// A bad input: where it is and what is wrong. Exit code 2.
#[derive(Debug, Clone, PartialEq)]
pub struct InputError {
    /// The file, or `<built-in>` / `<command line>`.
    pub file: String,
    /// 1-based line and column, when known.
    pub location: Option<(usize, usize)>,
    /// Dotted key path of the field, for example `vehicle.axles[2].mass_kg`.
    pub field: Option<String>,
    /// What is wrong and what is allowed.
    pub message: String,
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some((line, column)) = self.location {
            write!(f, ":{line}:{column}")?;
        }
        write!(f, ": ")?;
        if let Some(field) = &self.field {
            write!(f, "field `{field}`: ")?;
        }
        // A value quoted as the parser read it (serde writes 1e308 in 309 digits) is shortened.
        write!(f, "{}", vbi::units::with_short_numbers(&self.message))
    }
}

impl std::error::Error for InputError {}

impl InputError {
    /// A problem reading a data file that the key `key` of `file` names: the data file's own
    /// error when it has a line and column (a bad byte), otherwise an error at the key that
    /// names the file (missing, not a regular file, too long), quoting this one.
    pub fn at_naming_key(self, file: &SourceFile, key: &str) -> InputError {
        if self.location.is_some() {
            self
        } else {
            file.error_at(key, self.to_string())
        }
    }

    /// An error about a command-line option.
    pub fn command_line(option: &str, message: impl Into<String>) -> Self {
        InputError {
            file: "<command line>".into(),
            location: None,
            field: Some(option.into()),
            message: message.into(),
        }
    }
}

/// The largest TOML input file that vbi reads: 16 MiB (the largest shipped example is under
/// 10 KiB; a scenario with a thousand vehicles is under 1 MiB).
pub const MAX_INPUT_FILE_BYTES: u64 = 16 << 20;

/// The largest data file that vbi reads (a measurement record, a road profile, modal shapes, a
/// run summary): 1 GiB, four hours of a 32-channel logger at 200 Hz in CSV.
pub const MAX_DATA_FILE_BYTES: u64 = 1 << 30;

/// Reads a whole file as UTF-8 text, or refuses it with an error that names it: a path that is
/// not a regular file (a directory; a FIFO or a device such as `/dev/zero`, which would block
/// or be read without end), a file longer than `limit` bytes (checked before reading, and again
/// while reading, for a file that grows), and text that is not UTF-8 (located at its line and
/// column).
pub fn read_bounded(path: &Path, limit: u64) -> Result<String, InputError> {
    use std::io::Read;
    let refuse = |message: String| InputError {
        file: path.display().to_string(),
        location: None,
        field: None,
        message,
    };
    let metadata =
        std::fs::metadata(path).map_err(|e| refuse(format!("cannot read the file: {e}")))?;
    if !metadata.is_file() {
        return Err(refuse(
            "cannot read the file: it is not a regular file (a directory, a FIFO or a device); \
             give the path of a file"
                .into(),
        ));
    }
    let too_long = || {
        refuse(format!(
            "cannot read the file: it is longer than the limit of {limit} bytes ({} MiB)",
            limit >> 20
        ))
    };
    if metadata.len() > limit {
        return Err(too_long());
    }
    let file =
        std::fs::File::open(path).map_err(|e| refuse(format!("cannot read the file: {e}")))?;
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| refuse(format!("cannot read the file: {e}")))?;
    if bytes.len() as u64 > limit {
        return Err(too_long());
    }
    String::from_utf8(bytes).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = valid.iter().filter(|&&b| b == b'\n').count() + 1;
        let line_start = valid.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
        let column = String::from_utf8_lossy(&valid[line_start..])
            .chars()
            .count()
            + 1;
        InputError {
            location: Some((line, column)),
            ..refuse("the file is not UTF-8 text: an invalid byte here".into())
        }
    })
}

/// A path named in `file`, relative to that file's folder.
pub fn relative(file: &SourceFile, reference: &str) -> PathBuf {
    file.path.parent().unwrap_or(Path::new(".")).join(reference)
}

/// One key of a parsed document: its dotted path and where its key and value stand.
#[derive(Debug, Clone)]
struct KeySpan {
    path: String,
    key: Range<usize>,
    value: Range<usize>,
}

/// A TOML input file held in memory, able to point at any of its keys.
#[derive(Debug, Clone)]
pub struct SourceFile {
    /// Path as the user gave it.
    pub path: PathBuf,
    /// The whole text.
    pub text: String,
    keys: Vec<KeySpan>,
}

impl SourceFile {
    /// Reads a TOML input file of at most [`MAX_INPUT_FILE_BYTES`] ([`read_bounded`]).
    pub fn read(path: &Path) -> Result<SourceFile, InputError> {
        let text = read_bounded(path, MAX_INPUT_FILE_BYTES)?;
        Ok(SourceFile::from_text(path.to_path_buf(), text))
    }

    /// Wraps text that did not come from a file (a built-in example), named `name`.
    pub fn from_text(path: PathBuf, text: String) -> SourceFile {
        let mut keys = Vec::new();
        if let Ok(table) = toml::de::DeTable::parse(&text) {
            collect_table(table.get_ref(), "", &mut keys);
        }
        SourceFile { path, text, keys }
    }

    /// The file name as shown in messages.
    pub fn name(&self) -> String {
        self.path.display().to_string()
    }

    /// Deserialises the whole document; syntax and type errors point at the offending key.
    pub fn parse<T: DeserializeOwned>(&self) -> Result<T, InputError> {
        toml::from_str::<T>(&self.text).map_err(|e| {
            let span = e.span();
            let field = span.as_ref().and_then(|s| self.key_path_at(s.start));
            InputError {
                file: self.name(),
                location: span.map(|s| self.line_column(s.start)),
                field,
                message: e.message().trim().to_string(),
            }
        })
    }

    /// Whether the document holds the key at `path` (dotted, with `[i]` for array elements).
    pub fn has_key(&self, path: &str) -> bool {
        self.keys.iter().any(|k| k.path == path)
    }

    /// An error about the field at `path` (dotted, with `[i]` for array elements). Falls back to
    /// the nearest existing parent key when the field itself is absent (a missing key).
    pub fn error_at(&self, path: &str, message: impl Into<String>) -> InputError {
        let mut probe = path.to_string();
        let location = loop {
            if let Some(k) = self.keys.iter().find(|k| k.path == probe) {
                break Some(self.line_column(k.key.start));
            }
            match probe.rfind(['.', '[']) {
                Some(i) => probe.truncate(i),
                None => break None,
            }
        };
        InputError {
            file: self.name(),
            location,
            field: Some(path.to_string()),
            message: message.into(),
        }
    }

    /// 1-based line and column of a byte offset.
    pub fn line_column(&self, offset: usize) -> (usize, usize) {
        let before = &self.text[..offset.min(self.text.len())];
        let line = before.matches('\n').count() + 1;
        let column = before
            .rfind('\n')
            .map_or(before.len(), |i| before.len() - i - 1)
            + 1;
        (line, column)
    }

    /// The innermost key whose key or value contains the offset.
    fn key_path_at(&self, offset: usize) -> Option<String> {
        self.keys
            .iter()
            .filter(|k| k.key.contains(&offset) || k.value.contains(&offset))
            .min_by_key(|k| k.value.len())
            .map(|k| k.path.clone())
    }
}

fn collect_table(table: &toml::de::DeTable<'_>, prefix: &str, out: &mut Vec<KeySpan>) {
    for (key, value) in table.iter() {
        let path = if prefix.is_empty() {
            key.get_ref().to_string()
        } else {
            format!("{prefix}.{}", key.get_ref())
        };
        out.push(KeySpan {
            path: path.clone(),
            key: key.span(),
            value: value.span(),
        });
        collect_value(value.get_ref(), &path, out);
    }
}

fn collect_value(value: &toml::de::DeValue<'_>, path: &str, out: &mut Vec<KeySpan>) {
    match value {
        toml::de::DeValue::Table(t) => collect_table(t, path, out),
        toml::de::DeValue::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                let item_path = format!("{path}[{i}]");
                out.push(KeySpan {
                    path: item_path.clone(),
                    key: item.span(),
                    value: item.span(),
                });
                collect_value(item.get_ref(), &item_path, out);
            }
        }
        _ => {}
    }
}

/// Checks that a number is finite and within `[low, high]`; otherwise an error naming the range.
pub fn require_in_range(
    file: &SourceFile,
    path: &str,
    value: f64,
    low: f64,
    high: f64,
    unit: &str,
) -> Result<f64, InputError> {
    if value.is_finite() && value >= low && value <= high {
        Ok(value)
    } else {
        // The smallest positive number as a bound means "positive" (not 300 digits of it).
        let positive = low == f64::MIN_POSITIVE;
        let allowed = match (low.is_finite(), high.is_finite()) {
            (true, true) if positive => format!("more than 0 and at most {} {unit}", shown(high)),
            (true, true) => format!("from {} to {} {unit}", shown(low), shown(high)),
            (true, false) if positive => format!("more than 0 {unit}"),
            (true, false) => format!("at least {} {unit}", shown(low)),
            (false, true) => format!("at most {} {unit}", shown(high)),
            (false, false) => "a finite number".to_string(),
        };
        Err(file.error_at(
            path,
            format!("{} is not allowed; expected {allowed}", shown(value)),
        ))
    }
}

pub use vbi::units::shown;

/// Checks that a number is finite and strictly positive.
pub fn require_positive(
    file: &SourceFile,
    path: &str,
    value: f64,
    unit: &str,
) -> Result<f64, InputError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(file.error_at(
            path,
            format!(
                "{} is not allowed; expected a positive number of {unit}",
                shown(value)
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Doc {
        bridge: Bridge,
    }
    #[derive(serde::Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Bridge {
        spans: Vec<f64>,
        modulus_gpa: f64,
    }

    fn file(text: &str) -> SourceFile {
        SourceFile::from_text("b.toml".into(), text.into())
    }

    /// Issue 17, defect 4: `/dev/zero` and a FIFO were read until memory ran out (or blocked);
    /// a directory, a file over the limit and bytes that are not UTF-8 are refused too, each
    /// naming the file (and the line and column of the bad byte).
    #[test]
    fn only_regular_utf8_files_within_the_limit_are_read() {
        let message = |path: &Path, limit| read_bounded(path, limit).unwrap_err().to_string();
        assert!(message(Path::new("/dev/zero"), 1 << 20).contains("not a regular file"));
        let scratch = tempfile::Builder::new()
            .prefix("vbi-read-bounded-")
            .tempdir()
            .unwrap();
        let dir = scratch.path();
        assert!(message(dir, 1 << 20).contains("not a regular file"));
        let fifo = dir.join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            assert!(message(&fifo, 1 << 20).contains("not a regular file"));
        }
        let text = dir.join("a.toml");
        std::fs::write(&text, b"a = 1\nb = \"x\xff\"\n").unwrap();
        let error = read_bounded(&text, 1 << 20).unwrap_err();
        assert_eq!(error.location, Some((2, 7)));
        assert!(message(&text, 4).contains("longer than the limit of 4 bytes"));
        std::fs::write(&text, b"a = 1\n").unwrap();
        assert_eq!(read_bounded(&text, 6).unwrap(), "a = 1\n");
    }

    #[test]
    fn a_type_error_names_line_column_and_field() {
        let f = file("[bridge]\nspans = [30.0]\nmodulus_gpa = \"hard\"\n");
        let e = f.parse::<Doc>().unwrap_err();
        assert_eq!(e.location, Some((3, 15)));
        assert_eq!(e.field.as_deref(), Some("bridge.modulus_gpa"));
        assert!(e
            .to_string()
            .starts_with("b.toml:3:15: field `bridge.modulus_gpa`"));
    }

    #[test]
    fn an_unknown_key_is_reported_with_its_line() {
        let f = file("[bridge]\nspans = [30.0]\nmodulus_gpa = 34.5\ncolour = 1\n");
        let e = f.parse::<Doc>().unwrap_err();
        assert_eq!(e.location.map(|l| l.0), Some(4));
        assert!(e.message.contains("colour"), "{}", e.message);
    }

    #[test]
    fn error_at_points_at_array_elements_and_falls_back_to_the_parent() {
        let f = file("[bridge]\nspans = [30.0, -2.0]\nmodulus_gpa = 34.5\n");
        let e = require_positive(&f, "bridge.spans[1]", -2.0, "m").unwrap_err();
        assert_eq!(e.location, Some((2, 16)));
        let e = f.error_at("bridge.missing_key", "is required");
        assert_eq!(e.location, Some((1, 2)));
    }
}
