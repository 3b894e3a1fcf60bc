//! The configuration of the obstacle, column and beam stage (see the `obstacles` module).

use crate::error::Result;
use cloud::check_range;
use serde::{Deserialize, Serialize};

/// Configuration of the obstacle, column and beam stage.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ObstacleConfig {
    /// Edge of the occupancy grid's cells. 10 cm: finer than any gap a robot passes through,
    /// coarser than the spacing of a 0.25-0.5 degree laser's returns within ~10 m, so that one
    /// surface fills its cells.
    pub cell_m: f64,
    /// Points this far above the floor at least: twice the floor's labelling tolerance
    /// (4 cm), above the laser's range noise (1-2 cm) and a levelling residue.
    pub min_above_floor_m: f64,
    /// ... and this far under the ceiling at least (lamps and sprinklers flush with it).
    pub below_ceiling_m: f64,
    /// Bands split here: a beam's underside is above it. 1.95 m: above the stature of 99 % of
    /// adults (~1.90 m) and under the 2.0-2.1 m door heights and 2.0 m minimum headroom of
    /// building codes, so what is above passes over people and robots.
    pub head_height_m: f64,
    /// Points this far off a wall's slab still belong to the wall (face noise and roughness).
    pub wall_margin_m: f64,
    /// Fewest points in an occupied cell (a single return in a cell is a stray or mixed pixel).
    pub min_cell_points: usize,
    /// Fewest points of a cluster: an object of 0.1 m x 0.1 m seen within 10 m by a 0.5 degree
    /// laser gets a few returns per line over several lines; fewer are noise.
    pub min_points: usize,
    /// A column is at most this across (pillars of buildings are 0.2-0.8 m).
    pub column_max_across_m: f64,
    /// A column's bottom and top within this of the floor and ceiling reach them (the bands
    /// above are left out, and the ceiling's junction is often unseen).
    pub full_height_margin_m: f64,
    /// A beam is at least this long (and twice as long as wide).
    pub beam_min_length_m: f64,
    /// A low cluster's top climbs through points above head height with gaps up to this:
    /// a few of a laser's line spacings at 10 m (0.5-1 degree, 9-17 cm).
    pub max_vertical_gap_m: f64,
    /// Neighbouring cells whose tops differ by more than this are of different things (or
    /// parts, put together again when one lies within the other). One cell (10 cm): a surface
    /// sloping up to 45 degrees changes its top by at most that from cell to cell, and the
    /// laser's range noise (1-3 cm) by much less; the things a building holds step by more
    /// (seat 0.45 m, desk 0.72-0.76 m, backrest 0.85-0.9 m, car bonnet to roof ~0.5 m).
    pub max_top_step_m: f64,
    /// A cluster at most this thin, parallel to a wall (or as thin both ways) and within
    /// `wall_margin_m` plus this of its faces' planes, is the wall's residue: twice the wall margin's allowance for face noise.
    /// Thin things do stand against walls (pipes, radiators, skirting), but at this depth
    /// they are the wall to a robot.
    pub sliver_max_across_m: f64,
    /// A partial-height wall is at most this thick: walls and partitions are 0.05-0.25 m;
    /// a cabinet, a shelf or a car is deeper (and one seen from its front only reaches back
    /// to the wall behind it, step 5).
    pub partition_max_thickness_m: f64,
    /// ... at least this long (and four times as long as thick) ...
    pub partition_min_length_m: f64,
    /// ... at least this high above the floor: a partition or a parapet is 1.0-1.8 m; lower,
    /// it is a kerb or a bench to a robot, an obstacle all the same.
    pub partition_min_height_m: f64,
    /// ... its face seen down to this height above the floor: a wall stands on the floor,
    /// while a car's body is 0.2-0.3 m clear of it between the wheels, and furniture stands
    /// on legs or a recessed plinth ...
    pub partition_max_bottom_m: f64,
    /// ... and up to its top, along at least this fraction of its length (a row of things side
    /// by side has gaps; a wall's face is hidden in places by what stands before it).
    pub partition_min_standing: f64,
    /// A slab along a wall nearer to its face than this is a cabinet's or shelf's front, not
    /// a partition: 0.7 m, about the narrowest passage a person walks (building codes ask
    /// 0.8-0.9 m for a corridor).
    pub partition_min_passage_m: f64,
    /// ... and the floor is seen beside it on both sides along at least this fraction of its
    /// length: it divides space, while the face of a block (a car, a crate, a cabinet seen from
    /// one side) has the block's unseen footprint behind it. (A panel seen from one side and
    /// round its free end needs the floor seen on its side along as much of it.)
    pub partition_min_floor_both_sides: f64,
    /// A cluster thicker than a partition may be one with things standing against it (a desk
    /// pushed against it, a chair's back touching it): the slab of its returns this thick
    /// holding the most of them is looked at as a partition. A panel's two faces (0.05-0.12
    /// m apart) and the registration's spread of them (1-2 cm).
    pub partition_slab_m: f64,
}

