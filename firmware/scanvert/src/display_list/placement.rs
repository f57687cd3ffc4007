//! A segment's placement: the transforms the `place` command (and
//! [`Scene::place`](crate::scene::Scene::place)) puts before its
//! procedure's.

use crate::geometry::{Angle, Point3, TransformError, TransformStack, Q16};

/// Where a segment is placed: its procedure's output is built as if the
/// procedure began with `translate`, then `rotate` about x, y and z in
/// that order, then `scale` (each left out when it is the identity, so
/// [`Placement::IDENTITY`] changes nothing).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Placement {
    /// Moves the segment.
    pub translate: Point3,
    /// Turns it about x, then y, then z.
    pub rotate: [Angle; 3],
    /// Scales it, per axis.
    pub scale: Point3,
}

impl Default for Placement {
    fn default() -> Self {
        Placement::IDENTITY
    }
}

impl Placement {
    /// No move: where the procedure puts it.
    pub const IDENTITY: Placement = Placement {
        translate: Point3::ORIGIN,
        rotate: [Angle::ZERO; 3],
        scale: Point3::new(Q16::ONE, Q16::ONE, Q16::ONE),
    };

    /// A move by `(x, y, z)`.
    pub const fn translation(x: Q16, y: Q16, z: Q16) -> Placement {
        Placement {
            translate: Point3::new(x, y, z),
            ..Placement::IDENTITY
        }
    }

    /// Applies it to the top of `stack`, as the commands
    /// `translate`, `rotate x`, `rotate y`, `rotate z`, `scale` would.
    pub fn apply<const DEPTH: usize>(
        &self,
        stack: &mut TransformStack<DEPTH>,
    ) -> Result<(), TransformError> {
        let t = self.translate;
        if t != Point3::ORIGIN {
            stack.translate(t.x, t.y, t.z)?;
        }
        let [x, y, z] = self.rotate;
        if x != Angle::ZERO {
            stack.rotate_x(x)?;
        }
        if y != Angle::ZERO {
            stack.rotate_y(y)?;
        }
        if z != Angle::ZERO {
            stack.rotate_z(z)?;
        }
        let s = self.scale;
        if s != Placement::IDENTITY.scale {
            stack.scale(s.x, s.y, s.z)?;
        }
        Ok(())
    }
}
