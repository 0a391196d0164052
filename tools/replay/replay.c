/*
 * replay.c - a capture into a fresh board (see replay.h).
 *
 * Time is virtual: before each record the board runs the control ticks up
 * to the record's tick (xgo-emu stamps every record with the board tick it
 * happened at; a capture without ticks, from a real robot's port, uses the
 * record's time / 2 ms), then the record's bytes are fed at its time. What
 * the board answers is appended to the replayed stream, what the capture
 * holds (sent or discarded) to the recorded one; both are compared as they
 * grow, and the first byte that differs ends the replay.
 */
#include <stdlib.h>
#include <string.h>

#include "replay.h"
#include "meaning.h"
#include "xgo/emulator.h"

#define XGO_REPLAY_TICK_US (1000000u / XGO_TICK_HZ)

/* ---- the settings note: "xgo-emu 0.1.0 profile=mini battery=100 ..." */

static int xgo_replay_hex_name(const char *hex, char name[XGO_BT_NAME_LEN])
{
    size_t i;
    for (i = 0; i < XGO_BT_NAME_LEN; i++) {
        char pair[3] = {hex[2 * i], hex[2 * i + 1], '\0'};
        char *end;
        if (pair[0] == '\0' || pair[1] == '\0') {
            return 0;
        }
        name[i] = (char)strtoul(pair, &end, 16);
        if (*end != '\0') {
            return 0;
        }
    }
    return 1;
}

static void xgo_replay_offsets(const char *text, int32_t out[XGO_SERVO_COUNT])
{
    size_t i;
    for (i = 0; i < XGO_SERVO_COUNT && *text != '\0'; i++) {
        char *end;
        out[i] = (int32_t)strtol(text, &end, 10);
        text = *end == ',' ? end + 1 : end;
    }
}

/* Applies one "key=value" of the note to the configuration being built. */
static void xgo_replay_setting(const char *kv, xgo_board_config_t *cfg, int32_t tilt[2],
                               xgo_board_nv_t *nv, int *has_nv)
{
    if (strncmp(kv, "profile=", 8) == 0 && xgo_host_model_by_name(kv + 8) >= 0) {
        cfg->model = (xgo_model_t)xgo_host_model_by_name(kv + 8);
    } else if (strncmp(kv, "battery=", 8) == 0) {
        cfg->battery_pct = (uint8_t)strtoul(kv + 8, NULL, 10);
    } else if (strncmp(kv, "timeout_ms=", 11) == 0) {
        cfg->parser_timeout_ms = (uint32_t)strtoul(kv + 11, NULL, 10);
    } else if (strncmp(kv, "ground_tilt_mdeg=", 17) == 0) {
        char *end;
        tilt[0] = (int32_t)strtol(kv + 17, &end, 10);
        tilt[1] = *end == ',' ? (int32_t)strtol(end + 1, NULL, 10) : 0;
    } else if (strncmp(kv, "bt_name_hex=", 12) == 0) {
        *has_nv |= xgo_replay_hex_name(kv + 12, nv->bt_name);
    } else if (strncmp(kv, "zero_offsets_mdeg=", 18) == 0) {
        xgo_replay_offsets(kv + 18, nv->zero_offset_mdeg);
    }
}

/* A fresh board as the capture's first note describes it (options win). */
static void xgo_replay_start(xgo_replay_t *r, const char *note, size_t n)
{
    xgo_board_config_t cfg;
    xgo_board_nv_t nv;
    int32_t tilt[2] = {0, 0};
    int has_nv = 0;
    char text[1024];
    char *tok, *save = NULL;
    xgo_board_default_config(&cfg);
    memset(&nv, 0, sizeof nv);
    snprintf(text, sizeof text, "%.*s", (int)(n < sizeof text ? n : sizeof text - 1), note);
    if (strncmp(text, "xgo-emu ", 8) == 0) {
        for (tok = strtok_r(text, " ", &save); tok != NULL; tok = strtok_r(NULL, " ", &save)) {
            xgo_replay_setting(tok, &cfg, tilt, &nv, &has_nv);
        }
    }
    if (r->opts.profile >= 0) {
        cfg.model = (xgo_model_t)r->opts.profile;
    }
    if (r->opts.battery >= 0) {
        cfg.battery_pct = (uint8_t)r->opts.battery;
    }
    xgo_board_init(&r->board, &cfg);
    xgo_board_set_ground_tilt(&r->board, tilt[0], tilt[1]);
    if (has_nv) {
        (void)xgo_board_set_nv(&r->board, &nv);
    }
    if (r->opts.trace) {
        xgo_host_trace_init(&r->trace, stderr, 0);
        xgo_board_set_trace(&r->board, xgo_host_trace_event, &r->trace);
    }
    r->started = 1;
}

