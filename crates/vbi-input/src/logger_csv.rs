//! The CSV files that data loggers write, read into a table of text cells with the 1-based file
//! line of each row: the reading behind a `[measurement]` file's `csv` (and its crawl run's).
//!
//! `[measurement.csv_format]` says how the logger wrote the file: the column separator (`,`,
//! `;`, tab, or runs of spaces and tabs), the decimal mark (`.` or a decimal comma), the lines
//! of the column names and of the units (a logger's preamble before them is skipped), lines to
//! skip before the data, the comment character, and whether the time column holds seconds or
//! timestamps. Without the table a file is read as before: comma-separated, `#` comments, the
//! first other line the header.
//!
//! Whatever the table says: a UTF-8 byte order mark at the start is ignored; line ends may be
//! LF, CRLF or CR; blank lines are ignored; quoted cells (`"TIMESTAMP"`) are unquoted; cells
//! are trimmed. A file that is not UTF-8 is read as Latin-1 (ISO 8859-1: one character per
//! byte), as Windows loggers write their unit lines (`µ` as the byte B5, `²` as B2): numbers are
//! ASCII in either, and a stray byte in a number is still refused as not a number at its line.
//!
//! Every refusal names the file, the line and what is allowed; a likely dialect mistake (a
//! decimal comma, a semicolon-separated header, a timestamp read as seconds) names the
//! `csv_format` key that reads it.

use std::borrow::Cow;
use std::io::Read;
use std::path::Path;

use serde::Deserialize;

use crate::source::{InputError, SourceFile, MAX_DATA_FILE_BYTES};

/// The largest magnitude of a sample as written (in the logger's unit).
const MAX_SAMPLE_MAGNITUDE: f64 = 1e15;

/// The most cells a record's table keeps (rows × columns read): 2^27, 134 million samples,
/// 1 GiB as numbers. Four hours of 32 channels at 200 Hz are 92 million. A file under the
/// size limit of 1 GiB may still hold more (short cells, every column read), and each sample
/// takes 8 bytes as a number and several copies in the processing: refused while reading, with
/// this limit named, before the memory is spent (issue 47).
pub const MAX_RECORD_CELLS: usize = 1 << 27;

/// `[measurement.csv_format]` as written; [`CsvFormat::from_raw`] checks it.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCsvFormat {
    delimiter: Option<String>,
    decimal: Option<String>,
    header_line: Option<usize>,
    unit_line: Option<usize>,
    skip_lines_after_header: Option<usize>,
    comment: Option<String>,
    time_format: Option<String>,
}

/// What separates the cells of a row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Delimiter {
    /// One byte: `,`, `;` or a tab.
    Byte(u8),
    /// One or more spaces or tabs (the `.txt`/`.dat` exports of some loggers).
    Whitespace,
}

/// What the time column holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeFormat {
    /// Numbers, in seconds.
    Seconds,
    /// `YYYY-MM-DD hh:mm:ss[.fff]` (or `T` between date and time), read as seconds from the
    /// first sample.
    Timestamp,
}

/// How a logger wrote its CSV, checked. The default reads a plain CSV.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CsvFormat {
    /// The cell separator.
    pub delimiter: Delimiter,
    /// Whether numbers are written with a decimal comma (`0,308216`).
    pub decimal_comma: bool,
    /// The 1-based line that names the columns (default: the first line that is neither blank
    /// nor a comment).
    pub header_line: Option<usize>,
    /// The 1-based line that holds each column's unit.
    pub unit_line: Option<usize>,
    /// Lines skipped after the later of the header and the unit line.
    pub skip_lines_after_header: usize,
    /// The comment character (lines that start with it are skipped), if any.
    pub comment: Option<u8>,
    /// What the time column holds.
    pub time_format: TimeFormat,
}

impl Default for CsvFormat {
    fn default() -> Self {
        CsvFormat {
            delimiter: Delimiter::Byte(b','),
            decimal_comma: false,
            header_line: None,
            unit_line: None,
            skip_lines_after_header: 0,
            comment: Some(b'#'),
            time_format: TimeFormat::Seconds,
        }
    }
}

/// The most lines a logger's preamble and header take, for `header_line`, `unit_line` and
/// `skip_lines_after_header` (a guard against a typo such as 10000000).
const MAX_HEADER_LINES: usize = 10_000;

impl CsvFormat {
    /// Checks the table at `key` (`measurement.csv_format`) of `file`.
    pub fn from_raw(file: &SourceFile, key: &str, raw: &RawCsvFormat) -> Result<Self, InputError> {
        let at = |k: &str| format!("{key}.{k}");
        let line = |k: &str, v: Option<usize>| -> Result<Option<usize>, InputError> {
            match v {
                Some(n) if !(1..=MAX_HEADER_LINES).contains(&n) => Err(file.error_at(
                    &at(k),
                    format!("line {n} is not allowed; lines are numbered from 1, at most {MAX_HEADER_LINES}"),
                )),
                _ => Ok(v),
            }
        };
        let format = CsvFormat {
            delimiter: delimiter(file, &at("delimiter"), raw.delimiter.as_deref())?,
            decimal_comma: decimal_comma(file, &at("decimal"), raw.decimal.as_deref())?,
            header_line: line("header_line", raw.header_line)?,
            unit_line: line("unit_line", raw.unit_line)?,
            skip_lines_after_header: skip_lines(file, &at("skip_lines_after_header"), raw)?,
            comment: comment(file, &at("comment"), raw.comment.as_deref())?,
            time_format: time_format(file, &at("time_format"), raw.time_format.as_deref())?,
        };
        if format.decimal_comma && format.delimiter == Delimiter::Byte(b',') {
            return Err(file.error_at(
                &at("decimal"),
                "a decimal comma with the default delimiter \",\" is ambiguous (a comma would \
                 separate both the columns and the decimals); set delimiter = \";\", \"\\t\" or \
                 \"whitespace\", as the file separates its columns",
            ));
        }
        if format.unit_line.is_some() && format.unit_line == format.header_line {
            return Err(file.error_at(
                &at("unit_line"),
                format!(
                    "unit_line = {} is the header_line; the units must be on a line of their own",
                    format.unit_line.unwrap_or(0)
                ),
            ));
        }
        Ok(format)
    }
}

