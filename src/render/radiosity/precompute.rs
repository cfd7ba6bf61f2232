//! The precompute on the CPU, step by step with its times, sizes and errors: patches within
//! the memory budget, form factors, the colour and k-bounce matrices, the compressed matrix
//! after 0, 1 and 2 reordering passes (exact and sketched searches), the k-bounce light against the Neumann series, and the
//! per-frame cost of the dense product against classic gathering (Jacobi and Gauss–Seidel) to
//! convergence; the renderer's compressed matrix is kept for timing its product on a device. `glrt radiosity` prints
//! [`Report`]; `bench/radiosity.md` keeps its numbers. The two heavy steps, the form factors
//! and the k-bounce matrix, run where the caller's [`Steps`] say (a Vulkan device:
//! [`super::stage::OnDevice`]; a form-factor function alone: the k-bounce matrix on the CPU).

use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::Vec3;

use super::bounces::{colour_matrix, gather, gauss_seidel, k_bounce, neumann};
use super::cache;
use super::compress::{self, CompressedMatrix, Errors, LogRange, Reorder, compress};
use super::form_factors::FormFactors;
use super::matrix::ColourMatrix;
use super::patches::{self, Patches, area};
use super::progress::Progress;
use super::reorder::Search;
use super::settings::Settings;
use crate::frame::world::StaticChunk;

/// Where the precompute's two heavy steps run.
pub trait Steps {
    /// The form factors of `p`.
    fn form_factors(&mut self, p: &Patches) -> FormFactors;
    /// The k-bounce matrix of `colour` with `k` bounces, its progress on `progress`.
    fn k_bounce(&mut self, colour: &ColourMatrix, k: u32, progress: Progress) -> ColourMatrix;
}

/// A form-factor function, the k-bounce matrix on the CPU ([`k_bounce`]).
impl<F: FnMut(&Patches) -> FormFactors> Steps for F {
    fn form_factors(&mut self, p: &Patches) -> FormFactors {
        self(p)
    }

    fn k_bounce(&mut self, colour: &ColourMatrix, k: u32, progress: Progress) -> ColourMatrix {
        k_bounce(colour, k, progress)
    }
}

/// Factor the automatic patch size grows by while the patches exceed the budget.
const GROWTH: f32 = 1.25;
/// Relative size of the last bounce at which the Neumann series counts as converged.
const TOLERANCE: f32 = 1.0e-6;
/// Most patches the report compresses with the seed's exact search too when the settings ask
/// for the sketched one (the exact passes are O(n³): 75 s each at 16k patches on 16 cores).
pub const EXACT_REPORT_PATCHES: usize = 4096;

/// The patches of `chunks` at the settings' patch size, or, when it is 0, at the smallest
/// size (from `sqrt(area / max patches)` up, by [`GROWTH`]) whose patches fit the budget.
/// When a given size makes more patches than the budget holds, the automatic size is used
/// instead and the note says so. A world that no size fits (more surface orientations than
/// the budget's patches) gets no patches, and a note saying so.
pub fn patches_within_budget(chunks: &[Arc<StaticChunk>], settings: &Settings) -> (Patches, Option<String>) {
    let max = settings.max_patches();
    let mut note = None;
    if settings.patch_size > 0.0 {
        let p = patches::build(chunks, settings.patch_size);
        if p.patches.len() <= max {
            return (p, None);
        }
        note = Some(format!(
            "{} patches of size {} exceed the memory budget of {} MiB ({max} patches): using larger patches (raise radiosity_budget_mb or patch_size)",
            p.patches.len(),
            settings.patch_size,
            settings.budget_mb
        ));
    }
    let total: f32 = chunks.iter().flat_map(|c| c.positions.chunks_exact(3)).map(|t| area(&[t[0].into(), t[1].into(), t[2].into()])).filter(|a| a.is_finite()).sum();
    if !(total > 0.0) {
        return (patches::build(&[], 1.0), note);
    }
    // Past the world's extent a larger size merges nothing more: the patches are then one per
    // surface orientation (quantised normal), which a world of curved surfaces may have more
    // of than the budget holds.
    let (lo, hi) = chunks.iter().flat_map(|c| c.positions.iter()).map(|&p| Vec3::from(p)).filter(|p| p.is_finite()).fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
    let extent = (hi - lo).length();
    let mut size = (total / max as f32).sqrt();
    loop {
        let p = patches::build(chunks, size);
        if p.patches.len() <= max {
            if let Some(n) = &mut note {
                *n = format!("{n}; size {size:.4}, {} patches", p.patches.len());
            }
            return (p, note);
        }
        if !(size <= extent) {
            let refused = format!(
                "the static world makes {} patches even at size {size:.4} (past its extent: one per surface orientation), more than the memory budget of {} MiB holds ({max} patches): radiosity is off (raise radiosity_budget_mb)",
                p.patches.len(),
                settings.budget_mb
            );
            let note = note.map_or_else(|| refused.clone(), |n| format!("{n}; {refused}"));
            return (patches::build(&[], 1.0), Some(note));
        }
        size *= GROWTH;
    }
}

