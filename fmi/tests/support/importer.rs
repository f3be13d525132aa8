//! An FMU importer of the tests' own, written from the standards and not
//! from the exporter: it unpacks an archive (zip, stored or not, each
//! entry's CRC-32 checked), reads `modelDescription.xml`, loads the
//! library from the platform directory the FMI version names, and calls
//! the C functions by the names and signatures of `fmi2Functions.h` and
//! `fmi3Functions.h`, as any importer does.

use libloading::Library;
use std::ffi::{c_char, c_int, c_uint, c_void, CStr, CString};
use std::path::{Path, PathBuf};
use std::ptr::null;

/// A status other than `fmi2OK` / `fmi3OK`, with the call that returned it.
#[derive(Debug)]
pub struct Status {
    /// The C function.
    pub call: &'static str,
    /// Its status (1 warning, 2 discard, 3 error, 4 fatal, 5 pending).
    pub code: c_int,
}

/// `Ok` for status 0.
fn ok(call: &'static str, code: c_int) -> Result<(), Status> {
    if code == 0 {
        Ok(())
    } else {
        Err(Status { call, code })
    }
}

/// An unpacked archive: its directory and its model description.
pub struct Unpacked {
    /// Where the archive was unpacked.
    pub dir: PathBuf,
    /// `modelDescription.xml`.
    pub description: String,
}

impl Unpacked {
    /// Unpacks `archive` into a fresh directory beside it.
    pub fn new(archive: &Path) -> Unpacked {
        let bytes = std::fs::read(archive).expect("the archive reads");
        let dir = archive.with_extension("unpacked");
        let _ = std::fs::remove_dir_all(&dir);
        for (name, data) in entries(&bytes) {
            assert!(
                !name.starts_with('/') && !name.split('/').any(|p| p == ".."),
                "entry {name} leaves the archive's directory"
            );
            let path = dir.join(&name);
            if name.ends_with('/') {
                std::fs::create_dir_all(&path).unwrap();
                continue;
            }
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(&path, data).unwrap();
        }
        let description = std::fs::read_to_string(dir.join("modelDescription.xml"))
            .expect("the archive holds modelDescription.xml");
        Unpacked { dir, description }
    }

    /// The value of the first attribute `name` in the description.
    pub fn attribute(&self, name: &str) -> String {
        let key = format!(" {name}=\"");
        let at = self.description.find(&key).unwrap_or_else(|| panic!("no attribute {name}"));
        let rest = &self.description[at + key.len()..];
        rest[..rest.find('"').unwrap()].to_string()
    }

    /// The value reference of the variable called `variable`.
    pub fn reference(&self, variable: &str) -> u32 {
        let key = format!("name=\"{variable}\"");
        let at = self.description.find(&key).unwrap_or_else(|| panic!("no variable {variable}"));
        let element = &self.description[at..];
        let element = &element[..element.find('>').unwrap()];
        let value = element.split("valueReference=\"").nth(1).expect("a value reference");
        value[..value.find('"').unwrap()].parse().unwrap()
    }

    /// The library of this archive for `version` (2 or 3): FMI 2.0's
    /// `binaries/linux64/`, FMI 3.0's `binaries/x86_64-linux/` (each
    /// standard's name for this platform), named by the model identifier.
    fn library(&self, version: u32) -> Library {
        let (fmi2_platform, fmi3_platform, ext) = daegen_fmi::archive::platform();
        let platform = if version == 2 { fmi2_platform } else { fmi3_platform };
        let identifier = self.attribute("modelIdentifier");
        let path = self.dir.join("binaries").join(platform).join(format!("{identifier}.{ext}"));
        assert!(path.exists(), "FMI {version}.0 wants the library at {}", path.display());
        // SAFETY: the library of an FMU the tests exported.
        unsafe { Library::new(&path) }.expect("the library loads")
    }
}