fn delimiter(file: &SourceFile, key: &str, value: Option<&str>) -> Result<Delimiter, InputError> {
    match value {
        None | Some(",") => Ok(Delimiter::Byte(b',')),
        Some(";") => Ok(Delimiter::Byte(b';')),
        Some("\t") => Ok(Delimiter::Byte(b'\t')),
        Some("whitespace") => Ok(Delimiter::Whitespace),
        Some(other) => Err(file.error_at(
            key,
            format!(
                "{other:?} is not allowed; expected \",\", \";\", \"\\t\" (a tab) or \
                 \"whitespace\" (one or more spaces or tabs)"
            ),
        )),
    }
}

fn decimal_comma(file: &SourceFile, key: &str, value: Option<&str>) -> Result<bool, InputError> {
    match value {
        None | Some(".") => Ok(false),
        Some(",") => Ok(true),
        Some(other) => Err(file.error_at(
            key,
            format!("{other:?} is not allowed; expected \".\" or \",\" (a decimal comma)"),
        )),
    }
}

fn skip_lines(file: &SourceFile, key: &str, raw: &RawCsvFormat) -> Result<usize, InputError> {
    match raw.skip_lines_after_header.unwrap_or(0) {
        n if n > MAX_HEADER_LINES => Err(file.error_at(
            key,
            format!("{n} is not allowed; expected 0 to {MAX_HEADER_LINES} lines"),
        )),
        n => Ok(n),
    }
}

fn comment(file: &SourceFile, key: &str, value: Option<&str>) -> Result<Option<u8>, InputError> {
    match value {
        None => Ok(Some(b'#')),
        Some("") => Ok(None),
        Some(c) if c.len() == 1 && c.is_ascii() && !c.contains(['"', '\r', '\n']) => {
            Ok(Some(c.as_bytes()[0]))
        }
        Some(other) => Err(file.error_at(
            key,
            format!(
                "{other:?} is not allowed; expected one ASCII character (default \"#\"), or \"\" \
                 for none"
            ),
        )),
    }
}

fn time_format(
    file: &SourceFile,
    key: &str,
    value: Option<&str>,
) -> Result<TimeFormat, InputError> {
    match value {
        None | Some("seconds") => Ok(TimeFormat::Seconds),
        Some("timestamp") => Ok(TimeFormat::Timestamp),
        Some(other) => Err(file.error_at(
            key,
            format!(
                "{other:?} is not allowed; expected \"seconds\" (numbers in s) or \"timestamp\" \
                 (YYYY-MM-DD hh:mm:ss[.fff], read as seconds from the first sample)"
            ),
        )),
    }
}

/// A logger's CSV: its header, its units when a unit line is given, and its rows of trimmed
/// text cells with the 1-based file line of each.
#[derive(Debug, Clone)]
pub struct LoggerTable {
    /// The file, as shown in messages.
    pub file: String,
    /// How it was read.
    pub format: CsvFormat,
    /// The column names.
    pub header: Vec<String>,
    /// The line of the column names.
    pub header_line: usize,
    /// One unit per column (empty where the unit line has none), with its line.
    pub units: Option<(usize, Vec<String>)>,
    /// For each column, the position of its cells among the stored ones (`None`: not read).
    stored_position: Vec<Option<usize>>,
    /// The number of stored columns.
    stored_count: usize,
    /// The text of every stored data cell, trimmed and unquoted, one after the other, row by row:
    /// stored cell `c` of row `r` is `cells[cell_ends[k - 1]..cell_ends[k]]` with
    /// `k = r·stored_count + c`.
    /// One string rather than a `String` per cell: a `Vec<Vec<String>>` took 40 bytes and an
    /// allocation per cell, 5.2 GB for a 920 MB logger file (issue 47); this takes the cells'
    /// own bytes and 4 bytes each.
    cells: String,
    /// The end of each cell in `cells` (a file is at most 1 GiB, so a `u32` holds it).
    cell_ends: Vec<u32>,
    /// The 1-based file line of each row.
    pub lines: Vec<usize>,
}

/// Why a logger's CSV cannot be read.
#[derive(Debug)]
pub enum ReadProblem {
    /// The file cannot be read (missing, not a regular file, too long).
    Unreadable(InputError),
    /// A `csv_format` key does not fit the file: the key (below `csv_format`) and why.
    Key(&'static str, String),
    /// A problem at a line of the file.
    Csv(InputError),
}

/// Reads a logger's CSV at `path` as `format` says.
/// Only the cells of the columns named in `columns` are kept (all of them when it is `None`):
/// a logger writes 32 columns when a measurement reads 3.
pub fn read(
    path: &Path,
    format: &CsvFormat,
    columns: Option<&[String]>,
) -> Result<LoggerTable, ReadProblem> {
    let name = path.display().to_string();
    let text = match crate::source::read_bounded(path, MAX_DATA_FILE_BYTES) {
        Ok(text) => text,
        // Located: valid up to a byte that is not UTF-8 (the only located reading error).
        Err(e) if e.location.is_some() => read_latin1(path).map_err(ReadProblem::Unreadable)?,
        Err(e) => return Err(ReadProblem::Unreadable(e)),
    };
    parse(name, &text, format, columns)
}

/// The file read again as bytes (its kind and size were checked by `read_bounded`), as Latin-1.
fn read_latin1(path: &Path) -> Result<String, InputError> {
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_DATA_FILE_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| InputError {
            file: path.display().to_string(),
            location: None,
            field: None,
            message: format!("cannot read the file: {e}"),
        })?;
    Ok(text_of_bytes(bytes))
}

