//! A validated impact case: two bodies (or a sphere and a rigid flat) with masses, initial
//! velocities and spins, friction, an optional prescribed restitution, a sweep of one initial
//! condition, the solvers to run and the checks to judge. Read and validated by
//! `load_impact` (spherecontact-case) (`crates/case/src/impact_rules.rs`), like every case field.
//!
//! Axes (docs/impact.md): the motion lies in the x–z plane; z is the contact normal, pointing
//! from body 2 into body 1 (body 1 is "above"); x is the tangential direction. A spin ω is about
//! the axis normal to the plane, signed per body so that ω > 0 moves that body's contact point
//! towards +x: the contact point of body k moves tangentially at v_x + R_k ω_k.

use std::path::PathBuf;

use spherecontact_model::pair::{Body, ContactPair, Material};

/// One body of an impact: a sphere with mass, or a rigid flat.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImpactBody {
    /// Radius [m] and material (a rigid flat: R = ∞, E = ∞).
    pub body: Body,
    /// Density [kg/m³]; `None` for a rigid flat (infinite mass).
    pub density: Option<f64>,
    /// Initial velocity of the centre [m/s]: (tangential x, normal z).
    pub velocity: [f64; 2],
    /// Initial spin [rad/s], signed so that ω > 0 moves the contact point towards +x.
    pub spin: f64,
}

impl ImpactBody {
    /// A rigid flat at rest: infinite radius, modulus and mass.
    pub fn rigid_flat() -> Self {
        Self {
            body: Body {
                radius: f64::INFINITY,
                material: Material {
                    young: f64::INFINITY,
                    poisson: 0.0,
                },
            },
            density: None,
            velocity: [0.0, 0.0],
            spin: 0.0,
        }
    }

    /// Mass [kg] (∞ for the flat).
    pub fn mass(&self) -> f64 {
        self.density.map_or(f64::INFINITY, |rho| {
            rho * 4.0 / 3.0 * std::f64::consts::PI * self.body.radius.powi(3)
        })
    }

    /// Moment of inertia about a diameter, 2/5 m R² [kg m²] (∞ for the flat).
    pub fn inertia(&self) -> f64 {
        0.4 * self.mass() * self.body.radius.powi(2)
    }

    /// True for the rigid flat.
    pub fn is_rigid(&self) -> bool {
        self.density.is_none()
    }
}

/// The initial condition a sweep varies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SweepVariable {
    /// Body 1's incident angle from the normal [rad], its speed kept: v = |v|(sin θ, −cos θ).
    IncidentAngle,
    /// Body 1's tangential velocity [m/s], its normal velocity kept.
    TangentialVelocity,
    /// Body 1's spin [rad/s]; body 2's follows by [`Body2Spin`].
    Spin,
    /// The prescribed coefficient of normal restitution.
    Restitution,
}

impl SweepVariable {
    /// The name written in case files and the `sweep` column.
    pub fn name(self) -> &'static str {
        match self {
            Self::IncidentAngle => "incident_angle",
            Self::TangentialVelocity => "tangential_velocity",
            Self::Spin => "spin",
            Self::Restitution => "restitution",
        }
    }

    /// Every variable, for messages.
    pub const ALL: [Self; 4] = [
        Self::IncidentAngle,
        Self::TangentialVelocity,
        Self::Spin,
        Self::Restitution,
    ];
}

/// What body 2's spin does in a spin sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Body2Spin {
    /// Body 2 keeps the spin of the case.
    Kept,
    /// Body 2's contact point moves opposite to body 1's at the same speed: ω2 = −ω1 R1/R2.
    Opposite,
}

/// A sweep of one initial condition (SI values: rad, m/s, rad/s).
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    /// The variable.
    pub variable: SweepVariable,
    /// Its values, SI.
    pub values: Vec<f64>,
    /// Body 2's spin in a spin sweep.
    pub body2_spin: Body2Spin,
}

/// The quantities of an impact's outcome, in the order of the output columns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Quantity {
    /// Duration of the contact [s].
    ContactDuration,
    /// Largest total normal force [N].
    MaxNormalForce,
    /// Largest overlap (approach) [m].
    MaxOverlap,
    /// Normal coefficient of restitution.
    NormalRestitution,
    /// Tangential coefficient of restitution of the contact point.
    TangentialRestitution,
    /// Body 1's spin after the impact [rad/s].
    ReboundAngularVelocity,
    /// Angle of the contact point's rebound velocity from the normal [rad].
    ReboundAngle,
}

impl Quantity {
    /// Every quantity, in column order.
    pub const ALL: [Self; 7] = [
        Self::ContactDuration,
        Self::MaxNormalForce,
        Self::MaxOverlap,
        Self::NormalRestitution,
        Self::TangentialRestitution,
        Self::ReboundAngularVelocity,
        Self::ReboundAngle,
    ];

