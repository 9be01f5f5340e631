//! Time per evaluation: on the adapter, in both stages, a shader that feeds each result into
//! the next evaluation (so nothing is optimised away), its chain grown until a run lasts 10 ms,
//! timed by timestamp queries at the pass's start and end where the device has them (wall
//! clock around a synchronised submit otherwise, and the report says which): a compute
//! dispatch of 2^14 invocations, and a fullscreen draw into a 1920x1080 target whose fragment
//! shader runs the chain (G-buffer packing and lighting are fragment work, and some GPUs run
//! fragments on few of their units). On the CPU, the f32 mirror over the same kind of inputs.
//! All are medians of several runs.

mod gpu;
mod harness;

pub use gpu::gpu_time;
pub use harness::{fragment_harness, harness, BASELINE_ROW};

use std::time::Instant;

use gbuffer::glam::Vec4;
use gbuffer_gpu::Gpu;

/// Invocations per dispatch, and the evaluations per invocation a calibration starts from.
const INVOCATIONS: u32 = 1 << 14;
const CHAIN: u32 = 64;
/// The fragment stage's target: one invocation per pixel.
const FRAGMENT_WIDTH: u32 = 1920;
const FRAGMENT_HEIGHT: u32 = 1080;
/// The chain grows until one run lasts this long (seconds), or reaches `MAX_CHAIN`.
const TARGET_RUN: f64 = 0.010;
const MAX_CHAIN: u32 = 1 << 16;
/// Timed runs per row, after the calibration's.
pub const GPU_RUNS: usize = 7;
const CPU_RUNS: usize = 5;

/// Where a row's chain runs on the adapter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// A compute dispatch.
    Compute,
    /// A fullscreen draw's fragment shader.
    Fragment,
}

impl Stage {
    /// Both stages, in report order.
    pub const ALL: [Stage; 2] = [Stage::Compute, Stage::Fragment];

    /// The stage's name in the report: `compute` or `fragment`.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Compute => "compute",
            Stage::Fragment => "fragment",
        }
    }
}

/// How a run was timed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    /// Timestamp queries written at the start and end of the pass.
    Timestamps,
    /// Wall clock around a synchronised submit.
    Wall,
}

impl Clock {
    /// The clock's name in the report: `timestamps` or `wall`.
    pub fn name(self) -> &'static str {
        match self {
            Clock::Timestamps => "timestamps",
            Clock::Wall => "wall",
        }
    }
}

/// A row's time on the adapter, per evaluation and invocation, over `GPU_RUNS` runs of
/// `chain` evaluations in each of `invocations`.
#[derive(Clone, Copy, Debug)]
pub struct GpuTime {
    /// The stage timed.
    pub stage: Stage,
    /// How it was timed.
    pub clock: Clock,
    /// The median run's time divided by the evaluations of a run (`chain` x `invocations`),
    /// in nanoseconds: device nanoseconds per evaluation, the whole device's throughput (not
    /// one invocation's latency).
    pub median_ns: f64,
    /// The fastest run's, likewise.
    pub min_ns: f64,
    /// The slowest run's, likewise.
    pub max_ns: f64,
    /// Evaluations per invocation, as calibrated.
    pub chain: u32,
    /// Invocations per run.
    pub invocations: u32,
    /// The median run's milliseconds.
    pub run_ms: f64,
    /// False once the consistency check found the adapter's times out of the order the
    /// instruction counts predict: no time of the run is then printed.
    pub trusted: bool,
}

impl GpuTime {
    /// The time less `harness`'s (the baseline row's), each statistic less the harness's
    /// median.
    pub fn less(self, harness: Option<GpuTime>) -> GpuTime {
        let base = harness.map_or(0.0, |harness| harness.median_ns);
        GpuTime {
            median_ns: self.median_ns - base,
            min_ns: self.min_ns - base,
            max_ns: self.max_ns - base,
            ..self
        }
    }

