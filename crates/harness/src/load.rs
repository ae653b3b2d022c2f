//! Reading fixture files: every error names the file, the case and the field
//! (line and column for JSON syntax), and one bad case or file never costs the
//! others.
//!
//! Only regular files are read, and none above [`MAX_INPUT_BYTES`]; folders are
//! walked without entering one already walked (so links back up the tree end),
//! and each file is read once however often it is named.
//!
//! A file is read in two passes. The first checks the JSON syntax and splits the
//! `cases` array into raw slices without converting a single number, so a number
//! beyond `f64` in one case does not sink its neighbours. The second reads each
//! case on its own (the field path of a type error comes from
//! `serde_path_to_error`, its line and column are made absolute in the file), then
//! checks what the type system cannot: that a shape has one key (the derives
//! refuse unknown keys at every other level: the file, the case, the shapes'
//! fields, `expect`), finite numbers, positive radii, non-zero normals, `min ≤
//! max`, mesh indices in range, shapes that fit the query.

use crate::case::{Case, Expect, MeshSpec, Query, SCHEMA, Shape};
use crate::mesh::{Mesh, load_mesh_file};
use oracle::geom::P3;
use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde_json::value::RawValue;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::io::Read;
use std::path::{Path, PathBuf};

/// The largest fixture or mesh file read: 64 MiB. Reason: a file is read whole
/// and its cases held in memory several times over (text, cases, results), the
/// shipped files are all under 128 KiB (the bunny's mesh is the largest), and a
/// file of 100,000 cases is about 40 MiB; anything larger is far more likely a
/// wrong path (a log, a disk image) than a case file, and is refused before it
/// is read.
pub const MAX_INPUT_BYTES: u64 = 64 << 20;

/// [`MAX_INPUT_BYTES`] as written in messages.
const MAX_INPUT_TEXT: &str = "64 MiB";

/// A refusal of malformed input.
#[derive(Clone, Debug, PartialEq)]
pub struct InputError {
    /// The file.
    pub file: PathBuf,
    /// The case's name (or `#index` when it has none), if the error is inside a case.
    pub case: Option<String>,
    /// The field's path inside the case (or file), if known: `a.sphere.radius`.
    pub field: Option<String>,
    /// Line and column (1-based) in the file, for JSON syntax and type errors.
    pub position: Option<(usize, usize)>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some((line, col)) = self.position {
            write!(f, ":{line}:{col}")?;
        }
        if let Some(case) = &self.case {
            write!(f, ": case \"{case}\"")?;
        }
        if let Some(field) = &self.field {
            write!(f, ": field `{field}`")?;
        }
        write!(f, ": {}", self.message)
    }
}

/// A case ready to run: the parsed case with its mesh files read.
#[derive(Clone, Debug)]
pub struct LoadedCase {
    /// The file it came from.
    pub file: PathBuf,
    /// The case as written.
    pub case: Case,
    /// Meshes of `a` and `b`, resolved (inline or read from their files).
    pub meshes: [Option<Mesh>; 2],
}

/// The points a `bounds` case bounds.
pub fn bounded_points(lc: &LoadedCase) -> std::borrow::Cow<'_, [P3]> {
    use std::borrow::Cow;
    match (&lc.case.a, &lc.meshes[0]) {
        (Shape::Points(p), _) => Cow::Borrowed(&p.points),
        (Shape::Box(b), _) => Cow::Owned(box_corners(&b.to_geom()).to_vec()),
        (_, Some(m)) => Cow::Borrowed(&m.vertices),
        _ => Cow::Borrowed(&[]),
    }
}

/// A box's eight corners in `f64`: `center ± h₀R₀ ± h₁R₁ ± h₂R₂` with the
/// rotation matrix rounded (each corner within a few ulps of the box's size
/// of the exact one), halved before the sums where they would overflow.
pub fn box_corners(b: &oracle::geom::OrientedBox) -> [P3; 8] {
    let r = b.rotation_matrix();
    let h = b.half_extents;
    std::array::from_fn(|k| {
        let s = [0, 1, 2].map(|j| if k >> j & 1 == 1 { h[j] } else { -h[j] });
        std::array::from_fn(|i| {
            let off = r[i][0] * s[0] + r[i][1] * s[1] + r[i][2] * s[2];
            let x = b.center[i] + off;
            if x.is_finite() { x } else { 2.0 * (b.center[i] / 2.0 + off / 2.0) }
        })
    })
}

