//! Where `semsim console` and `semsim report` find what they show: the world (a semantic map,
//! a building, or the scenario's building) and the point-cloud layer, given explicitly or found
//! beside the map or run folder in the layout `semsim demo` and `semsim run` write
//! (`OUT/map/semantic_map.json`, `OUT/map/labels.pcd`, `OUT/registration/map.pcd`,
//! `OUT/simulation/`).

use crate::error::Result;
use crate::world::ConsoleWorld;
use std::path::{Path, PathBuf};

/// The semantic map a folder given as `--map` stands for, relative to it: a demo's or run's
/// output folder first, then a map folder.
const MAP_IN_FOLDER: [&str; 2] = ["map/semantic_map.json", "semantic_map.json"];
/// The map beside a run folder that `semsim run` or `semsim demo` wrote (`OUT/simulation`).
const MAP_BESIDE_RUN: &str = "../map/semantic_map.json";
/// The registered clouds beside a map file's folder, best first: the cloud labelled by the map,
/// then the registration's merged cloud.
const CLOUDS_BESIDE_MAP: [&str; 2] = ["labels.pcd", "../registration/map.pcd"];
/// The same clouds seen from a run folder (`OUT/simulation`).
const CLOUDS_BESIDE_RUN: [&str; 2] = ["../map/labels.pcd", "../registration/map.pcd"];

/// A file given on the command line, or found beside another one (which the CLI says, so the
/// user knows which file is shown).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Located {
    /// Named by the user (a folder given as `--map` resolved to its map file counts as named).
    Given(PathBuf),
    /// Not named: found beside the map or run folder.
    Found(PathBuf),
}

impl Located {
    /// The file.
    pub fn path(&self) -> &Path {
        match self {
            Located::Given(p) | Located::Found(p) => p,
        }
    }

    /// Whether it was found rather than named.
    pub fn was_found(&self) -> bool {
        matches!(self, Located::Found(_))
    }
}

/// Where the world comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum WorldFile {
    /// A semantic map file.
    Map(Located),
    /// A building description file.
    Building(PathBuf),
    /// The built-in default building.
    DefaultBuilding,
}

impl WorldFile {
    /// The world it describes; errors name the file.
    pub fn load(&self) -> Result<ConsoleWorld> {
        match self {
            WorldFile::Map(m) => ConsoleWorld::from_semantic_map_file(m.path()),
            WorldFile::Building(b) => ConsoleWorld::from_building(&scanner::Building::load(b)?),
            WorldFile::DefaultBuilding => {
                ConsoleWorld::from_building(&scanner::Building::default_building()?)
            }
        }
    }
}

/// What the user named: `--map`, `--building`, `--run`, `--cloud` (each optional).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ConsoleInputs {
    /// A semantic map file, or a folder holding one (`map/semantic_map.json` or
    /// `semantic_map.json`).
    pub map: Option<PathBuf>,
    /// A building description, or `default` for the built-in building.
    pub building: Option<PathBuf>,
    /// A recorded run folder.
    pub run: Option<PathBuf>,
    /// A point cloud for the cloud layer.
    pub cloud: Option<PathBuf>,
}

impl ConsoleInputs {
    /// The semantic map: `--map` (a folder means the first of its `map/semantic_map.json`,
    /// `semantic_map.json` that is a file, else the latter, whose absence the loader reports);
    /// without `--map` and `--building`, the map beside a `--run` folder that `semsim run` or
    /// `semsim demo` wrote (`OUT/simulation` beside `OUT/map`), the world it ran in.
    pub fn map_file(&self) -> Option<Located> {
        let Some(m) = &self.map else {
            let run = self.run.as_ref().filter(|_| self.building.is_none())?;
            return first_file(run, &[MAP_BESIDE_RUN]).map(Located::Found);
        };
        if !m.is_dir() {
            return Some(Located::Given(m.clone()));
        }
        let file = first_file(m, &MAP_IN_FOLDER).unwrap_or_else(|| m.join(MAP_IN_FOLDER[1]));
        Some(Located::Given(file))
    }

    /// Where the world comes from: the map ([`Self::map_file`]), else `--building` (`default`:
    /// the built-in one), else the building the scenario names
    /// ([`sim::Scenario::building_file`], relative to the scenario's folder `scenario_dir`).
    pub fn world_source(&self, scenario: &sim::Scenario, scenario_dir: &Path) -> WorldFile {
        if let Some(m) = self.map_file() {
            return WorldFile::Map(m);
        }
        match &self.building {
            Some(b) if b.as_os_str() == "default" => WorldFile::DefaultBuilding,
            Some(b) => WorldFile::Building(b.clone()),
            None => match scenario.building_file(scenario_dir) {
                Some(file) => WorldFile::Building(file),
                None => WorldFile::DefaultBuilding,
            },
        }
    }

    /// The cloud layer's file: `--cloud`, else the registered cloud beside the map
    /// (`labels.pcd`, else `../registration/map.pcd`) or beside the `--run` folder
    /// (`../map/labels.pcd`, else `../registration/map.pcd`); `None` where there is none.
    pub fn cloud_file(&self) -> Option<Located> {
        if let Some(c) = &self.cloud {
            return Some(Located::Given(c.clone()));
        }
        self.map_file()
            .and_then(|m| first_file(m.path().parent()?, &CLOUDS_BESIDE_MAP))
            .or_else(|| first_file(self.run.as_ref()?, &CLOUDS_BESIDE_RUN))
            .map(Located::Found)
    }
}