impl Default for ObstacleConfig {
    fn default() -> Self {
        ObstacleConfig {
            cell_m: 0.1,
            min_above_floor_m: 0.08,
            below_ceiling_m: 0.1,
            head_height_m: 1.95,
            wall_margin_m: 0.1,
            min_cell_points: 2,
            min_points: 15,
            column_max_across_m: 1.0,
            full_height_margin_m: 0.35,
            beam_min_length_m: 1.0,
            max_vertical_gap_m: 0.3,
            max_top_step_m: 0.1,
            sliver_max_across_m: 0.2,
            partition_max_thickness_m: 0.25,
            partition_min_length_m: 1.0,
            partition_min_height_m: 1.0,
            partition_max_bottom_m: 0.15,
            partition_min_standing: 0.7,
            partition_min_passage_m: 0.7,
            partition_min_floor_both_sides: 0.5,
            partition_slab_m: 0.15,
        }
    }
}

impl ObstacleConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "obstacles.cell_m",
            self.cell_m,
            0.01,
            1.0,
            "within 0.01..1 m",
        )?;
        for (name, v) in [
            ("obstacles.min_above_floor_m", self.min_above_floor_m),
            ("obstacles.below_ceiling_m", self.below_ceiling_m),
            ("obstacles.head_height_m", self.head_height_m),
            ("obstacles.wall_margin_m", self.wall_margin_m),
            ("obstacles.column_max_across_m", self.column_max_across_m),
            ("obstacles.full_height_margin_m", self.full_height_margin_m),
            ("obstacles.beam_min_length_m", self.beam_min_length_m),
            ("obstacles.max_vertical_gap_m", self.max_vertical_gap_m),
            ("obstacles.max_top_step_m", self.max_top_step_m),
            ("obstacles.sliver_max_across_m", self.sliver_max_across_m),
            (
                "obstacles.partition_max_thickness_m",
                self.partition_max_thickness_m,
            ),
            (
                "obstacles.partition_min_length_m",
                self.partition_min_length_m,
            ),
            (
                "obstacles.partition_min_height_m",
                self.partition_min_height_m,
            ),
            (
                "obstacles.partition_max_bottom_m",
                self.partition_max_bottom_m,
            ),
            (
                "obstacles.partition_min_passage_m",
                self.partition_min_passage_m,
            ),
            ("obstacles.partition_slab_m", self.partition_slab_m),
        ] {
            check_range(name, v, 0.0, 100.0, "within 0..100 m")?;
        }
        check_range(
            "obstacles.min_cell_points",
            self.min_cell_points as f64,
            1.0,
            1e6,
            "within 1..1e6",
        )?;
        check_range(
            "obstacles.partition_min_floor_both_sides",
            self.partition_min_floor_both_sides,
            0.0,
            1.0,
            "a fraction within 0..1",
        )?;
        check_range(
            "obstacles.partition_min_standing",
            self.partition_min_standing,
            0.0,
            1.0,
            "a fraction within 0..1",
        )?;
        check_range(
            "obstacles.min_points",
            self.min_points as f64,
            1.0,
            1e9,
            "within 1..1e9",
        )?;
        Ok(())
    }
}