/// What reading some paths gave: the good cases, and an error for each bad one.
#[derive(Clone, Debug, Default)]
pub struct Loaded {
    /// Cases that passed every check, in file order.
    pub cases: Vec<LoadedCase>,
    /// One error per refused file or case.
    pub errors: Vec<InputError>,
    /// Files read (including ones with errors).
    pub files: Vec<PathBuf>,
}

/// Reads files, and folders searched recursively for `*.json` (in sorted order).
///
/// A folder already walked is not entered again (its canonical path decides,
/// so a link to `.` or to a parent ends the walk instead of looping), and a
/// file is read once however many names reach it. A folder with no `*.json`
/// file, and a selection with no case at all, are input errors ("no cases
/// found in …"): a check of nothing must not pass.
pub fn load_paths<P: AsRef<Path>>(paths: &[P]) -> Loaded {
    let mut out = Loaded::default();
    let mut read = BTreeSet::new();
    for p in paths {
        let p = p.as_ref();
        if let Some(selected) = crate::builtin::selects(p) {
            let mut any = false;
            for (shown, bytes) in crate::builtin::files() {
                let json = shown.extension().is_some_and(|e| e == "json");
                any |= json && shown.starts_with(&selected);
                if json && shown.starts_with(&selected) && read.insert(shown.clone()) {
                    out.files.push(shown.clone());
                    match std::str::from_utf8(bytes) {
                        Ok(text) => load_text_into(&shown, text, &mut out, true),
                        Err(e) => out.errors.push(file_error(&shown, format!("not UTF-8 text: {e}"))),
                    }
                }
            }
            if !any {
                out.errors.push(file_error(p, "no built-in fixture file or folder of this name".into()));
            }
        } else if std::fs::metadata(p).is_ok_and(|m| m.is_dir()) {
            let mut files = Vec::new();
            collect_json(p, &mut files, &mut BTreeSet::new(), &mut out.errors);
            if files.is_empty() {
                out.errors
                    .push(file_error(p, "no cases found in this folder (no *.json file in it or below it)".into()));
            }
            files.sort();
            for f in files {
                if read.insert(canonical(&f)) {
                    load_file_into(&f, &mut out);
                }
            }
        } else if read.insert(canonical(p)) {
            load_file_into(p, &mut out);
        }
    }
    if out.cases.is_empty() && out.errors.is_empty() {
        let names: Vec<String> = paths.iter().map(|p| p.as_ref().display().to_string()).collect();
        out.errors.push(InputError {
            file: PathBuf::from(names.join(", ")),
            case: None,
            field: None,
            position: None,
            message: "no cases found in the files named (each has an empty `cases`)".into(),
        });
    }
    out
}

/// The canonical path of `p` (links and `..` resolved), or `p` itself when it
/// has none (a missing file: reading it then reports why).
fn canonical(p: &Path) -> PathBuf {
    std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf())
}

fn collect_json(dir: &Path, files: &mut Vec<PathBuf>, walked: &mut BTreeSet<PathBuf>, errors: &mut Vec<InputError>) {
    if !walked.insert(canonical(dir)) {
        return;
    }
    let entries = match std::fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) => {
            errors.push(file_error(dir, format!("cannot read folder: {e}")));
            return;
        }
    };
    let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    paths.sort();
    for path in paths {
        // `metadata` follows links: a link to a folder is walked (once), a link
        // to a file is read (once), and anything else named `*.json` (a FIFO, a
        // device, a broken link) is refused by `load_file_into` with its reason.
        if std::fs::metadata(&path).is_ok_and(|m| m.is_dir()) {
            collect_json(&path, files, walked, errors);
        } else if path.extension().is_some_and(|x| x == "json") {
            files.push(path);
        }
    }
}

fn file_error(file: &Path, message: String) -> InputError {
    InputError { file: file.to_path_buf(), case: None, field: None, position: None, message }
}

/// Reads one file into `out`.
pub fn load_file_into(path: &Path, out: &mut Loaded) {
    out.files.push(path.to_path_buf());
    let text = match read_input(path) {
        Ok(t) => t,
        Err(message) => {
            out.errors.push(file_error(path, message));
            return;
        }
    };
    load_str_into(path, &text, out);
}

