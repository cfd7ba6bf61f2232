//! BVH build, refit and traversal checked against brute force over every triangle (same
//! intersection arithmetic, so distances compare exactly), and the GPU layout's sizes.

use std::time::Instant;

use glam::{Affine3A, Quat, Vec2, Vec3};
use obvhs::BvhBuildParams;

use super::cpu::{self, Hit, Instance, Scene};
use super::{Aabb, Blas, GpuNode, GpuTriangle, GpuWideNode, Layout, Tlas, sah_cost};
use crate::render::trace::shader_constants::BVH_MAX_DEPTH;

/// A deterministic xorshift generator.
struct Rng(u64);

impl Rng {
    fn f32(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A point uniformly in [-s, s]³.
    fn vec(&mut self, s: f32) -> Vec3 {
        Vec3::new(self.f32() * 2.0 - 1.0, self.f32() * 2.0 - 1.0, self.f32() * 2.0 - 1.0) * s
    }
}

/// `n` random triangles of size about `size` in [-1, 1]³.
fn soup(rng: &mut Rng, n: usize, size: f32) -> Vec<[Vec3; 3]> {
    (0..n)
        .map(|_| {
            let c = rng.vec(1.0);
            [c + rng.vec(size), c + rng.vec(size), c + rng.vec(size)]
        })
        .collect()
}

/// A UV sphere of radius 1 at the origin (shared edges and vertices).
fn sphere(rings: usize, segments: usize) -> Vec<[Vec3; 3]> {
    let p = |r: usize, s: usize| {
        let (theta, phi) = (r as f32 / rings as f32 * std::f32::consts::PI, s as f32 / segments as f32 * std::f32::consts::TAU);
        Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin())
    };
    let mut out = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            out.push([p(r, s), p(r + 1, s), p(r + 1, s + 1)]);
            out.push([p(r, s), p(r + 1, s + 1), p(r, s + 1)]);
        }
    }
    out
}

/// A placed geometry: its triangles (object space), its transform, alpha testing.
struct Placed<'a> {
    triangles: &'a [[Vec3; 3]],
    object_to_eye: Affine3A,
    alpha_tested: bool,
}

/// The shared buffers of a scene of BLASes and instances, as an uploader lays them out.
struct Built {
    blas: Vec<Blas>,
    tlas: Tlas,
    nodes: Vec<GpuNode>,
    triangles: Vec<GpuTriangle>,
    instances: Vec<Instance>,
}

impl Built {
    fn new(placed: &[Placed], blas: Vec<Blas>) -> Built {
        let (mut nodes, mut triangles) = (Vec::new(), Vec::new());
        let mut instances = Vec::new();
        let mut bounds = Vec::new();
        for (p, b) in placed.iter().zip(&blas) {
            let (root, first) = (nodes.len() as u32, triangles.len() as u32);
            nodes.extend_from_slice(&b.nodes);
            triangles.extend_from_slice(&b.triangles);
            instances.push(Instance::new(&p.object_to_eye, root, first, p.alpha_tested));
            bounds.push(b.bounds.transformed(&p.object_to_eye));
        }
        Built { blas, tlas: Tlas::build(&bounds, Layout::Binary), nodes, triangles, instances }
    }

    fn scene(&self) -> Scene<'_> {
        Scene { tlas: &self.tlas.nodes, blas_nodes: &self.nodes, triangles: &self.triangles, instances: &self.instances }
    }
}

/// Builds each placed geometry's BLAS and the TLAS.
fn build(placed: &[Placed]) -> Built {
    Built::new(placed, placed.iter().map(|p| Blas::build(p.triangles, Layout::Binary)).collect())
}

/// Rejects odd triangles (the alpha test of these tests).
fn even(_: u32, triangle: u32, _: Vec2) -> bool {
    triangle.is_multiple_of(2)
}

