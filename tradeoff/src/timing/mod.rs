//! Time per evaluation, by the one timing protocol (`gbuffer_gpu::timing`): on the adapter,
//! in both stages, a shader that feeds each result into the next evaluation (so nothing is
//! optimised away), [`CHAINS`] such chains side by side in each invocation, their length
//! calibrated until a run lasts 10 ms and twice the chain takes twice the time, timed by
//! timestamp queries at the pass's start and end where the device has them (wall clock around
//! a synchronised submit otherwise, and the report says which): a compute dispatch of 2^20
//! invocations, and a fullscreen draw into a 1920x1080 target whose fragment shader runs the
//! chains (G-buffer packing and lighting are fragment work, and some GPUs run fragments on few
//! of their units). Every row, the harness's own among them, is timed once a round after the
//! clock has warmed up ([`Timer`]), each round at its chain and at twice its chain: a row's
//! time is what the second chain adds, so a run's fixed cost (the launch, each invocation's
//! loads and stores) is charged to no row however short its chain. On the CPU, the f32 mirror
//! over the same kind of inputs, in as many chains.

mod gpu;
mod harness;

pub use gpu::Timer;
pub use harness::{fragment_harness, harness, BASELINE_ROW, CHAINS};

use std::time::Instant;

use gbuffer_core::Named;
use gbuffer_gpu::timing::Spread;
use glam::Vec4;

/// Invocations per dispatch: enough threads to fill a large GPU (an H100 holds 270,000), so
/// that the time is the device's throughput and not one thread's latency (which the chains
/// side by side in each invocation also hide, where the adapter runs one thread's steps in
/// order: `harness`).
const INVOCATIONS: u32 = 1 << 20;
/// The static costs' chain (the compute harness as counted).
const CHAIN: u32 = 64;
/// The fragment stage's target: one invocation per pixel.
const FRAGMENT_WIDTH: u32 = 1920;
const FRAGMENT_HEIGHT: u32 = 1080;
/// The chain grows until one run lasts this long (seconds), or reaches `MAX_CHAIN`.
const TARGET_RUN: f64 = 0.010;
/// What doubling the chain must then add to a run (seconds), a row's time being that
/// difference: twice a run's least, so that a run slowed by a few milliseconds of another
/// process's work cannot swamp it.
const TARGET_ADDED: f64 = 0.020;
const MAX_CHAIN: u32 = 1 << 16;
const CPU_RUNS: usize = 5;

/// Where a row's chain runs on the adapter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// A compute dispatch.
    Compute,
    /// A fullscreen draw's fragment shader.
    Fragment,
}

// Both stages, in report order.
gbuffer_core::named!(
    /// The stage's name in the report: `compute` or `fragment`.
    Stage {
        Compute => "compute",
        Fragment => "fragment",
    }
);

/// How a run was timed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    /// Timestamp queries written at the start and end of the pass.
    Timestamps,
    /// Wall clock around a synchronised submit.
    Wall,
}

gbuffer_core::named!(
    /// The clock's name in the report: `timestamps` or `wall`.
    Clock {
        Timestamps => "timestamps",
        Wall => "wall",
    }
);

/// A row's time on the adapter, per evaluation, over the protocol's rounds of `chains` chains
/// of `chain` evaluations in each of `invocations`.
#[derive(Clone, Copy, Debug)]
pub struct GpuTime {
    /// The stage timed.
    pub stage: Stage,
    /// How it was timed.
    pub clock: Clock,
    /// What each round's run of twice the chain took beyond its run of the chain, divided by
    /// the evaluations the chain adds (`chains` x `chain` x `invocations`), in nanoseconds,
    /// over the rounds: device nanoseconds per evaluation, the whole device's throughput (not
    /// one invocation's latency), with no share of the run's fixed cost.
    pub ns: Spread,
    /// Steps of each chain, as calibrated.
    pub chain: u32,
    /// Independent chains side by side in each invocation ([`CHAINS`] in the timed harness).
    pub chains: u32,
    /// Invocations per run.
    pub invocations: u32,
    /// The median round's milliseconds for a run of the chain.
    pub run_ms: f64,
    /// A run of twice the chain over a run of the chain, at calibration: 2 where the work
    /// resolves.
    pub doubling_ratio: f64,
    /// Whether that ratio is 2 within the protocol's tolerance.
    pub doubled: bool,
}

