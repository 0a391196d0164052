/*
 * actions.c - preset actions (register 0x3E): keyframe tables and their
 * player. Format, easing and the list of motions: docs/actions.md.
 *
 * Table format (all const, in flash):
 *   An action lists the pose channels it moves (a bit mask over the 18
 *   channels below; the others stay 0) and its keyframes. A keyframe is
 *   one unsigned byte dt - the time from the previous keyframe in
 *   centiseconds (10 ms = 5 ticks; 1..255) - followed by one int8 per
 *   channel in the mask, in channel order: millimetres for translations and
 *   foot offsets, degrees for the attitude. Keyframe -1 is implicit: the
 *   zero pose at time 0. The last keyframe must be the zero pose.
 *   One optional loop section (keyframes loop_first..loop_last, played
 *   loop_reps times) keeps periodic motions short; the expanded sequence
 *   is called "virtual" below.
 *
 * Interpolation: per channel, a monotone cubic Hermite spline through the
 * keyframes (Fritsch-Butland tangents: the harmonic mean of the two
 * neighbouring slopes, at most twice the smaller one; 0 at a turning point,
 * at the first and at the last keyframe). It hits every keyframe exactly, has a continuous velocity and
 * never leaves the range of its two end keyframes, so a table whose
 * keyframes are inside the limits plays inside the limits (per channel).
 * Arithmetic: 32-bit tangents, Q16 curve parameter, 64-bit products; no
 * float, one 32-bit division per tangent and one per tick.
 */
#include "actions.h"

#include <stddef.h>

#include "check.h"
#include "xgo/config.h" /* XGO_TICK_HZ */

#if (XGO_TICK_HZ % 100u) != 0u
#error "actions: keyframe times are centiseconds; XGO_TICK_HZ must be a multiple of 100"
#endif
#define TICKS_PER_CS (XGO_TICK_HZ / 100u)
#define UNIT 1000 /* table unit (mm, degree) in um / mdeg */

/* ------------------------------------------------------------ channels */

enum {
    C_BX, C_BY, C_BZ, C_ROLL, C_PITCH, C_YAW,
    C_LFX, C_LFY, C_LFZ, /* leg 0, left front  */
    C_RFX, C_RFY, C_RFZ, /* leg 1, right front */
    C_RHX, C_RHY, C_RHZ, /* leg 2, right hind  */
    C_LHX, C_LHY, C_LHZ, /* leg 3, left hind   */
    C_COUNT
};

#define CH(c) (1ul << (c))
#define BIT(m, n) (((m) >> (n)) & 1u)
/* Channels in a mask, as a constant expression. */
#define NCH(m)                                                                                    \
    (BIT(m, 0) + BIT(m, 1) + BIT(m, 2) + BIT(m, 3) + BIT(m, 4) + BIT(m, 5) + BIT(m, 6) +          \
     BIT(m, 7) + BIT(m, 8) + BIT(m, 9) + BIT(m, 10) + BIT(m, 11) + BIT(m, 12) + BIT(m, 13) +      \
     BIT(m, 14) + BIT(m, 15) + BIT(m, 16) + BIT(m, 17))

/* dt in centiseconds, 1..255, stored in an int8 cell (read back as uint8). */
#define DT(cs) ((int8_t)((cs) > 127 ? (cs) - 256 : (cs)))

typedef struct action_s {
    const int8_t *frames; /* nframes x (1 + nch) cells */
#if XGO_WITH_NAMES
    const char *name;
#endif
    /* Bit fields: 12 bytes a row, not 16 (26 rows in flash). */
    unsigned mask : C_COUNT;  /* channels present */
    unsigned nch : 5;         /* channels in mask */
    unsigned loop_first : 3;  /* loop section, inclusive; reps 1 = no repeat */
    unsigned loop_last : 3;
    uint8_t nframes;
    uint8_t loop_reps;
    uint8_t seconds;          /* the vendor library's wait */
} action_t;

/* A table's size must be a whole number of keyframes (compile-time). */
#define CHECK_TABLE(t, m) typedef char t##_whole_frames[(sizeof(t) % (1u + NCH(m))) == 0u ? 1 : -1]

/* ------------------------------------------------------------ tables
 * Conventions (actions.h): x forward, y left, z up; roll + lifts the
 * left side, pitch + lowers the nose, yaw + turns left. Legs: LF RF RH LH. */

/* 1 lie down, 3 s: hind end down first, then the belly on the floor (the
 * hips 49 mm low: 48.6 mm above the ground; knees folded to -51 degrees,
 * hips at 88 of their 93), rest, back up. */
