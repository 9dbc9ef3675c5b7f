//! The figures of the study, drawn with plotters into docs/study/.

use std::path::Path;

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use reyes_hider::{Frame, Hider, HiderConfig, Pairing, ShutterShape};
use reyes_render::{RenderOptions, render};

use super::edges::{EdgeStudy, fit_slope};
use super::patterns::{self, Sampler};
use super::{
    ADAPTIVE, AdaptiveResults, Area, CaseResults, FONT, Res, colour, rmse_of, samples_per_pixel,
    significant,
};

/// Grey level in [0, 1] (linear) as an sRGB colour.
fn grey(v: f32) -> RGBColor {
    let g = (reyes_film::srgb_encode(v.clamp(0.0, 1.0)) * 255.0).round() as u8;
    RGBColor(g, g, g)
}

/// A perceptual colour map (viridis, by linear interpolation of 6 stops) for `u` in [0, 1].
fn viridis(u: f64) -> RGBColor {
    const STOPS: [(f64, f64, f64); 6] = [
        (68.0, 1.0, 84.0),
        (65.0, 68.0, 135.0),
        (42.0, 120.0, 142.0),
        (34.0, 168.0, 132.0),
        (122.0, 209.0, 81.0),
        (253.0, 231.0, 37.0),
    ];
    let x = u.clamp(0.0, 1.0) * 5.0;
    let i = (x.floor() as usize).min(4);
    let f = x - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let l = |p: f64, q: f64| (p + (q - p) * f).round() as u8;
    RGBColor(l(a.0, b.0), l(a.1, b.1), l(a.2, b.2))
}

/// Pixel and stratum grid lines on a chart over `[0, px] x [0, px]`.
fn grid(
    chart: &mut ChartContext<'_, BitMapBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    px: u32,
    strata: u32,
) -> Res {
    let fine = px * strata;
    for i in 0..=fine {
        let v = i as f64 / strata as f64;
        let style = if i % strata == 0 {
            ShapeStyle::from(&BLACK).stroke_width(2)
        } else {
            ShapeStyle::from(&RGBColor(200, 200, 200)).stroke_width(1)
        };
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(v, 0.0), (v, px as f64)],
            style,
        )))?;
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(0.0, v), (px as f64, v)],
            style,
        )))?;
    }
    Ok(())
}

/// FIGS. 3, 5, 6, 7, random, Owen-Sobol and the joint sampler: 3 x 3 pixels of 4 x 4
/// samples each.
pub(super) fn patterns(path: &Path) -> Res {
    let root = BitMapBackend::new(path, (1600, 860)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "Sample positions, 4 x 4 samples per pixel over 3 x 3 pixels (thick: pixels; thin: strata)",
        (FONT, 22),
    )?;
    for (panel, sampler) in root.split_evenly((2, 4)).iter().zip(Sampler::ALL) {
        let pts = patterns::samples(sampler, 4, 4, 3, 3, 7, Pairing::Decorrelated);
        let mut chart = ChartBuilder::on(panel)
            .caption(sampler.label(), (FONT, 20))
            .margin(12)
            .build_cartesian_2d(0.0..3.0, 3.0..0.0)?;
        grid(&mut chart, 3, 4)?;
        chart.draw_series(
            pts.iter().map(|s| Circle::new((s.x as f64, s.y as f64), 4, colour(sampler).filled())),
        )?;
    }
    root.present()?;
    Ok(())
}

