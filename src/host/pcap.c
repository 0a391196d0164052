/* pcap.c - capture files (see pcap.h). */
#include "pcap.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define XGO_PCAP_MAGIC_US 0xA1B2C3D4u
#define XGO_PCAP_MAGIC_NS 0xA1B23C4Du
#define XGO_PCAP_SNAPLEN 65535u
#define XGO_PCAP_FILE_HEADER_LEN 24u
#define XGO_PCAP_RECORD_HEADER_LEN 16u

static void xgo_pcap_put32(uint8_t *p, uint32_t v)
{
    memcpy(p, &v, 4); /* native order: the magic tells readers which */
}

static void xgo_pcap_put16(uint8_t *p, uint16_t v)
{
    memcpy(p, &v, 2);
}

static uint64_t xgo_pcap_wall_us(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_REALTIME, &ts) != 0) {
        return 0;
    }
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

/* Writes all of buf with one write() if the system allows; a short write
 * (disk full) is cut off again so the file ends on a whole record. */
static int xgo_pcap_write_whole(xgo_host_pcap_writer_t *w, const uint8_t *buf, size_t n)
{
    off_t before = lseek(w->fd, 0, SEEK_CUR);
    size_t done = 0;
    while (done < n) {
        ssize_t k = write(w->fd, buf + done, n - done);
        if (k > 0) {
            done += (size_t)k;
            continue;
        }
        if (k < 0 && errno == EINTR) {
            continue;
        }
        if (k == 0) {
            errno = ENOSPC;
        }
        {
            int saved = errno;
            if (before >= 0 && ftruncate(w->fd, before) == 0) {
                (void)lseek(w->fd, before, SEEK_SET);
            }
            errno = saved;
        }
        w->failed = 1;
        return -1;
    }
    return 0;
}

int xgo_host_pcap_create(xgo_host_pcap_writer_t *w, const char *path, uint64_t now_mono_us,
                         char *err, size_t err_size)
{
    uint8_t h[XGO_PCAP_FILE_HEADER_LEN];
    memset(w, 0, sizeof *w);
    w->fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (w->fd < 0) {
        snprintf(err, err_size, "cannot create capture %s: %s", path, strerror(errno));
        return -1;
    }
    w->origin_wall_us = xgo_pcap_wall_us();
    w->origin_mono_us = now_mono_us;
    xgo_pcap_put32(h, XGO_PCAP_MAGIC_US);
    xgo_pcap_put16(h + 4, 2); /* version 2.4 */
    xgo_pcap_put16(h + 6, 4);
    xgo_pcap_put32(h + 8, 0);  /* thiszone */
    xgo_pcap_put32(h + 12, 0); /* sigfigs */
    xgo_pcap_put32(h + 16, XGO_PCAP_SNAPLEN);
    xgo_pcap_put32(h + 20, XGO_PCAP_LINKTYPE);
    if (xgo_pcap_write_whole(w, h, sizeof h) != 0) {
        snprintf(err, err_size, "cannot write capture %s: %s", path, strerror(errno));
        close(w->fd);
        w->fd = -1;
        return -1;
    }
    return 0;
}

static int xgo_pcap_write_record(xgo_host_pcap_writer_t *w, uint64_t mono_us, uint8_t dir,
                                 uint32_t tick, const uint8_t *bytes, size_t n)
{
    uint8_t rec[XGO_PCAP_RECORD_HEADER_LEN + XGO_PCAP_PSEUDO_LEN + XGO_PCAP_MAX_BYTES];
    uint64_t t = w->origin_wall_us + (mono_us > w->origin_mono_us ? mono_us - w->origin_mono_us : 0);
    uint32_t len = (uint32_t)(XGO_PCAP_PSEUDO_LEN + n);
    xgo_pcap_put32(rec, (uint32_t)(t / 1000000u));
    xgo_pcap_put32(rec + 4, (uint32_t)(t % 1000000u));
    xgo_pcap_put32(rec + 8, len);
    xgo_pcap_put32(rec + 12, len);
    rec[16] = dir;
    rec[17] = (uint8_t)(tick & 0xFFu); /* the pseudo-header is little-endian always */
    rec[18] = (uint8_t)((tick >> 8) & 0xFFu);
    rec[19] = (uint8_t)((tick >> 16) & 0xFFu);
    rec[20] = (uint8_t)(tick >> 24);
    if (n > 0) {
        memcpy(rec + XGO_PCAP_RECORD_HEADER_LEN + XGO_PCAP_PSEUDO_LEN, bytes, n);
    }
    if (xgo_pcap_write_whole(w, rec, XGO_PCAP_RECORD_HEADER_LEN + len) != 0) {
        return -1;
    }
    w->records++;
    return 0;
}

int xgo_host_pcap_write(xgo_host_pcap_writer_t *w, uint64_t mono_us, xgo_pcap_dir_t dir,
                        uint32_t tick, const uint8_t *bytes, size_t n)
{
    if (w->fd < 0 || w->failed) {
        return -1;
    }
    while (n > 0) {
        size_t part = n < XGO_PCAP_MAX_BYTES ? n : XGO_PCAP_MAX_BYTES;
        if (xgo_pcap_write_record(w, mono_us, (uint8_t)dir, tick, bytes, part) != 0) {
            return -1;
        }
        bytes += part;
        n -= part;
    }
    return 0;
}