/// Checks that `path` is a file crashtest may read: a regular file (a FIFO
/// would block the run, a device such as `/dev/zero` never ends) of at most
/// [`MAX_INPUT_BYTES`]. Returns its size. Nothing is opened. `what` names the
/// file in the message when it cannot be read (`file`, `mesh`).
pub fn check_input_file(path: &Path, what: &str) -> Result<u64, String> {
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read {what}: {e}"))?;
    if !meta.is_file() {
        return Err(format!("not a regular file ({}): refused without reading it", file_kind(&meta)));
    }
    if meta.len() > MAX_INPUT_BYTES {
        return Err(format!(
            "file is {} bytes, over the limit of {MAX_INPUT_TEXT} ({MAX_INPUT_BYTES} bytes) for an input file: refused \
             without reading it",
            meta.len()
        ));
    }
    Ok(meta.len())
}

/// Reads a fixture file whole, after [`check_input_file`]; never more than
/// [`MAX_INPUT_BYTES`] even if the file grows meanwhile.
pub fn read_input(path: &Path) -> Result<String, String> {
    let size = check_input_file(path, "file")?;
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read file: {e}"))?;
    let mut text = String::with_capacity(size as usize);
    file.take(MAX_INPUT_BYTES + 1).read_to_string(&mut text).map_err(|e| format!("cannot read file: {e}"))?;
    if text.len() as u64 > MAX_INPUT_BYTES {
        return Err(format!("file grew past the limit of {MAX_INPUT_TEXT} while being read: refused"));
    }
    Ok(text)
}

/// What a path that is not a regular file is, in words.
fn file_kind(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "a folder";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "not a file"
}

/// The keys of a fixture file's top level.
const FILE_FIELDS: &[&str] = &["schema", "cases"];

/// The top level of a fixture file, read without converting a number: its
/// `schema`, and its `cases` as raw slices. Anything but an object (a bare
/// array of cases, say) is refused, and so is any key but [`FILE_FIELDS`].
struct RawFile<'a> {
    schema: Option<String>,
    cases: Option<Vec<&'a RawValue>>,
}

impl<'de> Deserialize<'de> for RawFile<'de> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Top;
        impl<'de> Visitor<'de> for Top {
            type Value = RawFile<'de>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an object with `schema` and `cases`")
            }
            fn visit_map<M: MapAccess<'de>>(self, mut m: M) -> Result<RawFile<'de>, M::Error> {
                let mut file = RawFile { schema: None, cases: None };
                while let Some(key) = m.next_key::<std::borrow::Cow<'de, str>>()? {
                    match key.as_ref() {
                        "schema" if file.schema.is_none() => file.schema = Some(m.next_value()?),
                        "cases" if file.cases.is_none() => file.cases = Some(m.next_value()?),
                        "schema" | "cases" => return Err(de::Error::custom(format!("duplicate field `{key}`"))),
                        other => return Err(de::Error::unknown_field(other, FILE_FIELDS)),
                    }
                }
                Ok(file)
            }
        }
        d.deserialize_map(Top)
    }
}

/// The field an "unknown field `x`" message names, if it is one.
fn unknown_field(message: &str) -> Option<&str> {
    message.strip_prefix("unknown field `")?.split('`').next()
}

/// A shape is one key, its kind (`{"sphere": {…}}`). serde's own error for a
/// second key does not name it, so the keys are checked here first: the error
/// names the shape's field, the extra key and where the shape starts.
fn check_shape_keys(case_slice: &str) -> Option<(String, usize, String)> {
    let keys: BTreeMap<String, &RawValue> = serde_json::from_str(case_slice).ok()?;
    for slot in ["a", "b"] {
        let Some(raw) = keys.get(slot) else { continue };
        let Ok(shape) = serde_json::from_str::<BTreeMap<String, &RawValue>>(raw.get()) else { continue };
        if shape.len() > 1 {
            let names: Vec<String> = shape.keys().map(|k| format!("`{k}`")).collect();
            let offset = raw.get().as_ptr() as usize - case_slice.as_ptr() as usize;
            return Some((
                slot.to_string(),
                offset,
                format!("a shape has exactly one key, its kind; found {}", names.join(", ")),
            ));
        }
    }
    None
}

#[derive(Deserialize)]
struct NameOnly {
    name: Option<serde_json::Value>,
}

