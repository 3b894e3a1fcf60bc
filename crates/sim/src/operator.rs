//! Operator control of a running simulation: a person's drive command that overrides the
//! scenario's scripted commands (timed velocities, waypoints) while it is set, and what a live
//! session needs besides (the robot's drive limits, marking a run interrupted when it is saved
//! before its end). The simulation stays deterministic: the same commands set before the same
//! steps give bit-identical results.

use crate::simulation::Simulation;

impl Simulation {
    /// Drives the robot at `(linear m/s, angular rad/s)` from the next step on instead of the
    /// scenario's commands; the motors clamp it to the robot's limits ([`Simulation::drive_limits`]),
    /// and a non-finite number counts as 0. `None` hands the robot back to the scenario.
    ///
    /// ```
    /// # let building = scanner::Building::from_toml_str(r#"
    /// #     [floor]
    /// #     min_m = [0.0, -2.0]
    /// #     max_m = [6.0, 2.0]
    /// #     [ceiling]
    /// #     height_m = 2.5
    /// # "#, std::path::Path::new("tiny.toml")).unwrap();
    /// # let spec = sim::WorldSpec::from_building(&building).unwrap();
    /// # let scenario = sim::Scenario::from_toml_str(r#"
    /// #     time_limit_s = 2.0
    /// #     start = { x_m = 1.0, y_m = 0.0, yaw_deg = 0.0 }
    /// # "#, "doctest").unwrap();
    /// # let model = sim::RobotModel::builtin("pioneer3at").unwrap();
    /// let mut sim = sim::Simulation::new(&spec, &scenario, &model).unwrap();
    /// sim.set_operator_drive(Some((0.5, 0.0)));
    /// sim.run_until(1.5);
    /// assert!(sim.robot_pose().x_m > 1.2);
    /// ```
    pub fn set_operator_drive(&mut self, command: Option<(f64, f64)>) {
        let finite = |x: f64| if x.is_finite() { x } else { 0.0 };
        self.operator = command.map(|(v, w)| (finite(v), finite(w)));
    }

    /// The operator's command, if the operator drives.
    pub fn operator_drive(&self) -> Option<(f64, f64)> {
        self.operator
    }

    /// The robot's drive limits: (top speed m/s, top yaw rate rad/s); zeros without a robot.
    pub fn drive_limits(&self) -> (f64, f64) {
        self.world
            .robots
            .first()
            .map(|r| (r.drive.max_speed_mps, r.drive.max_yaw_rate_radps))
            .unwrap_or((0.0, 0.0))
    }

    /// Marks the run interrupted now, as a stopped [`Simulation::run_with`] does: the verdict
    /// and the outcome say so (rules not decided yet fail as not decided) until the next step.
    /// For saving a live session before its end.
    pub fn interrupt(&mut self) {
        self.interrupted_at_s = Some(self.time_s());
    }
}
