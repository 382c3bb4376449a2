//! The camera image on the budget model: what uploading and converting ARCore's CPU image costs
//! each phone per camera frame, the largest image each tier affords
//! ([`quality::TierSettings::camera_image_max_px`], [`quality::CAMERA_IMAGE_SHARE`] of the frame
//! of the phone the tier is made for), and the config the phone's session then chooses from the
//! back camera's documented list (`ar::arcore::choose_camera_config`).

use ar::arcore::{CameraConfigSize, DOCUMENTED_BACK_CAMERA, choose_camera_config};
use quality::{CAMERA_IMAGE_SHARE, Tier};
use serde_json::json;

use super::budget_model::{PHONES, PhoneGpu, camera_yuv_work};
use super::budget_run::Row;
use super::shader_cost::Trips;
use crate::Table;
use regatta::error::{AppError, AppResult};

/// The phone and frame rate a tier is made for (quality's tier docs): `low` and `medium` the
/// OPPO A54 at 30 fps, `high` and `ultra` the Pixel 2 XL at 60 fps.
pub fn tier_frame(tier: Tier) -> (&'static PhoneGpu, f64) {
    match tier {
        Tier::Low | Tier::Medium => (&PHONES[0], 30.0),
        Tier::High | Tier::Ultra => (&PHONES[1], 60.0),
    }
}

/// Milliseconds of one camera image of `image` pixels on `phone` at the slow end of its spec
/// sheets (upload and conversion; the conversion shader has no loop, so no trip counts).
pub fn camera_image_ms(phone: &PhoneGpu, image: [u32; 2]) -> Result<f64, String> {
    let no_loops = Trips {
        waves: 0.0,
        resolved_waves_in_pixel: 0.0,
        fading_waves_in_pixel: 0.0,
        wake_sources_per_vertex: 0.0,
        wake_foam_sources_per_vertex: 0.0,
        vertex_waves_per_vertex: 0.0,
        marks: 0.0,
    };
    Ok(camera_yuv_work(image, 1.0, &no_loops)?.ms(phone, false))
}

/// The most pixels a camera image may have so that its upload and conversion take at most
/// [`CAMERA_IMAGE_SHARE`] of the frame `tier` is made for, on the model (the cost is
/// proportional to the pixels: every term of the roofline is).
pub fn affordable_px(tier: Tier) -> Result<f64, String> {
    let (phone, fps) = tier_frame(tier);
    let per_mpx = camera_image_ms(phone, [1000, 1000])?;
    Ok(CAMERA_IMAGE_SHARE * (1e3 / fps) / per_mpx * 1e6)
}

/// The back-camera config a session at `tier` chooses from the documented list (a portrait
/// screen of `screen` pixels).
pub fn chosen_config(tier: Tier, screen: [u32; 2]) -> CameraConfigSize {
    let budget = tier.settings().camera_image_max_px;
    let i = choose_camera_config(&DOCUMENTED_BACK_CAMERA, budget, Some(screen))
        .expect("the documented list is not empty");
    DOCUMENTED_BACK_CAMERA[i]
}

/// Per phone and tier: the tier's camera budget, the config chosen, its cost per camera frame
/// and its share of the tier's frame on that phone (the model's `rows`).
pub(crate) fn camera_table(rows: &[Row]) -> AppResult<Table> {
    let mut t = Table::new(
        "budget_camera",
        "The camera image per tier: the largest ARCore CPU image the budget affords, its upload and conversion on the model",
        &[
            "phone",
            "tier",
            "tier made for",
            "affordable px (model)",
            "camera_image_max_px",
            "CPU image chosen",
            "camera ms (slow spec)",
            "share of the tier's frame (1 / its fps)",
            "model ms with the image",
            "model fps with the image",
        ],
    );
    let err = AppError::new;
    for r in rows {
        let (goal_phone, fps) = tier_frame(r.tier);
        let chosen = chosen_config(r.tier, r.phone.screen);
        let ms = camera_image_ms(r.phone, chosen.image).map_err(err)?;
        // Every pass adds its milliseconds (`frame_ms`): the frame with the image is the sum.
        let with = r.model_ms.1 + ms;
        t.row(vec![
            json!(r.phone.phone),
            json!(r.tier.name()),
            json!(format!("{} at {fps} fps", goal_phone.phone)),
            json!(affordable_px(r.tier).map_err(err)?.floor()),
            json!(r.tier.settings().camera_image_max_px),
            json!(format!("{} × {}", chosen.image[0], chosen.image[1])),
            json!(ms),
            json!(ms * fps / 1e3),
            json!(with),
            json!(1e3 / with),
        ]);
    }
    t.note(format!(
        "A new camera image every frame (the worst frame: ARCore's camera runs at 30 fps, so at \
         60 fps every other frame carries one). Upload 1.5 B per pixel at the phone's memory \
         bandwidth and the YUV → RGBA pass (shaders/effects/camera_yuv.wgsl); the roofline's \
         slowest of ALU, texture and memory. Budget: {:.0} % of the frame of the phone the tier \
         is made for. Configs: the back camera's documented three (640 × 480, 1280 × 720, \
         1920 × 1080; texture 1920 × 1080).",
        CAMERA_IMAGE_SHARE * 100.0
    ));
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tiers' stated budgets are the model's affordable pixels rounded down to 1,000
    /// (the model derived them; a change of the shader or the phones' rates shows here), and
    /// the image each tier chooses costs at most the stated share of its frame.
    #[test]
    fn each_tiers_camera_budget_is_what_the_model_affords() {
        for tier in Tier::ALL {
            let affordable = affordable_px(tier).expect("model");
            let stated = tier.settings().camera_image_max_px as f64;
            assert_eq!(
                stated,
                (affordable / 1e3).floor() * 1e3,
                "{tier}: the model affords {affordable:.0} px"
            );
            let (phone, fps) = tier_frame(tier);
            let chosen = chosen_config(tier, phone.screen);
            let ms = camera_image_ms(phone, chosen.image).expect("model");
            assert!(
                ms <= CAMERA_IMAGE_SHARE * 1e3 / fps,
                "{tier}: {ms} ms for {:?}",
                chosen.image
            );
        }
    }

    /// The model's camera cost is linear in the pixels (so the budget is a pixel count), and
    /// bounded below by the upload alone: 1.5 bytes per pixel at the phone's memory bandwidth.
    #[test]
    fn the_camera_cost_is_proportional_to_the_pixels_and_at_least_the_upload() {
        for phone in &PHONES {
            let vga = camera_image_ms(phone, [640, 480]).expect("model");
            let hd = camera_image_ms(phone, [1920, 1080]).expect("model");
            let ratio = hd / vga;
            assert!((ratio - 6.75).abs() < 1e-9, "{ratio}");
            let upload_ms = 640.0 * 480.0 * 1.5 / (phone.gbytes[0] * 1e9) * 1e3;
            assert!(vga >= upload_ms, "{vga} < {upload_ms}");
        }
    }
}