#define LIE_DOWN_CH (CH(C_BZ) | CH(C_PITCH))
static const int8_t k_lie_down[] = {
    /* dt       bz  pitch */
    DT(60),  -25,  -6,
    DT(50),  -49,   0,
    DT(80),  -49,   0,
    DT(110),   0,   0,
};
CHECK_TABLE(k_lie_down, LIE_DOWN_CH);

/* 2 stand up, 3 s: down to lying, front end up first, stand tall, settle. */
#define STAND_UP_CH (CH(C_BZ) | CH(C_PITCH))
static const int8_t k_stand_up[] = {
    /* dt      bz  pitch */
    DT(70), -49,   0,
    DT(30), -49,   0,
    DT(60), -15, -10,
    DT(60),  15,   0,
    DT(30),  15,   0,
    DT(50),   0,   0,
};
CHECK_TABLE(k_stand_up, STAND_UP_CH);

/* 3 creep, 5 s: the body 18 mm low (hips at 79.6 mm), then the walk gait
 * (one foot at a time, lifted 10 mm) forward at 60 mm/s for 2.5 s - 15 cm
 * (k_walks) - then up. The keyframes give the body; the gait the feet. */
#define CREEP_CH (CH(C_BZ))
static const int8_t k_creep[] = {
    /* dt      bz */
    DT(50),  -18, /* lower */
    DT(250), -18, /* crawl (k_walks: 0.5 .. 3 s) */
    DT(100), -18, /* the gait stops, feet home */
    DT(100),   0, /* up */
};
CHECK_TABLE(k_creep, CREEP_CH);

/* 4 circle, 5 s: the dog turns round on the spot - the trot turning at
 * 120 deg/s for 3 s, a full turn (k_walks) - then stands. */
#define CIRCLE_CH 0ul
static const int8_t k_circle[] = {
    DT(250),
    DT(250),
};
CHECK_TABLE(k_circle, CIRCLE_CH);

/* 5 step (mark time), 4 s: trot in place, diagonal pairs lift 20 mm
 * alternately, 0.5 s per cycle, eight cycles. */
#define STEP_CH (CH(C_LFZ) | CH(C_RFZ) | CH(C_RHZ) | CH(C_LHZ))
static const int8_t k_step[] = {
    /* dt     LFz RFz RHz LHz */
    DT(12),  20,  0, 20,  0, /* loop: LF + RH up */
    DT(13),   0,  0,  0,  0,
    DT(12),   0, 20,  0, 20, /* RF + LH up */
    DT(13),   0,  0,  0,  0,
};
CHECK_TABLE(k_step, STEP_CH);

/* 6 squat, 4 s: down to 77.5 mm and up to 109.5 mm, three and a half times. */
#define SQUAT_CH (CH(C_BZ))
static const int8_t k_squat[] = {
    /* dt      bz */
    DT(50), -20,
    DT(50),  12, /* loop */
    DT(50), -20,
    DT(50),   0,
};
CHECK_TABLE(k_squat, SQUAT_CH);

/* 7 roll, 4 s: +-18 degrees, two periods. */
#define ROLL_CH (CH(C_ROLL))
static const int8_t k_roll[] = {
    /* dt     roll */
    DT(50),   18,
    DT(100), -18,
    DT(100),  18,
    DT(100), -18,
    DT(50),    0,
};
CHECK_TABLE(k_roll, ROLL_CH);

/* 8 pitch, 4 s: +-18 degrees: k_roll's keyframes on the pitch channel
 * (one table in flash for both). */
#define PITCH_CH (CH(C_PITCH))

/* 9 yaw, 4 s: +-14 degrees. */
#define YAW_CH (CH(C_YAW))
static const int8_t k_yaw[] = {
    /* dt     yaw */
    DT(50),   14,
    DT(100), -14,
    DT(100),  14,
    DT(100), -14,
    DT(50),    0,
};
CHECK_TABLE(k_yaw, YAW_CH);

/* 10 three-axis rotation, 7 s: roll, pitch and yaw one after the other
 * (1.5 s each), then one 2.1 s cone (roll and pitch 12 degrees in
 * quadrature, yaw +-10 degrees at twice the rate). */
