//! An FMU archive from a built library: the library asked for its two
//! model descriptions (the symbol `export_fmu!` adds), and for each FMI
//! version a zip archive of the description and the library, named as
//! that version's platform directory wants it. The archives are stored
//! (not compressed), with fixed timestamps: the same library always makes
//! the same bytes.

use std::ffi::{c_char, c_int, CStr};
use std::path::{Path, PathBuf};

/// The two archives made from one library.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Archives {
    /// The FMI 3.0 archive, `<identifier>.fmu`.
    pub fmi3: PathBuf,
    /// The FMI 2.0 archive, `<identifier>_fmi2.fmu`.
    pub fmi2: PathBuf,
}

/// This machine's platform: FMI 2.0's directory, FMI 3.0's, and the
/// library's extension.
pub fn platform() -> (&'static str, &'static str, &'static str) {
    if cfg!(all(target_os = "linux", target_arch = "x86_64")) {
        ("linux64", "x86_64-linux", "so")
    } else if cfg!(all(target_os = "linux", target_arch = "aarch64")) {
        ("linux64", "aarch64-linux", "so")
    } else if cfg!(all(target_os = "macos", target_arch = "aarch64")) {
        ("darwin64", "aarch64-darwin", "dylib")
    } else if cfg!(target_os = "macos") {
        ("darwin64", "x86_64-darwin", "dylib")
    } else if cfg!(target_os = "windows") {
        ("win64", "x86_64-windows", "dll")
    } else {
        ("linux64", "x86_64-linux", "so")
    }
}

/// The model identifier of a library file: its name without the `lib`
/// prefix and the extension (`libdc_motor.so` → `dc_motor`).
pub fn identifier_of(library: &Path) -> Result<String, String> {
    let stem = library
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or_else(|| format!("{} has no file name", library.display()))?;
    let id =
        if cfg!(target_os = "windows") { stem } else { stem.strip_prefix("lib").unwrap_or(stem) };
    Ok(id.to_string())
}

/// The model descriptions `library` carries: (FMI 2.0, FMI 3.0).
pub fn descriptions(library: &Path) -> Result<(String, String), String> {
    // SAFETY: loading runs the library's initializers; it is the user's
    // own FMU, built from Rust by `export_fmu!`.
    let lib = unsafe { libloading::Library::new(library) }
        .map_err(|e| format!("cannot load {}: {e}", library.display()))?;
    type Describe = unsafe extern "C" fn(c_int) -> *const c_char;
    // SAFETY: the symbol `export_fmu!` defines, of this type.
    let describe: libloading::Symbol<'_, Describe> =
        unsafe { lib.get(b"daegen_fmi_model_description\0") }.map_err(|_| {
            format!(
                "{} has no model description: is it a cdylib with `daegen_fmi::export_fmu!(YourModel);`?",
                library.display()
            )
        })?;
    let text = |version: c_int| -> Result<String, String> {
        // SAFETY: the function returns a static NUL-terminated string.
        let ptr = unsafe { describe(version) };
        if ptr.is_null() {
            return Err(format!("{} gave no description for FMI {version}", library.display()));
        }
        // SAFETY: non-null and NUL-terminated, alive as long as the library.
        Ok(unsafe { CStr::from_ptr(ptr) }.to_string_lossy().into_owned())
    };
    Ok((text(2)?, text(3)?))
}

