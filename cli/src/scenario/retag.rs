//! The `kind` key of a slot's table chooses its implementation. serde's
//! internally tagged enums read such a table through a buffer that drops
//! the spans of its values, so an error inside it could name neither the
//! key nor the line. The reader moves the tag out instead — `{ kind =
//! "penalty-coulomb", penalty = 2e9 }` becomes `{ penalty-coulomb = {
//! penalty = 2e9 } }`, serde's external tag — and every value keeps its
//! place in the file.

use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// The tables that carry a `kind` tag: top-level sections, and tables
/// inside the elements of top-level arrays.
pub const TAGGED_SECTIONS: [&str; 8] = [
    "driver",
    "kinematics",
    "boundary",
    "law",
    "integrator",
    "linear_solver",
    "lp_solver",
    "run",
];

/// The arrays of tagged tables, and the tagged tables inside their
/// elements.
pub const TAGGED_ARRAYS: [(&str, &[&str]); 1] = [("bodies", &["motion"])];

/// The arrays of untagged tables, and the tagged tables inside their
/// elements (`[[pair_laws]]`: each entry's `law`).
pub const ARRAYS_OF_TAGGED: [(&str, &[&str]); 1] = [("pair_laws", &["law"])];

/// The variant name given to a table that has no `kind` key, so that
/// serde refuses it with the list of the kinds it knows.
pub const MISSING_KIND: &str = "";

/// Move the `kind` tag of every tagged table of `tree` out, as serde's
/// external tag.
pub fn retag(tree: &mut Spanned<DeTable<'_>>) {
    let root = tree.get_mut();
    for section in TAGGED_SECTIONS {
        if let Some(value) = root.get_mut(section) {
            retag_value(value);
        }
    }
    for (array, inner) in TAGGED_ARRAYS {
        retag_array(root, array, inner, true);
    }
    for (array, inner) in ARRAYS_OF_TAGGED {
        retag_array(root, array, inner, false);
    }
}

/// Retag the tables `inner` of each element of the top-level array
/// `array`, and with `tagged` the element itself.
fn retag_array(root: &mut DeTable<'_>, array: &str, inner: &[&str], tagged: bool) {
    if let Some(value) = root.get_mut(array) {
        if let DeValue::Array(items) = value.get_mut() {
            for item in items.iter_mut() {
                if let DeValue::Table(table) = item.get_mut() {
                    for key in inner {
                        if let Some(v) = table.get_mut(*key) {
                            retag_value(v);
                        }
                    }
                }
                if tagged {
                    retag_value(item);
                }
            }
        }
    }
}

/// `{ kind = K, rest… }` → `{ K = { rest… } }`; a table without a string
/// `kind` gets the tag [`MISSING_KIND`] (a `kind` that is not a string is
/// left in the table, where serde refuses it as an unknown field of its
/// kind's table... at its own place in the file).
fn retag_value(value: &mut Spanned<DeValue<'_>>) {
    let span = value.span();
    let DeValue::Table(table) = value.get_mut() else {
        return;
    };
    let tag = match table.get("kind").map(|k| (k.get_ref(), k.span())) {
        Some((DeValue::String(kind), kind_span)) => {
            let kind = kind.clone();
            table.remove("kind");
            Spanned::new(kind_span, kind)
        }
        Some((_, kind_span)) => Spanned::new(kind_span, MISSING_KIND.into()),
        None => Spanned::new(span.clone(), MISSING_KIND.into()),
    };
    let rest = std::mem::take(table);
    let mut outer = DeTable::new();
    outer.insert(tag, Spanned::new(span.clone(), DeValue::Table(rest)));
    *value = Spanned::new(span, DeValue::Table(outer));
}
