/*
 * --trace words for register values (src/host/decode.c): the action names and
 * the unload set come from the core, so every preset the core plays has its
 * name in a trace (20..24 included) and the words follow the core's tables.
 */
#include <string.h>

#include "decode.h"
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

static void test_action_words_are_the_core_names_for_every_preset(void)
{
    unsigned id;
    TEST_ASSERT_EQUAL_STRING("default stance", words(XGO_REG_ACTION, 0));
    TEST_ASSERT_EQUAL_STRING("lie down", words(XGO_REG_ACTION, 1));
    TEST_ASSERT_EQUAL_STRING("shake hands", words(XGO_REG_ACTION, 19));
    TEST_ASSERT_EQUAL_STRING("chicken head", words(XGO_REG_ACTION, 20));
    TEST_ASSERT_EQUAL_STRING("naughty", words(XGO_REG_ACTION, 24));
    TEST_ASSERT_EQUAL_STRING("reset", words(XGO_REG_ACTION, 255));
    TEST_ASSERT_EQUAL_STRING("action 25", words(XGO_REG_ACTION, 25));
    for (id = 1; id <= XGO_ACTION_LAST; id++) {
        TEST_ASSERT_EQUAL_STRING(xgo_action_name((uint8_t)id), words(XGO_REG_ACTION, (uint8_t)id));
    }
}

static void test_unload_words_cover_the_register_set(void)
{
    unsigned v, valid = 0;
    TEST_ASSERT_EQUAL_STRING("all servos loaded", words(XGO_REG_UNLOAD, 0x00));
    TEST_ASSERT_EQUAL_STRING("unload all servos", words(XGO_REG_UNLOAD, 0x01));
    TEST_ASSERT_EQUAL_STRING("unload leg 1", words(XGO_REG_UNLOAD, 0x11));
    TEST_ASSERT_EQUAL_STRING("unload leg 4", words(XGO_REG_UNLOAD, 0x14));
    TEST_ASSERT_EQUAL_STRING("load leg 2", words(XGO_REG_UNLOAD, 0x22));
    TEST_ASSERT_EQUAL_STRING("load leg 4", words(XGO_REG_UNLOAD, 0x24));
    TEST_ASSERT_EQUAL_STRING("invalid", words(XGO_REG_UNLOAD, 0x15));
    TEST_ASSERT_EQUAL_STRING("invalid", words(XGO_REG_UNLOAD, 0x02));
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
    TEST_ASSERT_EQUAL_STRING("0%", words(XGO_REG_VX, 0x80));
    TEST_ASSERT_EQUAL_STRING("0%", words(XGO_REG_VX, 0x7F));
    TEST_ASSERT_EQUAL_STRING("+100%", words(XGO_REG_VX, 0xFF));
    TEST_ASSERT_EQUAL_STRING("-100%", words(XGO_REG_SERVO43, 0x00));
    TEST_ASSERT_EQUAL_STRING("slow_trot", words(XGO_REG_GAIT_TYPE, 3));
    TEST_ASSERT_EQUAL_STRING("invalid", words(XGO_REG_GAIT_TYPE, 4));
    TEST_ASSERT_EQUAL_STRING("off", words(XGO_REG_PERIOD_X, 0));
    TEST_ASSERT_EQUAL_STRING("", words(XGO_REG_PERIOD_X, 9)); /* the raw value says it all */
    TEST_ASSERT_EQUAL_STRING("", words(XGO_REG_BATTERY, 50));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_action_words_are_the_core_names_for_every_preset);
    RUN_TEST(test_unload_words_cover_the_register_set);
    RUN_TEST(test_centred_and_choice_words);
    return UNITY_END();
}
