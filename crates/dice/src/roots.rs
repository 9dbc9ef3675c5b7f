//! Root patches under crack-free dicing: which sides of an object's surfaces are shared.
//!
//! Every root patch gets its four sides as [`Edge`]s (split/edge.rs). Surfaces of one object
//! that meet along a boundary must read one edge, not make one each: each would fix its own
//! polyline from its own tolerance and its own evaluation of the common curve, and the two
//! grids' boundaries would differ (background showing through between them). So the first
//! surface to reach a boundary makes its edge and the others read it:
//! - the sub-patches of a bicubic patch mesh, and the spans of a NURBS, meet along the rows
//!   and columns of their layout, which name the edges (a wrapped mesh's last boundary is its
//!   first);
//! - the patches of a subdivision surface meet along edges of the once-subdivided mesh, named
//!   by their two corners' point ids; neighbouring patches may run along an edge in opposite
//!   directions and with it as different sides, and read it reversed ([`Edge::reversed`]).
//!
//! Other shapes are one surface (or faces with straight edges, which stay one piece) and
//! make their own sides.

use std::collections::HashMap;
use std::sync::Arc;

use reyes_scene::{Object, Shape, Wrap};

use crate::motion::Pose;
use crate::shapes::Surface;
use crate::split::{Edge, Extent, Patch, SharedSides, Splitter};

/// How an object's surfaces meet.
enum Layout {
    /// Crack-free dicing is off: plain root patches.
    Off,
    /// Each surface makes its own sides.
    Alone,
    /// A `cols x rows` layout of sub-patches, wrapped or not along u and v.
    Grid { cols: usize, rows: usize, uwrap: bool, vwrap: bool },
    /// Patches named by their corners' point ids.
    Corners,
}

/// The shared sides made so far for one object.
pub(crate) struct Roots {
    layout: Layout,
    /// Patch-mesh edges by (runs along v, column, row): `(false, c, r)` is the side along u
    /// of column `c` at row boundary `r`, `(true, c, r)` the side along v of row `r` at
    /// column boundary `c`.
    grid: HashMap<(bool, usize, usize), Arc<Edge>>,
    /// Subdivision edges by their corner ids (lower first), with the id they were made from.
    by_corners: HashMap<(usize, usize), (usize, Arc<Edge>)>,
    /// The raster extent of the whole object, when its surfaces are pieces of one primitive
    /// (a blobby's faces): the scale of the edges' relative flatness.
    extent: Option<Extent>,
}

impl Roots {
    /// The sharing rule of `object`'s `surface_count` surfaces.
    pub fn new(object: &Object, crack_free: bool, surface_count: usize) -> Roots {
        let layout = if !crack_free {
            Layout::Off
        } else if matches!(object.shape, Shape::Curves { .. } | Shape::Points { .. }) {
            // Ribbons meet their neighbours only at their ends, where both evaluate the
            // same points; a million of them cannot each keep four edges.
            Layout::Off
        } else if matches!(object.shape, Shape::SubdivisionMesh { .. } | Shape::Blobby { .. }) {
            Layout::Corners
        } else if let Some((cols, rows)) = reyes_scene::patches::bezier_grid(&object.shape)
            .filter(|&(c, r)| c * r == surface_count)
        {
            let (uwrap, vwrap) = match &object.shape {
                Shape::PatchMesh { uwrap, vwrap, .. } => {
                    (*uwrap == Wrap::Periodic, *vwrap == Wrap::Periodic)
                }
                _ => (false, false),
            };
            Layout::Grid { cols, rows, uwrap, vwrap }
        } else {
            Layout::Alone
        };
        Roots { layout, grid: HashMap::new(), by_corners: HashMap::new(), extent: None }
    }

    /// The same rule, with the object's raster extent the scale of every edge's tolerance.
    pub fn with_extent(self, extent: Option<Extent>) -> Roots {
        Roots { extent, ..self }
    }

    /// The root patch of surface `surface` (in `poses`), its sides shared with the surfaces
    /// before it where they meet.
    pub fn root(&mut self, decide: &Splitter, surface: usize, poses: &[Pose<'_>]) -> Patch {
        match self.layout {
            Layout::Off => Patch::root(),
            Layout::Alone => decide.root_with_sides(poses),
            Layout::Grid { cols, rows, uwrap, vwrap } => {
                let (c, r) = (surface % cols, surface / cols);
                // Keys: (along v, column boundary, row) and (along u, column, row boundary).
                let right = if uwrap { (c + 1) % cols } else { c + 1 };
                let top = if vwrap { (r + 1) % rows } else { r + 1 };
                let keys = [(false, c, r), (false, c, top), (true, c, r), (true, right, r)];
                let [bottom, top_edge, left, right_edge] = keys.map(|k| self.grid.get(&k).cloned());
                let (top, right, extent) = (top_edge, right_edge, self.extent.clone());
                let given = SharedSides { bottom, top, left, right, extent };
                let root = decide.root_sharing(poses, given);
                if let Some(sides) = &root.sides {
                    let made = [&sides.bottom, &sides.top, &sides.left, &sides.right];
                    for (k, e) in keys.into_iter().zip(made) {
                        self.grid.entry(k).or_insert_with(|| e.clone());
                    }
                }
                root
            }
            Layout::Corners => {
                let c = match poses.first().map(|p| p.surface) {
                    Some(Surface::Subdiv(s)) => s.corners(),
                    Some(Surface::Blob(b)) => b.corner_ids(),
                    _ => return decide.root_with_sides(poses),
                };
                // Each side from its start to its end, in the side's own direction of
                // increasing parameter: bottom (0,0)->(1,0), top (0,1)->(1,1), left
                // (0,0)->(0,1), right (1,0)->(1,1).
                let runs = [(c[0], c[1]), (c[3], c[2]), (c[0], c[3]), (c[1], c[2])];
                let key = |(a, b): (usize, usize)| (a.min(b), a.max(b));
                let [bottom, top, left, right] = runs.map(|(a, b)| {
                    self.by_corners.get(&key((a, b))).map(|(from, e)| {
                        if *from == a { e.clone() } else { Arc::new(e.reversed()) }
                    })
                });
                let extent = self.extent.clone();
                let root =
                    decide.root_sharing(poses, SharedSides { bottom, top, left, right, extent });
                if let Some(sides) = &root.sides {
                    let made = [&sides.bottom, &sides.top, &sides.left, &sides.right];
                    for (run, e) in runs.into_iter().zip(made) {
                        self.by_corners.entry(key(run)).or_insert_with(|| (run.0, e.clone()));
                    }
                }
                root
            }
        }
    }
}

/// The raster extent of a blobby's bound at each breakpoint, or `None` for any other object.
pub(crate) fn blobby_extent(
    motion: &crate::motion::ObjectMotion,
    decide: &Splitter,
) -> Option<Extent> {
    let poses = motion.poses(0);
    let crate::shapes::Surface::Blob(face) = poses.first()?.surface else { return None };
    let (lo, hi) = face.program.bound()?;
    let corners = crate::shapes::box_corners(lo.as_vec3(), hi.as_vec3());
    Some(Extent::per_breakpoint(
        poses
            .iter()
            .map(|pose| decide.extent_of(corners.iter().map(|p| pose.moment.camera_point(*p))))
            .collect(),
    ))
}
