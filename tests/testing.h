/* A small test harness: CHECK counts and reports, testing_finish prints the
 * closing line "N passed, M failed" and gives the exit status; backends to
 * test are every one that can be created here (OpenCL is required when
 * AMSPH_REQUIRE_OPENCL=1, as in CI). */
#ifndef AMSPH_TESTING_H
#define AMSPH_TESTING_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "case.h"
#include "error.h"

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

static inline int testing_finish(void)
{
    printf("%d passed, %d failed\n", testing_passed, testing_failed);
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

/* Loads cases/validation/<relative> of the source tree (a failure fails the
 * test); AMSPH_SOURCE_DIR in the environment names the tree where the tests
 * run away from the one they were built from (tools/gpu_run.sh). */
static inline int testing_load_case(const char *relative, amsph_case *c)
{
    char path[1024], err[1024];
    const char *source = getenv("AMSPH_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/cases/validation/%s", source ? source : AMSPH_SOURCE_DIR, relative);
    const int status = amsph_case_load(path, c, err, sizeof err);
    CHECK(status == 0, "%s", err);
    return status;
}

#endif
