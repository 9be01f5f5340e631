//! The one timing protocol behind every time the project prints: the trade-off study's rows
//! and packing table, its frame table and the renderer's bench.
//!
//! A GPU runs at the clock its recent load asks for: a data-centre GPU's SM clock idles at a
//! fraction of its loaded rate and takes tens of milliseconds of work to rise, and a CPU
//! rasteriser shares its cores with whatever else runs. A time therefore means something only when
//!
//! 1. the clock has settled: [`warm_up`] runs the work until consecutive runs agree;
//! 2. no clock change falls on one item alone: [`in_rounds`] times every item once a round, so
//!    a change spreads over all of them, and starts each round one item later, so no item is
//!    always timed first;
//! 3. the work is large enough to measure: doubling it doubles the time ([`doubles`]), which
//!    a run hidden under its launch or its memory traffic does not;
//! 4. each figure carries its spread ([`Spread`]: min, median and max over the rounds).
//!
//! [`Protocol::FULL`] is what the report and the benches use; [`Protocol::SHORT`] keeps the
//! tests quick, and the report and the benches take it where the environment asks for it
//! ([`Protocol::chosen`]: CI, which checks their tables, not their times).

/// The protocol's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Protocol {
    /// Warm-up ends when a run's time is within this fraction of the run before it.
    pub settled_within: f64,
    /// Warm-up runs at least this many times (the first runs also compile lazily)...
    pub min_warm_up_runs: usize,
    /// ... and at most this many: a clock that never settles is timed anyway, and the spread
    /// shows it.
    pub max_warm_up_runs: usize,
    /// Rounds: each item is timed once a round, so this is each figure's number of samples.
    pub rounds: usize,
    /// Doubled work must take between 2 x (1 - this) and 2 x (1 + this) times as long.
    pub doubling_within: f64,
}

impl Protocol {
    /// The report's and the bench's.
    pub const FULL: Protocol = Protocol {
        settled_within: 0.05,
        min_warm_up_runs: 3,
        max_warm_up_runs: 40,
        rounds: 7,
        doubling_within: 0.15,
    };

    /// The tests': fewer rounds, a looser warm-up.
    pub const SHORT: Protocol = Protocol {
        settled_within: 0.10,
        min_warm_up_runs: 2,
        max_warm_up_runs: 10,
        rounds: 3,
        doubling_within: 0.25,
    };

    /// The environment variable that chooses a timed command's protocol: `full` (or unset)
    /// for [`Protocol::FULL`], `short` for [`Protocol::SHORT`].
    pub const VARIABLE: &'static str = "GBUFFER_TIMING";

    /// The protocol a timed command (the report, the benches) runs: [`Protocol::FULL`] unless
    /// [`Protocol::VARIABLE`] says `short`. Any other value is an error that names the variable
    /// and the values it takes.
    pub fn chosen() -> Result<Protocol, String> {
        Self::named(std::env::var_os(Self::VARIABLE).as_deref())
    }

    /// The protocol a value of [`Protocol::VARIABLE`] names (`None`: the variable is unset).
    fn named(value: Option<&std::ffi::OsStr>) -> Result<Protocol, String> {
        match value {
            None => Ok(Protocol::FULL),
            Some(value) if value == "full" => Ok(Protocol::FULL),
            Some(value) if value == "short" => Ok(Protocol::SHORT),
            Some(value) => Err(format!(
                "{}={value:?}: the timing protocol is `full` or `short`",
                Self::VARIABLE
            )),
        }
    }
}

/// The least, middle and greatest of some samples, in their unit (the caller's name says it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    /// The smallest sample.
    pub min: f64,
    /// The middle sample (the upper of the two middle ones for an even count).
    pub median: f64,
    /// The largest sample.
    pub max: f64,
}

impl Spread {
    /// The spread of `samples`; `None` when there are none.
    pub fn of(samples: &[f64]) -> Option<Spread> {
        let mut sorted = samples.to_vec();
        sorted.sort_by(f64::total_cmp);
        Some(Spread {
            min: *sorted.first()?,
            median: sorted[sorted.len() / 2],
            max: *sorted.last()?,
        })
    }

