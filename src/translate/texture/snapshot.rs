//! What each texture unit samples for the next draw: the texture of the highest-priority
//! enabled target (cube map, 3D, 2D, 1D; OpenGL 1.5 section 3.8.15), if it is complete
//! (section 3.8.10), as a [`TextureRef`] whose content is built once per content version.

use std::sync::Arc;

use super::super::Context;
use super::super::gl;
use super::super::limits::MAX_TEXTURE_UNITS;
use super::formats::Base;
use super::image::resolve_indices;
use super::objects::{Level, Target, TextureObject, next_version};
use super::palette::Palette;
use super::params::uses_mipmaps;
use crate::translate::glsl::builtins::{SamplerDepth, sampler_depth};
use crate::frame::texture::{TexImage, TexelFormat, TextureContent, TextureKind, TextureRef};

/// Whether `obj` is complete: its base level exists on every face with a non-zero size (cube
/// faces square and equal), and, when its minification filter uses mipmaps, every level from
/// the base to the 1×1 level (or the max level) halves the one above.
pub fn is_complete(obj: &TextureObject, target: Target) -> bool {
    let base = obj.params.levels[0].max(0) as usize;
    let max = obj.params.levels[1].max(0) as usize;
    let faces = target.faces();
    let Some(first) = obj.level(0, base) else { return false };
    let inner = |l: &Level| l.size.map(|s| s.saturating_sub(2 * l.border).max(1));
    let top = inner(first);
    if top.contains(&0) || first.size[0] == 0 {
        return false;
    }
    for face in 0..faces {
        let Some(l) = obj.level(face, base) else { return false };
        if inner(l) != top || (target == Target::Cube && top[0] != top[1]) {
            return false;
        }
        if !uses_mipmaps(obj.params.min_filter) {
            continue;
        }
        let mut size = top;
        let mut level = base;
        while size.iter().any(|&s| s > 1) && level < max {
            level += 1;
            size = size.map(|s| (s / 2).max(1));
            match obj.level(face, level) {
                Some(l) if inner(l) == size => {}
                _ => return false,
            }
        }
    }
    true
}

/// The image the renderer samples for a level: paletted levels resolved with `shared` when the
/// shared palette is in use.
/// Whether the base level of `obj` has an integer format (EXT_texture_integer). Fixed-function
/// texturing of integer textures is undefined (section 3.8: "the result of using fixed
/// functionality with integer textures is undefined"); glrt keeps it harmless by leaving the
/// unit as if no texture were enabled, so integer levels never reach a frame.
fn is_integer(obj: &TextureObject) -> bool {
    let base = obj.params.levels[0].max(0) as usize;
    obj.level(0, base).is_some_and(|l| l.image.precision == crate::frame::texture::Precision::Integer)
}

fn level_image(level: &Level, shared: Option<&Palette>) -> Arc<TexImage> {
    match (&level.indices, shared) {
        (Some(indices), Some(palette)) => Arc::new(TexImage { texels: resolve_indices(indices, palette), ..(*level.image).clone() }),
        _ => level.image.clone(),
    }
}

/// The key of `obj`'s cached snapshot for its content version and the shared palette's.
fn snapshot_key(obj: &TextureObject, shared: Option<(&Palette, u64)>) -> u64 {
    shared.map_or(obj.version, |(_, v)| v.max(obj.version) ^ (1 << 63))
}

/// The reference of `obj` for a draw when it is complete ([`is_complete`]). A cached snapshot
/// of the current key is returned without the check: snapshots are built only of complete
/// objects, and every change of images or parameters drops them
/// ([`TextureObject::touch`]), so the object is as complete as when it was built. A draw
/// thus costs one comparison per texture, not a walk over its mipmap levels.
fn complete_ref(name: u32, obj: &mut TextureObject, target: Target, shared: Option<(&Palette, u64)>) -> Option<TextureRef> {
    let key = snapshot_key(obj, shared);
    if let Some((_, r)) = obj.snapshot.as_ref().filter(|(k, _)| *k == key) {
        return Some(r.clone());
    }
    is_complete(obj, target).then(|| texture_ref(name, obj, target, shared))
}

/// Builds the reference of `obj` for a draw and caches it as its snapshot.
fn texture_ref(name: u32, obj: &mut TextureObject, target: Target, shared: Option<(&Palette, u64)>) -> TextureRef {
    let key = snapshot_key(obj, shared);
    let palette = shared.map(|(p, _)| p);
    let faces = (0..target.faces())
        .map(|f| obj.faces.get(f).map_or_else(Vec::new, |levels| levels.iter().map(|l| l.as_ref().map(|l| level_image(l, palette))).collect()))
        .collect();
    let base = obj.params.levels[0].max(0) as usize;
    let format = match obj.level(0, base).map(|l| l.base) {
        Some(Base::Texel(f)) => f,
        _ => TexelFormat::Rgba,
    };
    let kind = match target {
        Target::D1 => TextureKind::D1,
        Target::D2 => TextureKind::D2,
        Target::D3 => TextureKind::D3,
        Target::Cube => TextureKind::Cube,
        Target::Rect => TextureKind::Rect,
    };
    let version = if shared.is_some() { next_version() } else { obj.version };
    let mut sampler = obj.params.sampler();
    sampler.border_color = super::formats::expand(format, sampler.border_color);
    let content = Arc::new(TextureContent { kind, format, faces, sampler });
    let r = TextureRef { id: name, version, content };
    obj.snapshot = Some((key, r.clone()));
    r
}