#define THREE_AXIS_CH (CH(C_ROLL) | CH(C_PITCH) | CH(C_YAW))
static const int8_t k_three_axis[] = {
    /* dt    roll pitch yaw */
    DT(40),  15,   0,   0,
    DT(70), -15,   0,   0,
    DT(40),   0,   0,   0,
    DT(40),   0,  15,   0,
    DT(70),   0, -15,   0,
    DT(40),   0,   0,   0,
    DT(40),   0,   0,  13,
    DT(70),   0,   0, -13,
    DT(40),   0,   0,   0,
    DT(30),   8,   8,  10, /* cone */
    DT(30),  12,   0,   0,
    DT(30),   8,  -8, -10,
    DT(30),   0, -12,   0,
    DT(30),  -8,  -8,  10,
    DT(30), -12,   0,   0,
    DT(30),  -8,   8, -10,
    DT(40),   0,   0,   0,
};
CHECK_TABLE(k_three_axis, THREE_AXIS_CH);

/* 11 pee, 7 s: weight to the right and forward, left hind foot up 35 mm
 * and out 10 mm, a little tremble, down. */
#define PEE_CH (CH(C_BX) | CH(C_BY) | CH(C_ROLL) | CH(C_LHX) | CH(C_LHY) | CH(C_LHZ))
static const int8_t k_pee[] = {
    /* dt      bx  by roll  LHx LHy LHz */
    DT(80),    5, -12,  6,   0,  0,  0,
    DT(80),    5, -12,  6,  -5, 10, 35,
    DT(20),    5, -12,  6,  -5, 11, 39, /* loop: tremble */
    DT(20),    5, -12,  6,  -5, 10, 35,
    DT(100),   5, -12,  6,   0,  0,  0,
    DT(120),   0,   0,  0,   0,  0,  0,
};
CHECK_TABLE(k_pee, PEE_CH);

/* 12 sit, 5 s: rump back and down, the front legs straight: the body 56 mm
 * back over the hind feet and 22 mm low, nose up 28 degrees - the rear hips
 * 40 mm above the ground, the front knees at 54 of their 57 degrees -
 * hold 2.2 s, up. The feet stay where they stand. */
#define SIT_CH (CH(C_BX) | CH(C_BZ) | CH(C_PITCH))
static const int8_t k_sit[] = {
    /* dt       bx  bz pitch */
    DT(60),  -25, -10, -12,
    DT(60),  -56, -22, -28,
    DT(220), -56, -22, -28,
    DT(160),   0,   0,   0,
};
CHECK_TABLE(k_sit, SIT_CH);

/* 13 beckon, 7 s: weight right and back, left front paw up 40 mm and
 * curled toward the body six times ("come here"). */
#define BECKON_CH (CH(C_BX) | CH(C_BY) | CH(C_ROLL) | CH(C_PITCH) | CH(C_LFX) | CH(C_LFZ))
static const int8_t k_beckon[] = {
    /* dt      bx   by roll pitch LFx LFz */
    DT(80),  -10, -10,  4,  -6,   0,  0,
    DT(60),  -10, -10,  4,  -6,  20, 40,
    DT(35),  -10, -10,  4,  -6,   8, 25, /* loop: curl */
    DT(35),  -10, -10,  4,  -6,  20, 40,
    DT(60),  -10, -10,  4,  -6,   0,  0,
    DT(80),    0,   0,  0,   0,   0,  0,
};
CHECK_TABLE(k_beckon, BECKON_CH);

/* 14 stretch, 10 s: play bow (body back, nose down 20 degrees), then the
 * other way (body forward, nose up 15 degrees), then the right hind leg
 * stretched back. */
#define STRETCH_CH (CH(C_BX) | CH(C_BY) | CH(C_BZ) | CH(C_PITCH) | CH(C_RHX) | CH(C_RHZ))
static const int8_t k_stretch[] = {
    /* dt       bx  by  bz pitch RHx RHz */
    DT(140),  -15,  0, -5,  18,   0,  0,
    DT(140),  -18,  0, -6,  20,   0,  0,
    DT(120),    8,  0,  0, -12,   0,  0,
    DT(120),   10,  0,  0, -14,   0,  0,
    DT(100),    0,  0,  0,   0,   0,  0,
    DT(80),     5, 12,  0,   0,   0,  0,
    DT(80),     5, 12,  0,   0, -18, 18,
    DT(100),    5, 12,  0,   0, -22, 20,
    DT(60),     5, 12,  0,   0,   0,  0,
    DT(60),     0,  0,  0,   0,   0,  0,
};
CHECK_TABLE(k_stretch, STRETCH_CH);

/* 15 wave, 6 s: weight right and back, the left front paw high (60 mm) and
 * forward, waved from side to side (+18 / -12 mm) five times - beckon keeps
 * its paw low and curls it toward the body instead. */
#define WAVE_CH                                                                                   \
    (CH(C_BX) | CH(C_BY) | CH(C_ROLL) | CH(C_PITCH) | CH(C_LFX) | CH(C_LFY) | CH(C_LFZ))
