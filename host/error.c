#include "error.h"

#include <stdarg.h>
#include <stdio.h>

static _Thread_local char last_error[1024];

static void record(const char *format, va_list args)
{
    vsnprintf(last_error, sizeof last_error, format, args);
}

int amsph_fail(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    record(format, args);
    va_end(args);
    return AMSPH_FAILED;
}

int amsph_bad_input(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    record(format, args);
    va_end(args);
    return AMSPH_BAD_INPUT;
}

const char *amsph_last_error(void) { return last_error; }