/// Bytes as text: UTF-8 when they are, else Latin-1 (each byte the character of its code).
fn text_of_bytes(bytes: Vec<u8>) -> String {
    String::from_utf8(bytes).unwrap_or_else(|e| {
        let bytes = e.into_bytes();
        let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes);
        bytes.iter().map(|&b| char::from(b)).collect()
    })
}

/// Parses the text of a logger's CSV named `file`.
pub(crate) fn parse(
    file: String,
    text: &str,
    format: &CsvFormat,
    columns: Option<&[String]>,
) -> Result<LoggerTable, ReadProblem> {
    let text = text.strip_prefix('\u{FEFF}').unwrap_or(text);
    let text = normalise_line_ends(text);
    let found = find_header_line(&file, &text, format)?;
    let header_line = found.unwrap_or(1);
    let header = found
        .and_then(|h| line_text(&text, h))
        .map(|l| split_cells(l, format.delimiter))
        .unwrap_or_default();
    if header.iter().all(String::is_empty) {
        let message = match format.header_line {
            None => "no header row; the first line must name the columns".to_string(),
            Some(h) => format!(
                "line {h} (csv_format.header_line) holds no column names; it must name the columns"
            ),
        };
        return Err(ReadProblem::Csv(located(
            &file,
            header_line,
            1,
            None,
            message,
        )));
    }
    let units = read_units(&file, &text, format, header_line, header.len())?;
    let data_line =
        header_line.max(format.unit_line.unwrap_or(0)) + 1 + format.skip_lines_after_header;
    let mut stored_count = 0;
    let stored_position = header
        .iter()
        .map(|name| {
            let kept = columns.is_none_or(|names| names.iter().any(|n| n == name));
            kept.then(|| {
                stored_count += 1;
                stored_count - 1
            })
        })
        .collect();
    let mut table = LoggerTable {
        file,
        format: format.clone(),
        stored_position,
        stored_count,
        header,
        header_line,
        units,
        cells: String::new(),
        cell_ends: Vec::new(),
        lines: Vec::new(),
    };
    let data = &text[line_offset(&text, data_line).unwrap_or(text.len())..];
    read_rows(&mut table, data, data_line).map_err(ReadProblem::Csv)?;
    Ok(table)
}

/// The text with every line end a `\n`: a file of lone CR line ends (old Mac exports) is
/// rewritten; LF and CRLF files are kept as they are (the readers take CRLF).
fn normalise_line_ends(text: &str) -> Cow<'_, str> {
    let bytes = text.as_bytes();
    let lone_cr = bytes
        .iter()
        .enumerate()
        .any(|(i, &b)| b == b'\r' && bytes.get(i + 1) != Some(&b'\n'));
    if lone_cr {
        Cow::Owned(text.replace("\r\n", "\n").replace('\r', "\n"))
    } else {
        Cow::Borrowed(text)
    }
}

/// The lines of the text (1-based number, byte offset of the start, text without its line end).
fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, usize, &str)> {
    text.split_inclusive('\n')
        .scan(0usize, |offset, line| {
            let start = *offset;
            *offset += line.len();
            Some((start, line))
        })
        .enumerate()
        .map(|(i, (start, line))| {
            let content = line.strip_suffix('\n').unwrap_or(line);
            (i + 1, start, content.strip_suffix('\r').unwrap_or(content))
        })
}

fn line_text(text: &str, number: usize) -> Option<&str> {
    numbered_lines(text).nth(number - 1).map(|(_, _, l)| l)
}

fn line_offset(text: &str, number: usize) -> Option<usize> {
    numbered_lines(text)
        .nth(number - 1)
        .map(|(_, start, _)| start)
}

fn line_count(text: &str) -> usize {
    numbered_lines(text).count()
}

fn is_comment(line: &str, comment: Option<u8>) -> bool {
    comment.is_some_and(|c| line.as_bytes().first() == Some(&c))
}

/// The header's line: `header_line`, or the first line neither blank nor a comment.
/// None when every line is blank or a comment.
fn find_header_line(
    file: &str,
    text: &str,
    format: &CsvFormat,
) -> Result<Option<usize>, ReadProblem> {
    match format.header_line {
        Some(h) if line_text(text, h).is_none() => Err(ReadProblem::Key(
            "header_line",
            format!(
                "line {h} is beyond the end of {file}, which has {} lines",
                line_count(text)
            ),
        )),
        Some(h) => Ok(Some(h)),
        None => Ok(numbered_lines(text)
            .find(|(_, _, l)| !l.trim().is_empty() && !is_comment(l, format.comment))
            .map(|(n, _, _)| n)),
    }
}

/// The units of the unit line, one per column (padded with empty units).
fn read_units(
    file: &str,
    text: &str,
    format: &CsvFormat,
    header_line: usize,
    columns: usize,
) -> Result<Option<(usize, Vec<String>)>, ReadProblem> {
    let Some(u) = format.unit_line else {
        return Ok(None);
    };
    if u == header_line {
        return Err(ReadProblem::Key(
            "unit_line",
            format!("unit_line = {u} is the line of the column names in {file}; the units must be on a line of their own (set header_line if the names are elsewhere)"),
        ));
    }
    let Some(line) = line_text(text, u) else {
        return Err(ReadProblem::Key(
            "unit_line",
            format!(
                "line {u} is beyond the end of {file}, which has {} lines",
                line_count(text)
            ),
        ));
    };
    let mut units = split_cells(line, format.delimiter);
    if units.len() > columns {
        return Err(ReadProblem::Csv(located(
            file,
            u,
            columns + 1,
            None,
            format!(
                "the unit line (csv_format.unit_line) has {} cells but the header (line {header_line}) names {columns} columns; expected at most one unit per column",
                units.len()
            ),
        )));
    }
    units.resize(columns, String::new());
    Ok(Some((u, units)))
}

