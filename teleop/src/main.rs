//! `pomdar`: the POMDAR teleoperation and scoring station (its command line is
//! [`teleop::command::cli`]).

fn main() -> std::process::ExitCode {
    teleop::command::cli::main()
}
