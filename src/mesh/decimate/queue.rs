//! The candidate collapses and the queue that hands them out cheapest first; entries made
//! stale by later collapses are skipped when popped and dropped in bulk.

/// A candidate collapse of the edge `(first, second)`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate {
    pub(super) cost: f32,
    pub(super) first: u32,
    pub(super) second: u32,
    /// The collapse counter when pushed: stale once either endpoint changed later.
    pub(super) pushed_at: u32,
}

/// A 4-ary min-heap of candidates with the costs in their own array: popping is the
/// inner loop's bottleneck, and a sift-down that compares four adjacent `f32` costs
/// touches one cache line per level, over half as many levels as a binary heap.
/// (Measured on 500k faces: `std`'s `BinaryHeap` of whole entries spent twice as
/// long; keys pointing into a slab made the periodic compaction slower than it saved.)
#[derive(Default)]
pub(super) struct CandidateQueue {
    pub(super) costs: Vec<f32>,
    /// `(first, second, pushed_at)`, parallel to `costs`.
    pub(super) edges: Vec<[u32; 3]>,
}

impl CandidateQueue {
    pub(super) fn heapify(&mut self) {
        for index in (0..self.costs.len().div_ceil(4)).rev() {
            self.sift_down(index);
        }
    }

    /// Keeps only the candidates for which `keep` holds.
    pub(super) fn retain(&mut self, mut keep: impl FnMut(&Candidate) -> bool) {
        let mut kept = 0;
        for index in 0..self.costs.len() {
            let [first, second, pushed_at] = self.edges[index];
            if keep(&Candidate { cost: self.costs[index], first, second, pushed_at }) {
                self.costs[kept] = self.costs[index];
                self.edges[kept] = self.edges[index];
                kept += 1;
            }
        }
        self.costs.truncate(kept);
        self.edges.truncate(kept);
        self.heapify();
    }

    pub(super) fn len(&self) -> usize {
        self.costs.len()
    }

    pub(super) fn push(&mut self, candidate: Candidate) {
        let edge = [candidate.first, candidate.second, candidate.pushed_at];
        self.costs.push(candidate.cost);
        self.edges.push(edge);
        let mut index = self.costs.len() - 1;
        while index > 0 {
            let parent = (index - 1) / 4;
            if self.costs[parent] <= candidate.cost {
                break;
            }
            self.costs[index] = self.costs[parent];
            self.edges[index] = self.edges[parent];
            index = parent;
        }
        self.costs[index] = candidate.cost;
        self.edges[index] = edge;
    }

    pub(super) fn pop(&mut self) -> Option<Candidate> {
        let cost = *self.costs.first()?;
        let [first, second, pushed_at] = self.edges[0];
        let (last_cost, last_edge) = (self.costs.pop().expect("not empty"), self.edges.pop().expect("parallel"));
        if !self.costs.is_empty() {
            self.costs[0] = last_cost;
            self.edges[0] = last_edge;
            self.sift_down(0);
        }
        Some(Candidate { cost, first, second, pushed_at })
    }

    fn sift_down(&mut self, mut index: usize) {
        let (cost, edge) = (self.costs[index], self.edges[index]);
        let length = self.costs.len();
        loop {
            let first_child = 4 * index + 1;
            if first_child >= length {
                break;
            }
            let children = &self.costs[first_child..(first_child + 4).min(length)];
            let (offset, &smallest) =
                children.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)).expect("a child");
            if smallest >= cost {
                break;
            }
            self.costs[index] = smallest;
            self.edges[index] = self.edges[first_child + offset];
            index = first_child + offset;
        }
        self.costs[index] = cost;
        self.edges[index] = edge;
    }
}
