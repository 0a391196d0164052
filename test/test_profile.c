/*
 * The robot models as data (src/core/profile.c): the vendor library's ranges
 * and the URDF geometry, each range well formed, and the one numbering of
 * legs, joints, servos and registers agreeing with the register table.
 */
#include <stdio.h>

#include "codec.h" /* XGO_RANGE_SPAN_LIMIT */
#include "unity.h"
#include "xgo/profile.h"
#include "xgo/regs.h"

void setUp(void) {}
void tearDown(void) {}

/* Where each leg is: x +1 front, y +1 left (LF, RF, RH, LH). */
static const int k_side[4][2] = {{1, 1}, {1, -1}, {-1, -1}, {-1, 1}};

static void test_profiles_and_numbering(void)
{
    const xgo_profile_t *m = xgo_profile_mini(), *l = xgo_profile_lite();
    int leg, j;
    TEST_ASSERT_EQUAL_PTR(m, xgo_profile_get(XGO_PROFILE_MINI));
    TEST_ASSERT_EQUAL_PTR(l, xgo_profile_get(XGO_PROFILE_LITE));
    TEST_ASSERT_EQUAL_PTR(m, xgo_profile_get(7));
    TEST_ASSERT_EQUAL_STRING("mini", m->name);
    TEST_ASSERT_EQUAL_STRING("lite", l->name);
    /* vendor library ranges */
    TEST_ASSERT_EQUAL_INT32(-73000, m->joint_mdeg[XGO_JOINT_KNEE].lo);
    TEST_ASSERT_EQUAL_INT32(57000, m->joint_mdeg[XGO_JOINT_KNEE].hi);
    TEST_ASSERT_EQUAL_INT32(-66000, m->joint_mdeg[XGO_JOINT_HIP].lo);
    TEST_ASSERT_EQUAL_INT32(93000, m->joint_mdeg[XGO_JOINT_HIP].hi);
    TEST_ASSERT_EQUAL_INT32(31000, m->joint_mdeg[XGO_JOINT_ABAD].hi);
    TEST_ASSERT_EQUAL_INT32(75000, m->foot_um[XGO_AXIS_Z].lo);
    TEST_ASSERT_EQUAL_INT32(115000, m->foot_um[XGO_AXIS_Z].hi);
    TEST_ASSERT_EQUAL_INT32(19500, m->body_um[XGO_AXIS_Y].hi);
    TEST_ASSERT_EQUAL_INT32(-70000, l->joint_mdeg[XGO_JOINT_KNEE].lo);
    TEST_ASSERT_EQUAL_INT32(90000, l->joint_mdeg[XGO_JOINT_HIP].hi);
    TEST_ASSERT_EQUAL_INT32(10000, l->body_mdeg[1].hi);
    TEST_ASSERT_EQUAL_INT32(59900, m->thigh_um);
    TEST_ASSERT_EQUAL_INT32(30988, m->abad_offset_um);
    /* every range is well formed, the stand height inside the body range */
    for (j = 0; j < 3; ++j) {
        TEST_ASSERT_TRUE(m->joint_mdeg[j].lo < m->joint_mdeg[j].hi);
        TEST_ASSERT_TRUE(l->foot_um[j].lo < l->foot_um[j].hi);
        TEST_ASSERT_TRUE(m->body_mdeg[j].lo < m->body_mdeg[j].hi);
    }
    TEST_ASSERT_TRUE(m->stand_height_um > m->body_um[2].lo && m->stand_height_um < m->body_um[2].hi);
    TEST_ASSERT_TRUE(l->stand_height_um > l->body_um[2].lo && l->stand_height_um < l->body_um[2].hi);
    /* numbering agrees with the register table */
    TEST_ASSERT_EQUAL_UINT(XGO_REG_LEG1_X, XGO_FOOT_REG(XGO_LEG_LF, XGO_AXIS_X));
    TEST_ASSERT_EQUAL_UINT(XGO_REG_LEG2_Y, XGO_FOOT_REG(XGO_LEG_RF, XGO_AXIS_Y));
    TEST_ASSERT_EQUAL_UINT(XGO_REG_LEG3_Z, XGO_FOOT_REG(XGO_LEG_RH, XGO_AXIS_Z));
    TEST_ASSERT_EQUAL_UINT(XGO_REG_LEG4_Z, XGO_FOOT_REG(XGO_LEG_LH, XGO_AXIS_Z));
    TEST_ASSERT_EQUAL_UINT(XGO_REG_SERVO11, XGO_SERVO_REG(XGO_LEG_LF, XGO_JOINT_KNEE));
    TEST_ASSERT_EQUAL_UINT(XGO_REG_SERVO22, XGO_SERVO_REG(XGO_LEG_RF, XGO_JOINT_HIP));
    TEST_ASSERT_EQUAL_UINT(XGO_REG_SERVO33, XGO_SERVO_REG(XGO_LEG_RH, XGO_JOINT_ABAD));
    TEST_ASSERT_EQUAL_UINT(XGO_REG_SERVO43, XGO_SERVO_REG(XGO_LEG_LH, XGO_JOINT_ABAD));
    TEST_ASSERT_EQUAL_UINT(11u, XGO_SERVO_ID(XGO_LEG_LF, XGO_JOINT_KNEE));
    TEST_ASSERT_EQUAL_UINT(43u, XGO_SERVO_ID(XGO_LEG_LH, XGO_JOINT_ABAD));
    for (leg = 0; leg < 4; ++leg) {
        TEST_ASSERT_EQUAL_INT(k_side[leg][0], xgo_leg_side_x((xgo_leg_t)leg));
        TEST_ASSERT_EQUAL_INT(k_side[leg][1], xgo_leg_side_y((xgo_leg_t)leg));
    }
}

