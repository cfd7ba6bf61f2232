//! Matching traced draws with the instances of the previous frame, so that each keeps a
//! stable id. Two passes over the frame's traced draws, in program order:
//!
//! 1. exact: same geometry key, texture names and state key; among several previous
//!    instances with that key (the same mesh drawn at several places), the nearest;
//! 2. slot, for draws not matched exactly (their vertices changed): same texture names, state
//!    key, vertex and index counts; among several, the nearest, then the one at the same
//!    place in the order of appearance of that slot.
//!
//! "Nearest" compares the eye-space position of the first vertex, which moves little from one
//! frame to the next. Instances not drawn are remembered for [`KEEP_FRAMES`] frames (not across
//! a camera cut), so that an object culled for a while keeps its id when it comes back. A previous instance is matched at most once, and new instances take ids
//! never used before, so ids are unique within a frame. The maps are kept between frames and
//! only cleared, so a frame allocates nothing once they have grown.

use std::collections::HashMap;

use glam::{Mat4, Vec3};

use crate::frame::class::{DrawClass, Match};

/// What matching needs of a traced draw.
#[derive(Clone, Copy, Debug, Default)]
pub struct Probe {
    /// Geometry, texture and state keys combined.
    pub exact: u64,
    /// Texture and state keys, vertex and index counts combined.
    pub slot: u64,
    /// Eye-space position of the first vertex.
    pub anchor: Vec3,
}

/// A traced instance as the next frame will match it.
#[derive(Clone, Copy, Debug)]
pub struct Record {
    /// Its id.
    pub id: u64,
    /// Its probe.
    pub probe: Probe,
    /// Its place in the order of appearance of its slot.
    pub ordinal: u32,
    /// Its modelview.
    pub modelview: Mat4,
    /// Object to world, when the view was known.
    pub model: Option<Mat4>,
    /// Its class.
    pub class: DrawClass,
    /// Frames since it was last drawn (0: drawn in the previous frame).
    pub age: u32,
}

/// Frames an instance that is no longer drawn is remembered.
pub const KEEP_FRAMES: u32 = 120;

/// The outcome for one draw.
#[derive(Clone, Copy, Debug)]
pub struct Found {
    /// The id.
    pub id: u64,
    /// How it was matched.
    pub matched: Match,
    /// Its place in the order of appearance of its slot in this frame.
    pub ordinal: u32,
    /// The previous frame's instance it matched, if any.
    pub previous: Option<Record>,
}

/// Instances across frames.
#[derive(Default)]
pub struct Matcher {
    previous: Vec<Record>,
    taken: Vec<bool>,
    by_exact: HashMap<u64, Vec<u32>>,
    by_slot: HashMap<u64, Vec<u32>>,
    ordinals: HashMap<u64, u32>,
    last_id: u64,
    lost: usize,
}

impl Matcher {
    /// Matches the probes of one frame, in program order, into `found` (one per probe).
    pub fn match_frame(&mut self, probes: &[Probe], found: &mut Vec<Found>) {
        self.taken.clear();
        self.taken.resize(self.previous.len(), false);
        self.ordinals.clear();
        found.clear();
        for p in probes {
            let ordinal = self.ordinals.entry(p.slot).or_insert(0);
            found.push(Found { id: 0, matched: Match::New, ordinal: *ordinal, previous: None });
            *ordinal += 1;
        }
        for (p, f) in probes.iter().zip(found.iter_mut()) {
            if let Some(i) = self.nearest(&self.by_exact, p.exact, p.anchor, None) {
                self.take(i, f, Match::Exact);
            }
        }
        for (p, f) in probes.iter().zip(found.iter_mut()) {
            if f.previous.is_none()
                && let Some(i) = self.nearest(&self.by_slot, p.slot, p.anchor, Some(f.ordinal))
            {
                self.take(i, f, Match::Slot);
            }
        }
        for f in found.iter_mut().filter(|f| f.previous.is_none()) {
            self.last_id += 1;
            f.id = self.last_id;
        }
        self.lost = self.taken.iter().zip(&self.previous).filter(|(t, r)| !**t && r.age == 0).count();
    }

