//! `castellan`: the command-line front end. It parses arguments, reads inputs, calls the
//! library crates and writes outputs atomically; the work itself lives in the libraries.

mod cli;
mod corners_cmd;
mod demo_cmd;
mod facade_cmd;
mod flags;
#[cfg(test)]
mod fuzz_tests;
mod gothic_cmd;
mod images;
mod output;
mod plan_batch;
mod plan_cmd;
mod progress;
mod reconstruct_cmd;
mod reconstruction;
mod rectify_cmd;
mod report;
mod serve;
mod text;
mod vsg_cmd;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    output::clean_up_on_interrupt();
    match dispatch(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// Runs one command (main, and the fuzz tests that drive every command in-process).
fn dispatch(command: cli::Command) -> anyhow::Result<()> {
    match command {
        cli::Command::Vsg(cli::VsgCommand::Run(args)) => vsg_cmd::run(&args),
        cli::Command::Corners(args) => corners_cmd::run(&args),
        cli::Command::CornersEval(args) => corners_cmd::eval(&args),
        cli::Command::Plan(args) => plan_cmd::run(&args),
        cli::Command::Rectify(args) => rectify_cmd::run(&args),
        cli::Command::Facade(args) => facade_cmd::run(&args),
        cli::Command::Gothic(args) => gothic_cmd::run(&args),
        cli::Command::Reconstruct(args) => reconstruct_cmd::run(&args),
        cli::Command::Demo(args) => demo_cmd::run(&args),
        cli::Command::Serve(args) => serve::run(&args),
    }
}