/// The cells of one line, trimmed; a cell that starts with a double quote runs to the closing
/// quote (`""` in it is one quote), separators included. By hand rather than by the csv crate:
/// each line is split on its own, so that every row keeps its exact file line (the csv crate's
/// record positions leave out comment lines within the data and count CRLF line ends late),
/// and the whitespace delimiter (runs of spaces and tabs) is one more case. A logger's cells do
/// not span lines.
fn split_cells(line: &str, delimiter: Delimiter) -> Vec<String> {
    let is_separator = |c: char| match delimiter {
        Delimiter::Byte(d) => c == char::from(d),
        Delimiter::Whitespace => c == ' ' || c == '\t',
    };
    if line.trim().is_empty() {
        return Vec::new();
    }
    let whitespace = delimiter == Delimiter::Whitespace;
    let mut cells = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        // Blanks before a cell (a tab is one only when it does not separate the cells).
        while chars
            .next_if(|c| matches!(c, ' ' | '\t') && (whitespace || !is_separator(*c)))
            .is_some()
        {}
        if whitespace && chars.peek().is_none() {
            return cells;
        }
        let mut cell = String::new();
        if chars.next_if_eq(&'"').is_some() {
            while let Some(c) = chars.next() {
                match c {
                    '"' if chars.next_if_eq(&'"').is_some() => cell.push('"'),
                    '"' => break,
                    _ => cell.push(c),
                }
            }
        }
        while let Some(c) = chars.next_if(|c| !is_separator(*c)) {
            cell.push(c);
        }
        cells.push(cell.trim().to_string());
        if !whitespace && chars.next().is_none() {
            return cells;
        }
    }
}

/// The data rows, from the text that starts at file line `first_line`: blank lines and
/// comment lines are skipped.
fn read_rows(table: &mut LoggerTable, data: &str, first_line: usize) -> Result<(), InputError> {
    for (n, _, line) in numbered_lines(data) {
        if !is_comment(line, table.format.comment) {
            let cells = split_cells(line, table.format.delimiter);
            table.push_row(first_line - 1 + n, cells)?;
        }
    }
    Ok(())
}

fn located(
    file: &str,
    line: usize,
    column: usize,
    field: Option<String>,
    message: String,
) -> InputError {
    InputError {
        file: file.to_string(),
        location: Some((line, column)),
        field,
        message,
    }
}

impl LoggerTable {
    /// Adds a row read at `line`: a blank line is skipped, a row of another length than the
    /// header refused.
    fn push_row(&mut self, line: usize, cells: Vec<String>) -> Result<(), InputError> {
        if cells.iter().all(String::is_empty) && cells.len() <= 1 {
            return Ok(());
        }
        if cells.len() != self.header.len() {
            let message = format!(
                "this row has {} fields but the header has {}; every row needs one value per column{}",
                cells.len(),
                self.header.len(),
                self.row_length_hint(cells.len())
            );
            return Err(located(&self.file, line, 1, None, message));
        }
        if (self.row_count() + 1) * self.stored_count > MAX_RECORD_CELLS {
            let message = format!(
                "the record holds more than {MAX_RECORD_CELLS} samples in the {} columns read \
                 (the time column and the channels' columns), {} rows; at most {} rows: split \
                 the record",
                self.stored_count,
                self.row_count() + 1,
                MAX_RECORD_CELLS / self.stored_count
            );
            return Err(located(&self.file, line, 1, None, message));
        }
        let stored = cells
            .iter()
            .zip(&self.stored_position)
            .filter_map(|(cell, position)| position.map(|_| cell));
        for cell in stored {
            self.cells.push_str(cell);
            // The cells are at most the file's bytes, and the file at most 1 GiB.
            let end = u32::try_from(self.cells.len()).map_err(|_| {
                located(
                    &self.file,
                    line,
                    1,
                    None,
                    "the data cells hold more than 4 GiB of text; a logger file is read up to 1 GiB"
                        .to_string(),
                )
            })?;
            self.cell_ends.push(end);
        }
        self.lines.push(line);
        Ok(())
    }

    /// The number of data rows.
    pub fn row_count(&self) -> usize {
        self.lines.len()
    }

    /// Cell `index` of data row `row` (trimmed, unquoted); empty for a column not read.
    pub fn cell(&self, row: usize, index: usize) -> &str {
        let Some(position) = self.stored_position[index] else {
            return "";
        };
        let k = row * self.stored_count + position;
        let start = if k == 0 {
            0
        } else {
            self.cell_ends[k - 1] as usize
        };
        &self.cells[start..self.cell_ends[k] as usize]
    }

    /// The cells of data row `row`.
    pub fn row(&self, row: usize) -> Vec<&str> {
        (0..self.header.len()).map(|c| self.cell(row, c)).collect()
    }

    /// The likely cause of a row of `len` cells against the header's: a separator or decimal
    /// comma not set, or a logger's preamble taken for the header.
    fn row_length_hint(&self, len: usize) -> String {
        let columns = self.header.len();
        if let Some(hint) = self.separator_hint() {
            let commas = self.format.delimiter == Delimiter::Byte(b',') && len > 1;
            let also = if commas {
                "; the commas in this row look like decimal commas: set csv_format.decimal = \",\" too"
            } else {
                ""
            };
            format!("; {hint}{also}")
        } else if len == 2 * columns
            && self.format.delimiter == Delimiter::Byte(b',')
            && !self.format.decimal_comma
        {
            "; this looks like a decimal comma (each number split in two at its comma): set \
             csv_format.decimal = \",\", with the delimiter that separates the columns (\";\", \
             \"\\t\" or \"whitespace\")"
                .to_string()
        } else if self.format.header_line.is_none() && len >= 2 * columns {
            format!(
                "; the header was taken from line {}: if that line is a logger's preamble, set \
                 csv_format.header_line to the line that names the columns",
                self.header_line
            )
        } else {
            String::new()
        }
    }

