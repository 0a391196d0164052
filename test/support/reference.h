/*
 * reference.h - double-precision references the tests and benches compare
 * the fixed-point core against (libm; host only).
 */
#ifndef XGO_TEST_REFERENCE_H
#define XGO_TEST_REFERENCE_H

/* Body attitude R = Rz(yaw) * Ry(pitch) * Rx(roll), angles in radians, the
 * convention of xgo_body_pose_t (xgo/kinematics.h): m[i][j] is row i, so a
 * vector v in body axes is m v in machine axes, and m^T takes it back. */
void xgo_ref_rotation(double roll, double pitch, double yaw, double m[3][3]);

#endif /* XGO_TEST_REFERENCE_H */
