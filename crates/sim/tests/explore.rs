use sim::*;

fn show(o: &Outcome) {
    for e in o.events.iter().filter(|e| e.kind.is_significant()) {
        println!("{}", e.to_json_line());
    }
    let last = o.trajectory.last().unwrap();
    println!("final {:?}", last);
    for r in &o.verdict.rules { println!("{:?}", r); }
}

#[test]
fn explore_default() {
    let b = scanner::Building::default_building().unwrap();
    let spec = WorldSpec::from_building(&b).unwrap();
    let sc = Scenario::default_scenario().unwrap();
    let m = RobotModel::builtin(&sc.robot).unwrap();
    let t = std::time::Instant::now();
    let o = run_scenario(&spec, &sc, &m).unwrap();
    println!("wall {:?}", t.elapsed());
    show(&o);
    for p in o.trajectory.iter().step_by(10) { println!("{:.1} {:.2} {:.2} {:.2} r{:.1} p{:.1} y{:.1} v{:.2}", p.time_s, p.pose.x_m, p.pose.y_m, p.pose.z_m, p.pose.roll_deg, p.pose.pitch_deg, p.pose.yaw_deg, p.pose.speed_mps); }
}