    /// When the header is one cell holding another separator (`time;u;a` read with commas):
    /// the `csv_format.delimiter` that reads it.
    pub fn separator_hint(&self) -> Option<String> {
        let [cell] = self.header.as_slice() else {
            return None;
        };
        let (_, shown, key) = [
            (Delimiter::Byte(b';'), "`;`", "\";\""),
            (Delimiter::Byte(b'\t'), "a tab", "\"\\t\""),
            (Delimiter::Byte(b','), "`,`", "\",\""),
            (Delimiter::Whitespace, "spaces", "\"whitespace\""),
        ]
        .into_iter()
        .find(|(d, _, _)| {
            *d != self.format.delimiter
                && match d {
                    Delimiter::Byte(b) => cell.as_bytes().contains(b),
                    Delimiter::Whitespace => cell.split_whitespace().nth(1).is_some(),
                }
        })?;
        Some(format!(
            "the header (line {}) is one cell holding {shown}: set csv_format.delimiter = {key}",
            self.header_line
        ))
    }

    /// The index of the column named `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// The column names for a message: listed when they look like names (at most 24, each of
    /// at most 40 characters without control characters); otherwise only their count, so that
    /// a file that is not a CSV (a binary record, a text whose first line is data) is not
    /// echoed. With the delimiter that would read a one-cell header.
    pub fn columns_shown(&self) -> String {
        let header = &self.header;
        let name_like = |h: &String| h.chars().count() <= 40 && !h.chars().any(char::is_control);
        let shown = if header.len() <= 24 && header.iter().all(name_like) {
            format!("its columns are {}", header.join(", "))
        } else {
            format!(
                "its first line has {} cells that do not look like column names (is it the CSV \
                 of a logger, with a header row?)",
                header.len()
            )
        };
        match self.separator_hint() {
            Some(hint) => format!("{shown}; {hint}"),
            // A logger's dialect without header_line: the first line may be its preamble.
            None if self.format.header_line.is_none() && self.format != CsvFormat::default() => {
                format!(
                    "{shown} (from line {}: if the names are on a later line, after a logger's \
                     preamble, set csv_format.header_line)",
                    self.header_line
                )
            }
            None => shown,
        }
    }

    /// The unit of column `index` from the unit line (with that line), when one is given and
    /// its cell is not empty.
    pub fn unit(&self, index: usize) -> Option<(usize, &str)> {
        let (line, units) = self.units.as_ref()?;
        let unit = units.get(index)?.as_str();
        (!unit.is_empty()).then_some((*line, unit))
    }

    fn cell_error(&self, row: usize, index: usize, message: String) -> InputError {
        located(
            &self.file,
            self.lines[row],
            index + 1,
            Some(self.header[index].clone()),
            message,
        )
    }

    /// Column `index` as finite numbers (with the decimal mark of the format).
    pub fn numbers(&self, index: usize) -> Result<Vec<f64>, InputError> {
        (0..self.row_count())
            .map(|r| self.number(r, index))
            .collect()
    }

    fn number(&self, row: usize, index: usize) -> Result<f64, InputError> {
        let cell = self.cell(row, index);
        let err = |message: String| self.cell_error(row, index, message);
        if cell.is_empty() {
            return Err(err(
                "empty cell (a gap in the data); every sample must be a finite number".into(),
            ));
        }
        let text: Cow<str> = if self.format.decimal_comma {
            if cell.contains('.') {
                return Err(err(format!(
                    "`{cell}` holds a point, but csv_format.decimal = \",\" (a decimal comma): a \
                     point is not allowed (a thousands separator is not read); every sample \
                     must be a finite number"
                )));
            }
            Cow::Owned(cell.replace(',', "."))
        } else {
            Cow::Borrowed(cell)
        };
        let v: f64 = text.parse().map_err(|_| {
            err(format!(
                "`{cell}` is not a number; every sample must be a finite number{}",
                self.number_hint(cell)
            ))
        })?;
        if !v.is_finite() {
            return Err(err(format!("`{cell}` is not allowed; every sample must be a finite number (no NaN, no infinity)")));
        }
        // A sample beyond 1e15 in the logger's unit is no measurement, and its square (spectra,
        // RMS, the baseline's fit) would overflow to infinity (issue 47: -1e308 gave NaN deep
        // in the processing, with no location).
        if v.abs() > MAX_SAMPLE_MAGNITUDE {
            return Err(err(format!(
                "`{cell}` is not allowed; every sample must be a finite number of magnitude at \
                 most 1e15"
            )));
        }
        Ok(v)
    }

    /// The likely cause of a cell that is not a number: a decimal comma or a timestamp.
    fn number_hint(&self, cell: &str) -> &'static str {
        if !self.format.decimal_comma && cell.replace(',', ".").parse::<f64>().is_ok() {
            "; this looks like a decimal comma; set csv_format.decimal = \",\""
        } else if parse_timestamp(cell).is_some() {
            "; this looks like a timestamp; set csv_format.time_format = \"timestamp\""
        } else {
            ""
        }
    }

    /// The time column `index` in seconds: its numbers, or its timestamps as seconds from the
    /// first sample. With a unit line, a time column in numbers must be in `s`.
    pub fn times(&self, index: usize) -> Result<Vec<f64>, InputError> {
        match self.format.time_format {
            TimeFormat::Seconds => {
                if let Some((line, unit)) = self.unit(index) {
                    if !matches!(unit, "s" | "sec") {
                        return Err(located(
                            &self.file,
                            line,
                            index + 1,
                            Some(self.header[index].clone()),
                            format!("the time column's unit is `{unit}` (csv_format.unit_line); expected s: the time column is read in seconds (or give sampling_rate_hz without time_column)"),
                        ));
                    }
                }
                self.numbers(index)
            }
            TimeFormat::Timestamp => self.timestamps(index),
        }
    }

    fn timestamps(&self, index: usize) -> Result<Vec<f64>, InputError> {
        let mut first = None;
        let mut out = Vec::with_capacity(self.row_count());
        for r in 0..self.row_count() {
            let cell = self.cell(r, index);
            let Some(t) = parse_timestamp(cell) else {
                return Err(self.cell_error(
                    r,
                    index,
                    format!(
                    "`{cell}` is not a timestamp; expected YYYY-MM-DD hh:mm:ss with an optional \
                     fraction of up to 9 digits (.fff), a space or T between date and time, no \
                     time zone (csv_format.time_format = \"timestamp\")"
                ),
                ));
            };
            out.push(seconds_between(*first.get_or_insert(t), t));
        }
        Ok(out)
    }
}

