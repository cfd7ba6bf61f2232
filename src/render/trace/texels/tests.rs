//! Packing, memory management and the CPU sampler, on small hand-made textures.

use std::sync::Arc;

use super::*;
use crate::frame::texture::{MinFilter, Sampler};

/// A level of `w` × `h` texels (border included) given as RGBA8 pixels.
fn level(w: u32, h: u32, border: u32, pixels: &[[u8; 4]]) -> Option<Arc<TexImage>> {
    let mut texels: Vec<u8> = pixels.iter().flatten().copied().collect();
    texels.resize((w * h * 4) as usize, 0);
    Some(Arc::new(TexImage { width: w, height: h, depth: 1, border, texels, ..TexImage::default() }))
}

/// A 2D texture version with `levels` and `sampler`.
fn texture(id: u32, version: u64, levels: Vec<Option<Arc<TexImage>>>, sampler: Sampler) -> TextureRef {
    TextureRef { id, version, content: Arc::new(TextureContent { kind: TextureKind::D2, faces: vec![levels], sampler, ..TextureContent::default() }) }
}

/// Filters and wraps: `min` texel filter, mipmap filter, magnification, wrap of s and t.
fn sampler(min: Filter, mip: Option<Filter>, mag: Filter, wrap: Wrap) -> Sampler {
    Sampler { min_filter: MinFilter { texel: min, mipmap: mip }, mag_filter: mag, wrap: [wrap; 3], ..Sampler::default() }
}

/// A w × h texture of solid grey `v` (one level).
fn grey(id: u32, w: u32, h: u32, v: u8) -> TextureRef {
    texture(id, 1, vec![level(w, h, 0, &vec![[v, v, v, 255]; (w * h) as usize])], sampler(Filter::Nearest, None, Filter::Nearest, Wrap::Repeat))
}

const RED: [u8; 4] = [255, 0, 0, 255];
const GREEN: [u8; 4] = [0, 255, 0, 255];
const BLUE: [u8; 4] = [0, 0, 255, 255];
const WHITE: [u8; 4] = [255, 255, 255, 255];

/// 2×2: red, green (bottom row), blue, white (top row).
fn quad(s: Sampler) -> TextureRef {
    texture(7, 1, vec![level(2, 2, 0, &[RED, GREEN, BLUE, WHITE])], s)
}

/// Frames in flight of the renderer the tests' pools serve.
const IN_FLIGHT: u64 = 2;

/// A pool of the default budget serving `IN_FLIGHT` frames in flight.
fn new_pool() -> TexelPool {
    TexelPool::new(MAX_WORDS, IN_FLIGHT as usize)
}

fn rgba(c: [u8; 4]) -> [f32; 4] {
    c.map(|v| f32::from(v) / 255.0)
}

fn assert_near(got: [f32; 4], want: [f32; 4]) {
    assert!(got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-5), "got {got:?}, want {want:?}");
}

fn word(c: [u8; 4]) -> u32 {
    u32::from_le_bytes(c)
}

#[test]
fn packs_given_levels_consecutively_as_rgba8_words() {
    let t = texture(1, 1, vec![level(2, 2, 0, &[RED, GREEN, BLUE, WHITE]), level(1, 1, 0, &[[10, 20, 30, 40]])], sampler(Filter::Linear, Some(Filter::Linear), Filter::Linear, Wrap::MirroredRepeat));
    let mut pool = new_pool();
    assert_eq!(pool.prepare(&[&t]), [0]);
    assert_eq!(pool.words(), [word(RED), word(GREEN), word(BLUE), word(WHITE), word([10, 20, 30, 40])]);
    let g = pool.textures()[0];
    assert_eq!((g.offset, g.width, g.height, g.levels), (0, 2, 2, 2));
    assert_eq!((g.wrap(0), g.wrap(1)), (TEXEL_WRAP_MIRROR, TEXEL_WRAP_MIRROR));
    let filters = TEXEL_MAG_LINEAR | TEXEL_MIN_LINEAR | TEXEL_MIPMAP | TEXEL_MIP_LINEAR;
    assert_eq!(g.flags & !0xf, filters);
    // The average of the base level: (255 + 0 + 0 + 255) / 4 rounds to 128 in red.
    assert_eq!(g.average.to_le_bytes(), [128, 128, 128, 255]);
    assert_eq!(pool.take_uploads(), vec![0..5]);
    assert!(pool.take_uploads().is_empty());
    // The same version the next frame is not packed again.
    assert_eq!(pool.prepare(&[&t, &t]), [0, 0]);
    assert!(pool.take_uploads().is_empty());
}

