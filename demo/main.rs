//! glrt-demo: an OpenGL 1.x program written like an old game.

fn main() {}
