//! The `glrt` command: `info` for now; `replay`, `dump` and `bench` come with captures.

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("info") | None => {
            println!("glrt {}", env!("CARGO_PKG_VERSION"));
            println!("exports: {} functions", glrt::gl_entry::exports::PROCS.len());
        }
        Some(other) => {
            eprintln!("glrt: unknown command '{other}' (known: info)");
            std::process::exit(2);
        }
    }
}
