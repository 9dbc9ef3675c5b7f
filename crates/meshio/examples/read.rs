//! Reads one mesh file and prints its size and the time taken: `cargo run --release -p
//! reyes-meshio --example read -- FILE`, under `/usr/bin/time -v` for the peak memory.
//! `--grid N DIR` first writes the benchmark's N x N grid as DIR/grid.obj and DIR/grid.ply.

use std::io::BufWriter;
use std::process::ExitCode;
use std::time::Instant;

#[path = "../benches/grid.rs"]
mod grid;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.as_slice() {
        [flag, n, dir] if flag == "--grid" => {
            let Ok(n) = n.parse() else {
                eprintln!("--grid: '{n}' is not a number");
                return ExitCode::from(2);
            };
            let mesh = grid::grid(n);
            let dir = std::path::Path::new(dir);
            let write = || -> std::io::Result<()> {
                let mut w = BufWriter::new(std::fs::File::create(dir.join("grid.obj"))?);
                reyes_meshio::write_obj(&mesh, &mut w)?;
                let mut w = BufWriter::new(std::fs::File::create(dir.join("grid.ply"))?);
                reyes_meshio::write_ply_binary(&mesh, &mut w, false)
            };
            if let Err(e) = write() {
                eprintln!("{}: {e}", dir.display());
                return ExitCode::from(1);
            }
            ExitCode::SUCCESS
        }
        [file] => {
            let start = Instant::now();
            match reyes_meshio::read(file) {
                Ok(m) => {
                    let s = start.elapsed().as_secs_f64();
                    println!(
                        "{file}: {} points, {} faces in {s:.3} s",
                        m.points.len(),
                        m.face_count()
                    );
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("{e}");
                    ExitCode::from(if e.is_io() { 1 } else { 2 })
                }
            }
        }
        _ => {
            eprintln!("usage: read FILE | read --grid N DIR");
            ExitCode::from(2)
        }
    }
}