    /// Whether the median stands clear of the runs' spread: a time within the spread (or
    /// under zero, once the harness is taken off) is not a measurement to print.
    pub fn resolved(&self) -> bool {
        self.trusted && self.median_ns > 0.0 && self.median_ns > self.max_ns - self.min_ns
    }

    /// Where the time does not resolve but was trusted: an upper bound on it, in nanoseconds
    /// per evaluation. The row's own time (the run's less the harness's) is then smaller than
    /// the runs' spread, so it is at most the median (taken as zero when the harness's time
    /// exceeded it) plus that spread. Never negative.
    pub fn upper_bound_ns(&self) -> Option<f64> {
        (self.trusted && !self.resolved())
            .then(|| self.median_ns.max(0.0) + (self.max_ns - self.min_ns).max(0.0))
    }

    /// Evaluations per run, over the whole device.
    pub fn evaluations_per_run(&self) -> u64 {
        u64::from(self.chain) * u64::from(self.invocations)
    }

    /// Evaluations per second over the whole device at the median run: a run's evaluations over
    /// its time, the harness's own time taken off (once [`GpuTime::less`] has), which is
    /// 1e9 / [`GpuTime::median_ns`].
    pub fn evaluations_per_second(&self) -> f64 {
        let evaluations = self.evaluations_per_run() as f64;
        let run_seconds = self.median_ns * evaluations / 1e9;
        evaluations / run_seconds
    }

    /// The time of runs of `chain` evaluations in each of `invocations`, from their durations
    /// in seconds (any order).
    pub fn of_runs(
        stage: Stage,
        clock: Clock,
        mut run_seconds: Vec<f64>,
        chain: u32,
        invocations: u32,
    ) -> GpuTime {
        let ns_per_evaluation = 1e9 / (f64::from(invocations) * f64::from(chain));
        let median = median(&mut run_seconds);
        GpuTime {
            stage,
            clock,
            median_ns: median * ns_per_evaluation,
            min_ns: run_seconds[0] * ns_per_evaluation,
            max_ns: run_seconds[run_seconds.len() - 1] * ns_per_evaluation,
            chain,
            invocations,
            run_ms: median * 1e3,
            trusted: true,
        }
    }
}

/// A row's times in both stages, each less the harness's own (the baseline row's) in that
/// stage; `None` where the stage could not be timed.
#[derive(Clone, Copy, Debug, Default)]
pub struct StageTimes {
    /// The compute dispatch's.
    pub compute: Option<GpuTime>,
    /// The fullscreen draw's.
    pub fragment: Option<GpuTime>,
}

impl StageTimes {
    /// Times `row_wgsl` in both stages (see [`gpu_time`]), less `baseline`'s; a stage that
    /// fails is reported on stderr and left out.
    pub fn measure(
        gpu: &Gpu,
        row_wgsl: &str,
        lut: &[[f32; 2]],
        lut_size: usize,
        baseline: &StageTimes,
    ) -> StageTimes {
        let mut times = StageTimes::default();
        for stage in Stage::ALL {
            *times.get_mut(stage) = gpu_time(gpu, stage, row_wgsl, lut, lut_size)
                .map_err(|error| eprintln!("  {} timing failed: {error}", stage.name()))
                .ok()
                .map(|time| time.less(baseline.get(stage)));
        }
        times
    }

    /// The time in `stage`.
    pub fn get(&self, stage: Stage) -> Option<GpuTime> {
        match stage {
            Stage::Compute => self.compute,
            Stage::Fragment => self.fragment,
        }
    }

    fn get_mut(&mut self, stage: Stage) -> &mut Option<GpuTime> {
        match stage {
            Stage::Compute => &mut self.compute,
            Stage::Fragment => &mut self.fragment,
        }
    }

    /// Marks both stages' times untrusted.
    pub fn distrust(&mut self) {
        for time in [&mut self.compute, &mut self.fragment]
            .into_iter()
            .flatten()
        {
            time.trusted = false;
        }
    }
}