#[test]
fn missing_levels_are_box_filtered_down_to_one_texel() {
    // 4×2, no mipmaps: levels 4×2, 2×1 and 1×1 are packed, the last two generated.
    let pixels: Vec<[u8; 4]> = [0u8, 40, 80, 120, 160, 200, 240, 255].iter().map(|&v| [v, 0, 0, 255]).collect();
    let t = texture(1, 1, vec![level(4, 2, 0, &pixels)], sampler(Filter::Linear, None, Filter::Linear, Wrap::Repeat));
    let mut pool = new_pool();
    pool.prepare(&[&t]);
    let g = pool.textures()[0];
    assert_eq!(g.levels, 3);
    assert_eq!(g.words(), 8 + 2 + 1);
    assert!(g.has(TEXEL_MIPMAP) && g.has(TEXEL_MIP_LINEAR));
    let red: Vec<u8> = pool.words()[8..].iter().map(|w| w.to_le_bytes()[0]).collect();
    // (0 + 40 + 160 + 200) / 4 = 100, (80 + 120 + 240 + 255) / 4 = 173.75; then (100 + 174) / 2.
    assert_eq!(red, [100, 174, 137]);
    // A nearest-filtered texture gets the chain too, sampled level by level.
    let n = texture(2, 1, vec![level(4, 2, 0, &pixels)], sampler(Filter::Nearest, None, Filter::Nearest, Wrap::Repeat));
    pool.prepare(&[&t, &n]);
    let g = pool.textures()[1];
    assert_eq!(g.levels, 3);
    assert!(g.has(TEXEL_MIPMAP) && !g.has(TEXEL_MIP_LINEAR));
    // A mipmapped texture stops at its max level.
    let mut s = sampler(Filter::Linear, Some(Filter::Linear), Filter::Linear, Wrap::Repeat);
    s.levels = [0, 1];
    let capped = texture(3, 1, vec![level(4, 2, 0, &pixels), level(2, 1, 0, &[RED, GREEN])], s);
    let at = pool.prepare(&[&capped])[0];
    let g = pool.textures()[at as usize];
    assert_eq!(g.levels, 2);
    assert_eq!(pool.words()[g.offset as usize + 8..g.offset as usize + 10], [word(RED), word(GREEN)]);
}

#[test]
fn base_level_borders_cubes_and_3d_textures_pack_their_first_image() {
    // Base level 1 of a texture whose level 0 is junk.
    let s = sampler(Filter::Nearest, None, Filter::Nearest, Wrap::Repeat);
    let based = texture(1, 1, vec![level(8, 8, 0, &[]), level(1, 1, 0, &[GREEN])], Sampler { levels: [1, 1000], ..s });
    // A 3×3 bordered image: the centre texel is sampled.
    let bordered = texture(2, 1, vec![level(3, 3, 1, &[RED, RED, RED, RED, BLUE, RED, RED, RED, RED])], s);
    let mut cube = (*quad(s).content).clone();
    cube.kind = TextureKind::Cube;
    cube.faces = vec![vec![level(1, 1, 0, &[WHITE])], vec![level(1, 1, 0, &[RED])]];
    let cube = TextureRef { id: 3, version: 1, content: Arc::new(cube) };
    let mut d3 = (*quad(s).content).clone();
    d3.kind = TextureKind::D3;
    let mut slices = (*level(1, 1, 0, &[GREEN, RED]).unwrap()).clone();
    slices.depth = 2;
    slices.texels.resize(8, 0);
    slices.texels[4..].copy_from_slice(&RED);
    d3.faces = vec![vec![Some(Arc::new(slices))]];
    let d3 = TextureRef { id: 4, version: 1, content: Arc::new(d3) };
    let mut pool = new_pool();
    let at = pool.prepare(&[&based, &bordered, &cube, &d3]);
    let colours: Vec<[f32; 4]> = at.iter().map(|&i| pool.sample(i, [0.5, 0.5], 0.0)).collect();
    assert_eq!(colours, [rgba(GREEN), rgba(BLUE), rgba(WHITE), rgba(GREEN)]);
    assert_eq!(pool.textures()[at[1] as usize].width, 1);
}