impl GpuTime {
    /// The time less `harness`'s (the baseline row's), each statistic less the harness's
    /// median.
    pub fn less(self, harness: Option<GpuTime>) -> GpuTime {
        let base = harness.map_or(0.0, |harness| harness.ns.median);
        GpuTime {
            ns: self.ns.map(|ns| ns - base),
            ..self
        }
    }

    /// Whether the time is a measurement: twice the chain took twice the time, and the median
    /// (the harness's taken off) stands clear of the rounds' spread. A time within the spread,
    /// or under zero, is not a measurement to print.
    pub fn resolved(&self) -> bool {
        self.doubled && self.ns.median > 0.0 && self.ns.median > self.ns.width()
    }

    /// Where the time does not resolve: an upper bound on it, in nanoseconds per evaluation.
    /// A row's own time (the run's less the harness's) is at most the median (taken as zero
    /// when the harness's time exceeded it) plus the rounds' spread; a run that did not double
    /// holds a fixed cost besides the row's, which only adds. Never negative.
    pub fn upper_bound_ns(&self) -> Option<f64> {
        (!self.resolved()).then(|| self.ns.median.max(0.0) + self.ns.width().max(0.0))
    }

    /// Evaluations per run, over the whole device.
    pub fn evaluations_per_run(&self) -> u64 {
        u64::from(self.chains) * u64::from(self.chain) * u64::from(self.invocations)
    }

    /// Evaluations per second over the whole device at the median run: a run's evaluations over
    /// its time, the harness's own time taken off (once [`GpuTime::less`] has), which is
    /// 1e9 over the median of [`GpuTime::ns`].
    pub fn evaluations_per_second(&self) -> f64 {
        let evaluations = self.evaluations_per_run() as f64;
        let run_seconds = self.ns.median * evaluations / 1e9;
        evaluations / run_seconds
    }

    /// The time of runs of `chains` chains of `calibration.chain` evaluations in each of
    /// `invocations`, from the spread of the seconds that doubling the chain added to a run
    /// (`added`) and the median run's seconds.
    pub fn of_runs(
        stage: Stage,
        clock: Clock,
        added: Spread,
        run_seconds: f64,
        chains: u32,
        invocations: u32,
        calibration: Calibration,
    ) -> GpuTime {
        let evaluations = f64::from(chains) * f64::from(calibration.chain) * f64::from(invocations);
        GpuTime {
            stage,
            clock,
            ns: added.map(|seconds| seconds * 1e9 / evaluations),
            chain: calibration.chain,
            chains,
            invocations,
            run_ms: run_seconds * 1e3,
            doubling_ratio: calibration.doubling_ratio,
            doubled: calibration.doubled,
        }
    }
}

/// What calibration found for a row in one stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Calibration {
    /// Evaluations per invocation.
    pub chain: u32,
    /// A run of twice the chain over a run of the chain: 2 where the work resolves.
    pub doubling_ratio: f64,
    /// Whether that ratio is 2 within the protocol's tolerance.
    pub doubled: bool,
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
    /// The time in `stage`.
    pub fn get(&self, stage: Stage) -> Option<GpuTime> {
        match stage {
            Stage::Compute => self.compute,
            Stage::Fragment => self.fragment,
        }
    }

    /// Each stage's time less `base`'s in that stage ([`GpuTime::less`]).
    pub fn less(&self, base: &StageTimes) -> StageTimes {
        let mut times = *self;
        for &stage in Stage::ALL {
            *times.get_mut(stage) = self.get(stage).map(|time| time.less(base.get(stage)));
        }
        times
    }

    pub(super) fn get_mut(&mut self, stage: Stage) -> &mut Option<GpuTime> {
        match stage {
            Stage::Compute => &mut self.compute,
            Stage::Fragment => &mut self.fragment,
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
/// other's instructions) but whose resolved times say the opposite, every run of one slower
/// than every run of the other: a line each. A finding about the adapter, not a failed timing
/// (the protocol decides what resolves): a software rasteriser emulates the pack builtins, so
/// a fast conversion can cost it more than the exact one's arithmetic.
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
                && cheap_time.ns.min > dear_time.ns.max
            {
                found.push(format!(
                    "{} ({} instructions) took {:.3} ns, more than {} ({} instructions) at {:.3} ns",
                    cheap.name,
                    cheap.instructions,
                    cheap_time.ns.median,
                    dear.name,
                    dear.instructions,
                    dear_time.ns.median
                ));
            }
        }
    }
    found
}