    /// Every statistic through `f` (a change of unit; `f` must not reorder them).
    pub fn map(self, f: impl Fn(f64) -> f64) -> Spread {
        Spread {
            min: f(self.min),
            median: f(self.median),
            max: f(self.max),
        }
    }

    /// The width of the spread: max less min.
    pub fn width(&self) -> f64 {
        self.max - self.min
    }
}

/// How a warm-up ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WarmUp {
    /// The runs it took.
    pub runs: usize,
    /// Whether the last two agreed within [`Protocol::settled_within`] (else it gave up at
    /// [`Protocol::max_warm_up_runs`]).
    pub settled: bool,
}

/// Runs `run` (which returns one run's seconds) until two consecutive runs agree within
/// `protocol.settled_within`, at least `min_warm_up_runs` and at most `max_warm_up_runs`
/// times.
pub fn warm_up(
    protocol: &Protocol,
    run: &mut dyn FnMut() -> Result<f64, String>,
) -> Result<WarmUp, String> {
    let mut previous: Option<f64> = None;
    for runs in 1..=protocol.max_warm_up_runs.max(1) {
        let time = run()?;
        let settled = previous.is_some_and(|previous| {
            (time - previous).abs() <= protocol.settled_within * previous.abs()
        });
        if settled && runs >= protocol.min_warm_up_runs {
            return Ok(WarmUp {
                runs,
                settled: true,
            });
        }
        previous = Some(time);
    }
    Ok(WarmUp {
        runs: protocol.max_warm_up_runs.max(1),
        settled: false,
    })
}

/// Times `items` items in `protocol.rounds` rounds (at least one): each round calls
/// `run(item)` once for every item, starting one item later than the round before (round r
/// times r, r + 1, ... and wraps), so no item is always timed first. Each item's spread over
/// the rounds.
pub fn in_rounds(
    protocol: &Protocol,
    items: usize,
    run: &mut dyn FnMut(usize) -> Result<f64, String>,
) -> Result<Vec<Spread>, String> {
    let rounds = protocol.rounds.max(1);
    let mut samples = vec![Vec::with_capacity(rounds); items];
    for round in 0..rounds {
        for offset in 0..items {
            let item = (round + offset) % items;
            samples[item].push(run(item)?);
        }
    }
    Ok(samples
        .iter()
        .map(|samples| Spread::of(samples).expect("at least one round"))
        .collect())
}

/// The whole protocol over `items` items that need no calibration (frames): warm-up rounds,
/// each calling `run(item)` once for every item, until two consecutive rounds' totals agree
/// (so every item has run, compiled and cached before any is timed), then the timed rounds
/// ([`in_rounds`]). How the warm-up ended, and each item's spread.
pub fn time_items(
    protocol: &Protocol,
    items: usize,
    run: &mut dyn FnMut(usize) -> Result<f64, String>,
) -> Result<(WarmUp, Vec<Spread>), String> {
    let warm = warm_up(protocol, &mut || {
        (0..items).try_fold(0.0, |total, item| Ok(total + run(item)?))
    })?;
    Ok((warm, in_rounds(protocol, items, run)?))
}

