//! The pass rule of a check: what the computed value is compared with, and
//! how, in one place, so that the verdict, the words printed beside it and
//! the reference shown are derived from the same rule.

/// A value a rule compares the computed value with, and what it is.
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    /// The number.
    pub value: f64,
    /// What the number is (`eq. (38)`, `exact`), or empty for a bare bound
    /// such as 1 for a ratio or 0.005 for an error.
    pub name: String,
    /// Whether the number is the paper's.
    pub from_paper: bool,
}

impl Reference {
    /// A bare number: 1 for a ratio, 0 for a residual, a bound on an error.
    pub fn number(value: f64) -> Self {
        Self {
            value,
            name: String::new(),
            from_paper: false,
        }
    }

    /// A value printed in the paper.
    pub fn paper(value: f64) -> Self {
        Self {
            value,
            name: "the paper's".into(),
            from_paper: true,
        }
    }

    /// A value with a name: a closed form (`eq. (38)`), an exact solution,
    /// a second method.
    pub fn named(name: impl Into<String>, value: f64) -> Self {
        Self {
            value,
            name: name.into(),
            from_paper: false,
        }
    }

    /// The reference in words: `1`, `the paper's 1.764`, `eq. (38) = 16.49`.
    pub fn words(&self) -> String {
        if self.name.is_empty() {
            number(self.value)
        } else if self.from_paper {
            format!("{} {}", self.name, number(self.value))
        } else {
            format!("{} = {}", self.name, number(self.value))
        }
    }
}

/// When a check passes, as a comparison of the computed value with a
/// [`Reference`], or as a condition the study judged on other numbers.
#[derive(Debug, Clone, PartialEq)]
pub enum Rule {
    /// `|computed − reference| ≤ tolerance`.
    Near {
        /// The value compared with.
        reference: Reference,
        /// Largest accepted difference.
        tolerance: f64,
    },
    /// `computed ≤ reference + margin`: above the reference by at most the
    /// margin (an overshoot), any distance below.
    AtMostAbove {
        /// The value compared with.
        reference: Reference,
        /// Largest accepted excess.
        margin: f64,
    },
    /// `computed ≤ reference`.
    AtMost(Reference),
    /// `computed < reference`.
    Below(Reference),
    /// `computed ≥ reference`.
    AtLeast(Reference),
    /// `computed > reference`.
    Above(Reference),
    /// Any of the alternatives holds (a table entry or a closed form).
    AnyOf(Vec<Rule>),
    /// A condition on other numbers than the computed one (a solve that
    /// converged, two methods that agree on a verdict), judged by the study
    /// and stated in words.
    Holds {
        /// The condition, in words.
        condition: String,
        /// Whether it holds.
        holds: bool,
    },
}

impl Rule {
    /// `|computed − reference| ≤ tolerance`.
    pub fn near(reference: Reference, tolerance: f64) -> Self {
        Rule::Near {
            reference,
            tolerance,
        }
    }

    /// A condition judged by the study, in words.
    pub fn holds(condition: impl Into<String>, holds: bool) -> Self {
        Rule::Holds {
            condition: condition.into(),
            holds,
        }
    }

    /// Whether `computed` passes (NaN never passes a comparison).
    pub fn passes(&self, computed: f64) -> bool {
        match self {
            Rule::Near {
                reference,
                tolerance,
            } => (computed - reference.value).abs() <= *tolerance,
            Rule::AtMostAbove { reference, margin } => computed <= reference.value + margin,
            Rule::AtMost(r) => computed <= r.value,
            Rule::Below(r) => computed < r.value,
            Rule::AtLeast(r) => computed >= r.value,
            Rule::Above(r) => computed > r.value,
            Rule::AnyOf(rules) => rules.iter().any(|r| r.passes(computed)),
            Rule::Holds { holds, .. } => *holds,
        }
    }