static const int8_t k_wave[] = {
    /* dt     bx   by roll pitch LFx LFy LFz */
    DT(60), -12, -12,  6,  -8,   0,   0,  0,
    DT(60), -12, -12,  6,  -8,  25,   0, 60,
    DT(35), -12, -12,  6,  -8,  25,  18, 60, /* loop: wave */
    DT(35), -12, -12,  6,  -8,  25, -12, 60,
    DT(50), -12, -12,  6,  -8,   0,   0,  0,
    DT(80),   0,   0,  0,   0,   0,   0,  0,
};
CHECK_TABLE(k_wave, WAVE_CH);

/* 16 sway, 6 s: body side to side +-16 mm, leaning 8 degrees into it. */
#define SWAY_CH (CH(C_BY) | CH(C_ROLL))
static const int8_t k_sway[] = {
    /* dt       by roll */
    DT(50),    16,  -8,
    DT(100),  -16,   8, /* loop */
    DT(100),   16,  -8,
    DT(100),  -16,   8,
    DT(50),     0,   0,
};
CHECK_TABLE(k_sway, SWAY_CH);

/* 17 beg for food, 4 s: sit (as 12) and raise both front paws to the chest
 * (40 mm up, 15 mm back), paddle them twice, down, up. */
#define BEG_CH                                                                                    \
    (CH(C_BX) | CH(C_BZ) | CH(C_PITCH) | CH(C_LFX) | CH(C_LFZ) | CH(C_RFX) | CH(C_RFZ))
static const int8_t k_beg[] = {
    /* dt       bx  bz pitch LFx LFz RFx RFz */
    DT(70),   -56, -22, -28,   0,  0,   0,  0,
    DT(40),   -56, -22, -30, -15, 40, -15, 40,
    DT(30),   -56, -22, -30, -12, 46, -12, 46, /* loop: paddle */
    DT(30),   -56, -22, -30, -15, 40, -15, 40,
    DT(40),   -56, -22, -28,   0,  0,   0,  0,
    DT(130),    0,   0,   0,   0,  0,   0,  0,
};
CHECK_TABLE(k_beg, BEG_CH);

/* 18 search for food, 6 s: nose down 15 degrees and forward, sweeping
 * left and right +-14 degrees. */
#define SEARCH_CH (CH(C_BX) | CH(C_BZ) | CH(C_PITCH) | CH(C_YAW))
static const int8_t k_search[] = {
    /* dt       bx  bz pitch yaw */
    DT(80),    10, -6,  15,   0,
    DT(80),    10, -6,  15,  14,
    DT(110),   10, -6,  15, -14,
    DT(110),   10, -6,  15,  14,
    DT(100),   10, -6,  15, -14,
    DT(60),    10, -6,  15,   0,
    DT(60),     0,  0,   0,   0,
};
CHECK_TABLE(k_search, SEARCH_CH);

/* 19 shake hands, 10 s: weight left and back, right front paw forward
 * 30 mm and up 40 mm, shaken six times, held, put down. */
#define SHAKE_CH (CH(C_BX) | CH(C_BY) | CH(C_ROLL) | CH(C_PITCH) | CH(C_RFX) | CH(C_RFZ))
static const int8_t k_shake[] = {
    /* dt      bx  by roll pitch RFx RFz */
    DT(80),  -10, 10,  -4,  -6,   0,  0,
    DT(80),  -10, 10,  -4,  -6,  30, 40,
    DT(50),  -10, 10,  -4,  -6,  30, 30, /* loop: shake */
    DT(50),  -10, 10,  -4,  -6,  30, 42,
    DT(60),  -10, 10,  -4,  -6,  30, 40,
    DT(90),  -10, 10,  -4,  -6,   0,  0,
    DT(90),    0,  0,   0,   0,   0,  0,
};
CHECK_TABLE(k_shake, SHAKE_CH);

/* 20 chicken head, 9 s: pecking, the body darts forward and down with the
 * nose dipping, eight times. */
#define CHICKEN_CH (CH(C_BX) | CH(C_BZ) | CH(C_PITCH))
static const int8_t k_chicken[] = {
    /* dt       bx  bz pitch */
    DT(40),    20, -5,   5, /* loop: peck */
    DT(60),   -10,  0,   0,
    DT(100),    0,  0,   0,
};
CHECK_TABLE(k_chicken, CHICKEN_CH);

/* 21 push-up, 8 s: front end down (nose down 14 degrees, 12 mm lower) and
 * up, seven times. */
