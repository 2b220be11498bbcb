//! The one CSV writer of wingcheck (the `csv` crate): every CSV output — `simulate --out
//! run.csv`, the search's `results.csv`, `failures.csv`, `boundary.csv`, `timings.csv`, the
//! report's figure data — goes through [`CsvWriter`], so quoting, line endings and number
//! formatting are the same everywhere (fields quoted only when they must be, `\n` line ends,
//! f64 in Rust's shortest round-trip form).
//!
//! Column names follow one rule, documented with every column in `docs/outputs.md`: letters,
//! digits and `_` only, starting with a letter (numpy's structured loaders keep such names
//! as they are; a `.` or a space would be dropped or replaced), and the unit as a suffix
//! ([`column_name`]).

use std::io::Write;

use crate::number;

/// A CSV writer over any `Write` (a file being staged, a `Vec<u8>`).
pub struct CsvWriter<W: Write> {
    inner: csv::Writer<W>,
}

/// A CSV error with the I/O error it came from when there is one.
fn to_io(e: csv::Error) -> std::io::Error {
    match e.into_kind() {
        csv::ErrorKind::Io(e) => e,
        other => std::io::Error::other(format!("{other:?}")),
    }
}

impl<W: Write> CsvWriter<W> {
    /// A writer whose first record is `header`.
    pub fn new<I, S>(out: W, header: I) -> std::io::Result<CsvWriter<W>>
    where
        I: IntoIterator<Item = S>,
        S: AsRef<[u8]>,
    {
        let inner = csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(out);
        let mut w = CsvWriter { inner };
        w.row(header)?;
        Ok(w)
    }

    /// One record (the fields are quoted where the CSV format needs it).
    pub fn row<I, S>(&mut self, fields: I) -> std::io::Result<()>
    where
        I: IntoIterator<Item = S>,
        S: AsRef<[u8]>,
    {
        self.inner.write_record(fields).map_err(to_io)
    }

    /// Flushes and returns the underlying writer.
    pub fn finish(self) -> std::io::Result<W> {
        self.inner.into_inner().map_err(|e| e.into_error())
    }
}

/// A whole table as CSV text (header, then the rows).
pub fn csv_text<H, S, R, F, T>(header: H, rows: R) -> String
where
    H: IntoIterator<Item = S>,
    S: AsRef<[u8]>,
    R: IntoIterator<Item = F>,
    F: IntoIterator<Item = T>,
    T: AsRef<[u8]>,
{
    let mut w = CsvWriter::new(Vec::new(), header).expect("writing to memory cannot fail");
    for r in rows {
        w.row(r).expect("writing to memory cannot fail");
    }
    String::from_utf8(w.finish().expect("writing to memory cannot fail")).expect("the fields are UTF-8")
}

/// A table of numbers as CSV text (header, then one record per row, each number in the form
/// of [`number`]): the text [`csv_text`] writes for the numbers' texts, with the records
/// joined directly, since a number never needs quoting (digits, `-`, `.`, `NaN`, `inf`).
pub fn csv_numbers<H, S, R, F>(header: H, rows: R) -> String
where
    H: IntoIterator<Item = S>,
    S: AsRef<[u8]>,
    R: IntoIterator<Item = F>,
    F: IntoIterator<Item = f64>,
{
    let mut text = csv_record(header);
    for row in rows {
        for (i, v) in row.into_iter().enumerate() {
            if i > 0 {
                text.push(',');
            }
            crate::push_number(&mut text, v);
        }
        text.push('\n');
    }
    text
}

/// A column name: `base` followed by `_` and the unit suffix (`t_s`, `q_tip_m`, `tau2_N_m`),
/// or `base` alone for a dimensionless column (`suffix` empty).
pub fn column_name(base: &str, suffix: &str) -> String {
    if suffix.is_empty() {
        base.to_string()
    } else {
        format!("{base}_{suffix}")
    }
}

/// A configuration key (`control.a`) as a column name: sections joined by `__`
/// (`control__a`), so the name survives numpy's loaders and maps back to the key (keys hold
/// single `_` only).
pub fn key_column(key: &str) -> String {
    key.replace('.', "__")
}

/// Whether `name` follows the column-name rule (letters, digits, `_`; a letter first).
pub fn is_column_name(name: &str) -> bool {
    name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// A coordinate of a regular grid (a sample time, a grid point) as written in a CSV: rounded to
/// the decimal places that resolve 1/1000 of the grid's `spacing` (so 0.9500000000000001 on a
/// 0.01-s grid is written 0.95), then in the shortest round-trip form. The rounding moves it by
/// at most spacing/2000. A non-positive or non-finite spacing writes [`number`].
pub fn grid_number(x: f64, spacing: f64) -> String {
    if !(spacing > 0.0 && spacing.is_finite() && x.is_finite()) {
        return number(x);
    }
    let decimals = (3.0 - spacing.log10().floor()).clamp(0.0, 17.0) as usize;
    number(format!("{x:.decimals$}").parse().unwrap_or(x))
}

/// One CSV record as text with its line end (for files written row by row).
pub fn csv_record<I, S>(fields: I) -> String
where
    I: IntoIterator<Item = S>,
    S: AsRef<[u8]>,
{
    let mut w = csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(Vec::new());
    w.write_record(fields).expect("writing to memory cannot fail");
    String::from_utf8(w.into_inner().expect("writing to memory cannot fail")).expect("the fields are UTF-8")
}

#[cfg(test)]
mod grid_number_tests {
    use super::*;

    #[test]
    fn grid_coordinates_lose_only_their_noise() {
        // references: the decimal values the grids are made of, written by hand
        assert_eq!(grid_number(0.9500000000000001, 0.01), "0.95");
        assert_eq!(grid_number(0.35000000000000003, 0.05), "0.35");
        assert_eq!(grid_number(20.0, 0.01), "20");
        assert_eq!(grid_number(1e5 - 1e-3, 1e-3), "99999.999");
        assert_eq!(grid_number(0.3, 0.0), "0.3");
    }
}
