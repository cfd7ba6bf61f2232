//! The Vulkan raster renderer on Mesa lavapipe (the machine's Vulkan driver when its ICD file
//! is missing), driven through `translate::Context` or frames built by hand, one test binary:
//! draws and read-back ([`draws`]), the fixed-function shaders ([`fixed_function`]), the pixel
//! path ([`pixels`]), colour buffers ([`buffers`]), framebuffer objects ([`fbo`]),
//! multisampling ([`msaa`]), RGB drawables ([`rgb`]), OpenGL 2.0 fixed-function features
//! ([`gl20`]) and programs ([`program`]), texture formats ([`texture_formats`]), frames
//! submitted in parts ([`parts`]) and radiosity's indirect light in the lighting
//! ([`radiosity`]). Each test
//! owns its renderer and context.

#[path = "../lavapipe/mod.rs"]
mod lavapipe;

mod buffers;
mod draws;
mod fbo;
mod fixed_function;
mod gl20;
mod msaa;
mod parts;
mod pixels;
mod program;
mod radiosity;
mod rgb;
mod texture_formats;
