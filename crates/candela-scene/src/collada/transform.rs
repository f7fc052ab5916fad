//! Node transforms and the up-axis change.
//!
//! COLLADA composes a node's `<matrix>`, `<translate>`, `<rotate>` and
//! `<scale>` children in document order: the local transform is
//! `T1 * T2 * ... * Tn`, applied to points as column vectors, so the last
//! element acts first. `<matrix>` is written row-major (translation in the
//! last column).

use super::numbers::floats;
use super::xml::{elements, Ctx, XNode};
use crate::error::{ErrorKind, LoadError};
use glam::{Mat3, Mat4, Vec3};

/// The file's `asset/up_axis`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum UpAxis {
    X,
    Y,
    Z,
}

/// The rotation from file space to Candela's Y-up world space.
///
/// - `Y_UP`: identity.
/// - `Z_UP`: x' = -x, y' = z, z' = y (a half turn about (0, 1, 1)/√2, as the
///   CS184 program does).
/// - `X_UP`: x' = y, y' = x, z' = -z (the analogous half turn about
///   (1, 1, 0)/√2: the up axis and Y swap, the third axis flips).
///
/// All three are proper rotations (determinant +1), so handedness and winding
/// are preserved.
pub(crate) fn up_axis_matrix(axis: UpAxis) -> Mat4 {
    let m = match axis {
        UpAxis::Y => Mat3::IDENTITY,
        UpAxis::Z => Mat3::from_cols(
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.0, 1.0, 0.0),
        ),
        UpAxis::X => Mat3::from_cols(
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -1.0),
        ),
    };
    Mat4::from_mat3(m)
}

/// A row-major 4x4 matrix as COLLADA writes it.
pub(crate) fn matrix_from_row_major(v: &[f32; 16]) -> Mat4 {
    Mat4::from_cols_array(v).transpose()
}

/// A rotation by `deg` degrees about `axis` (need not be unit length).
pub(crate) fn rotation(axis: Vec3, deg: f32) -> Option<Mat4> {
    let axis = axis.try_normalize()?;
    Some(Mat4::from_axis_angle(axis, deg.to_radians()))
}

/// The local transform of a `<node>`: its transform elements composed in
/// document order. Unsupported ones (`lookat`, `skew`) are reported and skipped.
pub(crate) fn local_transform(ctx: &Ctx, node: XNode) -> Result<Mat4, LoadError> {
    let mut m = Mat4::IDENTITY;
    for el in elements(node) {
        let t = match el.tag_name().name() {
            "matrix" => matrix_from_row_major(&super::lenient::matrix(ctx, el)?),
            "translate" => {
                let v = floats(ctx, el, Some(3)).map_err(|e| expected(e, 3))?;
                Mat4::from_translation(Vec3::new(v[0], v[1], v[2]))
            }
            "scale" => {
                let v = floats(ctx, el, Some(3)).map_err(|e| expected(e, 3))?;
                Mat4::from_scale(Vec3::new(v[0], v[1], v[2]))
            }
            "rotate" => {
                let v = floats(ctx, el, Some(4)).map_err(|e| expected(e, 4))?;
                rotation(Vec3::new(v[0], v[1], v[2]), v[3]).ok_or_else(|| {
                    ctx.err(el, ErrorKind::BadValue, "rotation axis has zero length")
                })?
            }
            "lookat" | "skew" => {
                ctx.warn(
                    el,
                    format!(
                        "<{}> transform not supported; ignored",
                        el.tag_name().name()
                    ),
                )?;
                continue;
            }
            _ => continue,
        };
        m *= t;
    }
    Ok(m)
}

/// Rephrases a count mismatch on a transform element (which has no `count`).
fn expected(mut e: LoadError, n: usize) -> LoadError {
    if e.kind == ErrorKind::CountMismatch {
        e.message = format!(
            "expected {n} numbers ({})",
            e.message.replace("count=", "needs ")
        );
    }
    e
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).abs().max_element() < 1e-5
    }

    #[test]
    fn row_major_matrix_puts_translation_in_last_column() {
        let m = matrix_from_row_major(&[
            1., 0., 0., 5., 0., 1., 0., 6., 0., 0., 1., 7., 0., 0., 0., 1.,
        ]);
        assert!(close(m.transform_point3(Vec3::ZERO), Vec3::new(5., 6., 7.)));
        // A non-symmetric linear part: row 0 = (0, 2, 0) means x' = 2y.
        let m = matrix_from_row_major(&[
            0., 2., 0., 0., 0., 0., 3., 0., 4., 0., 0., 0., 0., 0., 0., 1.,
        ]);
        assert!(close(
            m.transform_point3(Vec3::new(1., 10., 100.)),
            Vec3::new(20., 300., 4.)
        ));
    }

    #[test]
    fn rotate_is_right_handed_in_degrees() {
        let r = rotation(Vec3::new(0., 0., 2.), 90.).unwrap();
        assert!(close(r.transform_vector3(Vec3::X), Vec3::Y));
        assert!(rotation(Vec3::ZERO, 30.).is_none());
    }

    #[test]
    fn up_axis_matrices_map_up_to_y_and_are_rotations() {
        let z = up_axis_matrix(UpAxis::Z);
        assert!(close(
            z.transform_point3(Vec3::new(1., 2., 3.)),
            Vec3::new(-1., 3., 2.)
        ));
        let x = up_axis_matrix(UpAxis::X);
        assert!(close(x.transform_vector3(Vec3::X), Vec3::Y));
        assert!(close(
            x.transform_point3(Vec3::new(1., 2., 3.)),
            Vec3::new(2., 1., -3.)
        ));
        for m in [z, x, up_axis_matrix(UpAxis::Y)] {
            assert!((m.determinant() - 1.0).abs() < 1e-6);
        }
    }
}
