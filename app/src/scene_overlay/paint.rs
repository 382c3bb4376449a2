//! The overlays' screen part, painted with egui after the frame: boat labels (team-colour
//! bar, rank and name, a stem down to the masthead), the gap texts of the ahead/behind lines
//! and the wind figure. The desktop window paints them in its egui pass; `regatta render`
//! paints the same shapes into its offscreen frame with egui-wgpu ([`render_with_overlays`]).

use super::OverlayFrame;
use super::labels::{self, BAR_PT, LABEL_TEXT_PT, PAD_PT, PlacedLabel};
use crate::hud::EguiPainter;

/// A text at a framebuffer pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct ScreenText {
    pub pos: [f64; 2],
    pub text: String,
    pub colour: [f32; 3],
}

/// Size of the gap and wind texts, points.
pub const SCENE_TEXT_PT: f64 = 12.0;

/// egui's colour of a linear RGB colour.
pub fn colour32(c: [f32; 3], alpha: u8) -> egui::Color32 {
    let s = |v: f32| {
        let v = v.clamp(0.0, 1.0);
        let e = if v <= 0.003_130_8 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        };
        (e * 255.0).round() as u8
    };
    egui::Color32::from_rgba_unmultiplied(s(c[0]), s(c[1]), s(c[2]), alpha)
}

/// Pixels per point of a headless frame of `size`: a portrait frame is a phone 360 points
/// wide (720×1600 → 2, 1080×2400 → 3); a landscape one a desktop window (1 up to 1080 rows).
pub fn headless_pixels_per_point(size: [u32; 2]) -> f64 {
    let [w, h] = size.map(f64::from);
    if h > w {
        (w / 360.0).max(1.0)
    } else {
        (h / 1080.0).max(1.0)
    }
}

/// A text's size in pixels at `font_px` pixels, as egui lays it out (inside an egui pass).
pub fn measure(ctx: &egui::Context, text: &str, font_px: f64) -> [f64; 2] {
    let ppp = f64::from(ctx.pixels_per_point());
    let size = ctx.fonts_mut(|f| {
        f.layout_no_wrap(
            text.to_string(),
            egui::FontId::proportional((font_px / ppp) as f32),
            egui::Color32::WHITE,
        )
        .size()
    });
    [f64::from(size.x) * ppp, f64::from(size.y) * ppp]
}

/// Places the frame's labels with egui's text sizes and paints them and the scene texts on
/// `ctx`'s background layer; returns the placed labels (for picking).
pub fn paint(ctx: &egui::Context, frame: &OverlayFrame, screen_px: [u32; 2]) -> Vec<PlacedLabel> {
    let ppp = f64::from(ctx.pixels_per_point());
    let placed = labels::place(
        &frame.labels,
        screen_px.map(f64::from),
        ppp,
        &|t: &str, px: f64| measure(ctx, t, px),
    );
    let painter = ctx.layer_painter(egui::LayerId::background());
    let pt = |p: [f64; 2]| egui::pos2((p[0] / ppp) as f32, (p[1] / ppp) as f32);
    // Scene texts where they overlap no label and no text before them, on a dark plate.
    let mut taken: Vec<[f64; 4]> = placed.iter().map(|l| l.rect).collect();
    let pad = 3.0 * ppp;
    for t in &frame.texts {
        let [w, h] = measure(ctx, &t.text, SCENE_TEXT_PT * ppp);
        let r = [
            t.pos[0],
            t.pos[1] - h / 2.0 - pad,
            t.pos[0] + w + 2.0 * pad,
            t.pos[1] + h / 2.0 + pad,
        ];
        if taken.iter().any(|q| labels::overlaps(q, &r, 1.0)) {
            continue;
        }
        taken.push(r);
        let plate = egui::Rect::from_min_max(pt([r[0], r[1]]), pt([r[2], r[3]]));
        painter.rect_filled(plate, 3.0, egui::Color32::from_black_alpha(150));
        painter.text(
            egui::pos2(plate.left() + 3.0, plate.center().y),
            egui::Align2::LEFT_CENTER,
            &t.text,
            egui::FontId::proportional(SCENE_TEXT_PT as f32),
            colour32(t.colour.map(|c| 0.35 + 0.65 * c), 255),
        );
    }
    // Lowest priority first, so the leader's and the selected boats' labels end on top.
    for l in placed.iter().rev() {
        let r = egui::Rect::from_min_max(pt([l.rect[0], l.rect[1]]), pt([l.rect[2], l.rect[3]]));
        let stem_top = egui::pos2(pt(l.anchor).x.clamp(r.left(), r.right()), r.bottom());
        painter.line_segment(
            [pt(l.anchor), stem_top],
            egui::Stroke::new(1.5, egui::Color32::from_white_alpha(200)),
        );
        painter.rect_filled(r, 3.0, egui::Color32::from_black_alpha(185));
        let bar = egui::Rect::from_min_size(r.min, egui::vec2(BAR_PT as f32, r.height()));
        painter.rect_filled(bar, 2.0, colour32(l.colour, 255));
        if l.selected {
            painter.rect_stroke(
                r,
                3.0,
                egui::Stroke::new(2.0, egui::Color32::WHITE),
                egui::StrokeKind::Outside,
            );
        }
        painter.text(
            egui::pos2(r.left() + (BAR_PT + PAD_PT) as f32, r.center().y),
            egui::Align2::LEFT_CENTER,
            &l.text,
            egui::FontId::proportional(LABEL_TEXT_PT as f32),
            egui::Color32::WHITE,
        );
    }
    placed
}

/// Draws `scene` with `renderer` into an offscreen frame and paints the overlay's egui part
/// over it, as the window does: the image, the frame record and the placed labels.
pub fn render_with_overlays(
    gpu: &render::Gpu,
    renderer: &mut render::Renderer,
    scene: &render::Scene,
    size: [u32; 2],
    frame: &OverlayFrame,
    pixels_per_point: f64,
) -> Result<(image::RgbaImage, render::FrameReport, Vec<PlacedLabel>), render::GpuError> {
    let format = renderer.targets.colour;
    let texture = render::gpu::texture_2d_with_views(
        &gpu.device,
        "overlay frame",
        size,
        format,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        &[format.remove_srgb_suffix()],
    );
    let report = renderer.render(gpu, &texture.create_view(&Default::default()), size, scene)?;
    let mut painter = EguiPainter::for_format(&gpu.device, format.remove_srgb_suffix());
    let placed = paint_over(&mut painter, gpu, &texture, size, frame, pixels_per_point);
    let img = gpu.read_texture(&texture)?;
    Ok((img, report, placed))
}

/// Paints the overlay's egui part over `texture` (`size` pixels) with `painter` (one egui pass
/// at `pixels_per_point`, no input); returns the placed labels.
pub fn paint_over(
    painter: &mut EguiPainter,
    gpu: &render::Gpu,
    texture: &wgpu::Texture,
    size: [u32; 2],
    frame: &OverlayFrame,
    pixels_per_point: f64,
) -> Vec<PlacedLabel> {
    let mut raw = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(size[0] as f32, size[1] as f32) / pixels_per_point as f32,
        )),
        ..Default::default()
    };
    raw.viewports
        .entry(egui::ViewportId::ROOT)
        .or_default()
        .native_pixels_per_point = Some(pixels_per_point as f32);
    let mut placed = Vec::new();
    painter.paint(&gpu.device, &gpu.queue, texture, size, raw, |ui| {
        placed = paint(ui.ctx(), frame, size);
    });
    placed
}
