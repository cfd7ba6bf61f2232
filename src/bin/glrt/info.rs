//! `glrt info`: without a file, the build and the Vulkan devices of this machine (their
//! features, which one glrt uses, and the mode and tracer each would get); with a capture
//! file, what it holds and the hash of each texture draws used (by which `glrt.toml` tags
//! textures).

use std::sync::Arc;

use glrt::render::devices::{self, DeviceReport};
use glrt::replay::{self, reader::Capture, summary::Summary};
use glrt::translate::classify::report::TextureCatalog;

/// Prints the build and the device list (a machine without Vulkan gets the reason instead).
pub fn build_and_devices() {
    println!("glrt {}", env!("CARGO_PKG_VERSION"));
    println!("exports: {} functions", glrt::gl_entry::exports::PROCS.len());
    match devices::survey() {
        Ok(list) if list.is_empty() => println!("Vulkan devices: none (the loader reports no physical device)"),
        Ok(list) => {
            println!("Vulkan devices (GLRT_DEVICE=INDEX or a part of the name chooses; '>' marks the one glrt uses):");
            for device in &list {
                print!("{}", describe(device));
            }
            if !list.iter().any(|d| d.chosen) {
                println!("GLRT_DEVICE={} matches none of them: frames are not drawn", std::env::var("GLRT_DEVICE").unwrap_or_default());
            }
        }
        Err(e) => println!("Vulkan devices: none ({e})"),
    }
}

/// One device as three or four lines.
fn describe(d: &DeviceReport) -> String {
    let yes = |b: bool| if b { "yes" } else { "no" };
    let mark = if d.chosen { '>' } else { ' ' };
    let mut text = format!(
        "{mark} {}: {}\n    {}, Vulkan {}, {:.1} GiB device memory\n    ray-tracing pipeline: {}, acceleration structures: {}, BC textures: {}\n",
        d.index,
        d.name,
        d.kind,
        d.api_version,
        d.device_memory as f64 / (1u64 << 30) as f64,
        yes(d.ray_tracing_pipeline),
        yes(d.acceleration_structure),
        yes(d.bc_textures),
    );
    match &d.unusable {
        Some(why) => text += &format!("    not usable by glrt: {why}\n"),
        None => text += &format!("    mode: {}\n", d.rendering),
    }
    text
}

/// Prints what `capture` holds, then the textures its draws used (that needs a replay: a
/// capture that cannot be replayed still gets its summary).
pub fn capture(capture: &Capture) -> Result<(), String> {
    print!("{}", Summary::of(capture)?.report(capture));
    let catalog = TextureCatalog::default();
    let sink = catalog.clone();
    let options = replay::Options { sink: Some(replay::SinkWrapper(Arc::new(move |_| Box::new(sink.clone())))), ..Default::default() };
    match replay::run(capture, &options) {
        Ok(_) => print!("{}", catalog.report()),
        Err(e) => println!("textures drawn with: unknown (the replay failed: {e})"),
    }
    Ok(())
}
