/* A small test harness: CHECK counts and reports, testing_finish prints the
 * closing line "N passed, M failed" and gives the exit status; backends to
 * test are every one that can be created here (OpenCL is required when
 * AMSPH_REQUIRE_OPENCL=1, as in CI). */
#ifndef AMSPH_TESTING_H
#define AMSPH_TESTING_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "backend.h"
#include "case.h"
#include "error.h"

/* Constants the known answers are written with. */
#define PI 3.14159265358979323846
#define STEFAN_BOLTZMANN 5.670374419e-8 /* W/(m^2 K^4) */

static int testing_passed, testing_failed;

#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (cond) {                                                                                \
            ++testing_passed;                                                                      \
        } else {                                                                                   \
            ++testing_failed;                                                                      \
            fprintf(stderr, "%s:%d: FAILED %s: ", __FILE__, __LINE__, #cond);                      \
            fprintf(stderr, __VA_ARGS__);                                                          \
            fputc('\n', stderr);                                                                   \
        }                                                                                          \
    } while (0)

/* Fails the test on a non-zero library status, with the library's message. */
#define CHECK_OK(call) CHECK((call) == 0, "%s", amsph_last_error())

/* Output directories of a test: made by testing_temp_dir, removed by
 * testing_finish when every check passed, kept (and named) for a look at
 * what went wrong otherwise. They hold files only. */
#define TESTING_MAX_TEMP_DIRS 64
static char testing_temp_dirs[TESTING_MAX_TEMP_DIRS][256];
static int testing_n_temp_dirs;

/* Deterministic uniform numbers in [0, 1) from a seeded LCG (Knuth's MMIX
 * constants): a test's draws are the same on every run and machine. */
static inline double testing_random(unsigned long long *state)
{
    *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*state >> 11) * 0x1.0p-53;
}

/* Makes the directory /tmp/amsph_test_<tag>_XXXXXX; its name into dir. */
static inline int testing_temp_dir(char *dir, size_t size, const char *tag)
{
    const int fits = snprintf(dir, size, "/tmp/amsph_test_%s_XXXXXX", tag) < (int)size && size <= 256;
    const int made = fits && mkdtemp(dir) != NULL;
    CHECK(made, "mkdtemp %s", dir);
    if (made && testing_n_temp_dirs < TESTING_MAX_TEMP_DIRS)
        strcpy(testing_temp_dirs[testing_n_temp_dirs++], dir);
    return made ? 0 : -1;
}

static inline void testing_remove_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    char path[512];
    for (struct dirent *e; (e = readdir(d)) != NULL;)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0 &&
            snprintf(path, sizeof path, "%s/%.255s", dir, e->d_name) < (int)sizeof path)
            unlink(path);
    closedir(d);
    rmdir(dir);
}

static inline int testing_finish(void)
{
    printf("%d passed, %d failed\n", testing_passed, testing_failed);
    for (int k = 0; k < testing_n_temp_dirs; ++k) {
        if (testing_failed)
            fprintf(stderr, "kept for inspection: %s\n", testing_temp_dirs[k]);
        else
            testing_remove_dir(testing_temp_dirs[k]);
    }
    return testing_failed ? 1 : 0;
}

/* Creates backend k of {openmp, opencl}; returns NULL where it cannot be
 * made here (and fails the test if OpenCL was required). */
static inline amsph_backend *testing_backend(int k)
{
    static const char *names[] = {"openmp", "opencl"};
    amsph_backend *b = NULL;
    if (k < 0 || k > 1)
        return NULL;
    if (amsph_backend_create(names[k], -1, &b)) {
        const char *required = getenv("AMSPH_REQUIRE_OPENCL");
        const int must = k == 1 && required && strcmp(required, "1") == 0;
        CHECK(!must, "OpenCL required but unavailable: %s", amsph_last_error());
        if (!must)
            fprintf(stderr, "note: backend %s skipped: %s\n", names[k], amsph_last_error());
        return NULL;
    }
    return b;
}

#define TESTING_BACKENDS 2

/* The path of cases/validation/<relative> in the source tree;
 * AMSPH_SOURCE_DIR in the environment names the tree where the tests run
 * away from the one they were built from (tools/gpu_run.sh). */
static inline void testing_case_path(const char *relative, char *path, size_t size)
{
    const char *source = getenv("AMSPH_SOURCE_DIR");
    snprintf(path, size, "%s/cases/validation/%s", source ? source : AMSPH_SOURCE_DIR, relative);
}

/* Loads cases/validation/<relative> (a failure fails the test). */
static inline int testing_load_case(const char *relative, amsph_case *c)
{
    char path[1024], err[1024];
    testing_case_path(relative, path, sizeof path);
    const int status = amsph_case_load(path, c, err, sizeof err);
    CHECK(status == 0, "%s", err);
    return status;
}

#endif