/// Reads fixture text (named `path` in errors; meshes resolved beside `path`).
pub fn load_str_into(path: &Path, text: &str, out: &mut Loaded) {
    load_text_into(path, text, out, false);
}

/// [`load_str_into`]; `embedded`: the text is a built-in fixture's, whose
/// meshes named by `file` are the embedded ones ([`crate::builtin`]).
fn load_text_into(path: &Path, text: &str, out: &mut Loaded, embedded: bool) {
    let raw: RawFile = match serde_json::from_str(text) {
        Ok(r) => r,
        Err(e) => {
            let syntax = e.is_syntax() || e.is_eof();
            out.errors.push(InputError {
                file: path.to_path_buf(),
                case: None,
                // serde_json gives column 0 for an error before the first
                // character of a line (a value of the wrong type at its start).
                position: Some((e.line(), e.column().max(1))),
                message: if syntax { format!("JSON syntax: {e}") } else { format!("not a fixture file: {e}") }
                    .replace(&format!(" at line {} column {}", e.line(), e.column()), ""),
                field: unknown_field(&e.to_string()).map(str::to_string),
            });
            return;
        }
    };
    match raw.schema.as_deref() {
        Some(SCHEMA) => {}
        Some(other) => {
            out.errors.push(InputError {
                field: Some("schema".into()),
                ..file_error(path, format!("unknown schema \"{other}\", expected \"{SCHEMA}\""))
            });
            return;
        }
        None => {
            out.errors.push(InputError {
                field: Some("schema".into()),
                ..file_error(path, format!("missing field, expected \"{SCHEMA}\""))
            });
            return;
        }
    }
    let Some(cases) = raw.cases else {
        out.errors.push(InputError { field: Some("cases".into()), ..file_error(path, "missing field".into()) });
        return;
    };
    let base = path.parent().unwrap_or(Path::new("."));
    let mut names = BTreeSet::new();
    for (i, rawcase) in cases.iter().enumerate() {
        let slice = rawcase.get();
        let offset = slice.as_ptr() as usize - text.as_ptr() as usize;
        let label = match serde_json::from_str::<NameOnly>(slice).ok().and_then(|n| n.name) {
            Some(serde_json::Value::String(s)) => s,
            _ => format!("#{i}"),
        };
        let err = |field: Option<String>, position, message: String| InputError {
            file: path.to_path_buf(),
            case: Some(label.clone()),
            field,
            position,
            message,
        };
        if let Some((field, at, msg)) = check_shape_keys(slice) {
            out.errors.push(err(Some(field), Some(absolute(text, offset + at, 1, 1)), msg));
            continue;
        }
        let mut de = serde_json::Deserializer::from_str(slice);
        let case: Case = match serde_path_to_error::deserialize(&mut de) {
            Ok(c) => c,
            Err(e) => {
                let path = e.path().to_string();
                let inner = e.into_inner();
                let pos = absolute(text, offset, inner.line(), inner.column());
                let msg = inner.to_string();
                let msg = msg.split(" at line ").next().unwrap_or(&msg).to_string();
                // An unknown key's field is the key itself, inside the object
                // the path names.
                let field = match (unknown_field(&msg), path.as_str()) {
                    (Some(key), ".") => Some(key.to_string()),
                    (Some(key), p) if !p.ends_with(key) => Some(format!("{p}.{key}")),
                    (_, ".") => None,
                    _ => Some(path.clone()),
                };
                out.errors.push(err(field, Some(pos), msg));
                continue;
            }
        };
        if !names.insert(case.name.clone()) {
            out.errors.push(err(Some("name".into()), None, "duplicate case name in this file".into()));
            continue;
        }
        if let Err((field, msg)) = validate(&case) {
            out.errors.push(err(Some(field), None, msg));
            continue;
        }
        let mut meshes = [None, None];
        let mut failed = false;
        for (slot, (key, shape)) in [("a", Some(&case.a)), ("b", case.b.as_ref())].into_iter().enumerate() {
            if let Some(Shape::Mesh(m)) = shape {
                match resolve_mesh(m, base, embedded) {
                    Ok(mesh) => meshes[slot] = Some(mesh),
                    Err((field, msg)) => {
                        out.errors.push(err(Some(format!("{key}.mesh.{field}")), None, msg));
                        failed = true;
                    }
                }
            }
        }
        if failed {
            continue;
        }
        out.cases.push(LoadedCase { file: path.to_path_buf(), case, meshes });
    }
}

