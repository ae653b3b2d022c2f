//! Engines listed in an engines file: named commands speaking
//! `crashtest-engine/1`, each with the known divergences it carries. The same
//! format serves `--engines-file` and the peer engines crashtest ships adapters
//! for (`engines/engines.json`).
//!
//! ```json
//! {
//!   "install": "engines/install",
//!   "engines": {
//!     "mine": ["./my-engine", "--fast"],
//!     "fcl": { "command": ["{here}/.venv/bin/python", "{here}/fcl/engine.py"], "known": "{here}/fcl/known.json" }
//!   }
//! }
//! ```
//!
//! An entry is a command (program and arguments) or an object with `command`
//! and `known` (a `crashtest-known/1` file: [`crate::divergence::DataRule`]).
//! `{here}` in a command or a path is the engines file's folder. An engine whose
//! program is a path that does not exist is *not installed*: a run over `all`
//! leaves it out and its report says so, with `install` (the command that
//! installs it), and naming it is an error that says the same.

use crate::divergence::{DataRule, Known, load_known};
use crate::engine::Engine;
use crate::protocol::client::{ProcessEngine, ProcessSpec};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// One engine of an engines file.
#[derive(Clone, Debug)]
pub struct Listed {
    /// How to run it.
    pub spec: ProcessSpec,
    /// The known divergences it carries (from its `known` file).
    pub known: Vec<DataRule>,
    /// Why it is not installed, and how to install it; `None` when it is.
    pub missing: Option<String>,
    /// Its `known` file, if it names one.
    pub known_file: Option<PathBuf>,
}

impl Listed {
    /// Starts it (see [`ProcessEngine::start`]: an engine that cannot start is
    /// returned marked down) as an engine carrying its known divergences.
    pub fn start(self) -> Engine {
        let known = Known::data(self.known);
        Engine::from_process(ProcessEngine::start(self.spec)).with_known(known)
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EnginesFile {
    #[serde(default)]
    install: Option<String>,
    #[serde(deserialize_with = "in_file_order")]
    engines: Vec<(String, Entry)>,
}

/// The engines of the file, in the file's order (the report's order).
fn in_file_order<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<(String, Entry)>, D::Error> {
    struct Named;
    impl<'de> serde::de::Visitor<'de> for Named {
        type Value = Vec<(String, Entry)>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("an object of named engines")
        }
        fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
            let mut out = Vec::new();
            while let Some(entry) = map.next_entry::<String, Entry>()? {
                out.push(entry);
            }
            Ok(out)
        }
    }
    d.deserialize_map(Named)
}