/// A measured item for the consistency check: its name, SPIR-V instructions and time.
pub struct Timed<'a> {
    /// Names the item in a message.
    pub name: String,
    /// Its SPIR-V instructions.
    pub instructions: usize,
    /// Its time, where measured.
    pub time: Option<&'a GpuTime>,
}

/// Pairs of one group whose order the instruction counts predict (one has at least twice the
/// other's instructions) but whose resolved times say the opposite: a line each. Empty when
/// the adapter's times can be trusted.
pub fn inconsistencies(group: &[Timed]) -> Vec<String> {
    let mut found = Vec::new();
    for cheap in group {
        for dear in group {
            let (Some(cheap_time), Some(dear_time)) = (cheap.time, dear.time) else {
                continue;
            };
            let predicted = 2 * cheap.instructions <= dear.instructions;
            if predicted
                && cheap_time.resolved()
                && dear_time.resolved()
                && cheap_time.min_ns > dear_time.max_ns
            {
                found.push(format!(
                    "{} ({} instructions) took {:.3} ns, more than {} ({} instructions) at {:.3} ns",
                    cheap.name,
                    cheap.instructions,
                    cheap_time.median_ns,
                    dear.name,
                    dear.instructions,
                    dear_time.median_ns
                ));
            }
        }
    }
    found
}

/// Nanoseconds per evaluation of a row's CPU mirror, chained as on the GPU (median of runs).
pub fn cpu_ns_per_eval(evaluate: &dyn Fn(Vec4) -> Vec4) -> f64 {
    const EVALUATIONS: u32 = 1 << 16;
    let mut times = Vec::new();
    for _ in 0..CPU_RUNS {
        let mut x = Vec4::new(0.3, 0.6, 0.2, 0.7);
        let start = Instant::now();
        for _ in 0..EVALUATIONS {
            let y = evaluate(std::hint::black_box(x));
            x = (y * 0.25 + x * 0.75 + Vec4::splat(0.1)).fract();
        }
        std::hint::black_box(x);
        times.push(start.elapsed().as_secs_f64());
    }
    median(&mut times) * 1e9 / f64::from(EVALUATIONS)
}

