//! An evaluation as a table for people (`semsim eval map` prints it).

use crate::Evaluation;
use std::fmt;

impl fmt::Display for Evaluation {
    /// Per-class expected / detected / matched counts with precision, recall and F1, the wall
    /// endpoint errors, each staircase's steps and rise/run errors, and what was missed or spurious.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{:<16} {:>8} {:>8} {:>8} {:>6} {:>6} {:>6}",
            "class", "expected", "detected", "matched", "P", "R", "F1"
        )?;
        for (name, s) in [
            ("walls", &self.walls),
            ("door openings", &self.door_openings),
            ("door leaves", &self.doors),
            ("floor", &self.floor),
            ("ceiling", &self.ceiling),
            ("stairs", &self.stairs),
            ("obstacles", &self.obstacles),
            ("columns", &self.columns),
            ("beams", &self.beams),
            ("ramps", &self.ramps),
        ] {
            writeln!(
                f,
                "{name:<16} {:>8} {:>8} {:>8} {:>6.3} {:>6.3} {:>6.3}",
                s.expected, s.detected, s.matched, s.precision, s.recall, s.f1
            )?;
        }
        write!(
            f,
            "wall endpoint error: mean {:.3} m, max {:.3} m",
            self.wall_endpoint_error_mean_m, self.wall_endpoint_error_max_m
        )?;
        write!(
            f,
            "\nwall length: {:.2} of {:.2} m covered ({:.3})",
            self.wall_length.covered_m, self.wall_length.expected_m, self.wall_length.recall
        )?;
        write!(
            f,
            "\nwalls on beams or columns: {}",
            self.walls_on_beams_or_columns
        )?;
        for s in &self.stairs_matches {
            write!(
                f,
                "\nstairs {}: {} steps (truth {}), rise error {:+.3} m, run error {:+.3} m",
                s.truth, s.steps, s.steps_truth, s.rise_error_m, s.run_error_m
            )?;
        }
        for r in &self.ramp_matches {
            write!(
                f,
                "\nramp {}: pitch error {:+.2} deg, rise error {:+.3} m",
                r.truth, r.pitch_error_deg, r.rise_error_m
            )?;
        }
        for s in self.stairs_seen.iter().filter(|s| s.steps_seen < s.steps) {
            write!(
                f,
                "\nstairs {}: the scans saw {} of its {} steps",
                s.truth, s.steps_seen, s.steps
            )?;
        }
        if !self.missed.is_empty() {
            write!(f, "\nmissed: {}", self.missed.join(", "))?;
        }
        if !self.spurious.is_empty() {
            write!(f, "\nspurious entity ids: {:?}", self.spurious)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::Evaluation;

    #[test]
    fn the_table_lists_every_class_and_what_was_missed() {
        let mut ev = Evaluation::default();
        ev.walls.f1 = 0.5;
        ev.missed = vec!["walls[3]".into()];
        let text = ev.to_string();
        for want in [
            "class",
            "walls",
            "door openings",
            "stairs",
            "0.500",
            "wall endpoint error",
            "wall length",
            "obstacles",
            "beams",
            "ramps",
            "walls on beams or columns: 0",
            "missed: walls[3]",
        ] {
            assert!(text.contains(want), "{want} in {text}");
        }
    }
}
