/* fuzz_main.c - replay inputs through a fuzz target without libFuzzer (as
   stb's fuzz_main.c does), so any C compiler can run the corpus and the
   regressions:

       gcc -std=c99 -O1 -g fuzz_main.c fuzz_grow.c -o replay_grow -lm
       ./replay_grow corpus/grow regressions/grow-*.bin

   Each argument is a file or a directory (its regular files, one level).
   Prints one line per input and a total; a contract violation in the
   target aborts with the failing check on stderr. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int replay_file(const char *path, int verbose)
{
    FILE *f = fopen(path, "rb");
    uint8_t *buf;
    long n;
    if (!f) {
        fprintf(stderr, "cannot open %s\n", path);
        return 0;
    }
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = (uint8_t *)malloc(n > 0 ? (size_t)n : 1u);
    if (!buf || (n > 0 && fread(buf, 1, (size_t)n, f) != (size_t)n)) {
        fprintf(stderr, "cannot read %s\n", path);
        fclose(f);
        free(buf);
        return 0;
    }
    fclose(f);
    if (verbose) printf("%s (%ld bytes)\n", path, n);
    LLVMFuzzerTestOneInput(buf, (size_t)n);
    free(buf);
    return 1;
}

int main(int argc, char **argv)
{
    int i, total = 0, verbose = getenv("FUZZ_VERBOSE") != NULL;
    for (i = 1; i < argc; ++i) {
        struct stat st;
        if (stat(argv[i], &st) != 0) {
            fprintf(stderr, "no such file: %s\n", argv[i]);
            return 2;
        }
        if (S_ISDIR(st.st_mode)) {
            DIR *d = opendir(argv[i]);
            struct dirent *e;
            while (d && (e = readdir(d)) != NULL) {
                char path[4096];
                struct stat fs;
                if (e->d_name[0] == '.') continue;
                snprintf(path, sizeof path, "%s/%s", argv[i], e->d_name);
                if (stat(path, &fs) == 0 && S_ISREG(fs.st_mode))
                    total += replay_file(path, verbose);
            }
            if (d) closedir(d);
        } else {
            total += replay_file(argv[i], verbose);
        }
    }
    printf("replayed %d inputs: no contract violation\n", total);
    return 0;
}
