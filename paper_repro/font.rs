//! The font of every plot (paper_repro, the benchmark generator and criterion's reports):
//! plotters lays out text with a TrueType font that must be registered by hand (the crate is
//! built with `ab_glyph`, for criterion too, since features are unified).

use plotters::style::FontStyle;

/// Font files tried, in order, after $BWCL_FONT (PNG and SVG both need a font for the text
/// layout; Debian/Ubuntu: `apt-get install fonts-dejavu-core`).
const FONT_PATHS: [&str; 6] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/usr/share/fonts/truetype/freefont/FreeSans.ttf",
];

/// Registers a sans-serif font for plotters; returns the file used.
pub fn init_font() -> Result<String, String> {
    let mut tried = Vec::new();
    let env = std::env::var("BWCL_FONT").ok();
    for path in env.iter().map(String::as_str).chain(FONT_PATHS) {
        tried.push(path.to_string());
        if let Ok(bytes) = std::fs::read(path) {
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            for style in [FontStyle::Normal, FontStyle::Bold, FontStyle::Italic] {
                plotters::style::register_font("sans-serif", style, bytes)
                    .map_err(|_| format!("'{path}' is not a usable TrueType font"))?;
            }
            return Ok(path.to_string());
        }
    }
    Err(format!(
        "no font found for the plots (tried {}); install fonts-dejavu-core or set BWCL_FONT \
         to a .ttf file",
        tried.join(", ")
    ))
}
