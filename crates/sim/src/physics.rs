//! Physical constants of the world (DESIGN §5), all configurable.

use serde::{Deserialize, Serialize};

use crate::scenario::SurfaceKind;

/// Friction coefficient of each surface kind (ViVAE's table).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct FrictionTable {
    /// Friction of road.
    ///
    /// Paper: 1 (ViVAE).
    pub road: f64,
    /// Friction of grass (the background, unless the scenario names another).
    ///
    /// Paper: 10 (ViVAE).
    pub grass: f64,
    /// Friction of sand.
    ///
    /// Paper: 3.5 (ViVAE).
    pub sand: f64,
    /// Friction of water.
    ///
    /// Paper: 6.5 (ViVAE).
    pub water: f64,
}

impl Default for FrictionTable {
    fn default() -> Self {
        FrictionTable {
            road: 1.0,
            grass: 10.0,
            sand: 3.5,
            water: 6.5,
        }
    }
}

impl FrictionTable {
    /// Friction of `kind`.
    pub fn of(&self, kind: SurfaceKind) -> f64 {
        match kind {
            SurfaceKind::Road => self.road,
            SurfaceKind::Grass => self.grass,
            SurfaceKind::Sand => self.sand,
            SurfaceKind::Water => self.water,
        }
    }

    /// Smallest and largest friction in the table.
    pub fn range(&self) -> (f64, f64) {
        let v = [self.road, self.grass, self.sand, self.water];
        (
            v.iter().copied().fold(f64::INFINITY, f64::min),
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    }
}

/// Physics constants: robot kinematics, movable-object masses and damping, friction.
///
/// The defaults are DESIGN §5's; each field's doc comment is also its entry in
/// `vivae config reference` (a closing `Unit:` note gives its unit).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct PhysicsParams {
    /// Robot disc radius.
    ///
    /// Unit: px.
    pub robot_radius: f64,
    /// Top forward speed.
    ///
    /// Unit: px/step.
    pub v_max: f64,
    /// Acceleration at full throttle.
    ///
    /// Unit: px/step².
    pub a_max: f64,
    /// Turn rate at full wheel difference and standstill.
    ///
    /// Unit: rad/step.
    pub omega_max: f64,
    /// Friction drag factor: the speed loses `k·μ·v` per step on a surface of friction `μ`.
    ///
    /// Unit: 1/step.
    pub k: f64,
    /// Robot mass, for pushing movable objects.
    pub robot_mass: f64,
    /// Puck mass per unit area (at 0.002 a radius-10 puck weighs about 0.6 robots).
    ///
    /// Unit: 1/px².
    pub puck_density: f64,
    /// Fraction of a puck's velocity lost per step.
    pub puck_damping: f64,
    /// Movable-obstacle mass per unit area.
    ///
    /// Unit: 1/px².
    pub obstacle_density: f64,
    /// Fraction of a movable obstacle's velocity lost per step.
    pub obstacle_damping: f64,
    /// Contact-resolution passes per step.
    pub collision_iterations: u32,
    /// Friction of each surface kind.
    pub friction: FrictionTable,
}

impl Default for PhysicsParams {
    fn default() -> Self {
        PhysicsParams {
            robot_radius: 6.0,
            v_max: 5.0,
            a_max: 0.5,
            omega_max: 0.2,
            k: 0.1,
            robot_mass: 1.0,
            puck_density: 0.002,
            puck_damping: 0.2,
            obstacle_density: 0.02,
            obstacle_damping: 0.5,
            collision_iterations: 4,
            friction: FrictionTable::default(),
        }
    }
}

/// A physics or sensor parameter out of range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid parameter {field} = {value}: {reason}")]
pub struct ParamError {
    /// Field name.
    pub field: &'static str,
    /// Its value.
    pub value: f64,
    /// What is required.
    pub reason: &'static str,
}

pub(crate) fn check(
    field: &'static str,
    value: f64,
    ok: bool,
    reason: &'static str,
) -> Result<(), ParamError> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(ParamError {
            field,
            value,
            reason,
        })
    }
}

impl PhysicsParams {
    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), ParamError> {
        check(
            "robot_radius",
            self.robot_radius,
            self.robot_radius > 0.0,
            "must be > 0",
        )?;
        check("v_max", self.v_max, self.v_max > 0.0, "must be > 0")?;
        check("a_max", self.a_max, self.a_max >= 0.0, "must be >= 0")?;
        check(
            "omega_max",
            self.omega_max,
            self.omega_max >= 0.0,
            "must be >= 0",
        )?;
        check("k", self.k, self.k >= 0.0, "must be >= 0")?;
        check(
            "robot_mass",
            self.robot_mass,
            self.robot_mass > 0.0,
            "must be > 0",
        )?;
        check(
            "puck_density",
            self.puck_density,
            self.puck_density > 0.0,
            "must be > 0",
        )?;
        check(
            "puck_damping",
            self.puck_damping,
            (0.0..=1.0).contains(&self.puck_damping),
            "must be in [0, 1]",
        )?;
        check(
            "obstacle_density",
            self.obstacle_density,
            self.obstacle_density > 0.0,
            "must be > 0",
        )?;
        check(
            "obstacle_damping",
            self.obstacle_damping,
            (0.0..=1.0).contains(&self.obstacle_damping),
            "must be in [0, 1]",
        )?;
        let it = self.collision_iterations as f64;
        check(
            "collision_iterations",
            it,
            (1.0..=64.0).contains(&it),
            "must be in 1..=64",
        )?;
        let f = &self.friction;
        for (name, v) in [
            ("friction.road", f.road),
            ("friction.grass", f.grass),
            ("friction.sand", f.sand),
            ("friction.water", f.water),
        ] {
            check(name, v, v >= 0.0, "must be >= 0")?;
        }
        let (lo, hi) = f.range();
        check(
            "friction (max - min)",
            hi - lo,
            hi > lo,
            "the table needs two different values",
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_as_specified() {
        let p = PhysicsParams::default();
        p.validate().unwrap();
        assert_eq!(
            (p.robot_radius, p.v_max, p.a_max, p.omega_max, p.k),
            (6.0, 5.0, 0.5, 0.2, 0.1)
        );
    }

    #[test]
    fn validate_names_the_bad_field() {
        let p = PhysicsParams {
            v_max: -1.0,
            ..Default::default()
        };
        assert_eq!(p.validate().unwrap_err().field, "v_max");
        let p = PhysicsParams {
            puck_damping: f64::NAN,
            ..Default::default()
        };
        assert_eq!(p.validate().unwrap_err().field, "puck_damping");
    }

    #[test]
    fn unknown_toml_like_fields_are_rejected() {
        let r: Result<PhysicsParams, _> = serde_json::from_str(r#"{"v_maks": 3}"#);
        assert!(r.is_err());
        let p: PhysicsParams = serde_json::from_str(r#"{"v_max": 3}"#).unwrap();
        assert_eq!(p.v_max, 3.0);
        assert_eq!(p.k, 0.1);
    }
}
