//! `crashtest`: the command line. Thin: it parses arguments and calls the harness.

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "crashtest", version, about = "Is your collision code right, how right, how fast, and where does it break?")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run fixture cases through every engine; compare with each case's `expect`
    /// and with the exact referee. Exit 0 when the default engine (collide/robust)
    /// passes every case, 1 when it fails one, 2 for bad input.
    Check {
        /// Fixture files, or folders searched recursively for *.json.
        #[arg(required = true)]
        paths: Vec<PathBuf>,
        /// Print the results as JSON on standard output (the closing
        /// `N passed, M failed` line then goes to standard error).
        #[arg(long)]
        json: bool,
    },
    /// Print the JSON Schema of the fixture format (crashtest-fixture/1).
    Schema,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Check { paths, json } => {
            let loaded = harness::load::load_paths(&paths);
            let result = harness::check::check(&loaded.cases, &loaded.errors);
            if json {
                match serde_json::to_string_pretty(&result) {
                    Ok(s) => println!("{s}"),
                    Err(e) => eprintln!("error: cannot write JSON: {e}"),
                }
                eprintln!("{} passed, {} failed", result.passed, result.failed);
            } else {
                print!("{}", harness::check::render_text(&result));
            }
            ExitCode::from(result.exit_code() as u8)
        }
        Command::Schema => {
            print!("{}", harness::case::json_schema());
            ExitCode::SUCCESS
        }
    }
}
