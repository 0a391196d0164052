/*
 * nv_file.c - non-volatile data in a host file through semihosting (see
 * nv_file.h).
 */
#include "nv_file.h"

#include <string.h>

#include "semihost.h"

#define OFF_VERSION 4u
#define OFF_NAME 8u
#define OFF_OFFSETS 20u
#define OFF_CRC 68u
#define VERSION 1u

static const uint8_t k_magic[4] = {'X', 'G', 'N', 'V'};

/* CRC-32 (reflected, polynomial 0xEDB88320, zlib's), bit by bit: 72 bytes
 * once per save need no table. */
static uint32_t crc32(const uint8_t *p, size_t n)
{
    uint32_t crc = 0xFFFFFFFFu;
    size_t i;
    unsigned bit;
    for (i = 0; i < n; i++) {
        crc ^= p[i];
        for (bit = 0; bit < 8u; bit++) {
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
        }
    }
    return ~crc;
}

static void put_le32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static uint32_t get_le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

void xgo_nv_record_encode(const xgo_board_nv_t *nv, uint8_t out[XGO_NV_FILE_RECORD_SIZE])
{
    unsigned i;
    memset(out, 0, XGO_NV_FILE_RECORD_SIZE);
    memcpy(out, k_magic, sizeof k_magic);
    out[OFF_VERSION] = VERSION;
    memcpy(out + OFF_NAME, nv->bt_name, XGO_BT_NAME_LEN);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        put_le32(out + OFF_OFFSETS + 4u * i, (uint32_t)nv->zero_offset_mdeg[i]);
    }
    put_le32(out + OFF_CRC, crc32(out, OFF_CRC));
}

int xgo_nv_record_decode(const uint8_t in[XGO_NV_FILE_RECORD_SIZE], xgo_board_nv_t *nv)
{
    unsigned i;
    if (memcmp(in, k_magic, sizeof k_magic) != 0 || in[OFF_VERSION] != VERSION ||
        get_le32(in + OFF_CRC) != crc32(in, OFF_CRC)) {
        return 0;
    }
    memcpy(nv->bt_name, in + OFF_NAME, XGO_BT_NAME_LEN);
    for (i = 0; i < XGO_SERVO_COUNT; i++) {
        nv->zero_offset_mdeg[i] = (int32_t)get_le32(in + OFF_OFFSETS + 4u * i);
    }
    return 1;
}

void xgo_nv_file_init(xgo_nv_file_t *f)
{
    char line[XGO_NV_FILE_PATH_MAX + 32u];
    const char *p = line;
    size_t n = 0;
    memset(f, 0, sizeof *f);
    if (!xgo_sh_cmdline(line, sizeof line)) {
        return;
    }
    while (*p != '\0' && *p != ' ') {
        p++; /* the program's name */
    }
    while (*p == ' ') {
        p++;
    }
    while (p[n] != '\0' && p[n] != ' ' && n < sizeof f->path - 1u) {
        f->path[n] = p[n];
        n++;
    }
    if (p[n] != '\0' && p[n] != ' ') {
        f->path[0] = '\0'; /* too long: better no file than another one */
    }
}

int xgo_nv_file_load(xgo_nv_file_t *f, xgo_board_nv_t *nv)
{
    uint8_t record[XGO_NV_FILE_RECORD_SIZE];
    int handle, ok;
    if (f->path[0] == '\0') {
        if (f->ram_valid) {
            *nv = f->ram;
        }
        return f->ram_valid;
    }
    handle = xgo_sh_open(f->path, "rb");
    if (handle < 0) {
        return 0; /* first start */
    }
    ok = xgo_sh_read(handle, record, sizeof record) == sizeof record &&
         xgo_nv_record_decode(record, nv);
    (void)xgo_sh_close(handle);
    return ok;
}

int xgo_nv_file_save(xgo_nv_file_t *f, const xgo_board_nv_t *nv)
{
    uint8_t record[XGO_NV_FILE_RECORD_SIZE];
    int handle, ok;
    if (f->path[0] == '\0') {
        f->ram = *nv;
        f->ram_valid = 1;
        return 1;
    }
    xgo_nv_record_encode(nv, record);
    handle = xgo_sh_open(f->path, "wb");
    if (handle < 0) {
        return 0;
    }
    ok = xgo_sh_write(handle, record, sizeof record) == sizeof record;
    return xgo_sh_close(handle) == 0 && ok;
}
