//! What keeps the C boundary safe whatever the importer does: instances
//! and FMU states are handed out as handles (numbers, never reused) that
//! every call looks up before it touches anything (in this thread's last
//! instance, checked alive, then the registry), so a null, stale, freed
//! or foreign pointer is refused, not dereferenced; each instance
//! has its own lock, so instances run on different threads at once and
//! two threads calling one instance at the same time get an error, not a
//! race; every call runs under `catch_unwind`, so a panic becomes a
//! `Fatal` status and a log message, never an unwind across the boundary;
//! and the pointers a call is given are checked for null before they are
//! read.

use crate::instance::{refuse, Instance, Outcome, Status};
use daegen_runtime::Model;
use std::any::Any;
use std::cell::RefCell;
use std::collections::HashMap;
use std::ffi::{c_char, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, TryLockError};

/// Where an instance's messages go: the importer's callback, wrapped by
/// the version layer.
pub type Logger = Box<dyn Fn(Status, &str, &str) + Send + Sync>;

/// An instance as the boundary keeps it.
pub struct Entry<M: Model> {
    /// The instance.
    pub instance: Instance<M>,
    /// The name the importer gave it.
    pub name: String,
    /// Whether debug messages are logged (errors always are).
    pub debug: bool,
    /// C strings handed out by `GetString`, alive until the next call.
    pub strings: Vec<CString>,
}

struct Shared<M: Model> {
    log: Logger,
    entry: Mutex<Entry<M>>,
}

type Registry<T> = Mutex<HashMap<usize, T>>;

/// A registered instance, of whatever model, and whether it is still
/// registered.
#[derive(Clone)]
struct Slot {
    alive: Arc<AtomicBool>,
    instance: Arc<dyn Any + Send + Sync>,
}

static NEXT_HANDLE: AtomicUsize = AtomicUsize::new(1);

thread_local! {
    /// The instance this thread called last, by handle: a run of calls on
    /// one instance (an importer's integrator) finds it here without the
    /// registry's lock, checking only that it is still alive.
    static LAST: RefCell<Option<(usize, Slot)>> = const { RefCell::new(None) };
}

fn instances() -> &'static Registry<Slot> {
    static INSTANCES: std::sync::OnceLock<Registry<Slot>> = std::sync::OnceLock::new();
    INSTANCES.get_or_init(Default::default)
}

fn fmu_states() -> &'static Registry<Vec<f64>> {
    static STATES: std::sync::OnceLock<Registry<Vec<f64>>> = std::sync::OnceLock::new();
    STATES.get_or_init(Default::default)
}

