//! The field files a deck leaves at the path positions (FreeFEM's `field_*.vtu`, dolfinx's
//! `field_*.xdmf` with the `.h5` it names), read for the surface pressure p(r) through meshio by
//! `scripts/read_fields.py`, run as a subprocess.
//!
//! meshio opens what it is handed and what an XDMF names, so each file is checked first as a file
//! from elsewhere ([`spherecontact_system::input::foreign`], docs/security.md "Deck folders"): a regular file in
//! the deck's folder (a link only to a file inside it), of at most
//! [`MAX_FIELD_FILE_BYTES`]; an XDMF file (at most [`MAX_XDMF_BYTES`], read whole) may name
//! data only in an HDF5 file beside it, by its plain name, checked the same way, and nothing the
//! scan below cannot see (an entity declaration, a DataItem of another format or whose data is
//! not plain text). A link out of the folder, a FIFO or `/proc/self/environ` never reaches
//! meshio. What meshio says about a file is not shown (it quotes what it cannot read): a failure
//! is the script's own line, naming the file and what was expected.

use std::path::Path;
use std::time::Duration;

use super::readback;
use spherecontact_model::limits::{MAX_DECK_TABLE_BYTES, MAX_FIELD_FILE_BYTES, MAX_XDMF_BYTES};
use spherecontact_system::input::{foreign, line_and_column};
use spherecontact_system::process::{self, Job};
use spherecontact_system::toolchain::Toolchain;

/// The glue script, compiled in and written into a private folder when needed.
pub const READ_FIELDS_PY: &str = include_str!("../../../scripts/read_fields.py");

/// What starts each line of `scripts/read_fields.py`'s own messages (the lines shown).
const SCRIPT_LINE: &str = "read_fields: ";

/// One point of the spherical surface in a field file, SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Radius r [m].
    pub r: f64,
    /// Contact pressure [Pa].
    pub pressure: f64,
    /// Height of the deformed surface above the contact plane, z + u_z [m] (negative inside the
    /// contact by the penalty's penetration p/k).
    pub gap: f64,
}

/// The surface of one field file, sorted by r.
pub type Profile = Vec<SurfacePoint>;

