/*
 * xgo/board_state.h - the parts of the board's state, as complete types.
 *
 * Why this header exists: the caller owns the board (xgo_board_t in
 * xgo/board.h: static, on the stack, inside its own struct; no heap), so its
 * definition must be complete where board.h is included, and so must the
 * types of its parts: the register file and the motion core with the gait,
 * the action player, the servos, the sensors and the odometry. Here they are,
 * and nothing else: no functions, no constants beyond array sizes.
 *
 * Everything in this file is PRIVATE. Read the board through board.h (its
 * observers cover what a tool or a test needs); fields change without
 * notice. The functions that work on these types are declared in the
 * core's private headers in src/core, one per module.
 */
#ifndef XGO_BOARD_STATE_H
#define XGO_BOARD_STATE_H

#include <stdint.h>

#include "xgo/config.h"  /* XGO_WITH_* */
#include "xgo/profile.h" /* XGO_LEG_COUNT, XGO_SERVO_COUNT, xgo_profile_t */
#include "xgo/regs.h"    /* XGO_REG_COUNT, XGO_FIRMWARE_LEN */
#include "xgo/types.h"   /* xgo_vec3_t, xgo_body_pose_t */

#ifdef __cplusplus
extern "C" {
#endif

/* The register file (src/core/regfile.h): the 256-byte image and its
 * computed views, the write flags the motion core takes, the counters. */
typedef struct xgo_regs_stats_s {
    uint32_t writes_ok;
    uint32_t rejected_read_only;
    uint32_t rejected_value;
    uint32_t ignored_unmapped; /* accepted write frames with bytes for addresses the Mini lacks */
} xgo_regs_stats_t;

/* Addresses the flat image holds: every register below the diagnostic
 * block (0x00..0x93; regs.c checks it against the table). Nothing above is
 * stored: the block is formed from the board's counters when it is read,
 * the rest is unmapped and reads 0 (108 bytes of RAM). */
#define XGO_REGS_STORED 0x94u

/* Without the Mini2 the image skips three gaps where no model it serves has
 * a register: 0x22..0x2F, 0x6C..0x7F (the arm's are there) and 0x83..0x8F;
 * the addresses after a gap sit lower in mem and in written by its length
 * (regs.c; 51 bytes of RAM). With the Mini2 the gaps are empty: the image
 * is flat. */
#if XGO_WITH_MINI2
#define XGO_REGS_GAP1_START XGO_REGS_STORED
#define XGO_REGS_GAP1_END XGO_REGS_STORED
#define XGO_REGS_GAP2_START XGO_REGS_STORED
#define XGO_REGS_GAP2_END XGO_REGS_STORED
#define XGO_REGS_GAP3_START XGO_REGS_STORED
#define XGO_REGS_GAP3_END XGO_REGS_STORED
#else
#define XGO_REGS_GAP1_START 0x22u
#define XGO_REGS_GAP1_END 0x30u
#define XGO_REGS_GAP2_START 0x6Cu
#define XGO_REGS_GAP2_END 0x80u
#define XGO_REGS_GAP3_START 0x83u
#define XGO_REGS_GAP3_END 0x90u
#endif
#define XGO_REGS_IMAGE_LEN                                                             \
    (XGO_REGS_STORED - (XGO_REGS_GAP1_END - XGO_REGS_GAP1_START) -                     \
     (XGO_REGS_GAP2_END - XGO_REGS_GAP2_START) - (XGO_REGS_GAP3_END - XGO_REGS_GAP3_START))

typedef struct xgo_regs_s {
    uint8_t mem[XGO_REGS_IMAGE_LEN]; /* the image (0x00..0x93 but the gaps above);
                                        unmapped addresses stay 0 */
    uint8_t written[(XGO_REGS_IMAGE_LEN + 7u) / 8u]; /* bit per stored address (as mem):
                                                        written since last taken */
    char firmware_at_gait;           /* the firmware string's byte at 0x09, where the
                                        image has the gait type (the rest of the
                                        string is in the image, read-only) */
    int32_t attitude_mdeg[3];        /* roll, pitch, yaw in millidegrees */
#if XGO_WITH_INERTIAL /* else the IMU block's acceleration and rate read 0 */
    int16_t accel[3];                /* IMU block: acceleration, 16384 = 1 g */
    int16_t gyro[3];                 /* IMU block: angular rate, 16.4 = 1 deg/s */
#endif
    uint8_t turn_to[2];              /* last heading command at 0x3F, int16 BE */
    uint8_t servo_cmd[12];           /* servo-mode commands written to 0x50..0x5B
                                        (a read there gives the joints as they
                                        are, formed by the board) */
#if XGO_WITH_MINI2
    uint8_t servo_speed;             /* last value written to 0x5C (on the Mini2
                                        0x5C reads the claw instead; without the
                                        Mini2 the image's 0x5C is that value) */
#endif
    uint8_t arm;                     /* the model has the arm: XGO_REGF_ARM rows */
    uint8_t any_written;             /* a flag of `written` was set since the last
                                        xgo_regs_take_any_written (in padding) */
    xgo_regs_stats_t stats;
} xgo_regs_t;

/* XGO_GAIT_HOST_CACHES: 1 on a 64-bit host, whose RAM no budget limits:
 * the gait keeps more across ticks there (the fields at the end of
 * xgo_gait_t's caches; src/core/gait.c). The MCUs have no room for them (docs/mcu.md,
 * Budgets: device object + stack). Set by the target alone, so every file
 * of one build sees the same xgo_gait_t. */
#if defined(__SIZEOF_POINTER__) && __SIZEOF_POINTER__ == 8
#define XGO_GAIT_HOST_CACHES 1
#else
#define XGO_GAIT_HOST_CACHES 0
#endif

/* The gait generator (src/core/gait.h). */
typedef struct xgo_gait_s {
    /* ---- outputs, valid after xgo_gait_init and after every tick ---- */
    xgo_vec3_t foot_um[XGO_LEG_COUNT]; /* feet relative to the body, z up */
    uint8_t contact[XGO_LEG_COUNT];    /* 1 = stance (on the ground) */
    int32_t vx_um_s;                   /* velocity produced this tick */
    int32_t vy_um_s;
    int32_t vyaw_mdeg_s;

    /* ---- configuration (from xgo_gait_init) ---- */
    int32_t stance_um[XGO_LEG_COUNT][2]; /* nominal feet x, y */

    /* ---- state ---- */
    int32_t pos_q8[XGO_LEG_COUNT][2];  /* feet x, y in 1/256 um */
    int32_t lift_q8[XGO_LEG_COUNT][2]; /* where the current swing started */
    int32_t land_q8[XGO_LEG_COUNT][2]; /* where it lands: the touchdown point,
                                          frozen over the swing's second half */
    int32_t swing_height_um[XGO_LEG_COUNT]; /* latched at lift-off */
    int32_t reach_y_um[XGO_LEG_COUNT]; /* y reach of a planted foot: set at
                                          touchdown, only grows in stance */
    uint8_t swinging[XGO_LEG_COUNT];
    uint32_t phase;      /* master phase, 2^32 = one cycle */
    uint32_t rate;       /* phase advance of the last tick */
    uint32_t rate_base;  /* nominal rate, slewed after pace/gait changes */
    uint8_t type;        /* gait table in use */
    uint8_t standing;    /* 1 = stopped, four feet at stance */
    uint8_t brake;       /* slowing down until a pending gait switch fits */
    uint8_t land_is_td;  /* bit leg: land_q8 is the touchdown point of the cached
                            velocity and cadence (cache_v, cache_rate_fit; in what
                            was padding) */
    int32_t v_ramp[3];   /* produced vx, vy (um/s), vyaw (mdeg/s) */

    /* ---- caches (pure functions of the keys; save work in steady state) ---- */
    int32_t cache_cmd[3];      /* command the speed limit was computed for */
    int32_t cache_lambda_q16;  /* its scale factor (65536 = not limited) */
    int32_t cache_v[3];        /* velocity the fitted cadence is for */
    uint32_t cache_rate_base;
    uint32_t cache_rate_fit;
    uint8_t cache_cmd_type;
    uint8_t cache_v_type;
    uint16_t cache_swing_q16;  /* the swing time at cache_rate_fit (in what was padding) */
#if XGO_GAIT_HOST_CACHES
    int32_t tangent_q8[XGO_LEG_COUNT][4]; /* a swing foot's end tangents m0 x, y and
                                             m1 x, y (1/256 um per swing) */
    uint8_t tangents_kept; /* bit leg: tangent_q8 holds them for its lift-off
                              point, its landing point while that is the
                              touchdown point (land_is_td), the cached velocity
                              and cache_swing_q16 */
    uint8_t front_kept;    /* 1: a tick under the command front_cmd,
                              front_cmd_type, front_cmd_pace ends its front
                              stages as the last one did (gait.c,
                              steady_front), with these: */
    uint8_t front_resting;
    uint8_t front_cmd_type, front_cmd_pace;
    int32_t front_cmd[5];  /* vx, vy, vyaw, mark time, step height as given */
    int32_t front_mark, front_height; /* limited */
    uint32_t front_widening; /* the yaw widening of the stride budget and reach */
    int32_t front_w_q24;     /* the yaw rate, rad/s Q24 */
#endif

    /* ---- diagnostics ---- */
    uint32_t ticks;           /* ticks since init */
    uint32_t limited_ticks;   /* ticks with the speed limited (cadence cap) */
    uint32_t boosted_ticks;   /* ticks with the cadence raised by a transient */
    uint32_t governed_ticks;  /* ticks where planted feet held back the ramp */
    uint32_t outside_ticks;   /* ticks where a planted foot's predicted end was
                                 (by rounding) just outside its reach */
    uint32_t clamped_ticks;   /* ticks where a stance foot hit the reach box */
    uint32_t switches;        /* gait table switches performed */
} xgo_gait_t;

/* The preset-action player (src/core/actions.h): which action, and where
 * in it. */
typedef struct xgo_action_player_s {
    uint8_t id;         /* running action, 0 = none */
    uint16_t seg;       /* segment (keyframe interval) being played */
    uint16_t seg_start; /* keyframe time (ticks) at which it starts */
    uint16_t elapsed;   /* ticks since the start */
    uint16_t lead;      /* ticks of lead-in before the keyframes; 0xFFFF: still in it */
    uint32_t scale_q16; /* keyframe ticks per tick after the lead-in, Q16 */
} xgo_action_player_t;

/* Feet on their way home to the stance (src/core/settle.h). */
typedef struct xgo_settle_s {
    xgo_vec3_t foot[XGO_LEG_COUNT]; /* where each foot is (machine frame, z up) */
    xgo_vec3_t from[XGO_LEG_COUNT]; /* where the current move started */
    int32_t lift_um;                /* the current move's clearance */
    int32_t v[3];                   /* the body still moving: vx, vy (um/s), yaw rate (mdeg/s) */
    uint16_t tick;                  /* ticks into the current move */
    uint16_t ticks;                 /* its length */
    uint8_t planted;                /* bit leg: on the ground */
    uint8_t moving;                 /* bit leg: in the current move */
    uint8_t active;
} xgo_settle_t;

/* The nearest pose the legs hold for the one asked (src/core/reach.h). */
typedef struct xgo_reach_s {
    xgo_body_pose_t key;    /* the pose asked for, periodic channels at their middle */
    xgo_body_pose_t spread; /* key: the periodic channels' amplitude (0: none) */
    xgo_body_pose_t stand;  /* the standing pose: always held */
    xgo_body_pose_t held;   /* the last pose handed out (kept while a search runs) */
    xgo_vec3_t stroke[XGO_LEG_COUNT]; /* key, walking: each planted foot's run either way */
    xgo_vec3_t shift;       /* the search's body shift at this scale (um) */
    xgo_vec3_t found;       /* the shift found (with scale), once the search ended */
    uint32_t best;          /* the total miss at shift (um) */
    int32_t step;           /* the descent's step (um); 0: not started at this scale */
    uint8_t dir;            /* the descent's next probe: +x, -x, +y, -y, +z, -z; 6: the jump */
    uint8_t walking;        /* key: the stroke is checked */
    uint8_t searching;      /* 1 while the search goes on */
    uint8_t scale;          /* share of the deviation from stand kept, in 1/8 */
    uint8_t valid;          /* key holds a search */
} xgo_reach_t;

/* The body pose following its target (src/core/follow.h): x, y, z (um),
 * roll, pitch, yaw (mdeg), all in 1/256. */
typedef struct xgo_follow_s {
    int32_t pos_q8[6];
    int32_t vel_q8[6]; /* per tick */
} xgo_follow_t;

/* The twelve emulated servos (src/core/servos.h), register order. */
typedef struct xgo_servos_s {
    int32_t angle_mdeg[XGO_SERVO_COUNT];  /* where each joint is now */
    int32_t target_mdeg[XGO_SERVO_COUNT]; /* where it is going (limits applied) */
    int32_t zero_offset_mdeg[XGO_SERVO_COUNT];
    uint16_t unloaded;                    /* bit i: joint i is limp */
    const xgo_profile_t *profile;
} xgo_servos_t;

/* Battery and IMU models (src/core/sensors.h). */
typedef struct xgo_battery_s {
    uint32_t charge_upct; /* 0 .. 100,000,000 */
} xgo_battery_t;

typedef struct xgo_imu_s {
#if XGO_WITH_EMULATOR_INPUTS /* else the attitude is the body's (xgo/config.h) */
    int32_t ground_roll_mdeg;  /* tilt of the ground under the robot */
    int32_t ground_pitch_mdeg;
    int32_t push_q10[2];       /* a shove's tilt (roll, pitch), mdeg * 1024 */
    int32_t push_rate_q10[2];  /* its rate per tick, same unit */
#endif
    int32_t yaw_acc;           /* integrated yaw, mdeg * XGO_TICK_HZ, wrapped */
    int32_t roll_mdeg;         /* outputs, updated by xgo_imu_tick */
    int32_t pitch_mdeg;
    int32_t yaw_mdeg;
} xgo_imu_t;

/* Leg odometry (src/core/odometry.h); without it (XGO_WITH_ODOMETRY 0,
 * xgo/config.h) nothing: the pose stays at the origin. */
typedef struct xgo_odometry_s {
#if XGO_WITH_ODOMETRY
    int64_t x_q8;                           /* world position, 1/256 um */
    int64_t y_q8;
    uint32_t yaw;                           /* heading, binary angle (xgo_bam_t) */
    int32_t yaw_sc[2];                      /* its sine and cosine, Q30 (kept with it:
                                               the tick needs them twice) */
    xgo_vec3_t prev_um[XGO_LEG_COUNT];      /* last tick's feet (machine frame; z unused) */
    uint8_t prev_contact;                   /* bit leg: planted last tick */
    uint8_t have_prev;                      /* prev_* are valid */
    uint8_t prev_unmeasured;                /* bit leg: prev_um not measured (a foot in
                                               the air; in what was padding) */
    int32_t last_d_q8[2];                   /* last tick's translation (body frame) */
    int32_t last_dyaw;                      /* last tick's rotation (signed BAM) */
    uint32_t extrapolated_ticks;            /* ticks with < 2 common planted feet */
#else
    uint8_t unused; /* C99 has no empty struct */
#endif
} xgo_odometry_t;

/* Turn to heading, register 0x3F (src/core/heading.h). */
typedef struct xgo_heading_s {
    int32_t origin_mdeg; /* the IMU yaw that heading 0 means */
    int32_t target_mdeg; /* absolute IMU yaw to reach, [-180000, 180000) */
    uint8_t state;       /* xgo_heading_state_t */
} xgo_heading_t;

/* Accelerometer and gyroscope of the IMU block 0x65 (src/core/inertial.h). */
typedef struct xgo_inertial_s {
#if XGO_WITH_INERTIAL /* else only the outputs, 0 (xgo/config.h) */
    int64_t pos_q8[2][3];    /* body centre, world, 1/256 um: last tick, the one before */
    int32_t att_mdeg[3];     /* last tick's roll, pitch, yaw */
    int32_t accel_q8[3];     /* filter states, LSB * 256 */
    int32_t gyro_q8[3];
    int32_t trig_mdeg[2];    /* the roll and pitch whose sin, cos (Q30) trig_q30 holds */
    int32_t trig_q30[2][2];
    uint8_t history;         /* ticks seen, up to 2 */
#endif
    int16_t accel[3];        /* outputs, LSB */
    int16_t gyro[3];
} xgo_inertial_t;

/* The Mini2's arm and claw (src/core/arm.h); geo NULL on a model without. */
typedef struct xgo_arm_s {
    const xgo_arm_geometry_t *geo;
    int32_t q_mdeg[XGO_ARM_JOINT_COUNT];      /* servo angles: where they are */
#if XGO_WITH_MINI2 /* else no model has the arm: geo stays NULL (xgo/config.h) */
    int32_t target_mdeg[XGO_ARM_JOINT_COUNT]; /* where they are going */
    int32_t point_um[2];                      /* commanded claw point x, z (arm frame) */
    uint8_t follow_point;  /* the joints serve point_um (else direct servo commands) */
#endif
    uint8_t out_of_reach;  /* the point now served had to be projected */
} xgo_arm_t;

/* The motion core (src/core/motion.h): registers in, twelve joints out. */
typedef struct xgo_motion_s {
    const xgo_profile_t *profile;
    uint8_t mode;             /* xgo_mode_t */
    uint8_t group_mode;       /* the mode the last group write selected */
    uint8_t perform;          /* 0x03 = 1: cycle actions */
    uint8_t perform_last;     /* the action perform mode started last */
    uint8_t calibration;
    uint8_t action_id;        /* running preset action (incl. 255 reset), 0 none */
    uint8_t contact;          /* bit leg: foot on the ground this tick */
    uint8_t feet_as_solved;   /* the joints are where the last IK put them, all feet
                                 reached: the feet are ik_cache's (xgo_motion_feet_body;
                                 without odometry the joints are compared there) */
    xgo_gait_t gait;
    xgo_action_player_t actions;
    xgo_servos_t servos;
    xgo_imu_t imu;
    xgo_battery_t battery;
    xgo_vec3_t stance_um[XGO_LEG_COUNT];
    xgo_body_pose_t pose;     /* body pose used this tick (machine frame) */
    xgo_body_pose_t stand;    /* the standing pose (initial body registers) */
    int32_t servo_cmd_mdeg[XGO_SERVO_COUNT]; /* servo-mode commands */
    uint32_t periodic_phase[6]; /* roll, pitch, yaw, x, y, z (xgo_bam_t) */
    int32_t stab_mdeg[2];     /* self-stabilisation roll, pitch correction */
    uint32_t nv_changes;      /* counts changes of non-volatile data */
    xgo_heading_t heading;    /* turn to heading (0x3F) and its origin (0x06) */
    xgo_inertial_t inertial;  /* accelerometer and gyroscope (0x65) */
    xgo_arm_t arm;            /* the Mini2's arm and claw */
    xgo_settle_t settle;      /* transitions: feet on their way home to the stance */
    xgo_follow_t follow;      /* the body pose following its target */
    xgo_body_pose_t pose_target; /* the pose asked for (registers made reachable, action), before following */
    xgo_reach_t reach;        /* the registers' pose made reachable */
    xgo_vec3_t stroke[XGO_LEG_COUNT]; /* walking: how far each planted foot runs either way */
    int32_t stroke_key[6];    /* the command the stroke is for: vx, vy, vyaw, mark time,
                                 type | pace << 8, and the margin */
    int32_t stroke_margin_um; /* added to the stroke after a planted foot ran out of reach */
    uint8_t stroke_walks;     /* the command walks (stroke is its) */
    uint8_t stroke_on;        /* stroke applies (walking, or still stopping) */
    xgo_odometry_t odom;      /* world pose from the planted feet (here: without the
                                 option one byte, in what is padding after the flags) */
#if XGO_WITH_ODOMETRY
    struct {                  /* the joints and body pose of the feet odom holds
                                 unmeasured (prev_unmeasured): measured if it needs them */
        int32_t q_mdeg[XGO_SERVO_COUNT];
        xgo_body_pose_t pose;
    } fk_later;
#endif
    uint32_t clamped_pose_ticks; /* whole-unit ticks whose pose is not the one asked (reach.h) */
    uint32_t reach_clamped_ticks; /* ticks with the body pose or the arm's point out of reach
                                     (diagnostic reach_clamped) */
    xgo_vec3_t leg_feet_um[XGO_LEG_COUNT]; /* leg mode: the feet asked for now (leg frames,
                                              moving toward the registers' at a bounded speed) */
    uint16_t servo_written;   /* servo mode: joints written since entering it */
    uint8_t leg_ready;        /* leg mode: home reached, leg_feet_um valid */
    uint8_t servo_ready;      /* servo mode: home reached, unwritten joints captured */
    struct {                  /* 0x30..0x3C as last decoded (motion_pose.c) */
        uint8_t valid;            /* cleared when they are written or reset */
        uint8_t periodic;         /* bit axis: 0x39..0x3B, 0x80..0x82 run a periodic
                                     motion on it (in what was padding) */
        int32_t body[6];          /* 0x36..0x38, 0x33..0x35: mdeg, um; an axis with a
                                     periodic motion: its phase step per tick instead */
        int32_t velocity[3];      /* 0x30..0x32: um/s, um/s, mdeg/s */
        int32_t mark_time_um;     /* 0x3C */
    } decoded;
    struct {                  /* last body + leg IK solve (skipped when unchanged) */
        xgo_body_pose_t pose;
        int32_t rot_q30[9];                 /* pose's rotation (xgo_body_rotation), kept
                                               for mapping measured feet back (36 B) */
        xgo_vec3_t feet[XGO_LEG_COUNT];     /* machine frame, as asked */
        int32_t q_mdeg[XGO_SERVO_COUNT];
        uint8_t projected;                  /* bit leg: target was unreachable */
        uint8_t valid;
    } ik_cache;
} xgo_motion_t;

#ifdef __cplusplus
}
#endif

#endif /* XGO_BOARD_STATE_H */
