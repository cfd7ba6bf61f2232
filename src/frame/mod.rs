//! The per-frame scene that `translate` hands to `render` at `glXSwapBuffers` (or at a
//! read-back that needs pixels): draws in object space with their state, lights, fog, clears
//! and viewport. No GL enums here: `translate` converts them to these types.

/// One frame of the program's rendering.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// Frame number, from 0.
    pub number: u64,
    /// Draws in program order.
    pub draws: Vec<Draw>,
}

/// One draw: primitives of one state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Draw {
    /// Vertex count.
    pub vertex_count: usize,
}
