//! The compressed k-bounce matrix on disk, so that a static world seen before skips the
//! precompute: one file per [`key`] (the world's hash, which covers its chunks and the patch
//! size, and every setting the matrix depends on), under
//! `$XDG_CACHE_HOME/glrt/radiosity/` (else `~/.cache/glrt/radiosity/`).
//!
//! Format, little-endian: the magic `GLRTRAD\0`, [`VERSION`], the key, `n`, the BC1 image's
//! side, the quantised part's maximum and log shift, the order (`n` words), the BC1 blocks
//! (length, bytes), the sparse rows (`n + 1` offsets, the entry count, columns, values as three
//! floats), and last the XXH3 hash of everything before it. A file that is short, of another
//! version or key, fails its hash or holds sizes that do not fit together is refused with a
//! message saying why; the caller recomputes and writes it again. Files are written under a
//! temporary name and renamed over, so a reader never sees half a file.

use std::path::{Path, PathBuf};

use xxhash_rust::xxh3::{Xxh3, xxh3_64};

use super::bc1::Bc1Matrix;
use super::compress::{CompressedMatrix, LogRange, Reorder};
use super::reorder::Search;
use super::settings::Settings;
use super::sparse::SparseRows;

/// The file's first bytes.
const MAGIC: &[u8; 8] = b"GLRTRAD\0";
/// The format's version: a file of another is recomputed.
pub const VERSION: u32 = 1;

/// The key of the matrix of the world `world_hash` (see
/// [`super::patches::world_hash`]) under `settings`, compressed over `range` and reordered by
/// `reorder`.
pub fn key(world_hash: u64, settings: &Settings, range: LogRange, reorder: Reorder) -> u64 {
    let mut h = Xxh3::new();
    h.update(b"radiosity matrix");
    h.update(&VERSION.to_le_bytes());
    h.update(&world_hash.to_le_bytes());
    h.update(&settings.bounces.to_le_bytes());
    h.update(&settings.top_share.to_le_bytes());
    h.update(&[range as u8]);
    h.update(&reorder.passes.to_le_bytes());
    let search = match reorder.search {
        Search::Exact => [0; 3],
        Search::Sketch { samples, candidates } => [1, samples, candidates],
    };
    h.update(bytemuck::cast_slice(&search));
    h.digest()
}

/// The cache file of `key` under the cache directory `dir` (normally
/// [`crate::config::cache_dir`]).
pub fn path(dir: &Path, key: u64) -> PathBuf {
    dir.join("glrt").join("radiosity").join(format!("{key:016x}.glrtrad"))
}

/// The bytes of the file of `m` under `key`.
pub fn encode(key: u64, m: &CompressedMatrix) -> Vec<u8> {
    let mut b = Vec::with_capacity(m.bytes() + 64);
    b.extend_from_slice(MAGIC);
    b.extend_from_slice(&VERSION.to_le_bytes());
    b.extend_from_slice(&key.to_le_bytes());
    for x in [m.texture.n as u32, m.texture.side as u32] {
        b.extend_from_slice(&x.to_le_bytes());
    }
    for x in [m.max, m.shift] {
        b.extend_from_slice(&x.to_le_bytes());
    }
    b.extend_from_slice(bytemuck::cast_slice(&m.order));
    b.extend_from_slice(&(m.texture.blocks.len() as u64).to_le_bytes());
    b.extend_from_slice(&m.texture.blocks);
    b.extend_from_slice(bytemuck::cast_slice(&m.sparse.offsets));
    b.extend_from_slice(&(m.sparse.columns.len() as u32).to_le_bytes());
    b.extend_from_slice(bytemuck::cast_slice(&m.sparse.columns));
    b.extend_from_slice(bytemuck::cast_slice(&m.sparse.values));
    let hash = xxh3_64(&b);
    b.extend_from_slice(&hash.to_le_bytes());
    b
}

/// Reads `bytes` front to back.
struct Reader<'a> {
    bytes: &'a [u8],
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        if n > self.bytes.len() {
            return Err("it ends early".to_owned());
        }
        let (head, rest) = self.bytes.split_at(n);
        self.bytes = rest;
        Ok(head)
    }

    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }

    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")))
    }

    fn f32(&mut self) -> Result<f32, String> {
        self.u32().map(f32::from_bits)
    }

    fn words(&mut self, n: usize) -> Result<Vec<u32>, String> {
        let bytes = self.take(n.checked_mul(4).ok_or("a size overflows")?)?;
        Ok(bytes.chunks_exact(4).map(|w| u32::from_le_bytes(w.try_into().expect("4 bytes"))).collect())
    }
}