/// The closest accepted hit by testing every triangle of every instance: as (t, instance,
/// index in the placed input).
fn brute(built: &Built, placed: &[Placed], o: Vec3, d: Vec3, tmax: f32) -> Option<(f32, u32, u32)> {
    let mut best: Option<(f32, u32, u32)> = None;
    for (i, (p, b)) in placed.iter().zip(&built.blas).enumerate() {
        let inst = &built.instances[i];
        let (oo, od) = (cpu::transform(&inst.eye_to_object, o, 1.0), cpu::transform(&inst.eye_to_object, d, 0.0));
        for (k, &input) in b.order.iter().enumerate() {
            let global = inst.first_triangle + k as u32;
            let limit = best.map_or(tmax, |h| h.0);
            if let Some((t, _)) = cpu::intersect(&built.triangles[global as usize], oo, od, 0.0, limit)
                && (!p.alpha_tested || even(i as u32, global, Vec2::ZERO))
            {
                best = Some((t, i as u32, input));
            }
        }
    }
    best
}

/// Traces `rays` random rays from around the scene through it; checks closest and any hits
/// against brute force; returns how many hit.
fn check_rays(built: &Built, placed: &[Placed], rng: &mut Rng, rays: usize, spread: f32) -> usize {
    let scene = built.scene();
    let mut hits = 0;
    for _ in 0..rays {
        let o = rng.vec(spread);
        let d = (rng.vec(0.7) - o).normalize_or(Vec3::X);
        let tmax = if rng.f32() < 0.5 { f32::INFINITY } else { rng.f32() * 4.0 };
        let got = cpu::closest(&scene, o, d, 0.0, tmax, even);
        let want = brute(built, placed, o, d, tmax);
        let got_key = got.map(|h: Hit| {
            (h.t, h.instance, built.blas[h.instance as usize].order[(h.triangle - built.instances[h.instance as usize].first_triangle) as usize])
        });
        match (got_key, want) {
            (Some(g), Some(w)) => {
                assert_eq!(g.0, w.0, "t differs: ray {o} {d}: {g:?} vs {w:?}");
                // Equal t on another triangle is a tie (shared edge or vertex): either is right.
                hits += 1;
            }
            (g, w) => assert_eq!(g, w, "ray {o} {d} tmax {tmax}"),
        }
        assert_eq!(cpu::any(&scene, o, d, 0.0, tmax, even), want.is_some(), "any: ray {o} {d} tmax {tmax}");
    }
    hits
}

/// The most nodes on a root-to-leaf path.
fn depth(nodes: &[GpuNode], node: usize) -> usize {
    1 + nodes[node].children.iter().filter(|c| !c.is_leaf()).map(|c| depth(nodes, c.index as usize)).max().unwrap_or(0)
}

#[test]
fn soup_matches_brute_force() {
    let mut rng = Rng(0x1234_5678_9abc);
    let tris = soup(&mut rng, 3000, 0.1);
    let placed = [Placed { triangles: &tris, object_to_eye: Affine3A::IDENTITY, alpha_tested: false }];
    let built = build(&placed);
    let mut order = built.blas[0].order.clone();
    order.sort_unstable();
    assert_eq!(order, (0..3000).collect::<Vec<u32>>(), "order is a permutation");
    assert!(depth(&built.blas[0].nodes, 0) <= BVH_MAX_DEPTH);
    let hits = check_rays(&built, &placed, &mut rng, 4000, 1.5);
    assert!(hits > 1000, "only {hits} hits");
}

