//! `regatta bench --only budget-model`: the budget's machine-independent model alone (no
//! timed repetitions, no throughput kernel, no accuracy references), with where the AR water's
//! work goes per shader function, and the camera image each tier affords
//! ([`super::budget_camera`]). The model is deterministic: the same commit gives the same
//! figures as `budget`'s model columns, in a fraction of its time.

use quality::Tier;
use serde_json::json;

use super::budget_camera::camera_table;
use super::budget_model::{PHONES, pass_shaders};
use super::budget_run::{Row, goal, measure, passes_table};
use super::shader_cost::{entry_cost, function_costs};
use crate::{BenchContext, Table};
use regatta::error::{AppError, AppResult};
use regatta::tier_render::TierRender;

/// Section `budget-model`.
pub fn run(ctx: &BenchContext) -> AppResult<Vec<Table>> {
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| AppError::new(format!("the budget model needs a GPU adapter: {e}")))?;
    let mut rows = Vec::new();
    for phone in &PHONES {
        for tier in Tier::ALL {
            rows.push(measure(ctx, &gpu, None, phone, tier, 0)?);
        }
    }
    let mut tiers = Table::new(
        "budget_model",
        "Phone frame budget per quality tier on the machine-independent model",
        &[
            "phone",
            "tier",
            "model ms (slow spec, the phone's HSR)",
            "model fps (slow spec, the phone's HSR)",
            "model fps range",
            "AR water GFLOP",
            "wake sources per vertex",
            "wake binning ms here (median, IQR)",
            "wake height bound of dropped sources m",
            "goal met",
        ],
    );
    for r in &rows {
        let fps = 1e3 / r.model_ms.1;
        let water = r.work.iter().find(|w| w.pass == "ar_water");
        tiers.row(vec![
            json!(r.phone.phone),
            json!(r.tier.name()),
            json!(r.model_ms.1),
            json!(fps),
            json!(format!(
                "{:.1}–{:.1}",
                1e3 / r.model_range.1,
                1e3 / r.model_range.0
            )),
            json!(water.map(|w| w.cost.alu * 1e-9)),
            json!(r.trips.wake_sources_per_vertex),
            json!(format!(
                "{:.1} ± {:.0} %",
                r.binning_ms.0,
                100.0 * r.binning_ms.1
            )),
            json!(r.report.wakes.as_ref().map_or(0.0, |w| w.drop_bound_m)),
            json!(goal(r.phone, r.tier).map(|(g, _)| fps >= g)),
        ]);
    }
    tiers.note(
        "The budget section's model (budget_passes explains it), without its timed part: same \
         commit, same figures. Only the wake binning column is timed: this CPU culling and \
         binning the frame's wake sources as the renderer does every frame (bin_wakes).",
    );
    Ok(vec![
        tiers,
        passes_table(&rows),
        functions_table(&rows)?,
        camera_table(&rows)?,
    ])
}

/// The AR water's work per invocation of each stage at `ultra` on the first phone, by shader
/// function ([`function_costs`]).
fn functions_table(rows: &[Row]) -> AppResult<Table> {
    let mut t = Table::new(
        "budget_functions",
        "Where the AR water's work goes: ALU operations per invocation by shader function (ultra)",
        &[
            "phone",
            "stage",
            "function",
            "ALU per invocation",
            "share of the stage",
            "texture per invocation",
        ],
    );
    let ultra = TierRender::of(Tier::Ultra);
    let (src, vs, fs) = pass_shaders("ar_water", &ultra.ar).expect("the AR water's shaders");
    let cs = render::shader::source(&[&render::shader::wake(), render::shader::WATER_VERTICES]);
    for r in rows.iter().filter(|r| r.tier == Tier::Ultra) {
        for (stage, source, entry) in [
            ("fragment", src.as_str(), fs),
            ("vertex", src.as_str(), vs),
            ("compute (per vertex)", cs.as_str(), "cs_displace"),
        ] {
            let total = entry_cost(source, entry, &r.trips).map_err(AppError::new)?;
            t.row(vec![
                json!(r.phone.phone),
                json!(stage),
                json!(format!("{entry} (all)")),
                json!(total.alu),
                json!(1.0),
                json!(total.tex),
            ]);
            for (name, c) in function_costs(source, entry, &r.trips).map_err(AppError::new)? {
                t.row(vec![
                    json!(r.phone.phone),
                    json!(stage),
                    json!(name),
                    json!(c.alu),
                    json!(c.alu / total.alu.max(1e-9)),
                    json!(c.tex),
                ]);
            }
        }
    }
    t.note(
        "A function's share: the stage's work less its work with that function's body counted \
         as nothing (its calls, in loops times their trips, with what it calls); nested \
         functions' shares overlap. Trip counts: the frame's (waves, wake sources per vertex, \
         marks).",
    );
    Ok(t)
}