/// Nanoseconds per evaluation of a row's CPU mirror, chained as on the GPU, [`CHAINS`] chains
/// side by side so that the core overlaps them as the GPU's harness lets it (median of runs).
pub fn cpu_ns_per_eval(evaluate: &dyn Fn(Vec4) -> Vec4) -> f64 {
    const STEPS: u32 = 1 << 14;
    let mut times = Vec::new();
    for _ in 0..CPU_RUNS {
        let start = Vec4::new(0.3, 0.6, 0.2, 0.7);
        let mut chains: [Vec4; CHAINS as usize] = std::array::from_fn(|chain| {
            (start + Vec4::splat(chain as f32 / CHAINS as f32)).fract()
        });
        let begin = Instant::now();
        for _ in 0..STEPS {
            for x in &mut chains {
                let y = evaluate(std::hint::black_box(*x));
                *x = (y * 0.25 + *x * 0.75 + Vec4::splat(0.1)).fract();
            }
        }
        std::hint::black_box(chains);
        times.push(begin.elapsed().as_secs_f64());
    }
    Spread::of(&times).map_or(f64::NAN, |spread| spread.median) * 1e9 / f64::from(STEPS * CHAINS)
}

#[cfg(test)]
mod tests {
    use super::*;
    use gbuffer_core::Named;

    /// Runs whose evaluations and times are known: 7 rounds whose doubled chains of 100
    /// evaluations in each of 1000 invocations (1e5 a run, in 4 chains of 25) added 10 ms at
    /// the median give 100 ns per evaluation and 1e7 evaluations a second, whatever the run
    /// itself took (15 ms: 5 of them fixed); with a harness whose chain adds 2 ms taken off,
    /// 80 ns and 1e5 evaluations in 8 ms.
    #[test]
    fn the_units_are_what_their_names_say() {
        let runs = vec![0.011, 0.0095, 0.010, 0.0102, 0.0099, 0.0105, 0.0098];
        let time = of_runs(runs);
        assert_eq!(time.evaluations_per_run(), 100_000);
        assert!((time.ns.median - 100.0).abs() < 1e-9, "{}", time.ns.median);
        assert!((time.run_ms - 15.0).abs() < 1e-9);
        assert!((time.ns.min - 95.0).abs() < 1e-9 && (time.ns.max - 110.0).abs() < 1e-9);
        assert!((time.evaluations_per_second() - 1e7).abs() < 1e-3);
        let harness = of_runs(vec![0.002; 7]);
        let less = time.less(Some(harness));
        assert!((less.ns.median - 80.0).abs() < 1e-9);
        assert!((less.evaluations_per_second() - 1e5 / 0.008).abs() < 1e-3);
    }

    /// Runs of 4 chains of 25 evaluations in each of 1000 invocations (100 evaluations an
    /// invocation), whose doubled chain added `runs` seconds, a run of the chain lasting half
    /// as long again.
    fn of_runs(runs: Vec<f64>) -> GpuTime {
        let added = Spread::of(&runs).unwrap();
        let calibration = Calibration {
            chain: 25,
            doubling_ratio: 2.0,
            doubled: true,
        };
        GpuTime::of_runs(
            Stage::Compute,
            Clock::Wall,
            added,
            1.5 * added.median,
            4,
            1000,
            calibration,
        )
    }

