//! A table of cells as an Apache Parquet file (the `parquet` crate's column writer, without
//! Arrow): the same columns as the CSV beside it, typed so that pandas, Polars, DuckDB or Spark
//! read numbers as numbers. A column is
//! - text (UTF-8) when it is one of [`TEXT_COLUMNS`] or a filled cell is not a number,
//! - an unsigned 64-bit integer when every filled cell is a whole number from 0 to 2⁶⁴ − 1 (road
//!   seeds need all 64 bits; stored as INT64 with the unsigned 64-bit integer logical type),
//! - a double otherwise (the cell's shortest round-trip text read back exactly, NaN and the
//!   infinities included);
//!
//! and every column is optional: an empty cell is a null. One row group; written whole or not at
//! all (through [`write_atomic`]).

use std::path::Path;
use std::sync::Arc;

use anyhow::{Context, Result};
use parquet::basic::{LogicalType, Repetition, Type as PhysicalType};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;

use crate::output::write_atomic;

/// Columns that hold text even where every cell looks like a number (as in the Python package).
pub const TEXT_COLUMNS: [&str; 5] = ["case", "rdm_station", "warnings", "error", "kind"];

/// The storage of a column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColumnKind {
    /// UTF-8 text.
    Text,
    /// Unsigned 64-bit integer.
    Unsigned,
    /// 64-bit float.
    Double,
}

/// The kind of the column `name` with these cells.
pub fn column_kind<'a>(name: &str, mut cells: impl Iterator<Item = &'a str> + Clone) -> ColumnKind {
    let filled = cells.clone().filter(|c| !c.is_empty());
    if TEXT_COLUMNS.contains(&name) {
        ColumnKind::Text
    } else if filled.clone().all(|c| c.parse::<u64>().is_ok()) && cells.any(|c| !c.is_empty()) {
        ColumnKind::Unsigned
    } else if filled.clone().all(|c| c.parse::<f64>().is_ok()) {
        ColumnKind::Double
    } else {
        ColumnKind::Text
    }
}

/// Writes `rows` under `header` as the Parquet file `path`.
pub fn write_parquet(path: &Path, header: &[&str], rows: &[Vec<String>]) -> Result<()> {
    let bytes =
        parquet_bytes(header, rows).with_context(|| format!("writing {}", path.display()))?;
    write_atomic(path, &bytes)
}

/// The Parquet file of a table, in memory.
pub fn parquet_bytes(header: &[&str], rows: &[Vec<String>]) -> Result<Vec<u8>> {
    let kinds: Vec<ColumnKind> = header
        .iter()
        .enumerate()
        .map(|(j, name)| column_kind(name, rows.iter().map(move |r| r[j].as_str())))
        .collect();
    let fields = header
        .iter()
        .zip(&kinds)
        .map(|(name, kind)| field(name, *kind).map(Arc::new))
        .collect::<Result<Vec<_>>>()?;
    let schema = Type::group_type_builder("schema")
        .with_fields(fields)
        .build()?;
    let properties = Arc::new(WriterProperties::builder().build());
    let mut writer = SerializedFileWriter::new(Vec::new(), Arc::new(schema), properties)?;
    let mut group = writer.next_row_group()?;
    let mut j = 0;
    while let Some(mut column) = group.next_column()? {
        let cells: Vec<&str> = rows.iter().map(|r| r[j].as_str()).collect();
        let levels: Vec<i16> = cells.iter().map(|c| i16::from(!c.is_empty())).collect();
        let filled = cells.iter().filter(|c| !c.is_empty());
        match kinds[j] {
            ColumnKind::Text => {
                let values: Vec<ByteArray> = filled.map(|c| ByteArray::from(*c)).collect();
                column
                    .typed::<ByteArrayType>()
                    .write_batch(&values, Some(&levels), None)?;
            }
            ColumnKind::Unsigned => {
                // The unsigned logical type keeps the bits: u64 → i64 two's complement.
                let values: Vec<i64> = filled
                    .map(|c| c.parse::<u64>().map(|v| v as i64))
                    .collect::<Result<_, _>>()?;
                column
                    .typed::<Int64Type>()
                    .write_batch(&values, Some(&levels), None)?;
            }
            ColumnKind::Double => {
                let values: Vec<f64> = filled.map(|c| c.parse()).collect::<Result<_, _>>()?;
                column
                    .typed::<DoubleType>()
                    .write_batch(&values, Some(&levels), None)?;
            }
        }
        column.close()?;
        j += 1;
    }
    group.close()?;
    Ok(writer.into_inner()?)
}

