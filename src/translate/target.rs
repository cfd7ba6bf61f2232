//! The context's drawable as the renderer sees it: made current on a drawable (GLX 1.4
//! section 3.3.7) the viewport takes its size the first time only, and the renderer is told
//! where frames go ([`crate::frame::FrameSink::set_target`]) whenever that changes, including
//! when the window is resized (which never changes the viewport).

use super::Context;
use crate::frame::{Surface, Target};

impl Context {
    /// Called when the context is made current on a drawable: sizes the viewport the first
    /// time (see [`Context::bind_drawable`]) and tells the renderer the new target.
    pub fn bind_target(&mut self, target: Target) {
        let [w, h] = target.size;
        self.bind_drawable(w.min(i32::MAX as u32) as i32, h.min(i32::MAX as u32) as i32);
        if self.target != Some(target) {
            self.target = Some(target);
            self.sink.set_target(target);
        }
    }

    /// The current drawable now measures `width` × `height` and has swap interval
    /// `swap_interval` (checked at each swap): a change is passed to the renderer; the
    /// viewport is left alone.
    pub fn refresh_target(&mut self, width: i32, height: i32, swap_interval: u32) {
        self.drawable_size = Some((width, height));
        let size = [width.max(0) as u32, height.max(0) as u32];
        self.frame.size = size;
        let drawable = self.target.unwrap_or(Target { size, surface: Surface::Offscreen, swap_interval, samples: 1, alpha: true });
        let target = Target { size, swap_interval, ..drawable };
        if self.target != Some(target) {
            self.target = Some(target);
            self.sink.set_target(target);
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use parking_lot::Mutex;

    use crate::frame::Frame;
    use crate::frame::{FrameSink, Surface, Target};
    use crate::translate::Context;
    use crate::translate::context::ContextConfig;
    use crate::translate::gl;

    /// Keeps the targets it is given.
    #[derive(Clone, Default)]
    struct Targets(Arc<Mutex<Vec<Target>>>);

    impl FrameSink for Targets {
        fn present(&mut self, _frame: Frame) {}
        fn set_target(&mut self, target: Target) {
            self.0.lock().push(target);
        }
    }

    #[test]
    fn targets_reach_the_sink_once_per_change_and_resizes_keep_the_viewport() {
        let sink = Targets::default();
        let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(sink.clone()) });
        let first = Target { size: [320, 200], surface: Surface::Offscreen, swap_interval: 1, samples: 1, alpha: true };
        ctx.bind_target(first);
        ctx.bind_target(first);
        assert_eq!(*sink.0.lock(), [first]);
        ctx.refresh_target(320, 200, 1);
        assert_eq!(sink.0.lock().len(), 1, "same size: nothing new");
        ctx.refresh_target(640, 480, 1);
        assert_eq!(sink.0.lock()[1], Target { size: [640, 480], surface: Surface::Offscreen, swap_interval: 1, samples: 1, alpha: true });
        assert_eq!(ctx.query(gl::GL_VIEWPORT).unwrap().to_ints(), [0, 0, 320, 200], "GLX: resizes keep the viewport");
        assert_eq!(ctx.frame.size, [640, 480], "the frame is rendered at the new size");
        // Binding another drawable tells the sink; the viewport still keeps its first value.
        ctx.bind_target(Target { size: [100, 50], surface: Surface::Offscreen, swap_interval: 1, samples: 1, alpha: true });
        assert_eq!(sink.0.lock().len(), 3);
        ctx.refresh_target(100, 50, 0);
        assert_eq!(sink.0.lock()[3].swap_interval, 0, "a new swap interval reaches the sink");
        assert_eq!(ctx.query(gl::GL_VIEWPORT).unwrap().to_ints(), [0, 0, 320, 200]);
    }
}