    /// An id no instance has had, for a draw that is not matched (routed before its frame
    /// ends).
    pub fn new_id(&mut self) -> u64 {
        self.last_id += 1;
        self.last_id
    }

    fn take(&mut self, i: usize, f: &mut Found, matched: Match) {
        self.taken[i] = true;
        let previous = self.previous[i];
        (f.id, f.matched, f.previous) = (previous.id, matched, Some(previous));
    }

    /// The untaken previous instance under `key` in `map` nearest to `anchor` (then the one
    /// of the same `ordinal`).
    fn nearest(&self, map: &HashMap<u64, Vec<u32>>, key: u64, anchor: Vec3, ordinal: Option<u32>) -> Option<usize> {
        let candidates = map.get(&key)?.iter().map(|&i| i as usize).filter(|&i| !self.taken[i]);
        candidates.min_by(|&a, &b| {
            let score = |i: usize| {
                let r = &self.previous[i];
                (r.probe.anchor.distance_squared(anchor), ordinal.is_some_and(|o| o != r.ordinal))
            };
            let (sa, sb) = (score(a), score(b));
            sa.0.total_cmp(&sb.0).then(sa.1.cmp(&sb.1))
        })
    }

    /// Instances of the previous frame that no draw of the last frame matched.
    pub fn lost(&self) -> usize {
        self.lost
    }

