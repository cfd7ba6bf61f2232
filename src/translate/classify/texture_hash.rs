//! Texture hashes, the names `glrt.toml` tags textures by: xxh3 of the level-0 texels of the
//! first face (canonical RGBA8, so the same image has the same hash whatever format the
//! program uploaded it in), computed once per content version. A new hash is announced to
//! whoever asked ([`announce_hashes_to`]): the `GLRT_TRACE` call log, which lives above
//! `translate` in `gl_entry`, writes it as `N # texture ID hash 0x…` so that users can learn
//! them.

use std::collections::HashMap;
use std::sync::OnceLock;

use crate::frame::TextureRef;
use crate::frame::texture::TextureContent;

/// The hash of a texture's level-0 content (0 for a texture without a level 0).
pub fn content_hash(content: &TextureContent) -> u64 {
    let level0 = content.faces.first().and_then(|f| f.first()).and_then(Option::as_ref);
    level0.map_or(0, |image| {
        let mut h = xxhash_rust::xxh3::Xxh3::new();
        h.update(&[image.width, image.height, image.depth].map(u32::to_le_bytes).concat());
        h.update(&image.texels);
        h.digest()
    })
}

/// What receives new texture hashes, once installed.
static ANNOUNCE: OnceLock<fn(u32, u64)> = OnceLock::new();

/// Makes `announce` receive the texture id and hash each time a texture's hash is new or
/// has changed. Installed once per process (by the call log when it opens); later calls are
/// ignored.
pub fn announce_hashes_to(announce: fn(u32, u64)) {
    let _ = ANNOUNCE.set(announce);
}

/// Whether something receives new texture hashes (then frames are classified, which hashes
/// their textures, even when no sink reads classes).
pub fn announced() -> bool {
    ANNOUNCE.get().is_some()
}

/// The hash of each texture's current content version.
#[derive(Default)]
pub struct TextureHashes {
    by_id: HashMap<u32, (u64, u64)>,
}

impl TextureHashes {
    /// The hash of `texture`, computed when its version was not seen before.
    pub fn hash(&mut self, texture: &TextureRef) -> u64 {
        if let Some(&(version, hash)) = self.by_id.get(&texture.id)
            && version == texture.version
        {
            return hash;
        }
        let hash = content_hash(&texture.content);
        let changed = self.by_id.insert(texture.id, (texture.version, hash)).is_none_or(|(_, old)| old != hash);
        if changed && let Some(announce) = ANNOUNCE.get() {
            announce(texture.id, hash);
        }
        hash
    }
}

#[cfg(test)]
pub(super) mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::frame::texture::TexImage;

    /// A 1×1 texture `id` of content `version` whose red texel is `texel`.
    pub(crate) fn texture(id: u32, version: u64, texel: u8) -> TextureRef {
        let image = TexImage { width: 1, height: 1, depth: 1, texels: vec![texel, 0, 0, 255], ..TexImage::default() };
        let content = TextureContent { faces: vec![vec![Some(Arc::new(image))]], ..TextureContent::default() };
        TextureRef { id, version, content: Arc::new(content) }
    }

    #[test]
    fn the_hash_follows_the_content_not_the_name_or_version() {
        let mut hashes = TextureHashes::default();
        let a = hashes.hash(&texture(1, 1, 10));
        assert_eq!(hashes.hash(&texture(2, 7, 10)), a, "same texels, another name: same hash");
        assert_ne!(hashes.hash(&texture(1, 2, 11)), a, "new content: new hash");
        // A stale content under a known version is not rehashed: computed once per version.
        assert_ne!(hashes.hash(&texture(1, 2, 10)), a);
        assert_eq!(content_hash(&TextureContent::default()), 0, "no level 0");
    }
}
