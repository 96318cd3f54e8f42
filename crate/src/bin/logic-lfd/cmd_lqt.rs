//! `logic-lfd lqt CASE.json [--pretty]`: the LQT-CP contract (`docs/formats.md`).

use crate::exit;
use logic_lfd::lqt::LqtError;
use logic_lfd::lqt::{run_case, CaseInput};
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `logic-lfd lqt`.
#[derive(clap::Args)]
pub struct Args {
    /// The case (JSON, format of docs/formats.md).
    pub case: PathBuf,
    /// Pretty-print the output object.
    #[arg(long)]
    pub pretty: bool,
}

/// Read the case, solve it, print the output object on stdout.
pub fn run(args: Args) -> ExitCode {
    let file = args.case.display().to_string();
    let text = match std::fs::read_to_string(&args.case) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("{file}: cannot read: {e}");
            return ExitCode::from(exit::BAD_INPUT);
        }
    };
    let result = CaseInput::from_json_str(&text).and_then(|input| run_case(&input));
    match result {
        Ok(out) => {
            let s = if args.pretty {
                serde_json::to_string_pretty(&out)
            } else {
                serde_json::to_string(&out)
            };
            match s {
                Ok(s) => {
                    println!("{s}");
                    ExitCode::from(exit::OK)
                }
                Err(e) => {
                    eprintln!("{file}: cannot serialise the output: {e}");
                    ExitCode::from(exit::BAD_INPUT)
                }
            }
        }
        Err(e @ LqtError::Json { .. }) => {
            eprintln!("{file}:{e}");
            ExitCode::from(exit::BAD_INPUT)
        }
        Err(e) => {
            eprintln!("{file}: {e}");
            ExitCode::from(exit::BAD_INPUT)
        }
    }
}
