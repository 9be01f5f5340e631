//! Rows of an image computed on every thread of the machine: the CPU reference's frames and
//! the baked inputs.

use std::sync::atomic::{AtomicU32, Ordering};

/// `row(y)` for every y below `height`, in order, computed on the machine's threads (rows
/// interleaved between them); `row_done(rows finished)` is called as they finish.
pub fn rows<T: Send>(
    height: u32,
    row: impl Fn(u32) -> Vec<T> + Sync,
    row_done: impl Fn(u32) + Sync,
) -> Vec<T> {
    let threads = std::thread::available_parallelism().map_or(2, |count| count.get()) as u32;
    let finished = AtomicU32::new(0);
    let mut rows: Vec<(u32, Vec<T>)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|thread| {
                let (row, row_done, finished) = (&row, &row_done, &finished);
                scope.spawn(move || {
                    (thread..height)
                        .step_by(threads as usize)
                        .map(|y| {
                            let values = row(y);
                            row_done(finished.fetch_add(1, Ordering::Relaxed) + 1);
                            (y, values)
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|worker| worker.join().expect("a worker thread panicked"))
            .collect()
    });
    rows.sort_by_key(|(y, _)| *y);
    rows.into_iter().flat_map(|(_, values)| values).collect()
}