    /// The column name.
    pub fn name(self) -> &'static str {
        match self {
            Self::ContactDuration => "contact_duration",
            Self::MaxNormalForce => "max_normal_force",
            Self::MaxOverlap => "max_overlap",
            Self::NormalRestitution => "normal_restitution",
            Self::TangentialRestitution => "tangential_restitution",
            Self::ReboundAngularVelocity => "rebound_angular_velocity",
            Self::ReboundAngle => "rebound_angle",
        }
    }

    /// The SI unit, for reports.
    pub fn unit(self) -> &'static str {
        match self {
            Self::ContactDuration => "s",
            Self::MaxNormalForce => "N",
            Self::MaxOverlap => "m",
            Self::NormalRestitution | Self::TangentialRestitution => "-",
            Self::ReboundAngularVelocity => "rad/s",
            Self::ReboundAngle => "rad",
        }
    }

    /// The quantity called `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|q| q.name() == name)
    }

    /// True for the quantities of the normal impact, which Hertz's closed forms give.
    pub fn is_normal(self) -> bool {
        matches!(
            self,
            Self::ContactDuration | Self::MaxNormalForce | Self::MaxOverlap | Self::NormalRestitution
        )
    }
}

/// Which run of a case a check judges.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Variant {
    /// With the case's prescribed restitution (the only run of an elastic case).
    Prescribed,
    /// The elastic variant, e = 1 (run beside the prescribed one when e < 1).
    Elastic,
}

impl Variant {
    /// The name in case files and file names.
    pub fn name(self) -> &'static str {
        match self {
            Self::Prescribed => "prescribed",
            Self::Elastic => "elastic",
        }
    }
}

/// What a check compares with.
#[derive(Clone, Debug, PartialEq)]
pub enum ImpactReference {
    /// Hertz's closed forms of elastic normal impact ([`crate::impact::closed_form`]).
    Hertz,
    /// Another solver of the case, in the same variant.
    Solver(String),
}

/// A check of an impact case.
#[derive(Clone, Debug, PartialEq)]
pub struct ImpactCheck {
    /// The solver judged.
    pub solver: String,
    /// The quantity.
    pub quantity: Quantity,
    /// The run judged.
    pub variant: Variant,
    /// The reference.
    pub reference: ImpactReference,
    /// Relative (`true`) or absolute error.
    pub relative: bool,
    /// The tolerance; `None` when informational.
    pub tolerance: Option<f64>,
    /// Why this tolerance (or why informational).
    pub reason: String,
}

impl ImpactCheck {
    /// The solvers the check needs: its subject, then its reference solver if any.
    pub fn solvers(&self) -> impl Iterator<Item = &String> {
        std::iter::once(&self.solver).chain(match &self.reference {
            ImpactReference::Solver(name) => Some(name),
            ImpactReference::Hertz => None,
        })
    }

    /// The check in words: solver, quantity, variant, reference and measure (a baseline's key,
    /// a JUnit test case's name).
    pub fn key(&self) -> String {
        let reference = match &self.reference {
            ImpactReference::Hertz => "hertz closed form",
            ImpactReference::Solver(name) => name,
        };
        format!(
            "{} {} ({}) vs {reference} ({})",
            self.solver,
            self.quantity.name(),
            self.variant.name(),
            if self.relative { "relative" } else { "absolute" }
        )
    }
}

/// A validated impact case.
#[derive(Clone, Debug)]
pub struct ImpactCase {
    /// The file it was read from.
    pub file: PathBuf,
    /// Its name (a plain name).
    pub name: String,
    /// A one-paragraph description.
    pub description: String,
    /// What kind of work it is (`labels::LABELS` (spherecontact-case)): the file's `labels`, else
    /// [`DEFAULT_LABELS`].
    pub labels: Vec<String>,
    /// Coulomb friction μ.
    pub friction: f64,
    /// The prescribed normal restitution (1: elastic).
    pub restitution: f64,
    /// Body 1, the impacting sphere.
    pub body1: ImpactBody,
    /// Body 2: a sphere or the rigid flat.
    pub body2: ImpactBody,
    /// The sweep; `None`: one impact.
    pub sweep: Option<Sweep>,
    /// The solvers, in the case's order.
    pub solvers: Vec<String>,
    /// Time steps per Hertz contact duration.
    pub steps: usize,
    /// MDR springs on the half-line.
    pub springs: usize,
    /// The checks.
    pub checks: Vec<ImpactCheck>,
    /// The solvers the case defines itself (stored results, programs), in the case's order.
    pub own_solvers: Vec<super::own_solver::OwnSolver>,
}

impl ImpactCase {
    /// The contact pair (for effective properties).
    pub fn pair(&self) -> ContactPair {
        ContactPair {
            body1: self.body1.body,
            body2: self.body2.body,
        }
    }