/// FIG. 12 and FIGS. 13-16: the time of each sample against its position.
pub(super) fn time_figure(path: &Path) -> Res {
    let root = BitMapBackend::new(path, (1600, 1180)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "Time against position (FIG. 12) and the shutter's time density (FIGS. 13-16)",
        (FONT, 22),
    )?;
    let rows = root.split_evenly((3, 1));
    let cases = [
        (Sampler::Fig6, Pairing::Original, "App. A: sample s in time stratum s"),
        (Sampler::Fig6, Pairing::Decorrelated, "FIG. 6, decorrelated pairing"),
        (Sampler::Sobol, Pairing::Decorrelated, "Owen-Sobol, scrambled time"),
        (Sampler::SobolJoint, Pairing::Decorrelated, "joint: time from the same net"),
    ];
    // Row 1: 2 x 2 pixels of 4 x 4 samples, coloured by time (dark: opening, yellow: closing).
    for (panel, (sampler, pairing, label)) in rows[0].split_evenly((1, 4)).iter().zip(cases) {
        let pts = patterns::samples(sampler, 4, 4, 2, 2, 3, pairing);
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("{label}: colour = time"), (FONT, 16))
            .margin(10)
            .build_cartesian_2d(0.0..2.0, 2.0..0.0)?;
        grid(&mut chart, 2, 4)?;
        chart.draw_series(
            pts.iter()
                .map(|s| Circle::new((s.x as f64, s.y as f64), 6, viridis(s.t as f64).filled())),
        )?;
    }
    // Row 2: time against sub-pixel y over 32 x 32 pixels.
    for (panel, (sampler, pairing, label)) in rows[1].split_evenly((1, 4)).iter().zip(cases) {
        let pts = patterns::samples(sampler, 4, 4, 32, 32, 3, pairing);
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("{label}: t against sub-pixel y"), (FONT, 16))
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(40)
            .build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("sub-pixel y")
            .y_desc("time")
            .label_style((FONT, 13))
            .draw()?;
        chart.draw_series(pts.iter().map(|s| {
            Circle::new(
                ((s.y - s.y.floor()) as f64, s.t as f64),
                1,
                colour(sampler).mix(0.5).filled(),
            )
        }))?;
    }
    // Row 3: one pixel's sample times per stratum (FIG. 13/14) and the time histograms of
    // the uniform (FIGS. 13-15) and gradual (FIG. 16) shutters.
    let panels = rows[2].split_evenly((1, 3));
    {
        let pts = patterns::samples(Sampler::Fig6, 2, 2, 8, 1, 5, Pairing::Decorrelated);
        let mut chart = ChartBuilder::on(&panels[0])
            .caption("FIGS. 13/14: 4 samples, one per quarter of the shutter", (FONT, 16))
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(40)
            .build_cartesian_2d(0.0..1.0, -0.5..7.5)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("time")
            .y_desc("pixel")
            .label_style((FONT, 13))
            .draw()?;
        for q in 0..=4 {
            let v = q as f64 / 4.0;
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(v, -0.5), (v, 7.5)],
                RGBColor(190, 190, 190),
            )))?;
        }
        chart.draw_series(pts.chunks(4).enumerate().flat_map(|(p, px)| {
            px.iter().map(move |s| {
                Circle::new((s.t as f64, p as f64), 4, colour(Sampler::Fig6).filled())
            })
        }))?;
    }
    for (panel, shape, label) in [
        (&panels[1], ShutterShape::Uniform, "uniform shutter (FIGS. 13-15): times"),
        (&panels[2], ShutterShape::Gradual { ramp: 0.3 }, "gradual shutter (FIG. 16): times"),
    ] {
        let cfg = HiderConfig { shutter: shape, ..HiderConfig::default() };
        let frame = Frame::new(64, 64, 0, 16, 16);
        let hider = Hider::new(cfg, frame);
        let bins = 40;
        let mut hist = vec![0usize; bins];
        let mut n = 0;
        for b in 0..frame.bucket_count() {
            for &t in &hider.bucket_samples(b).t {
                hist[((t * bins as f32) as usize).min(bins - 1)] += 1;
                n += 1;
            }
        }
        let mut chart = ChartBuilder::on(panel)
            .caption(label, (FONT, 16))
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(40)
            .build_cartesian_2d(0.0..1.0, 0.0..1.6)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("time")
            .y_desc("density")
            .label_style((FONT, 13))
            .draw()?;
        chart.draw_series(hist.iter().enumerate().map(|(i, &c)| {
            let d = c as f64 * bins as f64 / n as f64;
            Rectangle::new(
                [(i as f64 / bins as f64, 0.0), ((i + 1) as f64 / bins as f64, d)],
                colour(Sampler::Fig6).mix(0.5).filled(),
            )
        }))?;
        chart.draw_series(LineSeries::new(
            (0..=200).map(|i| {
                let t = i as f32 / 200.0;
                (t as f64, shape.density(t) as f64)
            }),
            BLACK.stroke_width(2),
        ))?;
    }
    root.present()?;
    Ok(())
}

/// Frequency bands (cycles per pixel) of the periodogram table in results.md.
pub(super) const BANDS: [(f64, f64); 5] =
    [(0.0, 0.5), (0.5, 1.0), (1.0, 2.0), (2.0, 4.0), (4.0, 8.0)];

