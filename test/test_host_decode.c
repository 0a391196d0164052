/*
 * --trace words for register values (src/host/decode.c): the action names and
 * the unload set come from the core, so every preset the core plays has its
 * name in a trace (20..24 included) and the words follow the core's tables.
 */
#include <string.h>

#include "decode.h"
#include "trace.h"
#include "unity.h"
#include "actions.h"
#include "xgo/regs.h"

void setUp(void)
{
}

void tearDown(void)
{
}

static const char *words(uint8_t addr, uint8_t value)
{
    static char out[64];
    memset(out, 'x', sizeof out);
    if (!xgo_host_decode_value(addr, value, out, sizeof out)) {
        TEST_ASSERT_EQUAL_HEX8(0, out[0]);
        return "";
    }
    return out;
}

/* One register value and the words --trace shows for it ("" = none). */
typedef struct case_s {
    uint8_t addr, value;
    const char *words;
} case_t;

static void check_cases(const case_t *c, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        TEST_ASSERT_EQUAL_STRING(c[i].words, words(c[i].addr, c[i].value));
    }
}

static void test_action_words_are_the_core_names_for_every_preset(void)
{
    static const case_t cases[] = {
        {XGO_REG_ACTION, 0, "default stance"}, {XGO_REG_ACTION, 1, "lie down"},
        {XGO_REG_ACTION, 19, "shake hands"},   {XGO_REG_ACTION, 20, "chicken head"},
        {XGO_REG_ACTION, 24, "naughty"},       {XGO_REG_ACTION, 255, "reset"},
        {XGO_REG_ACTION, 25, "action 25"},
    };
    unsigned id;
    check_cases(cases, sizeof cases / sizeof cases[0]);
    for (id = 1; id <= XGO_ACTION_LAST; id++) {
        TEST_ASSERT_EQUAL_STRING(xgo_action_name((uint8_t)id), words(XGO_REG_ACTION, (uint8_t)id));
    }
}

static void test_unload_words_cover_the_register_set(void)
{
    static const case_t cases[] = {
        {XGO_REG_UNLOAD, 0x00, "all servos loaded"}, {XGO_REG_UNLOAD, 0x01, "unload all servos"},
        {XGO_REG_UNLOAD, 0x11, "unload leg 1"},      {XGO_REG_UNLOAD, 0x14, "unload leg 4"},
        {XGO_REG_UNLOAD, 0x22, "load leg 2"},        {XGO_REG_UNLOAD, 0x24, "load leg 4"},
        {XGO_REG_UNLOAD, 0x15, "invalid"},           {XGO_REG_UNLOAD, 0x02, "invalid"},
    };
    unsigned v, valid = 0;
    check_cases(cases, sizeof cases / sizeof cases[0]);
    /* exactly the values the register file accepts have words */
    for (v = 0; v < 256; v++) {
        const int has_words = strcmp(words(XGO_REG_UNLOAD, (uint8_t)v), "invalid") != 0;
        TEST_ASSERT_EQUAL_INT(xgo_reg_value_valid(xgo_reg_find(XGO_REG_UNLOAD), (uint8_t)v), has_words);
        valid += (unsigned)has_words;
    }
    TEST_ASSERT_EQUAL_UINT(10, valid);
}

static void test_centred_and_choice_words(void)
{
    static const case_t cases[] = {
        {XGO_REG_VX, 0x80, "0%"},          {XGO_REG_VX, 0x7F, "0%"},
        {XGO_REG_VX, 0xFF, "+100%"},       {XGO_REG_SERVO43, 0x00, "-100%"},
        {XGO_REG_GAIT_TYPE, 3, "slow_trot"}, {XGO_REG_GAIT_TYPE, 4, "invalid"},
        {XGO_REG_PERIOD_X, 0, "off"},      {XGO_REG_PERIOD_X, 9, ""}, /* the raw value says it all */
        {XGO_REG_BATTERY, 50, ""},
    };
    check_cases(cases, sizeof cases / sizeof cases[0]);
}

/* --trace names a register as the board's model has it: 0x5D is the
 * standing posture on the Mini, the arm's servo 52 on the Mini2. */
static void test_trace_names_registers_by_model(void)
{
    const uint8_t one = 1;
    xgo_frame_t f;
    xgo_trace_event_t ev;
    xgo_host_trace_t t;
    char line[256];
    memset(&ev, 0, sizeof ev);
    f.type = XGO_TYPE_WRITE;
    f.addr = 0x5D;
    f.len = 1;
    f.data = &one;
    ev.kind = XGO_TRACE_RX;
    ev.frame = &f;
    xgo_host_trace_init(&t, NULL, 0);
    xgo_host_trace_format(&t, &ev, line, sizeof line);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(line, "write 0x5D stand n=1 [01] stand=01(do it)"), line);
    t.arm = 1;
    xgo_host_trace_format(&t, &ev, line, sizeof line);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(line, "write 0x5D servo52 n=1 [01] servo52=01"), line);
    TEST_ASSERT_NULL_MESSAGE(strstr(line, "do it"), line);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_action_words_are_the_core_names_for_every_preset);
    RUN_TEST(test_unload_words_cover_the_register_set);
    RUN_TEST(test_centred_and_choice_words);
    RUN_TEST(test_trace_names_registers_by_model);
    return UNITY_END();
}
