//! What the path tracer did: rays traced by kind and traversal work per frame (counted by
//! `pathtrace.comp` into the counters buffer), what the scene held ([`SceneCounts`]), the GPU
//! time of the tracing pass (timestamps around its dispatch), and the totals of a run, which
//! [`Totals::summary`] turns into rays per second (logged at `GLRT_LOG=info` when the renderer
//! is dropped: the numbers of `bench/`). A back end reports them as [`Statistics`].

/// What a ray-tracing back end reports ([`super::RayTracer::statistics`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Statistics {
    /// Rays of the last frame whose counters were read (a frame in flight behind).
    pub rays: RayCounts,
    /// Sums over every frame whose counters were read.
    pub totals: Totals,
    /// The scene of the last frame traced.
    pub scene: SceneCounts,
    /// Frames traced.
    pub frames: u64,
}

use super::gpu_types::GpuCounters;

/// Rays traced in one frame, by kind, and the traversal work they cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Camera rays.
    pub primary: u64,
    /// Shadow rays of next-event estimation.
    pub shadow: u64,
    /// Indirect rays of the diffuse lobe.
    pub diffuse: u64,
    /// Indirect rays of the specular lobe.
    pub specular: u64,
    /// BVH nodes visited by all rays (top and bottom levels).
    pub nodes_visited: u64,
    /// Ray-triangle intersection tests of all rays.
    pub triangles_tested: u64,
    /// Shadow rays towards the sky (in `shadow` too).
    pub sky: u64,
    /// Those of them that found the sky.
    pub sky_unoccluded: u64,
}

impl RayCounts {
    /// The counts in the counters buffer's bytes ([`GpuCounters`]; `None` when too short).
    pub fn from_counters(bytes: &[u8]) -> Option<RayCounts> {
        let c: GpuCounters = bytemuck::pod_read_unaligned(bytes.get(..size_of::<GpuCounters>())?);
        Some(RayCounts {
            primary: c.primary_rays.into(),
            shadow: c.shadow_rays.into(),
            diffuse: c.diffuse_rays.into(),
            specular: c.specular_rays.into(),
            nodes_visited: c.nodes_visited.into(),
            triangles_tested: c.triangles_tested.into(),
            sky: c.sky_rays.into(),
            sky_unoccluded: c.sky_unoccluded.into(),
        })
    }

    /// Every ray traced.
    pub fn total(&self) -> u64 {
        self.primary + self.shadow + self.diffuse + self.specular
    }
}

/// What one traced frame's acceleration structures held, and the BVH work it took.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneCounts {
    /// Instances of traced draws.
    pub draw_instances: u32,
    /// Instances of static-world chunks.
    pub chunk_instances: u32,
    /// Instances of the top level: draws and chunks, but the hardware tracer's merged
    /// regions of chunks count once ([`super::regions`]).
    pub top_instances: u32,
    /// Traced draws left out because the static world holds all their triangles.
    pub covered_draws: u32,
    /// Passes (draws of class `Layer`) traced in the surfaces of the draw instances.
    pub passes: u32,
    /// Triangles in the emitter list (next-event estimation of emissive surfaces).
    pub emitters: u32,
    /// Triangles of all instances.
    pub triangles: u64,
    /// Geometries whose BVH was built in this frame.
    pub built: u32,
    /// Geometries whose BVH was refitted in this frame.
    pub refitted: u32,
    /// CPU time of the frame's acceleration-structure work, in microseconds: BVH builds and
    /// refits of new geometry, the top level, and the hardware tracer's build recording.
    pub build_micros: u64,
}

/// GPU seconds of one frame's passes, from timestamps.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassSeconds {
    /// The tracing pass (its gradient pass included).
    pub trace: f64,
    /// The tracing pass's gradient pass (`trace/gradient.glsl`; 0 without one).
    pub gradient: f64,
    /// Geometry uploads and acceleration-structure builds.
    pub build: f64,
}