/// The schema field of a column.
fn field(name: &str, kind: ColumnKind) -> Result<Type> {
    let (physical, logical) = match kind {
        ColumnKind::Text => (PhysicalType::BYTE_ARRAY, Some(LogicalType::String)),
        ColumnKind::Unsigned => (PhysicalType::INT64, Some(LogicalType::integer(64, false))),
        ColumnKind::Double => (PhysicalType::DOUBLE, None),
    };
    Ok(Type::primitive_type_builder(name, physical)
        .with_repetition(Repetition::OPTIONAL)
        .with_logical_type(logical)
        .build()?)
}

/// The CSV file `csv` (as vbi writes it: a header and plain cells, no quoting needed) as the
/// Parquet file `parquet`, its columns typed as [`parquet_bytes`] types them. The table is held
/// in memory while it is converted (a lifetime's block maxima: blocks × effects rows).
pub fn csv_file_as_parquet(csv: &Path, parquet: &Path) -> Result<()> {
    let mut reader = ::csv::ReaderBuilder::new()
        .has_headers(true)
        .from_path(csv)
        .with_context(|| format!("reading {}", csv.display()))?;
    let header: Vec<String> = reader.headers()?.iter().map(str::to_string).collect();
    let rows = reader
        .records()
        .map(|record| Ok(record?.iter().map(str::to_string).collect()))
        .collect::<Result<Vec<Vec<String>>>>()
        .with_context(|| format!("reading {}", csv.display()))?;
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    write_parquet(parquet, &header, &rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use parquet::file::reader::{FileReader, SerializedFileReader};
    use parquet::record::{Field, RowAccessor};

    #[test]
    fn a_table_round_trips_through_parquet_with_its_types_and_nulls() {
        let header = ["case", "speed_kmh", "seed", "daf_m", "warnings"];
        let rows = vec![
            vec![
                "00ff",
                "60",
                "18446744073709551615",
                "1.0429121371186143",
                "",
            ],
            vec!["0100", "90.5", "7", "", "mode 9 under-resolved"],
            vec!["0101", "120", "0", "NaN", ""],
        ]
        .into_iter()
        .map(|r| r.into_iter().map(String::from).collect())
        .collect::<Vec<Vec<String>>>();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.parquet");
        write_parquet(&path, &header, &rows).unwrap();
        let reader = SerializedFileReader::new(std::fs::File::open(&path).unwrap()).unwrap();
        assert_eq!(reader.metadata().file_metadata().num_rows(), 3);
        let read: Vec<_> = reader
            .get_row_iter(None)
            .unwrap()
            .map(|r| r.unwrap())
            .collect();
        assert_eq!(read[0].get_string(0).unwrap(), "00ff");
        // speed_kmh has a fraction in one cell: doubles.
        assert_eq!(read[1].get_double(1).unwrap(), 90.5);
        // Seeds keep all 64 bits.
        assert_eq!(read[0].get_ulong(2).unwrap(), u64::MAX);
        assert_eq!(read[0].get_double(3).unwrap(), 1.0429121371186143);
        assert!(read[2].get_double(3).unwrap().is_nan());
        let cells: Vec<(&String, &Field)> = read[1].get_column_iter().collect();
        assert_eq!(*cells[3].1, Field::Null);
        assert_eq!(read[1].get_string(4).unwrap(), "mode 9 under-resolved");
        assert_eq!(
            column_kind("case", ["12", "13"].into_iter()),
            ColumnKind::Text
        );
    }
}
