//! The surfaces of the CityJSON writer (`cityjson.rs`, issue 24): a terminal's triangle mesh in
//! the file's frame becomes the faces of one solid, on the file's integer millimetre grid.
//!
//! - [`Pool`] quantises points to the grid (`transform`: scale 0.001, translate = the minimum
//!   corner) and interns them, so two points in one millimetre cell are one vertex of the file:
//!   neighbouring terminals share their corners, and cjval finds no duplicate; [`Vertices`]
//!   numbers the grid points the written rings use, so none is unused.
//! - [`faces`] drops the triangles the grid flattens (a repeated vertex, or three in a line) and
//!   merges each connected set of coplanar triangles into one polygon with its holes (an
//!   annulus stays one face with an inner ring), walking the set's boundary edges; a set whose
//!   boundary is not made of simple loops (a vertex where two loops touch) stays triangles,
//!   which are valid faces too. Rings keep the mesh's winding, counter-clockwise seen from
//!   outside (Sui 2011 §7.1.2: terminals are closed, outward meshes), and holes come out
//!   clockwise, as CityJSON wants them.

use std::collections::{HashMap, VecDeque};

use serde_json::{Value, json};

/// Metres per unit of the file's integer vertices: millimetres.
pub(super) const SCALE: f64 = 0.001;

/// Largest integer coordinate a JSON reader holds exactly in a double (2⁵³).
pub(super) const MAX_INTEGER: f64 = 9_007_199_254_740_992.0;

/// Two triangles are one face when their normals differ by less than this (1 − cos), and…
const SAME_NORMAL: f64 = 1e-9;
/// …the second's corners lie this close (metres) to the first's plane: primitives' coplanar
/// faces agree to rounding, far below the millimetre grid.
const SAME_PLANE: f64 = 1e-6;

/// A terminal's mesh in the file's frame (metres, x east, y north, z up), before quantisation.
pub(super) struct FileMesh {
    pub points: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

/// The file's vertices: points quantised to the millimetre grid, one index per grid point.
pub(super) struct Pool {
    translate: [f64; 3],
    index: HashMap<[i64; 3], u32>,
    /// Grid coordinates per index, in order of first use.
    pub keys: Vec<[i64; 3]>,
}

impl Pool {
    pub fn new(translate: [f64; 3]) -> Pool {
        Pool {
            translate,
            index: HashMap::new(),
            keys: Vec::new(),
        }
    }

    /// The grid point nearest `p`; points are checked finite and within [`MAX_INTEGER`] of
    /// the translate before, so the cast neither saturates nor loses a millimetre.
    fn key(&self, p: [f64; 3]) -> [i64; 3] {
        std::array::from_fn(|k| ((p[k] - self.translate[k]) / SCALE).round() as i64)
    }

    fn intern(&mut self, p: [f64; 3]) -> u32 {
        let key = self.key(p);
        let next = self.keys.len() as u32;
        let id = *self.index.entry(key).or_insert(next);
        if id == next {
            self.keys.push(key);
        }
        id
    }
}

/// The file's `vertices`: the grid points the written rings use, numbered in order of use,
/// so none is unused and none repeats.
pub(super) struct Vertices {
    /// Per pool index, its index in `keys` (`u32::MAX` until used).
    index: Vec<u32>,
    pub keys: Vec<[i64; 3]>,
}

impl Vertices {
    pub fn new(pool: &Pool) -> Vertices {
        Vertices {
            index: vec![u32::MAX; pool.keys.len()],
            keys: Vec::new(),
        }
    }

    pub fn ring(&mut self, ring: &[u32], pool: &Pool) -> Value {
        let ids: Vec<u32> = ring
            .iter()
            .map(|&p| {
                let slot = &mut self.index[p as usize];
                if *slot == u32::MAX {
                    *slot = self.keys.len() as u32;
                    self.keys.push(pool.keys[p as usize]);
                }
                *slot
            })
            .collect();
        json!(ids)
    }

