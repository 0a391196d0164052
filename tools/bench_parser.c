/*
 * Parser throughput: a 1 MiB stream of mixed valid frames (writes of 1..30
 * bytes, legacy writes, read requests) through the whole board (parser,
 * register file, replies drained), repeated. Prints MB/s (wall clock, for
 * information) and the byte count, so instructions per byte come from
 * callgrind:  valgrind --tool=callgrind ./build/bench_parser 1
 * (instructions of xgo_board_receive / bytes fed).
 *
 * With "parser" the same stream goes to a bare xgo_parser_t whose sink only
 * counts frames: the parser's own cost (the budget in docs/mcu.md):
 *   valgrind --tool=callgrind --toggle-collect=xgo_parser_feed \
 *       --callgrind-out-file=/dev/null ./build/bench_parser 1 parser
 * (Collected / the bytes printed).
 *
 * Usage: bench_parser [passes [parser]]   (default 20 passes, whole board)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "board_io.h" /* xgo_test_xorshift32 */
#include "test_clock.h"
#include "xgo/board.h"

#define STREAM_BYTES (1u << 20)

static uint8_t stream[STREAM_BYTES + XGO_FRAME_MAX_LEN];

static uint32_t rng_state = 0x2545F491u;
static uint32_t rng(void)
{
    return xgo_test_xorshift32(&rng_state);
}

/* Mixed traffic like a host's: mostly short writes to motion registers,
 * some reads of joints and attitude. Returns the stream size. */
static size_t build_stream(size_t *frames)
{
    size_t len = 0;
    *frames = 0;
    while (len < STREAM_BYTES) {
        uint8_t data[32];
        uint8_t type, addr;
        size_t n, k;
        const uint32_t r = rng() % 10;
        if (r < 3) {
            static const uint8_t reads[][2] = {{0x50, 15}, {0x62, 4}, {0x01, 1}, {0x07, 10}};
            const uint8_t *pick = reads[rng() % 4];
            type = XGO_TYPE_READ;
            addr = pick[0];
            data[0] = pick[1];
            n = 1;
        } else {
            type = (r == 3) ? XGO_TYPE_WRITE_LEGACY : XGO_TYPE_WRITE;
            addr = (uint8_t)(0x30 + rng() % 9);
            n = 1 + rng() % 3;
            for (k = 0; k < n; k++) {
                data[k] = (uint8_t)rng();
            }
        }
        len += xgo_frame_encode(type, addr, data, n, &stream[len], sizeof stream - len);
        (*frames)++;
    }
    return len;
}

/* Wall-clock seconds (test/support/test_clock.h). */
static double now_s(void)
{
    return xgo_test_now_us_f() * 1e-6;
}

static size_t parsed_frames;

static void count_frame(void *ctx, const xgo_frame_t *frame)
{
    (void)ctx;
    (void)frame;
    parsed_frames++;
}

/* The parser alone, in the same 64-byte chunks. Returns 0 when every frame
 * was found. */
static int parser_only(size_t len, size_t frames, int passes)
{
    static xgo_parser_t parser;
    xgo_parser_sink_t sink = {count_frame, NULL, NULL};
    size_t pass, pos;
    double t0, dt;
    xgo_parser_init(&parser, &sink, 0);
    t0 = now_s();
    for (pass = 0; pass < (size_t)passes; pass++) {
        for (pos = 0; pos < len; pos += 64) {
            xgo_parser_feed(&parser, &stream[pos], len - pos < 64 ? len - pos : 64, 0);
        }
    }
    dt = now_s() - t0;
    printf("bench_parser: parser only, %zu bytes x %d passes, %zu frames/pass, %zu parsed\n", len,
           passes, frames, parsed_frames);
    printf("bench_parser: %.1f MB/s (wall clock, %.3f s); instructions/byte: run under callgrind\n",
           (double)len * passes / dt / 1e6, dt);
    return parsed_frames == frames * (size_t)passes ? 0 : 1;
}

int main(int argc, char **argv)
{
    static xgo_board_t board;
    uint8_t out[4096];
    size_t frames, len, pass, pos;
    int passes = argc > 1 ? atoi(argv[1]) : 20;
    uint32_t counters[XGO_DIAG_COUNT];
    double t0, dt;

    if (passes < 1) {
        fprintf(stderr, "usage: bench_parser [passes>=1 [parser]]\n");
        return 2;
    }
    len = build_stream(&frames);
    if (argc > 2 && strcmp(argv[2], "parser") == 0) {
        return parser_only(len, frames, passes);
    }
    xgo_board_init(&board, NULL);
    t0 = now_s();
    for (pass = 0; pass < (size_t)passes; pass++) {
        /* Host-like chunks of 64 bytes, replies drained after each. */
        for (pos = 0; pos < len; pos += 64) {
            size_t chunk = len - pos < 64 ? len - pos : 64;
            xgo_board_receive(&board, &stream[pos], chunk, 0);
            while (xgo_board_transmit(&board, out, sizeof out) > 0) {
            }
        }
    }
    dt = now_s() - t0;
    xgo_board_counters(&board, counters);
    printf("bench_parser: %zu bytes x %d passes, %zu frames/pass, frames_ok=%lu discarded=%lu\n",
           len, passes, frames, (unsigned long)counters[XGO_DIAG_FRAMES_OK],
           (unsigned long)counters[XGO_DIAG_BYTES_DISCARDED]);
    printf("bench_parser: %.1f MB/s (wall clock, %.3f s); instructions/byte: run under callgrind\n",
           (double)len * passes / dt / 1e6, dt);
    return counters[XGO_DIAG_FRAMES_OK] == frames * (size_t)passes ? 0 : 1;
}
