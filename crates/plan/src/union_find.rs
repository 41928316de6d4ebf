//! Disjoint sets of indices (union–find with path halving): the towers made of several
//! tower-wall edges or of several rooms are counted and grouped with it.

/// Sets of the indices `0..n`, each at first alone.
pub(crate) struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    pub(crate) fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    /// The representative of `v`'s set.
    pub(crate) fn root(&mut self, mut v: usize) -> usize {
        while self.parent[v] != v {
            self.parent[v] = self.parent[self.parent[v]];
            v = self.parent[v];
        }
        v
    }

    /// Joins the sets of `a` and `b`.
    pub(crate) fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.root(a), self.root(b));
        self.parent[a] = b;
    }
}

#[cfg(test)]
mod tests {
    use super::UnionFind;

    #[test]
    fn joined_indices_share_a_root_and_others_keep_their_own() {
        let mut sets = UnionFind::new(6);
        sets.union(0, 1);
        sets.union(3, 4);
        sets.union(1, 4);
        let r = sets.root(0);
        assert!([1, 3, 4].iter().all(|&v| sets.root(v) == r));
        assert_eq!(sets.root(2), 2);
        assert_eq!(sets.root(5), 5);
        assert_ne!(sets.root(2), r);
    }
}
