//! Sequential registration of a scan series into one map (the 2009 paper's "meta scan"):
//! scan `k` is registered against the union of the registered scans `0..k`, kept
//! voxel-downsampled in the world frame.
//!
//! The guess for scan `k` applies the odometry's relative motion to the last registered pose:
//! `world_from_scan[k-1] * odom[k-1]^-1 * odom[k]`. Scan 0 defines the world and keeps its
//! odometry pose. Without odometry (or where its ICP fails), the initial alignment
//! ([`crate::initial`], [`SequenceConfig::initial_alignment`]) searches the scan's yaw and
//! position against the map first. With odometry, an ICP that moves the scan far from the
//! odometry's guess is checked against a narrow-gate ICP from the guess and an ICP from the
//! initial alignment's search (`long_correction`, [`SequenceResult::corrections_checked`]).

use crate::config::IcpConfig;
use crate::downsample::{finite_points, voxel_downsample, voxel_downsample_with};
use crate::error::{RegistrationError, Result};
use crate::initial::{self, InitialAlignment, InitialAlignmentReport};
use crate::long_correction::{self, CorrectionCheck};
use crate::registrar::Registrar;
use crate::result::IcpResult;
use crate::target::Target;
use cloud::{check_range, PointCloud};
use glam::{DAffine3, Vec3};
use serde::{Deserialize, Serialize};

/// Settings of a sequence registration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SequenceConfig {
    /// Settings of each scan-to-map registration (its `range_knee_m` is replaced by the
    /// sequence's).
    pub icp: IcpConfig,
    /// The range weighting of every scan-to-map registration (`IcpConfig::range_knee_m`;
    /// 0: off). Stop-and-scan scans from a rotating laser are less certain far from the
    /// sensor; on 3DTK's corridor 1 m brings the registration from 7.4 cm / 1.6 deg to
    /// 0.6 cm / 0.2 deg of slam6d's 2009 result (scan 1; `bench/registration_3dtk.sh`).
    pub range_knee_m: f64,
    /// Each scan is downsampled to this voxel edge before it is registered and merged.
    pub scan_voxel_m: f64,
    /// The map is kept downsampled to this voxel edge.
    pub map_voxel_m: f64,
    /// When a scan's yaw and position are searched against the map before its ICP (`auto`:
    /// every scan of a sequence without odometry, and with odometry only a scan whose ICP
    /// from the odometry fails; `always`; `off`: the previous behaviour, every scan from its
    /// guess). See [`InitialAlignment`]. ICP alone is local: without odometry each scan
    /// starts from the previous scan's pose, and a turn of more than about 20 degrees or a
    /// move of more than the gate lands it in a wrong minimum.
    pub initial_alignment: InitialAlignment,
    /// The initial alignment's resolution: the cell of its search from above, the voxel and
    /// the final gate of its coarse ICPs. 0.25 m: coarse enough to search a room in tens of
    /// milliseconds and to average a scan's noise, fine enough that a 0.5 m tall piece of
    /// furniture or a door jamb is structure and that the coarse ICP starts within its gate
    /// (three cells) of the solution.
    pub initial_cell_m: f64,
}

impl Default for SequenceConfig {
    fn default() -> Self {
        SequenceConfig {
            icp: IcpConfig::default(),
            range_knee_m: 1.0,
            scan_voxel_m: 0.05,
            map_voxel_m: 0.05,
            initial_alignment: InitialAlignment::Auto,
            initial_cell_m: 0.25,
        }
    }
}

impl SequenceConfig {
    /// Checks every value for a meaningful range (the ICP's settings with the sequence's
    /// range weighting, the voxels, the initial alignment's cell).
    pub fn validate(&self) -> Result<()> {
        IcpConfig {
            range_knee_m: self.range_knee_m,
            ..self.icp.clone()
        }
        .validate()?;
        check_range(
            "initial_cell_m",
            self.initial_cell_m,
            0.05,
            5.0,
            "must be a finite length within [0.05, 5] m (the initial alignment's cell)",
        )?;
        for (name, v) in [
            ("scan_voxel_m", self.scan_voxel_m),
            ("map_voxel_m", self.map_voxel_m),
        ] {
            if !(v.is_finite() && (1e-4..=100.0).contains(&v)) {
                return Err(RegistrationError::invalid(
                    name,
                    v,
                    "must be a finite length within [1e-4, 100] m",
                ));
            }
        }
        Ok(())
    }
}

