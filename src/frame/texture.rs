//! References from draws to texture content (placeholder until texture objects land).

/// A texture as a draw uses it: object name and content version.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct TextureRef {
    /// Texture object name.
    pub id: u32,
    /// Bumped by every change of the texture's images or parameters.
    pub version: u64,
}
