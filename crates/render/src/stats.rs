//! Render statistics: `--stats`, after Appendix A's `VisPrint("stat")` (hits, misses, lerps,
//! visible points) plus the dicer's counts and the time per stage.

use std::fmt;
use std::time::Duration;

use reyes_hider::{Frame, HiderConfig};
use reyes_scene::{Filter, Scene};

/// The dicer's counts.
#[derive(Debug, Clone, Copy, Default)]
pub struct DiceSummary {
    /// Primitives in the scene.
    pub primitives: u64,
    /// Split operations.
    pub splits: u64,
    /// Grids diced.
    pub grids: u64,
    /// Micropolygons the flatness rule diced beyond the shading rate's grids.
    pub flatness: u64,
    /// Grid vertices diced.
    pub vertices: u64,
    /// Of `vertices`, those shaded (the corners of kept micropolygons).
    pub shaded: u64,
    /// Micropolygons or patches culled.
    pub culled: u64,
    /// The most micropolygons held at once (lazy dicing keeps only the rows in flight).
    pub peak_micropolygons: u64,
    /// The whole scene was diced up front, because lazy dicing met a patch bound that
    /// missed (the image is the same).
    pub eager: bool,
    /// Cells of trimmed NURBS patches dropped whole in the trimmed region, and
    /// micropolygons a trim curve crosses (tested per sample by the hider).
    pub trimmed: u64,
    /// See `trimmed`.
    pub trim_boundary: u64,
}

/// The distributed ray tracing's counts: of the ray-tracing hider (Appendix B), in place of
/// the dicer's and the stochastic hider's, or of the stochastic hider's ray-traced vertex
/// shading, besides them.
#[derive(Debug, Clone, Copy, Default)]
pub struct RaySummary {
    /// The ray-tracing hider rendered the frame (else the stochastic hider, with ray-traced
    /// vertex shading).
    pub ray_hider: bool,
    /// Primitives the ray engine built from the scene.
    pub primitives: u64,
    /// Nodes of its bounding volume hierarchy.
    pub nodes: u64,
    /// Primary rays traced (one per sample of every bucket; 0 for vertex shading).
    pub primary: u64,
    /// Primary rays that met a surface.
    pub hits: u64,
    /// Grid vertices shaded with distributed rays (0 for the ray-tracing hider).
    pub vertices: u64,
    /// Rays per effect per vertex (`raytrace.vertex_rays`; 0 for the ray-tracing hider).
    pub vertex_rays: u32,
    /// Secondary rays, by kind.
    pub secondary: reyes_shade::RayCounts,
}

impl RaySummary {
    /// One line of secondary-ray counts.
    fn secondary_line(&self) -> String {
        let c = &self.secondary;
        format!(
            " Secondary rays: {} ({} shadow, {} reflection, {} refraction, {} continuation)",
            c.total(),
            c.shadow,
            c.reflection,
            c.refraction,
            c.continuation
        )
    }
}

/// Everything `--stats` prints.
#[derive(Debug, Clone)]
pub struct RenderStats {
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Samples per pixel (nx, ny).
    pub samples: (u32, u32),
    /// Reconstruction filter.
    pub filter: Filter,
    /// Bucket layout.
    pub frame: Frame,
    /// Buckets that had micropolygons.
    pub buckets_rendered: usize,
    /// Dicer counts.
    pub dice: DiceSummary,
    /// Micropolygons emitted.
    pub micropolygons: u64,
    /// Adaptive sampling was on (its counts are printed even when nothing was refined).
    pub adaptive: bool,
    /// Hider counts.
    pub hider: reyes_hider::Stats,
    /// Time to dice and shade (the ray-tracing hider: to build the ray engine).
    pub t_dice: Duration,
    /// Time in the bucket loop (sampling, resolving, filtering).
    pub t_hide: Duration,
    /// Time to accumulate bucket windows.
    pub t_film: Duration,
    /// Time to write the output file.
    pub t_write: Duration,
    /// Peak resident memory of the process in bytes, where the platform reports it.
    pub peak_memory: Option<u64>,
    /// The ray-tracing hider's counts, when it rendered the frame (then the dicer and hider
    /// counts are zero and not printed).
    pub rays: Option<RaySummary>,
    /// Look development's counts, when the scene has texture maps, displacement, bump or
    /// emission.
    pub lookdev: Option<LookdevSummary>,
    /// The shading-language machine's counts, when some object is shaded by an RSL shader.
    pub shaders: Option<ShaderSummary>,
}

/// The shading-language machine's counts (docs/shading.md).
#[derive(Debug, Clone, Copy, Default)]
pub struct ShaderSummary {
    /// Instructions run (IR nodes evaluated and loop iterations, over every grid).
    pub instructions: u64,
    /// Non-finite floats the shaders produced (replaced by 0 before the hider).
    pub nonfinite: u64,
    /// Diced cells displaced beyond their object's declared bound (all displacements).
    pub escapes: u64,
}