#define PUSH_UP_CH (CH(C_BX) | CH(C_BZ) | CH(C_PITCH))
static const int8_t k_push_up[] = {
    /* dt       bx  bz pitch */
    DT(50),     8, -12, 14, /* loop */
    DT(50),     0,   4,  0,
    DT(100),    0,   0,  0,
};
CHECK_TABLE(k_push_up, PUSH_UP_CH);

/* 22 look around, 7 s: look up-left, head tilted; up-right, tilted the
 * other way; then down. */
#define LOOK_CH (CH(C_ROLL) | CH(C_PITCH) | CH(C_YAW))
static const int8_t k_look[] = {
    /* dt     roll pitch yaw */
    DT(80),    0,  -8,  14,
    DT(100),   6,  -8,  14,
    DT(120),   0,  -8, -14,
    DT(100),  -6,  -8, -14,
    DT(100),   0,  10,   0,
    DT(80),    0,  10,   0,
    DT(120),   0,   0,   0,
};
CHECK_TABLE(k_look, LOOK_CH);

/* 23 dance, 6 s: dip and lean left, tap the right front paw; lean right,
 * tap the left one; back to the middle; four bars of 1.5 s. */
#define DANCE_CH (CH(C_BY) | CH(C_BZ) | CH(C_ROLL) | CH(C_LFZ) | CH(C_RFZ))
static const int8_t k_dance[] = {
    /* dt      by   bz roll LFz RFz */
    DT(30),   10, -10,  -8,   0,  0, /* loop: one bar */
    DT(15),   10, -10,  -8,   0, 15,
    DT(15),   10, -10,  -8,   0,  0,
    DT(45),  -10, -10,   8,   0,  0,
    DT(15),  -10, -10,   8,  15,  0,
    DT(15),  -10, -10,   8,   0,  0,
    DT(15),    0,   0,   0,   0,  0,
};
CHECK_TABLE(k_dance, DANCE_CH);

/* 24 naughty, 7 s: play bow, then wiggle (yaw +-10, roll +-5) ten times. */
#define NAUGHTY_CH (CH(C_BX) | CH(C_BZ) | CH(C_ROLL) | CH(C_PITCH) | CH(C_YAW))
static const int8_t k_naughty[] = {
    /* dt       bx  bz roll pitch yaw */
    DT(80),   -12, -6,   0,  14,   0,
    DT(25),   -12, -6,   5,  14,  10, /* loop: wiggle */
    DT(25),   -12, -6,  -5,  14, -10,
    DT(120),    0,  0,   0,   0,   0,
};
CHECK_TABLE(k_naughty, NAUGHTY_CH);

/* 255 reset, 1 s: stand still (the board resets the registers). */
#define RESET_CH 0ul
static const int8_t k_reset[] = {
    DT(100),
};
CHECK_TABLE(k_reset, RESET_CH);

#if XGO_WITH_NAMES
#define ACTION_NAME_(nm) nm,
#else
#define ACTION_NAME_(nm)
#endif
#define ACTION(t, m, lf, ll, reps, secs, nm)                                                      \
    { t, ACTION_NAME_(nm) (m), NCH(m), (lf), (ll), (uint8_t)(sizeof(t) / (1u + NCH(m))), (reps), \
      (secs) }
#define NO_ACTION { NULL, ACTION_NAME_(NULL) 0u, 0u, 0u, 0u, 0u, 1u, 0u }

static const action_t k_actions[XGO_ACTION_LAST + 1u] = {
    NO_ACTION,
    ACTION(k_lie_down, LIE_DOWN_CH, 0, 0, 1, 3, "lie down"),
    ACTION(k_stand_up, STAND_UP_CH, 0, 0, 1, 3, "stand up"),
    ACTION(k_creep, CREEP_CH, 0, 0, 1, 5, "creep"),
    ACTION(k_circle, CIRCLE_CH, 0, 0, 1, 5, "circle"),
    ACTION(k_step, STEP_CH, 0, 3, 8, 4, "step"),
    ACTION(k_squat, SQUAT_CH, 1, 2, 3, 4, "squat"),
    ACTION(k_roll, ROLL_CH, 0, 0, 1, 4, "roll"),
    ACTION(k_roll, PITCH_CH, 0, 0, 1, 4, "pitch"),
    ACTION(k_yaw, YAW_CH, 0, 0, 1, 4, "yaw"),
    ACTION(k_three_axis, THREE_AXIS_CH, 0, 0, 1, 7, "three-axis rotation"),
    ACTION(k_pee, PEE_CH, 2, 3, 8, 7, "pee"),
    ACTION(k_sit, SIT_CH, 0, 0, 1, 5, "sit"),
    ACTION(k_beckon, BECKON_CH, 2, 3, 6, 7, "beckon"),
    ACTION(k_stretch, STRETCH_CH, 0, 0, 1, 10, "stretch"),
    ACTION(k_wave, WAVE_CH, 2, 3, 5, 6, "wave"),
    ACTION(k_sway, SWAY_CH, 1, 2, 2, 6, "sway"),
    ACTION(k_beg, BEG_CH, 2, 3, 2, 4, "beg for food"),
    ACTION(k_search, SEARCH_CH, 0, 0, 1, 6, "search for food"),
    ACTION(k_shake, SHAKE_CH, 2, 3, 6, 10, "shake hands"),
    ACTION(k_chicken, CHICKEN_CH, 0, 1, 8, 9, "chicken head"),
    ACTION(k_push_up, PUSH_UP_CH, 0, 1, 7, 8, "push-up"),
    ACTION(k_look, LOOK_CH, 0, 0, 1, 7, "look around"),
    ACTION(k_dance, DANCE_CH, 0, 6, 4, 6, "dance"),
    ACTION(k_naughty, NAUGHTY_CH, 1, 2, 10, 7, "naughty"),
};