/* ---- comparing */

static void xgo_replay_hex(FILE *out, const uint8_t *b, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        fprintf(out, i ? " %02X" : "%02X", b[i]);
    }
}

/* One side of the report: its bytes over the frame's span. */
static void xgo_replay_show_side(FILE *out, const char *label, const xgo_replay_stream_t *s,
                                 size_t start, size_t len)
{
    fprintf(out, "  %s ", label);
    if (start >= s->len) {
        fprintf(out, "nothing (the stream ends after %lu bytes)\n", (unsigned long)s->len);
        return;
    }
    xgo_replay_hex(out, s->bytes + start, s->len - start < len ? s->len - start : len);
    fprintf(out, "\n");
}

/* The frame around byte `at`: from the replay (the board's own, always
 * whole) or else the capture; a bare 16 bytes if neither has one. */
static void xgo_replay_span(const xgo_replay_t *r, size_t at, size_t *number, size_t *start,
                            size_t *len)
{
    if (xgo_replay_stream_frame(&r->replayed, at, number, start, len) ||
        xgo_replay_stream_frame(&r->recorded, at, number, start, len)) {
        return;
    }
    *start = at;
    *len = 16;
}

static void xgo_replay_report(const xgo_replay_t *r, FILE *out, size_t at)
{
    const xgo_replay_stream_t *where = at < r->recorded.len ? &r->recorded : &r->replayed;
    const xgo_replay_chunk_t *c = xgo_replay_stream_chunk(where, at);
    size_t number = 0, start = at, len = 16;
    xgo_replay_span(r, at, &number, &start, &len);
    fprintf(out, "xgo-replay: first difference at %lu.%06lu s (record %lu, board tick %lu), reply frame %lu, "
                 "reply byte %lu (byte %lu of the frame):\n",
            c ? (unsigned long)(c->t_us / 1000000u) : 0ul, c ? (unsigned long)(c->t_us % 1000000u) : 0ul,
            c ? c->record : 0ul, c ? (unsigned long)c->tick : 0ul, (unsigned long)number,
            (unsigned long)at, (unsigned long)(at - start));
    xgo_replay_show_side(out, "capture:", &r->recorded, start, len);
    xgo_replay_show_side(out, "replay: ", &r->replayed, start, len);
}

/* Compares what both streams hold now; 1 at the first difference. */
static int xgo_replay_compare(xgo_replay_t *r)
{
    size_t n = r->recorded.len < r->replayed.len ? r->recorded.len : r->replayed.len;
    for (; r->compared < n; r->compared++) {
        if (r->recorded.bytes[r->compared] != r->replayed.bytes[r->compared]) {
            r->differs = 1;
            return 1;
        }
    }
    return 0;
}

/* ---- feeding */

static void xgo_replay_ticks_to(xgo_replay_t *r, uint32_t target)
{
    while (r->ticks < target) {
        xgo_board_tick(&r->board);
        r->ticks++;
        if (r->recording) {
            xgo_host_record_tick(&r->record);
        }
    }
}

/* The board's replies so far, into the replayed stream. */
static int xgo_replay_take_replies(xgo_replay_t *r, const xgo_host_pcap_record_t *rec, uint64_t t_us)
{
    uint8_t out[512];
    size_t n;
    while ((n = xgo_board_transmit(&r->board, out, sizeof out)) > 0) {
        if (xgo_replay_stream_add(&r->replayed, out, n, rec->number, t_us, r->ticks) != 0) {
            return -1;
        }
    }
    return 0;
}