/// Periodograms of every pattern (FIGS. 10, 11): 2-D maps and radial averages. Returns each
/// pattern's mean power in [`BANDS`].
pub(super) fn periodograms(out: &Path, windows: u32) -> Res<Vec<(Sampler, Vec<f64>)>> {
    let (half, step) = (64usize, 0.125);
    let spectra: Vec<(Sampler, patterns::Spectrum)> = Sampler::ALL
        .iter()
        .map(|&s| (s, patterns::mean_periodogram(s, 4, 8, windows, half, step, 11)))
        .collect();
    let bands = spectra
        .iter()
        .map(|(s, spec)| (*s, BANDS.iter().map(|&(lo, hi)| spec.band(lo, hi)).collect()))
        .collect();
    let path = out.join("periodograms.png");
    let root = BitMapBackend::new(&path, (1600, 880)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        &format!(
            "Periodograms, 4 x 4 samples per pixel, mean of {windows} windows of 8 x 8 pixels \
             (log scale: white noise = middle colour)"
        ),
        (FONT, 20),
    )?;
    let kmax = half as f64 * step;
    for (panel, (sampler, spec)) in root.split_evenly((2, 4)).iter().zip(&spectra) {
        let mut chart = ChartBuilder::on(panel)
            .caption(sampler.label(), (FONT, 18))
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(35)
            .build_cartesian_2d(-kmax..kmax, -kmax..kmax)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("cycles per pixel")
            .label_style((FONT, 12))
            .draw()?;
        let side = spec.side();
        chart.draw_series((0..side * side).map(|k| {
            let (i, j) = (k % side, k / side);
            let (fx, fy) = ((i as f64 - half as f64) * step, (j as f64 - half as f64) * step);
            // log10 power from -2 (dark) to +2 (yellow); white noise (power 1) in the middle.
            let u = (spec.power[k].max(1e-12).log10() + 2.0) / 4.0;
            Rectangle::new(
                [(fx - step / 2.0, fy - step / 2.0), (fx + step / 2.0, fy + step / 2.0)],
                viridis(u).filled(),
            )
        }))?;
    }
    root.present()?;

    let path = out.join("periodogram-radial.png");
    let root = BitMapBackend::new(&path, (1000, 600)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Radially averaged periodogram, 4 x 4 samples per pixel (regular and FIG. 5: spikes only, see the maps)",
            (FONT, 18),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..kmax, (1e-3..1e1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("frequency, cycles per pixel (sampling rate: 4)")
        .y_desc("power (1 = white noise)")
        .y_label_formatter(&|v| format!("{v}"))
        .light_line_style(RGBColor(240, 240, 240))
        .label_style((FONT, 15))
        .draw()?;
    // The regular grid and FIG. 5 are pure spikes (power zero between them): see the maps.
    for (sampler, spec) in
        spectra.iter().filter(|(s, _)| !matches!(s, Sampler::Regular | Sampler::Fig5))
    {
        let c = colour(*sampler);
        chart
            .draw_series(LineSeries::new(
                spec.radial().into_iter().map(|(k, p)| (k, p.max(1e-3))),
                c.stroke_width(2),
            ))?
            .label(sampler.label())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .label_font((FONT, 15))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(bands)
}

/// Draw a grey image (linear values) scaled by `scale` into `area`, at (x0, y0).
fn draw_image(area: &Area, img: &[f32], w: u32, scale: u32, at: (i32, i32)) -> Res {
    let h = img.len() as u32 / w;
    for y in 0..h * scale {
        for x in 0..w * scale {
            let v = img[((y / scale) * w + x / scale) as usize];
            area.draw_pixel((at.0 + x as i32, at.1 + y as i32), &grey(v))?;
        }
    }
    Ok(())
}

/// The picket fence (patent FIGS. 8 and 9) rendered with the regular grid, FIG. 6 jitter,
/// pure random, Owen-Sobol, the joint sampler and adaptive sampling; returns, for uniform and
/// adaptive sampling with the joint sampler, (label, samples per pixel spent, RMSE of the red
/// channel against a uniform 16 x 16 render).
pub(super) fn picket_fence(root_dir: &Path, path: &Path) -> Res<Vec<(String, f64, f64)>> {
    let regular = reyes_scene::load(&root_dir.join("scenes/picket-fence.ron"))?;
    let jittered = reyes_scene::load(&root_dir.join("scenes/picket-fence-jittered.ron"))?;
    let mut sobol = jittered.clone();
    sobol.hider.pattern = reyes_scene::SpatialPattern::Sobol;
    let mut random = jittered.clone();
    random.hider.pattern = reyes_scene::SpatialPattern::Random;
    let mut joint = jittered.clone();
    joint.hider.pattern = reyes_scene::SpatialPattern::SobolJoint;
    let mut adaptive = joint.clone();
    adaptive.hider.adaptive.max_level = 2;
    let panels = [
        ("picket-fence.ron: regular grid (FIG. 3 sampling; patent FIG. 8)", regular),
        ("picket-fence-jittered.ron: FIG. 6 jitter (patent FIG. 9)", jittered),
        ("the same, pure random", random),
        ("the same, Owen-Sobol (0,2)", sobol),
        ("the same, joint Sobol + CMJ", joint.clone()),
        ("the same, adaptive (2 x 2 base, 2 levels)", adaptive),
    ];
    let (w, h) = (panels[0].1.image.width, panels[0].1.image.height);
    let scale = 2;
    let (cw, ch) = (w * scale + 20, h * scale + 34);
    let root = BitMapBackend::new(path, (2 * cw + 20, 3 * ch + 40)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "Picket fence, 2 x 2 samples per pixel, one-pixel box filter (shown at 2x)",
        (FONT, 20),
    )?;
    for (i, (label, scene)) in panels.iter().enumerate() {
        let film = render(scene, &RenderOptions::default())?.film;
        let img: Vec<f32> = film.rgba().iter().map(|p| p[0]).collect();
        let (x0, y0) = (20 + (i as i32 % 2) * cw as i32, (i as i32 / 2) * ch as i32);
        root.draw_text(label, &(FONT, 16).into_text_style(&root), (x0, y0 + 4))?;
        draw_image(&root, &img, w, scale, (x0, y0 + 28))?;
    }
    root.present()?;

    // Uniform against adaptive, as differences from a uniform 16 x 16 render.
    let red = |scene: &reyes_scene::Scene| -> Res<(Vec<f32>, f64)> {
        let r = render(scene, &RenderOptions::default())?;
        let px = (scene.image.width * scene.image.height) as f64;
        let ns = (scene.hider.pixel_samples.0 * scene.hider.pixel_samples.1) as f64;
        let spp = ns + r.stats.hider.extra_samples as f64 / px;
        Ok((r.film.rgba().iter().map(|p| p[0]).collect(), spp))
    };
    let with = |n: u32, level: u32| {
        let mut s = joint.clone();
        s.hider.pixel_samples = (n, n);
        s.hider.adaptive.max_level = level;
        s
    };
    // Its own seed, so that its samples share nothing with those it is compared with.
    let mut reference = with(16, 0);
    reference.hider.seed += 1000;
    let reference = red(&reference)?.0;
    let mut rows = Vec::new();
    for (n, level) in [(2, 0), (4, 0), (8, 0), (2, 1), (2, 2), (4, 1), (4, 2)] {
        let (img, spp) = red(&with(n, level))?;
        let se: f64 =
            img.iter().zip(&reference).map(|(a, b)| (f64::from(*a) - f64::from(*b)).powi(2)).sum();
        let label = match level {
            0 => format!("uniform {n} x {n}"),
            l => format!("adaptive, {n} x {n} base, {l} level{}", if l > 1 { "s" } else { "" }),
        };
        rows.push((label, spp, (se / img.len() as f64).sqrt()));
    }
    Ok(rows)
}

/// The zone plate point-sampled through every pattern at 1 and 2 x 2 samples per pixel.
pub(super) fn zone_plates(path: &Path, size: u32) -> Res {
    let f = 1.5;
    let reference = patterns::zone_plate_reference(size, f);
    let cols = 1 + Sampler::ALL.len() as u32;
    let (cw, ch) = (size + 12, size + 28);
    let root = BitMapBackend::new(path, (cols * cw + 12, 2 * ch + 36)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        &format!(
            "Zone plate point-sampled through each pattern, one-pixel box filter; frequency 0 at \
             the centre, {f} cycles/pixel at the sides' midpoints. Top: 1 sample per pixel; \
             bottom: 2 x 2."
        ),
        (FONT, 16),
    )?;
    for (row, n) in [1u32, 2].into_iter().enumerate() {
        let mut images = vec![("box-filtered truth".to_string(), reference.clone())];
        for s in Sampler::ALL {
            images.push((s.label().to_string(), patterns::zone_plate(s, n, size, f, 3)));
        }
        for (i, (label, img)) in images.iter().enumerate() {
            let (x0, y0) = (12 + i as i32 * cw as i32, row as i32 * ch as i32);
            root.draw_text(label, &(FONT, 13).into_text_style(&root), (x0, y0 + 4))?;
            draw_image(&root, img, size, 1, (x0, y0 + 22))?;
        }
    }
    root.present()?;
    Ok(())
}

/// RMSE against samples per pixel, log-log, one panel per edge case. The axes are linear in
/// log10 of the values (labelled with the values), so the grid and labels stay plain.
pub(super) fn error_figure(
    path: &Path,
    study: &EdgeStudy,
    results: &[CaseResults],
    adaptive: &[AdaptiveResults],
) -> Res {
    let spp = samples_per_pixel();
    let lspp: Vec<f64> = spp.iter().map(|s| s.log10()).collect();
    let root = BitMapBackend::new(path, (1400, 1160)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        &format!(
            "RMSE of edge pixels against analytic truth, {} random edges per point \
             (legend: fitted slope; dashed: slopes -0.5 and -0.75)",
            study.edges
        ),
        (FONT, 18),
    )?;
    for ((panel, (case, rows)), (_, adapt)) in
        root.split_evenly((2, 2)).iter().zip(results).zip(adaptive)
    {
        let all =
            rows.iter().flat_map(|r| r.1.iter()).chain(adapt.iter().map(|a| &a.0)).map(|m| m.rmse);
        let lo = all.clone().fold(f64::INFINITY, f64::min).log10() - 0.15;
        let hi = all.fold(0.0, f64::max).log10() + 0.15;
        let mut chart = ChartBuilder::on(panel)
            .caption(case.label(), (FONT, 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(-0.1..2.7, lo..hi)?;
        chart
            .configure_mesh()
            .x_desc("samples per pixel")
            .y_desc("RMSE")
            .x_label_formatter(&|v| format!("{:.0}", 10f64.powf(*v)))
            .y_label_formatter(&|v| significant(10f64.powf(*v)))
            .light_line_style(WHITE)
            .bold_line_style(RGBColor(225, 225, 225))
            .label_style((FONT, 14))
            .draw()?;
        // Reference slopes through the random and FIG. 6 curves at 16 samples per pixel.
        let get = |s: Sampler| &rows.iter().find(|r| r.0 == s).expect("sampler").1;
        for (slope, at) in
            [(-0.5, get(Sampler::Random)[2].rmse * 1.3), (-0.75, get(Sampler::Fig6)[2].rmse / 1.3)]
        {
            let line = lspp.iter().map(|&x| (x, at.log10() + slope * (x - 16f64.log10())));
            chart.draw_series(DashedLineSeries::new(
                line.filter(|p| p.1 >= lo && p.1 <= hi),
                6,
                4,
                RGBColor(120, 120, 120).into(),
            ))?;
        }
        for (sampler, m) in rows {
            let rmse = &rmse_of(m);
            let c = colour(*sampler);
            let slope = fit_slope(&spp, rmse);
            let pts: Vec<(f64, f64)> =
                lspp.iter().zip(rmse).map(|(&x, r)| (x, r.log10())).collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))?
                .label(format!("{} ({slope:+.2})", sampler.label()))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 4, c.filled())))?;
        }
        // Adaptive sampling: one point per setting at the samples per pixel it spent.
        let c = RGBColor(86, 180, 233);
        let pts: Vec<(f64, f64)> =
            adapt.iter().map(|(m, spp)| (spp.log10(), m.rmse.log10())).collect();
        chart
            .draw_series(pts.iter().map(|&p| TriangleMarker::new(p, 7, c.filled())))?
            .label(format!(
                "adaptive, joint ({})",
                ADAPTIVE
                    .iter()
                    .map(|(n, l)| format!("{n}x{n} L{l}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
            .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 6, c.filled()));
        for ((n, l), p) in ADAPTIVE.iter().zip(&pts) {
            chart.draw_series(std::iter::once(Text::new(
                format!("{n}x{n} L{l}"),
                (p.0 + 0.03, p.1),
                (FONT, 12).into_font(),
            )))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerLeft)
            .label_font((FONT, 14))
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()?;
    }
    root.present()?;
    Ok(())
}
