//! Plan–model agreement (issue 25) on the bundled projects: floors under today's figures, so a
//! change that builds less of the plan fails here and an improvement can raise them. Measured
//! figures and the whole development set: `cargo run --release -p integrate --example
//! plan_model_agreement`.

use std::path::{Path, PathBuf};

use integrate::agreement::Agreement;
use integrate::pipeline::{self, Files, Reconstruction};
use integrate::project::Project;

struct Folder(PathBuf);

impl Files for Folder {
    fn image(&self, name: &str) -> Result<image::DynamicImage, String> {
        image::open(self.0.join(name)).map_err(|e| format!("{name}: {e}"))
    }

    fn json<T: serde::de::DeserializeOwned>(&self, name: &str, what: &str) -> Result<T, String> {
        let text =
            std::fs::read_to_string(self.0.join(name)).map_err(|e| format!("{name}: {e}"))?;
        serde_json::from_str(&text).map_err(|e| format!("{name} is not {what}: {e}"))
    }
}

fn reconstruct(example: &str) -> Reconstruction {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(example);
    let text = std::fs::read_to_string(dir.join("PROJECT.toml")).unwrap();
    let project = Project::from_toml(&text).unwrap();
    pipeline::reconstruct(
        &project,
        &Folder(dir),
        &pipeline::Options::default(),
        &|_| {},
    )
    .unwrap()
}

fn show(a: &Agreement) -> String {
    format!(
        "IoU {:.3}, precision {:.3}, recall {:.3}, rooms {} / {}, towers {} / {}",
        a.iou,
        a.precision,
        a.recall,
        a.rooms_present(),
        a.rooms.len(),
        a.towers_present(),
        a.towers.len()
    )
}

#[test]
fn coucy_model_covers_its_plan_at_least_as_well_as_today() {
    let r = reconstruct("coucy");
    let a = &r.agreement;
    // Measured (issue 25): IoU 0.721, precision 0.953, recall 0.747, rooms 11 / 21, towers
    // 4 / 6. The floors leave 0.02 for floating-point drift between builds; what is missing
    // is rooms without a circle or rectangle fit (no structure), the chapel among them, and
    // two tower rooms only walls cross (`--example plan_model_agreement -- --absent`).
    assert!(a.iou >= 0.70, "{}", show(a));
    assert!(a.recall >= 0.72, "{}", show(a));
    assert!(a.towers_present() >= 4, "{}", show(a));
    assert!(a.rooms_present() >= 11, "{}", show(a));
    // stats.json carries the same figures.
    assert_eq!(r.exports.stats["agreement"], a.summary());
    // Every covered pixel of a room belongs to a structure of the estimate.
    for room in a.rooms.iter().filter(|r| r.present()) {
        let id = room.structure.as_deref().unwrap();
        assert!(r.estimate.structures.iter().any(|s| s.id == id), "{id}");
    }
}

#[test]
fn the_synthetic_castle_is_built_where_it_is_drawn() {
    let r = reconstruct("demo");
    let a = &r.agreement;
    // Measured: IoU 0.958, precision 0.962, recall 0.995, rooms 3 / 3, towers 2 / 2.
    assert!(a.iou >= 0.94, "{}", show(a));
    assert_eq!(a.rooms_present(), a.rooms.len(), "{}", show(a));
    assert_eq!(a.towers_present(), a.towers.len(), "{}", show(a));
    assert!(a.towers.len() >= 2, "{}", show(a));
}