    /// A row faster than the harness can tell (its median, less the harness's, below zero: the
    /// "fully rough" row read -0.11 ns on llvmpipe) reports an upper bound, never a negative
    /// time; so does a row whose doubled chain did not take twice as long, however clear its
    /// median; a resolved row reports none.
    #[test]
    fn a_time_below_the_resolution_is_an_upper_bound() {
        let runs = vec![0.0100, 0.0104, 0.0098, 0.0101, 0.0099, 0.0102, 0.0097];
        let row = of_runs(runs);
        let less = row.less(Some(of_runs(vec![0.0101; 7])));
        assert!(less.ns.median < 0.0 && !less.resolved());
        let bound = less.upper_bound_ns().unwrap();
        // Spread 7 ns (97 to 104 ns a run), the median taken as zero.
        assert!((bound - 7.0).abs() < 1e-6, "{bound}");
        assert_eq!(time(100.0).upper_bound_ns(), None);
        let undoubled = GpuTime {
            doubled: false,
            doubling_ratio: 1.1,
            ..time(100.0)
        };
        assert!(!undoubled.resolved());
        assert!((undoubled.upper_bound_ns().unwrap() - 110.0).abs() < 1e-9);
    }

    fn time(median: f64) -> GpuTime {
        GpuTime {
            stage: Stage::Compute,
            clock: Clock::Wall,
            ns: Spread {
                min: median * 0.95,
                median,
                max: median * 1.05,
            },
            chain: 64,
            chains: CHAINS,
            invocations: INVOCATIONS,
            run_ms: 10.0,
            doubling_ratio: 2.0,
            doubled: true,
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

    /// The short protocol on the adapter, with timestamps where it has them and without:
    /// every row's runs last the target and its doubled chain took twice as long, and a row of
    /// eight square roots chained comes out dearer than the harness alone (the times are the
    /// row's, less the harness's).
    #[test]
    fn the_protocol_sizes_every_run_until_doubling_doubles_the_time() {
        let _cores = crate::tests::CORES
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let cheap =
            "fn row_eval(x: vec4<f32>) -> vec4<f32> {\n    return sqrt(x + vec4<f32>(0.5));\n}\n";
        let dear = "fn row_eval(x: vec4<f32>) -> vec4<f32> {\n    var y = x;\n    for (var i = 0; i < 8; i++) { y = sqrt(y + vec4<f32>(0.5)); }\n    return y;\n}\n";
        let with_timestamps = gbuffer_testkit::gpu_with(None, wgpu::Features::TIMESTAMP_QUERY);
        let Some(with_timestamps) = with_timestamps else {
            return;
        };
        for gpu in [with_timestamps, gbuffer_testkit::gpu().unwrap()] {
            let timestamps = gpu
                .device
                .features()
                .contains(wgpu::Features::TIMESTAMP_QUERY);
            // One round the shared cores slowed can put the dear row's spread over its
            // median: such a run is measured again, up to three times in all, as the packing
            // check does its conversions apart; a row that never stands clear of its spread
            // fails.
            let mut attempt = 0;
            let (rows, times) = loop {
                attempt += 1;
                let mut timer = Timer::new(&gpu, gbuffer_gpu::timing::Protocol::SHORT);
                let rows = [
                    timer.add("cheap", cheap, &[], 1),
                    timer.add("dear", dear, &[], 1),
                ];
                let times = timer.run();
                let dear_resolved = Stage::ALL
                    .iter()
                    .all(|&stage| (times[rows[1]].get(stage)).is_some_and(|time| time.resolved()));
                if dear_resolved || attempt == 3 {
                    break (rows, times);
                }
                eprintln!("the dear row did not resolve on attempt {attempt}: measuring again");
            };
            assert_eq!(times.len(), 2);
            for &stage in Stage::ALL {
                let [cheap, dear] = rows.map(|row| times[row].get(stage).unwrap());
                eprintln!("{stage:?}: {cheap:?}\n{dear:?}");
                for time in [cheap, dear] {
                    assert_eq!(time.stage, stage);
                    // Timestamps only where the device has them (and they bracket the work).
                    if !timestamps {
                        assert_eq!(time.clock, Clock::Wall);
                    }
                    // Calibration sized a run to `TARGET_RUN` by the wall clock, and takes the
                    // timestamps only where they come to half the wall clock's time or more;
                    // the rounds after it vary (a fifth here, on two shared cores).
                    let least = match time.clock {
                        Clock::Wall => 0.8,
                        Clock::Timestamps => 0.4,
                    } * 1e3
                        * TARGET_RUN;
                    assert!(
                        time.run_ms >= least || time.chain == MAX_CHAIN,
                        "{stage:?}: {time:?}"
                    );
                    assert!(time.ns.min <= time.ns.median && time.ns.median <= time.ns.max);
                    assert_eq!(time.upper_bound_ns().is_some(), !time.resolved());
                    if let Some(bound) = time.upper_bound_ns() {
                        assert!(bound >= 0.0);
                    }
                    let invocations = match stage {
                        Stage::Compute => INVOCATIONS,
                        Stage::Fragment => FRAGMENT_WIDTH * FRAGMENT_HEIGHT,
                    };
                    assert_eq!(time.invocations, invocations);
                }
                assert!(dear.doubled, "{stage:?}: {dear:?}");
                assert!(dear.resolved(), "{stage:?}: {dear:?}");
                assert!(dear.ns.median > cheap.upper_bound_ns().unwrap_or(cheap.ns.median));
            }
        }
    }

    /// The measuring chapter states the protocol's figures; they are this module's and
    /// `Protocol::FULL`'s, so changing one without the page fails here.
    #[test]
    fn the_guide_states_the_protocol_as_the_code_runs_it() {
        let chapter = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../book/src/measuring.md"
        ))
        .expect("the guide's measuring chapter");
        let flowed = chapter.split_whitespace().collect::<Vec<_>>().join(" ");
        let full = gbuffer_gpu::timing::Protocol::FULL;
        for stated in [
            format!("{CHAINS} chains side by side"),
            format!("2^{} invocations", INVOCATIONS.trailing_zeros()),
            format!("{FRAGMENT_WIDTH}x{FRAGMENT_HEIGHT} target"),
            format!("until a run lasts {} ms", TARGET_RUN * 1e3),
            format!(
                "until that difference itself lasts {} ms",
                TARGET_ADDED * 1e3
            ),
            format!("(within {}%)", full.doubling_within * 100.0),
            format!("within {}% of the one before", full.settled_within * 100.0),
            format!("{} rounds", full.rounds),
        ] {
            assert!(
                flowed.contains(&stated),
                "the measuring chapter does not say `{stated}`"
            );
        }
    }