/// Line and column in the whole text of a (line, column) inside the slice that
/// starts at byte `offset`.
fn absolute(text: &str, offset: usize, line: usize, column: usize) -> (usize, usize) {
    let before = &text[..offset];
    let start_line = before.matches('\n').count() + 1;
    let start_col = offset - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    if line <= 1 { (start_line, start_col + column.saturating_sub(1)) } else { (start_line + line - 1, column) }
}

fn resolve_mesh(m: &MeshSpec, base: &Path, embedded: bool) -> Result<Mesh, (String, String)> {
    match (&m.vertices, &m.triangles, &m.file) {
        (Some(v), Some(t), None) => Mesh::new(v.clone(), t.clone()),
        (None, None, Some(f)) if embedded => {
            let path = base.join(f);
            let bytes = crate::builtin::file(&path)
                .ok_or_else(|| ("file".to_string(), format!("{}: not among the built-in fixtures", path.display())))?;
            crate::mesh::load_mesh_bytes(&path, bytes).map_err(|m| ("file".to_string(), m))
        }
        (None, None, Some(f)) => {
            let path = base.join(f);
            check_input_file(&path, "mesh").map_err(|m| ("file".to_string(), format!("{}: {m}", path.display())))?;
            load_mesh_file(&path).map_err(|m| ("file".to_string(), m))
        }
        (_, _, Some(_)) => Err(("file".into(), "give either `file` or `vertices` and `triangles`, not both".into())),
        (None, _, None) => Err(("vertices".into(), "missing field (or give `file`)".into())),
        (Some(_), None, None) => Err(("triangles".into(), "missing field".into())),
    }
}

type FieldResult = Result<(), (String, String)>;

fn bad(field: impl Into<String>, msg: impl Into<String>) -> FieldResult {
    Err((field.into(), msg.into()))
}

fn finite3(field: &str, v: &P3) -> FieldResult {
    for (i, x) in v.iter().enumerate() {
        if !x.is_finite() {
            return bad(format!("{field}[{i}]"), "not a finite number");
        }
    }
    Ok(())
}

fn finite(field: &str, x: f64) -> FieldResult {
    if x.is_finite() { Ok(()) } else { bad(field, "not a finite number") }
}

