//! Work per shader invocation, counted from the compiled shader: the WGSL a pass is built from
//! is parsed and validated by naga (the compiler wgpu uses), and the entry point's IR is walked
//! statement by statement.
//!
//! - ALU: floating-point and integer operations per component (an `fma` or `mix` counts 2, a
//!   `dot` 2 per component, transcendentals (`exp`, `sin`, `sqrt`, `pow`, …) 4 per component:
//!   phone GPUs run them on a quarter-rate unit), so that the count is comparable to a GPU's
//!   FP32 FLOP rate (an FMA = 2 FLOP).
//! - Texture: one per sample or load (a bilinear fetch of one texel quad).
//! - Storage: bytes loaded from or written to storage buffers.
//!
//! Control flow: called functions are walked in (once per call); a branch whose condition is a
//! constant of the pipeline (`FX_MASK` through `fx_on(bit)`, `FX_CHEAP_CAUSTICS`) takes only
//! the branch that runs; any other `if` or `switch` counts its costlier side (a SIMD group pays
//! for the longest path whenever its lanes diverge). A loop counts its body times the trip
//! count the caller knows on the CPU ([`Trips`]), chosen by the function the loop is in.

use naga::valid::{Capabilities, FunctionInfo, ValidationFlags, Validator};
use naga::{Block, Expression, Function, Handle, MathFunction, Module, Statement, TypeInner};

/// Work of one invocation.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Cost {
    /// Arithmetic operations (FLOP-equivalent, see the module docs).
    pub alu: f64,
    /// Texture samples and loads.
    pub tex: f64,
    /// Storage-buffer bytes read or written.
    pub storage_bytes: f64,
}

impl Cost {
    pub fn add(&mut self, o: Cost) {
        self.alu += o.alu;
        self.tex += o.tex;
        self.storage_bytes += o.storage_bytes;
    }
    pub fn scaled(self, k: f64) -> Cost {
        Cost {
            alu: self.alu * k,
            tex: self.tex * k,
            storage_bytes: self.storage_bytes * k,
        }
    }
    /// The costlier of two paths (by arithmetic, then texture work).
    fn max(self, o: Cost) -> Cost {
        if (o.alu, o.tex) > (self.alu, self.tex) {
            o
        } else {
            self
        }
    }
}

/// Loop trip counts known on the CPU for one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trips {
    /// Waves of the sea the shaders sum (`frame.counts.x`).
    pub waves: f64,
    /// Turns of a fragment's `resolved_waves` loop (surface_frame's waves the pixel filter
    /// leaves whole, k·footprint < π/4, and the turn that meets the first it fades), the mean
    /// over the water's fragments. Counted on the CPU from each clip-map triangle's footprint
    /// (`render::clipmap::ClipMesh::footprints`); the frame's waves are sorted by wavenumber.
    pub resolved_waves_in_pixel: f64,
    /// Turns of a fragment's `fading_waves` loop (the waves the filter fades, π/4 ≤
    /// k·footprint < π/2, and the turn that meets the first it fades out entirely), the
    /// same mean.
    pub fading_waves_in_pixel: f64,
    /// Wake sources whose height a clip-map vertex sums (its bin's height list), the mean
    /// over the vertices (0 for a vertex in an empty bin).
    pub wake_sources_per_vertex: f64,
    /// Wake sources whose foam a clip-map vertex sums (its bin's foam list), the same mean.
    pub wake_foam_sources_per_vertex: f64,
    /// Waves whose slope sums a clip-map vertex carries to the pixels (`vertex_slope_sums`),
    /// the mean over the vertices.
    pub vertex_waves_per_vertex: f64,
    /// Course marks the flow map loops over (at most 8).
    pub marks: f64,
}

