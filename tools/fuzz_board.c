/*
 * Fuzz target for the parser + register file + board.
 *
 * Input layout: the first byte picks the chunk size pattern, the rest is the
 * byte stream the host sends; time advances 0..15 ms per chunk (from the
 * stream itself) so the silence timeout is exercised too. After every chunk
 * the target checks the board's promises and aborts on a broken one:
 *   - output is only whole, well-formed read replies (TYPE 0x12, good checksum
 *     and tail), never more replies than accepted read requests;
 *   - every byte fed is delivered in a frame, discarded or pending;
 *   - identity registers (version, firmware) never change; the mode and
 *     battery registers only ever hold documented values.
 *
 * Built with libFuzzer when the compiler is clang (fuzz_board), and always as
 * a replay driver (fuzz_board_replay FILE...) that runs saved inputs.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "xgo/board.h"

typedef struct {
    size_t accepted_bytes; /* bytes of frames the parser delivered */
    size_t reads;          /* accepted requests that are answered: reads, upgrade */
} fuzz_stats_t;

static void observe(void *ctx, const xgo_trace_event_t *ev)
{
    fuzz_stats_t *s = (fuzz_stats_t *)ctx;
    if (ev->frame == NULL || ev->kind == XGO_TRACE_TX || ev->reason == XGO_DROP_TX_OVERFLOW) {
        return;
    }
    s->accepted_bytes += ev->frame->len + XGO_FRAME_OVERHEAD;
    if (ev->frame->type == XGO_TYPE_READ ||
        (ev->kind == XGO_TRACE_RX && xgo_frame_asks_upgrade(ev->frame))) {
        s->reads++; /* a request that is answered */
    }
}

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "fuzz_board: broken promise: %s\n", what);
        abort();
    }
}

/* Walks the output: returns the number of replies, aborts on anything else. */
static size_t check_replies(const uint8_t *out, size_t n)
{
    size_t pos = 0, replies = 0;
    while (pos < n) {
        size_t len, k;
        check(n - pos >= 9, "truncated reply");
        len = out[pos + 2];
        check(out[pos] == 0x55 && out[pos + 1] == 0x00, "reply header");
        check(len >= 9 && pos + len <= n, "reply length");
        check(out[pos + 3] == XGO_TYPE_READ_REPLY, "reply type");
        k = len - XGO_FRAME_OVERHEAD;
        check(out[pos + 5 + k] == xgo_frame_checksum((uint8_t)len, out[pos + 3], out[pos + 4],
                                                     &out[pos + 5], k),
              "reply checksum");
        check(out[pos + len - 2] == 0x00 && out[pos + len - 1] == 0xAA, "reply tail");
        pos += len;
        replies++;
    }
    return replies;
}

/* One register as the board holds it (no frame, nothing counted). */
static uint8_t reg(const xgo_board_t *b, uint8_t addr)
{
    uint8_t v = 0;
    (void)xgo_board_read(b, addr, 1, &v);
    return v;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static xgo_board_t board; /* static: 2 KB, keeps the fuzzer's stack small */
    static uint8_t out[XGO_TX_BUFFER_SIZE];
    fuzz_stats_t stats;
    uint8_t identity[2];
    uint32_t now = 0;
    size_t pos = 1, replies = 0, fed = 0;
    uint32_t c[XGO_DIAG_COUNT];
    unsigned pattern;

    if (size < 1) {
        return 0;
    }
    pattern = data[0];
    memset(&stats, 0, sizeof stats);
    xgo_board_init(&board, NULL);
    xgo_board_set_trace(&board, observe, &stats);
    identity[0] = reg(&board, XGO_REG_VERSION);
    identity[1] = reg(&board, XGO_REG_FIRMWARE);

    while (pos < size) {
        size_t chunk = 1 + ((pattern + pos) % 37u);
        if (chunk > size - pos) {
            chunk = size - pos;
        }
        now += data[pos] & 0x0Fu;
        xgo_board_receive(&board, &data[pos], chunk, now);
        fed += chunk;
        pos += chunk;
        if ((pattern & 1u) != 0) {
            xgo_board_poll(&board, now + (data[pos - 1] & 0x1Fu));
        }
        if ((pattern & 2u) != 0) {
            xgo_board_tick(&board);
        }
        replies += check_replies(out, xgo_board_transmit(&board, out, sizeof out));
    }
    check(replies <= stats.reads, "unasked-for reply");
    xgo_board_counters(&board, c);
    check(fed == stats.accepted_bytes + c[XGO_DIAG_BYTES_DISCARDED] +
                     xgo_board_rx_pending(&board),
          "byte accounting");
    check(identity[0] == reg(&board, XGO_REG_VERSION) &&
              identity[1] == reg(&board, XGO_REG_FIRMWARE),
          "identity registers changed");
    check(reg(&board, XGO_REG_MODE) <= XGO_MODE_CALIBRATION &&
              reg(&board, XGO_REG_BATTERY) <= 100,
          "mode or battery out of range");
    return 0;
}

#ifndef XGO_LIBFUZZER
/* Replay driver: runs each file given, or a built-in seed set. */
int main(int argc, char **argv)
{
    static uint8_t buf[1 << 20];
    int i;
    if (argc < 2) {
        static const uint8_t seed[] = {0x03, 0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00,
                                       0xAA, 0x55, 0x00, 0x09, 0x00, 0x30, 0xFF, 0xC7, 0x00,
                                       0xAA, 0x55, 0x00, 0x40, 0x00};
        LLVMFuzzerTestOneInput(seed, sizeof seed);
        printf("fuzz_board_replay: built-in seed ok\n");
        return 0;
    }
    for (i = 1; i < argc; i++) {
        FILE *f = fopen(argv[i], "rb");
        size_t n;
        if (f == NULL) {
            fprintf(stderr, "fuzz_board_replay: cannot open %s\n", argv[i]);
            return 2;
        }
        n = fread(buf, 1, sizeof buf, f);
        fclose(f);
        LLVMFuzzerTestOneInput(buf, n);
    }
    printf("fuzz_board_replay: %d input(s) ok\n", argc - 1);
    return 0;
}
#endif
