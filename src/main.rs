//! `bwcl`: T_s and the coefficient of restitution of the Bouc–Wen collision models from the
//! command line (see `bwcl --help`). The program lives in [`cli`]; this is its entry point.

mod cli;

fn main() {
    std::process::exit(cli::run())
}