impl Trips {
    /// The trip count of a loop in function `name` (by what that function loops over) in an
    /// entry point of `stage`.
    fn of(&self, name: &str, stage: naga::ShaderStage) -> f64 {
        match name {
            // Only a fragment has a footprint; elsewhere the loop runs every wave.
            "resolved_waves" if stage == naga::ShaderStage::Fragment => {
                self.resolved_waves_in_pixel
            }
            "fading_waves" if stage == naga::ShaderStage::Fragment => self.fading_waves_in_pixel,
            // Elsewhere the footprint is 0: every wave is resolved, none fades.
            "fading_waves" => 0.0,
            "resolved_waves" | "sea_displaced" | "grid_point" | "wave_height" => self.waves,
            "wake_at" => self.wake_sources_per_vertex,
            "vertex_slope_sums" => self.vertex_waves_per_vertex,
            "wake_foam_at" => self.wake_foam_sources_per_vertex,
            "current_at" => self.marks.min(8.0),
            // caustic_scatter's splat: a landed triangle covers about one map cell.
            _ => 1.0,
        }
    }
}

/// A WGSL module parsed and validated, with the index of one entry point.
struct Parsed {
    module: Module,
    info: naga::valid::ModuleInfo,
    index: usize,
}

impl Parsed {
    fn new(source: &str, entry: &str) -> Result<Parsed, String> {
        let module = naga::front::wgsl::parse_str(source)
            .map_err(|e| format!("{entry}: {}", input::one_line(&e.emit_to_string(source))))?;
        let info = Validator::new(ValidationFlags::all(), Capabilities::all())
            .validate(&module)
            .map_err(|e| format!("{entry}: {}", input::one_line(&e.emit_to_string(source))))?;
        let index = module
            .entry_points
            .iter()
            .position(|e| e.name == entry)
            .ok_or_else(|| format!("no entry point {entry}"))?;
        Ok(Parsed {
            module,
            info,
            index,
        })
    }

    /// The entry's work per invocation, with function `without`'s body counted as nothing.
    fn cost(&self, trips: &Trips, without: Option<&str>) -> Cost {
        let ep = &self.module.entry_points[self.index];
        Walker {
            module: &self.module,
            info: &self.info,
            trips,
            stage: ep.stage,
            without,
        }
        .function(&ep.function, self.info.get_entry_point(self.index), "entry")
    }
}

/// The per-invocation work of entry point `entry` of the WGSL `source`.
pub fn entry_cost(source: &str, entry: &str, trips: &Trips) -> Result<Cost, String> {
    Ok(Parsed::new(source, entry)?.cost(trips, None))
}

/// Where the work of one invocation of `entry` goes: for each function it calls (directly or
/// not), the work that function's calls add to the invocation, loops and branches included
/// (the entry's cost less its cost with that function's body counted as nothing). A function
/// called inside another's loop counts once per turn; the shares of nested functions overlap
/// (a caller's share includes its callees'). Sorted by ALU work, costliest first; the entry's
/// own total is `entry_cost`.
pub fn function_costs(
    source: &str,
    entry: &str,
    trips: &Trips,
) -> Result<Vec<(String, Cost)>, String> {
    let parsed = Parsed::new(source, entry)?;
    let cost_without = |without: Option<&str>| parsed.cost(trips, without);
    let module = &parsed.module;
    let total = cost_without(None);
    let mut out: Vec<(String, Cost)> = module
        .functions
        .iter()
        .filter_map(|(_, f)| f.name.as_deref())
        .filter_map(|name| {
            let rest = cost_without(Some(name));
            let share = Cost {
                alu: total.alu - rest.alu,
                tex: total.tex - rest.tex,
                storage_bytes: total.storage_bytes - rest.storage_bytes,
            };
            (share != Cost::default()).then(|| (name.to_string(), share))
        })
        .collect();
    out.sort_by(|a, b| b.1.alu.total_cmp(&a.1.alu));
    Ok(out)
}

struct Walker<'a> {
    module: &'a Module,
    info: &'a naga::valid::ModuleInfo,
    trips: &'a Trips,
    /// The entry point's stage (some loops run fewer turns in a fragment: [`Trips::of`]).
    stage: naga::ShaderStage,
    /// A function whose body counts as no work ([`function_costs`]).
    without: Option<&'a str>,
}

