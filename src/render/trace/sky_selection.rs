//! How often a path vertex samples the sky (next-event estimation towards the sky,
//! `shaders/trace/sky_sampling.glsl`). A sky sample is a shadow ray to infinity; in a closed
//! room nearly every one is occluded and each costs about as much as the rest of the path (the
//! demo at 1280x720 on one NVIDIA H200: tracing pass 22.4 ms with a sky sample at every vertex,
//! 13.2 ms without), while under an open sky most find it and cut the noise of the sky's light.
//!
//! So each frame a vertex takes its sky sample with a probability that follows the fraction
//! of last frame's sky rays that found the sky: [`SkySelection::observe`] reads the counters
//! of a traced frame, [`SkySelection::probability`] is what the next frame uses. The sample's
//! density is that probability times the direction's, in its estimate and in the MIS weight
//! of continuation rays that miss, so every probability above 0 gives the same mean; it is
//! never below [`LOWEST`], so the fraction stays measured. The probability is a power of two
//! and moves one step a frame, outside a band around it: the temporal gradients of A-SVGF
//! replay last frame's random numbers and must make the same choices where nothing changed.

/// The fraction of sky rays finding the sky at and above which every vertex samples the sky.
pub const ALWAYS_AT: f32 = 0.5;
/// The lowest probability (a power of two).
pub const LOWEST: f32 = 1.0 / 16.0;

/// The probability that a path vertex samples the sky, kept from frame to frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkySelection {
    probability: f32,
}

impl Default for SkySelection {
    fn default() -> SkySelection {
        SkySelection { probability: 1.0 }
    }
}

impl SkySelection {
    /// The probability for the next frame traced.
    pub fn probability(&self) -> f32 {
        self.probability
    }

    /// Takes a traced frame's sky rays: `traced` shadow rays towards the sky, `unoccluded` of
    /// them found it. A frame without sky rays leaves the probability as it is.
    pub fn observe(&mut self, traced: u64, unoccluded: u64) {
        if traced == 0 {
            return;
        }
        let target = (unoccluded as f32 / traced as f32 / ALWAYS_AT).min(1.0);
        if target > self.probability * 1.5 {
            self.probability = (self.probability * 2.0).min(1.0);
        } else if target < self.probability / 3.0 {
            self.probability = (self.probability / 2.0).max(LOWEST);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The probability after `frames` frames with the fraction `open` of sky rays unoccluded.
    fn settle(mut s: SkySelection, open: f32, frames: usize) -> SkySelection {
        for _ in 0..frames {
            s.observe(1_000_000, (open * 1e6) as u64);
        }
        s
    }

    #[test]
    fn an_open_sky_is_sampled_at_every_vertex() {
        assert_eq!(settle(SkySelection::default(), 0.6, 10).probability(), 1.0);
        assert_eq!(settle(SkySelection::default(), ALWAYS_AT, 10).probability(), 1.0);
        assert_eq!(settle(SkySelection::default(), 0.4, 10).probability(), 1.0, "within the band of 1");
    }

    #[test]
    fn a_closed_room_falls_to_the_lowest_probability_one_halving_a_frame() {
        let mut s = SkySelection::default();
        let mut seen = Vec::new();
        for _ in 0..6 {
            s.observe(1_000_000, 0);
            seen.push(s.probability());
        }
        assert_eq!(seen, [0.5, 0.25, 0.125, 0.0625, 0.0625, 0.0625]);
    }

    #[test]
    fn a_window_settles_in_between_and_stays() {
        // 6 % of the sky rays find the sky: the target is 0.12. The probability halves while
        // the target is below a third of it: 1, 1/2, then 1/4 stays (0.12 is not below 1/12).
        let s = settle(SkySelection::default(), 0.06, 10);
        assert_eq!(s.probability(), 0.25);
        // Fractions that move within the band do not move the probability.
        for open in [0.045, 0.06, 0.09] {
            assert_eq!(settle(s, open, 10).probability(), 0.25, "open {open}");
        }
    }

    #[test]
    fn opening_up_raises_it_again() {
        let s = settle(SkySelection::default(), 0.0, 10);
        assert_eq!(s.probability(), LOWEST);
        assert_eq!(settle(s, 0.5, 4).probability(), 1.0);
    }

    #[test]
    fn frames_without_sky_rays_keep_it() {
        let mut s = settle(SkySelection::default(), 0.0, 10);
        s.observe(0, 0);
        assert_eq!(s.probability(), LOWEST);
    }
}
