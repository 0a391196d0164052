/*
 * host_port.c - the host variant of semihost.h and measure.h, so that the
 * same mcu_selftest.c runs natively: output to stdout, exit() for exit, and
 * the measuring stubs call the same functions and report 0.
 */
#include <stdio.h>
#include <stdlib.h>

#include "measure.h"
#include "semihost.h"

void sh_write0(const char *s)
{
    fputs(s, stdout);
}

void sh_exit(int code)
{
    fflush(stdout);
    exit(code);
}

int mcu_count_start(void)
{
    return 0;
}

uint32_t mcu_ticks_to_insns(uint32_t ticks)
{
    return ticks;
}

uint32_t mcu_ticks_empty(void)
{
    return 0;
}

uint32_t mcu_ticks_loop(uint32_t n)
{
    (void)n;
    return 0;
}

uint32_t mcu_ticks_tick(xgo_board_t *b)
{
    xgo_board_tick(b);
    return 0;
}

uint32_t mcu_ticks_receive(xgo_board_t *b, const uint8_t *bytes, size_t n, uint32_t now_ms)
{
    xgo_board_receive(b, bytes, n, now_ms);
    return 0;
}

uint32_t mcu_ticks_transmit(xgo_board_t *b, uint8_t *out, size_t max)
{
    (void)xgo_board_transmit(b, out, max);
    return 0;
}

uint32_t mcu_stack_used(void)
{
    return 0;
}

uint32_t mcu_stack_free_min(void)
{
    return 0;
}

uintptr_t mcu_stack_probe_begin(void)
{
    return 0;
}

uint32_t mcu_stack_probe_end(uintptr_t mark)
{
    (void)mark;
    return 0;
}