/// Look development's counts (docs/lookdev.md).
#[derive(Debug, Clone, Copy, Default)]
pub struct LookdevSummary {
    /// Grid vertices shaded (each once: the corners of kept micropolygons).
    pub vertices: u64,
    /// The texture system's totals (its cache counts depend on thread timing: they are
    /// printed with the times, not the counts).
    pub textures: reyes_dice::TextureStats,
    /// Diced cells with a corner displaced beyond its object's declared bound.
    pub escapes: u64,
}

/// Peak resident set size of this process (Linux: `VmHWM` in /proc/self/status).
pub fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

fn pct(a: u64, b: u64) -> f64 {
    100.0 * a as f64 / (b.max(1)) as f64
}

impl RenderStats {
    /// The statistics of a frame of `scene` rendered with `config` over `frame`, with every
    /// count and time still zero.
    pub fn new(scene: &Scene, config: &HiderConfig, frame: Frame) -> RenderStats {
        RenderStats {
            width: scene.image.width,
            height: scene.image.height,
            samples: (config.nx, config.ny),
            filter: scene.hider.filter,
            frame,
            buckets_rendered: 0,
            dice: DiceSummary::default(),
            micropolygons: 0,
            hider: Default::default(),
            adaptive: config.adaptive.is_some(),
            t_dice: Duration::ZERO,
            t_hide: Duration::ZERO,
            t_film: Duration::ZERO,
            t_write: Duration::ZERO,
            peak_memory: None,
            rays: None,
            lookdev: None,
            shaders: None,
        }
    }

    /// The counts only (no times): stable across runs and machines.
    pub fn counts(&self) -> String {
        let h = &self.hider;
        let f = &self.frame;
        let mut s = String::new();
        use std::fmt::Write;
        let _ = writeln!(
            s,
            " Image: {} x {}, {} by {} samples per pixel, {:?} filter {} pixels wide",
            self.width,
            self.height,
            self.samples.0,
            self.samples.1,
            self.filter.kind,
            match self.filter.height {
                Some(h) if h != self.filter.width => format!("{} x {h}", self.filter.width),
                _ => format!("{}", self.filter.width),
            }
        );
        if let Some(r) = self.rays.as_ref().filter(|r| r.ray_hider) {
            let _ = writeln!(
                s,
                " Buckets: {} x {} pixels, {} x {} ({} where rays met surfaces), border {}",
                f.bucket_w, f.bucket_h, f.buckets_x, f.buckets_y, self.buckets_rendered, f.border
            );
            let _ = writeln!(
                s,
                " Ray tracer: {} primitives, {} hierarchy nodes",
                r.primitives, r.nodes
            );
            let _ = writeln!(
                s,
                " Primary rays: {} ({:5.2}% hit a surface: {} hits and {} misses)",
                r.primary,
                pct(r.hits, r.primary),
                r.hits,
                r.primary - r.hits
            );
            let _ = writeln!(s, "{}", r.secondary_line());
            return s;
        }
        let _ = writeln!(
            s,
            " Buckets: {} x {} pixels, {} x {} ({} with micropolygons), border {}",
            f.bucket_w, f.bucket_h, f.buckets_x, f.buckets_y, self.buckets_rendered, f.border
        );
        let _ = writeln!(
            s,
            " Dicer: {} primitives, {} splits, {} grids, {} micropolygons, {} of {} vertices \
             shaded, {} culled, {} diced for flatness",
            self.dice.primitives,
            self.dice.splits,
            self.dice.grids,
            self.micropolygons,
            self.dice.shaded,
            self.dice.vertices,
            self.dice.culled,
            self.dice.flatness
        );
        let _ = writeln!(
            s,
            " Micropolygons in buckets: {} ({:.2} buckets per micropolygon)",
            h.micropolygons,
            h.micropolygons as f64 / self.micropolygons.max(1) as f64
        );
        let _ = writeln!(
            s,
            " Occlusion culling: {} micropolygons occlusion-culled ({:5.2}% of those in buckets), {} sample tests skipped behind opaque samples",
            h.occlusion_culled,
            pct(h.occlusion_culled, h.micropolygons),
            h.occluded_tests
        );
        if self.dice.trimmed + self.dice.trim_boundary + h.trim_tests > 0 {
            let _ = writeln!(
                s,
                " Trimming: {} cells dropped in trimmed regions, {} micropolygons on trim curves, {} samples tested against trim curves ({} trimmed away)",
                self.dice.trimmed, self.dice.trim_boundary, h.trim_tests, h.trimmed
            );
        }
        let tests = h.hits + h.misses;
        let _ = writeln!(
            s,
            " Hider samples: {:5.2}% ({} hits and {} misses)",
            pct(h.hits, tests),
            h.hits,
            h.misses
        );
        let _ = writeln!(
            s,
            " Hider lerps: {:5.2}% ({} lerps out of {} hits)",
            pct(h.lerps, h.hits),
            h.lerps,
            h.hits
        );
        let _ = writeln!(
            s,
            " Visiblepoints: {} created, {} peak in one bucket ({} kB)",
            h.points,
            h.peak_points,
            h.peak_points * std::mem::size_of::<reyes_hider::VisPoint>() as u64 / 1024
        );
        if h.refined_pixels > 0 || self.adaptive {
            let _ = writeln!(
                s,
                " Adaptive sampling: {} pixels refined, {} extra samples ({:.2} per pixel of the image)",
                h.refined_pixels,
                h.extra_samples,
                h.extra_samples as f64 / (self.width as f64 * self.height as f64).max(1.0)
            );
        }
        if let Some(r) = &self.rays {
            let _ = writeln!(
                s,
                " Ray-traced vertex shading: {} vertices, {} rays per effect per vertex; ray engine {} primitives, {} hierarchy nodes",
                r.vertices, r.vertex_rays, r.primitives, r.nodes
            );
            let _ = writeln!(s, "{}", r.secondary_line());
        }
        if let Some(sh) = &self.shaders {
            let _ = writeln!(
                s,
                " Shaders: {} instructions, {} non-finite values replaced by 0",
                sh.instructions, sh.nonfinite
            );
        }
        if let Some(l) = &self.lookdev {
            let t = &l.textures;
            let _ = writeln!(
                s,
                " Look development: {} vertices shaded, {} textures ({} texels in their MIP pyramids, {} kB), {} texture lookups, {} micropolygons displaced beyond their declared bound",
                l.vertices,
                t.textures,
                t.texels,
                t.pyramid_bytes / 1024,
                t.lookups,
                l.escapes
            );
        }
        s
    }
}