fn validate_shape(key: &str, shape: &Shape, query: Query) -> FieldResult {
    let k = format!("{key}.{}", shape.kind());
    let velocity = |v: &Option<P3>| match v {
        Some(v) => finite3(&format!("{k}.velocity"), v),
        None => Ok(()),
    };
    match shape {
        Shape::Sphere(s) => {
            finite3(&format!("{k}.center"), &s.center)?;
            finite(&format!("{k}.radius"), s.radius)?;
            if s.radius <= 0.0 {
                return bad(format!("{k}.radius"), format!("radius must be > 0, got {}", s.radius));
            }
            velocity(&s.velocity)?;
            if let Some(m) = s.mass {
                finite(&format!("{k}.mass"), m)?;
                if m <= 0.0 {
                    return bad(format!("{k}.mass"), format!("mass must be > 0, got {m}"));
                }
            }
            if query == Query::Response && s.mass.is_none() {
                return bad(format!("{k}.mass"), "missing field (response needs masses)");
            }
        }
        Shape::Plane(p) => {
            finite3(&format!("{k}.normal"), &p.normal)?;
            finite(&format!("{k}.offset"), p.offset)?;
            #[allow(clippy::float_cmp, reason = "the format refuses exactly the zero normal (either sign of zero)")]
            if p.normal == [0.0; 3] {
                return bad(format!("{k}.normal"), "zero normal");
            }
            velocity(&p.velocity)?;
        }
        Shape::Segment(s) => {
            finite3(&format!("{k}.start"), &s.start)?;
            finite3(&format!("{k}.end"), &s.end)?;
        }
        Shape::Triangle(t) => {
            for (i, v) in t.vertices.iter().enumerate() {
                finite3(&format!("{k}.vertices[{i}]"), v)?;
            }
            velocity(&t.velocity)?;
        }
        Shape::Point(p) => finite3(&format!("{k}.at"), &p.at)?,
        Shape::Convex(c) => {
            if c.points.is_empty() {
                return bad(format!("{k}.points"), "needs at least one point");
            }
            for (i, v) in c.points.iter().enumerate() {
                finite3(&format!("{k}.points[{i}]"), v)?;
            }
        }
        Shape::Points(p) => {
            if p.points.is_empty() {
                return bad(format!("{k}.points"), "needs at least one point");
            }
            for (i, v) in p.points.iter().enumerate() {
                finite3(&format!("{k}.points[{i}]"), v)?;
            }
        }
        Shape::Mesh(m) => {
            // Inline meshes are checked where they are built (indices, finiteness);
            // here only what a file mesh shares with them.
            velocity(&m.velocity)?;
        }
        Shape::Aabb(b) => {
            finite3(&format!("{k}.min"), &b.min)?;
            finite3(&format!("{k}.max"), &b.max)?;
            for i in 0..3 {
                if b.min[i] > b.max[i] {
                    return bad(format!("{k}.min[{i}]"), format!("min {} > max {}", b.min[i], b.max[i]));
                }
            }
        }
        Shape::MovingPoint(p) => {
            finite3(&format!("{k}.t0"), &p.t0)?;
            finite3(&format!("{k}.t1"), &p.t1)?;
        }
        Shape::MovingSegment(s) => {
            for (end, at) in [("t0", &s.t0), ("t1", &s.t1)] {
                for (i, v) in at.iter().enumerate() {
                    finite3(&format!("{k}.{end}[{i}]"), v)?;
                }
            }
        }
        Shape::MovingTriangle(t) => {
            for (end, at) in [("t0", &t.t0), ("t1", &t.t1)] {
                for (i, v) in at.iter().enumerate() {
                    finite3(&format!("{k}.{end}[{i}]"), v)?;
                }
            }
        }
        Shape::Box(b) => {
            velocity(&b.velocity)?;
            finite3(&format!("{k}.center"), &b.center)?;
            finite3(&format!("{k}.half_extents"), &b.half_extents)?;
            for (i, h) in b.half_extents.iter().enumerate() {
                if *h < 0.0 {
                    return bad(format!("{k}.half_extents[{i}]"), format!("half-extent must be ≥ 0, got {h}"));
                }
            }
            if let Some(q) = &b.rotation {
                for (i, x) in q.iter().enumerate() {
                    finite(&format!("{k}.rotation[{i}]"), *x)?;
                }
                if q.iter().all(|x| *x == 0.0) {
                    return bad(format!("{k}.rotation"), "zero quaternion (no rotation)");
                }
            }
        }
        Shape::Capsule(c) => {
            finite3(&format!("{k}.start"), &c.start)?;
            finite3(&format!("{k}.end"), &c.end)?;
            finite(&format!("{k}.radius"), c.radius)?;
            if c.radius <= 0.0 {
                return bad(format!("{k}.radius"), format!("radius must be > 0, got {}", c.radius));
            }
        }
    }
    Ok(())
}

/// The `expect` fields that belong to each query.
fn expect_fields(query: Query) -> &'static [&'static str] {
    match query {
        Query::Contact => &["contact", "degenerate"],
        Query::Intersect => &["hit", "parallel", "degenerate"],
        Query::Barycentric => &["barycentric", "degenerate"],
        Query::Bounds => &["aabb", "min_radius", "degenerate"],
        Query::Overlap => &["overlap", "degenerate"],
        Query::Toi => &["toi", "degenerate"],
        Query::Response => &["velocity_a", "velocity_b", "degenerate"],
        Query::Ccd => &["ccd", "impact", "degenerate"],
        Query::Distance => &["distance", "point_a", "point_b", "normal", "degenerate"],
    }
}

fn named_fields(e: &Expect) -> Vec<&'static str> {
    let mut v = Vec::new();
    let mut add = |present: bool, name| {
        if present {
            v.push(name)
        }
    };
    add(e.contact.is_some(), "contact");
    add(e.hit.is_some(), "hit");
    add(e.parallel.is_some(), "parallel");
    add(e.degenerate.is_some(), "degenerate");
    add(e.barycentric.is_some(), "barycentric");
    add(e.aabb.is_some(), "aabb");
    add(e.min_radius.is_some(), "min_radius");
    add(e.overlap.is_some(), "overlap");
    add(e.toi.is_some(), "toi");
    add(e.velocity_a.is_some(), "velocity_a");
    add(e.velocity_b.is_some(), "velocity_b");
    add(e.impact.is_some(), "impact");
    add(e.ccd.is_some(), "ccd");
    add(e.distance.is_some(), "distance");
    add(e.point_a.is_some(), "point_a");
    add(e.point_b.is_some(), "point_b");
    add(e.normal.is_some(), "normal");
    v
}

