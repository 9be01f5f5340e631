//! What each stage of a frame adds to it, from the frame built up stage by stage: frame 0 draws
//! nothing, frame k the first k stages, each timed over rounds ([`crate::timing`]).
//!
//! Stage k's time is frame k's less frame k-1's. Read from the medians as they come, a stage
//! whose frame happened to be timed fast reads negative and the stage before it takes its time
//! (a lavapipe frame that did, in the tests below).
//! So frames that the rounds cannot tell apart are pooled first: where a frame is not slower
//! than the frames before it by more than their spread, it joins them, and the pool's time is
//! its frames' mean (least squares under the order the stages impose, as in the pool adjacent
//! violators algorithm; Barlow et al., *Statistical Inference under Order Restrictions*, 1972,
//! with the spread as the least step). A pool's first stage carries what the whole pool adds;
//! the stages after it are said to be inseparable from it. The stages' times then never go
//! negative, and they sum to the last pool's time less the first's: the whole frame less the
//! empty passes, each within its spread.

use crate::timing::Spread;

/// What one stage adds to the frame before it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StageTime {
    /// The stage adds this much (the frames' unit) over the stages before it, with every stage
    /// after it marked [`StageTime::WithTheStageBefore`].
    Adds(f64),
    /// The rounds cannot separate this stage's frame from the one before: its time is in the
    /// figure of the stage before (or, for the first stages, in the empty passes' spread).
    WithTheStageBefore,
}

impl StageTime {
    /// What the stage adds, where the rounds separate it.
    pub fn adds(self) -> Option<f64> {
        match self {
            StageTime::Adds(time) => Some(time),
            StageTime::WithTheStageBefore => None,
        }
    }
}

/// Each stage's time, from `frames[k]`, the frame that draws the first `k` stages (frame 0
/// draws none): one [`StageTime`] per stage, `frames.len() - 1` of them.
pub fn stage_times(frames: &[Spread]) -> Vec<StageTime> {
    /// Consecutive frames pooled: the first, their sum of medians, how many, the widest spread.
    struct Pool {
        first: usize,
        sum: f64,
        frames: usize,
        width: f64,
    }
    impl Pool {
        fn time(&self) -> f64 {
            self.sum / self.frames as f64
        }
    }
    let mut pools: Vec<Pool> = Vec::new();
    for (index, frame) in frames.iter().enumerate() {
        let mut pool = Pool {
            first: index,
            sum: frame.median,
            frames: 1,
            width: frame.width(),
        };
        // Pool with the frames before while the step up is not above both spreads.
        while let Some(before) = pools.last() {
            if pool.time() - before.time() > before.width.max(pool.width) {
                break;
            }
            pool = Pool {
                first: before.first,
                sum: before.sum + pool.sum,
                frames: before.frames + pool.frames,
                width: before.width.max(pool.width),
            };
            pools.pop();
        }
        pools.push(pool);
    }
    let mut times = vec![StageTime::WithTheStageBefore; frames.len().saturating_sub(1)];
    for pair in pools.windows(2) {
        // Frame `first` is the one that adds stage `first` (times[first - 1]).
        times[pair[1].first - 1] = StageTime::Adds(pair[1].time() - pair[0].time());
    }
    times
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(median: f64, width: f64) -> Spread {
        Spread {
            min: median - width / 2.0,
            median,
            max: median + width / 2.0,
        }
    }

    fn adds(times: &[StageTime]) -> Vec<Option<f64>> {
        times
            .iter()
            .map(|time| time.adds().map(|ms| (ms * 1e6).round() / 1e6))
            .collect()
    }

    /// Frames that grow by more than their spreads: each stage is its difference, and the
    /// stages sum to the whole frame less the empty one.
    #[test]
    fn resolved_stages_are_the_frames_differences() {
        let frames = [
            frame(3.0, 0.5),
            frame(10.0, 0.5),
            frame(12.0, 0.5),
            frame(20.0, 1.0),
        ];
        assert_eq!(
            adds(&stage_times(&frames)),
            [Some(7.0), Some(2.0), Some(8.0)]
        );
    }

    /// The lavapipe frame that read negative: its lighting frame timed slow, its resolve and
    /// sky frames faster. The three pool: the lighting carries what they add together, the
    /// others are inseparable from it, nothing is negative and the stages sum to the pool's
    /// time less the empty passes'.
    #[test]
    fn a_frame_faster_than_the_one_before_pools_with_it() {
        let frames = [
            frame(3.53, 1.0),
            frame(34.65, 4.0),
            frame(40.99, 4.0),
            frame(161.19, 30.0),
            frame(133.53, 30.0),
            frame(141.34, 30.0),
        ];
        let times = adds(&stage_times(&frames));
        let pooled = (161.19 + 133.53 + 141.34) / 3.0;
        assert_eq!(
            times,
            [
                Some(31.12),
                Some(6.34),
                Some(((pooled - 40.99) * 1e6_f64).round() / 1e6),
                None,
                None
            ]
        );
        let sum: f64 = times.iter().flatten().sum();
        assert!((sum - (pooled - 3.53)).abs() < 1e-5, "{sum}");
    }

    /// A step within the spread pools, and pooling can reach back: the pooled frames' mean
    /// may then sit within the spread of the frame before them too.
    #[test]
    fn steps_within_the_spread_pool_back_as_far_as_they_must() {
        // Frame 2 adds 0.4 within a spread of 1: it pools with frame 1. Frame 3 reads below
        // both; their mean (10.1) is within the spread of frame 0's 9.5, so all four pool.
        let frames = [
            frame(9.5, 1.0),
            frame(10.6, 1.0),
            frame(11.0, 1.0),
            frame(8.8, 1.0),
        ];
        assert_eq!(adds(&stage_times(&frames)), [None, None, None]);
        // No stages, or one frame: nothing to say.
        assert!(stage_times(&[]).is_empty());
        assert!(stage_times(&[frame(1.0, 0.1)]).is_empty());
    }

    /// Whatever the medians and spreads (a thousand noisy built-up frames), no stage's time is
    /// negative, nor zero.
    #[test]
    fn no_stage_time_is_negative() {
        let mut state = 12345u32;
        let mut next = || {
            state = state.wrapping_mul(1664525).wrapping_add(1013904223);
            f64::from(state >> 8) / f64::from(1u32 << 24)
        };
        for _ in 0..1000 {
            let frames: Vec<Spread> = (0..6)
                .map(|stage| frame(stage as f64 * 2.0 + next() * 8.0, next() * 3.0))
                .collect();
            for ms in stage_times(&frames).iter().filter_map(|time| time.adds()) {
                assert!(ms > 0.0, "{frames:?}");
            }
        }
    }
}
