// SPDX-License-Identifier: MIT
// The one translation unit with doctest's main, built once and linked into every test executable.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