/// The entries of zip archive `bytes`, by its central directory (APPNOTE
/// 4.3.12–4.3.16): names and uncompressed contents. Only stored entries
/// (method 0) are read, as FMUs are often written; a compressed one is an
/// error that says so.
fn entries(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let u16_at = |at: usize| u16::from_le_bytes([bytes[at], bytes[at + 1]]) as usize;
    let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    let end = (0..=bytes.len() - 22)
        .rev()
        .find(|&at| u32_at(at) == 0x0605_4b50)
        .expect("an end of central directory record");
    let count = u16_at(end + 10);
    let mut at = u32_at(end + 16);
    let mut out = Vec::new();
    for _ in 0..count {
        assert_eq!(u32_at(at), 0x0201_4b50, "a central directory header at {at}");
        let method = u16_at(at + 10);
        let crc = u32_at(at + 16) as u32;
        let size = u32_at(at + 20);
        let name_len = u16_at(at + 28);
        let extra_len = u16_at(at + 30);
        let comment_len = u16_at(at + 32);
        let local = u32_at(at + 42);
        let name = String::from_utf8(bytes[at + 46..at + 46 + name_len].to_vec()).unwrap();
        assert_eq!(method, 0, "entry {name} is compressed (method {method}); stored only");
        assert_eq!(u32_at(local), 0x0403_4b50, "{name}: a local header");
        let data_at = local + 30 + u16_at(local + 26) + u16_at(local + 28);
        let data = bytes[data_at..data_at + size].to_vec();
        assert_eq!(crc32(&data), crc, "{name}: CRC-32");
        out.push((name, data));
        at += 46 + name_len + extra_len + comment_len;
    }
    out
}

/// CRC-32 of zip (the reflected polynomial 0xEDB88320), by a table.
fn crc32(data: &[u8]) -> u32 {
    let mut table = [0u32; 256];
    for (n, entry) in table.iter_mut().enumerate() {
        *entry =
            (0..8).fold(n as u32, |c, _| if c & 1 == 1 { 0xedb8_8320 ^ (c >> 1) } else { c >> 1 });
    }
    !data.iter().fold(!0u32, |c, &b| table[((c ^ b as u32) & 0xff) as usize] ^ (c >> 8))
}

/// Resolves `$name` in `$lib` as a function of type `$ty`.
macro_rules! symbol {
    ($lib:expr, $name:literal, $ty:ty) => {{
        // SAFETY: the standard's function of that name has this signature.
        *unsafe { $lib.get::<$ty>(concat!($name, "\0").as_bytes()) }
            .unwrap_or_else(|e| panic!("{}: {e}", $name))
    }};
}

type Component = *mut c_void;

/// `fmi2CallbackFunctions`; the logger is left out (null), which FMI 2.0
/// allows an FMU to accept.
#[repr(C)]
struct Callbacks2 {
    logger: *const c_void,
    allocate_memory: *const c_void,
    free_memory: *const c_void,
    step_finished: *const c_void,
    environment: *mut c_void,
}

/// `fmi2EventInfo`.
#[repr(C)]
#[derive(Default, Debug)]
pub struct EventInfo2 {
    /// `newDiscreteStatesNeeded`.
    pub new_discrete_states_needed: c_int,
    /// `terminateSimulation`.
    pub terminate_simulation: c_int,
    /// `nominalsOfContinuousStatesChanged`.
    pub nominals_changed: c_int,
    /// `valuesOfContinuousStatesChanged`.
    pub values_changed: c_int,
    /// `nextEventTimeDefined`.
    pub next_event_time_defined: c_int,
    /// `nextEventTime`.
    pub next_event_time: f64,
}

