/*
 * gen_tables.c - prints xgo_tables.lua for the Wireshark dissector (xgo.lua)
 * from the core's own tables, at build time: the register map (name, width,
 * access), what every byte of every register means on each model (the same
 * text xgo-cli prints: src/host/meaning.c), the diagnostic counters' names.
 * Lua table shapes are documented in the file's header comment.
 * The dissector re-types none of it. Usage: xgo-wireshark-tables > FILE.
 */
#include <stdio.h>

#include "meaning.h"
#include "pcap.h"
#include "xgo/board.h"
#include "xgo/regs.h"

/* A Lua string literal: quotes and backslashes escaped, the rest ASCII. */
static void lua_string(const char *s)
{
    putchar('"');
    for (; *s != '\0'; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') {
            printf("\\%c", c);
        } else if (c < 0x20 || c >= 0x7F) {
            printf("\\%03u", c);
        } else {
            putchar(c);
        }
    }
    putchar('"');
}

static const char *access_name(uint8_t access)
{
    return access == XGO_ACCESS_R ? "r" : (access == XGO_ACCESS_W ? "w" : "rw");
}

static void print_registers(void)
{
    size_t i;
    printf("  registers = {\n");
    for (i = 0; i < xgo_reg_table_size(); i++) {
        const xgo_reg_desc_t *d = xgo_reg_table_entry(i);
        printf("    { addr = %u, width = %u, access = \"%s\", name = ", d->addr, d->width,
               access_name(d->access));
        lua_string(d->name);
        printf(" },\n");
    }
    printf("  },\n");
}

/* How many bytes of register a have a meaning on model p. */
static unsigned meaning_count(const xgo_profile_t *p, unsigned a)
{
    unsigned b, n = 0;
    for (b = 0; b < 256; b++) {
        char text[96];
        xgo_host_reg_meaning(p, (uint8_t)a, (uint8_t)b, text, sizeof text);
        n += text[0] != '\0';
    }
    return n;
}

/* meanings[model][addr] = { all = {256 texts, byte 0 first} } where every
 * byte has one (unit registers), else { [byte] = text ... } where some do. */
static void print_meanings(const char *model, const xgo_profile_t *p)
{
    unsigned a, b;
    printf("  %s = {\n", model);
    for (a = 0; a < 256; a++) {
        unsigned n = meaning_count(p, a);
        if (n == 0) {
            continue;
        }
        printf(n == 256 ? "    [%u] = {all={" : "    [%u] = {", a);
        for (b = 0; b < 256; b++) {
            char text[96];
            xgo_host_reg_meaning(p, (uint8_t)a, (uint8_t)b, text, sizeof text);
            if (text[0] != '\0') {
                if (n != 256) {
                    printf("[%u]=", b);
                }
                lua_string(text);
                putchar(',');
            }
        }
        printf(n == 256 ? "}},\n" : "},\n");
    }
    printf("  },\n");
}

int main(void)
{
    unsigned i;
    printf("-- xgo_tables.lua: generated at build time by xgo-wireshark-tables from the\n"
           "-- core's register table and decodings (tools/wireshark/gen_tables.c).\n"
           "-- Do not edit, do not commit. meanings[model][addr] is {all = {texts of\n"
           "-- bytes 0..255}} or {[byte] = text} for the bytes that have one.\n"
           "return {\n");
    printf("  linktype = %u,\n  diag_addr = %u,\n", XGO_PCAP_LINKTYPE, XGO_REG_DIAG);
    print_registers();
    printf("  meanings = {\n");
    for (i = 0; i < XGO_HOST_MODEL_COUNT; i++) {
        print_meanings(xgo_profile_get(i)->name, xgo_profile_get(i));
    }
    printf("  },\n  diag = {");
    for (i = 0; i < XGO_DIAG_COUNT; i++) {
        lua_string(xgo_diag_name((xgo_diag_t)i));
        putchar(',');
    }
    printf("},\n}\n");
    return 0;
}