impl Walker<'_> {
    fn function(&self, f: &Function, fi: &FunctionInfo, name: &str) -> Cost {
        if self.without == Some(name) {
            return Cost::default();
        }
        let mut known = Vec::new();
        self.block(f, fi, name, &f.body, &mut known)
    }

    /// Cost of `block`; `known` collects call results that are pipeline constants.
    fn block(
        &self,
        f: &Function,
        fi: &FunctionInfo,
        name: &str,
        block: &Block,
        known: &mut Vec<(Handle<Expression>, bool)>,
    ) -> Cost {
        let mut c = Cost::default();
        for stmt in block.iter() {
            match stmt {
                Statement::Emit(range) => {
                    for h in range.clone() {
                        c.add(self.expression(f, fi, h));
                    }
                }
                Statement::Block(b) => c.add(self.block(f, fi, name, b, known)),
                Statement::If {
                    condition,
                    accept,
                    reject,
                } => match self.constant_bool(f, *condition, known) {
                    Some(true) => c.add(self.block(f, fi, name, accept, known)),
                    Some(false) => c.add(self.block(f, fi, name, reject, known)),
                    None => {
                        let a = self.block(f, fi, name, accept, known);
                        let r = self.block(f, fi, name, reject, known);
                        c.add(a.max(r));
                    }
                },
                Statement::Switch { cases, .. } => {
                    let worst = cases
                        .iter()
                        .map(|case| self.block(f, fi, name, &case.body, known))
                        .fold(Cost::default(), Cost::max);
                    c.add(worst);
                }
                Statement::Loop {
                    body, continuing, ..
                } => {
                    let mut once = self.block(f, fi, name, body, known);
                    once.add(self.block(f, fi, name, continuing, known));
                    c.add(once.scaled(self.trips.of(name, self.stage)));
                }
                Statement::Call {
                    function,
                    arguments,
                    result,
                } => {
                    let callee = &self.module.functions[*function];
                    let callee_name = callee.name.as_deref().unwrap_or("");
                    if callee_name == "fx_on"
                        && let (Some(bit), Some(mask), Some(r)) = (
                            arguments.first().and_then(|a| self.constant_u32(f, *a)),
                            self.named_u32("FX_MASK"),
                            result,
                        )
                    {
                        known.push((*r, mask & bit != 0));
                        continue;
                    }
                    c.add(self.function(callee, &self.info[*function], callee_name));
                }
                Statement::Store { value, pointer } if self.in_storage(f, fi, *pointer) => {
                    c.storage_bytes += self.bytes(fi, *value);
                }
                Statement::ImageStore { .. } => c.tex += 1.0,
                Statement::Atomic { .. } => c.storage_bytes += 4.0,
                _ => {}
            }
        }
        c
    }

    fn components(&self, _f: &Function, fi: &FunctionInfo, h: Handle<Expression>) -> f64 {
        match fi[h].ty.inner_with(&self.module.types) {
            TypeInner::Vector { size, .. } => f64::from(*size as u8),
            TypeInner::Matrix { columns, rows, .. } => f64::from(*columns as u8 * *rows as u8),
            _ => 1.0,
        }
    }

    /// Bytes of the value of `h` (a struct loaded whole counts all its fields).
    fn bytes(&self, fi: &FunctionInfo, h: Handle<Expression>) -> f64 {
        let inner = fi[h].ty.inner_with(&self.module.types);
        f64::from(inner.size(self.module.to_ctx()))
    }

    fn is_matrix(&self, fi: &FunctionInfo, h: Handle<Expression>) -> bool {
        matches!(
            fi[h].ty.inner_with(&self.module.types),
            TypeInner::Matrix { .. }
        )
    }

    /// Does `pointer` point into a storage buffer?
    fn in_storage(
        &self,
        f: &Function,
        _fi: &FunctionInfo,
        mut pointer: Handle<Expression>,
    ) -> bool {
        loop {
            match f.expressions[pointer] {
                Expression::Access { base, .. } | Expression::AccessIndex { base, .. } => {
                    pointer = base
                }
                Expression::GlobalVariable(g) => {
                    return matches!(
                        self.module.global_variables[g].space,
                        naga::AddressSpace::Storage { .. }
                    );
                }
                _ => return false,
            }
        }
    }

    fn expression(&self, f: &Function, fi: &FunctionInfo, h: Handle<Expression>) -> Cost {
        let n = self.components(f, fi, h);
        let mut c = Cost::default();
        match &f.expressions[h] {
            Expression::Binary { left, right, .. } => {
                c.alu = if self.is_matrix(fi, *left) || self.is_matrix(fi, *right) {
                    // A matrix product: an FMA per element of the inner dimension.
                    2.0 * 4.0 * n
                } else {
                    n
                };
            }
            Expression::Unary { .. }
            | Expression::Select { .. }
            | Expression::As { .. }
            | Expression::Relational { .. }
            | Expression::Derivative { .. } => c.alu = n,
            Expression::Math { fun, arg, .. } => {
                let arg_n = self.components(f, fi, *arg);
                c.alu = math_cost(*fun, n, arg_n);
            }
            Expression::ImageSample { .. } | Expression::ImageLoad { .. } => c.tex = 1.0,
            Expression::Load { pointer } if self.in_storage(f, fi, *pointer) => {
                c.storage_bytes = self.bytes(fi, h);
            }
            _ => {}
        }
        c
    }

    /// The value of a boolean condition fixed for the pipeline, if it is one.
    fn constant_bool(
        &self,
        f: &Function,
        h: Handle<Expression>,
        known: &[(Handle<Expression>, bool)],
    ) -> Option<bool> {
        if let Some((_, v)) = known.iter().find(|(k, _)| *k == h) {
            return Some(*v);
        }
        match &f.expressions[h] {
            Expression::Literal(naga::Literal::Bool(b)) => Some(*b),
            Expression::Constant(c) => {
                match self.module.global_expressions[self.module.constants[*c].init] {
                    Expression::Literal(naga::Literal::Bool(b)) => Some(b),
                    _ => None,
                }
            }
            Expression::Unary {
                op: naga::UnaryOperator::LogicalNot,
                expr,
            } => self.constant_bool(f, *expr, known).map(|b| !b),
            _ => None,
        }
    }

    fn constant_u32(&self, f: &Function, h: Handle<Expression>) -> Option<u32> {
        match &f.expressions[h] {
            Expression::Literal(naga::Literal::U32(v)) => Some(*v),
            Expression::Constant(c) => self.global_u32(self.module.constants[*c].init),
            _ => None,
        }
    }

    fn global_u32(&self, h: Handle<Expression>) -> Option<u32> {
        match self.module.global_expressions[h] {
            Expression::Literal(naga::Literal::U32(v)) => Some(v),
            _ => None,
        }
    }

    fn named_u32(&self, name: &str) -> Option<u32> {
        let (_, c) = self
            .module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some(name))?;
        self.global_u32(c.init)
    }
}

