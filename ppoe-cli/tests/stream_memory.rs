//! `render --format html` streams its frames: the command's peak memory does not grow with
//! the number of cases. Measured from outside, as the high-water mark of the child's
//! resident memory (`VmHWM` in `/proc/<pid>/status`, Linux), polled while it runs. (The
//! GIF writer's bound is a unit test: `picture::survey`, frames alive at once.)

mod common;
use common::*;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

/// The surface grid: each frame holds 400² points of 24 bytes (3.8 MB), so holding the
/// frames of the larger run would add more than 200 MB.
const GRID: &str = "400";

/// The child's peak resident memory in kB so far, if it is still running.
fn vm_hwm(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Runs `render --format html` on `n` cases; the last peak resident memory read (kB)
/// and the page's size.
fn peak_kb(n: usize) -> (u64, u64) {
    let dir = fresh_dir(&format!("stream-memory-{n}"));
    let input = dir.join("cases.json");
    std::fs::write(&input, seed_cases(n)).unwrap();
    let extra = ["--format", "html", "--grid", GRID, "--input"];
    let mut a = seed_args("render", &extra);
    a.extend([input.to_str().unwrap(), "--out", dir.to_str().unwrap()].map(String::from));
    let mut child = Command::new(BIN)
        .args(refs(&a))
        .current_dir(repo())
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    let mut peak = 0;
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        // VmHWM only grows, so the last read before the exit is the run's peak (up to
        // the last few milliseconds, after the page is complete).
        peak = vm_hwm(child.id()).unwrap_or(peak).max(peak);
        std::thread::sleep(Duration::from_millis(5));
    };
    assert!(status.success(), "render of {n} cases failed");
    let page = std::fs::metadata(dir.join("ppoe-render.html"))
        .unwrap()
        .len();
    (peak, page)
}

#[test]
fn html_peak_memory_does_not_grow_with_the_number_of_cases() {
    if !Path::new("/proc/self/status").exists() {
        eprintln!("no /proc: the peak memory cannot be read here");
        return;
    }
    let (small, small_page) = peak_kb(4);
    let (large, large_page) = peak_kb(64);
    assert!(small > 0 && large > 0, "no VmHWM read");
    assert!(
        large_page > 10 * small_page,
        "{small_page} -> {large_page} bytes"
    );
    // 60 more frames of 3.8 MB each would add 230 MB; allow 20 MB for the page's
    // buffered output and the allocator.
    assert!(
        large < small + 20_000,
        "peak resident memory {small} kB for 4 cases, {large} kB for 64"
    );
}
