//! Contact detection at the start of a step: for every candidate pair of
//! bodies (the broad phase, boxes grown by the search distance `d₀`), the
//! pair query of its shapes gives the contacts of the step and their fixed
//! geometry ([`crate::query::variation`]).
//!
//! | pair | contacts |
//! |---|---|
//! | polygon – polygon | every vertex of each against the other's edges it meets ([`entrance_edges`]: DDA's rule — the previous step's edge, else the shallowest — with the entrance line at corners, none from behind, both edges of a reflex corner) |
//! | polygon – wall | every polygon vertex against the wall (up to [`crate::query::variation::EDGE_END_TOLERANCE`] past its ends) |
//! | circle/ellipse – polygon | each polygon edge the smooth body faces, and each convex corner beyond the edges' ends |
//! | circle/ellipse – wall | the wall |
//! | circle/ellipse – circle/ellipse | one, along the normal of the signed distance (its search starts from the previous step's normal) |
//! | wall – wall | none |
//!
//! A wall's ends do not act as corners against polygons within a step.

use rustc_hash::FxHashMap;

use crate::query::variation::{
    entrance_edges, smooth_polygon_contacts, wall_edge, PairContact, PolygonCorner,
    SmoothEdgeContact, SmoothSide, SmoothSmoothContact, VariationError, VertexEdgeContact,
};
use crate::query::{ContactFeatures, Feature};

use super::body::{Body, BodyGeometry};

/// The name of a contact across steps: body A, its feature, body B, its
/// feature.
pub type ContactKey = (usize, Feature, usize, Feature);

/// One contact of a step: the bodies, the features that touch, and the
/// geometry fixed for the step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepContact {
    /// Body A (the vertex or smooth side).
    pub a: usize,
    /// Body B (the edge side, or the second smooth body).
    pub b: usize,
    /// The features of A and B.
    pub features: ContactFeatures,
    /// Geometry fixed for the step.
    pub geometry: PairContact,
}

impl StepContact {
    /// The contact's name across steps.
    pub fn key(&self) -> ContactKey {
        (self.a, self.features.a, self.b, self.features.b)
    }
}

/// What the previous step leaves to detection: the edge each vertex
/// touched, and the normal angle of each smooth pair.
#[derive(Debug, Clone, Default)]
pub struct Previous {
    /// `(vertex body, vertex, edge body) → edge`.
    pub edges: FxHashMap<(usize, usize, usize), usize>,
    /// Normal angle (rad, from A to B) of each smooth–smooth contact.
    pub angles: FxHashMap<ContactKey, f64>,
}

fn smooth_side(geometry: &BodyGeometry) -> Option<SmoothSide> {
    match geometry {
        BodyGeometry::Ellipse(e) => Some(SmoothSide::ellipse(e)),
        _ => None,
    }
}

/// The contacts of the candidate `pairs` at the start of a step, in a
/// deterministic order (pairs in order; within a pair as the table of the
/// module docs).
///
/// # Errors
/// [`VariationError::NormalNotFound`] when the normal search of a smooth
/// pair (two ellipses or circles, or one and a polygon's vertex) does not
/// settle, [`VariationError::NotAMaximum`] when the normal found is not a
/// strict maximiser of the separation (e.g. two concentric circles).
pub fn detect<const N: usize>(
    bodies: &[Body<N>],
    pairs: &[(usize, usize)],
    search: f64,
    previous: &Previous,
) -> Result<Vec<StepContact>, VariationError> {
    let mut out = Vec::new();
    for &(i, j) in pairs {
        let (gi, gj) = (bodies[i].geometry(), bodies[j].geometry());
        match (gi, gj) {
            (BodyGeometry::Polygon(_), BodyGeometry::Polygon(_)) => {
                for (a, b) in [(i, j), (j, i)] {
                    vertices_on_polygon(bodies, a, b, search, previous, &mut out);
                }
            }
            (BodyGeometry::Polygon(_), BodyGeometry::Wall(_)) => {
                vertices_on_wall(bodies, i, j, search, &mut out)
            }
            (BodyGeometry::Wall(_), BodyGeometry::Polygon(_)) => {
                vertices_on_wall(bodies, j, i, search, &mut out)
            }
            (BodyGeometry::Ellipse(_), BodyGeometry::Polygon(_)) => {
                smooth_on_polygon(bodies, i, j, search, &mut out)?
            }
            (BodyGeometry::Polygon(_), BodyGeometry::Ellipse(_)) => {
                smooth_on_polygon(bodies, j, i, search, &mut out)?
            }
            (BodyGeometry::Ellipse(_), BodyGeometry::Wall(_)) => {
                smooth_on_wall(bodies, i, j, search, &mut out)
            }
            (BodyGeometry::Wall(_), BodyGeometry::Ellipse(_)) => {
                smooth_on_wall(bodies, j, i, search, &mut out)
            }
            (BodyGeometry::Ellipse(ea), BodyGeometry::Ellipse(eb)) => {
                let key = (i, Feature::Whole, j, Feature::Whole);
                let start = previous.angles.get(&key).copied();
                let (sa, sb) = (SmoothSide::ellipse(ea), SmoothSide::ellipse(eb));
                if let Some(c) = SmoothSmoothContact::detect(&sa, &sb, search, start)? {
                    out.push(StepContact {
                        a: i,
                        b: j,
                        features: ContactFeatures::WHOLE,
                        geometry: PairContact::SmoothSmooth(c),
                    });
                }
            }
            (BodyGeometry::Wall(_), BodyGeometry::Wall(_)) => {}
        }
    }
    Ok(out)
}