/// One FMI 2.0 instance (Model Exchange or Co-Simulation) with the
/// functions the tests call.
pub struct Instance2 {
    c: Component,
    _lib: Library,
    /// Kept for the instance's life, as FMI 2.0 lets the FMU keep the
    /// pointer.
    _callbacks: Box<Callbacks2>,
    free: unsafe extern "C" fn(Component),
    setup_experiment: unsafe extern "C" fn(Component, c_int, f64, f64, c_int, f64) -> c_int,
    enter_initialization: unsafe extern "C" fn(Component) -> c_int,
    exit_initialization: unsafe extern "C" fn(Component) -> c_int,
    terminate: unsafe extern "C" fn(Component) -> c_int,
    get_real: unsafe extern "C" fn(Component, *const c_uint, usize, *mut f64) -> c_int,
    do_step: Option<unsafe extern "C" fn(Component, f64, f64, c_int) -> c_int>,
    enter_event_mode: unsafe extern "C" fn(Component) -> c_int,
    new_discrete_states: unsafe extern "C" fn(Component, *mut EventInfo2) -> c_int,
    enter_continuous_time_mode: unsafe extern "C" fn(Component) -> c_int,
    completed_integrator_step:
        unsafe extern "C" fn(Component, c_int, *mut c_int, *mut c_int) -> c_int,
    set_time: unsafe extern "C" fn(Component, f64) -> c_int,
    set_continuous_states: unsafe extern "C" fn(Component, *const f64, usize) -> c_int,
    get_continuous_states: unsafe extern "C" fn(Component, *mut f64, usize) -> c_int,
    get_derivatives: unsafe extern "C" fn(Component, *mut f64, usize) -> c_int,
    get_event_indicators: unsafe extern "C" fn(Component, *mut f64, usize) -> c_int,
}

/// FMI 2.0's `fmi2Type`.
#[derive(Clone, Copy)]
pub enum Kind {
    /// `fmi2ModelExchange`.
    ModelExchange = 0,
    /// `fmi2CoSimulation`.
    CoSimulation = 1,
}

impl Instance2 {
    /// `fmi2Instantiate` of `fmu`'s FMI 2.0 library, the token its `guid`.
    pub fn new(fmu: &Unpacked, kind: Kind) -> Instance2 {
        let lib = fmu.library(2);
        let guid = CString::new(fmu.attribute("guid")).unwrap();
        let resources = CString::new(format!("file://{}/resources", fmu.dir.display())).unwrap();
        type Instantiate = unsafe extern "C" fn(
            *const c_char,
            c_int,
            *const c_char,
            *const c_char,
            *const Callbacks2,
            c_int,
            c_int,
        ) -> Component;
        let instantiate = symbol!(lib, "fmi2Instantiate", Instantiate);
        let callbacks = Box::new(Callbacks2 {
            logger: null(),
            allocate_memory: null(),
            free_memory: null(),
            step_finished: null(),
            environment: std::ptr::null_mut(),
        });
        // SAFETY: the strings live across the call, the callbacks as long
        // as the instance.
        let c = unsafe {
            instantiate(
                c"instance".as_ptr(),
                kind as c_int,
                guid.as_ptr(),
                resources.as_ptr(),
                &*callbacks,
                0,
                0,
            )
        };
        assert!(!c.is_null(), "fmi2Instantiate returned null");
        Instance2 {
            c,
            free: symbol!(lib, "fmi2FreeInstance", unsafe extern "C" fn(Component)),
            setup_experiment: symbol!(
                lib,
                "fmi2SetupExperiment",
                unsafe extern "C" fn(Component, c_int, f64, f64, c_int, f64) -> c_int
            ),
            enter_initialization: symbol!(
                lib,
                "fmi2EnterInitializationMode",
                unsafe extern "C" fn(Component) -> c_int
            ),
            exit_initialization: symbol!(
                lib,
                "fmi2ExitInitializationMode",
                unsafe extern "C" fn(Component) -> c_int
            ),
            terminate: symbol!(lib, "fmi2Terminate", unsafe extern "C" fn(Component) -> c_int),
            get_real: symbol!(
                lib,
                "fmi2GetReal",
                unsafe extern "C" fn(Component, *const c_uint, usize, *mut f64) -> c_int
            ),
            do_step: matches!(kind, Kind::CoSimulation).then(|| {
                symbol!(
                    lib,
                    "fmi2DoStep",
                    unsafe extern "C" fn(Component, f64, f64, c_int) -> c_int
                )
            }),
            enter_event_mode: symbol!(
                lib,
                "fmi2EnterEventMode",
                unsafe extern "C" fn(Component) -> c_int
            ),
            new_discrete_states: symbol!(
                lib,
                "fmi2NewDiscreteStates",
                unsafe extern "C" fn(Component, *mut EventInfo2) -> c_int
            ),
            enter_continuous_time_mode: symbol!(
                lib,
                "fmi2EnterContinuousTimeMode",
                unsafe extern "C" fn(Component) -> c_int
            ),
            completed_integrator_step: symbol!(
                lib,
                "fmi2CompletedIntegratorStep",
                unsafe extern "C" fn(Component, c_int, *mut c_int, *mut c_int) -> c_int
            ),
            set_time: symbol!(lib, "fmi2SetTime", unsafe extern "C" fn(Component, f64) -> c_int),
            set_continuous_states: symbol!(
                lib,
                "fmi2SetContinuousStates",
                unsafe extern "C" fn(Component, *const f64, usize) -> c_int
            ),
            get_continuous_states: symbol!(
                lib,
                "fmi2GetContinuousStates",
                unsafe extern "C" fn(Component, *mut f64, usize) -> c_int
            ),
            get_derivatives: symbol!(
                lib,
                "fmi2GetDerivatives",
                unsafe extern "C" fn(Component, *mut f64, usize) -> c_int
            ),
            get_event_indicators: symbol!(
                lib,
                "fmi2GetEventIndicators",
                unsafe extern "C" fn(Component, *mut f64, usize) -> c_int
            ),
            _lib: lib,
            _callbacks: callbacks,
        }
    }

