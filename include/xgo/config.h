/*
 * xgo/config.h - the build options of the portable core, in one place.
 *
 * Each option has its default here. Override one by defining it on the
 * compiler command line (-DXGO_TX_BUFFER_SIZE=512), with the same value for
 * the core and for every file that includes a core header: the options size
 * structs the caller owns.
 *
 * Only macros; included by every public header that depends on an option.
 */
#ifndef XGO_CONFIG_H
#define XGO_CONFIG_H

/* Control loop rate in Hz: xgo_board_tick() is one period of 1/XGO_TICK_HZ s.
 * Not an option: the gait's cadence and step bounds, the velocity ramp and the
 * action timing are tuned and tested at 500 Hz (docs/decisions.md). Every
 * per-tick constant of the core is derived from this macro, so a change has
 * one place to start from. */
#define XGO_TICK_HZ 500u

/* Bytes of the board's transmit ring: replies wait there until the port drains
 * them. A reply is at most 255 bytes; smaller MCUs may go down to that. */
#ifndef XGO_TX_BUFFER_SIZE
#define XGO_TX_BUFFER_SIZE 1024u
#endif

/* Default mid-frame silence (ms) after which the parser abandons a partial
 * frame (xgo_board_config_t.parser_timeout_ms overrides it per board). */
#ifndef XGO_PARSER_DEFAULT_TIMEOUT_MS
#define XGO_PARSER_DEFAULT_TIMEOUT_MS 20u
#endif

/* Define XGO_WIDE_MUL_SPLIT to compute 32x32->64-bit products from 16-bit
 * halves and use the divider-free loops on any target, as the core does on
 * ARMv6-M (a test aid: same results, docs/mcu.md). Off by default. */

#if XGO_TX_BUFFER_SIZE < 255u || XGO_TX_BUFFER_SIZE > 65535u
#error "XGO_TX_BUFFER_SIZE must hold one whole reply (255 bytes) and fit uint16_t"
#endif

#endif /* XGO_CONFIG_H */
