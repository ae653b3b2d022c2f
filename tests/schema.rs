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