static const action_t k_reset_action = ACTION(k_reset, RESET_CH, 0, 0, 1, 1, "reset");

static const action_t *lookup(uint8_t id)
{
    if (id == XGO_ACTION_RESET) {
        return &k_reset_action;
    }
    if (id == 0u || id > XGO_ACTION_LAST || k_actions[id].frames == NULL) {
        return NULL;
    }
    return &k_actions[id];
}

/* ------------------------------------------------------------ walking */

/* Actions that walk: while the keyframe time is within [from, until) cs the
 * gait follows the command (its speeds scaled like the keyframes' time
 * after a lead-in, so the distance and the turn stay what they are); the
 * keyframes give the body pose, the gait the feet. */
typedef struct walk_s {
    uint8_t id;
    uint8_t type;   /* register 0x09: 0 trot, 1 walk */
    uint8_t pace;   /* register 0x3D */
    uint8_t lift_mm; /* swing height, 0 = the gait's */
    int16_t vx_mm_s, vy_mm_s, vyaw_deg_s;
    uint16_t from_cs, until_cs;
} walk_t;

static const walk_t k_walks[] = {
    /* 15 cm forward, one foot at a time, feet lifted only 10 mm: the body is low */
    {XGO_ACTION_CREEP, 1u, 0u, 10u, 60, 0, 0, 50u, 300u},
    {XGO_ACTION_CIRCLE, 0u, 0u, 0u, 0, 0, 120, 10u, 310u}, /* 360 degrees */
};

static const walk_t *walk_of(uint8_t id)
{
    unsigned i;
    for (i = 0; i < sizeof k_walks / sizeof k_walks[0]; i++) {
        if (k_walks[i].id == id) {
            return &k_walks[i];
        }
    }
    return NULL;
}

/* ------------------------------------------------------------ sequence */

static unsigned loop_len(const action_t *a)
{
    return (unsigned)a->loop_last - a->loop_first + 1u;
}

/* Keyframes after expanding the loop. */
static unsigned virtual_count(const action_t *a)
{
    return a->nframes + loop_len(a) * (a->loop_reps - 1u);
}

/* Keyframe v (0 <= v < virtual_count) of the expanded sequence. */
static const int8_t *keyframe(const action_t *a, unsigned v)
{
    unsigned len = loop_len(a);
    unsigned extra = len * (a->loop_reps - 1u);
    unsigned f;
    if (v <= a->loop_last) {
        f = v;
    } else if (v <= a->loop_last + extra) {
        f = a->loop_first + (v - a->loop_last - 1u) % len;
    } else {
        f = v - extra;
    }
    return a->frames + f * (1u + a->nch);
}

static unsigned frame_cs(const int8_t *f)
{
    return (uint8_t)f[0];
}

/* ------------------------------------------------------------ curve */

/* Hermite tangent at a keyframe between the segments before (rise da over
 * ha cs) and after it (db over hb), scaled to a segment of hs cs, in
 * um/mdeg: hs * 2 (da/ha)(db/hb) / (da/ha + db/hb), 0 at a turning point.
 * |da|, |db| <= 255 and h <= 255 keep every product below 2^31. */
static int32_t tangent(int da, int db, unsigned ha, unsigned hb, unsigned hs)
{
    uint32_t ua, ub, num, den, m40;
    if (da == 0 || db == 0 || (da < 0) != (db < 0)) {
        return 0;
    }
    ua = (uint32_t)(da < 0 ? -da : da);
    ub = (uint32_t)(db < 0 ? -db : db);
    num = 80u * ua * ub * hs;      /* 40 x 2 x ...: result in 1/40 unit */
    den = ua * hb + ub * ha;
    m40 = (num + den / 2u) / den;
    return (int32_t)(m40 * (UNIT / 40)) * (da < 0 ? -1 : 1);
}

