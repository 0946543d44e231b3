//! The claim that the frictional stress is not axisymmetric (the paper's Figure 11): the
//! transverse traction q_y against q_x, its sign pattern over the quadrants, the axisymmetry of
//! |q|, and the comparison of the judged solver with the other map solvers.

use crate::claims::measure::{AXIS_READ, BOXES_PER_RADIUS};
use crate::{
    claims::fields::cusp_sampling, claims::fields::fraction, claims::fields::Evidence, claims::fields::Found,
    claims::fields::Measured, claims::fields::References, claims::fields::Verdict,
    claims::fields::MAGNITUDE_AXISYMMETRY,
};

/// The transverse traction: its size against q_x (on the recovered values, judged; averaged over
/// boxes; at single samples), its sign
/// pattern, the axisymmetry of |q|, and how it compares with the other map solvers.
pub(super) fn claim(e: &Evidence, references: &References, others: &[&Evidence]) -> Found {
    let as_percent = |v: Option<f64>| v.map(|r| format!("{:.2} %", r * 100.0));
    let best = &e.best().measures;
    let peak = best.peak.map_or(0.0, |p| p.value);
    let sign = |v: f64| if v > 0.0 { "+" } else { "−" };
    let q1 = best.quadrants[0];
    let pattern = if best.is_odd_in_x_and_y(0.01) {
        format!(
            "q_y is odd in x and in y: over x > 0, y > 0 its integral is {} ({} over the stick zone, {} over the slip \
             annulus), the opposite in the neighbouring quadrants",
            sign(q1.total),
            sign(q1.stick),
            sign(q1.slip)
        )
    } else {
        "q_y is not odd in x and in y".to_owned()
    };
    let measured = format!(
        "max |q_y| / max |q_x| on the values the contact rule determines (a mesh's hat averages, a grid's panels) = {}; \
         averaged over boxes of side c/{:.0} = {}; at single samples {}; {pattern}; |q| read along x and along y \
         (r ≤ {AXIS_READ} c) differs, relative to its peak, by ≤ {}; q_y adds ≤ {:.2} % of the peak to |q|",
        e.across(|m| as_percent(m.measures.recovered_ratio)),
        BOXES_PER_RADIUS,
        e.across(|m| as_percent(boxed_ratio(m))),
        e.across(|m| as_percent(pointwise_ratio(m))),
        e.across(|m| as_percent(Some(fraction(m.measures.axis_difference, m.measures.peak.map_or(0.0, |p| p.value))))),
        fraction(best.transverse_share, peak) * 100.0
    );
    let Some(r) = recovered(e.best()).filter(|&r| r > 0.0) else {
        return Found::new(
            measured,
            Verdict::NotConfirmed,
            "no transverse traction",
            "max |q_y| / max |q_x| = 0".into(),
        );
    };
    // A mesh's single-sample maximum is a one-node overshoot at the stick edge (fit::recovery):
    // said, not judged on.
    let pointwise = match (e.change(pointwise_ratio), e.change(recovered)) {
        (Some(p), Some(b)) if p > b => format!(
            ". The single-sample maximum, one node at the stick edge, is not converged: it moves by {:.2} % of \
             max|q_x| between the two finest rungs, the recovered ratio by {:.2} %",
            p * 100.0,
            b * 100.0
        ),
        _ => String::new(),
    };
    let beside: String = others.iter().filter_map(|o| compare_transverse(e, o)).collect();
    let resolved = e.change(recovered).is_none_or(|change| change < r);
    // |q| departs from axisymmetry only beyond a tenth of a contour level, beyond what refinement
    // still moves, and beyond what the samples can tell at the cusp of |q| at the stick edge,
    // which a mesh samples differently along x and y (a grid symmetric in x and y alike).
    let magnitude = |m: &Measured| {
        fraction(
            m.measures.axis_difference,
            m.measures.peak.map_or(0.0, |p| p.value),
        )
    };
    let d = magnitude(e.best());
    let cusp = match e.best().measures.axes_alike {
        true => 0.0,
        false => cusp_sampling(references, e.best(), e.best().measures.spacing).unwrap_or(0.0),
    };
    let change = e.change(|m| Some(magnitude(m))).unwrap_or(0.0);
    let others_read: Vec<String> = others
        .iter()
        .map(|o| format!("{} {:.2} %", o.solver, magnitude(o.best()) * 100.0))
        .collect();
    let others_read = match others_read.is_empty() {
        true => String::new(),
        false => format!(" (beside it: {})", others_read.join(", ")),
    };
    let (verdict, finding) = match (resolved, d <= MAGNITUDE_AXISYMMETRY, d <= change.max(cusp)) {
        (false, _, _) => (
            Verdict::Partly,
            "q_y is not resolved: it changes under refinement by more than its size".to_owned(),
        ),
        (true, true, _) => (
            Verdict::Partly,
            format!(
                "the traction's direction is not axisymmetric (q_y up to {:.1} % of q_x), its magnitude |q| is, to \
                 {:.2} % of its peak, within a tenth of a contour level{others_read}",
                r * 100.0,
                d * 100.0
            ),
        ),
        (true, false, true) => (
            Verdict::Partly,
            format!(
                "the traction's direction is not axisymmetric (q_y up to {:.1} % of q_x); whether its magnitude |q| \
                 is cannot be told from these samples: |q| read along x and y differs by {:.2} % of its peak, within \
                 its change under refinement ({:.2} %) or what samples h apart can miss of the cusp of |q| at the \
                 stick edge (μp0 √(c_s h)/c, {:.1} % of the peak){others_read}",
                r * 100.0,
                d * 100.0,
                change * 100.0,
                cusp * 100.0
            ),
        ),
        (true, false, false) => (
            Verdict::Confirmed,
            format!(
                "both the direction (q_y) and the magnitude |q| depart from axisymmetry: |q| along x and y differs by \
                 {:.2} % of its peak, beyond its change under refinement and the cusp's sampling{others_read}",
                d * 100.0
            ),
        ),
    };
    let decides = format!(
        "max |q_y| / max |q_x| = {:.1} %; |q| along x against y {:.2} % against ≤ {:.2} % of its peak",
        r * 100.0,
        d * 100.0,
        (MAGNITUDE_AXISYMMETRY.max(change).max(cusp)) * 100.0
    );
    Found::new(
        measured,
        verdict,
        format!("{finding}{pointwise}{beside}"),
        decides,
    )
}

