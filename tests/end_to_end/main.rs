//! Programs run end to end through glrt as child processes (`glrt-demo`, Mesa's `glxgears`,
//! `glxinfo`, the `glrt` command), each with its own environment and, where it needs one, its
//! own Xvfb; one test binary: the demo's frames ([`demo`]), presentation on X windows
//! ([`present`]), captures and replays ([`capture_replay`], [`pathtrace_replay`]), the
//! denoiser's quality on the demo's replay ([`denoise`]), raster + radiosity on it
//! ([`radiosity_raster`]) and radiosity in the path tracer ([`radiosity_traced`]), hash
//! tracking of a re-batching program ([`classify_rebatch`]), pass-through ([`passthrough`]),
//! glrt as a glvnd vendor ([`glvnd_vendor`]), programs run by `glrt run` ([`glrt_run`]), an SFML-style program's window changing frame
//! after frame ([`sfml_style`]), a Windows OpenGL program under Wine ([`wine`]), and images against Mesa ([`raster_vs_mesa`]) and an NVIDIA
//! driver ([`raster_vs_nvidia`]).

#[path = "../images/mod.rs"]
mod images;
#[path = "../programs/mod.rs"]
mod programs;
#[path = "../x11/mod.rs"]
mod x11;

mod capture_replay;
mod classify_rebatch;
mod demo;
mod denoise;
mod glrt_run;
mod glvnd_vendor;
mod passthrough;
mod pathtrace_replay;
mod present;
mod radiosity_raster;
mod radiosity_traced;
mod raster_vs_mesa;
mod raster_vs_nvidia;
mod sfml_style;
mod wine;