/// The log range of the matrix the renderer uses (it halves the summed error of the seed's
/// on the test box, `bench/radiosity.md`).
pub const RANGE: LogRange = LogRange::Fitted;

/// A static world's radiosity as the renderer uses it.
pub struct StaticRadiosity {
    /// The patches.
    pub patches: Patches,
    /// The compressed k-bounce matrix ([`RANGE`], reordered as [`reorder_of`] says).
    pub matrix: CompressedMatrix,
    /// Whether the matrix came from the cache.
    pub loaded: bool,
    /// The cache file (read or written), when there is a cache directory.
    pub cache_file: Option<PathBuf>,
    /// What the user should know: the budget's fallback, an unusable or unwritable cache file.
    pub notes: Vec<String>,
}

/// The patches of `chunks` and their compressed matrix: read from the cache under the
/// directory `cache` when it holds this world's under these settings, else computed (the
/// heavy steps by `steps`) and written there. A cache file that cannot be used is
/// recomputed, with a note saying why.
pub fn load_or_build(chunks: &[Arc<StaticChunk>], settings: &Settings, cache: Option<&Path>, steps: &mut dyn Steps) -> StaticRadiosity {
    let (patches, note) = patches_within_budget(chunks, settings);
    let mut notes: Vec<String> = note.into_iter().collect();
    let key = cache::key(patches.world_hash, settings, RANGE, reorder_of(settings));
    let cache_file = cache.map(|dir| cache::path(dir, key));
    if let Some(file) = &cache_file {
        match cache::load(file, key) {
            Ok(Some(matrix)) if matrix.order.len() == patches.patches.len() => return StaticRadiosity { patches, matrix, loaded: true, cache_file, notes },
            Ok(Some(_)) => notes.push(format!("radiosity cache {}: its size differs from the patches': recomputing", file.display())),
            Ok(None) => {}
            Err(e) => notes.push(format!("{e}: recomputing")),
        }
    }
    let f = steps.form_factors(&patches);
    let albedo: Vec<Vec3> = patches.patches.iter().map(|x| x.albedo).collect();
    let matrix = matrix_of(&f, &albedo, settings, steps, Progress::Stderr);
    if let Some(file) = &cache_file {
        if let Err(e) = cache::save(file, key, &matrix) {
            notes.push(e);
        }
    }
    StaticRadiosity { patches, matrix, loaded: false, cache_file, notes }
}

/// The renderer's compressed k-bounce matrix of form factors `f` and albedos `albedo` (the
/// settings' bounces and top share, [`RANGE`], [`reorder_of`] the settings), the k-bounce
/// matrix by `steps`, its stages on `progress`.
pub fn matrix_of(f: &FormFactors, albedo: &[Vec3], settings: &Settings, steps: &mut dyn Steps, progress: Progress) -> CompressedMatrix {
    compress(&steps.k_bounce(&colour_matrix(f, albedo), settings.bounces, progress), settings.top_share, reorder_of(settings), RANGE, progress)
}

/// The renderer's reordering: the seed's two passes, searched as `radiosity_reorder` says.
pub fn reorder_of(settings: &Settings) -> Reorder {
    Reorder::seed(settings.reorder)
}

/// One compression of the k-bounce matrix.
#[derive(Clone, Debug)]
pub struct Compressed {
    /// Its log range.
    pub range: LogRange,
    /// Its reordering passes.
    pub passes: u32,
    /// How they searched.
    pub search: Search,
    /// Time to compress.
    pub time: Duration,
    /// Bytes.
    pub bytes: usize,
    /// Errors of the round trip.
    pub errors: Errors,
}

