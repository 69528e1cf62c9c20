//! The `truecost` command line: see `truecost --help`.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
