/* SPDX-License-Identifier: MIT */
/* Header test: the public header must compile alone (built as C99, C++11 and C++20, -Werror). */
#include <kairos/kairos.h>
