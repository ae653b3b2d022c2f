//! The committed JSON Schema of the fixture format is the one the types generate.

#[test]
fn committed_schema_is_current() {
    let committed = std::fs::read_to_string("schema/crashtest-fixture-1.schema.json").unwrap_or_default();
    let generated = harness::case::json_schema();
    assert!(
        committed == generated,
        "schema/crashtest-fixture-1.schema.json is stale: regenerate it with\n  cargo run -- schema > schema/crashtest-fixture-1.schema.json"
    );
}

/// The committed JSON Schema of the engine protocol's messages is the one the
/// types generate.
#[test]
fn committed_protocol_schema_is_current() {
    let committed = std::fs::read_to_string("schema/crashtest-engine-1.schema.json").unwrap_or_default();
    let generated = harness::protocol::messages::json_schema();
    assert!(
        committed == generated,
        "schema/crashtest-engine-1.schema.json is stale: regenerate it with\n  cargo run -- schema --protocol > schema/crashtest-engine-1.schema.json"
    );
}