/// What the precompute measured.
#[derive(Clone, Debug)]
pub struct Report {
    /// What the user should know (the budget's fallback).
    pub notes: Vec<String>,
    /// Triangles of the static world.
    pub triangles: usize,
    /// Patch size used.
    pub patch_size: f32,
    /// The patches' area-weighted mean albedo.
    pub mean_albedo: Vec3,
    /// The form factors' mean row sum (1 in a closed world, less where patches see the sky
    /// or nothing).
    pub mean_row_sum: f64,
    /// Times: patches, form factors, k-bounce matrix.
    pub times: [Duration; 3],
    /// Bounces of the k-bounce matrix.
    pub bounces: u32,
    /// Bytes: dense form factors, dense k-bounce colour matrix.
    pub dense_bytes: [usize; 2],
    /// The compressions: the seed's log range, then the fitted one, each without reordering,
    /// then after 1 and 2 passes of the exact search, then of the sketched one
    /// ([`Search::SKETCH`]); over [`EXACT_REPORT_PATCHES`] patches only the settings' search.
    pub compressed: Vec<Compressed>,
    /// The patches.
    pub patches: Patches,
    /// The compressed matrix the renderer would use ([`RANGE`], [`reorder_of`] the settings).
    pub matrix: CompressedMatrix,
    /// Sum of the k-bounce matrix's entries (the scale of the summed errors).
    pub total: f64,
    /// Relative error (largest over patches and channels, against the largest value) of
    /// `F^k · 1` against the Neumann series summed to convergence, for `h = 1..=k`.
    pub truncation: Vec<f32>,
    /// Bounces the Neumann series took to converge.
    pub neumann_bounces: u32,
    /// Sweeps Gauss–Seidel gathering took to converge.
    pub gauss_seidel_sweeps: u32,
    /// Per frame on one core: the dense k-bounce product, classic gathering to convergence
    /// (Jacobi: the Neumann series) and Gauss–Seidel gathering to convergence.
    pub frame_times: [Duration; 3],
}

/// Runs the precompute on `chunks`, the heavy steps by `steps` (the primary light of the
/// comparisons: 1 on every patch); `Err` with the budget's note when the world gets no
/// patches.
pub fn run(chunks: &[Arc<StaticChunk>], settings: &Settings, steps: &mut dyn Steps) -> Result<Report, String> {
    let start = Instant::now();
    let (p, note) = patches_within_budget(chunks, settings);
    if p.patches.is_empty() {
        return Err(note.unwrap_or_else(|| "the static world has no patches (no area)".to_owned()));
    }
    let t_patches = start.elapsed();
    let mean_albedo = p.patches.iter().map(|x| x.albedo * x.area).sum::<Vec3>() / p.patches.iter().map(|x| x.area).sum::<f32>().max(f32::MIN_POSITIVE);
    eprintln!("glrt: radiosity: {} patches, area-weighted mean albedo {mean_albedo:.4}", p.patches.len());
    let start = Instant::now();
    let f = steps.form_factors(&p);
    let mean_row_sum = (0..f.n).map(|i| f.row(i).iter().map(|&x| f64::from(x)).sum::<f64>()).sum::<f64>() / f.n as f64;
    let t_form = start.elapsed();
    let albedo: Vec<Vec3> = p.patches.iter().map(|x| x.albedo).collect();
    let start = Instant::now();
    let colour = colour_matrix(&f, &albedo);
    let k = steps.k_bounce(&colour, settings.bounces, Progress::Stderr);
    let t_k = start.elapsed();
    let total: f64 = k.channels.iter().flatten().map(|&x| f64::from(x)).sum();
    let searches = if settings.reorder == Search::Exact || f.n <= EXACT_REPORT_PATCHES { vec![Search::Exact, Search::SKETCH] } else { vec![settings.reorder] };
    let reorderings = std::iter::once(Reorder { passes: 0, search: Search::Exact })
        .chain(searches.into_iter().flat_map(|search| (1..=compress::REORDER_PASSES).map(move |passes| Reorder { passes, search })));
    let mut compressed = Vec::new();
    let mut matrix = None;
    for (range, reorder) in [LogRange::Seed, LogRange::Fitted].into_iter().flat_map(|range| reorderings.clone().map(move |reorder| (range, reorder))) {
        let stage = Progress::Stderr.stage(&format!("report: compression ({range:?} log range, {} passes, {:?})", reorder.passes, reorder.search), 1, "compressions");
        let start = Instant::now();
        let c = compress(&k, settings.top_share, reorder, range, Progress::Quiet);
        let t = start.elapsed();
        compressed.push(Compressed { range, passes: reorder.passes, search: reorder.search, time: t, bytes: c.bytes(), errors: compress::errors(&k, &c.decompress()) });
        stage.finish();
        if (range, reorder) == (RANGE, reorder_of(settings)) {
            matrix = Some(c);
        }
    }
    let matrix = matrix.unwrap_or_else(|| compress(&k, settings.top_share, reorder_of(settings), RANGE, Progress::Quiet));
    let ones = vec![Vec3::ONE; f.n];
    let start = Instant::now();
    let converged = neumann(&f, &albedo, &ones, TOLERANCE, 10_000);
    let t_classic = start.elapsed();
    let start = Instant::now();
    let sweeps = gauss_seidel(&f, &albedo, &ones, TOLERANCE, 10_000).bounces;
    let t_gauss_seidel = start.elapsed();
    let largest = converged.secondary.iter().map(|v| v.max_element()).fold(0.0f32, f32::max).max(f32::MIN_POSITIVE);
    let mut truncation = Vec::new();
    let (mut incident, mut sum) = (ones.clone(), vec![Vec3::ZERO; f.n]);
    for _ in 0..settings.bounces {
        incident = gather(&f, &albedo, &incident);
        for (s, x) in sum.iter_mut().zip(&incident) {
            *s += *x;
        }
        truncation.push(sum.iter().zip(&converged.secondary).map(|(a, b)| (*b - *a).abs().max_element()).fold(0.0f32, f32::max) / largest);
    }
    let start = Instant::now();
    std::hint::black_box(k.apply(&ones));
    let t_dense = start.elapsed();
    Ok(Report {
        notes: note.into_iter().collect(),
        triangles: chunks.iter().map(|c| c.triangles()).sum(),
        patch_size: patch_size_of(&p, settings),
        mean_albedo,
        mean_row_sum,
        patches: p,
        times: [t_patches, t_form, t_k],
        bounces: settings.bounces,
        dense_bytes: [f.bytes(), k.bytes()],
        compressed,
        matrix,
        total,
        truncation,
        neumann_bounces: converged.bounces,
        gauss_seidel_sweeps: sweeps,
        frame_times: [t_dense, t_classic, t_gauss_seidel],
    })
}