/// Every vertex of polygon `a` against the edges of polygon `b`.
fn vertices_on_polygon<const N: usize>(
    bodies: &[Body<N>],
    a: usize,
    b: usize,
    search: f64,
    previous: &Previous,
    out: &mut Vec<StepContact>,
) {
    let (Some(pa), Some(pb)) = (bodies[a].polygon(), bodies[b].polygon()) else {
        return;
    };
    for v in 0..pa.vertex_count() {
        let prev = previous.edges.get(&(a, v, b)).copied();
        let corner = PolygonCorner::of(pa, v);
        for (edge, c) in entrance_edges(&corner, pa.centroid(), pb, search, prev) {
            out.push(StepContact {
                a,
                b,
                features: ContactFeatures {
                    a: Feature::Vertex(v),
                    b: Feature::Edge(edge),
                },
                geometry: PairContact::VertexEdge(c),
            });
        }
    }
}

/// Every vertex of polygon `a` against wall `w`.
fn vertices_on_wall<const N: usize>(
    bodies: &[Body<N>],
    a: usize,
    w: usize,
    search: f64,
    out: &mut Vec<StepContact>,
) {
    let (Some(pa), BodyGeometry::Wall(segment)) = (bodies[a].polygon(), bodies[w].geometry())
    else {
        return;
    };
    let edge = wall_edge(segment);
    let reference = bodies[w].centroid();
    for v in 0..pa.vertex_count() {
        if let Some(c) =
            VertexEdgeContact::detect(pa.vertex(v), pa.centroid(), edge, reference, search)
        {
            out.push(StepContact {
                a,
                b: w,
                features: ContactFeatures {
                    a: Feature::Vertex(v),
                    b: Feature::Edge(0),
                },
                geometry: PairContact::VertexEdge(c),
            });
        }
    }
}

/// The smooth body `s` against the edges and convex corners of polygon `p`.
fn smooth_on_polygon<const N: usize>(
    bodies: &[Body<N>],
    s: usize,
    p: usize,
    search: f64,
    out: &mut Vec<StepContact>,
) -> Result<(), VariationError> {
    let (Some(side), Some(polygon)) = (smooth_side(bodies[s].geometry()), bodies[p].polygon())
    else {
        return Ok(());
    };
    for (k, contact) in smooth_polygon_contacts(&side, polygon, search)? {
        let b = match contact {
            PairContact::SmoothSmooth(_) => Feature::Vertex(k),
            _ => Feature::Edge(k),
        };
        out.push(StepContact {
            a: s,
            b: p,
            features: ContactFeatures {
                a: Feature::Whole,
                b,
            },
            geometry: contact,
        });
    }
    Ok(())
}

/// The smooth body `s` against wall `w`.
fn smooth_on_wall<const N: usize>(
    bodies: &[Body<N>],
    s: usize,
    w: usize,
    search: f64,
    out: &mut Vec<StepContact>,
) {
    let (Some(side), BodyGeometry::Wall(segment)) =
        (smooth_side(bodies[s].geometry()), bodies[w].geometry())
    else {
        return;
    };
    let reference = bodies[w].centroid();
    if let Some(c) = SmoothEdgeContact::detect(&side, wall_edge(segment), reference, search) {
        out.push(StepContact {
            a: s,
            b: w,
            features: ContactFeatures {
                a: Feature::Whole,
                b: Feature::Edge(0),
            },
            geometry: PairContact::SmoothEdge(c),
        });
    }
}