/// The sums over the frames of a run whose counters and pass times were read.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Totals {
    /// Frames counted.
    pub frames: u64,
    /// Rays and work, summed.
    pub rays: RayCounts,
    /// GPU seconds of the tracing pass, summed over the frames that had timestamps.
    pub trace_seconds: f64,
    /// GPU seconds of the tracing pass's gradient pass, summed over the same frames.
    pub gradient_seconds: f64,
    /// Frames whose pass time is in `trace_seconds`.
    pub timed_frames: u64,
    /// GPU seconds of the frames' uploads and acceleration-structure builds, summed over the
    /// frames in `timed_frames`.
    pub build_seconds: f64,
    /// Frames recorded.
    pub scenes: u64,
    /// Their scenes' counts, summed.
    pub scene: SceneTotals,
}

/// [`SceneCounts`] summed over frames.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SceneTotals {
    /// Triangles of all instances.
    pub triangles: u64,
    /// Instances of draws and of chunks.
    pub instances: u64,
    /// Instances of chunks.
    pub chunk_instances: u64,
    /// Instances of the top level.
    pub top_instances: u64,
    /// Passes traced in surfaces.
    pub passes: u64,
    /// Triangles in the emitter lists.
    pub emitters: u64,
    /// BVHs built.
    pub built: u64,
    /// BVHs refitted.
    pub refitted: u64,
    /// CPU microseconds of acceleration-structure work.
    pub build_micros: u64,
}

impl Totals {
    /// Adds one frame: its counts and, when the device timed it, its tracing pass's seconds.
    pub fn add(&mut self, rays: RayCounts, seconds: Option<PassSeconds>) {
        self.frames += 1;
        let r = &mut self.rays;
        r.primary += rays.primary;
        r.shadow += rays.shadow;
        r.diffuse += rays.diffuse;
        r.specular += rays.specular;
        r.nodes_visited += rays.nodes_visited;
        r.triangles_tested += rays.triangles_tested;
        r.sky += rays.sky;
        r.sky_unoccluded += rays.sky_unoccluded;
        if let Some(s) = seconds {
            self.trace_seconds += s.trace;
            self.gradient_seconds += s.gradient;
            self.build_seconds += s.build;
            self.timed_frames += 1;
        }
    }

    /// Adds one recorded frame's traced scene.
    pub fn add_scene(&mut self, counts: &SceneCounts) {
        self.scenes += 1;
        let t = &mut self.scene;
        t.triangles += counts.triangles;
        t.instances += u64::from(counts.draw_instances + counts.chunk_instances);
        t.chunk_instances += u64::from(counts.chunk_instances);
        t.top_instances += u64::from(counts.top_instances);
        t.passes += u64::from(counts.passes);
        t.emitters += u64::from(counts.emitters);
        t.built += u64::from(counts.built);
        t.refitted += u64::from(counts.refitted);
        t.build_micros += counts.build_micros;
    }