    // SAFETY (every call below): `self.c` is the live instance of the
    // library `self` keeps loaded; slices pass their own lengths.

    /// `fmi2SetupExperiment`, the tolerance and the start time.
    pub fn setup_experiment(&mut self, tolerance: Option<f64>, start: f64) -> Result<(), Status> {
        let code = unsafe {
            (self.setup_experiment)(
                self.c,
                tolerance.is_some() as c_int,
                tolerance.unwrap_or(0.0),
                start,
                0,
                0.0,
            )
        };
        ok("fmi2SetupExperiment", code)
    }

    /// `fmi2EnterInitializationMode` then `fmi2ExitInitializationMode`.
    pub fn initialize(&mut self) -> Result<(), Status> {
        ok("fmi2EnterInitializationMode", unsafe { (self.enter_initialization)(self.c) })?;
        ok("fmi2ExitInitializationMode", unsafe { (self.exit_initialization)(self.c) })
    }

    /// `fmi2GetReal`.
    pub fn get_real(&mut self, vrs: &[u32], values: &mut [f64]) -> Result<(), Status> {
        assert_eq!(vrs.len(), values.len());
        ok("fmi2GetReal", unsafe {
            (self.get_real)(self.c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr())
        })
    }

    /// `fmi2DoStep` from `t` over `h`.
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<(), Status> {
        let do_step = self.do_step.expect("a Co-Simulation instance");
        ok("fmi2DoStep", unsafe { do_step(self.c, t, h, 1) })
    }

    /// `fmi2EnterEventMode`.
    pub fn enter_event_mode(&mut self) -> Result<(), Status> {
        ok("fmi2EnterEventMode", unsafe { (self.enter_event_mode)(self.c) })
    }

    /// `fmi2NewDiscreteStates`.
    pub fn new_discrete_states(&mut self) -> Result<EventInfo2, Status> {
        let mut info = EventInfo2::default();
        ok("fmi2NewDiscreteStates", unsafe { (self.new_discrete_states)(self.c, &mut info) })?;
        Ok(info)
    }

    /// `fmi2EnterContinuousTimeMode`.
    pub fn enter_continuous_time_mode(&mut self) -> Result<(), Status> {
        ok("fmi2EnterContinuousTimeMode", unsafe { (self.enter_continuous_time_mode)(self.c) })
    }

    /// `fmi2CompletedIntegratorStep`: whether to enter event mode.
    pub fn completed_integrator_step(&mut self) -> Result<bool, Status> {
        let (mut event, mut stop) = (0, 0);
        let code = unsafe { (self.completed_integrator_step)(self.c, 1, &mut event, &mut stop) };
        ok("fmi2CompletedIntegratorStep", code)?;
        Ok(event != 0)
    }

    /// `fmi2SetTime`.
    pub fn set_time(&mut self, t: f64) -> Result<(), Status> {
        ok("fmi2SetTime", unsafe { (self.set_time)(self.c, t) })
    }

