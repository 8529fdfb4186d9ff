//! Measured CoR data: a CSV with the header `v0,e` (any column order, other columns ignored,
//! no column named twice), one collision per row: the impact speed ṽ0 > 0 [m/s] and the CoR ẽ ∈ [0, 1].
//!
//! Reading is bounded: at most [`MAX_FILE_BYTES`] bytes, [`MAX_LINE_CHARS`] characters per
//! line and [`MAX_ROWS`] rows, so a wrong file (`/dev/zero`, a log) is refused quickly.

use std::fmt;
use std::io::Read;
use std::path::Path;

/// Largest data file read [bytes] (4 MiB: some 10⁵ rows of two numbers).
pub const MAX_FILE_BYTES: u64 = 4 << 20;
/// Longest line [characters].
pub const MAX_LINE_CHARS: usize = 1000;
/// Most data rows (the cost J evaluates one CoR per row).
pub const MAX_ROWS: usize = 10_000;
/// Longest echo of a user's text in a message [characters], the ellipsis included.
pub const ECHO_CHARS: usize = 40;

/// A user's text as messages show it: control characters escaped (`\n`, `\t`, `\0`,
/// `\x1b`, `\u{85}`) and cut to [`ECHO_CHARS`] characters with an ellipsis, so one bad value
/// cannot flood or garble a terminal.
pub fn echo(text: &str) -> String {
    let mut out = String::new();
    let mut shown = 0;
    for (i, c) in text.char_indices() {
        let piece = match c {
            '\n' => "\\n".to_string(),
            '\r' => "\\r".to_string(),
            '\t' => "\\t".to_string(),
            '\0' => "\\0".to_string(),
            c if (c as u32) < 0x80 && c.is_control() => format!("\\x{:02x}", c as u32),
            c if c.is_control() || matches!(c, '\u{2028}' | '\u{2029}' | '\u{feff}') => {
                format!("\\u{{{:x}}}", c as u32)
            }
            c => c.to_string(),
        };
        let len = piece.chars().count();
        // keep room for the ellipsis unless this piece ends the text
        let last = i + c.len_utf8() == text.len();
        if shown + len > ECHO_CHARS - usize::from(!last) {
            out.push('…');
            return out;
        }
        shown += len;
        out.push_str(&piece);
    }
    out
}

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

    /// Reads a `v0,e` CSV file (UTF-8, a leading byte-order mark allowed), at most
    /// [`MAX_FILE_BYTES`] of it.
    pub fn read(path: &Path) -> Result<Self, DataError> {
        let name = echo(&path.to_string_lossy());
        let cannot = |e: std::io::Error| DataError(format!("'{name}': cannot read: {e}"));
        let file = std::fs::File::open(path).map_err(cannot)?;
        if file.metadata().map(|m| m.is_dir()).unwrap_or(false) {
            return Err(DataError(format!(
                "'{name}' is a directory, not a CSV file"
            )));
        }
        let mut bytes = Vec::new();
        file.take(MAX_FILE_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(cannot)?;
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(DataError(format!(
                "'{name}' is larger than {} MiB, the most read",
                MAX_FILE_BYTES >> 20
            )));
        }
        let text = String::from_utf8(bytes)
            .map_err(|e| DataError(format!("'{name}' is not UTF-8 text ({e})")))?;
        Self::parse(&text).map_err(|e| DataError(format!("'{name}': {e}")))
    }

    /// Parses CSV text: a header naming the columns `v0` and `e` (each once, nothing else),
    /// then one row per collision. A leading byte-order mark is dropped; blank lines and lines
    /// starting with `#` are skipped. A malformed row is reported with its line number
    /// (1-based, the header is line 1 when nothing precedes it) and its content (shortened).
    pub fn parse(text: &str) -> Result<Self, DataError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim_end_matches('\r')))
            .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
        let long = |ln: usize, line: &str| {
            (line.chars().count() > MAX_LINE_CHARS).then(|| {
                DataError(format!(
                    "line {ln}: '{}': longer than {MAX_LINE_CHARS} characters",
                    echo(line)
                ))
            })
        };
        let Some((hline, header)) = lines.next() else {
            return Err(DataError("empty file: a header 'v0,e' is required".into()));
        };
        if let Some(e) = long(hline, header) {
            return Err(e);
        }
        let names: Vec<String> = header
            .split(',')
            .map(|s| s.trim().trim_matches('"').to_ascii_lowercase())
            .collect();
        let is_v0 = |n: &String| n == "v0" || n == "v_0";
        let is_e = |n: &String| n == "e" || n == "cor";
        let count = |f: &dyn Fn(&String) -> bool| names.iter().filter(|n| f(n)).count();
        let repeated = (1..names.len()).any(|i| names[..i].contains(&names[i]));
        if count(&is_v0) != 1 || count(&is_e) != 1 || repeated {
            return Err(DataError(format!(
                "line {hline}: '{}': the header must name the columns v0 and e once each, and \
                 no column twice (e.g. 'v0,e')",
                echo(header)
            )));
        }
        let iv = names.iter().position(is_v0).unwrap_or(0);
        let ie = names.iter().position(is_e).unwrap_or(1);
        let (mut v0, mut e) = (Vec::new(), Vec::new());
        for (ln, line) in lines {
            if let Some(e) = long(ln, line) {
                return Err(e);
            }
            if v0.len() == MAX_ROWS {
                return Err(DataError(format!(
                    "line {ln}: more than {MAX_ROWS} data rows, the most read"
                )));
            }
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            if cells.len() != names.len() {
                return Err(DataError(format!(
                    "line {ln}: '{}': {} field(s), the header has {}",
                    echo(line),
                    cells.len(),
                    names.len()
                )));
            }
            let num = |i: usize, what: &str| -> Result<f64, DataError> {
                cells[i].parse::<f64>().map_err(|_| {
                    DataError(format!(
                        "line {ln}: '{}': {what} '{}' is not a number",
                        echo(line),
                        echo(cells[i])
                    ))
                })
            };
            let (v, c) = (num(iv, "v0")?, num(ie, "e")?);
            check_pair(v, c).map_err(|m| DataError(format!("line {ln}: '{}': {m}", echo(line))))?;
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
        return Err(format!("v0 = {v:e} must be a finite number > 0"));
    }
    if !(0.0..=1.0).contains(&e) {
        return Err(format!("e = {e:e} must be a number in [0, 1]"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn echo_escapes_control_characters_and_shortens() {
        assert_eq!(echo("1.5"), "1.5");
        assert_eq!(echo("a\nb\t\u{1b}[2J\0\u{85}"), r"a\nb\t\x1b[2J\0\u{85}");
        let cut = echo(&"9".repeat(1000));
        assert_eq!(cut.chars().count(), ECHO_CHARS);
        assert!(cut.ends_with('…'));
        // exactly the limit: no ellipsis
        assert_eq!(echo(&"9".repeat(ECHO_CHARS)), "9".repeat(ECHO_CHARS));
    }

    #[test]
    fn header_with_a_bom_is_read_and_a_repeated_column_refused() {
        let d = CorData::parse("\u{feff}v0,e\n1,0.5\n").unwrap();
        assert_eq!((d.v0.clone(), d.e.clone()), (vec![1.0], vec![0.5]));
        for h in ["v0,e,e", "v0,v_0,e", "e,cor,v0", "v0,e,x,x"] {
            let err = CorData::parse(&format!("{h}\n1,0.5,0.5,1\n")).unwrap_err();
            assert!(err.0.contains("twice"), "{h}: {err}");
        }
    }

    #[test]
    fn long_lines_and_too_many_rows_are_refused() {
        let err = CorData::parse(&format!("v0,e{}\n1,0.5\n", "x".repeat(5000))).unwrap_err();
        assert!(
            err.0.contains("1000 characters") && err.0.len() < 200,
            "{err}"
        );
        let rows = format!("v0,e\n{}", "1,0.5\n".repeat(MAX_ROWS));
        assert_eq!(CorData::parse(&rows).unwrap().len(), MAX_ROWS);
        let err = CorData::parse(&format!("{rows}1,0.5\n")).unwrap_err();
        assert!(err.0.contains("rows"), "{err}");
    }
}
