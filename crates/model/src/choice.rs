//! A deck setting a case chooses: a name from a fixed set (`[calculix] contact`, `[kratos]
//! element`, …) or a number within its allowed range. The one lookup every `[deck]` axis uses,
//! and the allowed set its error lists, whatever the axis.
//!
//! ```
//! use spherecontact_model::choice::{self, Choice};
//! use spherecontact_model::kratos_settings::Formulation;
//!
//! assert_eq!(choice::by_name::<Formulation>("penalty"), Some(Formulation::Penalty));
//! assert_eq!(choice::allowed::<Formulation>(), "alm-frictional, alm-frictionless, penalty");
//! assert_eq!(choice::within(1e9, [1.0, 1e6]), None);
//! ```

/// A value chosen by its name from a fixed set.
pub trait Choice: Copy + 'static {
    /// Every value, in the order error messages list them.
    fn all() -> &'static [Self];
    /// The name in case files and metadata.
    fn name(self) -> &'static str;
}

/// The value called `name`, if the set has one.
pub fn by_name<T: Choice>(name: &str) -> Option<T> {
    T::all().iter().copied().find(|value| value.name() == name)
}

/// The allowed names, comma-separated (what a bad value's error lists).
pub fn allowed<T: Choice>() -> String {
    T::all()
        .iter()
        .map(|value| value.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// `value` if it lies within `range`, ends included (NaN never does).
pub fn within(value: f64, range: [f64; 2]) -> Option<f64> {
    (range[0]..=range[1]).contains(&value).then_some(value)
}

/// Makes each listed type a [`Choice`] by its own `ALL` and `name`: the enums keep their names
/// where they are defined, and the lookup lives here once.
macro_rules! choices {
    ($($choice:ty),+) => {$(
        impl $crate::choice::Choice for $choice {
            fn all() -> &'static [Self] {
                &Self::ALL
            }

            fn name(self) -> &'static str {
                <$choice>::name(self)
            }
        }
    )+};
}

pub(crate) use choices;
