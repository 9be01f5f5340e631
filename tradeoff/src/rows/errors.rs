//! A row's error over its domain: the largest and the root-mean-square, accumulated sample by
//! sample.

/// The largest and root-mean-square error over a domain.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Errors {
    pub max: f64,
    pub rms: f64,
}

/// The running error of a row's samples.
#[derive(Default)]
pub(super) struct Accumulator {
    max: f64,
    sum_of_squares: f64,
    count: usize,
}

impl Accumulator {
    pub(super) fn add(&mut self, error: f64) {
        self.max = self.max.max(error);
        self.sum_of_squares += error * error;
        self.count += 1;
    }

    pub(super) fn finish(&self) -> Errors {
        Errors {
            max: self.max,
            rms: (self.sum_of_squares / self.count.max(1) as f64).sqrt(),
        }
    }
}
