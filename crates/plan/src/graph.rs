//! The planar graph of the skeleton (§5.1.4): vertices where curves end or three or more meet,
//! edges as pixel chains (multi-edges and loops allowed), faces with the white pixels each owns,
//! the outer face included; and the §5.1.6 simplification (leaf edges pruned, degree-2 merged).

use crate::thin::{Mask, NEIGHBOURS};
use raster::components::{Connectivity, components_where};

/// A graph vertex: a wall end or junction, at the mean of its skeleton pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct Vertex {
    pub x: f64,
    pub y: f64,
}

/// A wall: the skeleton pixels between two vertices, in order from `from` to `to`.
#[derive(Debug, Clone, PartialEq)]
pub struct Edge {
    pub from: usize,
    pub to: usize,
    pub points: Vec<(u32, u32)>,
}

/// Vertices and edges of the vectorised skeleton.
#[derive(Debug, Clone, Default)]
pub struct Graph {
    pub vertices: Vec<Vertex>,
    pub edges: Vec<Edge>,
}

const NONE: u32 = u32::MAX;

/// A merged chain: start vertex, end vertex, pixels, and the original edges it was made of.
type Chain = (usize, usize, Vec<(u32, u32)>, Vec<usize>);

fn xy(i: usize, w: usize) -> (i32, i32) {
    ((i % w) as i32, (i / w) as i32)
}

fn on_neighbours(m: &Mask, i: usize) -> impl Iterator<Item = usize> + '_ {
    let w = m.width as usize;
    let (x, y) = xy(i, w);
    NEIGHBOURS.iter().filter_map(move |&(dx, dy)| {
        let (nx, ny) = (x + dx, y + dy);
        (m.get(nx, ny) == 1).then(|| ny as usize * w + nx as usize)
    })
}

/// Vectorises a skeleton (§5.1.4). Node pixels (one neighbour, or three and more) are grouped
/// into 8-connected clusters, one vertex each; every other pixel has two neighbours and lies
/// on exactly one chain. Closed curves without a node get a vertex at their first pixel.
pub fn vectorise(skel: &Mask) -> Graph {
    let w = skel.width as usize;
    let n = skel.data.len();
    let mut vid = vec![NONE; n];
    let mut g = Graph::default();
    // Node clusters.
    for i in 0..n {
        if skel.data[i] == 0 || vid[i] != NONE || skel.count(i) == 2 {
            continue;
        }
        let id = g.vertices.len() as u32;
        let (mut sx, mut sy, mut k) = (0.0, 0.0, 0.0);
        let mut stack = vec![i];
        vid[i] = id;
        while let Some(j) = stack.pop() {
            let (x, y) = xy(j, w);
            sx += x as f64;
            sy += y as f64;
            k += 1.0;
            for nb in on_neighbours(skel, j) {
                if vid[nb] == NONE && skel.count(nb) != 2 {
                    vid[nb] = id;
                    stack.push(nb);
                }
            }
        }
        g.vertices.push(Vertex {
            x: sx / k,
            y: sy / k,
        });
    }
    let mut used = vec![false; n];
    // Walks a chain from `start` (a curve pixel next to `prev`) until a node pixel.
    let walk = |start: usize, prev: usize, used: &mut Vec<bool>| -> (Vec<usize>, Option<usize>) {
        let mut chain = vec![start];
        used[start] = true;
        let (mut cur, mut last) = (start, prev);
        for _ in 0..n {
            let next = on_neighbours(skel, cur).find(|&nb| nb != last && !chain.ends_with(&[nb]));
            let Some(nx) = next else { return (chain, None) };
            if vid[nx] != NONE {
                return (chain, Some(nx));
            }
            if used[nx] {
                return (chain, None);
            }
            used[nx] = true;
            chain.push(nx);
            last = cur;
            cur = nx;
        }
        (chain, None)
    };
    for i in 0..n {
        if vid[i] == NONE {
            continue;
        }
        for nb in on_neighbours(skel, i).collect::<Vec<_>>() {
            if vid[nb] != NONE || used[nb] {
                continue;
            }
            let (chain, end) = walk(nb, i, &mut used);
            let Some(end) = end else { continue };
            // A pixel hanging between two pixels of one cluster is part of the junction.
            if chain.len() == 1 && vid[end] == vid[i] {
                continue;
            }
            g.edges.push(Edge {
                from: vid[i] as usize,
                to: vid[end] as usize,
                points: chain
                    .iter()
                    .map(|&j| (j % w) as u32)
                    .zip(chain.iter().map(|&j| (j / w) as u32))
                    .collect(),
            });
        }
    }
    // Closed curves with no node.
    for i in 0..n {
        if skel.data[i] == 0 || used[i] || vid[i] != NONE {
            continue;
        }
        let id = g.vertices.len();
        let (x, y) = xy(i, w);
        g.vertices.push(Vertex {
            x: x as f64,
            y: y as f64,
        });
        used[i] = true;
        let mut chain = vec![i];
        let (mut cur, mut last) = (i, usize::MAX);
        for _ in 0..n {
            let Some(nx) = on_neighbours(skel, cur).find(|&nb| nb != last && !used[nb]) else {
                break;
            };
            used[nx] = true;
            chain.push(nx);
            last = cur;
            cur = nx;
        }
        if chain.len() >= 3 {
            g.edges.push(Edge {
                from: id,
                to: id,
                points: chain
                    .iter()
                    .map(|&j| ((j % w) as u32, (j / w) as u32))
                    .collect(),
            });
        }
    }
    g
}