    /// The rule in words, references included: `within 0.005 of 1`,
    /// `above 1`, `within 0.01 of the paper's 8.07 or within 1.6e-5 of
    /// eq. (38) = 16.49`.
    pub fn words(&self) -> String {
        match self {
            Rule::Near {
                reference,
                tolerance,
            } => format!("within {} of {}", number(*tolerance), reference.words()),
            Rule::AtMostAbove { reference, margin } => {
                format!("at most {} above {}", number(*margin), reference.words())
            }
            Rule::AtMost(r) => format!("at most {}", r.words()),
            Rule::Below(r) => format!("below {}", r.words()),
            Rule::AtLeast(r) => format!("at least {}", r.words()),
            Rule::Above(r) => format!("above {}", r.words()),
            Rule::AnyOf(rules) => rules
                .iter()
                .map(Rule::words)
                .collect::<Vec<_>>()
                .join(" or "),
            Rule::Holds { condition, .. } => condition.clone(),
        }
    }

    /// Every reference the rule compares with.
    pub fn references(&self) -> Vec<&Reference> {
        match self {
            Rule::Near { reference, .. } | Rule::AtMostAbove { reference, .. } => vec![reference],
            Rule::AtMost(r) | Rule::Below(r) | Rule::AtLeast(r) | Rule::Above(r) => vec![r],
            Rule::AnyOf(rules) => rules.iter().flat_map(Rule::references).collect(),
            Rule::Holds { .. } => Vec::new(),
        }
    }

    /// The reference `computed` is judged against: for alternatives, that
    /// of the first one met (else the first); `None` for a condition.
    pub fn reference_for(&self, computed: f64) -> Option<&Reference> {
        match self {
            Rule::AnyOf(rules) => rules
                .iter()
                .find(|r| r.passes(computed))
                .or(rules.first())
                .and_then(|r| r.reference_for(computed)),
            other => other.references().into_iter().next(),
        }
    }

    /// The paper's value the rule compares with, if it compares with one.
    pub fn paper_value(&self) -> Option<f64> {
        self.references()
            .into_iter()
            .find(|r| r.from_paper)
            .map(|r| r.value)
    }

    /// The accepted difference of a [`Rule::Near`] or excess of a
    /// [`Rule::AtMostAbove`] (of the first alternative); 0 for a bound or a
    /// condition, which have none.
    pub fn tolerance(&self) -> f64 {
        match self {
            Rule::Near { tolerance, .. } => *tolerance,
            Rule::AtMostAbove { margin, .. } => *margin,
            Rule::AnyOf(rules) => rules.first().map_or(0.0, Rule::tolerance),
            _ => 0.0,
        }
    }
}

/// A number in a rule's words: integers as they are, moderate magnitudes
/// to six significant digits, the rest in scientific notation (trailing
/// zeros dropped).
pub fn number(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == v.trunc() && v.abs() < 1e6 {
        return format!("{v}");
    }
    let magnitude = v.abs();
    if (1e-3..1e5).contains(&magnitude) {
        let decimals = (5 - magnitude.log10().floor() as i32).max(0) as usize;
        let text = format!("{v:.decimals$}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        let text = format!("{v:.3e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        format!("{mantissa}e{exponent}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_exact_where_they_can_be() {
        assert_eq!(number(1.0), "1");
        assert_eq!(number(0.005), "0.005");
        assert_eq!(number(1.764), "1.764");
        assert_eq!(number(8.0 + 6.0 * std::f64::consts::SQRT_2), "16.4853");
        assert_eq!(number(1e-6), "1e-6");
        assert_eq!(number(1.6485281e-5), "1.649e-5");
        assert_eq!(number(f64::NAN), "NaN");
    }

    #[test]
    fn alternatives_report_the_one_met() {
        let rule = Rule::AnyOf(vec![
            Rule::near(Reference::paper(8.07), 0.01),
            Rule::near(Reference::named("eq. (38)", 16.4853), 1e-3),
        ]);
        assert!(rule.passes(16.4853));
        assert_eq!(rule.reference_for(16.4853).unwrap().name, "eq. (38)");
        assert_eq!(rule.reference_for(3.0).unwrap().value, 8.07);
        assert_eq!(rule.paper_value(), Some(8.07));
    }

    #[test]
    fn nan_fails_every_comparison() {
        for rule in [
            Rule::near(Reference::number(1.0), 0.1),
            Rule::AtMostAbove {
                reference: Reference::number(1.0),
                margin: 0.1,
            },
            Rule::AtMost(Reference::number(1.0)),
            Rule::Below(Reference::number(1.0)),
            Rule::AtLeast(Reference::number(1.0)),
            Rule::Above(Reference::number(1.0)),
        ] {
            assert!(!rule.passes(f64::NAN), "{}", rule.words());
        }
    }
}
