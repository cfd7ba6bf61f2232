//! Fault injection, for tests: makes glrt meet, at a chosen moment, the failures DESIGN.md says
//! it must survive ("a missing Vulkan device or a lost device is reported once and degrades"),
//! so the degrade paths run on any machine (lavapipe in CI). Nothing reads this module but the
//! few places where each fault can happen, once per occurrence of a rare event (a GPU
//! allocation, a frame's submission, a swapchain acquisition, a pipeline creation, a capture
//! write); draws never pass through it.
//!
//! `GLRT_FAULTS` lists the faults, separated by commas, each `KIND@N`:
//!
//! | kind | what fails |
//! | --- | --- |
//! | `device-lost@N` | the N-th frame submission (`vkQueueSubmit` of a frame or a read-back) reports `VK_ERROR_DEVICE_LOST` |
//! | `alloc@N` | the N-th GPU memory allocation reports `VK_ERROR_OUT_OF_DEVICE_MEMORY` |
//! | `out-of-date@N` | the N-th swapchain image acquisition reports `VK_ERROR_OUT_OF_DATE_KHR` |
//! | `shader@N` | the N-th pipeline creation (raster or tracer) reports `VK_ERROR_INVALID_SHADER_NV` (a shader the driver cannot compile) |
//! | `disk-full@N` | the disk holding a capture file (`GLRT_CAPTURE`) is full after N bytes of it: writing further reports `ENOSPC` |
//!
//! Occurrences count from 1, per process, in the order they happen; each fault fires once.
//! Tests running glrt in their own process can also [`arm`] a fault relative to what already
//! happened ("the next allocation fails"). A value that does not parse is reported once and
//! ignored.

use std::sync::Once;
use std::sync::atomic::{AtomicU64, Ordering};

/// A failure glrt can be made to meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fault {
    /// The device is lost while a frame is submitted.
    DeviceLost,
    /// A GPU memory allocation fails.
    Allocation,
    /// The window's swapchain is out of date when an image is acquired.
    OutOfDate,
    /// A pipeline's shaders do not compile.
    ShaderCompile,
}

/// The counted faults, in the order of [`Fault::index`], with their names in `GLRT_FAULTS`.
const NAMES: [(&str, Fault); 4] =
    [("device-lost", Fault::DeviceLost), ("alloc", Fault::Allocation), ("out-of-date", Fault::OutOfDate), ("shader", Fault::ShaderCompile)];

/// The name of the byte limit of capture files in `GLRT_FAULTS`.
const DISK_FULL: &str = "disk-full";

impl Fault {
    fn index(self) -> usize {
        self as usize
    }
}

/// Per fault, occurrences so far.
static SEEN: [AtomicU64; 4] = [const { AtomicU64::new(0) }; 4];
/// Per fault, the occurrence that fails (0: none).
static ARMED: [AtomicU64; 4] = [const { AtomicU64::new(0) }; 4];
/// Bytes a capture file may hold plus one (0: no limit).
static DISK_ROOM: AtomicU64 = AtomicU64::new(0);

/// Reads `GLRT_FAULTS` once.
fn read_env() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let Ok(value) = std::env::var("GLRT_FAULTS") else { return };
        match parse(&value) {
            Ok(plan) => {
                for (fault, n) in plan.counted {
                    ARMED[fault.index()].store(n, Ordering::Relaxed);
                }
                if let Some(bytes) = plan.disk_room {
                    DISK_ROOM.store(bytes.saturating_add(1), Ordering::Relaxed);
                }
            }
            Err(e) => eprintln!("glrt: GLRT_FAULTS={value:?}: {e}; no fault is injected"),
        }
    });
}

/// What `GLRT_FAULTS` asks for.
#[derive(Debug, Default, PartialEq)]
struct Plan {
    /// Counted faults and the occurrence that fails.
    counted: Vec<(Fault, u64)>,
    /// Bytes a capture file may hold.
    disk_room: Option<u64>,
}

/// Parses a `GLRT_FAULTS` value (see the module doc).
fn parse(value: &str) -> Result<Plan, String> {
    let mut plan = Plan::default();
    for item in value.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let (kind, n) = item.split_once('@').ok_or_else(|| format!("'{item}' is not KIND@N"))?;
        let n: u64 = n.trim().parse().map_err(|_| format!("'{item}': N is not a number"))?;
        let kind = kind.trim();
        if kind == DISK_FULL {
            plan.disk_room = Some(n);
            continue;
        }
        let fault = NAMES.iter().find(|(name, _)| *name == kind).map(|&(_, f)| f).ok_or_else(|| {
            let kinds: Vec<_> = NAMES.iter().map(|(name, _)| *name).chain([DISK_FULL]).collect();
            format!("unknown fault '{kind}' (one of {})", kinds.join(", "))
        })?;
        if n == 0 {
            return Err(format!("'{item}': occurrences count from 1"));
        }
        plan.counted.push((fault, n));
    }
    Ok(plan)
}

/// Counts one occurrence of the event where `fault` can happen; `true` when this occurrence
/// must fail.
pub fn fires(fault: Fault) -> bool {
    read_env();
    let n = SEEN[fault.index()].fetch_add(1, Ordering::Relaxed) + 1;
    n == ARMED[fault.index()].load(Ordering::Relaxed)
}

/// Makes the `next`-th occurrence of `fault` from now fail (1: the next one), replacing what
/// `GLRT_FAULTS` set for it. For tests that run glrt in a process of their own.
pub fn arm(fault: Fault, next: u64) {
    read_env();
    let seen = SEEN[fault.index()].load(Ordering::Relaxed);
    ARMED[fault.index()].store(seen + next.max(1), Ordering::Relaxed);
}

/// How many bytes a capture file may hold (`disk-full@N`), if limited.
pub fn disk_room() -> Option<u64> {
    read_env();
    DISK_ROOM.load(Ordering::Relaxed).checked_sub(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faults_parse_with_their_occurrence() {
        let plan = parse("device-lost@3, alloc@10,disk-full@4096").unwrap();
        assert_eq!(plan.counted, [(Fault::DeviceLost, 3), (Fault::Allocation, 10)]);
        assert_eq!(plan.disk_room, Some(4096));
        assert_eq!(parse("").unwrap(), Plan::default());
        assert_eq!(parse("shader@1,out-of-date@2").unwrap().counted, [(Fault::ShaderCompile, 1), (Fault::OutOfDate, 2)]);
    }

    #[test]
    fn bad_values_say_what_is_wrong() {
        assert!(parse("lost@3").unwrap_err().contains("unknown fault 'lost'"));
        assert!(parse("alloc").unwrap_err().contains("KIND@N"));
        assert!(parse("alloc@x").unwrap_err().contains("not a number"));
        assert!(parse("alloc@0").unwrap_err().contains("from 1"));
    }

    #[test]
    fn an_armed_fault_fires_once_at_its_occurrence() {
        // No other unit test acquires swapchain images, so the count is this test's.
        arm(Fault::OutOfDate, 2);
        assert!(!fires(Fault::OutOfDate));
        assert!(fires(Fault::OutOfDate));
        assert!(!fires(Fault::OutOfDate));
    }
}
