/*
 * profile.c - the Mini, Lite and Mini2 profiles (sources of every number:
 * docs/geometry.md); the leg numbering helpers are inline in xgo/profile.h.
 */
#include "xgo/profile.h"

#include "xgo/config.h" /* XGO_WITH_LITE, XGO_WITH_MINI2 */

#include <stddef.h>

/* Leg geometry of the Mini, from the vendor-derived mini2 URDF
 * (sskorol/xgo_ros urdf/mini2_description.urdf):
 *   thigh 0.0599 m (joint 11 origin), abduction offset 0.030988 m (joint 12
 *   origin), foot at (0.001, 0.075988) m from the knee at x1 = 0, i.e. a
 *   75.995 mm shank line 0.754 degrees past the right angle. */
#define MINI_THIGH_UM XGO_MINI_THIGH_UM /* 59900 */
#define MINI_SHANK_UM XGO_MINI_SHANK_UM /* 75995 */
#define MINI_KNEE_OFFSET_MDEG XGO_MINI_KNEE_OFFSET_MDEG /* 754 */
#define MINI_ABAD_OFFSET_UM 30988
#define MINI_HIP_X_UM 75000
#define MINI_HIP_Y_UM 22500
#define MINI_LEG_GEOMETRY                                                                \
    MINI_THIGH_UM, MINI_SHANK_UM, MINI_KNEE_OFFSET_MDEG, MINI_ABAD_OFFSET_UM, MINI_HIP_X_UM, \
        MINI_HIP_Y_UM

/* The Mini's outline, standing height and register ranges (the Mini2 shares
 * them: the vendor library picks its Mini parameter set for both). */
#define MINI_OUTLINE_AND_RANGES                                                  \
    250000, /* product page: 250 x 150 x 60 mm */                              \
        150000, 97500, /* middle of the body-height register range 75..120 mm */ \
        /* vendor library changePara('xgomini'): x1, x2, x3 */                  \
        {{-73000, 57000}, {-66000, 93000}, {-31000, 31000}},                     \
        /* foot x, y, z */                                                       \
        {{-35000, 35000}, {-18000, 18000}, {75000, 115000}},                     \
        /* body x, y, z */                                                       \
        {{-35000, 35000}, {-19500, 19500}, {75000, 120000}},                     \
        /* body roll, pitch, yaw */                                              \
        {{-20000, 20000}, {-22000, 22000}, {-16000, 16000}},                     \
        /* mark time step height */                                              \
        {10000, 35000}

static const xgo_profile_t mini_profile = {
    "mini",
    MINI_LEG_GEOMETRY,
    MINI_OUTLINE_AND_RANGES,
    NULL,
};

#if XGO_WITH_LITE
/* No public kinematic model of the Lite exists: its link geometry is
 * ASSUMED equal to the Mini's (docs/geometry.md); its ranges are the vendor
 * library's Lite set. */
static const xgo_profile_t lite_profile = {
    "lite",
    MINI_LEG_GEOMETRY,
    250000,
    150000,
    85000, /* middle of the body-height register range 60..110 mm */
    {{-70000, 50000}, {-70000, 90000}, {-30000, 30000}},
    {{-25000, 25000}, {-18000, 18000}, {60000, 110000}},
    {{-25000, 25000}, {-18000, 18000}, {60000, 110000}},
    {{-20000, 20000}, {-10000, 10000}, {-12000, 12000}},
    {10000, 25000},
    NULL,
};
#endif

#if XGO_WITH_MINI2
/* The Mini2's arm. Link lengths and zero offsets: the vendor library's own
 * model of it (xgolib 1.1.10 XGO_DOG: arm_init(60, 60) and its offsets
 * offset1 - 3, offset2 - 11 for servos 53 and 52; arm_pos_update's angle
 * conventions). Limits and written bytes: its servo_set_angle table
 * (param_lt, bytes 1..255); read-back bytes: its MOTOR_LIMIT[3..5]
 * (read_motor). Command ranges: its ARM_LIMIT. Where the arm sits: the
 * shoulder joint 53 of the mini2 URDF the legs come from, (0.081751, 0,
 * 0.037854) m from base_link. */
static const xgo_arm_geometry_t mini2_arm = {
    81751,
    37854,
    60000,
    60000,
    {0, -11000, -3000},
    /* claw 51, elbow 52, shoulder 53 */
    {{-65000, 65000}, {-50000, 83000}, {-90000, 90000}},
    {{-65000, 65000}, {-85000, 50000}, {-75000, 90000}},
    {-80000, 155000},  /* x */
    {-95000, 155000},  /* z */
    {70000, 270000},   /* theta */
    {80000, 140000},   /* r */
};

/* The Mini2 (the vendor library's xgomini2sw, firmware 'W'): the Mini's
 * legs and ranges (the library picks its Mini parameter set for it) plus
 * the arm. */
static const xgo_profile_t mini2_profile = {
    "mini2",
    MINI_LEG_GEOMETRY,
    MINI_OUTLINE_AND_RANGES,
    &mini2_arm,
};
#endif

const xgo_profile_t *xgo_profile_mini(void)
{
    return &mini_profile;
}

#if XGO_WITH_LITE
const xgo_profile_t *xgo_profile_lite(void)
{
    return &lite_profile;
}
#endif

#if XGO_WITH_MINI2
const xgo_profile_t *xgo_profile_mini2(void)
{
    return &mini2_profile;
}
#endif

int xgo_profile_built_in(unsigned model)
{
    return model == XGO_PROFILE_MINI || (model == XGO_PROFILE_LITE && XGO_WITH_LITE) ||
           (model == XGO_PROFILE_MINI2 && XGO_WITH_MINI2);
}

const xgo_profile_t *xgo_profile_get(unsigned model)
{
#if XGO_WITH_LITE
    if (model == XGO_PROFILE_LITE) {
        return &lite_profile;
    }
#endif
#if XGO_WITH_MINI2
    if (model == XGO_PROFILE_MINI2) {
        return &mini2_profile;
    }
#endif
    (void)model;
    return &mini_profile;
}
