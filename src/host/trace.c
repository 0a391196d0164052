/* trace.c - one human-readable line per frame (see trace.h). */
#include "trace.h"

#include <stdarg.h>
#include <string.h>

#include "decode.h"

/* A bounded line being built: appends past the end are cut off, never
 * overflow. */
typedef struct xgo_host_line_s {
    char *buf;
    size_t size;
    size_t len;
    int arm; /* name registers as on the Mini2 (xgo_reg_find_model) */
} xgo_host_line_t;

static void xgo_host_line_add(xgo_host_line_t *l, const char *fmt, ...)
{
    va_list ap;
    int n;
    if (l->len + 1 >= l->size) {
        return;
    }
    va_start(ap, fmt);
    n = vsnprintf(l->buf + l->len, l->size - l->len, fmt, ap);
    va_end(ap);
    if (n > 0) {
        l->len += (size_t)n;
        if (l->len >= l->size) {
            l->len = l->size - 1;
        }
    }
}

static void xgo_host_line_hex(xgo_host_line_t *l, const uint8_t *bytes, size_t n)
{
    size_t i;
    xgo_host_line_add(l, "[");
    for (i = 0; i < n; i++) {
        xgo_host_line_add(l, i == 0 ? "%02X" : " %02X", bytes[i]);
    }
    xgo_host_line_add(l, "]");
}

/* "vx", "bt_name", "bt_name[3]" (inside a multi-byte register), or "-" for
 * an address the Mini lacks. */
static void xgo_host_line_reg(xgo_host_line_t *l, uint8_t addr)
{
    const xgo_reg_desc_t *d = xgo_reg_find_model(addr, l->arm);
    if (d == NULL) {
        xgo_host_line_add(l, "-");
    } else if (addr != d->addr) {
        xgo_host_line_add(l, "%s[%u]", d->name, (unsigned)(addr - d->addr));
    } else {
        xgo_host_line_add(l, "%s", d->name);
    }
}

/* "write 0x30 vx n=1 [FF]": the frame as received or sent. */
static void xgo_host_line_frame(xgo_host_line_t *l, const xgo_frame_t *f)
{
    const char *type;
    switch (f->type) {
    case XGO_TYPE_WRITE:
        type = "write";
        break;
    case XGO_TYPE_WRITE_LEGACY:
        type = "write(legacy 0x01)";
        break;
    case XGO_TYPE_READ:
        type = "read";
        break;
    case XGO_TYPE_READ_REPLY:
        type = "reply";
        break;
    default:
        type = "type?";
        break;
    }
    xgo_host_line_add(l, "%s 0x%02X ", type, f->addr);
    xgo_host_line_reg(l, f->addr);
    if (f->type == XGO_TYPE_READ) {
        xgo_host_line_add(l, " n=%u", (unsigned)f->data[0]);
        return;
    }
    xgo_host_line_add(l, " n=%u ", (unsigned)f->len);
    xgo_host_line_hex(l, f->data, f->len);
}

static int xgo_host_is_ascii_reg(const xgo_reg_desc_t *d)
{
    return d != NULL && d->valid == XGO_VALID_ASCII;
}

/* The meaning of each written byte: "vx=FF(+100%) vy=80(0%)". A run of
 * bytes into a text register (bt_name) reads better as a string. */
static void xgo_host_line_write_meaning(xgo_host_line_t *l, const xgo_frame_t *f, uint8_t unmapped)
{
    size_t i = 0;
    if (unmapped == f->len) {
        xgo_host_line_add(l, " ignored (not on the Mini)");
        return;
    }
    while (i < f->len) {
        uint8_t addr = (uint8_t)(f->addr + i);
        const xgo_reg_desc_t *d = xgo_reg_find_model(addr, l->arm);
        char meaning[48];

        if (xgo_host_is_ascii_reg(d)) {
            xgo_host_line_add(l, " %s=\"", d->name);
            while (i < f->len && xgo_reg_find_model((uint8_t)(f->addr + i), l->arm) == d) {
                uint8_t c = f->data[i];
                xgo_host_line_add(l, (c >= 0x20u && c < 0x7Fu && c != '"' && c != '\\') ? "%c"
                                                                                      : "\\x%02X",
                                  c);
                i++;
            }
            xgo_host_line_add(l, "\"");
            continue;
        }
        if (addr == XGO_REG_TURN_TO && i + 1u < f->len) {
            /* two bytes, one heading (int16 big-endian): 0x40 is not written */
            const int heading = (int16_t)(uint16_t)(f->data[i] << 8 | f->data[i + 1u]);
            xgo_host_line_add(l, " turn_to=%02X%02X(%+d deg)", f->data[i], f->data[i + 1u],
                              heading);
            i += 2;
            continue;
        }
        if (d == NULL) {
            xgo_host_line_add(l, " 0x%02X=%02X(ignored, not on the Mini)", addr, f->data[i]);
            i++;
            continue;
        }
        xgo_host_line_add(l, " ");
        xgo_host_line_reg(l, addr);
        /* the words are the Mini's registers' (0x5D on the Mini2 is a servo) */
        if (d == xgo_reg_find(addr) && xgo_host_decode_value(addr, f->data[i], meaning, sizeof meaning)) {
            xgo_host_line_add(l, "=%02X(%s)", f->data[i], meaning);
        } else {
            xgo_host_line_add(l, "=%02X", f->data[i]);
        }
        i++;
    }
}

