/* A minimal test harness for the C consumers: CHECK aborts the program with the file,
 * line, failed expression and the library's last error, so a failure under valgrind
 * names itself. */
#ifndef SHERD_TEST_CHECK_H
#define SHERD_TEST_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sherd.h"

#define CHECK(condition)                                                              \
    do {                                                                              \
        if (!(condition)) {                                                           \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n  last error: %s\n", __FILE__,  \
                    __LINE__, #condition, sherd_last_error_message());                \
            exit(1);                                                                  \
        }                                                                             \
    } while (0)

/* The call must return `expected`, and a failing call must leave a non-empty message. */
#define CHECK_STATUS(call, expected)                                                  \
    do {                                                                              \
        SherdStatus status_ = (call);                                                 \
        if (status_ != (SherdStatus)(expected)) {                                     \
            fprintf(stderr, "%s:%d: %s returned %s, expected %s\n  last error: %s\n", \
                    __FILE__, __LINE__, #call, sherd_status_name(status_),            \
                    sherd_status_name(expected), sherd_last_error_message());         \
            exit(1);                                                                  \
        }                                                                             \
        if (status_ != SHERD_STATUS_OK) {                                             \
            CHECK(strlen(sherd_last_error_message()) > 0);                            \
        }                                                                             \
    } while (0)

#define CHECK_OK(call) CHECK_STATUS(call, SHERD_STATUS_OK)

/* The last error message must contain `fragment`. */
#define CHECK_MESSAGE(fragment)                                                       \
    do {                                                                              \
        if (strstr(sherd_last_error_message(), (fragment)) == NULL) {                 \
            fprintf(stderr, "%s:%d: last error \"%s\" does not contain \"%s\"\n",     \
                    __FILE__, __LINE__, sherd_last_error_message(), (fragment));      \
            exit(1);                                                                  \
        }                                                                             \
    } while (0)

#define CHECK_NEAR(a, b, tolerance) CHECK(fabs((double)(a) - (double)(b)) <= (tolerance))

#endif