/// Whether work that took `single` seconds, doubled, taking `double`, resolves: the ratio is
/// 2 within `protocol.doubling_within` (a fixed cost, such as a launch, would make it less;
/// a clock change or a cache spill, more).
pub fn doubles(protocol: &Protocol, single: f64, double: f64) -> bool {
    let ratio = double / single;
    single > 0.0
        && ratio >= 2.0 * (1.0 - protocol.doubling_within)
        && ratio <= 2.0 * (1.0 + protocol.doubling_within)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_environment_chooses_the_protocol_by_name() {
        use std::ffi::OsStr;
        assert_eq!(Protocol::named(None), Ok(Protocol::FULL));
        assert_eq!(
            Protocol::named(Some(OsStr::new("full"))),
            Ok(Protocol::FULL)
        );
        assert_eq!(
            Protocol::named(Some(OsStr::new("short"))),
            Ok(Protocol::SHORT)
        );
        let error = Protocol::named(Some(OsStr::new("quick"))).unwrap_err();
        assert!(error.contains("GBUFFER_TIMING=\"quick\""), "{error}");
        assert!(error.contains("`full` or `short`"), "{error}");
    }

    #[test]
    fn a_spread_is_the_least_middle_and_greatest_sample() {
        let spread = Spread::of(&[3.0, 1.0, 2.0, 9.0, 4.0]).unwrap();
        assert_eq!(
            spread,
            Spread {
                min: 1.0,
                median: 3.0,
                max: 9.0
            }
        );
        assert_eq!(spread.width(), 8.0);
        assert_eq!(spread.map(|x| x * 1e3).median, 3000.0);
        assert_eq!(Spread::of(&[]), None);
    }

    /// A clock that ramps up (runs of 40, 30, 20, 12, 10.2, 10 ms) settles once two runs agree
    /// within 5%: after the sixth run, not before.
    #[test]
    fn warm_up_lasts_until_the_clock_settles() {
        let ramp = [0.040, 0.030, 0.020, 0.012, 0.0102, 0.0100, 0.0100];
        let mut next = ramp.iter();
        let warm = warm_up(&Protocol::FULL, &mut || Ok(*next.next().unwrap())).unwrap();
        assert_eq!(
            warm,
            WarmUp {
                runs: 6,
                settled: true
            }
        );
        // A clock that never settles gives up at the limit.
        let mut flip = 0.0;
        let warm = warm_up(&Protocol::SHORT, &mut || {
            flip += 1.0;
            Ok(0.01 * (1.0 + flip % 2.0))
        })
        .unwrap();
        assert_eq!(warm.runs, Protocol::SHORT.max_warm_up_runs);
        assert!(!warm.settled);
        // Errors pass through.
        assert!(warm_up(&Protocol::FULL, &mut || Err("lost".into())).is_err());
    }

    /// A clock that halves its speed half-way through: timed item by item, the items timed
    /// late look twice as slow as the early ones; timed in rounds, every item sees both
    /// clocks and their medians agree.
    #[test]
    fn rounds_spread_a_clock_change_over_every_item() {
        let protocol = Protocol {
            rounds: 4,
            ..Protocol::FULL
        };
        let mut calls = 0;
        let mut samples = vec![Vec::new(); 3];
        let mut clock = |item: usize| {
            calls += 1;
            let time = if calls <= 6 { 1.0 } else { 2.0 };
            samples[item].push(time);
            Ok(time)
        };
        let spreads = in_rounds(&protocol, 3, &mut clock).unwrap();
        assert_eq!(spreads.len(), 3);
        for (item, spread) in samples.iter().zip(&spreads) {
            assert_eq!(item.len(), 4);
            assert_eq!(item.iter().sum::<f64>(), 6.0, "{samples:?}");
            assert_eq!((spread.min, spread.max), (1.0, 2.0), "{spreads:?}");
        }
        // The order rotates: round 1 starts with item 1.
        let mut order = Vec::new();
        in_rounds(&protocol, 3, &mut |item| {
            order.push(item);
            Ok(0.0)
        })
        .unwrap();
        assert_eq!(order, [0, 1, 2, 1, 2, 0, 2, 0, 1, 0, 1, 2]);
    }

    /// Frames whose first run compiles (ten times slower): the warm-up rounds run every item
    /// until two rounds agree, and no timed sample holds a first run.
    #[test]
    fn every_item_is_warm_before_any_is_timed() {
        let mut runs = [0; 3];
        let (warm, spreads) = time_items(&Protocol::SHORT, 3, &mut |item| {
            runs[item] += 1;
            Ok(if runs[item] == 1 { 0.1 } else { 0.01 })
        })
        .unwrap();
        assert!(warm.settled);
        // The first round compiles, the second is warm, the third agrees with it.
        assert_eq!(warm.runs, 3);
        assert!(spreads.iter().all(|spread| spread.max == 0.01));
        assert_eq!(runs, [3 + Protocol::SHORT.rounds; 3]);
    }

    #[test]
    fn doubled_work_resolves_only_when_it_takes_twice_as_long() {
        let protocol = Protocol::FULL;
        assert!(doubles(&protocol, 0.010, 0.020));
        assert!(doubles(&protocol, 0.010, 0.0175));
        // A run hidden under a launch of 9 ms: 10 ms and 11 ms.
        assert!(!doubles(&protocol, 0.010, 0.011));
        assert!(!doubles(&protocol, 0.010, 0.025));
        assert!(!doubles(&protocol, 0.0, 0.0));
    }
}