/// The matrix in `bytes` (a file's content), if it is a whole file of `key`; else why not.
pub fn decode(key: u64, bytes: &[u8]) -> Result<CompressedMatrix, String> {
    if bytes.len() < MAGIC.len() + 8 || &bytes[..MAGIC.len()] != MAGIC {
        return Err("not a glrt radiosity matrix".to_owned());
    }
    let (body, hash) = bytes.split_at(bytes.len() - 8);
    if xxh3_64(body) != u64::from_le_bytes(hash.try_into().expect("8 bytes")) {
        return Err("its content does not match its hash (damaged or cut short)".to_owned());
    }
    let mut r = Reader { bytes: &body[MAGIC.len()..] };
    let version = r.u32()?;
    if version != VERSION {
        return Err(format!("format version {version}, this glrt reads {VERSION}"));
    }
    if r.u64()? != key {
        return Err("it holds another world's matrix".to_owned());
    }
    let (n, side) = (r.u32()? as usize, r.u32()? as usize);
    let (max, shift) = (r.f32()?, r.f32()?);
    if side != n.div_ceil(4) * 4 || !max.is_finite() || !shift.is_finite() {
        return Err(format!("bad header (n {n}, side {side}, max {max}, shift {shift})"));
    }
    let order = r.words(n)?;
    let mut seen = vec![false; n];
    if !order.iter().all(|&i| (i as usize) < n && !std::mem::replace(&mut seen[i as usize], true)) {
        return Err("its order is not a permutation".to_owned());
    }
    let blocks_len = r.u64()? as usize;
    if blocks_len != (side / 4) * (side / 4) * 8 {
        return Err(format!("{blocks_len} bytes of BC1 blocks for a side of {side}"));
    }
    let blocks = r.take(blocks_len)?.to_vec();
    let offsets = r.words(n + 1)?;
    let entries = r.u32()? as usize;
    if offsets.first() != Some(&0) || offsets.last() != Some(&(entries as u32)) || offsets.windows(2).any(|w| w[0] > w[1]) {
        return Err("its sparse rows' offsets do not fit".to_owned());
    }
    let columns = r.words(entries)?;
    if columns.iter().any(|&j| j as usize >= n) {
        return Err("a sparse entry's column is out of range".to_owned());
    }
    let values: Vec<[f32; 3]> = r.words(entries.checked_mul(3).ok_or("a size overflows")?)?.chunks_exact(3).map(|v| [0, 1, 2].map(|c| f32::from_bits(v[c]))).collect();
    if !r.bytes.is_empty() {
        return Err(format!("{} bytes left over", r.bytes.len()));
    }
    Ok(CompressedMatrix { order, max, shift, texture: Bc1Matrix { n, side, blocks }, sparse: SparseRows { offsets, columns, values } })
}

/// The matrix cached at `path` under `key`: `Ok(None)` when there is no file, `Err` with the
/// reason when there is one that cannot be used.
pub fn load(path: &Path, key: u64) -> Result<Option<CompressedMatrix>, String> {
    match std::fs::read(path) {
        Ok(bytes) => decode(key, &bytes).map(Some).map_err(|e| format!("radiosity cache {}: {e}", path.display())),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(format!("radiosity cache {}: {e}", path.display())),
    }
}

/// Writes `m` to `path` under `key` (its folders made as needed).
pub fn save(path: &Path, key: u64, m: &CompressedMatrix) -> Result<(), String> {
    let fail = |e: std::io::Error| format!("radiosity cache {}: {e}", path.display());
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(fail)?;
    }
    let temporary = path.with_extension(format!("tmp{}", std::process::id()));
    std::fs::write(&temporary, encode(key, m)).and_then(|()| std::fs::rename(&temporary, path)).map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        fail(e)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::radiosity::bounces::{colour_matrix, k_bounce};
    use crate::render::radiosity::compress::compress;
    use crate::render::radiosity::progress::Progress;
    use crate::render::radiosity::test_scenes::unit_box;

    #[test]
    fn a_matrix_comes_back_whole_and_a_damaged_file_is_refused_with_a_reason() {
        let (p, f) = unit_box();
        let albedo: Vec<_> = p.patches.iter().map(|x| x.albedo * 0.5).collect();
        let reorder = Reorder::seed(Search::SKETCH);
        let m = compress(&k_bounce(&colour_matrix(f, &albedo), 3, Progress::Quiet), 0.04, reorder, LogRange::Fitted, Progress::Quiet);
        let settings = Settings::default();
        let k = key(p.world_hash, &settings, LogRange::Fitted, reorder);
        assert_ne!(k, key(p.world_hash, &Settings { bounces: 2, ..settings }, LogRange::Fitted, reorder));
        assert_ne!(k, key(p.world_hash, &settings, LogRange::Seed, reorder));
        assert_ne!(k, key(p.world_hash ^ 1, &settings, LogRange::Fitted, reorder));
        assert_ne!(k, key(p.world_hash, &settings, LogRange::Fitted, Reorder::seed(Search::Exact)));
        assert_ne!(k, key(p.world_hash, &settings, LogRange::Fitted, Reorder { passes: 1, ..reorder }));

        let dir = std::env::temp_dir().join(format!("glrt-radiosity-cache-{}", std::process::id()));
        let file = path(&dir, k);
        assert!(file.ends_with(format!("glrt/radiosity/{k:016x}.glrtrad")));
        assert_eq!(load(&file, k), Ok(None));
        save(&file, k, &m).expect("written");
        let back = load(&file, k).expect("readable").expect("present");
        assert_eq!(back, m);
        assert_eq!(back.decompress(), m.decompress());
        assert!(load(&file, k ^ 1).unwrap_err().ends_with("it holds another world's matrix"));

        let bytes = std::fs::read(&file).unwrap();
        assert_eq!(bytes.len(), m.bytes() + 8 + 4 + 8 + 16 + 8 + 4 + 8);
        let mut flipped = bytes.clone();
        flipped[100] ^= 1;
        std::fs::write(&file, &flipped).unwrap();
        let e = load(&file, k).unwrap_err();
        assert!(e.contains("glrtrad: its content does not match its hash"), "{e}");
        std::fs::write(&file, &bytes[..bytes.len() / 2]).unwrap();
        assert!(load(&file, k).unwrap_err().contains("does not match its hash"));
        std::fs::write(&file, b"hello").unwrap();
        assert!(load(&file, k).unwrap_err().ends_with("not a glrt radiosity matrix"));
        // A well-hashed file whose order repeats a patch.
        let mut wrong = m.clone();
        wrong.order[1] = wrong.order[0];
        assert_eq!(decode(k, &encode(k, &wrong)), Err("its order is not a permutation".to_owned()));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
