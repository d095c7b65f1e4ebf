//! Writing outputs: whole files or nothing, CSV tables, JSON.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

/// Creates the output directory (and parents).
pub fn create_output_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating directory {}", dir.display()))
}

/// An exclusive lock on an output directory, held while a command writes there: the OS lock of
/// `DIR/.vbi.lock` (released when the process ends, however it ends), which holds the pid of
/// its holder for the message that another process gets.
pub struct OutputLock {
    _file: std::fs::File,
}

/// Creates the output directory and locks it, or says who holds it (exit 2, naming `--out`):
/// two processes writing one directory would interleave their files.
pub fn lock_output_dir(dir: &Path) -> Result<OutputLock> {
    create_output_dir(dir)?;
    let path = dir.join(".vbi.lock");
    let mut file = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(false)
        .open(&path)
        .with_context(|| format!("opening {}", path.display()))?;
    match file.try_lock() {
        Ok(()) => {
            file.set_len(0).ok();
            let _ = write!(file, "{}", std::process::id());
            Ok(OutputLock { _file: file })
        }
        Err(std::fs::TryLockError::WouldBlock) => {
            let holder = std::fs::read_to_string(&path).unwrap_or_default();
            let holder = match holder.trim() {
                "" => String::new(),
                pid => format!(" (pid {pid})"),
            };
            Err(vbi_input::source::InputError::command_line(
                "--out",
                format!(
                    "{} is being written by another vbi process{holder}; wait for it to end, \
                     or choose another --out",
                    dir.display()
                ),
            )
            .into())
        }
        Err(std::fs::TryLockError::Error(e)) => {
            Err(e).with_context(|| format!("locking {}", path.display()))
        }
    }
}

/// Writes `bytes` to `path` through a temporary file and a rename, so that a reader never sees a
/// half-written file and a failed run leaves no partial output behind.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic_with(path, |out| Ok(out.write_all(bytes)?))
}

/// Writes `path` through a temporary file and a rename, as [`write_atomic`], with the bytes
/// streamed by `write` into a buffered writer (a large table is never held whole in memory).
/// The temporary file is removed if `write` fails.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<()>,
) -> Result<()> {
    let mut tmp = PathBuf::from(path);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    tmp.set_file_name(format!(".{name}.partial"));
    let written = (|| -> Result<()> {
        let file =
            std::fs::File::create(&tmp).with_context(|| format!("creating {}", tmp.display()))?;
        let mut buffered = std::io::BufWriter::new(file);
        // Every failure names the file being written (a full disk: "writing DIR/histories.csv:
        // No space left on device"), whichever write met it.
        let writing = || format!("writing {}", path.display());
        write(&mut buffered).with_context(writing)?;
        let file = buffered
            .into_inner()
            .map_err(|e| e.into_error())
            .with_context(writing)?;
        file.sync_all().with_context(writing)?;
        Ok(())
    })();
    if let Err(error) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(error);
    }
    std::fs::rename(&tmp, path).with_context(|| format!("writing {}", path.display()))
}

/// Writes a CSV table of numbers row by row (`rows` yields each row's values), atomically and
/// without holding the table in memory: histories of many stations over many steps. Each value
/// is the text of [`number`] (`{}`: the shortest that reads back as the same f64, which never
/// needs quoting), formatted into one reused buffer: no string per cell, and the same bytes
/// as the csv writer's rows of [`number`] cells.
pub fn write_numbers_csv_streamed<R: IntoIterator<Item = f64>>(
    path: &Path,
    header: &[&str],
    rows: impl Iterator<Item = R>,
) -> Result<()> {
    write_atomic_with(path, |out| {
        let mut writer = csv::Writer::from_writer(Vec::new());
        writer.write_record(header)?;
        out.write_all(&writer.into_inner().context("formatting CSV")?)?;
        // Rows gathered into chunks of about 64 KiB, each written at once.
        const CHUNK: usize = 1 << 16;
        let mut chunk = String::with_capacity(2 * CHUNK);
        for row in rows {
            let mut columns = 0;
            for value in row {
                if columns > 0 {
                    chunk.push(',');
                }
                std::fmt::Write::write_fmt(&mut chunk, format_args!("{value}"))?;
                columns += 1;
            }
            // As the csv writer: every row as long as the header.
            anyhow::ensure!(
                columns == header.len(),
                "a row of {columns} values under a header of {} columns",
                header.len()
            );
            chunk.push('\n');
            if chunk.len() >= CHUNK {
                out.write_all(chunk.as_bytes())?;
                chunk.clear();
            }
        }
        out.write_all(chunk.as_bytes())?;
        Ok(())
    })
}

/// Writes a CSV table (header plus rows of already formatted cells) atomically.
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<String>]) -> Result<()> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(header)?;
    for row in rows {
        writer.write_record(row)?;
    }
    let bytes = writer.into_inner().context("formatting CSV")?;
    write_atomic(path, &bytes)
}

/// Writes pretty JSON atomically, with a trailing newline.
pub fn write_json<T: serde::Serialize>(path: &Path, value: &T) -> Result<()> {
    let mut text = serde_json::to_string_pretty(value)?;
    text.push('\n');
    write_atomic(path, text.as_bytes())
}

/// Formats a float for CSV output: shortest representation that round-trips (the library's,
/// which the study records' cells use too).
pub use vbi::study::number;

#[cfg(test)]
mod tests {
    use super::*;

    /// A write that fails (a full disk) names the file it was writing, and leaves neither it nor
    /// its temporary file behind (issue 47: `vbi run` on a full disk named no file).
    #[test]
    fn a_failed_write_names_its_file_and_leaves_nothing_behind() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("histories.csv");
        let full = std::io::Error::from_raw_os_error(28); // ENOSPC
        let error = write_atomic_with(&path, |_| Err(full.into())).unwrap_err();
        let text = format!("{error:#}");
        assert!(
            text.starts_with(&format!("writing {}", path.display())),
            "{text}"
        );
        assert!(text.contains("No space left on device"), "{text}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[test]
    fn a_streamed_table_of_numbers_has_the_bytes_of_the_csv_writers_table_of_number_cells() {
        // Reference: the csv crate's writer with `number` cells (the former route), on values
        // whose text is unusual (signed zero, non-finite, subnormal, huge, integral) and a header
        // that needs quoting; rows long enough to cross the 64 KiB chunks.
        let values = [
            0.0,
            -0.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            5e-324,
            1e300,
            -123456789.0,
            0.1 + 0.2,
            2.5e-16,
        ];
        let header = ["time_s", "a,b", "quote\"d"];
        let rows: Vec<Vec<f64>> = (0..20_000)
            .map(|i| {
                (0..3)
                    .map(|c| values[(i * 3 + c) % values.len()] * (1 + i) as f64)
                    .collect()
            })
            .collect();
        let scratch = tempfile::tempdir().unwrap();
        let path = scratch.path().join("table.csv");
        write_numbers_csv_streamed(&path, &header, rows.iter().map(|r| r.iter().copied())).unwrap();
        let mut expected = csv::Writer::from_writer(Vec::new());
        expected.write_record(header).unwrap();
        for row in &rows {
            expected
                .write_record(row.iter().map(|&v| number(v)))
                .unwrap();
        }
        let expected = expected.into_inner().unwrap();
        assert!(expected.len() > 1 << 17, "{} bytes", expected.len());
        assert!(std::fs::read(&path).unwrap() == expected);
    }
}