/// Checks what the types cannot; the error is `(field path, message)`.
pub fn validate(case: &Case) -> FieldResult {
    if case.name.is_empty() {
        return bad("name", "empty name");
    }
    let b_kind = case.b.as_ref().map(Shape::kind);
    if case.pair().is_none() {
        let field = if case.query == Query::Bounds && case.b.is_some() { "b" } else { "query" };
        return bad(
            field,
            format!(
                "query `{}` does not take a = {}{}",
                case.query,
                case.a.kind(),
                b_kind.map(|k| format!(", b = {k}")).unwrap_or_else(|| ", no b".into())
            ),
        );
    }
    validate_shape("a", &case.a, case.query)?;
    if let Some(b) = &case.b {
        validate_shape("b", b, case.query)?;
    }
    if let Some(t) = case.tol
        && !(t.is_finite() && t >= 0.0)
    {
        return bad("tol", format!("tolerance must be finite and ≥ 0, got {t}"));
    }
    if let Some(t) = case.t_max
        && !(t.is_finite() && t >= 0.0)
    {
        return bad("t_max", format!("t_max must be finite and ≥ 0, got {t}"));
    }
    if let Some(t) = case.t_max
        && case.query == Query::Ccd
        && t > 1.0
    {
        return bad("t_max", format!("a ccd case's t_max is within [0, 1] (the motion is given at 0 and 1), got {t}"));
    }
    match case.restitution {
        Some(e) if !(e.is_finite() && (0.0..=1.0).contains(&e)) => {
            return bad("restitution", format!("restitution must be in [0, 1], got {e}"));
        }
        None if case.query == Query::Response => return bad("restitution", "missing field"),
        _ => {}
    }
    if let Some(e) = &case.expect {
        let allowed = expect_fields(case.query);
        for f in named_fields(e) {
            if !allowed.contains(&f) {
                return bad(format!("expect.{f}"), format!("not an answer of query `{}`", case.query));
            }
        }
        validate_expect(e)?;
    }
    Ok(())
}

fn validate_expect(e: &Expect) -> FieldResult {
    if let Some(Some(c)) = &e.contact {
        finite3("expect.contact.point", &c.point)?;
        finite3("expect.contact.normal", &c.normal)?;
        finite("expect.contact.depth", c.depth)?;
    }
    if let Some(Some(h)) = &e.hit {
        finite("expect.hit.t", h.t)?;
        finite3("expect.hit.point", &h.point)?;
        finite3("expect.hit.normal", &h.normal)?;
        if let Some(b) = &h.barycentric {
            finite3("expect.hit.barycentric", b)?;
        }
    }
    if let Some(b) = &e.barycentric {
        finite3("expect.barycentric", b)?;
    }
    if let Some(b) = &e.aabb {
        finite3("expect.aabb.min", &b.min)?;
        finite3("expect.aabb.max", &b.max)?;
    }
    if let Some(r) = e.min_radius {
        finite("expect.min_radius", r)?;
        if r < 0.0 {
            return bad("expect.min_radius", format!("radius must be ≥ 0, got {r}"));
        }
    }
    if let Some(Some(t)) = &e.toi {
        finite("expect.toi.t", t.t)?;
        finite3("expect.toi.point", &t.point)?;
        finite3("expect.toi.normal", &t.normal)?;
    }
    if let Some(Some(c)) = &e.ccd {
        finite("expect.ccd.t", c.t)?;
    }
    if let (Some(impact), Some(ccd)) = (e.impact, &e.ccd)
        && impact != ccd.is_some()
    {
        return bad("expect.impact", format!("impact {impact} contradicts expect.ccd"));
    }
    for (name, v) in [("expect.velocity_a", &e.velocity_a), ("expect.velocity_b", &e.velocity_b)] {
        if let Some(v) = v {
            finite3(name, v)?;
        }
    }
    Ok(())
}