#[test]
fn odd_textures_do_not_panic() {
    let s = Sampler::default();
    let none = texture(1, 1, vec![], s);
    let no_base = texture(2, 1, vec![None, level(1, 1, 0, &[RED])], s);
    let zero = texture(3, 1, vec![level(0, 0, 0, &[])], s);
    let short = TextureRef { id: 4, version: 1, content: Arc::new(TextureContent { faces: vec![vec![Some(Arc::new(TexImage { width: 4, height: 4, depth: 1, ..TexImage::default() }))]], ..TextureContent::default() }) };
    let huge = texture(5, 1, vec![Some(Arc::new(TexImage { width: (1 << 24) + 1, height: 1, depth: 1, ..TexImage::default() }))], s);
    let mut pool = new_pool();
    let at = pool.prepare(&[&none, &no_base, &zero, &short, &huge]);
    assert_eq!([at[0], at[1], at[4]], [NO_TEXTURE; 3]);
    assert_eq!(pool.sample(NO_TEXTURE, [0.3, 0.3], 0.0), [1.0; 4]);
    assert_eq!(texel_size(pool.textures(), NO_TEXTURE), [1.0, 1.0]);
    // A zero-sized level is one texel; missing texel data reads as zero.
    assert_eq!(texel_size(pool.textures(), at[2]), [1.0, 1.0]);
    assert_eq!(pool.sample(at[3], [0.9, 0.1], 2.5), [0.0; 4]);
    assert_eq!(pool.sample(at[3], [0.9, 0.1], f32::NAN), [0.0; 4]);
    assert_eq!(pool.sample(at[3], [f32::INFINITY, -1e30], f32::INFINITY), [0.0; 4]);
}

#[test]
fn unused_versions_are_freed_and_their_space_reused() {
    let (a, b) = (grey(1, 4, 4, 10), grey(2, 2, 2, 20));
    let mut pool = new_pool();
    assert_eq!(pool.prepare(&[&a, &b]), [0, 1]);
    let a_words = pool.textures()[0].words();
    assert_eq!(a_words, 16 + 4 + 1);
    assert_eq!(pool.textures()[1].offset as usize, a_words);
    for _ in 0..KEEP_FRAMES {
        pool.prepare(&[&b]);
    }
    assert_eq!(pool.textures()[0].levels, 1 + 2, "a is kept {KEEP_FRAMES} frames");
    pool.prepare(&[&b]);
    assert_eq!(pool.textures()[0], GpuTexture::default(), "a is freed after {KEEP_FRAMES} frames");
    assert_eq!(pool.take_uploads(), vec![0..a_words + 5]);
    // Once the frames in flight are done with a's words, c takes a's slot and, first fit,
    // a's words.
    for _ in 1..IN_FLIGHT {
        pool.prepare(&[&b]);
    }
    let c = grey(3, 2, 2, 30);
    assert_eq!(pool.prepare(&[&b, &c]), [1, 0]);
    assert_eq!(pool.textures()[0].offset, 0);
    assert_eq!(pool.take_uploads(), vec![0..5]);
    assert_eq!(pool.sample(0, [0.5, 0.5], 0.0), rgba([30, 30, 30, 255]));
    // Freeing the last texture in the pool shrinks it, when its words are reclaimed.
    for _ in 0..=KEEP_FRAMES {
        pool.prepare(&[&c]);
    }
    assert_eq!(pool.words().len(), a_words + 5, "b's words are retired, not yet free");
    for _ in 0..IN_FLIGHT {
        pool.prepare(&[&c]);
    }
    assert_eq!(pool.words().len(), 5);
}