/// The median of `values` (sorted in place); they must not be empty.
pub(crate) fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs whose evaluations and times are known: 7 runs of 100 evaluations in each of 1000
    /// invocations (1e5 a run), the median lasting 10 ms, give 100 ns per evaluation and 1e7
    /// evaluations a second; with a harness whose median run lasts 2 ms taken off, 80 ns and
    /// 1e5 evaluations in 8 ms.
    #[test]
    fn the_units_are_what_their_names_say() {
        let runs = vec![0.011, 0.0095, 0.010, 0.0102, 0.0099, 0.0105, 0.0098];
        let time = GpuTime::of_runs(Stage::Compute, Clock::Wall, runs, 100, 1000);
        assert_eq!(time.evaluations_per_run(), 100_000);
        assert!((time.median_ns - 100.0).abs() < 1e-9, "{}", time.median_ns);
        assert!((time.run_ms - 10.0).abs() < 1e-9);
        assert!((time.min_ns - 95.0).abs() < 1e-9 && (time.max_ns - 110.0).abs() < 1e-9);
        assert!((time.evaluations_per_second() - 1e7).abs() < 1e-3);
        let harness = GpuTime::of_runs(Stage::Compute, Clock::Wall, vec![0.002; 7], 100, 1000);
        let less = time.less(Some(harness));
        assert!((less.median_ns - 80.0).abs() < 1e-9);
        assert!((less.evaluations_per_second() - 1e5 / 0.008).abs() < 1e-3);
    }

    /// A row faster than the harness can tell (its median, less the harness's, below zero: the
    /// "fully rough" row read -0.11 ns on llvmpipe) reports an upper bound, never a negative
    /// time; a resolved row reports none.
    #[test]
    fn a_time_below_the_resolution_is_an_upper_bound() {
        let runs = vec![0.0100, 0.0104, 0.0098, 0.0101, 0.0099, 0.0102, 0.0097];
        let row = GpuTime::of_runs(Stage::Compute, Clock::Wall, runs, 100, 1000);
        let harness = GpuTime::of_runs(Stage::Compute, Clock::Wall, vec![0.0101; 7], 100, 1000);
        let less = row.less(Some(harness));
        assert!(less.median_ns < 0.0 && !less.resolved());
        let bound = less.upper_bound_ns().unwrap();
        // Spread 7 ns (97 to 104 ns a run), the median taken as zero.
        assert!((bound - 7.0).abs() < 1e-6, "{bound}");
        assert_eq!(time(100.0).upper_bound_ns(), None);
        let mut untrusted = less;
        untrusted.trusted = false;
        assert_eq!(untrusted.upper_bound_ns(), None);
    }

    fn time(median_ns: f64) -> GpuTime {
        GpuTime {
            stage: Stage::Compute,
            clock: Clock::Wall,
            median_ns,
            min_ns: median_ns * 0.95,
            max_ns: median_ns * 1.05,
            chain: 64,
            invocations: INVOCATIONS,
            run_ms: 10.0,
            trusted: true,
        }
    }

    /// A builtin of 16 instructions and an exact conversion of 44, timed as given.
    fn pair<'a>(builtin: &'a GpuTime, exact: &'a GpuTime) -> Vec<Timed<'a>> {
        vec![
            Timed {
                name: "builtin".into(),
                instructions: 16,
                time: Some(builtin),
            },
            Timed {
                name: "exact".into(),
                instructions: 44,
                time: Some(exact),
            },
        ]
    }

    #[test]
    fn both_stages_calibrate_their_runs_to_ten_milliseconds_on_the_adapter() {
        let row =
            "fn row_eval(x: vec4<f32>) -> vec4<f32> {\n    return sqrt(x + vec4<f32>(0.5));\n}\n";
        // With the timestamp feature where the adapter has it, and without: the wall clock.
        let with_timestamps = gbuffer_testkit::gpu_with(None, wgpu::Features::TIMESTAMP_QUERY);
        let Some(with_timestamps) = with_timestamps else {
            return;
        };
        for gpu in [with_timestamps, gbuffer_testkit::gpu().unwrap()] {
            let timestamps = gpu
                .device
                .features()
                .contains(wgpu::Features::TIMESTAMP_QUERY);
            for stage in Stage::ALL {
                let time = gpu_time(&gpu, stage, row, &[], 1).unwrap();
                assert_eq!(time.stage, stage);
                // Timestamps only where the device has them (and they bracket the work).
                if !timestamps {
                    assert_eq!(time.clock, Clock::Wall);
                }
                eprintln!("{stage:?}: {} clock, {time:?}", time.clock.name());
                assert!(
                    time.run_ms >= 1e3 * TARGET_RUN || time.chain == MAX_CHAIN,
                    "{stage:?}: {time:?}"
                );
                assert!(time.min_ns <= time.median_ns && time.median_ns <= time.max_ns);
                let invocations = match stage {
                    Stage::Compute => INVOCATIONS,
                    Stage::Fragment => FRAGMENT_WIDTH * FRAGMENT_HEIGHT,
                };
                assert_eq!(time.invocations, invocations);
            }
        }
    }

    #[test]
    fn times_out_of_the_predicted_order_are_found_and_others_are_not() {
        let (fast, slow) = (time(2.0), time(5.0));
        assert!(inconsistencies(&pair(&fast, &slow)).is_empty());
        let found = inconsistencies(&pair(&slow, &fast));
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].starts_with("builtin (16 instructions) took 5.000 ns"));
        // Untrusted or unresolved times are not compared.
        let untrusted = GpuTime {
            trusted: false,
            ..slow
        };
        assert!(inconsistencies(&pair(&untrusted, &fast)).is_empty());
    }
}
