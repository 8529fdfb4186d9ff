//! Measured CoR data: a CSV with the header `v0,e` (any column order, other columns ignored
//! unless a name is a near miss of an optional one — `sigm`, `tcs` are refused —, no column
//! named twice), one collision per row: the impact speed ṽ0 > 0 [m/s] and the CoR ẽ ∈ [0, 1].
//!
//! Optional columns (issue #31):
//! - `sigma`: the error of that row's e (> 0): a standard deviation for `fit` (weights 1/σ²,
//!   as lmfit's and curve_fit's `sigma`), the bound ±σ of set-membership `identify`;
//! - `tc`: the contact duration t_s of that collision (> 0), in units of the base time scale
//!   T_c,b = T_c(v0 = 1 m/s) (eq:BWSHCCM_T_c: T_c = T_c,b v0^(−(p−1)/(p+1))), so that the model's
//!   value is T_s(𝓟(P*, v0)) v0^(−(p−1)/(p+1)) — a number of P* alone;
//! - `tc_sigma`: the error of that row's tc (> 0, only with `tc`).
//!
//! Reading is bounded: at most [`MAX_FILE_BYTES`] bytes, [`MAX_LINE_CHARS`] characters per
//! line and [`MAX_ROWS`] rows, so a wrong file (`/dev/zero`, a log) is refused quickly.

use std::fmt;
use std::io::Read;
use std::path::Path;

/// Largest data file read \[bytes\] (4 MiB: some 10⁵ rows of two numbers).
pub const MAX_FILE_BYTES: u64 = 4 << 20;
/// Longest line \[characters\].
pub const MAX_LINE_CHARS: usize = 1000;
/// Most data rows (the cost J evaluates one CoR per row).
pub const MAX_ROWS: usize = 10_000;
/// Longest echo of a user's text in a message \[characters\], the ellipsis included.
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
            // controls, line breaks, and the invisible format characters that reorder or hide
            // text on a terminal (bidirectional overrides and isolates, zero-width ones)
            c if c.is_control()
                || matches!(
                    c,
                    '\u{2028}' | '\u{2029}' | '\u{feff}' | '\u{061c}' | '\u{00ad}'
                )
                || ('\u{200b}'..='\u{200f}').contains(&c)
                || ('\u{202a}'..='\u{202e}').contains(&c)
                || ('\u{2060}'..='\u{206f}').contains(&c) =>
            {
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

/// The edit distance of `a` and `b` (insertions, deletions, substitutions; by characters).
fn edits(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let here = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb))
                .min(row[j] + 1)
                .min(here + 1);
            prev = here;
        }
    }
    row[b.len()]
}

/// M measured collisions (M ≥ 1): speeds and CoRs, in file order, and the optional columns of
/// the module doc (each `None` or of length M).
#[derive(Clone, Debug, PartialEq)]
pub struct CorData {
    pub v0: Vec<f64>,
    pub e: Vec<f64>,
    /// Per-row error of e (> 0).
    pub sigma: Option<Vec<f64>>,
    /// Per-row contact duration in units of T_c(v0 = 1 m/s) (> 0).
    pub tc: Option<Vec<f64>>,
    /// Per-row error of tc (> 0).
    pub tc_sigma: Option<Vec<f64>>,
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
        Ok(Self {
            v0,
            e,
            sigma: None,
            tc: None,
            tc_sigma: None,
        })
    }

    /// Adds the optional columns (each of length M, every value finite and > 0; `tc_sigma`
    /// only with `tc`).
    pub fn with_columns(
        mut self,
        sigma: Option<Vec<f64>>,
        tc: Option<Vec<f64>>,
        tc_sigma: Option<Vec<f64>>,
    ) -> Result<Self, DataError> {
        if tc_sigma.is_some() && tc.is_none() {
            return Err(DataError("tc_sigma is given without tc".into()));
        }
        for (name, col) in [("sigma", &sigma), ("tc", &tc), ("tc_sigma", &tc_sigma)] {
            if let Some(c) = col {
                if c.len() != self.len() {
                    return Err(DataError(format!(
                        "{} values of {name} for {} rows",
                        c.len(),
                        self.len()
                    )));
                }
                for (i, &x) in c.iter().enumerate() {
                    check_positive(name, x)
                        .map_err(|m| DataError(format!("row {}: {m}", i + 1)))?;
                }
            }
        }
        self.sigma = sigma;
        self.tc = tc;
        self.tc_sigma = tc_sigma;
        Ok(self)
    }

    /// The error of row i's e: its `sigma`, or `default`.
    pub fn e_error(&self, i: usize, default: f64) -> f64 {
        self.sigma.as_ref().map_or(default, |s| s[i])
    }

    /// The error of row i's tc: its `tc_sigma`, or `default`.
    pub fn tc_error(&self, i: usize, default: f64) -> f64 {
        self.tc_sigma.as_ref().map_or(default, |s| s[i])
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
        let optional = |n: &str| names.iter().position(|x| x == n);
        let (isg, itc, itcs) = (optional("sigma"), optional("tc"), optional("tc_sigma"));
        if itcs.is_some() && itc.is_none() {
            return Err(DataError(format!(
                "line {hline}: '{}': a column tc_sigma needs a column tc",
                echo(header)
            )));
        }
        // another column is ignored, unless its name is a near miss of an optional one: a
        // misspelt `sigm` would fit unweighted without a word (χ² 0.06 instead of 565)
        for n in &names {
            if is_v0(n) || is_e(n) || ["sigma", "tc", "tc_sigma"].contains(&n.as_str()) {
                continue;
            }
            if let Some(want) = [("sigma", 2), ("tc_sigma", 2), ("tc", 1)]
                .iter()
                // (a name of two letters, `ts`, is too short to be told from tc by a letter)
                .find(|(want, d)| n.chars().count() > 2 && edits(n, want) <= *d)
            {
                return Err(DataError(format!(
                    "line {hline}: the column '{}' is not one of v0, e, sigma, tc, tc_sigma: a \
                     misspelt {}? (another name is ignored; rename it so)",
                    echo(n),
                    want.0
                )));
            }
        }
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
        let (mut sg, mut tc, mut tcs) = (Vec::new(), Vec::new(), Vec::new());
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
            for (col, name, out) in [
                (isg, "sigma", &mut sg),
                (itc, "tc", &mut tc),
                (itcs, "tc_sigma", &mut tcs),
            ] {
                if let Some(i) = col {
                    let x = num(i, name)?;
                    check_positive(name, x)
                        .map_err(|m| DataError(format!("line {ln}: '{}': {m}", echo(line))))?;
                    out.push(x);
                }
            }
        }
        if v0.is_empty() {
            return Err(DataError(
                "no data rows after the header: at least one (v0, e) pair is needed".into(),
            ));
        }
        let some = |c: Option<usize>, v: Vec<f64>| c.map(|_| v);
        Ok(Self {
            v0,
            e,
            sigma: some(isg, sg),
            tc: some(itc, tc),
            tc_sigma: some(itcs, tcs),
        })
    }

    /// The data as CSV text with the header `v0,e` and the optional columns present
    /// (shortest round-trip decimals).
    pub fn to_csv(&self) -> String {
        let cols: Vec<(&str, &Vec<f64>)> = [
            ("sigma", &self.sigma),
            ("tc", &self.tc),
            ("tc_sigma", &self.tc_sigma),
        ]
        .into_iter()
        .filter_map(|(n, c)| c.as_ref().map(|c| (n, c)))
        .collect();
        let mut s = String::from("v0,e");
        for (n, _) in &cols {
            s.push(',');
            s.push_str(n);
        }
        s.push('\n');
        for (i, (v, c)) in self.v0.iter().zip(&self.e).enumerate() {
            s.push_str(&format!("{v},{c}"));
            for (_, col) in &cols {
                s.push_str(&format!(",{}", col[i]));
            }
            s.push('\n');
        }
        s
    }
}