#[test]
fn a_new_version_frees_the_old_one() {
    let v1 = grey(1, 2, 2, 10);
    let mut v2 = grey(1, 2, 2, 20);
    v2.version = 2;
    let mut pool = new_pool();
    assert_eq!(pool.prepare(&[&v1]), [0]);
    assert_eq!(pool.prepare(&[&v2]), [0], "v1's slot is reused at once");
    assert_eq!(pool.textures()[0].offset, 5, "v1's words are not: the last frame may still read them");
    assert_eq!(pool.sample(0, [0.5, 0.5], 0.0), rgba([20, 20, 20, 255]));
    // Both versions in one frame: both kept.
    let at = pool.prepare(&[&v1, &v2]);
    assert_eq!(at, [1, 0]);
}

#[test]
fn freed_words_are_handed_out_again_only_after_the_frames_in_flight() {
    // A texture updated every frame (a lightmap): each frame frees the last frame's version.
    let version = |v: u64| {
        let mut t = grey(1, 2, 2, v as u8 * 10);
        t.version = v;
        t
    };
    for in_flight in [0u64, 1, 2, 3] {
        let mut pool = TexelPool::new(MAX_WORDS, in_flight as usize);
        let mut offsets = Vec::new();
        for v in 1..=8 {
            let at = pool.prepare(&[&version(v)])[0];
            offsets.push(pool.textures()[at as usize].offset as usize);
            assert_eq!(pool.take_uploads(), vec![offsets[offsets.len() - 1]..offsets[offsets.len() - 1] + 5]);
        }
        // Version v's words are freed in frame v + 1; nothing may take them before frame
        // v + 1 + in_flight, which they go to (first fit, every version the same size).
        for (i, offset) in offsets.iter().enumerate() {
            if let Some(owner) = offsets[..i].iter().rposition(|o| o == offset) {
                let (frame, owner) = (i as u64 + 1, owner as u64 + 1);
                assert!(frame >= owner + 1 + in_flight, "{in_flight} in flight: frame {frame} reuses version {owner}'s words: {offsets:?}");
            }
        }
        let cycle = in_flight as usize + 1;
        assert_eq!(offsets, (0..8).map(|i| 5 * (i % cycle)).collect::<Vec<_>>(), "{in_flight} in flight");
    }
}

#[test]
fn over_budget_textures_sample_their_average_colour() {
    // Budget 30 words: a 4×4 chain takes 21, a second one does not fit.
    let (a, b) = (grey(1, 4, 4, 10), grey(2, 4, 4, 90));
    let mut pool = TexelPool::new(30, IN_FLIGHT as usize);
    assert_eq!(pool.prepare(&[&a, &b]), [0, 1]);
    assert_eq!(pool.textures()[1].levels, 0);
    assert_eq!(pool.sample(1, [0.3, 0.7], 0.0), rgba([90, 90, 90, 255]));
    assert_eq!(pool.words().len(), 21);
    assert_eq!(pool.take_uploads(), vec![0..21]);
    // Next frame only b is used: a is evicted for it, but the frame in flight still reads
    // a's words, so b stays average-coloured until they are reclaimed.
    assert_eq!(pool.prepare(&[&b]), [1]);
    assert_eq!(pool.textures()[0].levels, 0, "a is left with its average colour");
    for _ in 1..IN_FLIGHT {
        assert_eq!(pool.prepare(&[&b]), [1]);
        assert_eq!(pool.textures()[1].levels, 0, "a's words are retired");
    }
    assert!(pool.take_uploads().is_empty(), "nothing is written while a's words may be read");
    assert_eq!(pool.prepare(&[&b]), [1]);
    assert_eq!(pool.textures()[1].levels, 3);
    assert_eq!(pool.textures()[1].offset, 0);
    assert_eq!(pool.take_uploads(), vec![0..21]);
    assert_eq!(pool.sample(1, [0.3, 0.7], 0.0), rgba([90, 90, 90, 255]));
    // a again, with b: a does not fit and stays average-coloured; nothing used is evicted.
    assert_eq!(pool.prepare(&[&a, &b]), [0, 1]);
    assert_eq!((pool.textures()[0].levels, pool.textures()[1].levels), (0, 3));
    assert_eq!(pool.sample(0, [0.5, 0.5], 0.0), rgba([10, 10, 10, 255]));
    // Larger than the whole budget: average colour, never an error.
    let big = grey(3, 8, 8, 200);
    let at = pool.prepare(&[&big]);
    assert_eq!(pool.textures()[at[0] as usize].levels, 0);
    assert_eq!(pool.sample(at[0], [0.5, 0.5], 3.0), rgba([200, 200, 200, 255]));
}