    /// Ends the frame: `records` (this frame's traced instances, age 0) and the instances not
    /// drawn for fewer than [`KEEP_FRAMES`] frames (none after a camera `cut`) are what the
    /// next frame matches.
    pub fn finish(&mut self, records: impl Iterator<Item = Record>, cut: bool) {
        let kept = std::mem::take(&mut self.previous).into_iter().zip(std::mem::take(&mut self.taken));
        let kept: Vec<Record> = kept
            .filter(|(r, taken)| !taken && !cut && r.age + 1 < KEEP_FRAMES)
            .map(|(r, _)| Record { age: r.age + 1, ..r })
            .collect();
        self.previous.extend(records);
        self.previous.extend(kept);
        self.by_exact.values_mut().for_each(Vec::clear);
        self.by_slot.values_mut().for_each(Vec::clear);
        if self.by_exact.len() > 4 * self.previous.len() + 1024 {
            self.by_exact.retain(|_, v| !v.is_empty());
            self.by_slot.retain(|_, v| !v.is_empty());
        }
        for (i, r) in self.previous.iter().enumerate() {
            self.by_exact.entry(r.probe.exact).or_default().push(i as u32);
            self.by_slot.entry(r.probe.slot).or_default().push(i as u32);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn probe(exact: u64, slot: u64, x: f32) -> Probe {
        Probe { exact, slot, anchor: Vec3::new(x, 0.0, 0.0) }
    }

    fn run(m: &mut Matcher, probes: &[Probe]) -> Vec<Found> {
        let mut found = Vec::new();
        m.match_frame(probes, &mut found);
        let records = probes.iter().zip(&found).map(|(p, f)| Record {
            id: f.id,
            probe: *p,
            ordinal: f.ordinal,
            modelview: Mat4::IDENTITY,
            model: None,
            class: DrawClass::Static,
            age: 0,
        });
        m.finish(records.collect::<Vec<_>>().into_iter(), false);
        found
    }

    #[test]
    fn exact_then_slot_then_new() {
        let mut m = Matcher::default();
        let first = run(&mut m, &[probe(1, 10, 0.0), probe(2, 20, 5.0)]);
        assert_eq!((first[0].id, first[1].id), (1, 2));
        assert!(first.iter().all(|f| f.matched == Match::New));
        // Draw 2's vertices changed (new exact key, same slot); a third draw appears.
        let second = run(&mut m, &[probe(3, 20, 5.1), probe(1, 10, 0.0), probe(4, 40, 0.0)]);
        assert_eq!((second[0].id, second[0].matched), (2, Match::Slot));
        assert_eq!((second[1].id, second[1].matched), (1, Match::Exact));
        assert_eq!((second[2].id, second[2].matched), (3, Match::New));
        assert_eq!(m.lost(), 0);
        let third = run(&mut m, &[probe(1, 10, 0.0)]);
        assert_eq!(third[0].id, 1);
        assert_eq!(m.lost(), 2);
    }

    #[test]
    fn duplicates_match_the_nearest_and_ids_stay_unique() {
        let mut m = Matcher::default();
        let a = run(&mut m, &[probe(7, 1, 0.0), probe(7, 1, 10.0), probe(7, 1, 20.0)]);
        // Drawn in another order, slightly moved: each keeps its id by position.
        let b = run(&mut m, &[probe(7, 1, 20.2), probe(7, 1, 0.1), probe(7, 1, 9.9)]);
        assert_eq!(b.iter().map(|f| f.id).collect::<Vec<_>>(), vec![a[2].id, a[0].id, a[1].id]);
        // Four copies now: one new id, never one of the others.
        let c = run(&mut m, &[probe(7, 1, 0.0), probe(7, 1, 10.0), probe(7, 1, 20.0), probe(7, 1, 30.0)]);
        let mut ids: Vec<u64> = c.iter().map(|f| f.id).collect();
        ids.sort();
        ids.dedup();
        assert_eq!(ids.len(), 4);
        assert_eq!(c[3].id, 4);
    }

    #[test]
    fn slot_prefers_the_nearest_then_the_same_order() {
        let mut m = Matcher::default();
        let a = run(&mut m, &[probe(1, 5, 0.0), probe(2, 5, 0.0)]);
        let b = run(&mut m, &[probe(3, 5, 0.0), probe(4, 5, 0.0)]);
        assert_eq!((b[0].id, b[1].id), (a[0].id, a[1].id), "same distance: order of appearance");
        let mut m = Matcher::default();
        let a = run(&mut m, &[probe(1, 5, 0.0), probe(2, 5, 8.0)]);
        let c = run(&mut m, &[probe(5, 5, 8.1), probe(6, 5, 0.1)]);
        assert_eq!((c[0].id, c[1].id), (a[1].id, a[0].id), "the nearest wins over the order");
    }

    #[test]
    fn instances_not_drawn_for_a_while_keep_their_ids() {
        let mut m = Matcher::default();
        let a = run(&mut m, &[probe(1, 10, 0.0), probe(2, 20, 5.0)]);
        for _ in 0..KEEP_FRAMES - 2 {
            run(&mut m, &[probe(1, 10, 0.0)]);
        }
        assert_eq!(m.lost(), 0, "only instances of the previous frame count as lost");
        let back = run(&mut m, &[probe(1, 10, 0.0), probe(2, 20, 5.0)]);
        assert_eq!((back[1].id, back[1].matched, back[1].previous.unwrap().age), (a[1].id, Match::Exact, KEEP_FRAMES - 2));
        for _ in 0..KEEP_FRAMES {
            run(&mut m, &[probe(1, 10, 0.0)]);
        }
        assert_eq!(run(&mut m, &[probe(2, 20, 5.0)])[0].matched, Match::New, "forgotten after KEEP_FRAMES");
        // A camera cut forgets what is not drawn.
        let mut m = Matcher::default();
        run(&mut m, &[probe(1, 10, 0.0), probe(2, 20, 5.0)]);
        let mut found = Vec::new();
        m.match_frame(&[probe(1, 10, 0.0)], &mut found);
        let record = Record { id: found[0].id, probe: probe(1, 10, 0.0), ordinal: 0, modelview: Mat4::IDENTITY, model: None, class: DrawClass::Static, age: 0 };
        m.finish(std::iter::once(record), true);
        assert_eq!(run(&mut m, &[probe(2, 20, 5.0)])[0].matched, Match::New);
    }
}
