//! What a [`Dicer`] tells about itself: its CSG trees, trim regions, rows and counts.

use reyes_hider::CsgTree;

use super::Dicer;
use crate::DiceStats;

impl Dicer<'_> {
    /// The CSG tree of every solid ([`crate::CsgSetup::trees`]).
    pub fn csg_trees(&self) -> &[CsgTree] {
        &self.csg_trees
    }

    /// The trim regions of the scene's trimmed patches, for [`reyes_hider::Hider::with_trims`].
    pub fn trim_regions(&self) -> Vec<std::sync::Arc<reyes_scene::patches::trim::TrimRegion>> {
        self.trims.clone()
    }

    /// Rows of buckets.
    pub fn rows(&self) -> u32 {
        self.frame.buckets_y
    }

    /// The counts so far (the whole frame's once every row is diced).
    pub fn stats(&self) -> DiceStats {
        self.stats
    }

    /// The most micropolygons held at once (after dicing a row, before releasing one).
    pub fn peak_micropolygons(&self) -> u64 {
        self.peak_alive
    }
}
