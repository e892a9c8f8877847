//! How checks and values are shown to a reader: one console line each, and
//! the Markdown table of a report. Both print a check's rule in words with
//! the value it compares with, and put a paper value the rule does not test
//! apart, marked as not tested, so that it is never read as a reproduction.

use std::fmt::Write;

use super::rule::{number, Rule};
use super::summary::{Check, Reported};

/// One console line for a check: verdict, id, computed value, rule (with
/// its reference) and, apart, a paper value the rule does not test.
pub fn check_line(c: &Check) -> String {
    let mut line = format!(
        "[{}] {:<34} computed {:>13.6e}  rule: {}",
        if c.passed { "pass" } else { "FAIL" },
        c.id,
        c.computed,
        c.rule.words()
    );
    if let Some(met) = met_alternative(c) {
        let _ = write!(line, "; met: {met}");
    }
    if let Some(p) = c.untested_paper() {
        let _ = write!(line, "  | paper {} (not tested)", number(p));
    }
    line
}

/// One console line for a reported value: id, computed value and the
/// paper's value, if any (values are never judged).
pub fn value_line(v: &Reported) -> String {
    let paper = v.paper.map_or_else(|| "-".into(), number);
    format!(
        "[value] {:<33} computed {:>13.6e}  paper {paper} (reported, no rule)",
        v.id, v.computed
    )
}

/// For a rule with alternatives (` or `), which one the computed value met.
fn met_alternative(c: &Check) -> Option<String> {
    if !matches!(c.rule, Rule::AnyOf(_)) {
        return None;
    }
    Some(match c.rule.reference_for(c.computed) {
        Some(r) if c.passed => r.words(),
        _ => "none".into(),
    })
}

/// The Markdown table of `checks`: computed value, the rule with its
/// reference, verdict, and a paper value the rule does not test in a
/// column of its own.
pub fn checks_table(checks: &[Check]) -> String {
    let mut table = String::from(
        "| id | computed | passes when | passed | paper, not tested |\n|---|---|---|---|---|\n",
    );
    for c in checks {
        let unit = if c.unit == "-" {
            String::new()
        } else {
            format!(" {}", c.unit)
        };
        let mut rule = c.rule.words();
        if let Some(met) = met_alternative(c) {
            let _ = write!(rule, "; met: {met}");
        }
        let _ = writeln!(
            table,
            "| `{}` | {}{unit} | {rule} | {} | {} |",
            c.id,
            number(c.computed),
            if c.passed { "yes" } else { "**no**" },
            c.untested_paper().map_or_else(|| "–".into(), number),
        );
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::Reference;

    /// `slope.fs.elastic.static` of the HPM study: its rule is Fs > 1, and
    /// the paper's 1.764 is of another slope.
    fn fs_above_one() -> Check {
        Check::new(
            "slope.fs.elastic.static",
            "elastic HPM, static",
            "-",
            1.276,
            &Rule::Above(Reference::number(1.0)),
        )
        .beside_paper(1.764)
    }

    #[test]
    fn check_rule_not_comparing_paper_prints_no_paper_tol() {
        let line = check_line(&fs_above_one());
        assert!(line.contains("rule: above 1"), "{line}");
        assert!(line.contains("paper 1.764 (not tested)"), "{line}");
        assert!(!line.contains("tol"), "{line}");
        let table = checks_table(&[fs_above_one()]);
        assert!(
            table.contains("| `slope.fs.elastic.static` | 1.276 | above 1 | yes | 1.764 |"),
            "{table}"
        );
    }

    #[test]
    fn check_met_by_a_formula_not_the_misprinted_paper_says_so() {
        let rule = Rule::AnyOf(vec![
            Rule::near(Reference::paper(8.07), 0.01),
            Rule::near(Reference::named("eq. (38)", 16.4853), 1e-3),
        ]);
        let check = Check::new("table3.k4.n2", "LP", "C_p", 16.4853, &rule);
        let line = check_line(&check);
        assert!(
            line.contains("within 0.01 of the paper's 8.07 or within 0.001 of eq. (38) = 16.4853"),
            "{line}"
        );
        assert!(line.contains("met: eq. (38) = 16.4853"), "{line}");
        assert!(!line.contains("(not tested)"), "{line}");
    }
}
