//! The `glrt` command: its arguments (parsed by clap, which writes `--help` of the command and
//! of each subcommand and the usage errors) and the subcommands:
//! - `glrt info` ([`info`]): the build and the Vulkan devices, their features and the mode and
//!   tracer each would get; `glrt info FILE`: what a capture holds;
//! - `glrt replay FILE` ([`replay`]): replays a capture headless, optionally writing its frames
//!   as PNG, timing them or printing hash tracking's statistics;
//! - `glrt dump FILE`: the call log of a capture on standard output;
//! - `glrt radiosity FILE` ([`radiosity`]): the radiosity precompute on a capture's static
//!   world, its times, sizes and errors;
//! - `glrt run -- PROGRAM ARGS...` ([`run`]): runs a program on glrt ([`wine`]: what Wine
//!   needs);
//!
//! and [`progress`], the progress bars of long work.
//!
//! Exit status: 0 when the command did what it was asked, 1 when it failed (the message on
//! stderr says why), 2 for a usage error (clap's message names the argument); `glrt run`
//! becomes the program, whose status is then the command's.

mod info;
mod progress;
mod radiosity;
mod replay;
mod run;
mod wine;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use glrt::replay::reader::Capture;

/// glrt: a drop-in libGL.so.1 for OpenGL 1.x programs, rendered with Vulkan (rasterized or path
/// traced). This command runs programs on glrt, inspects the machine and replays captures
/// (GLRT_CAPTURE=FILE).
#[derive(Parser)]
#[command(name = "glrt", version, arg_required_else_help = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Lists the Vulkan devices glrt can use, or summarises a capture
    ///
    /// Without FILE: the build and the Vulkan devices (features, which one glrt uses, and the
    /// mode and tracer each would get). With FILE: what a capture holds (frames, calls, bytes,
    /// textures and the hashes draws used, by which glrt.toml tags textures).
    Info {
        /// A capture file (written by a program run with GLRT_CAPTURE=FILE).
        file: Option<PathBuf>,
    },
    /// Replays a capture headless, optionally writing its frames as PNG
    ///
    /// The environment's GLRT_* settings (GLRT_MODE, GLRT_DEVICE, ...) and glrt.toml apply as
    /// they would to the captured program.
    Replay(replay::Args),
    /// Prints the call log of a capture
    ///
    /// The GLRT_TRACE format, with the captured program's addresses: the same text on every run.
    Dump {
        /// The capture file.
        file: PathBuf,
    },
    /// Runs a program on glrt: glrt run [OPTIONS] -- PROGRAM ARGS...
    ///
    /// The program loads glrt's libGL.so.1 whatever it would have loaded (LD_LIBRARY_PATH, and
    /// glrt as the glvnd GLX vendor); the options become glrt's GLRT_* variables. As a Steam
    /// launch option: glrt run -- %command%
    Run(run::Args),
    /// Runs the radiosity precompute on a capture's static world
    ///
    /// Replays FILE without drawing, then computes form factors, the k-bounce matrix and its
    /// compression for the static world of the last frame with the [radiosity] settings
    /// (glrt.toml, GLRT_*), and prints times, sizes and errors as Markdown. The form factors
    /// are computed on the Vulkan device (GLRT_DEVICE), on the CPU without one.
    Radiosity {
        /// Only the compressed matrix the renderer uses: read from the cache
        /// ($XDG_CACHE_HOME/glrt/radiosity/) when it holds this world's, else computed and
        /// written there; then the per-frame update (direct light and product) under the last
        /// frame's lights, timed on the device
        #[arg(long)]
        matrix: bool,
        /// Instead of a capture's matrix, time the per-frame update (direct light and product)
        /// of about N patches (a closed box lit by four point lights, a synthetic compressed
        /// matrix) on the device (GLRT_DEVICE)
        #[arg(long, value_name = "N", conflicts_with_all = ["matrix", "file"])]
        synthetic: Option<usize>,
        /// Instead of a capture's matrix, time the precompute's stages (colour matrix, k-bounce
        /// matrix on the Vulkan device or the CPU, reordering passes and BC1 blocks) and the
        /// peak memory after each, for the inside of a closed box of about N patches (albedo
        /// 0.5; form factors by the disc approximation, without visibility)
        #[arg(long, value_name = "N", conflicts_with_all = ["matrix", "file", "synthetic"])]
        precompute: Option<usize>,
        /// With --precompute: then compresses the k-bounce matrix again with each reordering
        /// (none; exact and sketched searches, 1 and 2 passes), of the patches in the order
        /// they are built in and shuffled, and prints each one's errors, bytes and time
        #[arg(long, requires = "precompute")]
        orderings: bool,
        /// With a capture: the static world also holds the opaque static draws whose light is
        /// baked (lightmaps, vertex colours), which a game's radiosity leaves out (their bounced
        /// light is the bake's), so that a lightmapped game's geometry and albedos can be
        /// measured (a Quake-3 map); their vertex colours are dropped, the albedo is the
        /// texture's that does not hold light
        #[arg(long, conflicts_with_all = ["synthetic", "precompute"])]
        baked: bool,
        /// The capture file.
        #[arg(required_unless_present_any = ["synthetic", "precompute"])]
        file: Option<PathBuf>,
    },
}

fn main() -> ExitCode {
    default_sigpipe();
    // Usage errors exit here with status 2, `--help` and `--version` with 0.
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info { file: None } => {
            info::build_and_devices();
            Ok(())
        }
        Command::Info { file: Some(file) } => Capture::open(&file).and_then(|capture| info::capture(&capture)),
        Command::Replay(args) => replay::run(&args),
        Command::Dump { file } => Capture::open(&file).and_then(|capture| dump(&capture)),
        Command::Run(args) => run::run(&args),
        Command::Radiosity { synthetic: Some(n), .. } => radiosity::time_synthetic(n),
        Command::Radiosity { precompute: Some(n), orderings, .. } => radiosity::time_precompute(n, orderings),
        Command::Radiosity { matrix, baked, file, .. } => file
            .ok_or_else(|| "radiosity: a capture file, --synthetic N or --precompute N".to_owned())
            .and_then(|file| Capture::open(&file))
            .and_then(|capture| radiosity::run(&capture, matrix, baked)),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("glrt: {e}");
            ExitCode::FAILURE
        }
    }
}

fn dump(capture: &Capture) -> Result<(), String> {
    // The call log is read from the environment at the first GL call, which the replay makes.
    // Safety: single-threaded so far; nothing else reads the environment concurrently.
    unsafe { std::env::set_var("GLRT_TRACE", "/dev/stdout") };
    glrt::replay::run(capture, &glrt::replay::Options::default())?;
    glrt::gl_entry::call_log::flush();
    Ok(())
}

/// Restores the default action of `SIGPIPE`, so that `glrt dump FILE | head` ends quietly as
/// Unix tools do (Rust programs ignore it, which turns a closed pipe into a panic of `println!`).
#[cfg(target_os = "linux")]
fn default_sigpipe() {
    const SIGPIPE: i32 = 13;
    const SIG_DFL: usize = 0;
    unsafe extern "C" {
        fn signal(signum: i32, handler: usize) -> usize;
    }
    // Safety: libc's `signal` with a valid signal number and the default disposition.
    unsafe { signal(SIGPIPE, SIG_DFL) };
}

#[cfg(not(target_os = "linux"))]
fn default_sigpipe() {}