/// The patch size `p` was built at: the setting, or the automatic size (the square root of
/// the largest patch's area bounds it from below).
fn patch_size_of(p: &Patches, settings: &Settings) -> f32 {
    if settings.patch_size > 0.0 { settings.patch_size } else { p.patches.iter().map(|x| x.area).fold(0.0f32, f32::max).sqrt() }
}

impl Report {
    /// The report as Markdown tables.
    pub fn markdown(&self) -> String {
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let mib = |b: usize| b as f64 / f64::from(1 << 20);
        let mut s = String::new();
        for note in &self.notes {
            let _ = writeln!(s, "note: {note}\n");
        }
        let _ = writeln!(
            s,
            "static world: {} triangles, patch size {:.4}, {} patches; area-weighted mean albedo {:.4}, mean form-factor row sum {:.4}\n",
            self.triangles,
            self.patch_size,
            self.patches.patches.len(),
            self.mean_albedo,
            self.mean_row_sum
        );
        let _ = writeln!(s, "| step | ms |\n| --- | ---: |");
        for (name, t) in ["patches", "form factors", &format!("k-bounce matrix (k = {})", self.bounces)].iter().zip(self.times) {
            let _ = writeln!(s, "| {name} | {:.1} |", ms(t));
        }
        let _ = writeln!(s, "\n| matrix | bytes | MiB |\n| --- | ---: | ---: |");
        let _ = writeln!(s, "| form factors, dense f32 | {} | {:.3} |", self.dense_bytes[0], mib(self.dense_bytes[0]));
        let _ = writeln!(s, "| colour matrix, dense f32 x 3 | {} | {:.3} |", self.dense_bytes[1], mib(self.dense_bytes[1]));
        let _ = writeln!(s, "| k-bounce colour matrix, dense f32 x 3 | {} | {:.3} |", self.dense_bytes[1], mib(self.dense_bytes[1]));
        let c = self.matrix.bytes();
        let _ = writeln!(s, "| compressed (BC1 + exact top share + order) | {c} | {:.3} |", mib(c));
        let _ = writeln!(s, "\n| log range | reordering passes | search | mean error | max error | summed error | summed / sum of entries | compress ms |\n| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: |");
        for c in &self.compressed {
            let e = &c.errors;
            let range = match c.range {
                LogRange::Seed => "seed (shift 25)",
                LogRange::Fitted => "fitted",
            };
            let search = match (c.passes, c.search) {
                (0, _) => "",
                (_, Search::Exact) => "exact",
                (_, Search::Sketch { .. }) => "sketch",
            };
            let _ = writeln!(s, "| {range} | {} | {search} | {:.3e} | {:.3e} | {:.4} | {:.4} | {:.1} |", c.passes, e.mean, e.max, e.sum, e.sum / self.total.max(f64::MIN_POSITIVE), ms(c.time));
        }
        let _ = writeln!(s, "\nk bounces against the Neumann series ({} bounces to converge to {TOLERANCE:e}), primary light 1 on every patch; largest error / largest converged value:\n", self.neumann_bounces);
        let _ = writeln!(s, "| k | error |\n| ---: | ---: |");
        for (h, e) in self.truncation.iter().enumerate() {
            let _ = writeln!(s, "| {} | {e:.4} |", h + 1);
        }
        let _ = writeln!(
            s,
            "\nper frame (CPU, one core, f64 sums): dense k-bounce product {:.2} ms; classic gathering to convergence: Jacobi {:.2} ms ({} bounces), Gauss–Seidel {:.2} ms ({} sweeps)",
            ms(self.frame_times[0]),
            ms(self.frame_times[1]),
            self.neumann_bounces,
            ms(self.frame_times[2]),
            self.gauss_seidel_sweeps
        );
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::radiosity::form_factors;
    use crate::render::radiosity::test_scenes::quad;

    #[test]
    fn the_budget_sets_the_patch_size_and_the_report_has_every_number() {
        let x = Vec3::X * 2.0;
        let y = Vec3::Y * 2.0;
        let z = Vec3::Z * 2.0;
        // Grey walls: display 128 of 255, albedo 0.216 (linear).
        let grey = |c: Arc<StaticChunk>| Arc::new(StaticChunk { colors: vec![[128, 128, 128, 255]; 6], ..(*c).clone() });
        let chunks = [quad(1, Vec3::ZERO, x, y), quad(2, z, y, x), quad(3, Vec3::ZERO, y, z), quad(4, x, z, y), quad(5, Vec3::ZERO, z, x), quad(6, y, x, z)].map(grey);
        // 1 MiB holds 209 patches: 24 square metres over 209 patches, grown until they fit.
        let settings = Settings { budget_mb: 1, ..Settings::default() };
        let (p, note) = patches_within_budget(&chunks, &settings);
        assert!(p.patches.len() <= 209 && p.patches.len() >= 50 && note.is_none(), "{} {note:?}", p.patches.len());
        // Too fine for the budget: the automatic size instead, and a note.
        let too_fine = Settings { patch_size: 0.05, ..settings };
        let (fallback, note) = patches_within_budget(&chunks, &too_fine);
        assert_eq!(fallback, p);
        let note = note.expect("a note");
        assert!(note.starts_with("9600 patches of size 0.05 exceed the memory budget of 1 MiB (209 patches): using larger patches"), "{note}");
        assert!(note.ends_with(&format!("{} patches", p.patches.len())), "{note}");

        let report = run(&chunks, &Settings { patch_size: 1.0, ..settings }, &mut form_factors::compute).expect("patches");
        assert_eq!((report.patches.patches.len(), report.triangles, report.bounces), (24, 12, 3));
        assert_eq!(report.dense_bytes, [24 * 24 * 4, 24 * 24 * 12]);
        assert_eq!(report.compressed.len(), 10);
        // In a closed box each bounce is ρ = 0.216 of the one before: ~9 bounces to 1e-6; k
        // bounces fall short by ρ^(k+1) / (1 - ρ) against ρ / (1 - ρ) converged: ρ^k of it.
        assert!((8..=12).contains(&report.neumann_bounces), "{}", report.neumann_bounces);
        let rho = crate::render::trace::scene::srgb_to_linear(128.0 / 255.0);
        for (h, e) in report.truncation.iter().enumerate() {
            let expected = rho.powi(h as i32 + 1);
            assert!((e - expected).abs() < 0.02 * expected + 1e-4, "k = {}: {e} vs {expected}", h + 1);
        }
        let md = report.markdown();
        assert!(md.contains("static world: 12 triangles, patch size 1.0000, 24 patches; area-weighted mean albedo [0.2159, 0.2159, 0.2159], mean form-factor row sum "), "{md}");
        assert!((report.mean_row_sum - 1.0).abs() < 1.0e-3, "closed: {}", report.mean_row_sum);
        assert!(md.contains("| form factors, dense f32 | 2304 |"), "{md}");
    }

    #[test]
    fn a_world_of_more_orientations_than_the_budget_holds_gets_no_patches_and_a_note() {
        // 40 × 40 small quads facing as many directions (a curved world): more quantised
        // normals than the 209 patches of 1 MiB, whatever the size.
        let chunks: Vec<_> = (0..1600u64)
            .map(|k| {
                let (a, b) = ((k / 40) as f32 * 0.078, (k % 40) as f32 * 0.157);
                let n = Vec3::new(a.sin() * b.cos(), a.sin() * b.sin(), a.cos());
                let u = n.any_orthonormal_vector();
                quad(k, Vec3::new((k % 40) as f32, (k / 40) as f32, 0.0), u * 0.5, n.cross(u) * 0.5)
            })
            .collect();
        let settings = Settings { budget_mb: 1, ..Settings::default() };
        let (p, note) = patches_within_budget(&chunks, &settings);
        assert!(p.patches.is_empty(), "{} patches", p.patches.len());
        let note = note.expect("a note");
        assert!(note.starts_with("the static world makes ") && note.ends_with("more than the memory budget of 1 MiB holds (209 patches): radiosity is off (raise radiosity_budget_mb)"), "{note}");
        // A budget that holds them: patches.
        let (p, note) = patches_within_budget(&chunks, &Settings { budget_mb: 64, ..settings });
        assert!(!p.patches.is_empty() && note.is_none(), "{note:?}");
    }

    #[test]
    fn the_matrix_is_cached_reloaded_and_recomputed_when_its_file_is_damaged() {
        let (x, y, z) = (Vec3::X * 2.0, Vec3::Y * 2.0, Vec3::Z * 2.0);
        let chunks = [quad(1, Vec3::ZERO, x, y), quad(2, z, y, x), quad(3, Vec3::ZERO, y, z), quad(4, x, z, y), quad(5, Vec3::ZERO, z, x), quad(6, y, x, z)];
        let settings = Settings { patch_size: 1.0, ..Settings::default() };
        let dir = std::env::temp_dir().join(format!("glrt-radiosity-precompute-{}", std::process::id()));
        let mut computed = 0;
        let mut ff = |p: &Patches| {
            computed += 1;
            form_factors::compute(p)
        };
        let first = load_or_build(&chunks, &settings, Some(&dir), &mut ff);
        assert!(!first.loaded && first.notes.is_empty(), "{:?}", first.notes);
        assert_eq!(first.patches.patches.len(), 24);
        let file = first.cache_file.clone().expect("a cache file");
        assert!(file.starts_with(dir.join("glrt/radiosity")) && file.exists());
        let second = load_or_build(&chunks, &settings, Some(&dir), &mut ff);
        assert!(second.loaded && second.notes.is_empty());
        assert_eq!((second.matrix, second.patches, second.cache_file.as_ref()), (first.matrix.clone(), first.patches.clone(), Some(&file)));
        // Other settings, another file.
        let two = load_or_build(&chunks, &Settings { bounces: 2, ..settings }, Some(&dir), &mut ff);
        assert!(!two.loaded && two.cache_file.as_ref() != Some(&file));
        // A damaged file: recomputed with a note, and written again.
        let mut bytes = std::fs::read(&file).unwrap();
        let last = bytes.len() - 1;
        bytes[last] ^= 0xff;
        std::fs::write(&file, &bytes).unwrap();
        let again = load_or_build(&chunks, &settings, Some(&dir), &mut ff);
        assert!(!again.loaded);
        assert_eq!(again.notes, [format!("radiosity cache {}: its content does not match its hash (damaged or cut short): recomputing", file.display())]);
        assert_eq!(again.matrix, first.matrix);
        assert!(load_or_build(&chunks, &settings, Some(&dir), &mut ff).loaded);
        assert_eq!(computed, 3);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
