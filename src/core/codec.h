/*
 * codec.h - every byte encoding of the register file, in one place (private
 * to the core): how the values the board works with (um, mdeg, ms) map to and
 * from the bytes a host writes and reads.
 *
 *   the vendor's range map     xgo_range_to_byte / xgo_byte_to_range
 *   signed registers           xgo_signed_byte_to_value: 0x7F and 0x80 are 0
 *   servo, foot, body          joint angles, feet, body pose <-> bytes
 *   attitude 0x62..0x64        xgo_angle_to_byte (1-byte read),
 *                              xgo_mdeg_to_float32_bits (4-byte read)
 *   attitude 0x66..0x68        xgo_mdeg_to_centideg (int16 view)
 *   velocity 0x30..0x32, periods, mark time 0x3C, servo speed 0x5C
 *   unload 0x20                xgo_unload_decode (public: xgo/regs.h)
 *
 * Bytes are expected input: every function accepts any byte and any value
 * (out-of-range values saturate), nothing here can fail.
 * Portable: no OS calls, no heap, no globals, no floating point.
 */
#ifndef XGO_CORE_CODEC_H
#define XGO_CORE_CODEC_H

#include <stdint.h>

#include "kinematics.h" /* xgo_vec3_t, xgo_body_pose_t */
#include "xgo/profile.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Command ranges of the velocity registers 0x30..0x32 (vendor ranges; the
 * vendor gives no unit for vx/vy: cm/s, see docs/decisions.md). */
#define XGO_VX_MAX_UM_S 250000
#define XGO_VY_MAX_UM_S 180000
#define XGO_VYAW_MAX_MDEG_S 100000

/* Period registers 0x39..0x3B, 0x80..0x82: byte 1..255 -> 1.5 .. 8 s. */
#define XGO_PERIOD_MIN_MS 1500
#define XGO_PERIOD_MAX_MS 8000

/* Servo mode, register 0x5C: byte 0..255 -> 10 .. 600 deg/s. */
#define XGO_SERVO_SPEED_MIN_MDEG_S 10000
#define XGO_SERVO_SPEED_MAX_MDEG_S 600000

/* ------------------------------------------------------------ range map
 * The vendor library's linear map of a range [lo, hi] onto 0..255:
 *   encode: byte = floor(255 * (v - lo) / (hi - lo)), clamped to 0..255
 *           (the library's int(255 / (hi - lo) * (v - lo)), computed
 *           exactly; the middle of a symmetric range gives 0x7F);
 *   decode: v = lo + b * (hi - lo) / 255, rounded up to the next unit
 *           (error < 1 mdeg or 1 um; makes encode(decode(b)) == b).
 * No dead band here (0x7F and 0x80 decode to different values): that is
 * xgo_signed_byte_to_value. */
/* Every range mapped here spans less than this many units (checked: an
 * assertion; the profiles' ranges by test_profile). */
#define XGO_RANGE_SPAN_LIMIT (1u << 23)

uint8_t xgo_range_to_byte(const xgo_range_t *r, int32_t v);
int32_t xgo_byte_to_range(const xgo_range_t *r, uint8_t b);

/* The middle of byte b's step instead of its start: lo + (b + 1/2) * (hi -
 * lo) / 255, rounded, 0xFF giving hi. For commands whose senders truncate
 * (the library's int()): the value sent lies in [start, start + step), so
 * the middle halves the worst error (the Mini2's arm: docs/registers.md). */
int32_t xgo_byte_to_range_mid(const xgo_range_t *r, uint8_t b);

/* The vendor library's other map, servo_set_angle's: a value in [lo, hi]
 * is sent as int(1 + 254 * (v - lo) / (hi - lo)), bytes 1..255. Decoded to
 * the middle of the step; 0 gives lo, 0xFF hi. */
int32_t xgo_servo_byte_to_range_mid(const xgo_range_t *r, uint8_t b);

/* Signed register byte -> value in [-limit, limit]; 0x7F and 0x80 are both
 * zero (the vendor library sends 0x7F for zero). */
int32_t xgo_signed_byte_to_value(uint8_t b, int32_t limit);

/* ------------------------------------------------------------ joints, feet, body */

/* Servo registers: joint angle (mdeg) <-> byte, by joint index. */
uint8_t xgo_joint_to_byte(const xgo_profile_t *p, xgo_joint_t joint, int32_t mdeg);
int32_t xgo_byte_to_joint(const xgo_profile_t *p, xgo_joint_t joint, uint8_t b);

/* Foot registers: leg-frame coordinate (um) <-> byte, by axis. */
uint8_t xgo_foot_to_byte(const xgo_profile_t *p, xgo_axis_t axis, int32_t um);
int32_t xgo_byte_to_foot(const xgo_profile_t *p, xgo_axis_t axis, uint8_t b);

/* All twelve, in register order (out[0] is 0x50 / 0x40, out[11] is 0x5B / 0x4B). */
void xgo_joints_to_bytes(const xgo_profile_t *p, const int32_t q_mdeg[XGO_LEG_COUNT][XGO_JOINT_COUNT],
                         uint8_t out[XGO_LEG_COUNT * XGO_JOINT_COUNT]);
void xgo_bytes_to_joints(const xgo_profile_t *p, const uint8_t in[XGO_LEG_COUNT * XGO_JOINT_COUNT],
                         int32_t q_mdeg[XGO_LEG_COUNT][XGO_JOINT_COUNT]);
void xgo_feet_to_bytes(const xgo_profile_t *p, const xgo_vec3_t feet_leg_um[XGO_LEG_COUNT],
                       uint8_t out[XGO_LEG_COUNT * XGO_AXIS_COUNT]);
void xgo_bytes_to_feet(const xgo_profile_t *p, const uint8_t in[XGO_LEG_COUNT * XGO_AXIS_COUNT],
                       xgo_vec3_t feet_leg_um[XGO_LEG_COUNT]);

/* Body registers 0x33..0x38 (x, y, z shift, roll, pitch, yaw) <-> pose, the
 * plain range map (the board's own reading adds the dead band). */
void xgo_body_pose_to_bytes(const xgo_profile_t *p, const xgo_body_pose_t *pose, uint8_t out[6]);
void xgo_bytes_to_body_pose(const xgo_profile_t *p, const uint8_t in[6], xgo_body_pose_t *pose);

/* ------------------------------------------------------------ attitude */

uint8_t xgo_angle_to_byte(int32_t mdeg);         /* 0x80 = 0, 1 LSB = 180/128 deg */
uint32_t xgo_mdeg_to_float32_bits(int32_t mdeg); /* IEEE-754 bits of mdeg / 1000 */
/* The int16 views 0x66..0x68: 0.01 degree, rounded half away from zero,
 * saturated at the int16 range. */
int16_t xgo_mdeg_to_centideg(int32_t mdeg);

/* ------------------------------------------------------------ motion commands */

/* Period registers: byte 1..255 -> ms (0, "off", is the caller's). */
int32_t xgo_period_byte_to_ms(uint8_t b);

/* Mark time 0x3C: 0 = off; 1..255 -> step height in the profile's range. */
int32_t xgo_mark_time_byte_to_um(const xgo_profile_t *p, uint8_t b);

/* Servo speed 0x5C -> mdeg/s. */
int32_t xgo_servo_speed_byte_to_mdeg_s(uint8_t b);

#ifdef __cplusplus
}
#endif

#endif /* XGO_CORE_CODEC_H */