/* Little-endian float32 at p, as the vendor library decodes roll/pitch/yaw. */
static float xgo_host_le_float(const uint8_t *p)
{
    uint32_t bits = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                    (uint32_t)p[3] << 24;
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* Replies whose bytes are not self-explanatory: the firmware string, the
 * float angles, the battery. */
static void xgo_host_line_reply_meaning(xgo_host_line_t *l, const xgo_frame_t *f)
{
    if (f->addr == XGO_REG_FIRMWARE) {
        size_t i;
        xgo_host_line_add(l, " firmware=\"");
        for (i = 0; i < f->len && i < XGO_FIRMWARE_LEN && f->data[i] != 0; i++) {
            uint8_t c = f->data[i];
            xgo_host_line_add(l, (c >= 0x20u && c < 0x7Fu) ? "%c" : "\\x%02X", c);
        }
        xgo_host_line_add(l, "\"");
    } else if (f->addr >= XGO_REG_IMU_ROLL && f->addr <= XGO_REG_IMU_YAW && f->len >= 4) {
        xgo_host_line_add(l, " %s=%.3f deg", xgo_reg_name(f->addr),
                          (double)xgo_host_le_float(f->data));
    } else if (f->addr == XGO_REG_BATTERY) {
        xgo_host_line_add(l, " battery=%u%%", (unsigned)f->data[0]);
    }
}

void xgo_host_trace_init(xgo_host_trace_t *t, FILE *out, uint64_t origin_us)
{
    memset(t, 0, sizeof *t);
    t->out = out;
    t->origin_us = origin_us;
    t->now_us = origin_us;
}

/* "   1.234567 ": seconds since start. */
static void xgo_host_line_time(xgo_host_line_t *l, const xgo_host_trace_t *t, uint64_t at_us)
{
    uint64_t since = at_us >= t->origin_us ? at_us - t->origin_us : 0;
    xgo_host_line_add(l, "%4lu.%06lu ", (unsigned long)(since / 1000000u),
                      (unsigned long)(since % 1000000u));
}

/* "drop noise n=86 [68 65 6C ... ...]": the first bytes, "..." for more. */
static void xgo_host_line_noise(xgo_host_line_t *l, const uint8_t *head, size_t shown,
                                unsigned long n)
{
    xgo_host_line_add(l, "drop %s n=%lu ", xgo_drop_reason_name(XGO_DROP_NOISE), n);
    xgo_host_line_hex(l, head, shown);
    if (n > shown) {
        l->len--; /* reopen the bracket */
        xgo_host_line_add(l, " ...]");
    }
}

/* A bad checksum: which one the frame's bytes call for. */
static void xgo_host_line_checksum(xgo_host_line_t *l, const uint8_t *raw, size_t n)
{
    if (n < XGO_FRAME_OVERHEAD + 1u || raw[2] != n) {
        return;
    }
    xgo_host_line_add(l, " checksum %02X, expected %02X", raw[n - 3],
                      xgo_frame_checksum(raw[2], raw[3], raw[4], raw + 5,
                                         n - XGO_FRAME_OVERHEAD));
}

void xgo_host_trace_format(const xgo_host_trace_t *t, const xgo_trace_event_t *ev, char *line,
                           size_t line_size)
{
    xgo_host_line_t l;

    l.buf = line;
    l.size = line_size;
    l.len = 0;
    l.arm = t->arm;
    line[0] = '\0';
    xgo_host_line_time(&l, t, t->now_us);

    switch (ev->kind) {
    case XGO_TRACE_RX:
        xgo_host_line_add(&l, "rx ");
        if (ev->frame == NULL) {
            xgo_host_line_add(&l, "?");
            break;
        }
        xgo_host_line_frame(&l, ev->frame);
        if (ev->frame->type != XGO_TYPE_READ) {
            xgo_host_line_write_meaning(&l, ev->frame, ev->unmapped);
        }
        break;
    case XGO_TRACE_TX:
        xgo_host_line_add(&l, "tx ");
        if (ev->frame == NULL) {
            xgo_host_line_add(&l, "?");
            break;
        }
        xgo_host_line_frame(&l, ev->frame);
        xgo_host_line_reply_meaning(&l, ev->frame);
        break;
    case XGO_TRACE_DROP:
        if (ev->reason == XGO_DROP_NOISE) {
            xgo_host_line_noise(&l, ev->raw,
                                ev->raw_len < XGO_HOST_TRACE_NOISE_SHOWN ? ev->raw_len
                                                                         : XGO_HOST_TRACE_NOISE_SHOWN,
                                (unsigned long)ev->raw_len);
            break;
        }
        xgo_host_line_add(&l, "drop %s", xgo_drop_reason_name(ev->reason));
        if (ev->frame != NULL) {
            xgo_host_line_add(&l, ": ");
            xgo_host_line_frame(&l, ev->frame);
        }
        if (ev->raw != NULL && ev->raw_len > 0) {
            xgo_host_line_add(&l, " ");
            xgo_host_line_hex(&l, ev->raw, ev->raw_len);
        }
        if (ev->reason == XGO_DROP_BAD_CHECKSUM && ev->raw != NULL) {
            xgo_host_line_checksum(&l, ev->raw, ev->raw_len);
        }
        break;
    }
}

/* One fwrite per line on the unbuffered stderr: lines from one process
 * never interleave mid-line. */
static void xgo_host_trace_put(const xgo_host_trace_t *t, char *line, size_t size)
{
    size_t n = strlen(line);
    if (n + 1 < size) {
        line[n++] = '\n';
    }
    fwrite(line, 1, n, t->out);
}

void xgo_host_trace_flush(xgo_host_trace_t *t)
{
    char line[256];
    xgo_host_line_t l;
    size_t shown = t->noise_bytes < XGO_HOST_TRACE_NOISE_SHOWN ? t->noise_bytes
                                                               : XGO_HOST_TRACE_NOISE_SHOWN;
    if (t->noise_bytes == 0) {
        return;
    }
    l.buf = line;
    l.size = sizeof line;
    l.len = 0;
    l.arm = t->arm;
    line[0] = '\0';
    xgo_host_line_time(&l, t, t->noise_since_us);
    xgo_host_line_noise(&l, t->noise_head, shown, (unsigned long)t->noise_bytes);
    xgo_host_trace_put(t, line, sizeof line);
    t->noise_bytes = 0;
    t->noise_line_us = t->now_us;
    t->noise_printed = 1;
}

void xgo_host_trace_tick(xgo_host_trace_t *t, uint64_t now_us)
{
    if (t->noise_bytes > 0 &&
        (!t->noise_printed || now_us - t->noise_line_us >= XGO_HOST_TRACE_NOISE_US)) {
        t->now_us = now_us;
        xgo_host_trace_flush(t);
    }
}

static void xgo_host_trace_fold_noise(xgo_host_trace_t *t, const uint8_t *bytes, size_t n)
{
    size_t i;
    if (t->noise_bytes == 0) {
        t->noise_since_us = t->now_us;
    }
    for (i = 0; i < n && t->noise_bytes + i < XGO_HOST_TRACE_NOISE_SHOWN; i++) {
        t->noise_head[t->noise_bytes + i] = bytes[i];
    }
    t->noise_bytes += (uint32_t)n;
}

void xgo_host_trace_event(void *ctx, const xgo_trace_event_t *ev)
{
    xgo_host_trace_t *t = ctx;
    /* Long enough for a 255-byte frame in hex plus its decoding. */
    char line[4096];
    if (ev->kind == XGO_TRACE_DROP && ev->reason == XGO_DROP_NOISE) {
        xgo_host_trace_fold_noise(t, ev->raw, ev->raw_len);
        return;
    }
    xgo_host_trace_flush(t); /* the noise came first */
    xgo_host_trace_format(t, ev, line, sizeof line);
    xgo_host_trace_put(t, line, sizeof line);
}
