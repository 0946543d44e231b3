//! Validation of what makes a case's scene: its name, the bodies, the loading path, the derived
//! Hertz quantities, the focus and the positions with surface fields.

use toml::Spanned;

use super::error::ShortValue;
use super::raw::{RawBody, RawCase, RawPath};
use crate::{CaseError, Validator};
use spherecontact_model::hertz::Hertz;
use spherecontact_model::limits::{self, MAX_FIELD_POSITIONS, MAX_INCREMENTS};
use spherecontact_model::number::Short;
use spherecontact_model::pair::{Body, ContactPair, Material};
use spherecontact_model::path::{LoadingPath, Position};
use spherecontact_model::scene::FieldPositions;

impl Validator<'_> {
    /// The case's name, or its file's stem: a plain name either way (it names output folders).
    pub(super) fn name(&self, raw: Option<&Spanned<String>>) -> Result<String, CaseError> {
        let allowed = format!(
            "allowed: 1 to {} of {}",
            limits::MAX_NAME_CHARS,
            limits::NAME_CHARACTERS
        );
        match raw {
            Some(name) if limits::is_plain_name(name.get_ref()) => Ok(name.get_ref().clone()),
            Some(name) => Err(self.error(
                name,
                "name",
                format!("`{}` is not a plain name ({allowed})", name.get_ref()),
            )),
            None => {
                let stem = self
                    .file
                    .file_stem()
                    .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
                if limits::is_plain_name(&stem) {
                    Ok(stem)
                } else {
                    Err(CaseError::new(
                        self.file,
                        None,
                        "name",
                        format!("missing, and the file stem `{stem}` is not a plain name ({allowed})"),
                    ))
                }
            }
        }
    }

    pub(super) fn body(&self, raw: &RawBody, field: &str) -> Result<Body, CaseError> {
        let [r_min, r_max] = limits::RADIUS_RANGE;
        let radius = self.number(
            &raw.radius,
            &format!("{field}.radius"),
            |r| (r_min..=r_max).contains(&r) || r == f64::INFINITY,
            "1e-9 ≤ R ≤ 1e3 in m, or inf for a flat",
        )?;
        let [e_min, e_max] = limits::YOUNG_RANGE;
        let young = self.number(
            &raw.young,
            &format!("{field}.young"),
            |e| (e_min..=e_max).contains(&e),
            "1e3 ≤ E ≤ 1e13 Pa",
        )?;
        let poisson = self.number(
            &raw.poisson,
            &format!("{field}.poisson"),
            |v| v > -1.0 && v < 0.5,
            "−1 < ν < 0.5",
        )?;
        Ok(Body {
            radius,
            material: Material { young, poisson },
        })
    }

    /// The loading path, its values within the smaller radius of `pair`.
    pub(super) fn path(&self, raw: &RawPath, pair: &ContactPair) -> Result<LoadingPath, CaseError> {
        let unit = raw.unit.get_ref().as_str();
        let scale = match unit {
            "m" => 1.0,
            "mm" => 1e-3,
            // The micro sign (U+00B5) and the Greek mu (U+03BC) look alike: both are accepted.
            "um" | "µm" | "μm" => 1e-6,
            other => {
                return Err(self.error(
                    &raw.unit,
                    "path.unit",
                    format!("unknown unit `{other}` (allowed: m, mm, um, µm, μm)"),
                ))
            }
        };
        let r_min = pair.body1.radius.min(pair.body2.radius);
        let values = |list: &Spanned<Vec<Spanned<f64>>>, field: &str, symbol: &str| {
            list.get_ref()
                .iter()
                .enumerate()
                .map(|(i, v)| {
                    let si = *v.get_ref() * scale;
                    if si.is_finite() && si.abs() <= r_min {
                        return Ok(si);
                    }
                    Err(self.error(
                        v,
                        format!("path.{field}[{i}]"),
                        format!(
                            "{} {unit} is out of range (allowed: a finite |{symbol}| ≤ {} m, the \
                             smaller body radius)",
                            Short(*v.get_ref()),
                            Short(r_min)
                        ),
                    ))
                })
                .collect::<Result<Vec<f64>, CaseError>>()
        };
        let delta_n = values(&raw.delta_n, "delta_n", "δn")?;
        let delta_t = values(&raw.delta_t, "delta_t", "δt")?;
        if delta_n.is_empty() {
            return Err(self.error(
                &raw.delta_n,
                "path.delta_n",
                "no positions (allowed: at least one)",
            ));
        }
        if delta_t.len() != delta_n.len() {
            return Err(self.error(
                &raw.delta_t,
                "path.delta_t",
                format!(
                    "{} values for {} positions of delta_n (allowed: one per position)",
                    delta_t.len(),
                    delta_n.len()
                ),
            ));
        }
        let substeps = self.substeps(&raw.substeps, delta_n.len() - 1)?;
        let positions = delta_n
            .into_iter()
            .zip(delta_t)
            .map(|(delta_n, delta_t)| Position { delta_n, delta_t })
            .collect();
        Ok(LoadingPath::try_new(positions, substeps).expect("positions and substeps validated above"))
    }

    fn substeps(&self, raw: &Spanned<toml::Value>, segments: usize) -> Result<Vec<usize>, CaseError> {
        let count = |v: &toml::Value| match v {
            toml::Value::Integer(n) if *n >= 1 && *n <= MAX_INCREMENTS as i64 => Ok(*n as usize),
            other => Err(self.error(
                raw,
                "path.substeps",
                format!(
                    "{} is not a whole number from 1 to {MAX_INCREMENTS}",
                    ShortValue(other)
                ),
            )),
        };
        let counts: Vec<usize> = match raw.get_ref() {
            toml::Value::Array(list) if list.len() == segments => {
                list.iter().map(count).collect::<Result<_, _>>()?
            }
            toml::Value::Array(list) => {
                return Err(self.error(
                    raw,
                    "path.substeps",
                    format!(
                        "{} counts for {segments} segments (allowed: one count, or one per segment)",
                        list.len()
                    ),
                ))
            }
            single => vec![count(single)?; segments],
        };
        let total: usize = counts.iter().sum();
        if total > MAX_INCREMENTS {
            return Err(self.error(
                raw,
                "path.substeps",
                format!("{total} increments in all (allowed: at most {MAX_INCREMENTS})"),
            ));
        }
        Ok(counts)
    }

    /// The derived quantities every solver computes with: E*, R*, G*, and the Hertz scales at the
    /// largest approach, each a normal positive number (no zero, subnormal or overflow).
    pub(super) fn derived(
        &self,
        raw: &RawCase,
        pair: &ContactPair,
        friction: f64,
        path: &LoadingPath,
    ) -> Result<(), CaseError> {
        let fine = |v: f64| v.is_normal() && v > 0.0;
        let (e_star, g_star) = (pair.effective_modulus(), pair.mindlin_shear_modulus());
        for (what, value, unit) in [
            ("effective modulus E*", e_star, "Pa"),
            ("effective radius R*", pair.effective_radius(), "m"),
            ("Mindlin's shear modulus G*", g_star, "Pa"),
        ] {
            if !fine(value) {
                return Err(self.error(
                    &raw.body1.young,
                    "body1",
                    format!(
                        "the {what} of the pair is {} {unit} (allowed: bodies whose E*, R* and G* \
                         are normal positive numbers)",
                        Short(value)
                    ),
                ));
            }
        }
        let delta = path.max_approach();
        if delta <= 0.0 {
            return Ok(()); // the gap never closes: no Hertz scale to judge
        }
        let hertz = Hertz::of(pair);
        let (c, force) = (hertz.contact_radius(delta), hertz.force(delta));
        let mut scales = vec![
            ("contact_radius c", c, "m"),
            ("normal_force P", force, "N"),
            ("peak_pressure p0", hertz.peak_pressure(delta), "Pa"),
            ("normal stiffness 2E*c", 2.0 * e_star * c, "N/m"),
            ("tangential stiffness 8G*c", 8.0 * g_star * c, "N/m"),
        ];
        if friction > 0.0 {
            scales.push(("sliding force μP", friction * force, "N"));
        }
        let Some((what, value, unit)) = scales.into_iter().find(|s| !fine(s.1)) else {
            return Ok(());
        };
        let k = path
            .positions()
            .iter()
            .position(|p| p.delta_n == delta)
            .unwrap_or(0);
        Err(self.error(
            &raw.path.delta_n.get_ref()[k],
            format!("path.delta_n[{k}]"),
            format!(
                "at the largest approach δn = {} m the Hertz {what} is {} {unit} (allowed: a \
                 largest approach whose Hertz scales are normal positive numbers, or a path that \
                 never closes the gap)",
                Short(delta),
                Short(value)
            ),
        ))
    }

    pub(super) fn focus(&self, raw: Option<&Spanned<i64>>, path: &LoadingPath) -> Result<usize, CaseError> {
        let positions = path.positions();
        let Some(raw) = raw else {
            // The first position of largest δn.
            let largest = path.max_approach();
            return Ok(positions.iter().position(|p| p.delta_n == largest).unwrap_or(0));
        };
        match usize::try_from(*raw.get_ref()) {
            Ok(k) if k < positions.len() => Ok(k),
            _ => Err(self.error(
                raw,
                "focus",
                format!(
                    "{} is not a path position (allowed: 0 to {})",
                    raw.get_ref(),
                    positions.len() - 1
                ),
            )),
        }
    }

    /// The positions with surface fields: at most [`MAX_FIELD_POSITIONS`], the focus always
    /// among them.
    pub(super) fn fields(
        &self,
        raw: Option<&Spanned<toml::Value>>,
        positions: usize,
        focus: usize,
    ) -> Result<FieldPositions, CaseError> {
        let Some(raw) = raw else {
            return Ok(if positions <= MAX_FIELD_POSITIONS {
                FieldPositions::Every
            } else {
                FieldPositions::listed(vec![focus])
            });
        };
        let bad = |what: String| {
            self.error(
                raw,
                "fields",
                format!(
                    "{what} (allowed: \"every-position\", \"focus\" or a list of positions 0 to {}; \
                     at most {MAX_FIELD_POSITIONS} positions with fields, the focus included)",
                    positions - 1
                ),
            )
        };
        let listed = match raw.get_ref() {
            toml::Value::String(s) if s == "every-position" && positions <= MAX_FIELD_POSITIONS => {
                return Ok(FieldPositions::Every)
            }
            toml::Value::String(s) if s == "every-position" => {
                return Err(bad(format!("\"every-position\" asks for {positions} positions")))
            }
            toml::Value::String(s) if s == "focus" => vec![focus],
            toml::Value::Array(list) => {
                let index = |v: &toml::Value| match v {
                    toml::Value::Integer(k) if *k >= 0 && (*k as usize) < positions => Ok(*k as usize),
                    other => Err(bad(format!("position {} is not on the path", ShortValue(other)))),
                };
                let mut listed = list.iter().map(index).collect::<Result<Vec<_>, _>>()?;
                listed.push(focus);
                listed
            }
            other => return Err(bad(format!("`{}` is not understood", ShortValue(other)))),
        };
        let fields = FieldPositions::listed(listed);
        match &fields {
            FieldPositions::Listed(list) if list.len() > MAX_FIELD_POSITIONS => {
                Err(bad(format!("{} positions with the focus", list.len())))
            }
            _ => Ok(fields),
        }
    }
}