static int xgo_replay_record(xgo_replay_t *r, const xgo_host_pcap_record_t *rec)
{
    uint64_t t_us = rec->wall_us > r->origin_wall_us ? rec->wall_us - r->origin_wall_us : 0;
    uint32_t now_ms = (uint32_t)(t_us / 1000u);
    uint32_t tick = rec->tick != XGO_PCAP_TICK_UNKNOWN ? rec->tick : (uint32_t)(t_us / XGO_REPLAY_TICK_US);
    if (rec->dir == XGO_PCAP_NOTE) {
        return 0;
    }
    xgo_replay_ticks_to(r, tick);
    r->trace.now_us = t_us;
    xgo_board_poll(&r->board, now_ms);
    switch (rec->dir) {
    case XGO_PCAP_HOST_TO_BOARD:
        xgo_board_receive(&r->board, rec->bytes, rec->n, now_ms);
        return xgo_replay_take_replies(r, rec, t_us);
    case XGO_PCAP_BOARD_TO_HOST:
    case XGO_PCAP_DISCARDED:
        return xgo_replay_stream_add(&r->recorded, rec->bytes, rec->n, rec->number, t_us, tick);
    case XGO_PCAP_HANGUP:
        xgo_board_hangup(&r->board);
        return xgo_replay_take_replies(r, rec, t_us);
    default:
        return 0; /* a direction from a newer writer: not ours to judge */
    }
}

/* Starts the board at the first record (a note describes it, if any). */
static int xgo_replay_begin(xgo_replay_t *r, const xgo_host_pcap_record_t *rec)
{
    r->origin_wall_us = rec->wall_us;
    xgo_replay_start(r, rec->dir == XGO_PCAP_NOTE ? (const char *)rec->bytes : "",
                     rec->dir == XGO_PCAP_NOTE ? rec->n : 0);
    if (r->opts.record_path != NULL &&
        xgo_host_record_open(&r->record, r->opts.record_path, r->opts.record_hz, &r->board, r->err,
                             sizeof r->err) != 0) {
        return -1;
    }
    r->recording = r->opts.record_path != NULL;
    return 0;
}

static void xgo_replay_summary(const xgo_replay_t *r, FILE *out)
{
    uint32_t counters[XGO_DIAG_COUNT];
    xgo_board_counters(&r->board, counters);
    fprintf(out, "identical: %lu reply bytes to %lu requests, %lu records, %lu.%03lu s of board time "
                 "(%lu ticks)\n",
            (unsigned long)r->replayed.len, (unsigned long)counters[XGO_DIAG_FRAMES_OK], r->records,
            (unsigned long)(r->ticks / XGO_TICK_HZ),
            (unsigned long)(r->ticks % XGO_TICK_HZ * 1000u / XGO_TICK_HZ), (unsigned long)r->ticks);
}

/* Reads the capture through; 1 at a difference or a bad record. */
static int xgo_replay_records(xgo_replay_t *r, xgo_host_pcap_reader_t *reader, FILE *out)
{
    xgo_host_pcap_record_t rec;
    int got;
    while ((got = xgo_host_pcap_next(reader, &rec, r->err, sizeof r->err)) == 1) {
        r->records++;
        if (!r->started && xgo_replay_begin(r, &rec) != 0) {
            return -1;
        }
        if (xgo_replay_record(r, &rec) != 0) {
            snprintf(r->err, sizeof r->err, "out of memory at record %lu", rec.number);
            return -1;
        }
        if (xgo_replay_compare(r)) {
            xgo_replay_report(r, out, r->compared);
            return 1;
        }
    }
    if (got < 0) {
        fprintf(out, "xgo-replay: %s\n", r->err);
        return 1;
    }
    if (r->recorded.len != r->replayed.len) {
        xgo_replay_report(r, out, r->compared);
        return 1;
    }
    return 0;
}

int xgo_replay_run(xgo_replay_t *r, FILE *out)
{
    static xgo_host_pcap_reader_t reader;
    int rc;
    if (xgo_host_pcap_open(&reader, r->opts.capture, r->err, sizeof r->err) != 0) {
        fprintf(out, "xgo-replay: %s\n", r->err);
        return 1;
    }
    rc = xgo_replay_records(r, &reader, out);
    xgo_host_pcap_close_reader(&reader);
    if (rc == 0) {
        if (!r->started) {
            xgo_replay_start(r, "", 0); /* an empty capture: nothing to differ */
        }
        xgo_replay_summary(r, stdout);
    }
    if (r->recording && xgo_host_record_close(&r->record, out) != 0) {
        rc = rc == 0 ? -1 : rc;
    }
    if (r->opts.trace) {
        xgo_host_trace_flush(&r->trace);
    }
    return rc;
}