fn lock<T>(registry: &'static Registry<T>) -> MutexGuard<'static, HashMap<usize, T>> {
    // The registries hold no invariant a panic could break half-way.
    registry.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

fn new_handle() -> usize {
    NEXT_HANDLE.fetch_add(1, Ordering::Relaxed)
}

/// Registers a new instance; its handle, which the importer holds as the
/// instance pointer.
pub fn register<M: Model + Send + Sync + 'static>(entry: Entry<M>, log: Logger) -> *mut c_void {
    let handle = new_handle();
    let instance: Arc<dyn Any + Send + Sync> = Arc::new(Shared { log, entry: Mutex::new(entry) });
    let slot = Slot { alive: Arc::new(AtomicBool::new(true)), instance };
    lock(instances()).insert(handle, slot);
    handle as *mut c_void
}

/// Frees the instance behind `handle`; false if there is none.
pub fn release(handle: *mut c_void) -> bool {
    let Some(slot) = lock(instances()).remove(&(handle as usize)) else {
        return false;
    };
    slot.alive.store(false, Ordering::Release);
    // This thread's reference goes now; another thread's when it calls
    // another instance.
    LAST.with(|last| {
        if let Ok(mut last) = last.try_borrow_mut() {
            if last.as_ref().is_some_and(|(h, _)| *h == handle as usize) {
                *last = None;
            }
        }
    });
    true
}

/// The registered instance behind `handle` from the registry, which
/// this thread's cache then holds.
fn registered(handle: *mut c_void) -> Option<Slot> {
    let slot = lock(instances()).get(&(handle as usize))?.clone();
    LAST.with(|last| {
        if let Ok(mut last) = last.try_borrow_mut() {
            *last = Some((handle as usize, slot.clone()));
        }
    });
    Some(slot)
}

/// Runs `body` on the instance behind `handle` for the call named `call`:
/// the status it returns, its refusals logged through the importer's
/// callback, a panic turned into `Fatal`.
pub fn with<M, F>(handle: *mut c_void, call: &str, body: F) -> Status
where
    M: Model + Send + Sync + 'static,
    F: FnOnce(&mut Entry<M>) -> Outcome,
{
    let mut body = Some(body);
    // This thread's last instance, borrowed in place: no registry lock,
    // no reference count touched.
    let cached = LAST.with(|last| {
        let last = last.try_borrow().ok()?;
        let (h, slot) = last.as_ref()?;
        if *h != handle as usize || !slot.alive.load(Ordering::Acquire) {
            return None;
        }
        let shared = slot.instance.downcast_ref::<Shared<M>>()?;
        Some(call_on(shared, call, body.take()?))
    });
    if let Some(status) = cached {
        return status;
    }
    let slot = registered(handle);
    let (Some(shared), Some(body)) =
        (slot.as_ref().and_then(|s| s.instance.downcast_ref::<Shared<M>>()), body.take())
    else {
        // No callback to log through: the pointer is not an instance.
        eprintln!(
            "{call}: {handle:p} is not a live instance of this FMU (null, freed, or another FMU's)"
        );
        return Status::Error;
    };
    call_on(shared, call, body)
}

/// Runs `body` on `shared`'s entry under its lock and `catch_unwind`.
fn call_on<M, F>(shared: &Shared<M>, call: &str, body: F) -> Status
where
    M: Model + Send + Sync + 'static,
    F: FnOnce(&mut Entry<M>) -> Outcome,
{
    let mut entry = match shared.entry.try_lock() {
        Ok(entry) => entry,
        Err(TryLockError::WouldBlock) => {
            (shared.log)(
                Status::Error,
                "logStatusError",
                &format!("{call}: another call on this instance is running (an instance is used by one thread at a time)"),
            );
            return Status::Error;
        }
        Err(TryLockError::Poisoned(_)) => {
            (shared.log)(
                Status::Fatal,
                "logStatusFatal",
                &format!("{call}: an earlier call failed inside the FMU; free the instance"),
            );
            return Status::Fatal;
        }
    };
    match catch_unwind(AssertUnwindSafe(|| body(&mut entry))) {
        Ok(Ok(())) => Status::Ok,
        Ok(Err(refusal)) => {
            let category = match refusal.status {
                Status::Ok => "logStatusOK",
                Status::Warning => "logStatusWarning",
                Status::Discard => "logStatusDiscard",
                Status::Error => "logStatusError",
                Status::Fatal => "logStatusFatal",
            };
            (shared.log)(refusal.status, category, &format!("{call}: {}", refusal.message));
            refusal.status
        }
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            drop(entry);
            // Poison the instance: it cannot be trusted after this.
            let _ = catch_unwind(AssertUnwindSafe(|| {
                let _guard = shared.entry.lock();
                panic!("poison");
            }));
            (shared.log)(
                Status::Fatal,
                "logStatusFatal",
                &format!("{call}: internal error in the FMU ({what}); free the instance"),
            );
            Status::Fatal
        }
    }
}

/// Keeps a snapshot as an FMU state; its handle.
pub fn keep_state(snapshot: Vec<f64>) -> *mut c_void {
    let handle = new_handle();
    lock(fmu_states()).insert(handle, snapshot);
    handle as *mut c_void
}

/// Replaces the FMU state behind `handle`; false if there is none.
pub fn replace_state(handle: *mut c_void, snapshot: Vec<f64>) -> bool {
    match lock(fmu_states()).get_mut(&(handle as usize)) {
        Some(kept) => {
            *kept = snapshot;
            true
        }
        None => false,
    }
}