int xgo_host_pcap_event(xgo_host_pcap_writer_t *w, uint64_t mono_us, xgo_pcap_dir_t dir,
                        uint32_t tick)
{
    if (w->fd < 0 || w->failed) {
        return -1;
    }
    return xgo_pcap_write_record(w, mono_us, (uint8_t)dir, tick, NULL, 0);
}

int xgo_host_pcap_note(xgo_host_pcap_writer_t *w, uint64_t mono_us, const char *text)
{
    return xgo_host_pcap_write(w, mono_us, XGO_PCAP_NOTE, XGO_PCAP_TICK_UNKNOWN,
                               (const uint8_t *)text, strlen(text));
}

void xgo_host_pcap_close(xgo_host_pcap_writer_t *w)
{
    if (w->fd >= 0) {
        close(w->fd);
        w->fd = -1;
    }
}

/* ------------------------------------------------------------ reading */

static uint32_t xgo_pcap_get32(const xgo_host_pcap_reader_t *r, const uint8_t *p)
{
    uint32_t v;
    memcpy(&v, p, 4);
    if (r->swapped) {
        v = (v >> 24) | ((v >> 8) & 0xFF00u) | ((v << 8) & 0xFF0000u) | (v << 24);
    }
    return v;
}

int xgo_host_pcap_is_pcap(const uint8_t *head, size_t n)
{
    static const uint8_t magics[4][4] = {{0xD4, 0xC3, 0xB2, 0xA1}, {0xA1, 0xB2, 0xC3, 0xD4},
                                         {0x4D, 0x3C, 0xB2, 0xA1}, {0xA1, 0xB2, 0x3C, 0x4D}};
    size_t i;
    if (n < 4) {
        return 0;
    }
    for (i = 0; i < 4; i++) {
        if (memcmp(head, magics[i], 4) == 0) {
            return 1;
        }
    }
    return 0;
}

/* Reads the file header: byte order, resolution, link type. */
static int xgo_pcap_read_header(xgo_host_pcap_reader_t *r, char *err, size_t err_size)
{
    uint8_t h[XGO_PCAP_FILE_HEADER_LEN];
    uint32_t magic;
    if (fread(h, 1, sizeof h, r->file) != sizeof h || !xgo_host_pcap_is_pcap(h, sizeof h)) {
        snprintf(err, err_size, "%s is not a pcap capture", r->path);
        return -1;
    }
    memcpy(&magic, h, 4);
    r->swapped = magic != XGO_PCAP_MAGIC_US && magic != XGO_PCAP_MAGIC_NS;
    magic = xgo_pcap_get32(r, h);
    r->nanosecond = magic == XGO_PCAP_MAGIC_NS;
    if ((xgo_pcap_get32(r, h + 20) & 0xFFFFu) != XGO_PCAP_LINKTYPE) {
        snprintf(err, err_size, "%s: link type %lu, not an xgo serial capture (%u)", r->path,
                 (unsigned long)(xgo_pcap_get32(r, h + 20) & 0xFFFFu), XGO_PCAP_LINKTYPE);
        return -1;
    }
    return 0;
}

int xgo_host_pcap_open(xgo_host_pcap_reader_t *r, const char *path, char *err, size_t err_size)
{
    r->path = path;
    r->number = 0;
    r->file = fopen(path, "rb");
    if (r->file == NULL) {
        snprintf(err, err_size, "cannot open %s: %s", path, strerror(errno));
        return -1;
    }
    if (xgo_pcap_read_header(r, err, err_size) != 0) {
        fclose(r->file);
        r->file = NULL;
        return -1;
    }
    return 0;
}

int xgo_host_pcap_next(xgo_host_pcap_reader_t *r, xgo_host_pcap_record_t *rec, char *err,
                       size_t err_size)
{
    uint8_t h[XGO_PCAP_RECORD_HEADER_LEN];
    size_t got = fread(h, 1, sizeof h, r->file);
    uint32_t len;
    if (got == 0 && feof(r->file)) {
        return 0;
    }
    r->number++;
    if (got != sizeof h) {
        snprintf(err, err_size, "%s: record %lu is cut off", r->path, r->number);
        return -1;
    }
    len = xgo_pcap_get32(r, h + 8);
    if (len < XGO_PCAP_PSEUDO_LEN || len > sizeof r->buf) {
        snprintf(err, err_size, "%s: record %lu has a bad length %lu", r->path, r->number,
                 (unsigned long)len);
        return -1;
    }
    if (fread(r->buf, 1, len, r->file) != len) {
        snprintf(err, err_size, "%s: record %lu is cut off", r->path, r->number);
        return -1;
    }
    rec->number = r->number;
    rec->wall_us = (uint64_t)xgo_pcap_get32(r, h) * 1000000u +
                   (r->nanosecond ? xgo_pcap_get32(r, h + 4) / 1000u : xgo_pcap_get32(r, h + 4));
    rec->dir = r->buf[0];
    rec->tick = (uint32_t)r->buf[1] | (uint32_t)r->buf[2] << 8 | (uint32_t)r->buf[3] << 16 |
                (uint32_t)r->buf[4] << 24;
    rec->bytes = r->buf + XGO_PCAP_PSEUDO_LEN;
    rec->n = len - XGO_PCAP_PSEUDO_LEN;
    return 1;
}

void xgo_host_pcap_close_reader(xgo_host_pcap_reader_t *r)
{
    if (r->file != NULL) {
        fclose(r->file);
        r->file = NULL;
    }
}
