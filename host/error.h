/* Error reporting: functions return 0 on success and a non-zero status on
 * failure, after recording one human-readable message here. */
#ifndef AMSPH_ERROR_H
#define AMSPH_ERROR_H

#if defined(__GNUC__)
#define AMSPH_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define AMSPH_PRINTF(f, a)
#endif

/* Statuses: 1 a failure of the run or the machine, 2 bad input (command
 * line, case file, restart file); the command line exits with them. */
#define AMSPH_FAILED 1
#define AMSPH_BAD_INPUT 2

/* Records the message (printf format) and returns AMSPH_FAILED, so
 * `return amsph_fail(...)`; amsph_bad_input returns AMSPH_BAD_INPUT. */
int amsph_fail(const char *format, ...) AMSPH_PRINTF(1, 2);
int amsph_bad_input(const char *format, ...) AMSPH_PRINTF(1, 2);
const char *amsph_last_error(void);

/* Propagates a failing status to the caller. */
#define AMSPH_CHECK(call)                                                                          \
    do {                                                                                           \
        const int amsph_status_ = (call);                                                          \
        if (amsph_status_)                                                                         \
            return amsph_status_;                                                                  \
    } while (0)

#endif
