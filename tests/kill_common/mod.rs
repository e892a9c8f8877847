//! A run killed at a random step: the test re-executes its own binary as
//! a child process (`--exact NAME --nocapture`, with [`CHILD_FOLDER`] in
//! its environment) that runs the model, writes its checkpoints into a
//! folder (atomically, a file per checkpoint) and prints its progress
//! (`progress N`) after every step; the parent reads that progress and
//! sends the child SIGKILL as soon as it passes a step drawn at random,
//! wherever the child then is (inside a step, or inside the write of a
//! checkpoint). The parent then resumes from the last checkpoint on disk.
//!
//! The draw is seeded: the seed is printed, and `DISMECH_KILL_SEED=S`
//! draws the same step again (where the kill lands past it depends on
//! timing, and is printed too).

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

/// The environment variable that makes the test its child: the folder the
/// child writes its checkpoints into.
pub const CHILD_FOLDER: &str = "DISMECH_KILL_CHILD";

/// The environment variable that holds the last step the child may take
/// before it waits to be killed.
pub const CHILD_LIMIT: &str = "DISMECH_KILL_LIMIT";

/// The environment variable that fixes the draw's seed.
pub const SEED: &str = "DISMECH_KILL_SEED";

/// Where the child writes its checkpoints, and the last step it may take,
/// when this process is the child.
pub fn child() -> Option<(PathBuf, u64)> {
    let folder = std::env::var_os(CHILD_FOLDER)?;
    let limit = std::env::var(CHILD_LIMIT)
        .expect("the child is told its limit")
        .parse()
        .expect("the limit is a number");
    Some((PathBuf::from(folder), limit))
}

/// The child's progress line after step `step`.
pub fn report_progress(step: u64) {
    println!("progress {step}");
}

/// The path of the checkpoint after step `step`.
pub fn checkpoint_path(folder: &Path, step: u64) -> PathBuf {
    folder.join(format!("step_{step:08}.ckpt"))
}

/// The child, having reached its limit without being killed, waits for
/// the kill (and gives up after a minute, should the parent be gone).
pub fn wait_for_the_kill() -> ! {
    std::thread::sleep(Duration::from_secs(60));
    panic!("the child was not killed within a minute");
}

/// What the parent saw of the killed child.
#[derive(Debug)]
pub struct Killed {
    /// The step drawn.
    pub drawn: u64,
    /// The last step the child reported before it died.
    pub last_reported: u64,
    /// The last checkpoint on disk: its step and path.
    pub checkpoint: (u64, PathBuf),
}

/// Run the test `test` of this binary (its path from [`module_path!`],
/// whose first segment, the binary's own name, is dropped) as a child writing its checkpoints
/// into `folder` (emptied first), kill it with SIGKILL once it reports a
/// step at or past one drawn uniformly from `draw` (seeded by [`SEED`] or
/// the clock; printed), and give the last checkpoint it left. The child
/// may take at most `lead` steps past the drawn one before it waits, so
/// that the kill lands before the end of its run.
///
/// # Panics
/// Where the child cannot be started, ends before the drawn step (its
/// error output is shown), or left no checkpoint.
pub fn run_and_kill(
    test: &str,
    folder: &Path,
    draw: std::ops::RangeInclusive<u64>,
    lead: u64,
) -> Killed {
    let test = test.split_once("::").map_or(test, |(_binary, path)| path);
    let seed = match std::env::var(SEED) {
        Ok(s) => s.parse().expect("DISMECH_KILL_SEED is a number"),
        Err(_) => std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos() as u64,
    };
    let drawn = StdRng::seed_from_u64(seed).random_range(draw);
    println!("{test}: seed {seed} (rerun with {SEED}={seed}), kill at step {drawn}");
    let _ = std::fs::remove_dir_all(folder);
    std::fs::create_dir_all(folder).unwrap();

    let mut child = Command::new(std::env::current_exe().unwrap())
        .args(["--exact", test, "--nocapture", "--test-threads=1"])
        .env(CHILD_FOLDER, folder)
        .env(CHILD_LIMIT, (drawn + lead).to_string())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the test binary runs itself");
    let started = Instant::now();
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    let mut last_reported = 0;
    let mut killed = false;
    for line in lines.by_ref() {
        let line = line.unwrap();
        if let Some(step) = line.strip_prefix("progress ") {
            last_reported = step.parse().unwrap();
            if last_reported >= drawn {
                child.kill().unwrap(); // SIGKILL
                killed = true;
                break;
            }
        }
    }
    // What the child printed between the progress read and its death.
    for line in lines {
        if let Some(step) = line.unwrap().strip_prefix("progress ") {
            last_reported = step.parse().unwrap();
        }
    }
    let status = child.wait().unwrap();
    if !killed {
        let mut stderr = String::new();
        std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
        panic!("the child ended ({status}) at step {last_reported}, before step {drawn}: {stderr}");
    }
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        assert_eq!(
            status.signal(),
            Some(9),
            "the child died of SIGKILL: {status}"
        );
    }

    // The checkpoints are whole or absent: the latest by its name. A kill
    // inside a write leaves only the temporary file, named with a dot.
    let mut latest: Option<(u64, PathBuf)> = None;
    for entry in std::fs::read_dir(folder).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if name.starts_with('.') {
            continue;
        }
        let step: u64 = name
            .strip_prefix("step_")
            .and_then(|s| s.strip_suffix(".ckpt"))
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("unexpected file {name}"));
        if latest.as_ref().is_none_or(|(s, _)| step > *s) {
            latest = Some((step, path));
        }
    }
    let checkpoint = latest.expect("the child left a checkpoint");
    println!(
        "{test}: killed after step {last_reported} ({:.0} ms), resuming from the checkpoint of step {}",
        started.elapsed().as_secs_f64() * 1e3,
        checkpoint.0
    );
    Killed {
        drawn,
        last_reported,
        checkpoint,
    }
}