#[test]
fn nearest_and_bilinear_at_centres_and_midpoints() {
    let mut pool = new_pool();
    let near = pool.prepare(&[&quad(sampler(Filter::Nearest, None, Filter::Nearest, Wrap::Repeat))])[0];
    // Texel centres; t = 0.25 is the bottom row (red, green).
    assert_near(pool.sample(near, [0.25, 0.25], 0.0), rgba(RED));
    assert_near(pool.sample(near, [0.75, 0.25], -1.0), rgba(GREEN));
    assert_near(pool.sample(near, [0.25, 0.75], 0.0), rgba(BLUE));
    assert_near(pool.sample(near, [0.75, 0.75], 0.0), rgba(WHITE));
    let mut pool = new_pool();
    let lin = pool.prepare(&[&quad(sampler(Filter::Linear, None, Filter::Linear, Wrap::ClampToEdge))])[0];
    assert_near(pool.sample(lin, [0.25, 0.25], 0.0), rgba(RED));
    // Midway between red and green, and the centre of all four.
    assert_near(pool.sample(lin, [0.5, 0.25], 0.0), [0.5, 0.5, 0.0, 1.0]);
    assert_near(pool.sample(lin, [0.5, 0.5], 0.0), [0.5, 0.5, 0.5, 1.0]);
    // A quarter of the way from red to blue.
    assert_near(pool.sample(lin, [0.25, 0.375], 0.0), [0.75, 0.0, 0.25, 1.0]);
}

#[test]
fn wrap_modes_at_the_edges() {
    let at = |wrap, uv| {
        let mut pool = new_pool();
        let i = pool.prepare(&[&quad(sampler(Filter::Linear, None, Filter::Linear, wrap))])[0];
        pool.sample(i, uv, 0.0)
    };
    // s = 0 on the bottom row: repeat blends red with green, clamp keeps red.
    assert_near(at(Wrap::Repeat, [0.0, 0.25]), [0.5, 0.5, 0.0, 1.0]);
    assert_near(at(Wrap::ClampToEdge, [0.0, 0.25]), rgba(RED));
    assert_near(at(Wrap::Clamp, [-3.0, 0.25]), rgba(RED));
    assert_near(at(Wrap::ClampToBorder, [0.9, 0.25]), rgba(GREEN));
    assert_near(at(Wrap::MirroredRepeat, [0.0, 0.25]), rgba(RED));
    // Nearest: s = 1.25 repeats to red, mirrors to green; t = -0.25 repeats to the top row.
    let nearest = |wrap, uv| {
        let mut pool = new_pool();
        let i = pool.prepare(&[&quad(sampler(Filter::Nearest, None, Filter::Nearest, wrap))])[0];
        pool.sample(i, uv, 0.0)
    };
    assert_near(nearest(Wrap::Repeat, [1.25, 0.25]), rgba(RED));
    assert_near(nearest(Wrap::MirroredRepeat, [1.25, 0.25]), rgba(GREEN));
    assert_near(nearest(Wrap::MirroredRepeat, [-0.25, 0.25]), rgba(RED));
    assert_near(nearest(Wrap::MirroredRepeat, [-0.75, 0.25]), rgba(GREEN));
    assert_near(nearest(Wrap::Repeat, [0.25, -0.25]), rgba(BLUE));
    assert_near(nearest(Wrap::ClampToEdge, [0.25, -0.25]), rgba(RED));
}