/// Extracts p(r) on the spherical surface (radius `radius_mm`, r ≤ `window_mm`) from each field
/// file `files` of `dir` ([`check`]ed first), through meshio (`scripts/read_fields.py` run by the
/// toolchain's Python). The script, its output and its logs live in a private temporary folder:
/// nothing is written into `dir` (a run folder read back by `deck read` stays as the deck left
/// it).
pub fn read_profiles(
    dir: &Path,
    files: &[String],
    radius_mm: f64,
    window_mm: f64,
    toolchain: &Toolchain,
    timeout: Duration,
) -> Result<Vec<Profile>, String> {
    for name in files {
        check(dir, name)?;
    }
    let work = tempfile::Builder::new()
        .prefix("spherecontact-meshio-")
        .tempdir()
        .map_err(|e| format!("meshio: no temporary folder: {e}"))?;
    let script = work.path().join("read_fields.py");
    std::fs::write(&script, READ_FIELDS_PY).map_err(|e| format!("{}: {e}", script.display()))?;
    let out = "profiles.csv";
    let dir = std::path::absolute(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let paths: Vec<String> = files.iter().map(|f| dir.join(f).display().to_string()).collect();
    let mut args = vec![
        script.display().to_string(),
        "--radius".into(),
        radius_mm.to_string(),
        "--window".into(),
        window_mm.to_string(),
        "--out".into(),
        work.path().join(out).display().to_string(),
    ];
    args.extend(paths.iter().cloned());
    let job = Job {
        program: toolchain.python.clone(),
        args,
        env: vec![],
        timeout,
    };
    let run = process::run(&job, work.path(), "read_fields").map_err(|e| format!("meshio: {e}"))?;
    if let Some(failure) = run
        .ending
        .failure("python (meshio)", timeout, |_| "reading the field files failed")
    {
        let own: Vec<&str> = run
            .stderr
            .lines()
            .filter(|l| l.starts_with(SCRIPT_LINE))
            .collect();
        let why = match own.is_empty() {
            true => "read_fields.py gave no reason (meshio's own output is not shown)".to_owned(),
            false => own.join("; "),
        };
        return Err(format!("{failure}; {why}"));
    }
    parse_profiles(
        &readback::read_output(work.path(), out, MAX_DECK_TABLE_BYTES)?,
        &paths,
    )
}

/// Checks the field file `name` of `dir` before meshio opens it (see the module doc).
pub fn check(dir: &Path, name: &str) -> Result<(), String> {
    let file = dir.join(name);
    readback::present(&file)?;
    foreign::open(&file, MAX_FIELD_FILE_BYTES).map_err(|e| e.to_string())?;
    if !name.ends_with(".xdmf") {
        return Ok(());
    }
    let text = foreign::read_text(&file, MAX_XDMF_BYTES).map_err(|e| e.to_string())?;
    let at = |line: usize, why: String| format!("{}:{line}: {why}", file.display());
    // meshio looks for the HDF5 files beside the XDMF's own target.
    let folder = std::fs::canonicalize(&file)
        .ok()
        .and_then(|f| f.parent().map(Path::to_path_buf))
        .ok_or_else(|| at(1, "its folder cannot be resolved".into()))?;
    for (line, hdf5) in hdf5_files(&text).map_err(|(line, why)| at(line, why))? {
        let data = folder.join(&hdf5);
        readback::present(&data)
            .and_then(|()| foreign::open(&data, MAX_FIELD_FILE_BYTES).map_err(|e| e.to_string()))
            .map_err(|e| at(line, format!("the HDF5 file of a DataItem: {e}")))?;
    }
    Ok(())
}

/// The HDF5 files the DataItems of the XDMF `text` name (each with its line), or the line and
/// what is wrong where the text could make meshio read a file this scan does not see.
fn hdf5_files(text: &str) -> Result<Vec<(usize, String)>, (usize, String)> {
    let line = |offset: usize| line_and_column(text, offset).0;
    if let Some(at) = text.find("<!ENTITY") {
        return Err((
            line(at),
            "an entity declaration (allowed: none, as dolfinx writes)".into(),
        ));
    }
    let mut files = Vec::new();
    for (at, _) in text.match_indices("<DataItem") {
        let rest = &text[at + "<DataItem".len()..];
        if !rest.starts_with(|c: char| c.is_whitespace() || c == '>' || c == '/') {
            continue; // another element's name
        }
        let bad = |why: &str| (line(at), why.to_owned());
        let end = rest
            .find('>')
            .ok_or_else(|| bad("a DataItem tag that does not end"))?;
        let (tag, body) = (&rest[..end], &rest[end + 1..]);
        if tag.ends_with('/') {
            continue; // empty: no data
        }
        let format = attribute(tag, "Format").map_err(&bad)?;
        let data = &body[..body.find('<').unwrap_or(body.len())];
        if !body[data.len()..].starts_with("</DataItem") || data.contains('&') {
            return Err(bad(
                "a DataItem whose data is not plain text (allowed: numbers, or NAME.h5:/PATH)",
            ));
        }
        match format.as_deref() {
            None | Some("XML") => {}
            Some("HDF") => match data.trim().split_once(':') {
                Some((name, _)) if readback::is_plain_name(name) => files.push((line(at), name.to_owned())),
                _ => {
                    return Err(bad(
                        "a DataItem whose HDF5 file is not one beside the XDMF file (allowed: \
                         NAME.h5:/PATH, NAME a file in the same folder)",
                    ))
                }
            },
            Some(_) => {
                return Err(bad(
                    "a DataItem of a Format other than XML or HDF (allowed: XML, HDF)",
                ))
            }
        }
    }
    Ok(files)
}

/// The value of the attribute `name` in the attributes `tag` of a start tag, if it has one; an
/// error where the attributes cannot be read plainly (a value without quotes, an entity or a
/// character reference in the value sought).
fn attribute(tag: &str, name: &str) -> Result<Option<String>, &'static str> {
    let mut rest = tag.trim_start();
    while !rest.is_empty() && rest != "/" {
        let equals = rest.find('=').ok_or("a DataItem attribute without a value")?;
        let key = rest[..equals].trim();
        let value = rest[equals + 1..].trim_start();
        let quote = value
            .chars()
            .next()
            .filter(|c| matches!(c, '"' | '\''))
            .ok_or("a DataItem attribute value without quotes")?;
        let close = value[1..]
            .find(quote)
            .ok_or("a DataItem attribute value that does not end")?;
        let text = &value[1..1 + close];
        if key == name {
            if text.contains('&') {
                return Err("a reference in a DataItem's Format (allowed: XML, HDF)");
            }
            return Ok(Some(text.to_owned()));
        }
        rest = value[close + 2..].trim_start();
    }
    Ok(None)
}