    /// `fmi2SetContinuousStates`.
    pub fn set_continuous_states(&mut self, x: &[f64]) -> Result<(), Status> {
        ok("fmi2SetContinuousStates", unsafe {
            (self.set_continuous_states)(self.c, x.as_ptr(), x.len())
        })
    }

    /// `fmi2GetContinuousStates`.
    pub fn get_continuous_states(&mut self, x: &mut [f64]) -> Result<(), Status> {
        ok("fmi2GetContinuousStates", unsafe {
            (self.get_continuous_states)(self.c, x.as_mut_ptr(), x.len())
        })
    }

    /// `fmi2GetDerivatives`.
    pub fn get_derivatives(&mut self, dx: &mut [f64]) -> Result<(), Status> {
        ok("fmi2GetDerivatives", unsafe {
            (self.get_derivatives)(self.c, dx.as_mut_ptr(), dx.len())
        })
    }

    /// `fmi2GetEventIndicators`.
    pub fn get_event_indicators(&mut self, g: &mut [f64]) -> Result<(), Status> {
        ok("fmi2GetEventIndicators", unsafe {
            (self.get_event_indicators)(self.c, g.as_mut_ptr(), g.len())
        })
    }

    /// `fmi2Terminate`.
    pub fn terminate(&mut self) -> Result<(), Status> {
        ok("fmi2Terminate", unsafe { (self.terminate)(self.c) })
    }
}

impl Drop for Instance2 {
    fn drop(&mut self) {
        // SAFETY: the instance, freed once, before its library unloads.
        unsafe { (self.free)(self.c) }
    }
}

/// `fmi3LogMessageCallback`; messages go to the test's output.
unsafe extern "C" fn log3(
    _env: *mut c_void,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    // SAFETY: the FMU passes C strings.
    let text = |p: *const c_char| {
        if p.is_null() {
            String::new()
        } else {
            unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
        }
    };
    eprintln!("[fmi3 status {status}, {}] {}", text(category), text(message));
}

type Log3 = unsafe extern "C" fn(*mut c_void, c_int, *const c_char, *const c_char);

/// What `fmi3UpdateDiscreteStates` reports.
#[derive(Default, Debug)]
pub struct Update3 {
    /// `discreteStatesNeedUpdate`.
    pub needs_update: bool,
    /// `terminateSimulation`.
    pub terminate: bool,
    /// `nominalsOfContinuousStatesChanged`.
    pub nominals_changed: bool,
    /// `valuesOfContinuousStatesChanged`.
    pub values_changed: bool,
    /// `nextEventTimeDefined`.
    pub next_event_time_defined: bool,
    /// `nextEventTime`.
    pub next_event_time: f64,
}

/// One FMI 3.0 instance with the functions the tests call.
pub struct Instance3 {
    c: Component,
    _lib: Library,
    free: unsafe extern "C" fn(Component),
    enter_initialization: unsafe extern "C" fn(Component, bool, f64, f64, bool, f64) -> c_int,
    exit_initialization: unsafe extern "C" fn(Component) -> c_int,
    terminate: unsafe extern "C" fn(Component) -> c_int,
    get_float64: unsafe extern "C" fn(Component, *const u32, usize, *mut f64, usize) -> c_int,
    do_step: unsafe extern "C" fn(
        Component,
        f64,
        f64,
        bool,
        *mut bool,
        *mut bool,
        *mut bool,
        *mut f64,
    ) -> c_int,
    update_discrete_states: unsafe extern "C" fn(
        Component,
        *mut bool,
        *mut bool,
        *mut bool,
        *mut bool,
        *mut bool,
        *mut f64,
    ) -> c_int,
    enter_continuous_time_mode: unsafe extern "C" fn(Component) -> c_int,
    set_time: unsafe extern "C" fn(Component, f64) -> c_int,
    set_continuous_states: unsafe extern "C" fn(Component, *const f64, usize) -> c_int,
    get_continuous_states: unsafe extern "C" fn(Component, *mut f64, usize) -> c_int,
    get_derivatives: unsafe extern "C" fn(Component, *mut f64, usize) -> c_int,
}