/// Packages `library` (built by cargo with `export_fmu!`) into two FMUs
/// in `out_dir`: `<identifier>.fmu` (FMI 3.0) and `<identifier>_fmi2.fmu`
/// (FMI 2.0), each with Model Exchange and Co-Simulation.
pub fn package(library: &Path, out_dir: &Path) -> Result<Archives, String> {
    let id = identifier_of(library)?;
    let (fmi2_xml, fmi3_xml) = descriptions(library)?;
    if !fmi3_xml.contains(&format!("modelIdentifier=\"{id}\"")) {
        return Err(format!(
            "{} was renamed: its model identifier is not `{id}`; package the library cargo built",
            library.display()
        ));
    }
    let binary = std::fs::read(library).map_err(|e| format!("{}: {e}", library.display()))?;
    std::fs::create_dir_all(out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    let (dir2, dir3, ext) = platform();
    let archives = Archives {
        fmi3: out_dir.join(format!("{id}.fmu")),
        fmi2: out_dir.join(format!("{id}_fmi2.fmu")),
    };
    // One library in both archives: its checksum once.
    let binary_crc = crc32(&binary);
    for (path, xml, dir) in [(&archives.fmi3, &fmi3_xml, dir3), (&archives.fmi2, &fmi2_xml, dir2)] {
        let entries = [
            ("modelDescription.xml".to_string(), xml.as_bytes()),
            (format!("binaries/{dir}/{id}.{ext}"), &binary[..]),
        ];
        let crcs = [crc32(xml.as_bytes()), binary_crc];
        std::fs::write(path, zip_with_crcs(&entries, &crcs))
            .map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(archives)
}

/// A zip archive of `entries` (name, bytes), stored, dated 1980-01-01.
pub fn zip(entries: &[(String, &[u8])]) -> Vec<u8> {
    let crcs: Vec<u32> = entries.iter().map(|(_, data)| crc32(data)).collect();
    zip_with_crcs(entries, &crcs)
}

/// [`zip`] with each entry's CRC-32 known.
fn zip_with_crcs(entries: &[(String, &[u8])], crcs: &[u32]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut central = Vec::new();
    for ((name, data), &crc) in entries.iter().zip(crcs) {
        let offset = out.len() as u32;
        let size = data.len() as u32;
        let local = header(0x0403_4b50, name, crc, size, None);
        out.extend_from_slice(&local);
        out.extend_from_slice(data);
        central.extend_from_slice(&header(0x0201_4b50, name, crc, size, Some(offset)));
    }
    let start = out.len() as u32;
    let central_size = central.len() as u32;
    out.extend_from_slice(&central);
    let n = entries.len() as u16;
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    out.extend_from_slice(&[0, 0, 0, 0]);
    out.extend_from_slice(&n.to_le_bytes());
    out.extend_from_slice(&n.to_le_bytes());
    out.extend_from_slice(&central_size.to_le_bytes());
    out.extend_from_slice(&start.to_le_bytes());
    out.extend_from_slice(&[0, 0]);
    out
}

/// A local file header, or a central directory entry (with the local
/// header's offset).
fn header(signature: u32, name: &str, crc: u32, size: u32, offset: Option<u32>) -> Vec<u8> {
    let mut h = signature.to_le_bytes().to_vec();
    if offset.is_some() {
        h.extend_from_slice(&20u16.to_le_bytes()); // made by
    }
    h.extend_from_slice(&20u16.to_le_bytes()); // needed to extract
    h.extend_from_slice(&0u16.to_le_bytes()); // flags
    h.extend_from_slice(&0u16.to_le_bytes()); // stored
    h.extend_from_slice(&0u16.to_le_bytes()); // time 00:00
    h.extend_from_slice(&0x21u16.to_le_bytes()); // date 1980-01-01
    h.extend_from_slice(&crc.to_le_bytes());
    h.extend_from_slice(&size.to_le_bytes());
    h.extend_from_slice(&size.to_le_bytes());
    h.extend_from_slice(&(name.len() as u16).to_le_bytes());
    h.extend_from_slice(&0u16.to_le_bytes()); // extra
    if let Some(offset) = offset {
        h.extend_from_slice(&0u16.to_le_bytes()); // comment
        h.extend_from_slice(&0u16.to_le_bytes()); // disk
        h.extend_from_slice(&0u16.to_le_bytes()); // internal attributes
        h.extend_from_slice(&0u32.to_le_bytes()); // external attributes
        h.extend_from_slice(&offset.to_le_bytes());
    }
    h.extend_from_slice(name.as_bytes());
    h
}

/// CRC-32 (IEEE 802.3, reflected), as zip wants it, a byte at a time
/// from a table of the 256 bytes' remainders.
fn crc32(data: &[u8]) -> u32 {
    let mut table = [0u32; 256];
    for (b, entry) in table.iter_mut().enumerate() {
        let mut crc = b as u32;
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0xedb8_8320 } else { crc >> 1 };
        }
        *entry = crc;
    }
    let crc = data
        .iter()
        .fold(0xffff_ffffu32, |crc, &b| table[((crc ^ u32::from(b)) & 0xff) as usize] ^ (crc >> 8));
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc_of_the_check_string() {
        // The CRC-32 check value of "123456789" (Williams, A Painless
        // Guide to CRC Error Detection Algorithms, 1993).
        assert_eq!(crc32(b"123456789"), 0xcbf4_3926);
    }

    #[test]
    fn identifiers_drop_the_prefix_and_extension() {
        let (_, _, ext) = platform();
        let name = format!("libdc_motor.{ext}");
        let expected = if cfg!(target_os = "windows") { "libdc_motor" } else { "dc_motor" };
        assert_eq!(identifier_of(Path::new(&name)).unwrap(), expected);
    }
}