/// The FMU state behind `handle`.
pub fn state(handle: *mut c_void) -> Outcome<Vec<f64>> {
    lock(fmu_states())
        .get(&(handle as usize))
        .cloned()
        .ok_or_else(|| refuse(format!("{handle:p} is not a live FMU state of this FMU")))
}

/// Frees the FMU state behind `handle`; false if there is none.
pub fn free_state(handle: *mut c_void) -> bool {
    lock(fmu_states()).remove(&(handle as usize)).is_some()
}

/// The `n` values at `ptr` (nothing for `n = 0`), or a refusal naming
/// `what` if `ptr` is null.
///
/// # Safety
/// A non-null `ptr` must point to `n` readable values, as FMI requires.
pub unsafe fn slice<'a, T>(ptr: *const T, n: usize, what: &str) -> Outcome<&'a [T]> {
    if n == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(refuse(format!("`{what}` is a null pointer for {n} values")));
    }
    // SAFETY: non-null, and the importer passes n values, as FMI requires.
    Ok(unsafe { std::slice::from_raw_parts(ptr, n) })
}

/// The `n` writable values at `ptr`, as [`slice()`].
///
/// # Safety
/// A non-null `ptr` must point to `n` writable values, as FMI requires.
pub unsafe fn slice_mut<'a, T>(ptr: *mut T, n: usize, what: &str) -> Outcome<&'a mut [T]> {
    if n == 0 {
        return Ok(&mut []);
    }
    if ptr.is_null() {
        return Err(refuse(format!("`{what}` is a null pointer for {n} values")));
    }
    // SAFETY: non-null, and the importer passes n values, as FMI requires.
    Ok(unsafe { std::slice::from_raw_parts_mut(ptr, n) })
}

/// The value `ptr` points to, to be written.
///
/// # Safety
/// A non-null `ptr` must point to a writable value.
pub unsafe fn target<'a, T>(ptr: *mut T, what: &str) -> Outcome<&'a mut T> {
    // SAFETY: the importer's pointer, checked for null.
    unsafe { ptr.as_mut() }.ok_or_else(|| refuse(format!("`{what}` is a null pointer")))
}

/// The UTF-8 text of a C string, or a refusal if it is null or not UTF-8.
///
/// # Safety
/// A non-null `ptr` must point to a NUL-terminated string.
pub unsafe fn text<'a>(ptr: *const c_char, what: &str) -> Outcome<&'a str> {
    if ptr.is_null() {
        return Err(refuse(format!("`{what}` is a null pointer")));
    }
    // SAFETY: non-null, NUL-terminated as FMI requires.
    unsafe { CStr::from_ptr(ptr) }.to_str().map_err(|_| refuse(format!("`{what}` is not UTF-8")))
}

/// The numbers of a serialized FMU state (little-endian `f64`s).
pub fn numbers(bytes: &[u8]) -> Outcome<Vec<f64>> {
    if bytes.len() % 8 != 0 {
        return Err(refuse(format!("{} bytes are not a serialized FMU state", bytes.len())));
    }
    Ok(bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect())
}

/// Runs `body` for a call with no instance (instantiation), a panic
/// becoming `None`.
pub fn guarded<T>(body: impl FnOnce() -> Option<T>) -> Option<T> {
    catch_unwind(AssertUnwindSafe(body)).ok().flatten()
}

/// The handle of a new instance of `M` for the importer, or the reason
/// there is none.
pub fn instantiate<M: Model + Clone + Default + Send + Sync + 'static>(
    name: &str,
    interface: crate::instance::Interface,
    debug: bool,
    log: Logger,
) -> *mut c_void {
    match Instance::<M>::new(interface) {
        Ok(instance) => {
            let entry = Entry { instance, name: name.to_string(), debug, strings: Vec::new() };
            register(entry, log)
        }
        Err(message) => {
            log(Status::Error, "logStatusError", &message);
            std::ptr::null_mut()
        }
    }
}