/* v / 2^16 rounded to nearest, for |v| < 2^46, without shifting a
 * negative number. */
static int32_t round_q16(int64_t v)
{
    const int64_t bias = (int64_t)1 << 46;
    return (int32_t)(((v + bias + 32768) >> 16) - (bias >> 16));
}

/* The pose field a channel drives: the channels are in the order of
 * xgo_pose_t's fields (body x, y, z, roll, pitch, yaw, then each foot's x,
 * y, z), all int32_t, so channel c is the c-th of them (checked below):
 * no switch in flash. */
typedef char pose_is_channels[sizeof(xgo_pose_t) == C_COUNT * sizeof(int32_t) &&
                                      offsetof(xgo_pose_t, body.yaw_mdeg) == C_YAW * sizeof(int32_t) &&
                                      offsetof(xgo_pose_t, feet_um[1].y) == C_RFY * sizeof(int32_t)
                                  ? 1
                                  : -1];

static int32_t *channel(xgo_pose_t *o, unsigned c)
{
    return (int32_t *)(void *)((char *)o + c * sizeof(int32_t));
}

static void zero_pose(xgo_pose_t *o)
{
    static const xgo_pose_t zero = {{0, 0, 0, 0, 0, 0}, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
    *o = zero;
}

/* Pose at t_q8 (1/256 tick) into virtual segment k (which runs from
 * keyframe k-1 to k; keyframe -1 is the zero pose at time 0). */
static void evaluate(const action_t *a, unsigned k, uint32_t t_q8, xgo_pose_t *out)
{
    unsigned nv = virtual_count(a);
    const int8_t *fa = k >= 2u ? keyframe(a, k - 2u) : NULL; /* keyframe k-2 */
    const int8_t *fb = k >= 1u ? keyframe(a, k - 1u) : NULL; /* k-1 */
    const int8_t *fc = keyframe(a, k);                       /* k */
    const int8_t *fd = k + 1u < nv ? keyframe(a, k + 1u) : NULL;
    unsigned hb = fb != NULL ? frame_cs(fb) : 0u; /* segment k-1 */
    unsigned hc = frame_cs(fc);                   /* segment k */
    unsigned hd = fd != NULL ? frame_cs(fd) : 0u; /* segment k+1 */
    uint32_t h = hc * TICKS_PER_CS;
    int64_t s = (int64_t)((t_q8 * 256u + h / 2u) / h); /* Q16, [0, 1] (rounded) */
    int64_t s2 = (s * s) >> 16;
    int64_t s3 = (s2 * s) >> 16;
    /* The Hermite basis, Q16: |h| <= 1 as s <= 1 (the keyframes of every
     * table add up to its duration, so t stays inside the last segment
     * too), so 32 bits hold it and the products below are 32 x 32 -> 64
     * (one instruction on an M3, less flash on both). */
    int32_t h01 = (int32_t)(3 * s2 - 2 * s3);
    int32_t h10 = (int32_t)(s3 - 2 * s2 + s);
    int32_t h11 = (int32_t)(s3 - s2);
    unsigned c, slot = 0;
    XGO_ASSERT(s <= 65536);
    zero_pose(out);
    for (c = 0; c < (unsigned)C_COUNT; ++c) {
        int va, vb, vc, vd;
        int32_t m1 = 0, m2 = 0;
        if (((a->mask >> c) & 1u) == 0u) {
            continue;
        }
        va = fa != NULL ? fa[1u + slot] : 0;
        vb = fb != NULL ? fb[1u + slot] : 0;
        vc = fc[1u + slot];
        vd = fd != NULL ? fd[1u + slot] : 0;
        if (fb != NULL) { /* keyframe k-1 is a real one: it may be passed through */
            m1 = tangent(vb - va, vc - vb, hb, hc, hc);
        }
        if (fd != NULL) { /* keyframe k is not the last */
            m2 = tangent(vc - vb, vd - vc, hc, hd, hc);
        }
        *channel(out, c) = vb * UNIT + round_q16((int64_t)((vc - vb) * UNIT) * h01 +
                                                 (int64_t)m1 * h10 + (int64_t)m2 * h11);
        ++slot;
    }
}

/* ------------------------------------------------------------ player */

#define LEAD_HELD 0xFFFFu

void xgo_action_init(xgo_action_player_t *p)
{
    p->id = 0u;
    p->seg = 0u;
    p->seg_start = 0u;
    p->elapsed = 0u;
    p->lead = 0u;
    p->scale_q16 = 65536u;
}

int xgo_action_start(xgo_action_player_t *p, uint8_t id)
{
    if (lookup(id) == NULL) {
        return 0;
    }
    xgo_action_init(p);
    p->id = id;
    return 1;
}

void xgo_action_hold(xgo_action_player_t *p)
{
    if (p->id != 0u && p->elapsed == 0u) {
        p->lead = LEAD_HELD;
    }
}

int xgo_action_held(const xgo_action_player_t *p)
{
    return p->id != 0u && p->lead == LEAD_HELD;
}

/* The keyframes (N ticks of them) play in the N - lead ticks left. */
void xgo_action_go(xgo_action_player_t *p)
{
    const uint32_t n = xgo_action_duration_ticks(p->id);
    if (!xgo_action_held(p)) {
        return;
    }
    p->lead = p->elapsed;
    p->scale_q16 = p->elapsed + 1u < n ? (n << 16) / (n - p->elapsed) : n << 16;
}

void xgo_action_stop(xgo_action_player_t *p)
{
    xgo_action_init(p);
}

int xgo_action_tick(xgo_action_player_t *p, xgo_pose_t *out)
{
    const action_t *a = lookup(p->id);
    uint32_t now_q8;
    unsigned nv;
    if (a == NULL || ++p->elapsed >= (uint32_t)a->seconds * XGO_TICK_HZ) {
        xgo_action_init(p); /* at the last keyframe: the zero pose, done */
        zero_pose(out);
        return 0;
    }
    if (p->lead == LEAD_HELD) {
        zero_pose(out); /* the board is still bringing the robot home */
        return 1;
    }
    /* keyframe time now: (elapsed - lead) * scale, in 1/256 tick */
    now_q8 = ((uint32_t)(p->elapsed - p->lead) * p->scale_q16) >> 8;
    nv = virtual_count(a);
    while (p->seg + 1u < nv &&
           now_q8 >= ((uint32_t)p->seg_start + frame_cs(keyframe(a, p->seg)) * TICKS_PER_CS) << 8) {
        p->seg_start = (uint16_t)(p->seg_start + frame_cs(keyframe(a, p->seg)) * TICKS_PER_CS);
        ++p->seg;
    }
    evaluate(a, p->seg, now_q8 - ((uint32_t)p->seg_start << 8), out);
    return 1;
}

int xgo_action_walk(const xgo_action_player_t *p, xgo_action_walk_t *w)
{
    const walk_t *k = walk_of(p->id);
    uint32_t now_q8;
    w->vx_um_s = w->vy_um_s = w->vyaw_mdeg_s = 0;
    if (k == NULL) {
        return 0;
    }
    w->type = k->type;
    w->pace = k->pace;
    w->step_height_um = (int32_t)k->lift_mm * 1000;
    if (p->lead == LEAD_HELD) {
        return 1;
    }
    now_q8 = ((uint32_t)(p->elapsed - p->lead) * p->scale_q16) >> 8;
    if (now_q8 >= ((uint32_t)k->from_cs * TICKS_PER_CS) << 8 && now_q8 < ((uint32_t)k->until_cs * TICKS_PER_CS) << 8) {
        /* x 1000 (um, mdeg) x scale / 2^16 */
        w->vx_um_s = (int32_t)(((int64_t)k->vx_mm_s * 1000 * p->scale_q16) >> 16);
        w->vy_um_s = (int32_t)(((int64_t)k->vy_mm_s * 1000 * p->scale_q16) >> 16);
        w->vyaw_mdeg_s = (int32_t)(((int64_t)k->vyaw_deg_s * 1000 * p->scale_q16) >> 16);
    }
    return 1;
}

uint8_t xgo_action_running(const xgo_action_player_t *p)
{
    return p->id;
}

uint32_t xgo_action_duration_ticks(uint8_t id)
{
    const action_t *a = lookup(id);
    return a != NULL ? (uint32_t)a->seconds * XGO_TICK_HZ : 0u;
}

const char *xgo_action_name(uint8_t id)
{
    const action_t *a = lookup(id);
#if XGO_WITH_NAMES
    return a != NULL ? a->name : NULL;
#else
    return a != NULL ? "" : NULL;
#endif
}

uint8_t xgo_action_next_in_cycle(uint8_t id)
{
    if (id < XGO_ACTION_CREEP || id >= XGO_ACTION_LAST) {
        return XGO_ACTION_CREEP;
    }
    return (uint8_t)(id + 1u);
}
