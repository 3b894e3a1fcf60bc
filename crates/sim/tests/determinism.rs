//! The same inputs give byte-identical outputs.

mod common;

use sim::{write_outputs, ReportConfig, RobotModel, Scenario};

#[test]
fn same_inputs_give_byte_identical_events_jsonl() {
    let spec = common::default_world();
    let mut sc = Scenario::default_scenario().unwrap();
    sc.time_limit_s = 30.0;
    sc.start.x_m = 11.0;
    let model = RobotModel::builtin(&sc.robot).unwrap();
    let dirs = [tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap()];
    for d in &dirs {
        let outcome = sim::run_scenario(&spec, &sc, &model).unwrap();
        write_outputs(d.path(), &outcome, &ReportConfig::default()).unwrap();
    }
    for name in ["events.jsonl", "trajectory.csv", "report.md"] {
        let a = std::fs::read(dirs[0].path().join(name)).unwrap();
        let b = std::fs::read(dirs[1].path().join(name)).unwrap();
        assert!(a.len() > 100, "{name} is nearly empty");
        assert!(a == b, "{name} differs between two identical runs");
    }
    let events = std::fs::read_to_string(dirs[0].path().join("events.jsonl")).unwrap();
    let first = events.lines().next().unwrap();
    assert!(first.starts_with(r#"{"time_s":0.0167,"kind":"movement","entities":[{"id":31,"class":"robot","name":"robot"}],"detail":"","values":{"x_m":"#), "{first}");
    for line in events.lines() {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        assert!(v["time_s"].is_number() && v["kind"].is_string());
    }
}
