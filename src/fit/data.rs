//! Measured CoR data: a CSV with the header `v0,e` (any column order, extra columns
//! ignored), one collision per row: the impact speed ṽ0 > 0 [m/s] and the CoR ẽ ∈ [0, 1].

use std::fmt;
use std::path::Path;

/// M measured collisions (M ≥ 1): speeds and CoRs, in file order.
#[derive(Clone, Debug, PartialEq)]
pub struct CorData {
    pub v0: Vec<f64>,
    pub e: Vec<f64>,
}

/// Why a data file was refused: the message names the file line and its content.
#[derive(Clone, Debug, PartialEq)]
pub struct DataError(pub String);

impl fmt::Display for DataError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}
impl std::error::Error for DataError {}

impl CorData {
    /// Builds a data set from speeds and CoRs, checking every pair (v0 finite and > 0,
    /// e ∈ [0, 1]) and the lengths.
    pub fn new(v0: Vec<f64>, e: Vec<f64>) -> Result<Self, DataError> {
        if v0.len() != e.len() {
            return Err(DataError(format!(
                "{} speeds but {} CoRs",
                v0.len(),
                e.len()
            )));
        }
        if v0.is_empty() {
            return Err(DataError(
                "no data: at least one (v0, e) pair is needed".into(),
            ));
        }
        for (i, (&v, &c)) in v0.iter().zip(&e).enumerate() {
            check_pair(v, c).map_err(|m| DataError(format!("pair {}: {m}", i + 1)))?;
        }
        Ok(Self { v0, e })
    }

    /// The number of collisions M.
    pub fn len(&self) -> usize {
        self.v0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.v0.is_empty()
    }

    /// Reads a `v0,e` CSV file.
    pub fn read(path: &Path) -> Result<Self, DataError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| DataError(format!("cannot read '{}': {e}", path.display())))?;
        Self::parse(&text).map_err(|e| DataError(format!("'{}': {e}", path.display())))
    }

    /// Parses CSV text: a header naming the columns `v0` and `e`, then one row per collision.
    /// Blank lines and lines starting with `#` are skipped. A malformed row is reported with
    /// its line number (1-based, the header is line 1 when nothing precedes it) and content.
    pub fn parse(text: &str) -> Result<Self, DataError> {
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim_end_matches('\r')))
            .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
        let Some((hline, header)) = lines.next() else {
            return Err(DataError("empty file: a header 'v0,e' is required".into()));
        };
        let names: Vec<String> = header
            .split(',')
            .map(|s| s.trim().trim_matches('"').to_ascii_lowercase())
            .collect();
        let col = |want: &[&str]| names.iter().position(|n| want.contains(&n.as_str()));
        let (Some(iv), Some(ie)) = (col(&["v0", "v_0"]), col(&["e", "cor"])) else {
            return Err(DataError(format!(
                "line {hline}: '{header}': the header must name the columns v0 and e \
                 (e.g. 'v0,e')"
            )));
        };
        let (mut v0, mut e) = (Vec::new(), Vec::new());
        for (ln, line) in lines {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            if cells.len() != names.len() {
                return Err(DataError(format!(
                    "line {ln}: '{line}': {} field(s), the header has {}",
                    cells.len(),
                    names.len()
                )));
            }
            let num = |i: usize, what: &str| -> Result<f64, DataError> {
                cells[i].parse::<f64>().map_err(|_| {
                    DataError(format!(
                        "line {ln}: '{line}': {what} '{}' is not a number",
                        cells[i]
                    ))
                })
            };
            let (v, c) = (num(iv, "v0")?, num(ie, "e")?);
            check_pair(v, c).map_err(|m| DataError(format!("line {ln}: '{line}': {m}")))?;
            v0.push(v);
            e.push(c);
        }
        if v0.is_empty() {
            return Err(DataError(
                "no data rows after the header: at least one (v0, e) pair is needed".into(),
            ));
        }
        Ok(Self { v0, e })
    }

    /// The data as CSV text with the header `v0,e` (shortest round-trip decimals).
    pub fn to_csv(&self) -> String {
        let mut s = String::from("v0,e\n");
        for (v, c) in self.v0.iter().zip(&self.e) {
            s.push_str(&format!("{v},{c}\n"));
        }
        s
    }
}

fn check_pair(v: f64, e: f64) -> Result<(), String> {
    if !(v.is_finite() && v > 0.0) {
        return Err(format!("v0 = {v} must be a finite number > 0"));
    }
    if !(0.0..=1.0).contains(&e) {
        return Err(format!("e = {e} must be a number in [0, 1]"));
    }
    Ok(())
}