/// max|q_y| / max|q_x| over the boxes, if there is a q_x.
fn boxed_ratio(m: &Measured) -> Option<f64> {
    let [qx, qy] = m.measures.box_max;
    (qx > 0.0).then(|| qy / qx)
}

/// The judged ratio: max|q_y| / max|q_x| on the recovered values.
fn recovered(m: &Measured) -> Option<f64> {
    m.measures.recovered_ratio
}

/// max|q_y| / max|q_x| over the samples, if there is a q_x.
fn pointwise_ratio(m: &Measured) -> Option<f64> {
    (m.measures.qx_max > 0.0).then(|| m.measures.qy_max / m.measures.qx_max)
}

/// The transverse traction of `e` against another map solver's `o`: the sign pattern over the
/// quadrants, and the recovered ratio's difference against what the two discretisations explain —
/// each one's change between its two finest rungs, an estimate of its remaining error — with the
/// two models' difference in Q at the position beside it (a finite body against half-spaces
/// shears differently, and q_y follows the shear).
fn compare_transverse(e: &Evidence, o: &Evidence) -> Option<String> {
    let (a, b) = (recovered(e.best())?, recovered(o.best())?);
    let signs = |m: &Measured| m.measures.quadrants.map(|q| q.total > 0.0);
    let pattern = if signs(e.best()) == signs(o.best()) {
        "the same sign pattern"
    } else {
        "a different sign pattern"
    };
    let difference = (a - b).abs();
    let mut text = format!(
        ". Against {}: {pattern}; recovered ratio {:.2} % against {:.2} %, {:.2} % of max|q_x| apart ({:.1} % of {}'s)",
        o.solver,
        a * 100.0,
        b * 100.0,
        difference * 100.0,
        fraction(difference, b) * 100.0,
        o.solver
    );
    match (e.change(recovered), o.change(recovered)) {
        (Some(de), Some(dobj)) => {
            let within = if difference <= de + dobj {
                "within"
            } else {
                "beyond"
            };
            text.push_str(&format!(
                ", {within} what the two discretisations explain: their changes between the two finest rungs, {:.2} % + \
                 {:.2} %",
                de * 100.0,
                dobj * 100.0
            ));
        }
        _ => text.push_str(", without a resolution study to say what the discretisations explain"),
    }
    if let (Some(qe), Some(qo)) = (e.force, o.force.filter(|q| *q != 0.0)) {
        text.push_str(&format!(
            "; the two models' Q at this position differ by {:+.2} % ({} against {})",
            (qe / qo - 1.0) * 100.0,
            e.solver,
            o.solver
        ));
    }
    Some(text)
}