/// Nanoseconds from 1970-01-01 00:00 of a timestamp `YYYY-MM-DD hh:mm:ss[.f]`, with `T` or a
/// space between date and time and a fraction of 1 to 9 digits after `.` or `,`.
///
/// A small hand parser rather than a date crate: loggers (Campbell TOA5, Dewesoft, catman)
/// write this one fixed ISO-8601 layout, in the logger's clock without a time zone, and only
/// the differences between samples matter (day, month and year roll-overs included, by the
/// proleptic Gregorian calendar). A zone suffix (`Z`, `+01:00`) or a leap second is refused, not
/// guessed.
pub fn parse_timestamp(text: &str) -> Option<i128> {
    let b = text.as_bytes();
    if b.len() < 19
        || b[4] != b'-'
        || b[7] != b'-'
        || !matches!(b[10], b' ' | b'T')
        || b[13] != b':'
        || b[16] != b':'
    {
        return None;
    }
    let number = |from: usize, to: usize| -> Option<i64> {
        b[from..to].iter().try_fold(0i64, |acc, &c| {
            c.is_ascii_digit().then(|| acc * 10 + i64::from(c - b'0'))
        })
    };
    let (year, month, day) = (number(0, 4)?, number(5, 7)?, number(8, 10)?);
    let (hour, minute, second) = (number(11, 13)?, number(14, 16)?, number(17, 19)?);
    let nanos = fraction_nanos(&b[19..])?;
    if !(1..=12).contains(&month)
        || !(1..=days_in_month(year, month)).contains(&day)
        || hour > 23
        || minute > 59
        || second > 59
    {
        return None;
    }
    let seconds = days_from_civil(year, month, day) * 86_400 + hour * 3600 + minute * 60 + second;
    Some(i128::from(seconds) * 1_000_000_000 + i128::from(nanos))
}

/// The nanoseconds of a fraction `.fff` (or `,fff`, 1 to 9 digits); none is 0.
fn fraction_nanos(rest: &[u8]) -> Option<i64> {
    let Some((mark, digits)) = rest.split_first() else {
        return Some(0);
    };
    if !matches!(mark, b'.' | b',') || digits.is_empty() || digits.len() > 9 {
        return None;
    }
    let value = digits.iter().try_fold(0i64, |acc, &c| {
        c.is_ascii_digit().then(|| acc * 10 + i64::from(c - b'0'))
    })?;
    Some(value * 10i64.pow(9 - digits.len() as u32))
}