impl fmt::Display for RenderStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.counts())?;
        let total = self.t_dice + self.t_hide + self.t_film + self.t_write;
        let tests = self.hider.hits + self.hider.misses;
        writeln!(
            f,
            " Time: {} {:.3} s, hide {:.3} s, film {:.3} s, write {:.3} s, total {:.3} s",
            if self.rays.is_some_and(|r| r.ray_hider) { "ray engine" } else { "dice" },
            self.t_dice.as_secs_f64(),
            self.t_hide.as_secs_f64(),
            self.t_film.as_secs_f64(),
            self.t_write.as_secs_f64(),
            total.as_secs_f64()
        )?;
        if let Some(r) = self.rays.as_ref().filter(|r| r.ray_hider) {
            writeln!(
                f,
                " Primary rays per second (bucket loop, all threads): {:.3} million",
                r.primary as f64 / self.t_hide.as_secs_f64().max(1e-9) / 1e6
            )?;
            if let Some(m) = self.peak_memory {
                writeln!(f, " Memory: peak resident {:.1} MB", m as f64 / 1e6)?;
            }
            return Ok(());
        }
        writeln!(
            f,
            " Hider time (summed over threads): sampling {:.3} s, resolving visible points (CSG, compositing) {:.3} s",
            self.hider.sample_ns as f64 * 1e-9,
            self.hider.resolve_ns as f64 * 1e-9
        )?;
        writeln!(
            f,
            " Sample tests per second (bucket loop, all threads): {:.1} million",
            tests as f64 / self.t_hide.as_secs_f64().max(1e-9) / 1e6
        )?;
        if let Some(l) = &self.lookdev {
            let c = &l.textures.cache;
            writeln!(
                f,
                " Textures: loaded and MIP-mapped in {:.3} s; cache at most {} of {} kB, {} tile misses of {} requests, {} evictions; {:.2} million lookups and {:.2} million vertices shaded per second of dicing",
                l.textures.load_time.as_secs_f64(),
                c.peak / 1024,
                c.bound / 1024,
                c.misses,
                c.requests,
                c.evictions,
                l.textures.lookups as f64 / self.t_dice.as_secs_f64().max(1e-9) / 1e6,
                l.vertices as f64 / self.t_dice.as_secs_f64().max(1e-9) / 1e6
            )?;
        }
        if let Some(m) = self.peak_memory {
            write!(f, " Memory: peak resident {:.1} MB", m as f64 / 1e6)?;
            if self.dice.peak_micropolygons > 0 {
                write!(f, ", at most {} micropolygons held at once", self.dice.peak_micropolygons)?;
            }
            if self.dice.eager {
                write!(f, " (diced up front: a patch bound missed)")?;
            }
            writeln!(f)?;
        }
        Ok(())
    }
}
