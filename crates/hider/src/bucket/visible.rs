//! Visible points (stage: hider): the tail of Appendix A's `sample`, which makes a sample's
//! visible point once the inside test has passed (clipped at the sample's depth where the
//! micropolygon crosses hither or yon, and linked in depth order when occlusion culling
//! needs it), `gouraud`, and the resolution of every sample with its AOVs. Invariant: a
//! sample's list gets its points in the order the scan finds them, whatever the path.

use reyes_csg::shepard_weights;
use reyes_csg::{Composite, LERP_DONE, NIL, Resolver, VisPoint, lerpz, resolve_sample_traced};

use super::Surface;
use crate::aov::{AovPlan, AovValue, Sources, midpoint_depth};
use crate::mpoly::{Micropolygon, flags};
use crate::{Hider, Scratch};

impl Hider {
    /// Port of the tail of `sample`, once a sample is known to be inside: reject a moving
    /// hither/yon-straddling micropolygon under `original_moving_clip`, clip a crossing one at
    /// the sample's depth, and push a visible point on list `nsample`. `v` holds the vertices
    /// relative to the sample, as tested. Returns whether a point was created (otherwise the
    /// test is a miss, as in Appendix A, where those checks came first and rejected the
    /// sample whatever the inside test said). Out of line so the test loops stay small.
    #[inline(never)]
    pub(super) fn hit(
        &self,
        nsample: usize,
        s: &Surface,
        v: &[[f32; 3]; 4],
        scratch: &mut Scratch,
    ) -> bool {
        if s.mp.has(flags::TRIMMED) {
            scratch.stats.trim_tests += 1;
            let t = scratch.trims.get(s.index as usize);
            let region = t.and_then(|t| self.trims.get(t.region as usize));
            // A micropolygon flagged without its data is drawn untrimmed (never happens: the
            // renderer fills one entry per micropolygon).
            if let (Some(t), Some(region)) = (t, region)
                && crate::trim::trimmed_at(region, t, v)
            {
                scratch.stats.trimmed += 1;
                return false;
            }
        }
        if s.crossing && self.config.original_moving_clip && s.mp.has(flags::MOVING) {
            // Appendix A: a moving micropolygon straddling hither or yon at this sample's time
            // is rejected outright instead of clipped (appendix-a.md 3.6).
            let zlo = v[0][2].min(v[1][2]).min(v[2][2]).min(v[3][2]);
            let zhi = v[0][2].max(v[1][2]).max(v[2][2]).max(v[3][2]);
            if zlo < self.config.hither || zhi > self.config.yon {
                return false;
            }
        }
        let (minz, maxz, lerped) = if s.crossing {
            let z = lerpz(v);
            scratch.stats.lerps += 1;
            if !(z >= self.config.hither && z <= self.config.yon) {
                return false;
            }
            (z, z, LERP_DONE)
        } else {
            (s.zmin, s.zmax, 0)
        };
        let mp = s.mp;
        let (color, trans) =
            if mp.has(flags::GOURAUD) { gouraud(v, mp) } else { (mp.color[0], mp.trans[0]) };
        let index = scratch.points.len() as u32;
        if scratch.points.len() as u64 >= self.max_points {
            scratch.stats.dropped_points += 1;
            return false;
        }
        scratch.points.push(VisPoint {
            v: *v,
            minz,
            maxz,
            color,
            trans,
            flags: (mp.flags & !LERP_DONE) | lerped,
            csg_tree: mp.csg_tree,
            csg_node: mp.csg_node,
            glass_opacity: mp.glass_opacity,
            next: scratch.heads[nsample],
        });
        if scratch.occlusion.on {
            let occ = &mut scratch.occlusion;
            occ.link(&mut scratch.points, &mut scratch.heads, nsample, index, s.order);
            if s.occluder {
                occ.record(nsample, maxz);
            }
        } else {
            scratch.heads[nsample] = index;
        }
        if scratch.keep_mp {
            scratch.point_mp.push(s.index);
        }
        true
    }
}

impl Hider {
    /// `CSGResolve` of every sample with the AOVs of `plan`: the same composites as the plain
    /// loop (traced), then each sample's AOV values from its steps.
    pub(super) fn resolve_aovs(
        &self,
        plan: &AovPlan,
        (mpolys, data): (&[Micropolygon], &[f32]),
        resolver: &Resolver,
        lerps: &mut u64,
        scratch: &mut Scratch,
    ) {
        let n = scratch.heads.len();
        let channels = plan.channels();
        scratch.aov.clear();
        scratch.aov.resize(n * channels, 0.0);
        scratch.front_z.clear();
        scratch.front_z.resize(n, f32::INFINITY);
        let mut steps = std::mem::take(&mut scratch.steps);
        let midpoint = plan.values.contains(&AovValue::MidDepth);
        for k in 0..n {
            let head = scratch.heads[k];
            // Before the resolution, which may relink the list.
            let mid = if midpoint { midpoint_depth(&scratch.points, head) } else { 0.0 };
            steps.0.clear();
            let c = if head == NIL {
                Composite::EMPTY
            } else {
                resolve_sample_traced(&mut scratch.points, head, resolver, lerps, &mut steps)
            };
            scratch.rgba[k] = [c.rgb[0], c.rgb[1], c.rgb[2], c.alpha];
            scratch.z[k] = c.z;
            let sources =
                Sources { points: &scratch.points, point_mp: &scratch.point_mp, mpolys, data };
            let out = &mut scratch.aov[k * channels..(k + 1) * channels];
            scratch.front_z[k] = sources.sample(plan, &steps.0, mid, out);
        }
        scratch.steps = steps;
    }
}

/// Port of `gouraud`: the vertex colours and transmittances weighted by the Shepard weights of
/// `lerpz` at the sample point.
#[inline]
pub fn gouraud(v: &[[f32; 3]; 4], mp: &Micropolygon) -> ([f32; 3], [f32; 3]) {
    let w = shepard_weights(v);
    let mut c = [0.0; 3];
    let mut t = [0.0; 3];
    for (k, wk) in w.iter().enumerate() {
        for a in 0..3 {
            c[a] += wk * mp.color[k][a];
            t[a] += wk * mp.trans[k][a];
        }
    }
    (c, t)
}
