//! The `dismech` command as a user runs it: exit codes that tell the
//! outcomes apart, console lines that show what a check compares with, and
//! a study folder that an interrupted run leaves whole.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn dismech(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dismech"))
        .args(args)
        .output()
        .expect("the dismech binary runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dismech-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Names and contents of the files of a folder, sorted.
fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(e.path()).unwrap_or_default())
        })
        .collect();
    files.sort();
    files
}

#[test]
fn locked_lattice_exits_with_locked_code() {
    // Paper 002's U-model with more columns than rows is locked.
    let run = dismech(&[
        "lattice-limit-load",
        "--model",
        "u",
        "--m",
        "8",
        "--n",
        "4",
        "--nprime",
        "1",
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(stdout.contains("\"status\":\"Locked\""), "{stdout}");
    assert_eq!(run.status.code(), Some(3), "{stdout}");
}

#[test]
fn collapsing_lattice_exits_zero() {
    let run = dismech(&[
        "lattice-limit-load",
        "--model",
        "u",
        "--m",
        "8",
        "--n",
        "8",
        "--nprime",
        "2",
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(stdout.contains("\"status\":\"Collapse\""), "{stdout}");
    assert_eq!(run.status.code(), Some(0));
}

#[test]
fn odd_lattice_size_exits_with_bad_input_code() {
    let run = dismech(&["lattice-limit-load", "--model", "u", "--m", "3", "--n", "4"]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("invalid m (columns) = 3"), "{stderr}");
    assert_eq!(run.status.code(), Some(2));
}

/// The rolling L-model with one element per column has a zero limit load
/// (its loaded element rolls away); it was reported as a collapse at
/// P = −9.8e-25 with exit 0.
#[test]
fn rolling_l_lattice_of_one_row_exits_with_bad_input_code() {
    let run = dismech(&["lattice-limit-load", "--model", "l", "--m", "2", "--n", "1"]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("n (elements per column)"), "{stderr}");
    assert!(run.stdout.is_empty());
}

#[test]
fn unknown_study_exits_with_bad_input_code() {
    let out = scratch("unknown");
    let run = dismech(&["reproduce", "katsuki", "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("unknown study `katsuki`"), "{stderr}");
    assert_eq!(run.status.code(), Some(2));
    assert!(contents(&out).is_empty(), "nothing is written");
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn help_lists_the_exit_codes() {
    for args in [
        &["--help"][..],
        &["reproduce", "--help"],
        &["lattice-limit-load", "--help"],
    ] {
        let run = dismech(args);
        let stdout = String::from_utf8_lossy(&run.stdout);
        for line in [
            "Exit status:",
            "  0  success",
            "  1  a study ran and wrote its results, but a check failed",
            "  3  the lattice is locked",
            "  5  a solver or simulation could not go on",
        ] {
            assert!(stdout.contains(line), "{line:?} not in\n{stdout}");
        }
        assert_eq!(run.status.code(), Some(0));
    }
}

/// A study that cannot write its folder is reported as not run, with the
/// output code, and the file in its way is left alone.
#[test]
fn study_that_cannot_write_exits_with_output_code() {
    let out = scratch("blocked");
    std::fs::write(out.join("yamada2000"), "not a folder").unwrap();
    let run = dismech(&[
        "reproduce",
        "yamada2000",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        stdout.contains("yamada2000  could not run: cannot write"),
        "{stdout}"
    );
    assert_eq!(run.status.code(), Some(6), "{stdout}");
    assert_eq!(
        std::fs::read_to_string(out.join("yamada2000")).unwrap(),
        "not a folder"
    );
    assert_eq!(contents(&out).len(), 1, "no staging folder is left");
    std::fs::remove_dir_all(&out).unwrap();
}

/// Table 3 prints 8.07 for k = 4, n' = 2 where eq. (38) gives 16.49: the
/// check passes by eq. (38), and the console says so instead of showing
/// the misprint as the value reproduced.
#[test]
fn table3_misprint_is_shown_met_by_eq38_not_by_the_paper() {
    let out = scratch("yamada");
    let run = dismech(&[
        "reproduce",
        "yamada2000",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert_eq!(run.status.code(), Some(0), "{stdout}");
    let line = stdout
        .lines()
        .find(|l| l.contains("table3.k4.n2 "))
        .unwrap_or_else(|| panic!("no table3.k4.n2 line in\n{stdout}"));
    assert!(
        line.contains("within 0.01 of the paper's 8.07 or within"),
        "{line}"
    );
    assert!(line.contains("met: eq. (38) = 16.4853"), "{line}");
    assert!(!line.contains("tol"), "{line}");
    assert!(stdout.contains("yamada2000  passed ("), "{stdout}");
    std::fs::remove_dir_all(&out).unwrap();
}

/// A study killed while it writes leaves the previous results as they
/// were: no new file beside old ones, no stray temporary file inside.
#[test]
fn killed_study_leaves_old_results_whole() {
    let out = scratch("killed");
    let target = out.join("yamada2000");
    std::fs::create_dir_all(&target).unwrap();
    for (file, text) in [
        ("table1.csv", "old table 1"),
        ("table3.csv", "old table 3"),
        ("summary.json", "{\"old\": true}"),
    ] {
        std::fs::write(target.join(file), text).unwrap();
    }
    let old = contents(&target);
    let mut child = Command::new(env!("CARGO_BIN_EXE_dismech"))
        .args(["reproduce", "yamada2000", "--quiet", "--out"])
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Kill it as soon as it has written a first file, wherever it writes.
    let start = Instant::now();
    let written = |dir: &Path| {
        std::fs::read_dir(dir).is_ok_and(|entries| {
            entries.flatten().any(|e| {
                let path = e.path();
                path != target
                    && std::fs::read_dir(&path).is_ok_and(|mut files| files.next().is_some())
            })
        })
    };
    while contents(&target) == old && !written(&out) {
        assert!(
            start.elapsed() < Duration::from_secs(600),
            "the study wrote nothing"
        );
        assert!(
            child.try_wait().unwrap().is_none(),
            "the study ended before it was killed"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert_eq!(contents(&target), old);
    std::fs::remove_dir_all(&out).unwrap();
}