fn days_in_month(year: i64, month: i64) -> i64 {
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    match month {
        2 if leap => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

/// Days from 1970-01-01 to a date of the proleptic Gregorian calendar (H. Hinnant's
/// `days_from_civil`).
fn days_from_civil(year: i64, month: i64, day: i64) -> i64 {
    let y = if month <= 2 { year - 1 } else { year };
    let era = y.div_euclid(400);
    let year_of_era = y - era * 400;
    let day_of_year = (153 * ((month + 9) % 12) + 2) / 5 + day - 1;
    let day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
    era * 146_097 + day_of_era - 719_468
}

/// `to − from` [ns] in seconds, as the decimal number `s.nnnnnnnnn` parses: the same value as
/// the seconds a logger would have written (`0.005` from 5 000 000 ns), bit for bit.
fn seconds_between(from: i128, to: i128) -> f64 {
    let d = to - from;
    let sign = if d < 0 { "-" } else { "" };
    let a = d.abs();
    format!("{sign}{}.{:09}", a / 1_000_000_000, a % 1_000_000_000)
        .parse()
        .unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str, format: &CsvFormat) -> LoggerTable {
        match parse("t.csv".into(), text, format, None) {
            Ok(t) => t,
            Err(e) => panic!("{e:?}"),
        }
    }

    fn problem(text: &str, format: &CsvFormat) -> ReadProblem {
        parse("t.csv".into(), text, format, None).expect_err("refused")
    }

    fn csv_message(text: &str, format: &CsvFormat) -> InputError {
        match problem(text, format) {
            ReadProblem::Csv(e) => e,
            other => panic!("{other:?}"),
        }
    }

    fn semicolon_comma() -> CsvFormat {
        CsvFormat {
            delimiter: Delimiter::Byte(b';'),
            decimal_comma: true,
            ..CsvFormat::default()
        }
    }

    /// A `[measurement.csv_format]` table checked.
    fn format_of(keys: &str) -> Result<CsvFormat, InputError> {
        #[derive(Deserialize)]
        struct Doc {
            measurement: Measurement,
        }
        #[derive(Deserialize)]
        struct Measurement {
            csv_format: RawCsvFormat,
        }
        let file = SourceFile::from_text(
            "m.toml".into(),
            format!("[measurement.csv_format]\n{keys}\n"),
        );
        let doc: Doc = file.parse()?;
        CsvFormat::from_raw(&file, "measurement.csv_format", &doc.measurement.csv_format)
    }

    #[test]
    fn only_the_columns_read_are_kept_and_the_others_read_empty() {
        let text = "t,a,b\n0.0,1,2\n0.5,3,4\n";
        let columns = ["t".to_string(), "b".to_string()];
        let t = match parse("t.csv".into(), text, &CsvFormat::default(), Some(&columns)) {
            Ok(t) => t,
            Err(e) => panic!("{e:?}"),
        };
        assert_eq!(t.header, ["t", "a", "b"]);
        assert_eq!(t.row(1), ["0.5", "", "4"]);
        assert_eq!(t.numbers(2).unwrap(), [2.0, 4.0]);
        assert_eq!(t.cells, "0.020.54");
    }

    #[test]
    fn a_plain_csv_reads_as_before_with_comments_and_blank_lines() {
        let t = table(
            "# note\ntime_s,u\n0.000,1.5\n# gap note\n0.005,2.5\n\n\n",
            &CsvFormat::default(),
        );
        assert_eq!(t.header, ["time_s", "u"]);
        assert_eq!(t.header_line, 2);
        assert_eq!(t.lines, [3, 5]);
        assert_eq!(t.times(0).unwrap(), [0.0, 0.005]);
        assert_eq!(t.numbers(1).unwrap(), [1.5, 2.5]);
        let e = csv_message("t,u\n0,1\n0.1,2,3\n", &CsvFormat::default());
        assert_eq!(e.location, Some((3, 1)));
        assert_eq!(
            e.message,
            "this row has 3 fields but the header has 2; every row needs one value per column"
        );
    }

    #[test]
    fn a_byte_order_mark_crlf_and_cr_line_ends_are_read() {
        for text in ["\u{FEFF}t,u\r\n0,1\r\n0.5,2\r\n\r\n", "t,u\r0,1\r0.5,2\r"] {
            let t = table(text, &CsvFormat::default());
            assert_eq!(t.header, ["t", "u"], "{text:?}");
            assert_eq!(t.lines, [2, 3]);
            assert_eq!(t.numbers(1).unwrap(), [1.0, 2.0]);
        }
    }

    #[test]
    fn a_decimal_comma_reads_the_same_numbers_as_a_point() {
        let t = table(
            "Zeit;W1\n0,000;0,308216\n0,005;-7,775808e-04\n",
            &semicolon_comma(),
        );
        assert_eq!(
            t.times(0).unwrap(),
            ["0.000", "0.005"].map(|s| s.parse::<f64>().unwrap())
        );
        assert_eq!(t.numbers(1).unwrap(), [0.308216, -7.775808e-04]);
        // A point under a decimal comma is refused (a thousands separator is not guessed).
        let t = table("a;b\n1.234;1\n", &semicolon_comma());
        let e = t.numbers(0).unwrap_err();
        assert_eq!(e.location, Some((2, 1)));
        assert!(e.message.contains("holds a point"), "{}", e.message);
    }

    #[test]
    fn a_decimal_comma_read_without_the_key_is_named() {
        let format = CsvFormat {
            delimiter: Delimiter::Byte(b';'),
            ..CsvFormat::default()
        };
        let e = table("t;u\n0,000;1\n", &format).numbers(0).unwrap_err();
        assert_eq!((e.location, e.field.as_deref()), (Some((2, 1)), Some("t")));
        assert!(
            e.message.contains("set csv_format.decimal = \",\""),
            "{}",
            e.message
        );
        // With commas between the columns, each number splits in two.
        let e = csv_message("t,u\n0,000,0,5\n", &CsvFormat::default());
        assert!(e.message.contains("decimal comma"), "{}", e.message);
        // A semicolon file read with commas: the header is one cell.
        let e = csv_message("t;u\n0,000;0,5\n", &CsvFormat::default());
        assert!(
            e.message.contains("csv_format.delimiter = \";\"")
                && e.message.contains("csv_format.decimal"),
            "{}",
            e.message
        );
    }

    #[test]
    fn a_whitespace_delimiter_takes_runs_of_spaces_and_tabs_and_quotes() {
        let format = CsvFormat {
            delimiter: Delimiter::Whitespace,
            ..CsvFormat::default()
        };
        let t = table(
            "  \"time s\"\t u  \"a \"\"b\"\"\"\n# c\n0.0   1 \t2\n\n 0.5\t3 4  \n",
            &format,
        );
        assert_eq!(t.header, ["time s", "u", "a \"b\""]);
        assert_eq!(t.row(0), ["0.0", "1", "2"]);
        assert_eq!(t.row(1), ["0.5", "3", "4"]);
        assert_eq!(t.row_count(), 2);
        assert_eq!(t.lines, [3, 5]);
        // A tab delimiter keeps empty cells between two tabs, and spaces within a cell.
        let tab = CsvFormat {
            delimiter: Delimiter::Byte(b'\t'),
            ..CsvFormat::default()
        };
        let t = table("a\tb c\td\n1\t\t3\n", &tab);
        assert_eq!(t.header, ["a", "b c", "d"]);
        assert_eq!(t.row(0), ["1", "", "3"]);
        assert_eq!(t.row_count(), 1);
    }

    #[test]
    fn a_toa5_file_reads_its_header_units_and_timestamps() {
        let text = "\"TOA5\",\"SYNTHETIC\",\"CR1000X\"\n\
                    \"TIMESTAMP\",\"RECORD\",\"u\"\n\
                    \"TS\",\"RN\",\"mm\"\n\
                    \"\",\"\",\"Smp\"\n\
                    \"2026-02-28 23:59:59.995\",0,1.5\n\
                    \"2026-03-01 00:00:00\",1,2.5\n\
                    \"2026-03-01 00:00:00.005\",2,3.5\n";
        let format = CsvFormat {
            header_line: Some(2),
            unit_line: Some(3),
            skip_lines_after_header: 1,
            time_format: TimeFormat::Timestamp,
            ..CsvFormat::default()
        };
        let t = table(text, &format);
        assert_eq!(t.header, ["TIMESTAMP", "RECORD", "u"]);
        assert_eq!(t.unit(2), Some((3, "mm")));
        assert_eq!(t.lines, [5, 6, 7]);
        assert_eq!(t.times(0).unwrap(), [0.0, 0.005, 0.01]);
        // A timestamp read as seconds is named.
        let seconds = CsvFormat {
            time_format: TimeFormat::Seconds,
            unit_line: None,
            skip_lines_after_header: 2,
            ..format
        };
        let e = table(text, &seconds).times(0).unwrap_err();
        assert!(
            e.message.contains("time_format = \"timestamp\""),
            "{}",
            e.message
        );
    }

    #[test]
    fn latin1_bytes_are_read_as_latin1_and_utf8_as_utf8() {
        assert_eq!(text_of_bytes(b"s;\xB5m/m;m/s\xB2".to_vec()), "s;µm/m;m/s²");
        assert_eq!(text_of_bytes("s;µm/m".as_bytes().to_vec()), "s;µm/m");
        assert_eq!(text_of_bytes(b"\xEF\xBB\xBFs;\xB5".to_vec()), "s;µ");
        let format = CsvFormat {
            unit_line: Some(2),
            ..semicolon_comma()
        };
        let t = table(&text_of_bytes(b"t;e\ns;\xB5m/m\n0;1,5\n".to_vec()), &format);
        assert_eq!(t.unit(1), Some((2, "µm/m")));
    }

    #[test]
    fn header_and_unit_lines_that_do_not_fit_the_file_name_their_key() {
        let beyond = CsvFormat {
            header_line: Some(9),
            ..CsvFormat::default()
        };
        match problem("t,u\n0,1\n", &beyond) {
            ReadProblem::Key("header_line", m) => assert!(m.contains("has 2 lines"), "{m}"),
            other => panic!("{other:?}"),
        }
        let on_header = CsvFormat {
            unit_line: Some(2),
            ..CsvFormat::default()
        };
        match problem("# c\nt,u\ns,mm\n", &on_header) {
            ReadProblem::Key("unit_line", m) => assert!(m.contains("column names"), "{m}"),
            other => panic!("{other:?}"),
        }
        let e = csv_message("# only a comment\n", &CsvFormat::default());
        assert_eq!(
            e.message,
            "no header row; the first line must name the columns"
        );
    }

    #[test]
    fn timestamps_read_fractions_and_roll_over_days_months_and_years() {
        let ns = |s: &str| parse_timestamp(s).unwrap_or_else(|| panic!("{s}"));
        let at = |a: &str, b: &str| seconds_between(ns(a), ns(b));
        assert_eq!(ns("1970-01-01 00:00:00"), 0);
        assert_eq!(ns("1970-01-02T00:00:00.5"), 86_400_500_000_000);
        assert_eq!(at("2026-03-01 12:00:00", "2026-03-01T12:00:00.005"), 0.005);
        assert_eq!(at("2026-03-01 12:00:00,25", "2026-03-01 12:00:01.5"), 1.25);
        assert_eq!(
            at("2026-03-01 23:59:59.995", "2026-03-02 00:00:00.000"),
            0.005
        );
        assert_eq!(at("2026-02-28 23:59:59", "2026-03-01 00:00:00"), 1.0);
        assert_eq!(at("2024-02-28 23:59:59", "2024-03-01 00:00:00"), 86_401.0);
        assert_eq!(
            at("2025-12-31 23:59:59.999999999", "2026-01-01 00:00:00"),
            1e-9
        );
        assert_eq!(at("2026-01-01 00:00:01", "2026-01-01 00:00:00"), -1.0);
        for bad in [
            "2026-03-01 12:00:00Z",
            "2026-03-01 12:00:00+01:00",
            "2026-02-29 12:00:00",
            "2026-03-01 24:00:00",
            "2026-03-01 12:00:60",
            "2026-03-01 12:00:00.",
            "2026-03-01 12:00:00.1234567890",
            "2026-3-01 12:00:00",
            "01.03.2026 12:00:00",
            "0.005",
            "",
        ] {
            assert_eq!(parse_timestamp(bad), None, "{bad}");
        }
    }

    #[test]
    fn seconds_from_timestamps_are_the_numbers_a_logger_would_write() {
        // 5 ms steps over an hour: bit for bit the parse of the seconds written with 3 decimals.
        for k in 0..720_000i128 {
            let ms = 5 * k;
            let written: f64 = format!("{}.{:03}", ms / 1000, ms % 1000).parse().unwrap();
            assert_eq!(seconds_between(0, ms * 1_000_000), written, "{ms} ms");
        }
    }

    #[test]
    fn the_keys_are_checked_with_what_is_allowed() {
        let f = format_of("delimiter = \";\"\ndecimal = \",\"\nheader_line = 4\nunit_line = 5\n\
                           skip_lines_after_header = 1\ncomment = \"\"\ntime_format = \"timestamp\"")
        .unwrap();
        assert_eq!(
            f,
            CsvFormat {
                delimiter: Delimiter::Byte(b';'),
                decimal_comma: true,
                header_line: Some(4),
                unit_line: Some(5),
                skip_lines_after_header: 1,
                comment: None,
                time_format: TimeFormat::Timestamp,
            }
        );
        assert_eq!(
            format_of("delimiter = \"\\t\"").unwrap().delimiter,
            Delimiter::Byte(b'\t')
        );
        assert_eq!(format_of("").unwrap(), CsvFormat::default());
        for (keys, field, needle) in [
            ("decimal = \",\"", "decimal", "ambiguous"),
            ("delimiter = \"|\"", "delimiter", "\"whitespace\""),
            ("decimal = \"'\"", "decimal", "decimal comma"),
            ("header_line = 0", "header_line", "numbered from 1"),
            ("header_line = 3\nunit_line = 3", "unit_line", "header_line"),
            ("comment = \"//\"", "comment", "one ASCII character"),
            ("time_format = \"iso\"", "time_format", "\"timestamp\""),
        ] {
            let e = format_of(keys).unwrap_err();
            assert_eq!(
                e.field.as_deref(),
                Some(format!("measurement.csv_format.{field}").as_str()),
                "{keys}"
            );
            assert!(e.location.is_some() && e.message.contains(needle), "{e}");
        }
    }
}