/// Operations of one math builtin with `n` result and `arg_n` argument components.
fn math_cost(fun: MathFunction, n: f64, arg_n: f64) -> f64 {
    use MathFunction as M;
    match fun {
        M::Dot => 2.0 * arg_n,
        M::Cross => 9.0,
        M::Length | M::Distance => 2.0 * arg_n + 4.0,
        M::Normalize => 3.0 * arg_n + 4.0,
        M::Reflect => 4.0 * arg_n,
        M::Refract => 6.0 * arg_n + 8.0,
        M::Fma | M::Mix | M::Clamp => 2.0 * n,
        M::SmoothStep => 6.0 * n,
        M::Exp
        | M::Exp2
        | M::Log
        | M::Log2
        | M::Pow
        | M::Sin
        | M::Cos
        | M::Tan
        | M::Asin
        | M::Acos
        | M::Atan
        | M::Atan2
        | M::Sinh
        | M::Cosh
        | M::Tanh
        | M::Asinh
        | M::Acosh
        | M::Atanh
        | M::Sqrt
        | M::InverseSqrt => 4.0 * n,
        _ => n,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRIPS: Trips = Trips {
        waves: 10.0,
        resolved_waves_in_pixel: 4.0,
        fading_waves_in_pixel: 1.0,
        wake_sources_per_vertex: 3.0,
        wake_foam_sources_per_vertex: 1.0,
        vertex_waves_per_vertex: 1.0,
        marks: 2.0,
    };

    /// Hand-counted: a vec4 fma (8), a scalar add in a loop of `resolved_waves_in_pixel` turns
    /// in a function called `resolved_waves` in a fragment stage (4 × 1), one texture sample, a
    /// storage load of a vec4 (16 B).
    #[test]
    fn a_small_shader_counts_as_by_hand() {
        let src = r#"
@group(0) @binding(0) var t: texture_2d<f32>;
@group(0) @binding(1) var s: sampler;
@group(0) @binding(2) var<storage, read> buf: array<vec4<f32>>;
fn resolved_waves(n: u32) -> f32 {
    var x = 0.0;
    for (var i = 0u; i < n; i = i + 1u) { x = x + 1.5; }
    return x;
}
@fragment
fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let a = fma(p, p, p);
    let b = resolved_waves(u32(p.x));
    let c = textureSample(t, s, p.xy);
    let d = buf[0];
    return a + c + d + vec4<f32>(b);
}
"#;
        let c = entry_cost(src, "fs", &TRIPS).unwrap();
        // Loop: the add, the compare, the increment per turn (3 × 4); the entry: fma 8,
        // u32(p.x) 1, three vec4 adds 12, the splat 0.
        assert_eq!(c.tex, 1.0);
        assert_eq!(c.storage_bytes, 16.0);
        assert_eq!(c.alu, 8.0 + 1.0 + 12.0 + 12.0, "{c:?}");
    }

    /// The same loop in a compute stage runs every wave (no footprint there): 3 × 10.
    #[test]
    fn resolved_waves_runs_every_wave_outside_a_fragment() {
        let src = r#"
@group(0) @binding(0) var<storage, read_write> out: array<f32>;
fn resolved_waves(n: u32) -> f32 {
    var x = 0.0;
    for (var i = 0u; i < n; i = i + 1u) { x = x + 1.5; }
    return x;
}
const WG: u32 = 1u;
@compute @workgroup_size(WG)
fn cs(@builtin(global_invocation_id) id: vec3<u32>) {
    out[0] = resolved_waves(id.x);
}
"#;
        let c = entry_cost(src, "cs", &TRIPS).unwrap();
        // The loop 3 × 10; the entry: nothing but the call (the store is storage bytes).
        assert_eq!(c.alu, 30.0, "{c:?}");
    }

    /// The hand-counted shader above by function: `resolved_waves`' loop (3 × 10 turns) is
    /// its share, the rest the entry's own; a function called in a loop counts once per turn.
    #[test]
    fn a_function_share_is_its_calls_work_as_counted_by_hand() {
        let src = r#"
fn double_up(x: f32) -> f32 { return x * 2.0 + 1.0; }
fn resolved_waves(n: u32) -> f32 {
    var x = 0.0;
    for (var i = 0u; i < n; i = i + 1u) { x = double_up(x); }
    return x;
}
@fragment
fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(resolved_waves(u32(p.x)) + double_up(p.y));
}
"#;
        let total = entry_cost(src, "fs", &TRIPS).unwrap();
        let shares = function_costs(src, "fs", &TRIPS).unwrap();
        let share = |name: &str| shares.iter().find(|(n, _)| n == name).unwrap().1.alu;
        // double_up: 2 per call, 4 calls in the loop (a fragment's waves) and 1 in the entry;
        // the loop's compare and increment 2 per turn; the entry: u32(p.x) and the add.
        assert_eq!(share("double_up"), 2.0 * 5.0);
        assert_eq!(share("resolved_waves"), (2.0 + 2.0) * 4.0);
        assert_eq!(total.alu, 16.0 + 2.0 + 2.0, "{total:?}");
        assert_eq!(shares[0].0, "resolved_waves");
    }

    /// A branch on a pipeline constant counts only the branch that runs.
    #[test]
    fn pipeline_constants_prune_branches() {
        let body = r#"
fn fx_on(bit: u32) -> bool { return (FX_MASK & bit) != 0u; }
@fragment
fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    var c = p;
    if fx_on(2u) { c = c * c * c * c; }
    return c;
}
"#;
        let on = entry_cost(&format!("{body}const FX_MASK: u32 = 2u;"), "fs", &TRIPS).unwrap();
        let off = entry_cost(&format!("{body}const FX_MASK: u32 = 4u;"), "fs", &TRIPS).unwrap();
        assert_eq!(on.alu - off.alu, 12.0, "{on:?} {off:?}");
    }

    #[test]
    fn bad_wgsl_is_an_error_naming_the_entry() {
        let e = entry_cost("fn (", "fs", &TRIPS).unwrap_err();
        assert!(e.starts_with("fs:") && !e.contains('\n'), "{e}");
    }
}