#[test]
fn mesh_and_transformed_instances_match_brute_force() {
    let mut rng = Rng(99);
    let ball = sphere(24, 48);
    let rocks = soup(&mut rng, 500, 0.2);
    let single = [[Vec3::ZERO, Vec3::X, Vec3::Y]];
    let t = |s: f32, r: Quat, at: Vec3| Affine3A::from_scale_rotation_translation(Vec3::splat(s), r, at);
    let placed = [
        Placed { triangles: &ball, object_to_eye: t(0.5, Quat::from_rotation_y(0.3), Vec3::new(0.0, 0.0, -1.0)), alpha_tested: false },
        Placed { triangles: &rocks, object_to_eye: t(0.7, Quat::from_rotation_x(1.1), Vec3::new(0.8, 0.2, 0.0)), alpha_tested: true },
        Placed { triangles: &ball, object_to_eye: t(0.3, Quat::IDENTITY, Vec3::new(-0.6, -0.5, 0.4)), alpha_tested: false },
        Placed { triangles: &single, object_to_eye: t(2.0, Quat::from_rotation_z(0.5), Vec3::new(-1.0, 0.5, -0.5)), alpha_tested: false },
        Placed { triangles: &[], object_to_eye: Affine3A::IDENTITY, alpha_tested: false },
        Placed {
            triangles: &ball,
            object_to_eye: Affine3A::from_mat3_translation(glam::Mat3::from_diagonal(Vec3::new(0.2, 1.0, 0.4)), Vec3::new(0.5, -0.7, -0.6)),
            alpha_tested: false,
        },
    ];
    let built = build(&placed);
    let hits = check_rays(&built, &placed, &mut rng, 4000, 1.5);
    assert!(hits > 1000, "only {hits} hits");
    // The alpha-tested instance passes rays through its odd triangles.
    let scene = built.scene();
    let first = built.instances[1].first_triangle;
    let mut passed = 0;
    for k in 0..built.blas[1].triangles.len() as u32 {
        let tri = &built.triangles[(first + k) as usize];
        let object = Vec3::from(tri.v0) + Vec3::from(tri.e1) * 0.3 + Vec3::from(tri.e2) * 0.3;
        let eye = placed[1].object_to_eye.transform_point3(object);
        let o = Vec3::new(0.0, 0.0, 3.0);
        let hit = cpu::closest(&scene, o, eye - o, 0.0, f32::INFINITY, even);
        if (first + k) % 2 == 1 {
            assert!(hit.is_none_or(|h| h.triangle != first + k), "rejected triangle {k} was hit");
            passed += 1;
        }
    }
    assert!(passed > 100);
}

