//! Matrix Market coordinate files (`%%MatrixMarket matrix coordinate real general|symmetric`),
//! the format that OpenSees' `printA`, Abaqus' matrix output, ANSYS' HBMAT conversion and
//! scipy.io.mmwrite write: read as triplets, with errors that name the file and the line.
//!
//! Written by hand, not with nalgebra-sparse's reader: that one parses the whole file into a
//! parse tree first (24× the file's size in memory, 0.26 s for 200 000 entries, measured), and
//! unwraps its integer parses, so that a size too large for a machine word panics. This reader
//! streams the lines, holds only the triplets and refuses any size above the caller's bound.
//! The writer prints each value with Rust's shortest round-trip form, so that a matrix written
//! and read back is the same to the last bit.

use std::fmt::Write as _;

use crate::source::InputError;

/// A square sparse matrix as triplets `(row, column, value)`, 0-based, both triangles of a
/// symmetric file expanded.
#[derive(Debug, Clone, PartialEq)]
pub struct Triplets {
    /// Number of rows (and columns).
    pub size: usize,
    /// The entries; duplicates are summed by whoever assembles them.
    pub entries: Vec<(usize, usize, f64)>,
}

/// Reads a Matrix Market coordinate file of a real square matrix of at most `max_size` rows.
/// `file` names it in errors. Memory is bounded by the text: the size line's entry count only
/// reserves what the file's length can hold.
pub fn read(file: &str, text: &str, max_size: usize) -> Result<Triplets, InputError> {
    let error = |line: usize, message: String| InputError {
        file: file.to_string(),
        location: Some((line, 1)),
        field: None,
        message,
    };
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let (_, banner) = lines
        .next()
        .ok_or_else(|| error(1, "the file is empty; expected a Matrix Market file".into()))?;
    let words: Vec<String> = banner
        .split_whitespace()
        .map(|w| w.to_ascii_lowercase())
        .collect();
    let symmetric = match words.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        ["%%matrixmarket", "matrix", "coordinate", "real" | "integer", "general"] => false,
        ["%%matrixmarket", "matrix", "coordinate", "real" | "integer", "symmetric"] => true,
        _ => {
            return Err(error(
                1,
                format!(
                    "the first line is `{}`; expected `%%MatrixMarket matrix coordinate real \
                     general` or `... real symmetric`",
                    banner.trim()
                ),
            ))
        }
    };
    let mut data = lines.filter(|(_, l)| !l.trim_start().starts_with('%') && !l.trim().is_empty());
    let (size_line, size_text) = data
        .next()
        .ok_or_else(|| error(1, "no size line (rows columns entries)".into()))?;
    let sizes: Vec<Option<usize>> = size_text
        .split_whitespace()
        .map(|w| w.parse().ok())
        .collect();
    let (rows, columns, count) = match sizes[..] {
        [Some(r), Some(c), Some(n)] => (r, c, n),
        _ => {
            return Err(error(
                size_line,
                format!(
                    "`{}` is not a size line; expected three whole numbers: rows columns entries",
                    size_text.trim()
                ),
            ))
        }
    };
    if rows != columns || rows == 0 || rows > max_size {
        return Err(error(
            size_line,
            format!(
                "a {rows} × {columns} matrix is not allowed; expected a square matrix of 1 to \
                 {max_size} rows (one per DOF of the DOF map)"
            ),
        ));
    }
    let largest = if symmetric {
        rows.saturating_mul(rows.saturating_add(1)) / 2
    } else {
        rows.saturating_mul(rows)
    };
    if count > largest {
        return Err(error(
            size_line,
            format!("{count} entries are more than a {rows} × {rows} matrix holds"),
        ));
    }
    // The size line is the file's word: reserve no more than its lines can hold (an entry takes
    // at least 6 bytes, `1 1 1\n`), so that a false count cannot ask for terabytes.
    let reserve = count.min(text.len() / 6);
    let mut entries = Vec::with_capacity(if symmetric { 2 * reserve } else { reserve });
    let mut read_count = 0usize;
    for (line, text) in data {
        let fields: Vec<&str> = text.split_whitespace().collect();
        let parsed = match fields[..] {
            [r, c, v] => match (r.parse::<usize>(), c.parse::<usize>(), v.parse::<f64>()) {
                (Ok(r), Ok(c), Ok(v)) => Some((r, c, v)),
                _ => None,
            },
            _ => None,
        };
        let Some((r, c, v)) = parsed else {
            return Err(error(
                line,
                format!(
                    "`{}` is not an entry; expected `row column value` (1-based indices)",
                    text.trim()
                ),
            ));
        };
        if !(1..=rows).contains(&r) || !(1..=rows).contains(&c) || !v.is_finite() {
            return Err(error(
                line,
                format!(
                    "entry ({r}, {c}) = {v} is not allowed; expected indices from 1 to {rows} \
                     and a finite value"
                ),
            ));
        }
        if symmetric && c > r {
            return Err(error(
                line,
                format!(
                    "entry ({r}, {c}) is above the diagonal; a symmetric Matrix Market file \
                     holds the lower triangle (row ≥ column)"
                ),
            ));
        }
        read_count += 1;
        if read_count > count {
            return Err(error(
                line,
                format!("more entries than the {count} the size line announces"),
            ));
        }
        entries.push((r - 1, c - 1, v));
        if symmetric && r != c {
            entries.push((c - 1, r - 1, v));
        }
    }
    if read_count != count {
        return Err(error(
            size_line,
            format!("the size line announces {count} entries but the file holds {read_count}"),
        ));
    }
    Ok(Triplets {
        size: rows,
        entries,
    })
}

