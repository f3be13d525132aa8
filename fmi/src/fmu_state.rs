//! FMU states, the same in FMI 2.0 and 3.0: an instance's state kept as a
//! handle (`GetFMUState`), restored (`SetFMUState`), freed, and written
//! to and read from bytes (the snapshot's numbers, little-endian). The
//! version layers call these inside their checked calls.

use crate::boundary::{self, slice, slice_mut, target, Entry};
use crate::instance::{refuse, Instance, Outcome};
use daegen_runtime::Model;
use std::ffi::c_void;

/// Keeps the instance's state in `*state`: a new handle if it is null,
/// else the state it names replaced.
///
/// # Safety
/// `state` must be null or point to a state handle.
pub unsafe fn get<M: Model + Clone + Default + Send + Sync + 'static>(
    e: &mut Entry<M>,
    state: *mut *mut c_void,
) -> Outcome {
    // SAFETY: the importer's pointer, checked for null.
    let state = unsafe { target(state, "FMUState") }?;
    let snapshot = e.instance.snapshot();
    if state.is_null() || !boundary::replace_state(*state, snapshot.clone()) {
        *state = boundary::keep_state(snapshot);
    }
    Ok(())
}

/// Restores the state `state` names.
pub fn set<M: Model + Clone + Default + Send + Sync + 'static>(
    e: &mut Entry<M>,
    state: *mut c_void,
) -> Outcome {
    let snapshot = boundary::state(state)?;
    e.instance.restore(&snapshot)
}

/// Frees the state `*state` names (nothing for null) and nulls it.
///
/// # Safety
/// `state` must be null or point to a state handle.
pub unsafe fn free(state: *mut *mut c_void) -> Outcome {
    // SAFETY: the importer's pointer, checked for null.
    let state = unsafe { target(state, "FMUState") }?;
    if state.is_null() {
        return Ok(());
    }
    if !boundary::free_state(*state) {
        return Err(refuse(format!("{:p} is not a live FMU state", *state)));
    }
    *state = std::ptr::null_mut();
    Ok(())
}

/// Writes the size of the serialized `state` to `*size`.
///
/// # Safety
/// `size` must be null or point to a `size_t`.
pub unsafe fn size(state: *mut c_void, size: *mut usize) -> Outcome {
    // SAFETY: the importer's pointer, checked for null.
    let size = unsafe { target(size, "size") }?;
    *size = boundary::state(state)?.len() * 8;
    Ok(())
}

/// Writes `state` into the `size` bytes at `bytes`.
///
/// # Safety
/// `bytes` must be null or point to `size` bytes.
pub unsafe fn serialize(state: *mut c_void, bytes: *mut u8, size: usize) -> Outcome {
    let snapshot = boundary::state(state)?;
    if size != snapshot.len() * 8 {
        return Err(refuse(format!(
            "the buffer has {size} bytes; the state needs {} (SerializedFMUStateSize)",
            snapshot.len() * 8
        )));
    }
    // SAFETY: size bytes, as FMI requires.
    let out = unsafe { slice_mut(bytes, size, "serializedState") }?;
    for (chunk, v) in out.chunks_exact_mut(8).zip(&snapshot) {
        chunk.copy_from_slice(&v.to_le_bytes());
    }
    Ok(())
}

/// Reads a state of this model from the `size` bytes at `bytes` into a
/// new handle in `*state`.
///
/// # Safety
/// `bytes` must be null or point to `size` bytes; `state` null or to a
/// state handle.
pub unsafe fn deserialize<M: Model + Clone + Default + Send + Sync + 'static>(
    e: &mut Entry<M>,
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> Outcome {
    // SAFETY: size bytes and the importer's pointer, as FMI requires.
    let (bytes, state) =
        unsafe { (slice(bytes, size, "serializedState")?, target(state, "FMUState")?) };
    let snapshot = boundary::numbers(bytes)?;
    // Only a state of this model is kept.
    let mut probe = Instance::<M>::new(e.instance.interface).map_err(refuse)?;
    probe.restore(&snapshot)?;
    *state = boundary::keep_state(snapshot);
    Ok(())
}