#[test]
fn empty_and_degenerate_input() {
    let empty = Blas::build(&[], Layout::Binary);
    assert_eq!((empty.nodes.len(), empty.triangles.len(), empty.order.len()), (1, 0, 0));
    assert!(empty.bounds.is_empty());
    let tlas = Tlas::build(&[], Layout::Binary);
    assert_eq!(tlas.nodes.len(), 1);
    let scene = Scene { tlas: &tlas.nodes, blas_nodes: &empty.nodes, triangles: &[], instances: &[] };
    assert_eq!(cpu::closest(&scene, Vec3::ZERO, Vec3::NEG_Z, 0.0, f32::INFINITY, even), None);
    assert!(!cpu::any(&scene, Vec3::ZERO, Vec3::NEG_Z, 0.0, f32::INFINITY, even));

    // Zero-area, NaN and infinite triangles build and are never hit; the good one is.
    let (nan, inf) = (f32::NAN, f32::INFINITY);
    let tris = [
        [Vec3::ZERO; 3],
        [Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
        [Vec3::new(nan, 0.0, 0.0), Vec3::X, Vec3::Y],
        [Vec3::splat(inf), Vec3::splat(-inf), Vec3::Y],
        [Vec3::new(-1.0, -1.0, -2.0), Vec3::new(1.0, -1.0, -2.0), Vec3::new(0.0, 1.0, -2.0)],
        [Vec3::splat(1e30), Vec3::splat(-1e30), Vec3::new(1e30, 0.0, 0.0)],
    ];
    let blas = Blas::build(&tris, Layout::Binary);
    assert!(blas.bounds.is_finite());
    let mut order = blas.order.clone();
    order.sort_unstable();
    assert_eq!(order, [0, 1, 2, 3, 4, 5]);
    let instances = [Instance::new(&Affine3A::IDENTITY, 0, 0, false)];
    let tlas = Tlas::build(&[blas.bounds, Aabb::EMPTY, Aabb { min: Vec3::splat(nan), max: Vec3::ONE }], Layout::Binary);
    let scene = Scene { tlas: &tlas.nodes, blas_nodes: &blas.nodes, triangles: &blas.triangles, instances: &instances };
    let hit = cpu::closest(&scene, Vec3::ZERO, Vec3::NEG_Z, 0.0, f32::INFINITY, even).expect("the good triangle");
    assert_eq!((hit.t, hit.instance, blas.order[hit.triangle as usize]), (2.0, 0, 4));
    let mut rng = Rng(5);
    for _ in 0..2000 {
        let d = rng.vec(1.0);
        if let Some(h) = cpu::closest(&scene, rng.vec(0.5), d, 0.0, f32::INFINITY, even) {
            assert!(matches!(blas.order[h.triangle as usize], 4 | 5), "hit degenerate triangle {h:?}");
        }
    }
}

#[test]
fn only_the_selected_layout_is_built() {
    let mut rng = Rng(31);
    let tris = soup(&mut rng, 5000, 0.05);
    let binary = Blas::build(&tris, Layout::Binary);
    assert!(binary.wide.is_none(), "no wide collapse for the binary layout");
    assert_eq!(binary.node_count(), binary.nodes.len());
    assert_eq!(binary.node_bytes().len(), binary.nodes.len() * size_of::<GpuNode>());

    let wide = Blas::build(&tris, Layout::Wide);
    let collapsed = wide.wide.as_ref().expect("the wide collapse");
    assert_eq!(wide.node_count(), collapsed.nodes.len());
    assert_eq!(wide.node_bytes().len(), collapsed.nodes.len() * size_of::<GpuWideNode>());
    assert!(collapsed.nodes.len() * 2 < wide.nodes.len(), "{} wide nodes for {} binary", collapsed.nodes.len(), wide.nodes.len());
    // The same binary tree under both (its leaves renumbered for the wide one's order).
    assert_eq!(wide.nodes.len(), binary.nodes.len());
    assert_eq!(sah_cost(&wide.nodes), sah_cost(&binary.nodes));
    for blas in [&binary, &wide] {
        let mut order = blas.order.clone();
        order.sort_unstable();
        assert_eq!(order, (0..5000).collect::<Vec<u32>>());
    }

    let boxes: Vec<Aabb> = (0..300).map(|i| Aabb { min: Vec3::new(i as f32, 0.0, 0.0), max: Vec3::new(i as f32 + 0.5, 1.0, 1.0) }).collect();
    let tlas = Tlas::build(&boxes, Layout::Binary);
    assert_eq!((tlas.wide.is_none(), tlas.wide_count, tlas.wide_nodes().len()), (true, 0, 0));
    assert_eq!(tlas.node_bytes().len(), tlas.nodes.len() * size_of::<GpuNode>());
    let tlas = Tlas::build(&boxes, Layout::Wide);
    assert!(tlas.wide_count > 0 && tlas.wide_count * 2 < tlas.nodes.len());
    // The wide nodes, then one word per instance.
    assert_eq!(tlas.node_bytes().len(), tlas.wide_count * size_of::<GpuWideNode>() + 300 * 4);
}

#[test]
fn refit_follows_moved_vertices() {
    let mut rng = Rng(777);
    let before = soup(&mut rng, 2000, 0.1);
    let mut blas = Blas::build(&before, Layout::Binary);
    let after: Vec<[Vec3; 3]> = before
        .iter()
        .map(|t| {
            let shift = rng.vec(0.3);
            t.map(|v| v * 1.3 + shift + rng.vec(0.02))
        })
        .collect();
    let topology: Vec<_> = blas.nodes.iter().map(|n| n.children.map(|c| (c.index, c.meta))).collect();
    assert!(!blas.refit(&after[1..]), "a different count is refused");
    assert!(blas.refit(&after));
    assert_eq!(topology, blas.nodes.iter().map(|n| n.children.map(|c| (c.index, c.meta))).collect::<Vec<_>>());
    let placed = [Placed { triangles: &after, object_to_eye: Affine3A::IDENTITY, alpha_tested: false }];
    let built = Built::new(&placed, vec![blas]);
    let hits = check_rays(&built, &placed, &mut rng, 3000, 2.0);
    assert!(hits > 500, "only {hits} hits");
}

/// A merged BVH holds every member triangle once, each naming the member and the place there
/// of the triangle it copies (the same stored triangle), in both layouts and whatever order
/// the members store their triangles in; members whose counts do not add up are refused.
#[test]
fn merged_triangles_name_their_member_and_place() {
    let mut rng = Rng(4242);
    let members = [soup(&mut rng, 300, 0.1), sphere(6, 8), Vec::new(), soup(&mut rng, 50, 0.3)];
    for layout in [Layout::Binary, Layout::Wide] {
        // The members' own storage: built (BVH order), or in input order (the hardware tracer's).
        let stored: Vec<Blas> = members.iter().enumerate().map(|(m, t)| if m == 1 { Blas::unordered(t) } else { Blas::build(t, layout) }).collect();
        let orders: Vec<&[u32]> = stored.iter().map(|b| b.order.as_slice()).collect();
        let all: Vec<[Vec3; 3]> = members.concat();
        let merged = Blas::merged(&all, &orders, layout).expect("the counts add up");
        assert_eq!(merged.triangles.len(), all.len());
        let mut seen = std::collections::HashSet::new();
        for t in &merged.triangles {
            let copied = stored[t.member as usize].triangles[t.member_triangle as usize];
            assert_eq!((t.v0, t.e1, t.e2), (copied.v0, copied.e1, copied.e2), "{layout:?}: member {} triangle {}", t.member, t.member_triangle);
            assert!(seen.insert((t.member, t.member_triangle)), "each member triangle once");
        }
        assert_eq!(merged.bounds, stored.iter().fold(Aabb::EMPTY, |b, s| b.union(&s.bounds)));
        assert_eq!(merged.wide.is_some(), layout == Layout::Wide);
        assert!(Blas::merged(&all[1..], &orders, layout).is_none(), "a triangle short");
    }
}

/// The sphere of [`sphere`] wobbled at `time` (every vertex moved along its direction, as an
/// animated mesh deforms), placed at `centre`.
fn wobbled(ball: &[[Vec3; 3]], time: f32, centre: Vec3) -> Vec<[Vec3; 3]> {
    ball.iter().map(|t| t.map(|v| centre + v * (1.0 + 0.25 * (5.0 * v.x + 3.0 * time).sin() * (4.0 * v.y - 2.0 * time).cos()))).collect()
}

#[test]
fn a_refitted_deformed_mesh_hits_as_a_fresh_build() {
    let ball = sphere(40, 80);
    let mut refitted = Blas::build(&wobbled(&ball, 0.0, Vec3::ZERO), Layout::Binary);
    // Ten frames of animation, refitted each frame; the mesh also drifts sideways.
    let mut shape = Vec::new();
    for frame in 1..=10 {
        shape = wobbled(&ball, 0.3 * frame as f32, Vec3::new(0.05 * frame as f32, 0.0, 0.0));
        assert!(refitted.refit(&shape));
    }
    let fresh = Blas::build(&shape, Layout::Binary);
    let placed = [Placed { triangles: &shape, object_to_eye: Affine3A::from_rotation_y(0.4), alpha_tested: false }];
    let (a, b) = (Built::new(&placed, vec![refitted]), Built::new(&placed, vec![fresh]));
    let (sa, sb) = (a.scene(), b.scene());
    let mut rng = Rng(2024);
    let mut hits = 0;
    for _ in 0..5000 {
        let o = rng.vec(2.5);
        let d = (rng.vec(1.0) - o).normalize_or(Vec3::X);
        let input = |built: &Built, h: Hit| built.blas[0].order[h.triangle as usize];
        let (ha, hb) = (cpu::closest(&sa, o, d, 0.0, f32::INFINITY, even), cpu::closest(&sb, o, d, 0.0, f32::INFINITY, even));
        match (ha, hb) {
            (Some(x), Some(y)) => {
                assert_eq!(x.t, y.t, "ray {o} {d}: {x:?} vs {y:?}");
                // Another triangle at the same t is a tie on a shared edge or vertex.
                let (tx, ty) = (input(&a, x), input(&b, y));
                assert!(tx == ty || ball[tx as usize].iter().any(|v| ball[ty as usize].contains(v)), "ray {o} {d}: triangle {tx} vs {ty}");
                hits += 1;
            }
            (x, y) => assert_eq!(x.is_some(), y.is_some(), "ray {o} {d}"),
        }
        assert_eq!(cpu::any(&sa, o, d, 0.0, 3.0, even), cpu::any(&sb, o, d, 0.0, 3.0, even), "any: ray {o} {d}");
    }
    assert!(hits > 2000, "only {hits} hits");
    check_rays(&a, &placed, &mut rng, 1000, 2.5);
}

#[test]
fn deep_subtrees_are_rebalanced_within_the_depth_limit() {
    let mut rng = Rng(31337);
    let tris = soup(&mut rng, 1000, 0.05);
    let full = Blas::build(&tris, Layout::Binary);
    let limit = 10; // 1000 / 4 per leaf = 250 leaves: a median split is 8 deep
    assert!(depth(&full.nodes, 0) > limit, "PLOC's tree is already shallow; pick a lower limit");
    let shallow = Blas::build_limited(&tris, Layout::Binary, BvhBuildParams::fast_build(), limit);
    assert!(depth(&shallow.nodes, 0) <= limit);
    let placed = [Placed { triangles: &tris, object_to_eye: Affine3A::IDENTITY, alpha_tested: false }];
    let built = Built::new(&placed, vec![shallow]);
    check_rays(&built, &placed, &mut rng, 2000, 1.5);

    let boxes: Vec<Aabb> = (0..3000).map(|_| Aabb::of_points(&[rng.vec(1.0), rng.vec(1.0)])).collect();
    let tlas = Tlas::build_limited(&boxes, Layout::Binary, 12);
    assert!(depth(&tlas.nodes, 0) <= 12);
    let mut leaves: Vec<u32> = tlas.nodes.iter().flat_map(|n| n.children).filter(|c| c.is_leaf()).map(|c| c.index).collect();
    leaves.sort_unstable();
    assert_eq!(leaves, (0..3000).collect::<Vec<u32>>());
}

#[test]
fn transformed_box_is_the_box_of_transformed_corners() {
    let b = Aabb { min: Vec3::new(-1.0, 0.0, 2.0), max: Vec3::new(3.0, 1.0, 5.0) };
    let m =
        Affine3A::from_scale_rotation_translation(Vec3::new(2.0, 0.5, 1.0), Quat::from_euler(glam::EulerRot::XYZ, 0.3, -1.2, 2.0), Vec3::new(4.0, -2.0, 1.0));
    let corners: Vec<Vec3> = (0..8).map(|i| m.transform_point3(Vec3::select(glam::BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0), b.max, b.min))).collect();
    let want = Aabb::of_points(&corners);
    let got = b.transformed(&m);
    assert!(got.min.abs_diff_eq(want.min, 1e-5) && got.max.abs_diff_eq(want.max, 1e-5), "{got:?} vs {want:?}");
    assert!(Aabb::EMPTY.transformed(&m).is_empty());
}

