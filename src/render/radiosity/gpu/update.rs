//! The per-frame radiosity update: the patches' direct light ([`Direct`]: shadow rays to the
//! frame's lights, plus emission) is their primary radiosity `P`, which the product with the
//! compressed k-bounce matrix ([`Gather`]) turns into their radiosity `B = P + F^k P`.
//!
//! The two passes are two dispatches: `P` comes back to the host between them and goes into
//! the product's input (n · 16 bytes, a copy, not a recomputation). Chaining them in one
//! submission with a device buffer between is left for when the renderer records the update
//! into its frame.

use glam::Vec3;

use super::direct::{Direct, PatchLight, TraversalWork};
use super::gather::Gather;
use super::pass::DispatchTime;
use crate::render::radiosity::compress::CompressedMatrix;
use crate::render::radiosity::patches::Patches;
use crate::render::raster::device::{Device, Result};
use crate::render::trace::gpu_types::GpuLight;

/// One update's result.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Radiosity {
    /// Each patch's direct light (irradiance and primary radiosity).
    pub direct: Vec<PatchLight>,
    /// Each patch's radiosity: primary plus k bounces.
    pub radiosity: Vec<Vec3>,
}

/// How long an update's passes took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UpdateTime {
    /// The direct light.
    pub direct: DispatchTime,
    /// The product.
    pub gather: DispatchTime,
    /// The direct light's BVH traversal work.
    pub direct_work: TraversalWork,
}

/// The patches and their matrix on the device, and the two passes.
pub struct Update {
    direct: Direct,
    gather: Gather,
}

impl Update {
    /// Uploads `patches` and their compressed matrix `matrix` to `device`, the direct light
    /// traced in `slices` slices of the points ([`Direct`]).
    pub fn new(device: &Device, patches: &Patches, matrix: &CompressedMatrix, slices: u32) -> Result<Update> {
        let direct = Direct::new(device, patches, slices)?;
        match Gather::new(device, matrix) {
            Ok(gather) => Ok(Update { direct, gather }),
            Err(e) => {
                direct.destroy(device);
                Err(e)
            }
        }
    }

    /// The patches' radiosity under `lights` (in the patches' frame), and the passes' times.
    pub fn run(&mut self, device: &Device, lights: &[GpuLight]) -> Result<(Radiosity, UpdateTime)> {
        let (direct, direct_time) = self.direct.run(device, lights)?;
        let primary: Vec<Vec3> = direct.iter().map(|l| l.primary).collect();
        let (radiosity, gather_time) = self.gather.run(device, &primary)?;
        Ok((Radiosity { direct, radiosity }, UpdateTime { direct: direct_time, gather: gather_time, direct_work: self.direct.work() }))
    }

    /// Whether the last update's direct light is wholly its lights' ([`Direct::settled`]).
    pub fn settled(&self) -> bool {
        self.direct.settled()
    }

    /// Frees the device's objects.
    pub fn destroy(self, device: &Device) {
        self.direct.destroy(device);
        self.gather.destroy(device);
    }
}