#[test]
fn level_selection_nearest_and_trilinear() {
    // 2×2 plus a grey 1×1 level (given, not the average).
    let levels = || vec![level(2, 2, 0, &[RED, GREEN, BLUE, WHITE]), level(1, 1, 0, &[[100, 100, 100, 255]])];
    let grey = rgba([100, 100, 100, 255]);
    let mut pool = new_pool();
    let tri = texture(1, 1, levels(), sampler(Filter::Linear, Some(Filter::Linear), Filter::Nearest, Wrap::Repeat));
    let nmn = texture(2, 1, levels(), sampler(Filter::Nearest, Some(Filter::Nearest), Filter::Linear, Wrap::Repeat));
    let at = pool.prepare(&[&tri, &nmn]);
    // Trilinear at a texel centre: level 0 gives red, level 1 grey; λ = 0.25 blends a quarter.
    assert_near(pool.sample(at[0], [0.25, 0.25], 0.0), rgba(RED));
    let red = rgba(RED);
    assert_near(pool.sample(at[0], [0.25, 0.25], 0.25), std::array::from_fn(|c| red[c] * 0.75 + grey[c] * 0.25));
    assert_near(pool.sample(at[0], [0.25, 0.25], 1.0), grey);
    assert_near(pool.sample(at[0], [0.25, 0.25], 7.5), grey);
    // Magnification is nearest for the trilinear texture (λ ≤ 0).
    assert_near(pool.sample(at[0], [0.4, 0.25], -2.0), rgba(RED));
    // NEAREST_MIPMAP_NEAREST with linear magnification: magnification up to λ = 0.5
    // (bilinear: halfway red-green at s = 0.5), then the nearest level, ⌈λ + ½⌉ − 1 = 1.
    assert_near(pool.sample(at[1], [0.5, 0.25], 0.5), [0.5, 0.5, 0.0, 1.0]);
    assert_near(pool.sample(at[1], [0.5, 0.25], 0.51), grey);
    assert_near(pool.sample(at[1], [0.5, 0.25], 1.5), grey);
    // Without the linear magnification, λ in (0, 0.5] minifies on level 0 (nearest: green).
    let nn = texture(4, 1, levels(), sampler(Filter::Nearest, Some(Filter::Nearest), Filter::Nearest, Wrap::Repeat));
    let nn = pool.prepare(&[&tri, &nmn, &nn])[2];
    assert_near(pool.sample(nn, [0.5, 0.25], 0.5), rgba(GREEN));
    assert_near(pool.sample(nn, [0.5, 0.25], 0.51), grey);
    // The LOD range clamps λ.
    let mut s = sampler(Filter::Linear, Some(Filter::Linear), Filter::Nearest, Wrap::Repeat);
    s.lod = [0.5, 0.5];
    let clamped = pool.prepare(&[&texture(3, 1, levels(), s)])[0];
    assert_near(pool.sample(clamped, [0.25, 0.25], 9.0), std::array::from_fn(|c| (red[c] + grey[c]) * 0.5));
}

#[test]
fn rectangle_textures_take_texel_coordinates_and_srgb_decodes() {
    let mut rect = (*quad(sampler(Filter::Nearest, None, Filter::Nearest, Wrap::ClampToEdge)).content).clone();
    rect.kind = TextureKind::Rect;
    let rect = TextureRef { id: 1, version: 1, content: Arc::new(rect) };
    let mut srgb = (*grey(2, 1, 1, 0).content).clone();
    let mut img = (*level(1, 1, 0, &[[188, 0, 10, 128]]).unwrap()).clone();
    img.precision = Precision::Srgb8;
    srgb.faces = vec![vec![Some(Arc::new(img))]];
    let srgb = TextureRef { id: 2, version: 1, content: Arc::new(srgb) };
    let mut pool = new_pool();
    let at = pool.prepare(&[&rect, &srgb]);
    assert!(pool.textures()[at[0] as usize].has(TEXEL_RECT));
    assert_near(pool.sample(at[0], [1.5, 0.5], 0.0), rgba(GREEN));
    assert_near(pool.sample(at[0], [0.5, 1.5], 0.0), rgba(BLUE));
    assert_eq!(texel_size(pool.textures(), at[0]), [2.0, 2.0]);
    let c = pool.sample(at[1], [0.5, 0.5], 0.0);
    // sRGB 188 is linear 0.5029; 10 is 10 / 255 / 12.92; alpha stays linear.
    assert!((c[0] - 0.5029).abs() < 1e-3 && (c[2] - 0.003035).abs() < 1e-5 && c[1] == 0.0, "{c:?}");
    assert!((c[3] - 128.0 / 255.0).abs() < 1e-6);
}
