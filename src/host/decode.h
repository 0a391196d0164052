/*
 * decode.h - what a register value means, in words, for --trace. Only the
 * host port needs this (the core stays free of strings it never sends).
 */
#ifndef XGO_HOST_DECODE_H
#define XGO_HOST_DECODE_H

#include <stddef.h>
#include <stdint.h>

/* Writes a short meaning of `value` written to register `addr` into out
 * ("+100%", "lie down", "unload leg 2", ...). Returns 0 and leaves out empty
 * when the raw value says it all. */
int xgo_host_decode_value(uint8_t addr, uint8_t value, char *out, size_t out_size);

#endif /* XGO_HOST_DECODE_H */
