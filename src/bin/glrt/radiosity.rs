//! `glrt radiosity FILE`: replays a capture without drawing and runs the radiosity precompute
//! on the static world of its last frame with the `[radiosity]` settings (`glrt.toml`,
//! `GLRT_*`): times, sizes and errors as Markdown (`glrt::render::radiosity::precompute`).

use std::sync::Arc;

use glrt::frame::FrameSink;
use glrt::replay::{self, reader::Capture};

/// Keeps the static world of the last frame presented.
#[derive(Clone, Default)]
struct LastWorld(Arc<parking_lot::Mutex<Vec<Arc<glrt::frame::world::StaticChunk>>>>);

impl FrameSink for LastWorld {
    fn present(&mut self, frame: glrt::frame::Frame) {
        *self.0.lock() = frame.static_world.to_vec();
    }
}

/// Runs the precompute on `capture`'s last static world and prints its report.
pub fn run(capture: &Capture) -> Result<(), String> {
    let world = LastWorld::default();
    let sink = world.clone();
    let options = replay::Options { sink: Some(replay::SinkWrapper(Arc::new(move |_| Box::new(sink.clone())))), ..Default::default() };
    replay::run(capture, &options)?;
    let chunks = world.0.lock().clone();
    if chunks.is_empty() {
        return Err("radiosity: the capture's last frame has no static world".to_owned());
    }
    let report = glrt::render::radiosity::precompute::run(&chunks, &glrt::render::radiosity::settings::Settings::of_process())?;
    print!("{}", report.markdown());
    Ok(())
}