    /// `[minx, miny, minz, maxx, maxy, maxz]` in metres of the written vertices.
    pub fn extent(&self, translate: [f64; 3]) -> Option<[f64; 6]> {
        let first = *self.keys.first()?;
        let (lo, hi) = self
            .keys
            .iter()
            .fold((first, first), |(mut lo, mut hi), k| {
                for i in 0..3 {
                    lo[i] = lo[i].min(k[i]);
                    hi[i] = hi[i].max(k[i]);
                }
                (lo, hi)
            });
        let at = |k: [i64; 3], i: usize| translate[i] + k[i] as f64 * SCALE;
        Some([
            at(lo, 0),
            at(lo, 1),
            at(lo, 2),
            at(hi, 0),
            at(hi, 1),
            at(hi, 2),
        ])
    }
}

/// One planar face: its outer ring then its holes (indices into [`Pool::keys`]), the unit
/// normal of its plane (file frame) and the height range of its vertices in grid units.
pub(super) struct Face {
    pub rings: Vec<Vec<u32>>,
    pub normal: [f64; 3],
    pub z_range: [i64; 2],
}

/// One triangle that survives the grid: its corners in the mesh and in the pool.
struct Tri {
    mesh: [u32; 3],
    pool: [u32; 3],
}

/// The faces of one closed mesh on the grid of `pool` (which gains its vertices).
pub(super) fn faces(mesh: &FileMesh, pool: &mut Pool) -> Vec<Face> {
    let ids: Vec<u32> = mesh.points.iter().map(|&p| pool.intern(p)).collect();
    let tris: Vec<Tri> = mesh
        .triangles
        .iter()
        .filter(|t| t.iter().all(|&i| (i as usize) < ids.len()))
        .map(|t| Tri {
            mesh: *t,
            pool: t.map(|i| ids[i as usize]),
        })
        .filter(|t| !flat_on_grid(t.pool.map(|i| pool.keys[i as usize])))
        .collect();
    // Triangles by their directed edges on the grid. An edge used twice the same way (the grid
    // folded the mesh) makes "the neighbour across an edge" ambiguous: then no merging at all.
    let mut by_edge: HashMap<(u32, u32), usize> = HashMap::with_capacity(tris.len() * 3);
    let mut manifold = true;
    for (i, t) in tris.iter().enumerate() {
        for (a, b) in edges(t.pool) {
            manifold &= by_edge.insert((a, b), i).is_none();
        }
    }
    let plane = |t: &Tri| plane_of(t.mesh.map(|i| mesh.points[i as usize]));
    let mut group_of = vec![usize::MAX; tris.len()];
    let mut faces = Vec::new();
    for seed in 0..tris.len() {
        if group_of[seed] != usize::MAX {
            continue;
        }
        let (normal, offset) = plane(&tris[seed]);
        let mut group = vec![seed];
        group_of[seed] = seed;
        let mut queue = VecDeque::from([seed]);
        while manifold && let Some(t) = queue.pop_front() {
            for (a, b) in edges(tris[t].pool) {
                let Some(&u) = by_edge.get(&(b, a)) else {
                    continue;
                };
                let on_plane = || {
                    let (n, _) = plane(&tris[u]);
                    dot(n, normal) >= 1.0 - SAME_NORMAL
                        && tris[u].mesh.iter().all(|&i| {
                            (dot(mesh.points[i as usize], normal) - offset).abs() <= SAME_PLANE
                        })
                };
                if group_of[u] == usize::MAX && on_plane() {
                    group_of[u] = seed;
                    group.push(u);
                    queue.push_back(u);
                }
            }
        }
        let corners: Vec<[u32; 3]> = group.iter().map(|&t| tris[t].pool).collect();
        let rings = match boundary_rings(&corners, normal, &pool.keys) {
            Some(rings) => vec![rings],
            None => corners.iter().map(|c| vec![c.to_vec()]).collect(),
        };
        for rings in rings {
            let z = rings[0].iter().map(|&i| pool.keys[i as usize][2]);
            let z_range = [z.clone().min().unwrap_or(0), z.max().unwrap_or(0)];
            faces.push(Face {
                rings,
                normal,
                z_range,
            });
        }
    }
    faces
}

fn edges(t: [u32; 3]) -> [(u32, u32); 3] {
    [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]
}

/// Whether the grid made a triangle a point or a line (exact, in integers).
fn flat_on_grid(k: [[i64; 3]; 3]) -> bool {
    let d = |a: [i64; 3], b: [i64; 3]| std::array::from_fn::<i128, 3, _>(|i| (b[i] - a[i]) as i128);
    let (u, v) = (d(k[0], k[1]), d(k[0], k[2]));
    u[1] * v[2] == u[2] * v[1] && u[2] * v[0] == u[0] * v[2] && u[0] * v[1] == u[1] * v[0]
}

/// Unit normal (right hand, counter-clockwise) and offset of a triangle's plane; a triangle
/// too small for a normal in floating point gets `[0, 0, 0]` and merges with nothing.
fn plane_of([a, b, c]: [[f64; 3]; 3]) -> ([f64; 3], f64) {
    let n = cross(sub(b, a), sub(c, a));
    let len = dot(n, n).sqrt();
    if len.is_nan() || len <= 0.0 {
        return ([0.0; 3], 0.0);
    }
    let n = n.map(|v| v / len);
    (n, dot(n, a))
}

/// The boundary of a set of triangles as rings: the outer ring (counter-clockwise about
/// `normal`) first, then the holes; `None` unless the boundary edges form simple loops of
/// which exactly one winds positively.
fn boundary_rings(tris: &[[u32; 3]], normal: [f64; 3], keys: &[[i64; 3]]) -> Option<Vec<Vec<u32>>> {
    if tris.len() == 1 {
        return Some(vec![tris[0].to_vec()]);
    }
    let inner: std::collections::HashSet<(u32, u32)> =
        tris.iter().flat_map(|&t| edges(t)).collect();
    let mut next: HashMap<u32, u32> = HashMap::new();
    for (a, b) in tris.iter().flat_map(|&t| edges(t)) {
        if !inner.contains(&(b, a)) && next.insert(a, b).is_some() {
            return None; // two loops touch at `a`
        }
    }
    let mut rings: Vec<(f64, Vec<u32>)> = Vec::new();
    let mut starts: Vec<u32> = next.keys().copied().collect();
    starts.sort_unstable(); // a deterministic file
    for start in starts {
        if !next.contains_key(&start) {
            continue;
        }
        let mut ring = vec![start];
        let mut at = next.remove(&start)?;
        while at != start {
            ring.push(at);
            at = next.remove(&at)?;
        }
        if ring.len() < 3 {
            return None;
        }
        rings.push((dot(area_vector(&ring, keys), normal), ring));
    }
    let outer = rings.iter().filter(|(area, _)| *area > 0.0).count();
    if outer != 1 {
        return None;
    }
    rings.sort_by(|a, b| b.0.total_cmp(&a.0));
    Some(rings.into_iter().map(|(_, ring)| ring).collect())
}

/// Twice the vector area of a ring on the grid (Newell), relative to its first vertex.
fn area_vector(ring: &[u32], keys: &[[i64; 3]]) -> [f64; 3] {
    let o = keys[ring[0] as usize];
    let rel = |i: u32| {
        let k = keys[i as usize];
        [0, 1, 2].map(|j| (k[j] - o[j]) as f64)
    };
    let mut sum = [0.0; 3];
    for w in 0..ring.len() {
        let c = cross(rel(ring[w]), rel(ring[(w + 1) % ring.len()]));
        sum = [sum[0] + c[0], sum[1] + c[1], sum[2] + c[2]];
    }
    sum
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube (metres) with two triangles per side, counter-clockwise from outside.
    fn cube(size: f64) -> FileMesh {
        let points = (0..8)
            .map(|i| [i & 1, (i >> 1) & 1, (i >> 2) & 1].map(|b| b as f64 * size))
            .collect();
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let triangles = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        FileMesh { points, triangles }
    }

    #[test]
    fn a_cube_has_six_square_faces_on_eight_vertices() {
        let mut pool = Pool::new([0.0; 3]);
        let faces = faces(&cube(1.0), &mut pool);
        assert_eq!(faces.len(), 6);
        assert!(
            faces
                .iter()
                .all(|f| f.rings.len() == 1 && f.rings[0].len() == 4)
        );
        assert_eq!(pool.keys.len(), 8);
        // Outward: every face's ring winds about its normal, which points away from the centre.
        for f in &faces {
            let a = area_vector(&f.rings[0], &pool.keys);
            assert!((dot(a, f.normal) - 2.0e6).abs() < 1e-6, "{a:?}");
            let k = pool.keys[f.rings[0][0] as usize].map(|v| v as f64 - 500.0);
            assert!(dot(k, f.normal) > 0.0);
        }
    }

    #[test]
    fn a_cube_smaller_than_the_grid_vanishes() {
        let mut pool = Pool::new([0.0; 3]);
        assert!(faces(&cube(0.0004), &mut pool).is_empty());
    }

    #[test]
    fn a_square_with_a_square_hole_is_one_face_with_two_rings() {
        // An annulus of eight triangles around the square hole 1..2 in the square 0..3.
        let p = |x: f64, y: f64| [x, y, 0.0];
        let points = vec![
            p(0.0, 0.0),
            p(3.0, 0.0),
            p(3.0, 3.0),
            p(0.0, 3.0),
            p(1.0, 1.0),
            p(2.0, 1.0),
            p(2.0, 2.0),
            p(1.0, 2.0),
        ];
        let mut triangles = Vec::new();
        for k in 0..4u32 {
            let (o, o2, i, i2) = (k, (k + 1) % 4, k + 4, (k + 1) % 4 + 4);
            triangles.push([o, o2, i2]);
            triangles.push([o, i2, i]);
        }
        let mut pool = Pool::new([0.0; 3]);
        let faces = faces(&FileMesh { points, triangles }, &mut pool);
        assert_eq!(faces.len(), 1);
        let rings = &faces[0].rings;
        assert_eq!(rings.len(), 2);
        let up = [0.0, 0.0, 1.0];
        assert!((dot(area_vector(&rings[0], &pool.keys), up) - 18.0e6).abs() < 1e-3);
        assert!((dot(area_vector(&rings[1], &pool.keys), up) + 2.0e6).abs() < 1e-3);
    }

    #[test]
    fn triangles_the_grid_flattens_are_dropped() {
        assert!(flat_on_grid([[0, 0, 0], [1, 1, 1], [2, 2, 2]]));
        assert!(flat_on_grid([[0, 0, 0], [0, 0, 0], [2, 1, 2]]));
        assert!(!flat_on_grid([[0, 0, 0], [1, 0, 0], [0, 1, 0]]));
    }
}
