//! The runner of the studies, with stand-in studies: `all` goes on after a
//! study that cannot run, its table names every study's outcome, and a
//! study that fails midway leaves the previous results whole.

use std::path::{Path, PathBuf};

use super::outcome::{exit, table};
use super::*;
use crate::exit_status::Exit;
use dismech::io::write_atomically;
use dismech_cli::output::{Check, Reference, Rule};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dismech-runner-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn summary(name: &str, computed: f64) -> Summary {
    Summary {
        study: name.into(),
        paper: "none".into(),
        checks: vec![Check::new(
            "ratio",
            "a ratio",
            "-",
            computed,
            &Rule::near(Reference::number(1.0), 0.01),
        )],
        values: Vec::new(),
        files: Vec::new(),
    }
}

/// Writes two files and passes its check.
fn passing(options: &StudyOptions) -> Result<Summary> {
    write_atomically(&options.dir.join("a.csv"), b"new a")?;
    summary("passing", 1.0).write_with_report(&options.dir, "# new")
}

/// Writes its files; its check fails.
fn failing_check(options: &StudyOptions) -> Result<Summary> {
    summary("failing-check", 2.0).write_with_report(&options.dir, "# new")
}

/// Writes its first file, then its writer fails.
fn failing_writer(options: &StudyOptions) -> Result<Summary> {
    write_atomically(&options.dir.join("a.csv"), b"new a")?;
    Err(DismechError::Output {
        path: options.dir.join("b.csv").display().to_string(),
        message: "No space left on device".into(),
    })
}

const PASSING: Study = Study {
    name: "passing",
    run: passing,
};
const FAILING_CHECK: Study = Study {
    name: "failing-check",
    run: failing_check,
};
const FAILING_WRITER: Study = Study {
    name: "failing-writer",
    run: failing_writer,
};

fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn reproduce_all_continues_after_a_failed_study() {
    let out = scratch("all");
    let mut ended = Vec::new();
    let outcomes = run_all(
        &[FAILING_WRITER, FAILING_CHECK, PASSING],
        &out,
        false,
        |o| ended.push(o.study),
    );
    assert_eq!(ended, ["failing-writer", "failing-check", "passing"]);
    assert!(outcomes[0].result.is_err());
    assert!(out.join("passing/summary.json").is_file());
    assert!(out.join("failing-check/summary.json").is_file());
    let text = table(&outcomes);
    assert!(
        text.contains("failing-writer  could not run: cannot write"),
        "{text}"
    );
    assert!(
        text.contains("failing-check   FAILED (1 of 1 checks failed: ratio)"),
        "{text}"
    );
    assert!(text.contains("passing         passed (1 checks)"), "{text}");
    // The worst outcome: a study that could not run, for want of disk.
    assert_eq!(exit(&outcomes), Exit::OutputFailed);
    assert_eq!(exit(&outcomes[1..]), Exit::CheckFailed);
    assert_eq!(exit(&outcomes[2..]), Exit::Success);
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn study_whose_writer_fails_midway_leaves_old_results_whole() {
    let out = scratch("midway");
    let old = out.join("failing-writer");
    std::fs::create_dir_all(&old).unwrap();
    for (file, text) in [
        ("a.csv", "old a"),
        ("b.csv", "old b"),
        ("summary.json", "{}"),
    ] {
        std::fs::write(old.join(file), text).unwrap();
    }
    let outcomes = run_all(&[FAILING_WRITER], &out, false, |_| {});
    assert!(outcomes[0].result.is_err());
    assert_eq!(names(&out), ["failing-writer"]);
    assert_eq!(names(&old), ["a.csv", "b.csv", "summary.json"]);
    assert_eq!(std::fs::read_to_string(old.join("a.csv")).unwrap(), "old a");
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn study_that_ends_replaces_old_results_whole() {
    let out = scratch("replace");
    let old = out.join("passing");
    std::fs::create_dir_all(&old).unwrap();
    std::fs::write(old.join("a.csv"), "old a").unwrap();
    std::fs::write(old.join("from_an_older_version.csv"), "old").unwrap();
    let outcomes = run_all(&[PASSING], &out, false, |_| {});
    assert!(outcomes[0].result.is_ok());
    assert_eq!(names(&out), ["passing"]);
    assert_eq!(names(&old), ["a.csv", "report.md", "summary.json"]);
    assert_eq!(std::fs::read_to_string(old.join("a.csv")).unwrap(), "new a");
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn unknown_study_is_refused_before_anything_runs() {
    let err = select("katsuki").unwrap_err();
    assert!(err.to_string().contains("katsuki1990, yamada2000"), "{err}");
    assert_eq!(Exit::of_error(&err), Exit::BadInput);
    assert_eq!(select("all").unwrap().len(), STUDIES.len());
}
