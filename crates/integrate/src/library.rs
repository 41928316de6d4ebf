//! The medieval library (§7.2.2) compiled into the crate, so generated programs can import
//! `round_tower.vsg`, `curtain_wall.vsg`, … wherever the binary runs.

/// Every library program by file name.
pub const FILES: [(&str, &str); 7] = [
    (
        "round_tower.vsg",
        include_str!("../../../library/round_tower.vsg"),
    ),
    (
        "solid_tower.vsg",
        include_str!("../../../library/solid_tower.vsg"),
    ),
    (
        "square_tower.vsg",
        include_str!("../../../library/square_tower.vsg"),
    ),
    (
        "curtain_wall.vsg",
        include_str!("../../../library/curtain_wall.vsg"),
    ),
    (
        "gatehouse.vsg",
        include_str!("../../../library/gatehouse.vsg"),
    ),
    ("keep.vsg", include_str!("../../../library/keep.vsg")),
    (
        "gothic_window.vsg",
        include_str!("../../../library/gothic_window.vsg"),
    ),
];

/// Resolves imports from [`FILES`] and from programs generated for this model (the Gothic
/// façades' block programs).
#[derive(Debug, Clone, Default)]
pub struct Library {
    pub generated: Vec<(String, String)>,
}

impl Library {
    pub fn with(generated: Vec<(String, String)>) -> Library {
        Library { generated }
    }
}

impl vsg::import::Resolver for Library {
    fn load(&mut self, _from: &str, path: &str) -> Result<(String, String), String> {
        let name = path.trim_start_matches("./");
        FILES
            .iter()
            .map(|(n, t)| (*n, *t))
            .chain(self.generated.iter().map(|(n, t)| (n.as_str(), t.as_str())))
            .find(|(n, _)| *n == name)
            .map(|(n, text)| (n.to_string(), text.to_string()))
            .ok_or_else(|| {
                let names: Vec<&str> = FILES.iter().map(|(n, _)| *n).collect();
                format!("'{path}' is not in the library ({})", names.join(", "))
            })
    }
}