    /// The CPU mirror's time is per evaluation of its chains: eight square roots a step cost
    /// more than none, and neither reads zero, negative or unbounded.
    #[test]
    fn the_cpu_mirrors_time_grows_with_its_work() {
        let cheap = cpu_ns_per_eval(&|x| x);
        let dear = cpu_ns_per_eval(&|x| {
            (0..8).fold(x, |y, _| {
                let y = y + Vec4::splat(0.5);
                Vec4::new(y.x.sqrt(), y.y.sqrt(), y.z.sqrt(), y.w.sqrt())
            })
        });
        assert!(cheap > 0.0 && dear.is_finite(), "{cheap} {dear}");
        assert!(dear > cheap, "{dear} ns is not more than {cheap} ns");
    }

    #[test]
    fn times_out_of_the_predicted_order_are_found_and_others_are_not() {
        let (fast, slow) = (time(2.0), time(5.0));
        assert!(inconsistencies(&pair(&fast, &slow)).is_empty());
        let found = inconsistencies(&pair(&slow, &fast));
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].starts_with("builtin (16 instructions) took 5.000 ns"));
        // Unresolved times are not compared.
        let unresolved = GpuTime {
            doubled: false,
            ..slow
        };
        assert!(inconsistencies(&pair(&unresolved, &fast)).is_empty());
    }
}
