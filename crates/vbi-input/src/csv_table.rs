//! A CSV table read whole, with the 1-based line of each record, for errors that name the
//! file, the line, the column and what is allowed (imported modal data, DOF maps, nodes).

use std::path::Path;

use crate::source::InputError;

/// A CSV table: its header and its records with their 1-based line numbers.
pub(crate) struct Table {
    pub(crate) file: String,
    pub(crate) header: Vec<String>,
    pub(crate) rows: Vec<(usize, Vec<String>)>,
}

impl Table {
    pub(crate) fn read(path: &Path) -> Result<Table, InputError> {
        let file = path.display().to_string();
        let text = crate::source::read_bounded(path, crate::source::MAX_DATA_FILE_BYTES)?;
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        let header: Vec<String> = reader
            .headers()
            .map_err(|e| csv_error(&file, e))?
            .iter()
            .map(|h| h.to_string())
            .collect();
        let mut rows = Vec::new();
        for record in reader.records() {
            let record = record.map_err(|e| csv_error(&file, e))?;
            let line = record.position().map_or(0, |p| p.line() as usize);
            rows.push((line, record.iter().map(|v| v.to_string()).collect()));
        }
        Ok(Table { file, header, rows })
    }

    pub(crate) fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    pub(crate) fn require_column(&self, name: &str, allowed: &str) -> Result<usize, InputError> {
        self.column(name).ok_or_else(|| InputError {
            file: self.file.clone(),
            location: Some((1, 1)),
            field: Some(name.to_string()),
            message: format!("missing column `{name}`; the header must be {allowed}"),
        })
    }

    pub(crate) fn error(
        &self,
        line: usize,
        column: usize,
        message: impl Into<String>,
    ) -> InputError {
        InputError {
            file: self.file.clone(),
            location: Some((line, column + 1)),
            field: self.header.get(column).cloned(),
            message: message.into(),
        }
    }

    pub(crate) fn number(
        &self,
        line: usize,
        row: &[String],
        column: usize,
        unit: &str,
    ) -> Result<f64, InputError> {
        let text = row.get(column).map(String::as_str).unwrap_or("");
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(self.error(
                line,
                column,
                format!("`{text}` is not allowed; expected a finite number [{unit}]"),
            )),
        }
    }
}

impl Table {
    /// [`Table::number`] within ±`limit` [`unit`]: a value beyond it is a unit error or a
    /// corrupt cell, refused at its cell before its products overflow to infinity downstream.
    pub(crate) fn number_within(
        &self,
        line: usize,
        row: &[String],
        column: usize,
        unit: &str,
        limit: f64,
    ) -> Result<f64, InputError> {
        let value = self.number(line, row, column, unit)?;
        if value.abs() > limit {
            return Err(self.error(
                line,
                column,
                format!(
                    "{} is not allowed; expected a number within ±{limit} {unit}",
                    crate::source::shown(value)
                ),
            ));
        }
        Ok(value)
    }
}

fn csv_error(file: &str, error: csv::Error) -> InputError {
    let location = error.position().map(|p| (p.line() as usize, 1));
    InputError {
        file: file.to_string(),
        location,
        field: None,
        message: format!("malformed CSV: {error}"),
    }
}
