/* capture.c - xgo-emu --capture (see capture.h). */
#include "capture.h"

#include <errno.h>
#include <string.h>

#include "clock.h"
#include "options.h"

/* The board tick now: what xgo-replay runs its fresh board up to. */
static uint32_t xgo_host_capture_tick(const xgo_host_capture_t *c)
{
    return (uint32_t)((uint64_t)xgo_board_time_ms(c->board) * XGO_TICK_HZ / 1000u);
}

static void xgo_host_capture_on_line(void *ctx, int what, const uint8_t *bytes, size_t n)
{
    xgo_host_capture_t *c = ctx;
    if (n == 0 && what != XGO_HOST_LINE_HANGUP) {
        return;
    }
    if (c->pcap.failed) {
        return; /* reported once; the emulator keeps serving */
    }
    if (what == XGO_HOST_LINE_HANGUP) {
        (void)xgo_host_pcap_event(&c->pcap, xgo_host_clock_us(), XGO_PCAP_HANGUP,
                                  xgo_host_capture_tick(c));
    } else {
        (void)xgo_host_pcap_write(&c->pcap, xgo_host_clock_us(), (xgo_pcap_dir_t)what,
                                  xgo_host_capture_tick(c), bytes, n);
    }
    if (c->pcap.failed && !c->reported) {
        c->reported = 1;
        fprintf(stderr, "xgo-emu: capture %s: %s; capturing stopped\n", c->path, strerror(errno));
    }
}

/* "xgo-emu 0.1.0 profile=mini battery=100 timeout_ms=20 ground_tilt_mdeg=0,0
 * bt_name_hex=58474F... zero_offsets_mdeg=0,0,...": what a board needs to be
 * this one at tick 0. */
static void xgo_host_capture_settings(const xgo_board_t *b, char *out, size_t size)
{
    xgo_board_nv_t nv;
    int32_t roll, pitch;
    size_t len, i;
    xgo_board_get_nv(b, &nv);
    xgo_board_ground_tilt(b, &roll, &pitch);
    len = (size_t)snprintf(out, size,
                           "xgo-emu %s profile=%s battery=%u timeout_ms=%lu ground_tilt_mdeg=%ld,%ld "
                           "bt_name_hex=",
                           XGO_EMU_VERSION, xgo_profile_get((unsigned)b->config.model)->name,
                           (unsigned)b->config.battery_pct, (unsigned long)b->config.parser_timeout_ms,
                           (long)roll, (long)pitch);
    for (i = 0; i < XGO_BT_NAME_LEN && len + 3 < size; i++) {
        len += (size_t)snprintf(out + len, size - len, "%02X", (unsigned char)nv.bt_name[i]);
    }
    len += (size_t)snprintf(out + len, size - len, " zero_offsets_mdeg=");
    for (i = 0; i < XGO_SERVO_COUNT && len + 13 < size; i++) {
        len += (size_t)snprintf(out + len, size - len, i ? ",%ld" : "%ld", (long)nv.zero_offset_mdeg[i]);
    }
}

int xgo_host_capture_open(xgo_host_capture_t *c, const char *path, const xgo_board_t *board,
                          char *err, size_t err_size)
{
    char note[512];
    uint64_t now = xgo_host_clock_us();
    memset(c, 0, sizeof *c);
    c->path = path;
    c->board = board;
    if (xgo_host_pcap_create(&c->pcap, path, now, err, err_size) != 0) {
        return -1;
    }
    xgo_host_capture_settings(board, note, sizeof note);
    if (xgo_host_pcap_note(&c->pcap, now, note) != 0) {
        snprintf(err, err_size, "cannot write capture %s: %s", path, strerror(errno));
        xgo_host_pcap_close(&c->pcap);
        return -1;
    }
    c->service.on_line = xgo_host_capture_on_line;
    c->service.ctx = c;
    return 0;
}

int xgo_host_capture_close(xgo_host_capture_t *c, FILE *out)
{
    int failed = c->pcap.failed;
    xgo_host_pcap_close(&c->pcap);
    if (failed) {
        fprintf(out, "xgo-emu: capture %s is incomplete (a write failed)\n", c->path);
        return -1;
    }
    return 0;
}
