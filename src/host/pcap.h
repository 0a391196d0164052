/*
 * pcap.h - capture files of the serial byte stream: written by xgo-emu
 * --capture and xgo-cli --capture, read by xgo-replay, xgo-cli decode and
 * Wireshark (tools/wireshark/xgo.lua). Format (docs/capture.md):
 *
 *   classic libpcap file, microsecond timestamps (wall clock), link type
 *   LINKTYPE_USER0 = 147; every record is a 5-byte pseudo-header, then the
 *   bytes as they went over the line:
 *     byte 0     direction: XGO_PCAP_HOST_TO_BOARD, _BOARD_TO_HOST,
 *                _DISCARDED (replies the board made while no host was
 *                attached: never on the wire), _NOTE (ASCII text: who wrote
 *                the capture, with which settings), _HANGUP (no bytes: the
 *                board was told the host hung up)
 *     bytes 1-4  board tick (uint32 little-endian) at which the bytes were
 *                fed to the board or taken from it; XGO_PCAP_TICK_UNKNOWN
 *                when the writer cannot know (a real robot's port)
 *
 * The writer puts each record into the file with one write() as it happens
 * (no buffering), so a capture is valid up to its last whole record even if
 * the writer is killed. A record whose write came up short is cut off again.
 */
#ifndef XGO_HOST_PCAP_H
#define XGO_HOST_PCAP_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define XGO_PCAP_LINKTYPE 147u     /* LINKTYPE_USER0 */
#define XGO_PCAP_PSEUDO_LEN 5u     /* direction + tick */
#define XGO_PCAP_MAX_BYTES 4096u   /* bytes per record; longer runs are split */
#define XGO_PCAP_TICK_UNKNOWN 0xFFFFFFFFu

typedef enum xgo_pcap_dir_e {
    XGO_PCAP_HOST_TO_BOARD = 0,
    XGO_PCAP_BOARD_TO_HOST = 1,
    XGO_PCAP_DISCARDED = 2,
    XGO_PCAP_NOTE = 3,
    XGO_PCAP_HANGUP = 4 /* no bytes: the host hung up, the board dropped its partial frame */
} xgo_pcap_dir_t;

typedef struct xgo_host_pcap_writer_s {
    int fd;                  /* -1: not open */
    uint64_t origin_wall_us; /* wall clock (epoch us) at origin_mono_us */
    uint64_t origin_mono_us;
    unsigned long records;
    int failed;              /* a write failed: nothing more is written */
} xgo_host_pcap_writer_t;

/* Creates (truncates) path and writes the file header; now_mono_us is the
 * caller's monotonic clock, tied to the wall clock here. Returns 0, or -1
 * with a one-line message in err. */
int xgo_host_pcap_create(xgo_host_pcap_writer_t *w, const char *path, uint64_t now_mono_us,
                         char *err, size_t err_size);

/* Appends n bytes (split into records of XGO_PCAP_MAX_BYTES) stamped with
 * mono_us. Returns 0, or -1 (errno kept) when a write failed; from then on
 * the writer stays failed and writes nothing. n == 0 writes nothing. */
int xgo_host_pcap_write(xgo_host_pcap_writer_t *w, uint64_t mono_us, xgo_pcap_dir_t dir,
                        uint32_t tick, const uint8_t *bytes, size_t n);

/* A record without bytes (XGO_PCAP_HANGUP). */
int xgo_host_pcap_event(xgo_host_pcap_writer_t *w, uint64_t mono_us, xgo_pcap_dir_t dir,
                        uint32_t tick);

/* A NOTE record holding text. */
int xgo_host_pcap_note(xgo_host_pcap_writer_t *w, uint64_t mono_us, const char *text);

void xgo_host_pcap_close(xgo_host_pcap_writer_t *w);

/* ---- reading */

typedef struct xgo_host_pcap_record_s {
    unsigned long number; /* 1-based, as Wireshark counts */
    uint64_t wall_us;     /* timestamp, us since the epoch */
    uint8_t dir;          /* xgo_pcap_dir_t */
    uint32_t tick;
    const uint8_t *bytes; /* valid until the next read */
    size_t n;
} xgo_host_pcap_record_t;

typedef struct xgo_host_pcap_reader_s {
    FILE *file;
    const char *path;
    int swapped;    /* the file's byte order is not ours */
    int nanosecond; /* timestamps in ns (magic 0xa1b23c4d) */
    unsigned long number;
    uint8_t buf[XGO_PCAP_PSEUDO_LEN + 65536u];
} xgo_host_pcap_reader_t;

/* Opens a capture and checks its header (pcap magic, link type 147).
 * Returns 0, or -1 with a one-line message in err. */
int xgo_host_pcap_open(xgo_host_pcap_reader_t *r, const char *path, char *err, size_t err_size);

/* Is the file at path a pcap file (by its first four bytes)? */
int xgo_host_pcap_is_pcap(const uint8_t *head, size_t n);

/* The next record: 1 and *rec, 0 at the end, -1 with a message in err (a
 * cut-off record, a record too short for the pseudo-header, a read error). */
int xgo_host_pcap_next(xgo_host_pcap_reader_t *r, xgo_host_pcap_record_t *rec, char *err,
                       size_t err_size);

void xgo_host_pcap_close_reader(xgo_host_pcap_reader_t *r);

#endif /* XGO_HOST_PCAP_H */