    /// The solver the case defines itself under `name`, if any.
    pub fn own_solver(&self, name: &str) -> Option<&super::own_solver::OwnSolver> {
        self.own_solvers.iter().find(|s| s.name == name)
    }

    /// Lets the case's command solvers run under `permission` (they are refused until then).
    pub fn permit_commands(&mut self, permission: &spherecontact_system::permission::CommandPermission) {
        for solver in &mut self.own_solvers {
            if let super::own_solver::Source::Command { permission: p, .. } = &mut solver.source {
                *p = permission.clone();
            }
        }
    }

    /// Every solver the case needs: its own list, then those its checks name.
    pub fn required_solvers(&self) -> Vec<String> {
        let mut names = self.solvers.clone();
        for check in &self.checks {
            for name in check.solvers() {
                if !names.contains(name) {
                    names.push(name.clone());
                }
            }
        }
        names
    }

    /// The variants this case runs: the prescribed one, and the elastic one when e < 1.
    pub fn variants(&self) -> Vec<Variant> {
        if self.restitution < 1.0 {
            vec![Variant::Prescribed, Variant::Elastic]
        } else {
            vec![Variant::Prescribed]
        }
    }

    /// The swept variable's name as a sweep table's `sweep` column writes it ("none" without a
    /// sweep).
    pub fn sweep_name(&self) -> &'static str {
        self.sweep.as_ref().map_or("none", |s| s.variable.name())
    }

    /// The initial conditions of every sweep point in `variant`.
    pub fn points_of(&self, variant: Variant) -> Vec<Point> {
        let points = self.points();
        match variant {
            Variant::Prescribed => points,
            Variant::Elastic => points.into_iter().map(Point::elastic).collect(),
        }
    }

    /// The initial conditions of every sweep point: (sweep value, bodies, restitution).
    pub fn points(&self) -> Vec<Point> {
        let Some(sweep) = &self.sweep else {
            return vec![Point {
                value: None,
                body1: self.body1,
                body2: self.body2,
                restitution: self.restitution,
            }];
        };
        sweep
            .values
            .iter()
            .map(|&value| {
                let (mut body1, mut body2, mut restitution) = (self.body1, self.body2, self.restitution);
                match sweep.variable {
                    SweepVariable::IncidentAngle => {
                        let speed = body1.velocity[0].hypot(body1.velocity[1]);
                        body1.velocity = [speed * value.sin(), -speed * value.cos()];
                    }
                    SweepVariable::TangentialVelocity => body1.velocity[0] = value,
                    SweepVariable::Spin => {
                        body1.spin = value;
                        if sweep.body2_spin == Body2Spin::Opposite {
                            body2.spin = -value * body1.body.radius / body2.body.radius;
                        }
                    }
                    SweepVariable::Restitution => restitution = value,
                }
                Point {
                    value: Some(value),
                    body1,
                    body2,
                    restitution,
                }
            })
            .collect()
    }
}

/// The initial conditions of one impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// The sweep value (SI), if the case sweeps.
    pub value: Option<f64>,
    /// Body 1.
    pub body1: ImpactBody,
    /// Body 2.
    pub body2: ImpactBody,
    /// Prescribed normal restitution.
    pub restitution: f64,
}

impl Point {
    /// The approach speed along the normal, −(v1z − v2z) [m/s] (> 0: the bodies approach).
    pub fn approach_speed(&self) -> f64 {
        self.body2.velocity[1] - self.body1.velocity[1]
    }

    /// The effective mass m* = [1/m1 + 1/m2]⁻¹ [kg].
    pub fn effective_mass(&self) -> f64 {
        1.0 / (1.0 / self.body1.mass() + 1.0 / self.body2.mass())
    }

    /// The lever arms of the contact points [m]: the radii, 0 for a flat (its contact point is
    /// its surface, and it does not spin).
    pub fn lever_arms(&self) -> [f64; 2] {
        let arm = |b: &ImpactBody| {
            if b.body.radius.is_finite() {
                b.body.radius
            } else {
                0.0
            }
        };
        [arm(&self.body1), arm(&self.body2)]
    }

    /// The same impact with restitution 1.
    pub fn elastic(mut self) -> Self {
        self.restitution = 1.0;
        self
    }
}

/// The labels of an impact case whose file has no `labels`.
pub const DEFAULT_LABELS: [&str; 3] = ["impact", "dem", "fast"];

/// The exact reference of an impact: rigid-body dynamics with MDR as the contact law.
pub const REFERENCE: &str = "mdr";

/// The exact reference under LAMMPS's damping law and friction bound (`code_rule (spherecontact-impact)`).
pub const LAMMPS_REFERENCE: &str = "mdr-lammps";

/// The exact reference under YADE's damping law and friction bound.
pub const YADE_REFERENCE: &str = "mdr-yade";

/// The exact reference under LIGGGHTS' damping law and friction bound.
pub const LIGGGHTS_REFERENCE: &str = "mdr-liggghts";
