//! Closed triangle meshes of terminal shapes (§7.1.2: "a terminal shape's attributes are
//! represented by a surface mesh"), with the checks every primitive must pass: closed,
//! 2-manifold, consistently oriented outwards, and a signed volume by the divergence theorem.

use std::collections::HashMap;

/// An indexed triangle mesh in a shape's local frame. Triangles are counter-clockwise seen
/// from outside, so the signed volume of a closed mesh is positive.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    pub positions: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// Appends a vertex and returns its index.
    pub fn push_vertex(&mut self, p: [f64; 3]) -> u32 {
        self.positions.push(p);
        (self.positions.len() - 1) as u32
    }

    /// Appends a triangle `a, b, c` (counter-clockwise seen from outside).
    pub fn push_triangle(&mut self, a: u32, b: u32, c: u32) {
        self.triangles.push([a, b, c]);
    }

    /// Appends a planar convex polygon as a triangle fan (vertices counter-clockwise from outside).
    pub fn push_polygon(&mut self, ring: &[u32]) {
        for i in 1..ring.len().saturating_sub(1) {
            self.push_triangle(ring[0], ring[i], ring[i + 1]);
        }
    }

    /// Appends `other` (e.g. another piece of the same solid).
    pub fn append(&mut self, other: &TriMesh) {
        let base = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.triangles.extend(
            other
                .triangles
                .iter()
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
    }

    /// Signed volume enclosed by the mesh (divergence theorem); exact for a closed mesh.
    pub fn signed_volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.positions[i as usize]);
                (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]))
                    / 6.0
            })
            .sum()
    }

    /// Axis-aligned bounds `(min, max)`; `None` for an empty mesh.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut it = self.positions.iter();
        let first = *it.next()?;
        Some(it.fold((first, first), |(mut lo, mut hi), p| {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
            (lo, hi)
        }))
    }

    /// True when every directed edge appears exactly once and its reverse exactly once: the mesh
    /// is closed, 2-manifold at its edges, and consistently oriented. Triangles with a repeated
    /// vertex index count as defects.
    pub fn is_closed_oriented(&self) -> bool {
        let mut directed: HashMap<(u32, u32), u32> =
            HashMap::with_capacity(self.triangles.len() * 3);
        for t in &self.triangles {
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                return false;
            }
            for k in 0..3 {
                *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        directed
            .iter()
            .all(|(&(a, b), &n)| n == 1 && directed.get(&(b, a)) == Some(&1))
    }

    /// Merges vertices closer than `eps` (grid snapping) and drops triangles that become
    /// degenerate. Meshes built from rings that collapse (an apex, an axis) use this.
    pub fn weld(&mut self, eps: f64) {
        let mut index: HashMap<[i64; 3], u32> = HashMap::with_capacity(self.positions.len());
        let mut remap = Vec::with_capacity(self.positions.len());
        let mut positions = Vec::with_capacity(self.positions.len());
        for p in &self.positions {
            let key = p.map(|v| (v / eps).round() as i64);
            let id = *index.entry(key).or_insert_with(|| {
                positions.push(*p);
                (positions.len() - 1) as u32
            });
            remap.push(id);
        }
        self.positions = positions;
        self.triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|i| remap[i as usize]))
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_tetrahedron() -> TriMesh {
        let mut m = TriMesh::default();
        for p in [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ] {
            m.push_vertex(p);
        }
        m.triangles = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        m
    }

    #[test]
    fn tetrahedron_volume_is_one_sixth() {
        assert!((unit_tetrahedron().signed_volume() - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn tetrahedron_is_closed_and_oriented() {
        assert!(unit_tetrahedron().is_closed_oriented());
    }

    #[test]
    fn missing_face_is_not_closed() {
        let mut m = unit_tetrahedron();
        m.triangles.pop();
        assert!(!m.is_closed_oriented());
    }

    #[test]
    fn flipped_face_is_not_oriented() {
        let mut m = unit_tetrahedron();
        m.triangles[0] = [0, 1, 2];
        assert!(!m.is_closed_oriented());
    }

    #[test]
    fn weld_merges_duplicates_and_drops_degenerate_triangles() {
        let mut m = unit_tetrahedron();
        let dup = m.push_vertex([1.0, 0.0, 1e-12]);
        m.push_triangle(1, dup, 2);
        m.weld(1e-9);
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles.len(), 4);
    }
}