/// The first of `names` (relative to `dir`) that is a file.
fn first_file(dir: &Path, names: &[&str]) -> Option<PathBuf> {
    names.iter().map(|n| dir.join(n)).find(|p| p.is_file())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `semsim run` output folder: `map/semantic_map.json`, `simulation/`, and the clouds
    /// named in `clouds` (relative to it).
    fn run_output(clouds: &[&str]) -> tempfile::TempDir {
        let dir = tempfile::tempdir().expect("tempdir");
        for sub in ["map", "registration", "simulation"] {
            std::fs::create_dir(dir.path().join(sub)).expect("mkdir");
        }
        for f in std::iter::once(&"map/semantic_map.json").chain(clouds) {
            std::fs::write(dir.path().join(f), "x").expect("write");
        }
        dir
    }

    fn same(a: &Path, b: &Path) -> bool {
        a.canonicalize().ok() == b.canonicalize().ok() && a.exists()
    }

    #[test]
    fn a_run_folder_is_shown_in_the_map_and_labelled_cloud_beside_it() {
        let out = run_output(&["map/labels.pcd", "registration/map.pcd"]);
        let inputs = ConsoleInputs {
            run: Some(out.path().join("simulation")),
            ..ConsoleInputs::default()
        };
        let map = inputs.map_file().expect("the map beside the run");
        assert!(map.was_found());
        assert!(same(map.path(), &out.path().join("map/semantic_map.json")));
        let cloud = inputs.cloud_file().expect("a cloud beside the map");
        assert!(cloud.was_found());
        assert!(same(cloud.path(), &out.path().join("map/labels.pcd")));
    }

    #[test]
    fn without_labels_the_registered_cloud_is_found() {
        let out = run_output(&["registration/map.pcd"]);
        let inputs = ConsoleInputs {
            map: Some(out.path().to_path_buf()),
            ..ConsoleInputs::default()
        };
        assert_eq!(
            inputs.map_file(),
            Some(Located::Given(out.path().join("map/semantic_map.json")))
        );
        let cloud = inputs.cloud_file().expect("the registered cloud");
        assert!(same(cloud.path(), &out.path().join("registration/map.pcd")));
        let none = run_output(&[]);
        let inputs = ConsoleInputs {
            map: Some(none.path().to_path_buf()),
            ..ConsoleInputs::default()
        };
        assert_eq!(inputs.cloud_file(), None);
    }

    #[test]
    fn a_building_or_a_given_cloud_wins_over_what_is_beside_the_run() {
        let out = run_output(&["map/labels.pcd"]);
        let run = Some(out.path().join("simulation"));
        let inputs = ConsoleInputs {
            run: run.clone(),
            building: Some("b.toml".into()),
            cloud: Some("c.ply".into()),
            ..ConsoleInputs::default()
        };
        assert_eq!(inputs.map_file(), None);
        assert_eq!(
            inputs.world_source(&in_building("default"), Path::new(".")),
            WorldFile::Building("b.toml".into())
        );
        assert_eq!(inputs.cloud_file(), Some(Located::Given("c.ply".into())));
    }

    #[test]
    fn a_map_folder_without_a_map_names_the_missing_file() {
        let dir = tempfile::tempdir().expect("tempdir");
        let inputs = ConsoleInputs {
            map: Some(dir.path().to_path_buf()),
            ..ConsoleInputs::default()
        };
        let WorldFile::Map(m) = inputs.world_source(&in_building(""), Path::new(".")) else {
            panic!("a map");
        };
        assert_eq!(m.path(), dir.path().join("semantic_map.json"));
        let e = WorldFile::Map(m).load().expect_err("no map file");
        assert!(e.to_string().contains("semantic_map.json"), "{e}");
    }

    /// The built-in scenario naming `building`.
    fn in_building(building: &str) -> sim::Scenario {
        let mut scenario = sim::Scenario::default_scenario().expect("built-in scenario");
        scenario.building = building.to_string();
        scenario
    }

    #[test]
    fn the_scenario_building_is_relative_to_the_scenario() {
        let inputs = ConsoleInputs::default();
        let dir = Path::new("scenarios");
        assert_eq!(
            inputs.world_source(&in_building("default"), dir),
            WorldFile::DefaultBuilding
        );
        assert_eq!(
            inputs.world_source(&in_building(""), dir),
            WorldFile::DefaultBuilding
        );
        assert_eq!(
            inputs.world_source(&in_building("hall.toml"), dir),
            WorldFile::Building(dir.join("hall.toml"))
        );
        let default = ConsoleInputs {
            building: Some("default".into()),
            ..ConsoleInputs::default()
        };
        assert_eq!(
            default.world_source(&in_building("hall.toml"), dir),
            WorldFile::DefaultBuilding
        );
        assert!(WorldFile::DefaultBuilding.load().is_ok());
        let e = WorldFile::Building(dir.join("hall.toml"))
            .load()
            .expect_err("no such building");
        assert!(e.to_string().contains("hall.toml"), "{e}");
    }
}
