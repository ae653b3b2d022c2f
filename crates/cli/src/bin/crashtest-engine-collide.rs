//! `crashtest-engine-collide [ENGINE]`: one of collide's engines
//! (`collide/robust` by default; `collide/lecture`, `collide-f32/robust`,
//! `collide-f32/lecture`) behind `crashtest-engine/1` (docs/PROTOCOL.md), on
//! standard input and output. Its answers through the protocol are bit-identical
//! to the in-process ones (crates/cli/tests/protocol.rs).

use std::process::ExitCode;

fn main() -> ExitCode {
    let name = std::env::args().nth(1).unwrap_or_else(|| harness::engines::DEFAULT_ENGINE.to_string());
    let Some(engine) =
        harness::engines::judged().into_iter().find(|e| harness::engines::is_collide(e) && e.name == name)
    else {
        eprintln!(
            "error: `{name}` is not one of collide's engines (collide/robust, collide/lecture, collide-f32/robust, collide-f32/lecture)"
        );
        return ExitCode::from(2);
    };
    let served = harness::serve::Served {
        version: engine.version.clone(),
        capabilities: crashtest::Pair::ALL.to_vec(),
        provenance: [("served by".to_string(), "crashtest-engine-collide".to_string())].into(),
    };
    // A large read buffer: a batch arrives in a few reads, not hundreds.
    let input = std::io::BufReader::with_capacity(harness::protocol::client::PIPE_BUFFER, std::io::stdin());
    match harness::serve::serve(&engine, &served, input, std::io::stdout().lock()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}