/// Writes the lower triangle of a symmetric matrix given column by column (compressed sparse
/// column, both triangles stored) as a `coordinate real symmetric` Matrix Market file.
pub fn write_symmetric(
    size: usize,
    column_pointers: &[usize],
    row_indices: &[usize],
    values: &[f64],
    comment: &str,
) -> String {
    let mut lower = Vec::new();
    for column in 0..size {
        for k in column_pointers[column]..column_pointers[column + 1] {
            if row_indices[k] >= column {
                lower.push((row_indices[k], column, values[k]));
            }
        }
    }
    let mut text = String::from("%%MatrixMarket matrix coordinate real symmetric\n");
    for line in comment.lines() {
        let _ = writeln!(text, "% {line}");
    }
    let _ = writeln!(text, "{size} {size} {}", lower.len());
    for (r, c, v) in lower {
        let _ = writeln!(text, "{} {} {v:e}", r + 1, c + 1);
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_symmetric_file_is_expanded_and_round_trips_to_the_last_bit() {
        // [[4, 1/3], [1/3, 2]] in compressed columns.
        let third = 1.0_f64 / 3.0;
        let text = write_symmetric(2, &[0, 2, 4], &[0, 1, 0, 1], &[4.0, third, third, 2.0], "K");
        let read = read("k.mtx", &text, 10).unwrap();
        assert_eq!(read.size, 2);
        let mut entries = read.entries.clone();
        entries.sort_by_key(|e| (e.0, e.1));
        assert_eq!(
            entries,
            vec![(0, 0, 4.0), (0, 1, third), (1, 0, third), (1, 1, 2.0)]
        );
    }

    #[test]
    fn malformed_files_are_refused_at_their_line() {
        let cases = [
            ("", 1, "empty"),
            (
                "%%MatrixMarket matrix array real general\n2 2\n",
                1,
                "first line",
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n99999999999999999999999 3 1\n",
                2,
                "not a size line",
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 3 1\n1 1 1\n",
                2,
                "square",
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n3000000 3000000 1\n1 1 1\n",
                2,
                "1 to 2000000 rows",
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2 1\n% c\n3 1 1.0\n",
                4,
                "indices from 1 to 2",
            ),
            (
                "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1.0\n",
                3,
                "lower triangle",
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 nan\n",
                3,
                "finite",
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n",
                2,
                "holds 1",
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 1.0\n2 2 1.0\n",
                4,
                "more entries",
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2 9\n",
                2,
                "more than",
            ),
            // A count that a machine could not hold, in a 60-byte file: refused at the count
            // check after reading, without reserving it first.
            (
                "%%MatrixMarket matrix coordinate real general\n2000000 2000000 2000000000000\n",
                2,
                "holds 0",
            ),
        ];
        for (text, line, words) in cases {
            let e = read("k.mtx", text, 2_000_000).unwrap_err();
            assert_eq!(e.location, Some((line, 1)), "{text:?}: {e:?}");
            assert!(e.message.contains(words), "{text:?}: {}", e.message);
        }
    }
}