/// Faces: the 4-connected regions of the complement of the skeleton. Departure from §5.1.4's
/// wall-following over the embedded graph: for a pixel skeleton, flooding its complement gives
/// the same faces and hands each face its pixels directly. Returns a face id per pixel
/// (`u32::MAX` on the skeleton) and the number of faces.
pub fn faces(skel: &Mask) -> (Vec<u32>, usize) {
    let (w, h) = (skel.width as usize, skel.height as usize);
    let c = components_where(w, h, Connectivity::Four, |i| skel.data[i] == 0);
    // Component labels count from 1 in the order of their first pixel; face ids from 0.
    let fid = c
        .labels
        .into_iter()
        .map(|l| if l == 0 { NONE } else { l - 1 })
        .collect();
    (fid, c.sizes.len() - 1)
}

impl Graph {
    /// Number of edge ends at each vertex (a loop counts twice).
    pub fn degrees(&self) -> Vec<usize> {
        let mut d = vec![0; self.vertices.len()];
        for e in &self.edges {
            d[e.from] += 1;
            d[e.to] += 1;
        }
        d
    }

    /// §5.1.6: removes leaf edges until none is left, then merges the two edges at every
    /// vertex of degree two; vertices left without edges are dropped. Returns, for each edge
    /// of the result, the indices of the original edges it was made of.
    pub fn simplify(&self) -> (Graph, Vec<Vec<usize>>) {
        let mut alive = vec![true; self.edges.len()];
        for _ in 0..=self.edges.len() {
            let mut d = vec![0; self.vertices.len()];
            for (e, a) in self.edges.iter().zip(&alive) {
                if *a {
                    d[e.from] += 1;
                    d[e.to] += 1;
                }
            }
            let mut changed = false;
            for (e, a) in self.edges.iter().zip(alive.iter_mut()) {
                if *a && e.from != e.to && (d[e.from] == 1 || d[e.to] == 1) {
                    *a = false;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        // Chains of edges through degree-2 vertices.
        let mut inc: Vec<Vec<usize>> = vec![Vec::new(); self.vertices.len()];
        for (k, e) in self.edges.iter().enumerate() {
            if alive[k] {
                inc[e.from].push(k);
                inc[e.to].push(k);
            }
        }
        let keep_vertex = |v: usize| !inc[v].is_empty() && inc[v].len() != 2;
        let mut done = vec![false; self.edges.len()];
        let mut chains: Vec<Chain> = Vec::new();
        let mut start_chain = |k0: usize, v0: usize, done: &mut Vec<bool>| {
            let mut pts = Vec::new();
            let mut parts = Vec::new();
            let (mut k, mut v) = (k0, v0);
            for _ in 0..self.edges.len() {
                done[k] = true;
                parts.push(k);
                let e = &self.edges[k];
                let (next_v, forward) = if e.from == v {
                    (e.to, true)
                } else {
                    (e.from, false)
                };
                if forward {
                    pts.extend_from_slice(&e.points);
                } else {
                    pts.extend(e.points.iter().rev());
                }
                v = next_v;
                if keep_vertex(v) || v == v0 {
                    break;
                }
                let Some(&nk) = inc[v].iter().find(|&&c| !done[c]) else {
                    break;
                };
                let nv = &self.vertices[v];
                pts.push((nv.x.round() as u32, nv.y.round() as u32));
                k = nk;
            }
            chains.push((v0, v, pts, parts));
        };
        for (v, edges_at) in inc.iter().enumerate() {
            if keep_vertex(v) {
                for &k in edges_at {
                    if !done[k] {
                        start_chain(k, v, &mut done);
                    }
                }
            }
        }
        // Cycles made only of degree-2 vertices.
        for k in 0..self.edges.len() {
            if alive[k] && !done[k] {
                start_chain(k, self.edges[k].from, &mut done);
            }
        }
        let mut map = vec![NONE; self.vertices.len()];
        let mut out = Graph::default();
        let mut parts_out = Vec::new();
        for (a, b, pts, parts) in chains {
            let mut id = |v: usize, out: &mut Graph| {
                if map[v] == NONE {
                    map[v] = out.vertices.len() as u32;
                    out.vertices.push(self.vertices[v].clone());
                }
                map[v] as usize
            };
            let from = id(a, &mut out);
            let to = id(b, &mut out);
            out.edges.push(Edge {
                from,
                to,
                points: pts,
            });
            parts_out.push(parts);
        }
        (out, parts_out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A skeleton from rows of '#', with the corners of 4-connected steps removed as
    /// thinning does.
    fn mask(rows: &[&str]) -> Mask {
        let mut m = Mask::new(rows[0].len() as u32, rows.len() as u32);
        for (y, r) in rows.iter().enumerate() {
            for (x, c) in r.bytes().enumerate() {
                m.data[y * m.width as usize + x] = u8::from(c == b'#');
            }
        }
        crate::thin::remove_staircase(&mut m);
        m
    }

    #[test]
    fn t_junction_has_four_vertices_three_edges() {
        let g = vectorise(&mask(&[
            ".........",
            ".#######.",
            "....#....",
            "....#....",
            "....#....",
            ".........",
        ]));
        assert_eq!(g.vertices.len(), 4);
        assert_eq!(g.edges.len(), 3);
        assert_eq!(g.degrees().iter().filter(|&&d| d == 1).count(), 3);
    }

    #[test]
    fn closed_square_is_one_loop_and_two_faces() {
        let m = mask(&[
            ".......", ".#####.", ".#...#.", ".#...#.", ".#####.", ".......",
        ]);
        let g = vectorise(&m);
        assert_eq!(g.edges.len(), 1);
        assert_eq!(g.edges[0].from, g.edges[0].to);
        assert_eq!(g.edges[0].points.len(), 10);
        let (fid, n) = faces(&m);
        assert_eq!(n, 2);
        assert_ne!(fid[0], fid[2 * 7 + 3]);
    }

    #[test]
    fn theta_graph_has_multi_edges_and_three_faces() {
        let m = mask(&[
            "...........",
            ".#########.",
            ".#...#...#.",
            ".#...#...#.",
            ".#...#...#.",
            ".#...#...#.",
            ".#########.",
            "...........",
        ]);
        let g = vectorise(&m);
        let (_, n) = faces(&m);
        assert_eq!(n, 3);
        let (s, _) = g.simplify();
        assert_eq!(s.vertices.len(), 2, "{s:?}");
        assert_eq!(s.edges.len(), 3);
        assert!(s.edges.iter().all(|e| e.from != e.to));
    }

    #[test]
    fn simplify_prunes_leaves_and_merges() {
        // A loop with a spur: the spur goes, the loop stays as one edge.
        let m = mask(&[
            "...........",
            ".#####.....",
            ".#...#.....",
            ".#...######",
            ".#####.....",
            "...........",
        ]);
        let (s, parts) = vectorise(&m).simplify();
        assert_eq!(s.edges.len(), 1, "{s:?}");
        assert_eq!(s.edges[0].from, s.edges[0].to);
        assert_eq!(s.vertices.len(), 1);
        assert_eq!(parts[0].len(), 1);
        assert_eq!(s.edges[0].points.len(), 7);
    }
}
