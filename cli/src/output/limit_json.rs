//! The numbers of a limit analysis as JSON, the same in every output that
//! gives them (`lattice-limit-load`, a scenario's `summary.json`).

use dismech::limit::LimitResult;
use serde_json::{json, Map, Value};

/// The limit load and its two bounds in units of C_p (`p_over_cp`,
/// `kinematic_p_over_cp`, `static_p_over_cp`), the outcome's `status`,
/// the plate's length and the LP's size and solver (`solver`: its name,
/// status, iterations, variables, equality rows and nonzeros), for the
/// caller to add its own keys to.
pub fn limit_summary(result: &LimitResult, plate_length: f64) -> Map<String, Value> {
    let mut map = Map::new();
    map.insert("status".into(), json!(format!("{:?}", result.status)));
    map.insert("p_over_cp".into(), json!(result.load));
    map.insert("kinematic_p_over_cp".into(), json!(result.kinematic_load));
    map.insert("static_p_over_cp".into(), json!(result.static_load));
    map.insert("plate_length".into(), json!(plate_length));
    map.insert(
        "solver".into(),
        json!({
            "name": "clarabel",
            "status": result.solver_status,
            "iterations": result.iterations,
            "variables": result.lp_size.0,
            "equality_rows": result.lp_size.1,
            "nonzeros": result.lp_size.2,
        }),
    );
    map
}
