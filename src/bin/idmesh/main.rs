//! The `idmesh` command line: `idmesh triangle [SWITCHES] FILE` (Triangle-compatible 2D
//! meshing) and `idmesh tetgen [SWITCHES] FILE` (TetGen-compatible 3D meshing).
//!
//! Exit status 0 on success; 1 with a single line `idmesh: <message>` on standard error on any
//! error, including an internal one (a panic is caught and reported the same way); 130 after
//! Ctrl-C, which stops a run without leaving output files (see `progress_ui`).

mod names;
mod progress_ui;
mod show_cmd;
mod tetgen_cmd;
mod triangle_cmd;

use std::ffi::OsString;
use std::process::ExitCode;

const USAGE: &str = "\
idmesh: quality Delaunay meshing (drop-in alternative to Triangle and TetGen).

Usage:
  idmesh triangle [-SWITCHES] FILE   2D meshing with Triangle's switches and file formats
  idmesh tetgen [-SWITCHES] FILE     3D meshing with TetGen's switches and file formats
  idmesh show STEM [-o OUT.svg|png]  a picture of a mesh coloured by quality
  idmesh triangle --help             the 2D switches
  idmesh tetgen --help               the 3D switches
  idmesh --version

Examples:
  idmesh triangle -pq30a0.01V examples/data/square_hole.poly
  idmesh tetgen -pq1.414a0.01V examples/data/3d_box_hole.poly
";

fn main() -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        let text = info.to_string().replace('\n', " ");
        eprintln!("idmesh: internal error (please report): {text}");
    }));
    let args: Vec<OsString> = std::env::args_os().skip(1).collect();
    match std::panic::catch_unwind(|| run(&args)) {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(_)) if progress_ui::interrupted() => {
            eprintln!("idmesh: interrupted");
            ExitCode::from(progress_ui::EXIT_INTERRUPTED)
        }
        Ok(Err(message)) => {
            // Keep the promise of a single line whatever the message holds.
            eprintln!("idmesh: {}", message.trim_end().replace('\n', "; "));
            ExitCode::from(1)
        }
        // The panic hook has already printed the line.
        Err(_) => ExitCode::from(1),
    }
}

fn run(args: &[OsString]) -> Result<(), String> {
    let args = args
        .iter()
        .map(|a| {
            a.to_str()
                .map(str::to_string)
                .ok_or_else(|| format!("argument {a:?} is not valid UTF-8"))
        })
        .collect::<Result<Vec<String>, String>>()?;
    match args.first().map(String::as_str) {
        None => Err("no command given; try 'idmesh --help'".into()),
        Some("--help" | "-h" | "help") => {
            print!("{USAGE}");
            Ok(())
        }
        Some("--version") => {
            println!("idmesh {}", env!("CARGO_PKG_VERSION"));
            Ok(())
        }
        Some("triangle") => triangle_cmd::main(&args[1..]),
        Some("tetgen") => tetgen_cmd::main(&args[1..]),
        Some("show") => show_cmd::main(&args[1..]),
        Some(other) => Err(format!("unknown command '{other}'; try 'idmesh --help'")),
    }
}