/// Build time and SAH cost of 1M triangles per obvhs preset, and of a 10k-instance TLAS
/// (`cargo test --lib trace::bvh -- --ignored --nocapture`).
#[test]
#[ignore]
fn bvh_build_speed() {
    let mut rng = Rng(42);
    let mut tris = soup(&mut rng, 500_000, 0.01);
    tris.extend(sphere(500, 1000));
    let presets = [
        ("fast", BvhBuildParams::fast_build()),
        ("medium", BvhBuildParams::medium_build()),
        ("slow, no pre-split", BvhBuildParams { pre_split: false, ..BvhBuildParams::slow_build() }),
    ];
    for (name, params) in presets {
        for max_depth in [BVH_MAX_DEPTH, 48, 1000] {
            let start = Instant::now();
            let blas = Blas::build_limited(&tris, Layout::Binary, BvhBuildParams { max_prims_per_leaf: 8, ..params }, max_depth);
            println!(
                "{name}, depth limit {max_depth}: {} triangles in {:.0} ms, SAH {:.1}, {} nodes, depth {}",
                tris.len(),
                start.elapsed().as_secs_f64() * 1e3,
                sah_cost(&blas.nodes),
                blas.nodes.len(),
                depth(&blas.nodes, 0)
            );
        }
    }
    let boxes: Vec<Aabb> = (0..10_000)
        .map(|_| {
            let c = rng.vec(50.0);
            Aabb { min: c - rng.vec(1.0).abs(), max: c + rng.vec(1.0).abs() }
        })
        .collect();
    let start = Instant::now();
    let tlas = Tlas::build(&boxes, Layout::Binary);
    println!("TLAS: 10k instances in {:.2} ms, SAH {:.1}, depth {}", start.elapsed().as_secs_f64() * 1e3, sah_cost(&tlas.nodes), depth(&tlas.nodes, 0));
}