#[derive(Deserialize)]
#[serde(untagged)]
enum Entry {
    Command(Vec<String>),
    Full(Full),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Full {
    command: Vec<String>,
    #[serde(default)]
    known: Option<String>,
}

/// Reads an engines file. The error names the file and the field (line and
/// column for JSON syntax). An engine whose known-divergences file does not
/// read is returned with that as the reason it is [`Listed::missing`].
pub fn read(path: &Path) -> Result<Vec<Listed>, String> {
    let at = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| format!("{at}: cannot read: {e}"))?;
    let de = &mut serde_json::Deserializer::from_str(&text);
    let file: EnginesFile = serde_path_to_error::deserialize(de).map_err(|e| {
        let field = e.path().to_string();
        let inner = e.into_inner();
        if inner.is_syntax() || inner.is_eof() {
            format!("{at}: line {} column {}: {inner}", inner.line(), inner.column())
        } else if inner.to_string().starts_with("data did not match any variant") {
            format!("{at}: field `{field}`: expected a command ([\"program\", \"arg\", …]) or {{\"command\": […], \"known\": \"file\"}}")
        } else {
            format!("{at}: field `{field}`: {inner}")
        }
    })?;
    let here = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let here_text = here.to_string_lossy();
    let fill = |s: &str| s.replace("{here}", &here_text);
    let mut out = Vec::new();
    for (name, entry) in file.engines {
        let (command, known) = match entry {
            Entry::Command(c) => (c, None),
            Entry::Full(f) => (f.command, f.known),
        };
        let words: Vec<String> = command.iter().map(|w| fill(w)).collect();
        let spec = ProcessSpec::new(&name, words).map_err(|e| format!("{at}: engines.{name}: {e}"))?;
        let known_file = known.map(|k| PathBuf::from(fill(&k)));
        // Known divergences that do not read leave the engine out (named, it is
        // an error that says why; under `all` the report says so), and the rest
        // of the run goes on.
        let (rules, unreadable) = match &known_file {
            Some(k) => match load_known(k) {
                Ok(r) => (r, None),
                Err(e) => {
                    (Vec::new(), Some(format!("its known divergences do not read: {at}: engines.{name}.known: {e}")))
                }
            },
            None => (Vec::new(), None),
        };
        let program = Path::new(&spec.program);
        let missing = (program.components().count() > 1 && !program.exists())
            .then(|| {
                let how = file.install.as_deref().map(|i| format!("; install it with `{i}`")).unwrap_or_default();
                format!("not installed (`{}` does not exist){how}", spec.program)
            })
            .or(unreadable);
        out.push(Listed { spec, known: rules, missing, known_file });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(name: &str, text: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("crashtest-listed-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join(name);
        std::fs::write(&path, text).expect("write");
        path
    }

    #[test]
    fn an_engines_file_fills_here_and_says_what_is_not_installed() {
        let known = write("k.json", r#"{"schema": "crashtest-known/1", "known": []}"#);
        let path = write(
            "engines.json",
            r#"{"install": "engines/install", "engines": {
                "plain": ["python3", "{here}/engine.py"],
                "gone": {"command": ["{here}/nowhere/python", "x.py"], "known": "{here}/k.json"}}}"#,
        );
        let listed = read(&path).expect("reads");
        let here = path.parent().expect("folder").display().to_string();
        let plain = listed.iter().find(|l| l.spec.name == "plain").expect("plain");
        assert_eq!(plain.spec.program, "python3");
        assert_eq!(plain.spec.args, [format!("{here}/engine.py")]);
        assert!(plain.missing.is_none(), "a program found on the path is taken as installed");
        let gone = listed.iter().find(|l| l.spec.name == "gone").expect("gone");
        let why = gone.missing.as_deref().expect("missing");
        assert!(why.contains("nowhere/python") && why.contains("install it with `engines/install`"), "{why}");
        assert_eq!(gone.known_file.as_deref(), Some(known.as_path()));
    }

    #[test]
    fn a_bad_engines_file_is_refused_naming_the_field() {
        let path = write("bad1.json", r#"{"engines": {"x": {"command": ["p"], "knwn": "k"}}}"#);
        let err = read(&path).expect_err("unknown key");
        assert!(err.contains("bad1.json") && err.contains("engines.x"), "{err}");
        let path = write("bad2.json", r#"{"engines": {"x": {"command": ["p"], "known": "{here}/none.json"}}}"#);
        let listed = read(&path).expect("the file reads; its engine is left out");
        let why = listed[0].missing.as_deref().unwrap_or("");
        assert!(why.contains("engines.x.known") && why.contains("none.json: cannot read"), "{why}");
        let path = write("bad3.json", "{\"engines\": {\"x\": [\"p\"]}");
        let err = read(&path).expect_err("syntax");
        assert!(err.contains("bad3.json: line 1 column"), "{err}");
    }

    #[test]
    fn the_engines_keep_the_order_of_the_file() {
        let path = write("order.json", r#"{"engines": {"zeta": ["z"], "alpha": ["a"], "mid": ["m"]}}"#);
        let names: Vec<String> = read(&path).expect("reads").into_iter().map(|l| l.spec.name).collect();
        assert_eq!(names, ["zeta", "alpha", "mid"]);
    }
}