    /// One line: per-frame averages and, when every frame was timed, rays per second of the
    /// tracing pass by kind.
    pub fn summary(&self) -> String {
        if self.frames == 0 {
            return "path tracer: no frame traced".to_owned();
        }
        let n = self.frames as f64;
        let r = &self.rays;
        let per_ray = |work: u64| work as f64 / r.total().max(1) as f64;
        let scenes = self.scenes.max(1) as f64;
        let mut line = format!(
            "path tracer: {} frames; scene: {:.0} triangles in {:.0} instances ({:.0} of chunks; {:.0} in the top level) with {:.0} passes, {:.0} emitter triangles, {:.1} BVHs built and {:.1} refitted per frame; per frame: {:.0} primary, {:.0} shadow ({:.0} to the sky, {:.1} % of them unoccluded), {:.0} diffuse, {:.0} specular rays; per ray: {:.1} nodes, {:.1} triangle tests",
            self.frames,
            self.scene.triangles as f64 / scenes,
            self.scene.instances as f64 / scenes,
            self.scene.chunk_instances as f64 / scenes,
            self.scene.top_instances as f64 / scenes,
            self.scene.passes as f64 / scenes,
            self.scene.emitters as f64 / scenes,
            self.scene.built as f64 / scenes,
            self.scene.refitted as f64 / scenes,
            r.primary as f64 / n,
            r.shadow as f64 / n,
            r.sky as f64 / n,
            100.0 * r.sky_unoccluded as f64 / r.sky.max(1) as f64,
            r.diffuse as f64 / n,
            r.specular as f64 / n,
            per_ray(r.nodes_visited),
            per_ray(r.triangles_tested),
        );
        if self.timed_frames == self.frames && self.trace_seconds > 0.0 {
            let rate = |count: u64| count as f64 / self.trace_seconds / 1e6;
            line += &format!(
                "; tracing pass {:.3} ms per frame ({:.3} ms of it the gradient pass); Mrays/s: {:.1} primary, {:.1} shadow, {:.1} diffuse, {:.1} specular, {:.1} all",
                self.trace_seconds * 1e3 / n,
                self.gradient_seconds * 1e3 / n,
                rate(r.primary),
                rate(r.shadow),
                rate(r.diffuse),
                rate(r.specular),
                rate(r.total()),
            );
        }
        line += &format!("; acceleration structures per frame: {:.3} ms CPU", self.scene.build_micros as f64 / 1e3 / scenes);
        if self.timed_frames == self.frames {
            line += &format!(", {:.3} ms GPU (uploads and builds)", self.build_seconds * 1e3 / n);
        }
        line
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counters_are_read_in_shader_order() {
        let bytes: Vec<u8> = (1u32..=8).flat_map(u32::to_le_bytes).collect();
        let r = RayCounts::from_counters(&bytes).unwrap();
        assert_eq!(r, RayCounts { primary: 1, shadow: 2, diffuse: 3, specular: 4, nodes_visited: 5, triangles_tested: 6, sky: 7, sky_unoccluded: 8 });
        assert_eq!(RayCounts::from_counters(&bytes[..28]), None);
    }

    #[test]
    fn the_summary_gives_rates_of_the_timed_pass() {
        let mut t = Totals::default();
        let frame = RayCounts { primary: 1_000_000, shadow: 2_000_000, diffuse: 500_000, specular: 0, nodes_visited: 35_000_000, triangles_tested: 7_000_000, sky: 400_000, sky_unoccluded: 100_000 };
        let timed = Some(PassSeconds { trace: 0.001, gradient: 0.0002, build: 0.0005 });
        t.add(frame, timed);
        t.add(frame, timed);
        t.add_scene(&SceneCounts { draw_instances: 1, chunk_instances: 2, top_instances: 2, triangles: 1000, built: 3, passes: 2, build_micros: 3000, ..SceneCounts::default() });
        t.add_scene(&SceneCounts { draw_instances: 5, top_instances: 4, triangles: 3000, refitted: 1, emitters: 10, build_micros: 1000, ..SceneCounts::default() });
        let s = t.summary();
        assert!(s.contains("2 frames; scene: 2000 triangles in 4 instances (1 of chunks; 3 in the top level) with 1 passes, 5 emitter triangles, 1.5 BVHs built and 0.5 refitted per frame"), "{s}");
        assert!(s.contains("2000000 shadow (400000 to the sky, 25.0 % of them unoccluded)"), "{s}");
        assert!(s.contains("per ray: 10.0 nodes, 2.0 triangle tests"), "{s}");
        assert!(s.contains("tracing pass 1.000 ms per frame (0.200 ms of it the gradient pass); Mrays/s: 1000.0 primary, 2000.0 shadow, 500.0 diffuse, 0.0 specular, 3500.0 all"), "{s}");
        assert!(s.contains("acceleration structures per frame: 2.000 ms CPU, 0.500 ms GPU"), "{s}");
        t.add(frame, None);
        let s = t.summary();
        assert!(!s.contains("Mrays/s") && !s.contains("ms GPU"), "an untimed frame leaves the rates out: {s}");
    }
}