/// CPU time of a refit against a full build for deformed meshes of 10k and 100k triangles
/// (`cargo test --lib trace::bvh -- --ignored --nocapture refit_speed`), and the SAH cost of
/// the refitted tree against a fresh build's after 30 frames of animation.
#[test]
#[ignore]
fn refit_speed() {
    for (rings, segments) in [(50, 100), (160, 320)] {
        let ball = sphere(rings, segments);
        let frames = 30;
        let mut blas = Blas::build(&wobbled(&ball, 0.0, Vec3::ZERO), Layout::Binary);
        let (mut build_s, mut refit_s) = (0.0, 0.0);
        let mut fresh = blas.clone();
        for frame in 1..=frames {
            let shape = wobbled(&ball, 0.1 * frame as f32, Vec3::ZERO);
            let start = Instant::now();
            assert!(blas.refit(&shape));
            refit_s += start.elapsed().as_secs_f64();
            let start = Instant::now();
            fresh = Blas::build(&shape, Layout::Binary);
            build_s += start.elapsed().as_secs_f64();
        }
        println!(
            "{} triangles: build {:.2} ms, refit {:.2} ms per frame ({:.1}x); SAH after {frames} frames: refitted {:.1}, fresh build {:.1}",
            ball.len(),
            build_s * 1e3 / frames as f64,
            refit_s * 1e3 / frames as f64,
            build_s / refit_s,
            sah_cost(&blas.nodes),
            sah_cost(&fresh.nodes)
        );
    }
}