/// Splits `read_fields.py`'s CSV (file, r [mm], p [MPa], gap [mm]) into one SI profile per file.
pub fn parse_profiles(text: &str, files: &[String]) -> Result<Vec<Profile>, String> {
    let mut profiles = vec![Profile::new(); files.len()];
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    for (k, record) in reader.records().enumerate() {
        let record = record.map_err(|e| format!("profiles.csv row {}: {e}", k + 1))?;
        let values: Option<Vec<f64>> = (record.len() == 4)
            .then(|| (1..4).map(|i| record[i].parse::<f64>().ok()).collect())
            .flatten()
            .filter(|v: &Vec<f64>| v.iter().all(|x| x.is_finite()));
        let Some(v) = values else {
            return Err(format!(
                "profiles.csv row {}: not a finite (r, p, gap) triple",
                k + 1
            ));
        };
        let Some(i) = files.iter().position(|f| f == &record[0]) else {
            return Err(format!(
                "profiles.csv row {}: unknown file `{}`",
                k + 1,
                &record[0]
            ));
        };
        profiles[i].push(SurfacePoint {
            r: v[0] * 1e-3,
            pressure: v[1] * 1e6,
            gap: v[2] * 1e-3,
        });
    }
    if let Some(i) = profiles.iter().position(Vec::is_empty) {
        return Err(format!("no surface pressure read from {}", files[i]));
    }
    Ok(profiles)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profiles_split_by_file_and_reject_nan() {
        let files = vec!["a.vtu".to_string(), "b.vtu".to_string()];
        let text =
            "file,r,pressure,gap\na.vtu,0.0,450.0,-1e-8\nb.vtu,0.0,550.0,-1e-8\nb.vtu,0.5,300.0,-1e-8\n";
        let p = parse_profiles(text, &files).unwrap();
        assert_eq!(p[0].len(), 1);
        assert_eq!(p[0][0].pressure, 450e6);
        assert_eq!(p[1].len(), 2);
        assert!(parse_profiles("file,r,pressure,gap\na.vtu,0.0,nan,0\n", &files).is_err());
        let e = parse_profiles("file,r,pressure,gap\na.vtu,0.0,1.0,0\n", &files).unwrap_err();
        assert!(e.contains("b.vtu"), "{e}");
    }

    /// dolfinx's own XDMF (its first DataItems, as `cases/paper-fig7.toml`'s deck writes them).
    const DOLFINX: &str = "<?xml version=\"1.0\"?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n\
        <Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n  <Domain>\n\
        <Grid Name=\"mesh\" GridType=\"Uniform\">\n\
        <Topology TopologyType=\"Triangle_6\" NumberOfElements=\"10998\" NodesPerElement=\"6\">\n\
        <DataItem Dimensions=\"10998 6\" NumberType=\"Int\" Format=\"HDF\">field_5.h5:/Mesh/mesh/topology</DataItem>\n\
        </Topology>\n<Geometry GeometryType=\"XY\">\n\
        <DataItem Dimensions=\"22273 2\" Format=\"HDF\">field_5.h5:/Mesh/mesh/geometry</DataItem>\n\
        </Geometry>\n</Grid>\n</Domain>\n</Xdmf>\n";

    #[test]
    fn an_xdmf_names_its_hdf5_files_by_line() {
        assert_eq!(
            hdf5_files(DOLFINX).unwrap(),
            [(7, "field_5.h5".to_owned()), (10, "field_5.h5".to_owned())]
        );
        let inline = "<DataItem Dimensions=\"2\" Format='XML'> 1 2 </DataItem><DataItemList/>";
        assert_eq!(hdf5_files(inline).unwrap(), []);
    }

    /// Requirement: nothing in an XDMF can make meshio open a file outside its folder unseen:
    /// a path, an entity, a reference, CDATA or another format is refused with its line.
    #[test]
    fn an_xdmf_that_could_name_a_file_elsewhere_is_refused() {
        for (text, why) in [
            (
                "x\n<DataItem Format=\"HDF\">/etc/s.h5:/a</DataItem>",
                "not one beside",
            ),
            (
                "x\n<DataItem Format=\"HDF\">../s.h5:/a</DataItem>",
                "not one beside",
            ),
            ("x\n<DataItem Format=\"HDF\">s.h5</DataItem>", "not one beside"),
            (
                "x\n<DataItem Format=\"Binary\">secret</DataItem>",
                "other than XML or HDF",
            ),
            ("x\n<DataItem Format=\"&#72;DF\">s:/a</DataItem>", "a reference"),
            (
                "x\n<DataItem Format=\"HDF\">&#47;etc/s.h5:/a</DataItem>",
                "not plain text",
            ),
            (
                "x\n<DataItem Format=\"HDF\"><![CDATA[/etc/s.h5:/a]]></DataItem>",
                "not plain text",
            ),
            ("x\n<DataItem Format=HDF>s.h5:/a</DataItem>", "without quotes"),
            ("x\n<!ENTITY e \"/etc/s.h5:/a\">", "an entity declaration"),
        ] {
            let (line, e) = hdf5_files(text).unwrap_err();
            assert!(line == 2 && e.contains(why), "{text}: {line}: {e}");
        }
    }

    #[test]
    fn a_field_file_or_its_hdf5_data_out_of_the_folder_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let deck = dir.path().join("deck");
        std::fs::create_dir(&deck).unwrap();
        std::fs::write(dir.path().join("outside.h5"), "SECRET").unwrap();
        std::os::unix::fs::symlink("../outside.h5", deck.join("field_1.vtu")).unwrap();
        let e = check(&deck, "field_1.vtu").unwrap_err();
        assert!(e.contains("leads out of its folder"), "{e}");
        std::fs::write(deck.join("f.h5"), "data").unwrap();
        let xdmf = |name: &str| format!("<Xdmf>\n<DataItem Format=\"HDF\">{name}:/u</DataItem></Xdmf>");
        std::fs::write(deck.join("f.xdmf"), xdmf("f.h5")).unwrap();
        assert_eq!(check(&deck, "f.xdmf"), Ok(()));
        std::os::unix::fs::symlink("../outside.h5", deck.join("out.h5")).unwrap();
        std::fs::write(deck.join("f.xdmf"), xdmf("out.h5")).unwrap();
        let e = check(&deck, "f.xdmf").unwrap_err();
        assert!(
            e.contains("f.xdmf:2: the HDF5 file of a DataItem") && e.contains("leads out"),
            "{e}"
        );
        std::fs::write(deck.join("f.xdmf"), xdmf("gone.h5")).unwrap();
        assert!(check(&deck, "f.xdmf").unwrap_err().contains("output missing"));
        assert!(check(&deck, "none.vtu").unwrap_err().contains("output missing"));
    }
}
