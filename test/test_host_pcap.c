/*
 * Capture files (src/host/pcap.c): the exact bytes of the file header and of
 * a record, reading back what was written, long runs split into records, a
 * cut-off last record reported after the whole ones, a big-endian file with
 * nanosecond stamps read alike, foreign files refused.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "pcap.h"
#include "unity.h"

static char g_path[64];

void setUp(void)
{
    int fd;
    strcpy(g_path, "/tmp/xgo-pcap-XXXXXX");
    fd = mkstemp(g_path);
    TEST_ASSERT_TRUE(fd >= 0);
    close(fd);
}

void tearDown(void)
{
    unlink(g_path);
}

static size_t read_file(uint8_t *buf, size_t cap)
{
    FILE *f = fopen(g_path, "rb");
    size_t n;
    TEST_ASSERT_NOT_NULL(f);
    n = fread(buf, 1, cap, f);
    fclose(f);
    return n;
}

static void write_file(const uint8_t *buf, size_t n)
{
    FILE *f = fopen(g_path, "wb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_UINT64(n, fwrite(buf, 1, n, f));
    fclose(f);
}

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void test_header_and_record_bytes(void)
{
    xgo_host_pcap_writer_t w;
    char err[256];
    uint8_t buf[256];
    static const uint8_t frame[] = {0x55, 0x00, 0x09, 0x02, 0x50, 0x0C, 0x98, 0x00, 0xAA};
    size_t n;
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_create(&w, g_path, 1000000u, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_write(&w, 1250000u, XGO_PCAP_HOST_TO_BOARD, 0x01020304u,
                                                 frame, sizeof frame));
    xgo_host_pcap_close(&w);
    n = read_file(buf, sizeof buf);
    TEST_ASSERT_EQUAL_UINT64(24 + 16 + 5 + sizeof frame, n);
    /* this test runs on little-endian hosts (x86, ARM): the header is native */
    TEST_ASSERT_EQUAL_HEX32(0xA1B2C3D4u, le32(buf));
    TEST_ASSERT_EQUAL_HEX8(2, buf[4]);
    TEST_ASSERT_EQUAL_HEX8(4, buf[6]);
    TEST_ASSERT_EQUAL_UINT32(65535u, le32(buf + 16));
    TEST_ASSERT_EQUAL_UINT32(147u, le32(buf + 20));
    TEST_ASSERT_EQUAL_UINT32(5 + sizeof frame, le32(buf + 24 + 8));  /* incl_len */
    TEST_ASSERT_EQUAL_UINT32(5 + sizeof frame, le32(buf + 24 + 12)); /* orig_len */
    TEST_ASSERT_EQUAL_HEX8(XGO_PCAP_HOST_TO_BOARD, buf[40]);
    TEST_ASSERT_EQUAL_HEX32(0x01020304u, le32(buf + 41));
    TEST_ASSERT_EQUAL_HEX8_ARRAY(frame, buf + 45, sizeof frame);
}

static void test_records_read_back(void)
{
    xgo_host_pcap_writer_t w;
    xgo_host_pcap_reader_t *r = malloc(sizeof *r);
    xgo_host_pcap_record_t rec;
    char err[256];
    static const uint8_t a[] = {1, 2, 3};
    static const uint8_t b[] = {0x55, 0xAA};
    uint64_t t0;
    TEST_ASSERT_NOT_NULL(r);
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_create(&w, g_path, 5000u, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_note(&w, 5000u, "xgo-emu test"));
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_write(&w, 7000u, XGO_PCAP_HOST_TO_BOARD, 1, a, 3));
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_write(&w, 2007000u, XGO_PCAP_BOARD_TO_HOST, 1000, b, 2));
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_write(&w, 2008000u, XGO_PCAP_DISCARDED, 1001, b, 0));
    xgo_host_pcap_close(&w);

    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_open(r, g_path, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(1, xgo_host_pcap_next(r, &rec, err, sizeof err));
    TEST_ASSERT_EQUAL_UINT8(XGO_PCAP_NOTE, rec.dir);
    TEST_ASSERT_EQUAL_HEX32(XGO_PCAP_TICK_UNKNOWN, rec.tick);
    TEST_ASSERT_EQUAL_STRING_LEN("xgo-emu test", (const char *)rec.bytes, 12);
    TEST_ASSERT_EQUAL_UINT64(12, rec.n);
    t0 = rec.wall_us;
    TEST_ASSERT_EQUAL_INT(1, xgo_host_pcap_next(r, &rec, err, sizeof err));
    TEST_ASSERT_EQUAL_UINT32(2, rec.number);
    TEST_ASSERT_EQUAL_UINT8(XGO_PCAP_HOST_TO_BOARD, rec.dir);
    TEST_ASSERT_EQUAL_UINT32(1, rec.tick);
    TEST_ASSERT_EQUAL_HEX8_ARRAY(a, rec.bytes, 3);
    TEST_ASSERT_EQUAL_UINT64(2000u, rec.wall_us - t0);
    TEST_ASSERT_EQUAL_INT(1, xgo_host_pcap_next(r, &rec, err, sizeof err));
    TEST_ASSERT_EQUAL_UINT8(XGO_PCAP_BOARD_TO_HOST, rec.dir);
    TEST_ASSERT_EQUAL_UINT32(1000, rec.tick);
    TEST_ASSERT_EQUAL_UINT64(2002000u, rec.wall_us - t0);
    TEST_ASSERT_EQUAL_UINT64(2, rec.n);
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_next(r, &rec, err, sizeof err)); /* n == 0: no record */
    xgo_host_pcap_close_reader(r);
    free(r);
}

