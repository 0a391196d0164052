/*
 * xgo/config.h - the build options of the portable core, in one place.
 *
 * Each option has its default here. Override one by defining it on the
 * compiler command line (-DXGO_TX_BUFFER_SIZE=512), with the same value for
 * the core and for every file that includes a core header: the options size
 * structs the caller owns.
 *
 * Macros, and the one hook an option asks the application for
 * (xgo_assert_failed); included by every public header that depends on an
 * option.
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
 * them. A reply is at most 255 bytes (a read of 247). A smaller ring answers
 * the reads whose reply fits it; a longer one is dropped whole and counted
 * (tx_overflow), as a reply that finds the ring full is. The firmware images
 * take 113: reads of up to 105 bytes (the vendor library's longest is 24,
 * the diagnostic block 60; docs/mcu.md "Build options"). 113, not less:
 * tools/mcu/run.sh reads the image 0x00..0xC3 in reads as long as the
 * buffer answers, and with 105 its second read still starts on no view. */
#ifndef XGO_TX_BUFFER_SIZE
#define XGO_TX_BUFFER_SIZE 1024u
#endif

/* Longest frame (its LEN byte, 9..255) the parser takes. The parser holds
 * the frame being received whole, because nothing is applied before its
 * checksum and tail are checked, so this sizes its buffer. A longer frame
 * is dropped as a bad length (counted in bad_length) and its bytes are
 * rescanned like any rejected candidate's. 255: every frame the protocol
 * allows; the firmware images take 24, writes of up to 16 bytes (docs/mcu.md
 * "Build options": the vendor library's writes are a few bytes each, a
 * Bluetooth name up to 10, the twelve joints 12; 231 bytes of RAM less). */
#ifndef XGO_PARSER_FRAME_MAX
#define XGO_PARSER_FRAME_MAX 255u
#endif

/* Default mid-frame silence (ms) after which the parser abandons a partial
 * frame (xgo_board_config_t.parser_timeout_ms overrides it per board). */
#ifndef XGO_PARSER_DEFAULT_TIMEOUT_MS
#define XGO_PARSER_DEFAULT_TIMEOUT_MS 20u
#endif

/* Define XGO_WIDE_MUL_SPLIT to compute 32x32->64-bit products from 16-bit
 * halves and use the divider-free loops on any target, as the core does on
 * ARMv6-M (a test aid: same results, docs/mcu.md). Off by default. */

/* Features a build may leave out (1 = built in, the default; 0 = compiled
 * out). The host build keeps them all; the firmware images (ports/) build the
 * board they stand for, a Mini on a real IMU, without them
 * (XGO_FIRMWARE_OPTIONS in CMakeLists.txt; docs/mcu.md "Build options"):
 *
 * XGO_WITH_LITE, XGO_WITH_MINI2: the Lite's and the Mini2's profiles (the
 *   Mini2's with its arm: src/core/arm.c). A model that is not built in is
 *   served as the Mini: xgo_profile_get() returns the Mini's profile, the
 *   board reads version 0x00 and firmware "M-..." and has no arm registers
 *   (their bytes are dropped and counted in ignored_unmapped, reads give 0,
 *   as on the Mini).
 * XGO_WITH_INERTIAL: the accelerometer and gyroscope model of the IMU block
 *   (0x65): without it they read 0 (a port feeds a real IMU's there).
 *   Attitude (0x62..0x64) stays: the heading and the self-levelling use it.
 * XGO_WITH_ODOMETRY: the world pose from the planted feet (an emulator's
 *   observer, xgo_board_world_pose): without it the pose stays 0, 0, 0.
 *   The inertial model needs it.
 * XGO_WITH_EMULATOR_INPUTS: the emulator's inputs to the IMU model, the
 *   ground's tilt and a shove (xgo/emulator.h: xgo_board_set_ground_tilt,
 *   xgo_board_push): without them those calls do nothing, the ground reads
 *   level (xgo_board_ground_tilt 0, 0) and the attitude is the body's own
 *   (a real board's IMU measures the world instead).
 * XGO_WITH_NAMES: the names of registers, actions and counters, for traces
 *   and tools (the register table's name field, xgo_reg_name,
 *   xgo_action_name, xgo_diag_name): without them the table has no name
 *   field and each of these returns "" where it would return a name.
 * XGO_WITH_TRACE: the board's trace hook (xgo_board_set_trace), an observer
 *   of every frame and drop for the emulator's --trace, captures and tests:
 *   without it xgo_board_set_trace does nothing and no event is formed; the
 *   drops are counted all the same (a firmware reports them through the
 *   diagnostic block, 0xC4). */
#ifndef XGO_WITH_LITE
#define XGO_WITH_LITE 1
#endif
#ifndef XGO_WITH_MINI2
#define XGO_WITH_MINI2 1
#endif
#ifndef XGO_WITH_INERTIAL
#define XGO_WITH_INERTIAL 1
#endif
#ifndef XGO_WITH_ODOMETRY
#define XGO_WITH_ODOMETRY 1
#endif
#ifndef XGO_WITH_NAMES
#define XGO_WITH_NAMES 1
#endif
#ifndef XGO_WITH_TRACE
#define XGO_WITH_TRACE 1
#endif
#ifndef XGO_WITH_EMULATOR_INPUTS
#define XGO_WITH_EMULATOR_INPUTS 1
#endif
#if XGO_WITH_INERTIAL && !XGO_WITH_ODOMETRY
#error "XGO_WITH_INERTIAL needs XGO_WITH_ODOMETRY (the body's path comes from it)"
#endif

/* Checks for caller bugs (XGO_ASSERT in the core): 1 = on, 0 = compiled out.
 * Only bugs are checked this way - a NULL board, a joint index past 11, a
 * board configured with a battery over 100 %, a path the code rules out.
 * Bad input from the wire is expected and never asserted: it is dropped,
 * counted and traced (each header says which of its checks is which).
 * Default: on unless NDEBUG is defined; the CMake build sets it for hosted
 * builds with XGO_ASSERTS (on at top level), so tests run with the checks. */
#ifndef XGO_ASSERT_ENABLED
#ifdef NDEBUG
#define XGO_ASSERT_ENABLED 0
#else
#define XGO_ASSERT_ENABLED 1
#endif
#endif

#if XGO_ASSERT_ENABLED
/* Called when a check fails; must not return into the core (abort, reset,
 * or stop in a debugger). The application provides it: on a hosted system
 * the CMake target xgo::core brings a default that prints the check to
 * stderr and calls abort() (src/host/assert_hosted.c; a definition of your
 * own takes precedence); on a microcontroller it is the port's hook, e.g.
 * log over a debug channel and reset (tools/mcu/mcu_selftest.c has one). */
void xgo_assert_failed(const char *file, int line, const char *expr);
#endif

#if XGO_TX_BUFFER_SIZE < 9u || XGO_TX_BUFFER_SIZE > 65535u
#error "XGO_TX_BUFFER_SIZE must hold a one-byte reply (9 bytes) and fit uint16_t"
#endif

#if XGO_PARSER_FRAME_MAX < 9u || XGO_PARSER_FRAME_MAX > 255u
#error "XGO_PARSER_FRAME_MAX must hold a read request (9 bytes) and be a LEN byte (<= 255)"
#endif

#endif /* XGO_CONFIG_H */