/// The outcome of a sequence registration.
#[derive(Debug, Clone)]
pub struct SequenceResult {
    /// The registered pose of every scan.
    pub world_from_scan: Vec<DAffine3>,
    /// All scans merged in the world frame, voxel-downsampled to `map_voxel_m`.
    pub map: PointCloud,
    /// Each scan's registration; `None` for scan 0, which defines the world.
    pub results: Vec<Option<IcpResult>>,
    /// Each scan's initial alignment; `None` where there was none (scan 0, and every scan
    /// that registered from its guess).
    pub initial: Vec<Option<InitialAlignmentReport>>,
    /// Each scan's check of a long correction from the odometry's guess (see
    /// [`CorrectionCheck`]); `None` where none ran.
    pub corrections_checked: Vec<Option<CorrectionCheck>>,
}

/// Registers `scans` one after another against the growing map.
///
/// `world_from_scan_guess` is the odometry, one pose per scan, or empty for none (every
/// relative motion is then the identity, and with [`InitialAlignment::Auto`] each scan's yaw
/// and position are searched against the map). `progress(done, total)` is called after each scan.
/// A scan that fails to register stops the sequence with its error (for
/// [`RegistrationError::NotConverged`] the reason names the scan).
///
/// Opens the device of `config.icp.device` once for the whole sequence (see
/// [`register_sequence_with`] to choose it yourself).
pub fn register_sequence(
    scans: &[PointCloud],
    world_from_scan_guess: &[DAffine3],
    config: &SequenceConfig,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<SequenceResult> {
    let mut registrar = Registrar::new(&config.icp)?;
    register_sequence_with(
        &mut registrar,
        scans,
        world_from_scan_guess,
        config,
        progress,
    )
}

/// [`register_sequence`] on an open device: on a GPU the kernels and buffers serve every scan,
/// and each scan's map is uploaded once for all its iterations.
pub fn register_sequence_with(
    registrar: &mut Registrar,
    scans: &[PointCloud],
    world_from_scan_guess: &[DAffine3],
    config: &SequenceConfig,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<SequenceResult> {
    config.validate()?;
    let icp = IcpConfig {
        range_knee_m: config.range_knee_m,
        ..config.icp.clone()
    };
    if scans.is_empty() {
        return Err(RegistrationError::EmptyCloud {
            which: "scan sequence".into(),
        });
    }
    if !world_from_scan_guess.is_empty() && world_from_scan_guess.len() != scans.len() {
        return Err(RegistrationError::Mismatch {
            what: "world_from_scan_guess",
            msg: format!(
                "{} poses for {} scans (give one per scan, or none)",
                world_from_scan_guess.len(),
                scans.len()
            ),
        });
    }
    let odom = |k: usize| {
        world_from_scan_guess
            .get(k)
            .copied()
            .unwrap_or(DAffine3::IDENTITY)
    };
    if let Some(k) = (0..scans.len()).find(|&k| !odom(k).is_finite()) {
        return Err(RegistrationError::Mismatch {
            what: "world_from_scan_guess",
            msg: format!("pose {k} is not finite"),
        });
    }
    let total = scans.len();
    let has_odometry = !world_from_scan_guess.is_empty();
    let search_first = match config.initial_alignment {
        InitialAlignment::Off => false,
        InitialAlignment::Auto => !has_odometry,
        InitialAlignment::Always => true,
    };
    let settings = initial::Settings {
        cell_m: config.initial_cell_m,
        range_knee_m: config.range_knee_m,
    };
    let scan_points = |k: usize| -> Result<Vec<Vec3>> {
        let p = finite_points(&scans[k], &format!("scan {k}"))?;
        voxel_downsample(&p, config.scan_voxel_m, "scan_voxel_m")
    };

    // The map keeps, per point, the world position of the sensor that saw it, so that the
    // target's normals can be oriented and back faces rejected (see `Target::with_viewpoints`).
    let sensor = |k: usize| scans[k].sensor_origin;
    let mut world_from_scan = vec![odom(0)];
    let mut results = vec![None];
    let mut reports = vec![None];
    let mut checks = vec![None];
    let mut map = scan_points(0)?;
    move_points(&mut map, &odom(0));
    let views = vec![odom(0).transform_point3(sensor(0).as_dvec3()).as_vec3(); map.len()];
    let (mut map, mut views) =
        voxel_downsample_with(&map, &views, config.map_voxel_m, "map_voxel_m")?;
    progress(1, total);
    for k in 1..total {
        let points = scan_points(k)?;
        let map_cloud = PointCloud::from_points(std::mem::take(&mut map));
        let target = Target::with_viewpoints(&map_cloud, &views, &icp)?;
        map = map_cloud.points;
        let guess = world_from_scan[k - 1] * odom(k - 1).inverse() * odom(k);
        let mut source = PointCloud::from_points(points);
        source.sensor_origin = sensor(k);
        // The initial alignment: first where configured, else where the guess fails.
        let align = |map: &[Vec3], views: &[Vec3]| {
            let previous = (&world_from_scan[k - 1], sensor(k - 1));
            initial::align(map, views, &source, previous, &guess, settings)
        };
        let (outcome, report) = if search_first {
            let (start, report) = align(&map, &views)?;
            let outcome = registrar.register_to(&target, &source, start, &icp);
            (outcome, Some(report))
        } else {
            match registrar.register_to(&target, &source, guess, &icp) {
                Err(
                    RegistrationError::NotConverged { .. } | RegistrationError::NoOverlap { .. },
                ) if config.initial_alignment == InitialAlignment::Auto => {
                    let (start, report) = align(&map, &views)?;
                    let outcome = registrar.register_to(&target, &source, start, &icp);
                    (outcome, Some(report))
                }
                outcome => (outcome, None),
            }
        };
        let result = match outcome {
            Ok(r) => r,
            Err(RegistrationError::NotConverged { result, reason }) => {
                let after = if report.is_some() {
                    " (after the initial alignment)"
                } else {
                    ""
                };
                return Err(RegistrationError::NotConverged {
                    result,
                    reason: format!("scan {k}{after}: {reason}"),
                });
            }
            Err(e) => return Err(e),
        };
        // A long correction from the odometry's guess is checked against a narrow schedule.
        let (result, check) = if report.is_none() && has_odometry {
            let map_view = long_correction::MapView {
                points: &map,
                views: &views,
                target: &target,
                cell: (config.initial_cell_m, config.range_knee_m),
            };
            let search = || align(&map, &views).map(|(start, _)| start);
            long_correction::check(registrar, map_view, &source, &guess, result, &icp, search)?
        } else {
            (result, None)
        };
        let pose = result.target_from_source;
        let mut moved = source.points;
        move_points(&mut moved, &pose);
        let view = pose.transform_point3(sensor(k).as_dvec3()).as_vec3();
        views.extend(std::iter::repeat_n(view, moved.len()));
        map.extend(moved);
        (map, views) = voxel_downsample_with(&map, &views, config.map_voxel_m, "map_voxel_m")?;
        world_from_scan.push(pose);
        results.push(Some(result));
        reports.push(report);
        checks.push(check);
        progress(k + 1, total);
    }
    Ok(SequenceResult {
        world_from_scan,
        map: PointCloud::from_points(map),
        results,
        initial: reports,
        corrections_checked: checks,
    })
}

fn move_points(points: &mut [Vec3], world_from_scan: &DAffine3) {
    for p in points {
        *p = world_from_scan.transform_point3(p.as_dvec3()).as_vec3();
    }
}