fn check_positive(name: &str, x: f64) -> Result<(), String> {
    if !(x.is_finite() && x > 0.0) {
        return Err(format!("{name} = {x:e} must be a finite number > 0"));
    }
    Ok(())
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
        // a right-to-left override would reverse the rest of the line on a terminal; the other
        // invisible format characters hide what was written
        assert_eq!(echo("\u{202e}1"), r"\u{202e}1");
        assert_eq!(
            echo("1\u{200b}2\u{2066}3\u{ad}"),
            r"1\u{200b}2\u{2066}3\u{ad}"
        );
        assert_eq!(echo("é½٣"), "é½٣");
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
    fn optional_columns_are_read_checked_and_written_back() {
        let d = CorData::parse("tc,v0,sigma,e,tc_sigma\n3.1,1,0.01,0.8,0.05\n3,2,0.02,0.7,0.04\n")
            .unwrap();
        assert_eq!(d.sigma, Some(vec![0.01, 0.02]));
        assert_eq!(d.tc, Some(vec![3.1, 3.0]));
        assert_eq!(d.tc_sigma, Some(vec![0.05, 0.04]));
        assert_eq!(CorData::parse(&d.to_csv()).unwrap(), d);
        assert_eq!(CorData::parse("v0,e\n1,0.5\n").unwrap().sigma, None);
        // other names are still ignored
        let other = CorData::parse("run,v0,note,e,t_s,ts\n1,1,a,0.5,3,3\n").unwrap();
        assert_eq!((other.v0, other.sigma, other.tc), (vec![1.0], None, None));
        for (text, what) in [
            ("v0,e,sigma\n1,0.5,0\n", "sigma = 0e0"),
            ("v0,e,sigma\n1,0.5,-1\n", "sigma"),
            ("v0,e,tc\n1,0.5,nan\n", "tc = NaN"),
            ("v0,e,tc\n1,0.5,x\n", "tc 'x' is not a number"),
            ("v0,e,tc_sigma\n1,0.5,1\n", "needs a column tc"),
            (
                "v0,e,sigm\n1,0.5,0.1\n",
                "'sigm' is not one of v0, e, sigma, tc, tc_sigma: a misspelt sigma?",
            ),
            ("v0,e,Sigma_\n1,0.5,0.1\n", "a misspelt sigma?"),
            ("v0,e,tcs\n1,0.5,0.1\n", "a misspelt tc?"),
            ("v0,e,tc_sigm\n1,0.5,0.1\n", "a misspelt tc_sigma?"),
        ] {
            let err = CorData::parse(text).unwrap_err();
            assert!(err.0.contains(what), "{text}: {err}");
        }
        let err = CorData::new(vec![1.0], vec![0.5])
            .unwrap()
            .with_columns(None, None, Some(vec![1.0]))
            .unwrap_err();
        assert!(err.0.contains("without tc"), "{err}");
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
