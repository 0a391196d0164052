/*
 * qemu_pc_count.c - a QEMU TCG plugin: how many times each instruction
 * address below 256 KB (the micro:bit's flash) was executed. For
 * tools/mcu/profile.sh; not part of CI.
 *
 *   gcc -shared -fPIC -O2 qemu_pc_count.c -o libpccount.so
 *   qemu-system-arm ... -plugin ./libpccount.so,out=pc_counts.txt
 *
 * Writes "ADDRESS COUNT" lines (hex address, decimal count) at exit.
 * Debian's QEMU 7.2 supports -plugin but ships no qemu-plugin.h, so the
 * few API v1 declarations used are written out here (QEMU's
 * include/qemu/qemu-plugin.h, version 1).
 */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

typedef uint64_t qemu_plugin_id_t;
struct qemu_plugin_tb;
struct qemu_plugin_insn;
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 };

void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id,
                                           void (*cb)(qemu_plugin_id_t, struct qemu_plugin_tb *));
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn,
                                                enum qemu_plugin_op op, void *ptr, uint64_t imm);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, void (*cb)(qemu_plugin_id_t, void *),
                                    void *userdata);
int qemu_plugin_install(qemu_plugin_id_t id, const void *info, int argc, char **argv);

__attribute__((visibility("default"))) int qemu_plugin_version = 1;

#define SLOTS (256u * 1024u / 2u) /* one per halfword of flash */

static uint64_t counts[SLOTS];
static char out_path[512] = "pc_counts.txt";

static void on_translate(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    size_t i, n = qemu_plugin_tb_n_insns(tb);
    (void)id;
    for (i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        uint64_t pc = qemu_plugin_insn_vaddr(insn);
        if (pc / 2u < SLOTS) {
            qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                       &counts[pc / 2u], 1);
        }
    }
}

static void on_exit(qemu_plugin_id_t id, void *userdata)
{
    FILE *f = fopen(out_path, "w");
    size_t i;
    (void)id;
    (void)userdata;
    if (f == NULL) {
        perror(out_path);
        return;
    }
    for (i = 0; i < SLOTS; i++) {
        if (counts[i] != 0) {
            fprintf(f, "%lx %llu\n", (unsigned long)(i * 2u), (unsigned long long)counts[i]);
        }
    }
    fclose(f);
}

__attribute__((visibility("default"))) int qemu_plugin_install(qemu_plugin_id_t id,
                                                               const void *info, int argc,
                                                               char **argv)
{
    int i;
    (void)info;
    for (i = 0; i < argc; i++) {
        if (strncmp(argv[i], "out=", 4) == 0 && strlen(argv[i] + 4) < sizeof out_path) {
            strcpy(out_path, argv[i] + 4);
        }
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_translate);
    qemu_plugin_register_atexit_cb(id, on_exit, NULL);
    return 0;
}