static void check_ranges(const xgo_profile_t *p)
{
    int j;
    for (j = 0; j < XGO_AXIS_COUNT; ++j) {
        TEST_ASSERT_TRUE(p->joint_mdeg[j].lo < p->joint_mdeg[j].hi);
        TEST_ASSERT_TRUE(p->foot_um[j].lo < p->foot_um[j].hi);
        TEST_ASSERT_TRUE(p->body_um[j].lo < p->body_um[j].hi);
        TEST_ASSERT_TRUE(p->body_mdeg[j].lo < p->body_mdeg[j].hi);
    }
    /* symmetric where the board reads the register with a dead band at 0 */
    TEST_ASSERT_EQUAL_INT32(-p->body_um[XGO_AXIS_X].hi, p->body_um[XGO_AXIS_X].lo);
    TEST_ASSERT_EQUAL_INT32(-p->body_um[XGO_AXIS_Y].hi, p->body_um[XGO_AXIS_Y].lo);
    for (j = 0; j < 3; ++j) {
        TEST_ASSERT_EQUAL_INT32(-p->body_mdeg[j].hi, p->body_mdeg[j].lo);
    }
    TEST_ASSERT_EQUAL_INT32(10000, p->mark_time_um.lo);
    TEST_ASSERT_TRUE(p->mark_time_um.lo < p->mark_time_um.hi);
}

/* The register codec works in 32 bits because every range it maps spans
 * less than XGO_RANGE_SPAN_LIMIT units (codec.h). */
static void check_span(const xgo_range_t *r)
{
    TEST_ASSERT_TRUE(r->lo < r->hi);
    TEST_ASSERT_TRUE((uint32_t)(r->hi - r->lo) < XGO_RANGE_SPAN_LIMIT);
}

static void check_spans(const xgo_profile_t *p)
{
    int j;
    for (j = 0; j < 3; ++j) {
        check_span(&p->joint_mdeg[j]);
        check_span(&p->foot_um[j]);
        check_span(&p->body_um[j]);
        check_span(&p->body_mdeg[j]);
    }
    check_span(&p->mark_time_um);
    if (p->arm != NULL) {
        for (j = 0; j < XGO_ARM_JOINT_COUNT; ++j) {
            check_span(&p->arm->joint_mdeg[j]);
            check_span(&p->arm->read_mdeg[j]);
        }
        check_span(&p->arm->x_um);
        check_span(&p->arm->z_um);
        check_span(&p->arm->theta_mdeg);
        check_span(&p->arm->r_um);
    }
}

static void test_every_range_is_well_formed_and_mark_time_follows_the_vendor(void)
{
    check_ranges(xgo_profile_mini());
    check_ranges(xgo_profile_lite());
    check_spans(xgo_profile_mini());
    check_spans(xgo_profile_lite());
    check_spans(xgo_profile_mini2());
    /* vendor MARK_TIME_LIMIT: Mini 10..35 mm, Lite 10..25 mm */
    TEST_ASSERT_EQUAL_INT32(35000, xgo_profile_mini()->mark_time_um.hi);
    TEST_ASSERT_EQUAL_INT32(25000, xgo_profile_lite()->mark_time_um.hi);
}

/* Every servo and foot register the numbering macros name is the register
 * the table calls servoNN / legN_axis. */
static void test_numbering_names_the_registers_of_the_table(void)
{
    static const char axes[] = "xyz";
    char name[16];
    unsigned leg, j;
    for (leg = 0; leg < XGO_LEG_COUNT; ++leg) {
        for (j = 0; j < XGO_JOINT_COUNT; ++j) {
            snprintf(name, sizeof name, "servo%u", XGO_SERVO_ID(leg, j));
            TEST_ASSERT_EQUAL_STRING(name, xgo_reg_name((uint8_t)XGO_SERVO_REG(leg, j)));
            snprintf(name, sizeof name, "leg%u_%c", leg + 1u, axes[j]);
            TEST_ASSERT_EQUAL_STRING(name, xgo_reg_name((uint8_t)XGO_FOOT_REG(leg, j)));
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_profiles_and_numbering);
    RUN_TEST(test_every_range_is_well_formed_and_mark_time_follows_the_vendor);
    RUN_TEST(test_numbering_names_the_registers_of_the_table);
    return UNITY_END();
}