impl Instance3 {
    fn load(
        fmu: &Unpacked,
        instantiate: impl FnOnce(&Library, &CStr, &CStr) -> Component,
    ) -> Instance3 {
        let lib = fmu.library(3);
        let token = CString::new(fmu.attribute("instantiationToken")).unwrap();
        let resources = CString::new(format!("{}/resources/", fmu.dir.display())).unwrap();
        let c = instantiate(&lib, &token, &resources);
        assert!(!c.is_null(), "fmi3Instantiate… returned null");
        Instance3 {
            c,
            free: symbol!(lib, "fmi3FreeInstance", unsafe extern "C" fn(Component)),
            enter_initialization: symbol!(
                lib,
                "fmi3EnterInitializationMode",
                unsafe extern "C" fn(Component, bool, f64, f64, bool, f64) -> c_int
            ),
            exit_initialization: symbol!(
                lib,
                "fmi3ExitInitializationMode",
                unsafe extern "C" fn(Component) -> c_int
            ),
            terminate: symbol!(lib, "fmi3Terminate", unsafe extern "C" fn(Component) -> c_int),
            get_float64: symbol!(
                lib,
                "fmi3GetFloat64",
                unsafe extern "C" fn(Component, *const u32, usize, *mut f64, usize) -> c_int
            ),
            do_step: symbol!(
                lib,
                "fmi3DoStep",
                unsafe extern "C" fn(
                    Component,
                    f64,
                    f64,
                    bool,
                    *mut bool,
                    *mut bool,
                    *mut bool,
                    *mut f64,
                ) -> c_int
            ),
            update_discrete_states: symbol!(
                lib,
                "fmi3UpdateDiscreteStates",
                unsafe extern "C" fn(
                    Component,
                    *mut bool,
                    *mut bool,
                    *mut bool,
                    *mut bool,
                    *mut bool,
                    *mut f64,
                ) -> c_int
            ),
            enter_continuous_time_mode: symbol!(
                lib,
                "fmi3EnterContinuousTimeMode",
                unsafe extern "C" fn(Component) -> c_int
            ),
            set_time: symbol!(lib, "fmi3SetTime", unsafe extern "C" fn(Component, f64) -> c_int),
            set_continuous_states: symbol!(
                lib,
                "fmi3SetContinuousStates",
                unsafe extern "C" fn(Component, *const f64, usize) -> c_int
            ),
            get_continuous_states: symbol!(
                lib,
                "fmi3GetContinuousStates",
                unsafe extern "C" fn(Component, *mut f64, usize) -> c_int
            ),
            get_derivatives: symbol!(
                lib,
                "fmi3GetContinuousStateDerivatives",
                unsafe extern "C" fn(Component, *mut f64, usize) -> c_int
            ),
            _lib: lib,
        }
    }

    /// `fmi3InstantiateModelExchange`.
    pub fn model_exchange(fmu: &Unpacked) -> Instance3 {
        Instance3::load(fmu, |lib, token, resources| {
            type Instantiate = unsafe extern "C" fn(
                *const c_char,
                *const c_char,
                *const c_char,
                bool,
                bool,
                *mut c_void,
                Option<Log3>,
            ) -> Component;
            let instantiate = symbol!(lib, "fmi3InstantiateModelExchange", Instantiate);
            // SAFETY: the strings live across the call.
            unsafe {
                instantiate(
                    c"me".as_ptr(),
                    token.as_ptr(),
                    resources.as_ptr(),
                    false,
                    false,
                    std::ptr::null_mut(),
                    Some(log3),
                )
            }
        })
    }

    /// `fmi3InstantiateCoSimulation`, without event mode or early return.
    pub fn co_simulation(fmu: &Unpacked) -> Instance3 {
        Instance3::load(fmu, |lib, token, resources| {
            type Instantiate = unsafe extern "C" fn(
                *const c_char,
                *const c_char,
                *const c_char,
                bool,
                bool,
                bool,
                bool,
                *const u32,
                usize,
                *mut c_void,
                Option<Log3>,
                *const c_void,
            ) -> Component;
            let instantiate = symbol!(lib, "fmi3InstantiateCoSimulation", Instantiate);
            // SAFETY: the strings live across the call.
            unsafe {
                instantiate(
                    c"cs".as_ptr(),
                    token.as_ptr(),
                    resources.as_ptr(),
                    false,
                    false,
                    false,
                    false,
                    null(),
                    0,
                    std::ptr::null_mut(),
                    Some(log3),
                    null(),
                )
            }
        })
    }

