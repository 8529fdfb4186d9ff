//! `bwcl`: T_s and the coefficient of restitution of the Bouc–Wen collision models from the
//! command line (see `bwcl --help`). The program lives in the library's [`bwcl::cli`]; this is
//! its entry point.

fn main() {
    std::process::exit(bwcl::cli::run())
}
