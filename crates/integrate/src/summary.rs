//! What a reader names first (issue 25): the structures by role — the keep, the towers, the
//! curtain, the ranges, the rooms, the inner walls — with how many there are, how high, and
//! whether each height was measured, lent by a measured structure alike, or a default; and the
//! length of the walls. The report leads with it; the commands print it in one line.

use crate::estimate::{Estimate, Role, Source};

/// One role's structures.
#[derive(Debug, Clone, PartialEq)]
pub struct RoleSummary {
    pub role: Role,
    pub ids: Vec<String>,
    /// Lowest and highest, model units.
    pub heights: [f64; 2],
    /// Heights by source: set by the user, measured, lent, default.
    pub user: usize,
    pub measured: usize,
    pub lent: usize,
    pub defaulted: usize,
    /// Centreline length of the walls (curtain and inner walls), model units; 0 for the rest.
    pub length: f64,
}

/// The structures by role, in the order an expert names them (keep, towers, curtain, ranges,
/// rooms, walls); roles without structures are left out.
pub fn by_role(e: &Estimate) -> Vec<RoleSummary> {
    let mut out: Vec<RoleSummary> = Vec::new();
    let mut structures: Vec<_> = e.structures.iter().collect();
    structures.sort_by_key(|s| s.role);
    for s in structures {
        if out.last().is_none_or(|l| l.role != s.role) {
            out.push(RoleSummary {
                role: s.role,
                ids: Vec::new(),
                heights: [f64::INFINITY, f64::NEG_INFINITY],
                user: 0,
                measured: 0,
                lent: 0,
                defaulted: 0,
                length: 0.0,
            });
        }
        let line = out.last_mut().expect("pushed above");
        line.ids.push(s.id.clone());
        line.heights = [line.heights[0].min(s.height), line.heights[1].max(s.height)];
        match s.provenance.get("height").map(|p| p.source()) {
            Some(Source::User) => line.user += 1,
            Some(Source::Measured) => line.measured += 1,
            Some(Source::Lent) => line.lent += 1,
            Some(Source::Default) | None => line.defaulted += 1,
        }
        line.length += s
            .footprint
            .pieces()
            .iter()
            .map(|[a, b]| (b[0] - a[0]).hypot(b[1] - a[1]))
            .sum::<f64>();
    }
    out
}

impl RoleSummary {
    /// "5 towers", "1 keep", "4 curtain runs".
    pub fn counted(&self) -> String {
        let n = self.ids.len();
        let noun = match (self.role, n) {
            (Role::Curtain, 1) => "curtain run",
            (Role::Curtain, _) => "curtain runs",
            (Role::Wall, 1) => "inner wall",
            (Role::Wall, _) => "inner walls",
            (Role::Mass, 1) => "wall mass",
            (Role::Mass, _) => "wall masses",
            (r, 1) => r.name(),
            (Role::Keep, _) => "keeps",
            (Role::Tower, _) => "towers",
            (Role::Gatehouse, _) => "gatehouses",
            (Role::Range, _) => "ranges",
            (Role::Room, _) => "rooms",
        };
        format!("{n} {noun}")
    }
}

/// One line: "1 keep, 5 towers (1 measured, 3 lent), 4 curtain runs, 9 ranges, 8 inner walls".
pub fn line(e: &Estimate) -> String {
    by_role(e)
        .iter()
        .map(|r| {
            let told: Vec<String> = [
                (r.user, "user-set"),
                (r.measured, "measured"),
                (r.lent, "lent"),
            ]
            .iter()
            .filter(|(k, _)| *k > 0)
            .map(|(k, what)| format!("{k} {what}"))
            .collect();
            if told.is_empty() {
                r.counted()
            } else {
                format!("{} ({} height)", r.counted(), told.join(", "))
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimate::{Footprint, Kind, Provenance, Structure};
    use plan::label::Label;
    use plan::scale::{ModelScale, Units};

    fn structure(id: &str, role: Role, height: f64, source: &str) -> Structure {
        let mut provenance = std::collections::BTreeMap::new();
        let mut p = Provenance::new(source, "step", None);
        if source == "lent.png" {
            p.lent_by = Some("tower1".into());
        }
        provenance.insert("height".to_string(), p);
        Structure {
            id: id.into(),
            label: Label::UnknownRoom,
            role,
            kind: Kind::Solid,
            footprint: match role {
                Role::Curtain => Footprint::Wall {
                    centerline: vec![[0.0, 0.0], [30.0, 0.0], [30.0, 40.0]],
                    thickness: 3.0,
                    closed: false,
                    widths: Vec::new(),
                },
                _ => Footprint::Circle {
                    center: [0.0, 0.0],
                    radius: 5.0,
                },
            },
            height,
            wall_thickness: 2.0,
            facades: vec![],
            children: vec![],
            roof: None,
            crenellated: None,
            provenance,
        }
    }

    #[test]
    fn structures_are_told_by_role_with_the_sources_of_their_heights() {
        let e = Estimate {
            scale: ModelScale {
                units: Units::Metres,
                units_per_pixel: 1.0,
                units_per_metre: 1.0,
            },
            plan: crate::estimate::PlanSource {
                image: "plan.png".into(),
                width: 10,
                height: 10,
                towers: 2,
            },
            structures: vec![
                structure("curtain1", Role::Curtain, 12.0, "default"),
                structure("tower2", Role::Tower, 35.0, "lent.png"),
                structure("tower1", Role::Tower, 35.0, "elevation.png"),
                structure("keep1", Role::Keep, 52.5, "default"),
            ],
            assumptions: vec![],
        };
        let roles = by_role(&e);
        assert_eq!(
            roles.iter().map(|r| r.role).collect::<Vec<_>>(),
            [Role::Keep, Role::Tower, Role::Curtain]
        );
        let towers = &roles[1];
        assert_eq!((towers.measured, towers.lent, towers.defaulted), (1, 1, 0));
        assert_eq!(towers.heights, [35.0, 35.0]);
        assert_eq!(roles[2].length, 70.0);
        assert_eq!(
            line(&e),
            "1 keep, 2 towers (1 measured, 1 lent height), 1 curtain run"
        );
    }
}