    // SAFETY (every call below): as for `Instance2`.

    /// `fmi3EnterInitializationMode` then `fmi3ExitInitializationMode`.
    pub fn initialize(&mut self, tolerance: Option<f64>, start: f64) -> Result<(), Status> {
        let code = unsafe {
            (self.enter_initialization)(
                self.c,
                tolerance.is_some(),
                tolerance.unwrap_or(0.0),
                start,
                false,
                0.0,
            )
        };
        ok("fmi3EnterInitializationMode", code)?;
        ok("fmi3ExitInitializationMode", unsafe { (self.exit_initialization)(self.c) })
    }

    /// `fmi3GetFloat64`.
    pub fn get_float64(&mut self, vrs: &[u32], values: &mut [f64]) -> Result<(), Status> {
        let code = unsafe {
            (self.get_float64)(self.c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr(), values.len())
        };
        ok("fmi3GetFloat64", code)
    }

    /// `fmi3DoStep` from `t` over `h`: the time it reached.
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<f64, Status> {
        let (mut event, mut stop, mut early, mut reached) = (false, false, false, f64::NAN);
        let code = unsafe {
            (self.do_step)(self.c, t, h, true, &mut event, &mut stop, &mut early, &mut reached)
        };
        ok("fmi3DoStep", code)?;
        Ok(reached)
    }

    /// `fmi3UpdateDiscreteStates`.
    pub fn update_discrete_states(&mut self) -> Result<Update3, Status> {
        let mut u = Update3::default();
        let code = unsafe {
            (self.update_discrete_states)(
                self.c,
                &mut u.needs_update,
                &mut u.terminate,
                &mut u.nominals_changed,
                &mut u.values_changed,
                &mut u.next_event_time_defined,
                &mut u.next_event_time,
            )
        };
        ok("fmi3UpdateDiscreteStates", code)?;
        Ok(u)
    }

    /// `fmi3EnterContinuousTimeMode`.
    pub fn enter_continuous_time_mode(&mut self) -> Result<(), Status> {
        ok("fmi3EnterContinuousTimeMode", unsafe { (self.enter_continuous_time_mode)(self.c) })
    }

    /// `fmi3SetTime`.
    pub fn set_time(&mut self, t: f64) -> Result<(), Status> {
        ok("fmi3SetTime", unsafe { (self.set_time)(self.c, t) })
    }

    /// `fmi3SetContinuousStates`.
    pub fn set_continuous_states(&mut self, x: &[f64]) -> Result<(), Status> {
        ok("fmi3SetContinuousStates", unsafe {
            (self.set_continuous_states)(self.c, x.as_ptr(), x.len())
        })
    }

    /// `fmi3GetContinuousStates`.
    pub fn get_continuous_states(&mut self, x: &mut [f64]) -> Result<(), Status> {
        ok("fmi3GetContinuousStates", unsafe {
            (self.get_continuous_states)(self.c, x.as_mut_ptr(), x.len())
        })
    }

    /// `fmi3GetContinuousStateDerivatives`.
    pub fn get_derivatives(&mut self, dx: &mut [f64]) -> Result<(), Status> {
        ok("fmi3GetContinuousStateDerivatives", unsafe {
            (self.get_derivatives)(self.c, dx.as_mut_ptr(), dx.len())
        })
    }

    /// `fmi3Terminate`.
    pub fn terminate(&mut self) -> Result<(), Status> {
        ok("fmi3Terminate", unsafe { (self.terminate)(self.c) })
    }
}

impl Drop for Instance3 {
    fn drop(&mut self) {
        // SAFETY: as for `Instance2`.
        unsafe { (self.free)(self.c) }
    }
}