static void test_long_runs_are_split(void)
{
    xgo_host_pcap_writer_t w;
    xgo_host_pcap_reader_t *r = malloc(sizeof *r);
    xgo_host_pcap_record_t rec;
    static uint8_t big[XGO_PCAP_MAX_BYTES * 2 + 10];
    char err[256];
    size_t i, total = 0;
    unsigned records = 0;
    TEST_ASSERT_NOT_NULL(r);
    for (i = 0; i < sizeof big; i++) {
        big[i] = (uint8_t)(i * 7u);
    }
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_create(&w, g_path, 0, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_write(&w, 1, XGO_PCAP_BOARD_TO_HOST, 9, big, sizeof big));
    xgo_host_pcap_close(&w);
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_open(r, g_path, err, sizeof err));
    while (xgo_host_pcap_next(r, &rec, err, sizeof err) == 1) {
        TEST_ASSERT_TRUE(rec.n <= XGO_PCAP_MAX_BYTES);
        TEST_ASSERT_EQUAL_HEX8_ARRAY(big + total, rec.bytes, rec.n);
        total += rec.n;
        records++;
    }
    TEST_ASSERT_EQUAL_UINT(3, records);
    TEST_ASSERT_EQUAL_UINT64(sizeof big, total);
    xgo_host_pcap_close_reader(r);
    free(r);
}

static void test_cut_off_record_is_reported(void)
{
    xgo_host_pcap_writer_t w;
    xgo_host_pcap_reader_t *r = malloc(sizeof *r);
    xgo_host_pcap_record_t rec;
    static const uint8_t a[] = {1, 2, 3, 4, 5, 6};
    uint8_t buf[256];
    char err[256];
    size_t n;
    TEST_ASSERT_NOT_NULL(r);
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_create(&w, g_path, 0, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_write(&w, 1, XGO_PCAP_HOST_TO_BOARD, 0, a, 6));
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_write(&w, 2, XGO_PCAP_HOST_TO_BOARD, 0, a, 6));
    xgo_host_pcap_close(&w);
    n = read_file(buf, sizeof buf);
    write_file(buf, n - 3);
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_open(r, g_path, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(1, xgo_host_pcap_next(r, &rec, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(-1, xgo_host_pcap_next(r, &rec, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "record 2 is cut off"));
    xgo_host_pcap_close_reader(r);
    free(r);
}

/* A capture written elsewhere: big-endian, nanosecond timestamps. */
static void test_big_endian_nanosecond_file(void)
{
    static const uint8_t file[] = {
        0xA1, 0xB2, 0x3C, 0x4D, 0x00, 0x02, 0x00, 0x04, 0, 0, 0, 0, 0, 0, 0, 0,
        0x00, 0x00, 0xFF, 0xFF, 0x00, 0x00, 0x00, 0x93,
        0x00, 0x00, 0x00, 0x0A, 0x1D, 0xCD, 0x65, 0x00, 0, 0, 0, 7, 0, 0, 0, 7,
        0x01, 0x10, 0x00, 0x00, 0x00, 0xAB, 0xCD};
    xgo_host_pcap_reader_t *r = malloc(sizeof *r);
    xgo_host_pcap_record_t rec;
    char err[256];
    TEST_ASSERT_NOT_NULL(r);
    write_file(file, sizeof file);
    TEST_ASSERT_EQUAL_INT(0, xgo_host_pcap_open(r, g_path, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(1, xgo_host_pcap_next(r, &rec, err, sizeof err));
    TEST_ASSERT_EQUAL_UINT64(10u * 1000000u + 500000u, rec.wall_us); /* 0x1DCD6500 ns */
    TEST_ASSERT_EQUAL_UINT8(XGO_PCAP_BOARD_TO_HOST, rec.dir);
    TEST_ASSERT_EQUAL_UINT32(16, rec.tick); /* the pseudo-header stays little-endian */
    TEST_ASSERT_EQUAL_UINT64(2, rec.n);
    TEST_ASSERT_EQUAL_HEX8(0xAB, rec.bytes[0]);
    xgo_host_pcap_close_reader(r);
    free(r);
}

static void test_foreign_files_refused(void)
{
    static const uint8_t ethernet[24] = {0xD4, 0xC3, 0xB2, 0xA1, 2, 0, 4, 0, 0, 0, 0, 0,
                                         0, 0, 0, 0, 0xFF, 0xFF, 0, 0, 1, 0, 0, 0};
    static const uint8_t text[] = "55 00 09 02 50 0c 98 00 aa\n";
    xgo_host_pcap_reader_t *r = malloc(sizeof *r);
    char err[256];
    TEST_ASSERT_NOT_NULL(r);
    write_file(ethernet, sizeof ethernet);
    TEST_ASSERT_EQUAL_INT(-1, xgo_host_pcap_open(r, g_path, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "link type 1, not an xgo serial capture (147)"));
    write_file(text, sizeof text - 1);
    TEST_ASSERT_EQUAL_INT(-1, xgo_host_pcap_open(r, g_path, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "is not a pcap capture"));
    TEST_ASSERT_EQUAL_INT(-1, xgo_host_pcap_open(r, "/nonexistent/x.pcap", err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "cannot open /nonexistent/x.pcap"));
    free(r);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_header_and_record_bytes);
    RUN_TEST(test_records_read_back);
    RUN_TEST(test_long_runs_are_split);
    RUN_TEST(test_cut_off_record_is_reported);
    RUN_TEST(test_big_endian_nanosecond_file);
    RUN_TEST(test_foreign_files_refused);
    return UNITY_END();
}
