/*
 * replay.c - fuzz_board_replay: runs fuzz inputs through the fuzz target
 * without libFuzzer (any compiler), and writes the seed corpus.
 *
 *   fuzz_board_replay                      every generated seed (ctest)
 *   fuzz_board_replay FILE|DIR...          saved inputs, e.g. a crash-... file
 *   fuzz_board_replay --write-seeds DIR    the seed corpus as files in DIR
 *
 * A broken promise aborts (the message names it); exit 0 when all ran.
 */
#include <dirent.h>
#include <stdio.h>
#include <string.h>

#include "seeds.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint8_t g_buf[1u << 20];

static int run_seeds(void)
{
    unsigned i;
    size_t n;
    for (i = 0; (n = fuzz_seed(i, g_buf, sizeof g_buf)) > 0; i++) {
        LLVMFuzzerTestOneInput(g_buf, n);
    }
    printf("fuzz_board_replay: %u generated seeds ok\n", i);
    return 0;
}

static int write_seeds(const char *dir)
{
    unsigned i;
    size_t n;
    for (i = 0; (n = fuzz_seed(i, g_buf, sizeof g_buf)) > 0; i++) {
        char name[64], path[4096];
        FILE *f;
        snprintf(path, sizeof path, "%s/seed-%s", dir, fuzz_seed_name(i, name, sizeof name));
        f = fopen(path, "wb");
        if (f == NULL || fwrite(g_buf, 1, n, f) != n || fclose(f) != 0) {
            fprintf(stderr, "fuzz_board_replay: cannot write %s\n", path);
            return 1;
        }
    }
    printf("fuzz_board_replay: %u seeds written to %s\n", i, dir);
    return 0;
}

/* Runs one file; returns 0, or -1 if it cannot be read. */
static int run_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    size_t n;
    if (f == NULL) {
        return -1;
    }
    n = fread(g_buf, 1, sizeof g_buf, f);
    fclose(f);
    LLVMFuzzerTestOneInput(g_buf, n);
    return 0;
}

/* Runs every file in dir (not recursively); returns how many, -1 if none
 * could be opened as a directory. */
static int run_dir(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    int n = 0;
    if (d == NULL) {
        return -1;
    }
    while ((e = readdir(d)) != NULL) {
        char path[4096];
        if (e->d_name[0] == '.') {
            continue;
        }
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        n += run_file(path) == 0;
    }
    closedir(d);
    return n;
}

int main(int argc, char **argv)
{
    int i, inputs = 0;
    if (argc < 2) {
        return run_seeds();
    }
    if (strcmp(argv[1], "--write-seeds") == 0) {
        if (argc != 3) {
            fprintf(stderr, "usage: fuzz_board_replay [--write-seeds DIR | FILE|DIR...]\n");
            return 2;
        }
        return write_seeds(argv[2]);
    }
    for (i = 1; i < argc; i++) {
        int n = run_dir(argv[i]);
        if (n < 0 && run_file(argv[i]) != 0) {
            fprintf(stderr, "fuzz_board_replay: cannot open %s\n", argv[i]);
            return 2;
        }
        inputs += n < 0 ? 1 : n;
    }
    printf("fuzz_board_replay: %d input(s) ok\n", inputs);
    return 0;
}