impl Context {
    /// The texture bound to `target` of `unit`, whether or not the target is enabled, as a
    /// program's sampler reads it (`None` when incomplete or past the last unit), with the
    /// depth words of `glrt_SamplerDepth` (`shaders/glsl_builtins.glsl`).
    pub(crate) fn sampler_texture(&mut self, unit: usize, target: Target) -> (Option<TextureRef>, SamplerDepth) {
        let Some(&name) = self.texture.bindings.get(unit).map(|b| &b[target.index()]) else { return (None, [8, 0, 0, 0]) };
        self.with_object(target, name, |obj| {
            let p = &obj.params;
            let depth = obj.level(0, p.levels[0].max(0) as usize).is_some_and(|l| l.base == Base::Texel(TexelFormat::Depth));
            let words = sampler_depth(p.compare_mode, p.compare_func, p.depth_mode, depth);
            (complete_ref(name, obj, target, None), words)
        })
    }

    /// The enabled target of `unit` with the highest priority.
    fn enabled_target(&self, unit: usize) -> Option<Target> {
        [Target::Cube, Target::D3, Target::Rect, Target::D2, Target::D1].into_iter().find(|t| self.enables.unit_on(unit, t.gl()))
    }

    /// The texture each unit samples for the next draw (`None` where texturing is off or the
    /// texture is incomplete). Content versions are unique: the renderer uploads a
    /// `(id, version)` once and reuses it.
    pub fn texture_snapshot(&mut self) -> Vec<Option<TextureRef>> {
        self.texture_snapshot_of([true; MAX_TEXTURE_UNITS]).to_vec()
    }

    /// [`Context::texture_snapshot`] where only the units in `units` may have a texture target
    /// enabled (the others are not looked at); no allocation (a batch merged into the previous
    /// draw drops it).
    pub(crate) fn texture_snapshot_of(&mut self, units: [bool; MAX_TEXTURE_UNITS]) -> [Option<TextureRef>; MAX_TEXTURE_UNITS] {
        let use_shared = self.enables.is_on_const::<{ gl::GL_SHARED_TEXTURE_PALETTE_EXT }>() && !self.texture.shared_palette.entries.is_empty();
        let shared = use_shared.then(|| (self.texture.shared_palette.clone(), self.texture.shared_palette_version));
        std::array::from_fn(|unit| {
            let target = units[unit].then(|| self.enabled_target(unit)).flatten()?;
            let name = self.texture.bindings[unit][target.index()];
            self.with_object(target, name, |obj| {
                if is_integer(obj) {
                    return None;
                }
                complete_ref(name, obj, target, shared.as_ref().map(|(p, v)| (p, *v)))
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn snapshot_follows_enables_priority_and_versions() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 7);
        let px = [255u8, 0, 0, 255];
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 1, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, px.as_ptr().cast()) };
        assert_eq!(ctx.texture_snapshot(), vec![None; 4]);
        ctx.glEnable(gl::GL_TEXTURE_2D);
        let first = ctx.texture_snapshot()[0].clone().expect("unit 0 samples texture 7");
        assert_eq!(first.id, 7);
        assert_eq!(first.content.faces[0][0].as_ref().unwrap().texels, px);
        let again = ctx.texture_snapshot()[0].clone().unwrap();
        assert!(std::sync::Arc::ptr_eq(&first.content, &again.content));
        unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 0, 0, 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, [0u8, 255, 0, 255].as_ptr().cast()) };
        let changed = ctx.texture_snapshot()[0].clone().unwrap();
        assert!(changed.version > first.version);
        assert_eq!(changed.content.faces[0][0].as_ref().unwrap().texels, [0, 255, 0, 255]);
        // The frame keeps the old texels.
        assert_eq!(first.content.faces[0][0].as_ref().unwrap().texels, px);
        // Mipmapping filter with one level: incomplete.
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 8);
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        assert_eq!(ctx.texture_snapshot()[0], None);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_GENERATE_MIPMAP, 1);
        unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 0, 0, 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, px.as_ptr().cast()) };
        let mip = ctx.texture_snapshot()[0].clone().expect("complete after generation");
        assert_eq!(mip.content.faces[0][1].as_ref().unwrap().texels, [64, 0, 0, 64]);
        // A cube map enabled as well wins over 2D, but it is incomplete.
        ctx.glEnable(gl::GL_TEXTURE_CUBE_MAP);
        assert_eq!(ctx.texture_snapshot()[0], None);
    }

    #[test]
    fn a_cached_snapshot_does_not_outlive_the_completeness_it_was_built_for() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glEnable(gl::GL_TEXTURE_2D);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_LINEAR as i32);
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        let complete = ctx.texture_snapshot()[0].clone().expect("one level, no mipmaps: complete");
        assert_eq!(ctx.texture_snapshot()[0].as_ref().map(|t| t.version), Some(complete.version), "the cached snapshot");
        // A mipmapping filter without the levels makes it incomplete, though its images are the same.
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_LINEAR_MIPMAP_LINEAR as i32);
        assert_eq!(ctx.texture_snapshot()[0], None);
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 1, gl::GL_RGBA as i32, 1, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        let mipmapped = ctx.texture_snapshot()[0].clone().expect("complete with its 1x1 level");
        assert!(mipmapped.version > complete.version);
        // A base level past the levels given: incomplete again.
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BASE_LEVEL, 2);
        assert_eq!(ctx.texture_snapshot()[0], None);
    }
}