/// CPU seconds of this process so far, all threads (`utime + stime` of `/proc/self/stat`, in
/// ticks of 1/100 s): unlike wall time, not counting waits for a CPU on a loaded machine.
fn process_cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").expect("/proc/self/stat");
    // The fields after the command's closing parenthesis; utime and stime are the 14th and 15th.
    let fields: Vec<&str> = stat[stat.rfind(')').expect("(comm)") + 2..].split_whitespace().collect();
    (fields[11].parse::<u64>().expect("utime") + fields[12].parse::<u64>().expect("stime")) as f64 / 100.0
}

/// CPU time of BLAS and TLAS builds per layout: 40 meshes of 25,000 triangles (the 1M-triangle
/// world's size) and a TLAS of 500 instances, 5 times over
/// (`cargo test --lib trace::bvh -- --ignored --nocapture layout_build_cost`).
#[test]
#[ignore]
fn layout_build_cost() {
    let ball = sphere(100, 125);
    let meshes: Vec<Vec<[Vec3; 3]>> = (0..40).map(|k| ball.iter().map(|t| t.map(|v| v * (1.0 + k as f32 * 0.01) + Vec3::X * k as f32)).collect()).collect();
    let mut rng = Rng(3);
    let boxes: Vec<Aabb> = (0..500)
        .map(|_| {
            let c = rng.vec(50.0);
            Aabb { min: c - rng.vec(1.0).abs(), max: c + rng.vec(1.0).abs() }
        })
        .collect();
    for layout in [Layout::Binary, Layout::Wide, Layout::Binary, Layout::Wide] {
        let (cpu, wall) = (process_cpu_seconds(), Instant::now());
        let mut nodes = 0;
        for _ in 0..5 {
            nodes += meshes.iter().map(|m| Blas::build(m, layout).node_bytes().len()).sum::<usize>();
        }
        let blas = (process_cpu_seconds() - cpu, wall.elapsed().as_secs_f64());
        let (cpu, wall) = (process_cpu_seconds(), Instant::now());
        for _ in 0..50 {
            nodes += Tlas::build(&boxes, layout).node_bytes().len();
        }
        let tlas = (process_cpu_seconds() - cpu, wall.elapsed().as_secs_f64());
        println!(
            "{}: BLAS {:.1} ms CPU ({:.1} ms wall) per 25k triangles, TLAS of 500 {:.2} ms CPU ({:.2} wall); {} node bytes",
            layout.name(),
            blas.0 * 1e3 / 200.0,
            blas.1 * 1e3 / 200.0,
            tlas.0 * 1e3 / 50.0,
            tlas.1 * 1e3 / 50.0,
            nodes
        );
    }
}
